"""clr: planar mechanisms with clearance joints, contact, friction and flexible links, and
spatial rigid multibody models (``Model(space="spatial")``, helpers in :mod:`clr_sim.spatial`).

Build a model (:class:`Model`, or a model file, or a built-in model by name), run it
(:func:`simulate`) and sweep its parameters in parallel (:func:`sweep`); the geometries of
contact shapes are in :mod:`clr_sim.shapes`, the contact and friction laws on their own in
:mod:`clr_sim.contact`. Everything runs in Rust through the same
code as the ``clr`` command, so the numbers are those of ``clr run`` and ``clr sweep`` bit for
bit. SI units throughout (docs/python.md).
"""

from __future__ import annotations

import json
import os
import warnings as _warnings
from typing import Any, Dict, Iterator, List, Mapping, Optional, Sequence, Tuple, Union

from . import _native, contact, errors, fmu, inertia, shapes, spatial
from .contact import FrictionLaw, JournalJoint, NormalLaw, RevoluteJoint
from .errors import (
    ClrError,
    ContactError,
    FieldError,
    ModelError,
    OverrideError,
    PlausibilityWarning,
    SimulationError,
    UnknownModelError,
)
from .model import Model, SpatialModel, at, friction, material, motion, node, normal
from .progress import Progress
from .result import Result, SweepResult, _rows

__version__ = _native.__version__

__all__ = [
    "Model",
    "SpatialModel",
    "spatial",
    "at",
    "node",
    "material",
    "normal",
    "friction",
    "motion",
    "shapes",
    "fmu",
    "simulate",
    "sweep",
    "sweep_point",
    "Result",
    "SweepResult",
    "list_models",
    "list_studies",
    "run_study",
    "run_model",
    "contact",
    "NormalLaw",
    "FrictionLaw",
    "RevoluteJoint",
    "JournalJoint",
    *errors.__all__,
]

#: What :func:`simulate` and :func:`sweep` run: a :class:`Model`, a built-in model name
#: (:func:`list_models`) or the path of a model file.
Target = Union[Model, str, "os.PathLike[str]"]


def _positive(name: str, v: Optional[float]) -> Optional[float]:
    if v is None:
        return None
    try:
        f = float(v)
    except (TypeError, ValueError):
        raise ModelError(f"{v!r} is not a number", field=name) from None
    if not (f > 0.0 and f < float("inf")):
        raise ModelError(f"{f} must be > 0 and finite", field=name)
    return f


def _job(model: Target, set: Optional[Mapping[str, Any]], t_end, rtol) -> "_native.JobCore":
    t_end, rtol = _positive("t_end", t_end), _positive("rtol", rtol)
    if isinstance(model, Model):
        return model._job(set, t_end, rtol)
    if isinstance(model, (str, os.PathLike)):
        return _native.JobCore.from_target(
            os.fspath(model), None if set is None else dict(set), t_end, rtol
        )
    raise ModelError(
        f"cannot run a {type(model).__name__}; give a clr_sim.Model, a built-in model name or a "
        "model file path",
        field="model",
    )


def simulate(
    model: Target,
    t_end: Optional[float] = None,
    *,
    rtol: Optional[float] = None,
    set: Optional[Mapping[str, Any]] = None,
    check: bool = True,
    strict: bool = False,
    inputs: Optional[Mapping[str, Any]] = None,
) -> Result:
    """Run ``model`` as ``clr run`` does (without writing files; the GIL is released).

    ``inputs`` maps the names of load inputs (:meth:`Model.input` driving a force, torque or
    actuator force) to Python callables ``f(t, measures) -> value`` (N or N·m): a controller or
    a custom force prototyped in Python, called at every evaluation of the forces with the time
    (s) and a dict of the model's position- and velocity-level measure columns
    (``"flap.angle"``, ``"tip.vx"``, ...) at the evaluated state. Each call takes the GIL and
    costs some microseconds (docs/fmu.md); the FMU is the fast path. An exception inside the
    callable stops the run and is raised as the cause of the :class:`SimulationError`.

    ``t_end`` (s) and ``rtol`` override the model's end time and relative tolerance (``rtol``
    also sets ``atol`` = 1e-3·rtol, reported in ``notes``); ``set`` maps dotted names to values
    like ``clr run --set`` (``{"clearance.B.journal_radius": 0.0099}``, a built-in's
    ``{"restitution": 0.5}``).

    Returns a :class:`Result`. Raises :class:`ModelError` and its subclasses for input that
    cannot run (with the field to change), and, when ``check`` is true,
    :class:`SimulationError` when the integration fails (its ``result`` keeps the rows up to
    the failure); with ``check=False`` such a result is returned with ``error`` set.

    The plausibility checks' findings are in ``result.warnings`` and are issued as
    :class:`PlausibilityWarning`; ``strict=True`` (``clr run --strict``) refuses them: before
    integrating as a :class:`ModelError`, after the run as a :class:`SimulationError` whose
    ``result`` is complete.
    """
    job = _job(model, set, t_end, rtol)
    errors: list = []
    if inputs:
        job = _with_inputs(job, inputs, errors)
    try:
        raw = job.run(strict)
    except FieldError as e:
        # found by the run (the assembly of the initial conditions): name the element
        if isinstance(model, Model):
            raise model._named(e) from None
        raise
    result = Result(dict(raw))
    for w in result.warnings:
        _warnings.warn(f"{w['field']}: {w['message']}", PlausibilityWarning, stacklevel=2)
    if check and result.error is not None:
        if errors:
            raise SimulationError(
                f"an input function raised {type(errors[0]).__name__}: {errors[0]}", result
            ) from errors[0]
        raise SimulationError(result.error, result)
    return result


def _with_inputs(job, inputs: Mapping[str, Any], errors: list):
    """``job`` with each load input of ``inputs`` a Python callable f(t, measures)."""
    try:
        names = job.feedback_columns()
    except ValueError as e:
        raise ModelError(str(e), field="inputs") from None
    for name, f in inputs.items():
        if not callable(f):
            raise ModelError(
                f"input {name!r}: give a callable f(t, measures) -> value, got "
                f"{type(f).__name__}",
                field=f"inputs.{name}",
            )

        def call(t, values, f=f):
            return f(t, dict(zip(names, values)))

        try:
            job = job.with_input_function(str(name), call, errors)
        except ValueError as e:
            raise ModelError(str(e), field=f"inputs.{name}") from None
    return job


def sweep(
    model: Target,
    vary: Mapping[str, Sequence[Any]],
    *,
    t_end: Optional[float] = None,
    rtol: Optional[float] = None,
    set: Optional[Mapping[str, Any]] = None,
    jobs: Optional[int] = None,
    progress: bool = True,
    executor: Any = None,
) -> SweepResult:
    """Run the cartesian product of the values in ``vary`` (dotted name → values, the last
    varying fastest) over ``model``, as ``clr sweep --vary name=v1,v2 ...`` does: the same
    points in the same order, the same numbers.

    The points run on ``jobs`` Rust threads (default: one per core) without the GIL; a progress
    line is shown (terminal or Jupyter; ``progress=False`` hides it). Every point is checked
    before the first runs. Ctrl-C (KeyboardInterrupt) skips the points not yet started, waits
    for those running and raises. A point whose integration fails does not stop the sweep: its
    result has ``error`` set and ``SweepResult.failed`` lists it.

    ``executor`` runs the points elsewhere: any :class:`concurrent.futures.Executor` (a process
    pool, a dask.distributed ``Client.get_executor()``, Ray's), or any object whose
    ``submit(fn, *args)`` returns jobs with ``done()`` and ``result()``, such as submitit's
    ``AutoExecutor`` on Slurm (one Slurm job per point; its jobs are polled every 0.25 s). Each point is sent as a plain description (the model file's path, a built-in's
    name or a :class:`Model`'s TOML text, with its overrides) to :func:`sweep_point`, which
    runs it where it lands; the results come back as the same :class:`SweepResult`, value for
    value (docs/scaling.md). With a process pool use the ``spawn`` start method
    (``mp_context=multiprocessing.get_context("spawn")``): forking a process that holds the
    library's threads can hang the child. ``jobs`` does not apply then.
    """
    if not isinstance(vary, Mapping) or not vary:
        raise OverrideError(
            "give the varied parameters as a dict of dotted name → list of values",
            field="vary",
        )
    axes: List[Tuple[str, list]] = []
    for name, values in vary.items():
        if isinstance(values, (str, bytes)) or not hasattr(values, "__iter__"):
            raise OverrideError(
                f"the values of {name!r} must be a list (got {type(values).__name__})",
                field=str(name),
            )
        axes.append((str(name), list(values)))
    if jobs is not None and (not isinstance(jobs, int) or jobs < 1):
        raise ModelError(f"{jobs!r}: give a positive number of threads", field="jobs")
    if executor is not None:
        if jobs is not None:
            raise ModelError("give either jobs (threads here) or executor", field="jobs")
        return _sweep_on(executor, model, axes, set, t_end, rtol, progress)
    run = _native.SweepRun(_job(model, set, t_end, rtol), axes, jobs)
    bar = Progress(run.total, enabled=progress)
    try:
        while not run.wait(0.1):
            bar.update(run.done())
    except KeyboardInterrupt:
        run.cancel()
        bar.close(run.done())
        raise
    bar.close(run.done())
    return SweepResult([a for a, _ in axes], _rows(run.results()))


def sweep_point(
    target: Union[str, Tuple[str, str]],
    set: Mapping[str, Any],
    t_end: Optional[float],
    rtol: Optional[float],
) -> Result:
    """Run one sweep point where an executor put it (:func:`sweep` with ``executor``):
    ``target`` is a model file's path or a built-in's name, or ``("toml", text)`` for a
    :class:`Model`; ``set`` the point's overrides. A failed integration returns its result with
    ``error`` set, as a sweep point does."""
    model: Target = Model.from_toml(target[1]) if isinstance(target, tuple) else target
    return simulate(model, t_end, rtol=rtol, set=dict(set), check=False)


def _sweep_on(executor, model, axes, set, t_end, rtol, progress) -> SweepResult:
    """:func:`sweep` on ``executor``: every point checked here, then submitted."""
    import itertools

    if isinstance(model, Model):
        target: Union[str, Tuple[str, str]] = ("toml", model.to_toml())
    elif isinstance(model, (str, os.PathLike)):
        target = os.fspath(model)
        if os.path.exists(target):
            # the workers may start in another folder
            target = os.path.abspath(target)
    else:
        _job(model, set, t_end, rtol)  # raises the ModelError naming the type
        raise AssertionError("unreachable")
    names = [a for a, _ in axes]
    points = []
    for k, values in enumerate(itertools.product(*[v for _, v in axes])):
        overrides = {**dict(set or {}), **dict(zip(names, values))}
        _job(model, overrides, t_end, rtol)  # a bad value stops the sweep before anything runs
        points.append((k, list(values), overrides))
    futures = [executor.submit(sweep_point, target, o, t_end, rtol) for _, _, o in points]
    bar = Progress(len(points), enabled=progress)
    results: List[Optional[Result]] = [None] * len(points)
    try:
        index = {id(f): k for k, f in enumerate(futures)}
        for n, f in enumerate(_completed(futures), 1):
            results[index[id(f)]] = f.result()
            bar.update(n)
    except KeyboardInterrupt:
        for f in futures:
            f.cancel()
        bar.close(sum(r is not None for r in results))
        raise
    bar.close(len(points))
    return SweepResult(names, [(k, v, results[k]) for k, v, _ in points])


def _completed(futures: List[Any], poll_s: float = 0.25) -> Iterator[Any]:
    """The futures as they complete: ``concurrent.futures.as_completed`` for the standard
    library's futures (process and thread pools, dask's ``Client.get_executor()``), else by
    polling ``done()`` every ``poll_s`` seconds (submitit's jobs have ``done()`` and
    ``result()`` but are not ``concurrent.futures.Future``s)."""
    from concurrent.futures import Future, as_completed

    if all(isinstance(f, Future) for f in futures):
        yield from as_completed(futures)
        return
    import time

    pending = list(futures)
    while pending:
        ready = [f for f in pending if f.done()]
        for f in ready:
            pending.remove(f)
            yield f
        if not ready:
            time.sleep(poll_s)


def list_models() -> List[Tuple[str, str]]:
    """The built-in models as ``(name, description)`` pairs (as ``clr list`` prints them)."""
    return list(_native.list_models())


def list_studies() -> List[Tuple[str, str, str]]:
    """The paper studies as ``(name, model, description)`` (``clr list``)."""
    return list(_native.list_studies())


def run_study(name: str, out: Union[str, "os.PathLike[str]"]) -> int:
    """Run the paper study ``name`` into the folder ``out`` as ``clr study`` does (a CSV per
    run, summary.csv, figures); returns the number of runs. Long: minutes for some."""
    return int(_native.run_study(name, os.fspath(out)))


def run_model(
    name_or_path: str,
    set: Optional[Mapping[str, Any]] = None,
    t_end: Optional[float] = None,
    rtol: Optional[float] = None,
) -> Dict[str, Any]:
    """The former dict interface: :func:`simulate` of a built-in name or a model file, as a
    dict (``time`` and every column, ``units``, ``metrics``, ``metric_units``, ``impacts``,
    ``notes``, ``initial_conditions`` (JSON text), ``parameters``, ``model``, ``source``,
    ``wall_s``). Raises
    :class:`SimulationError` with that dict as ``result`` when the integration fails."""
    result = simulate(str(name_or_path), t_end, rtol=rtol, set=set, check=False)
    d = result.to_dict()
    # this interface gave the assembly report as JSON text
    d["initial_conditions"] = json.dumps(d["initial_conditions"])
    error = d.pop("error")
    if error is not None:
        raise SimulationError(error, d)
    return d
