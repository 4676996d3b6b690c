"""Co-simulation FMUs (FMI 3.0, or 2.0 on request) of planar models: :func:`export` writes what ``clr fmu`` writes
(docs/fmu.md).

The FMU embeds the clr runtime library (``libclr_fmu.so``, built by ``cargo build --release -p
clr-fmu``; it lands next to the ``clr`` command in ``target/release``) with the model file. Its
inputs are the model's :meth:`Model.input`\\ s, its outputs the measure columns (or the columns
named), its parameters the model-file fields named (fixed: set before the end of
initialization).

>>> from clr_sim import fmu                                     # doctest: +SKIP
>>> fmu.export("models/examples/flap_fmu.toml", "flap.fmu",
...            parameters=["clearance.J4.journal_radius"])      # doctest: +SKIP
"""

from __future__ import annotations

import json
import os
import shutil
from pathlib import Path
from typing import Any, Dict, Optional, Sequence, Union

from . import _native
from .errors import ModelError

__all__ = ["export", "find_library"]

_LIBRARY = "libclr_fmu.so"


def find_library(library: Optional[Union[str, "os.PathLike[str]"]] = None) -> Path:
    """The FMU runtime library: ``library`` if given, else ``$CLR_FMU_LIBRARY``, else
    ``libclr_fmu.so`` next to ``$CLR_BIN`` or next to the ``clr`` command on the ``PATH``.

    Raises :class:`FileNotFoundError` saying where it looked and how to build it."""
    looked = []
    candidates = []
    if library is not None:
        candidates.append(Path(library))
    elif os.environ.get("CLR_FMU_LIBRARY"):
        candidates.append(Path(os.environ["CLR_FMU_LIBRARY"]))
    else:
        for exe in (os.environ.get("CLR_BIN"), shutil.which("clr")):
            if exe:
                candidates.append(Path(exe).resolve().parent / _LIBRARY)
    for c in candidates:
        if c.is_file():
            return c
        looked.append(str(c))
    raise FileNotFoundError(
        f"the FMU runtime library {_LIBRARY} was not found (looked at: "
        f"{', '.join(looked) or 'nothing: no CLR_FMU_LIBRARY, CLR_BIN or clr on the PATH'}); "
        "build it with `cargo build --release -p clr-fmu` and pass library=..., or set "
        "CLR_FMU_LIBRARY"
    )


def export(
    model: Any,
    path: Union[str, "os.PathLike[str]"],
    *,
    outputs: Optional[Sequence[str]] = None,
    parameters: Sequence[str] = (),
    step_size: Optional[float] = None,
    library: Optional[Union[str, "os.PathLike[str]"]] = None,
    fmi_version: int = 3,
) -> Dict[str, Any]:
    """Write the co-simulation FMU (FMI 3.0) of ``model`` (a :class:`~clr_sim.Model` or the
    path of a planar model file) to ``path``.

    ``outputs``: output columns (default: the measure columns, or every column of a model
    without measures); ``parameters``: model-file fields as ``--set`` paths
    (``"clearance.J4.journal_radius"``); ``step_size``: the default experiment's
    communication step, s (default the model's output interval); ``library``: the runtime
    library (:func:`find_library`); ``fmi_version``: 3 (default) or 2 for masters that read only
    FMI 2.0 (the same runtime and numbers).

    Returns the FMU's configuration (inputs, outputs, parameters with value references in that
    order after ``time`` = 0, the default experiment). Raises :class:`~clr_sim.ModelError`
    for a model the FMU cannot carry (spatial, a built-in form) or unknown outputs or
    parameters."""
    from .model import Model

    if isinstance(model, Model):
        src, file = model.to_toml(), "model.toml"
    else:
        file = os.fspath(model)
        src = Path(file).read_text()
    lib = find_library(library)
    try:
        text = _native.fmu_export(
            src,
            file,
            os.fspath(path),
            str(lib),
            None if outputs is None else list(outputs),
            list(parameters),
            step_size,
            fmi_version,
        )
    except ValueError as e:
        raise ModelError(str(e)) from None
    return json.loads(text)
