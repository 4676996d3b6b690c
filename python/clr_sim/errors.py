"""Typed errors of clr. Every one carries ``field``, the path of what to change: a model field
(``body[1].mass``, ``clearance[0].normal.restitution``), a ``set=``/sweep key
(``clearance.B.journal_radius``), ``model`` for an unknown built-in name, ``parameters`` for the
parameters of a built-in model, a law argument (``delta[3]``), or ``solver`` for a failed
integration. The message says what to change.

An error about an element of a model built in Python also names the element
(``element == "clearance 'B'"``) and the line of the script that wrote it: ``where``
(``"script.py:12"``) when the method call itself is refused, ``added_at`` when the error is
found only when the model is used (``simulate()``, ``check()``).
"""

from __future__ import annotations

from typing import Any, Optional

__all__ = [
    "ClrError",
    "ModelError",
    "FieldError",
    "OverrideError",
    "UnknownModelError",
    "ContactError",
    "SimulationError",
    "PlausibilityWarning",
]


class PlausibilityWarning(UserWarning):
    """A finding of clr's plausibility checks (an initial penetration, units that look wrong,
    energy created by the run); the same findings are in ``Result.warnings``. Turn them into
    errors with ``clr_sim.simulate(..., strict=True)`` (or Python's ``warnings.simplefilter``)."""


class ClrError(Exception):
    """Base of every clr error: ``message`` (what is wrong and what to change) and ``field``
    (where)."""

    def __init__(self, message: str, field: str = ""):
        self.message = message
        self.field = field
        super().__init__(self._render())

    def _render(self) -> str:
        return f"field `{self.field}`: {self.message}" if self.field else self.message


class ModelError(ClrError, ValueError):
    """A model, built-in parameter or override that cannot be used (a ``ValueError``).

    ``file``, ``line`` and ``column`` place it in a model file or TOML text when known; for a
    model built with :class:`clr_sim.Model`, ``element`` names the element (``"body 'crank'"``)
    and ``where`` (refused at the call) or ``added_at`` (found when the model is used) the
    script line (``"script.py:12"``) that wrote it.
    """

    def __init__(
        self,
        message: str,
        field: str = "",
        file: Optional[str] = None,
        line: Optional[int] = None,
        column: Optional[int] = None,
        element: Optional[str] = None,
        where: Optional[str] = None,
        added_at: Optional[str] = None,
    ):
        #: the element of a model built in Python (``"clearance 'B'"``, ``"[solver]"``)
        self.element = element
        #: ``file:line`` of the script line whose call was refused (errors at the call)
        self.where = where
        #: ``file:line`` of the script line that added the element (errors found at the run)
        self.added_at = added_at
        self.file = file
        # a model built in Python has no text of its own: its lines would be those of the
        # generated TOML, which the user never sees
        built = file is not None and file.startswith("<clr_sim.Model")
        self.line = None if built else line
        self.column = None if built else column
        super().__init__(message, field)

    def _render(self) -> str:
        element = ""
        if self.element:
            added = f" (added at {self.added_at})" if self.added_at else ""
            element = f"{self.element}{added}: "
        if self.where:
            return f"{self.where}: {element}{super()._render()}"
        return self._place() + element + super()._render()

    def _place(self) -> str:
        place = ""
        if self.file == "--set":
            place = "set: "
        elif self.file and not self.file.startswith("<clr_sim.Model"):
            place = self.file
            if self.line is not None:
                place += f":{self.line}"
                if self.column is not None:
                    place += f":{self.column}"
            place += ": "
        elif self.file and self.file.startswith("<clr_sim.Model"):
            place = f"{self.file[1:-1]}: "
        return place


class FieldError(ModelError):
    """A field of a model description: unknown field (with the closest valid one), missing
    value, wrong type, value out of range, unknown name of a body or point."""


class OverrideError(ModelError):
    """A ``set=`` override or sweep value: unknown path, or a value that does not apply."""


class UnknownModelError(ModelError):
    """No built-in model or study has this name (``field == "model"``); the message lists the
    valid names."""


class ContactError(ClrError, ValueError):
    """An invalid contact-law parameter (``field == "parameters"``) or law input (the argument,
    e.g. ``delta[3]`` for a non-finite element)."""


class SimulationError(ClrError, RuntimeError):
    """The integrator failed (``field == "solver"``: the message names the ``[solver]`` setting
    to change). ``result`` keeps what was computed up to the failure (a :class:`clr_sim.Result`,
    or for :func:`clr_sim.run_model` the dict it returns)."""

    def __init__(self, message: str, result: Any = None, field: str = "solver"):
        self.result = result
        super().__init__(message, field)
