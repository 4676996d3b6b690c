"""Helpers of spatial models (``clr_sim.Model(space="spatial")``, :class:`clr_sim.model.SpatialModel`):
the ends of joints, forces and clearance joints (:func:`at`) and the four forms of a body's
initial orientation (:func:`quaternion`, :func:`axis_angle`, :func:`euler`, :func:`matrix`).
Each returns the dict the model file takes (docs/model-file.md, "Spatial models"); the
reader checks the values when the dict reaches a :class:`~clr_sim.model.SpatialModel`
method. ``None``, a string or a vector of the wrong length where a number or a 3-vector is
required is a :class:`clr_sim.errors.FieldError` naming the argument (``axis_angle.angle``),
as in the planar helpers.

SI units: m, rad.
"""

from __future__ import annotations

from typing import Any, Dict, List, Optional, Sequence

from .errors import FieldError
from .model import SpatialModel, _caller, _number, _text

__all__ = ["SpatialModel", "at", "quaternion", "axis_angle", "euler", "matrix"]


def _vector(field: str, v: Any, n: int, what: str) -> List[float]:
    """``v`` as a list of ``n`` floats (a tuple, list or numpy array), or a FieldError."""
    if v is None:
        raise FieldError(f"missing value: give {what}, not None", field=field, where=_caller())
    if hasattr(v, "tolist"):
        v = v.tolist()
    if isinstance(v, (str, bytes)) or not isinstance(v, Sequence) or len(v) != n:
        raise FieldError(
            f"{v!r} is not {n} numbers; give {what}", field=field, where=_caller()
        )
    return [_number(f"{field}[{k}]", x, what) for k, x in enumerate(v)]


def at(
    body: str,
    x: float = 0.0,
    y: float = 0.0,
    z: float = 0.0,
    *,
    axis: Optional[Sequence[float]] = None,
) -> Dict[str, Any]:
    """An end: the point (x, y, z) (m) in the frame of ``body`` (``"ground"`` for the world
    frame) and, for joints, the ``axis`` direction in the same frame (normalized by the
    reader; which joints need it: docs/model-file.md)."""
    end: Dict[str, Any] = {
        "body": _text("at.body", body, "the body name (\"ground\" for the fixed frame)"),
        "at": [_number("at.x", x, "x (m)"), _number("at.y", y, "y (m)"),
               _number("at.z", z, "z (m)")],
    }
    if axis is not None:
        end["axis"] = _vector("at.axis", axis, 3, "the axis direction [x, y, z]")
    return end


def quaternion(w: float, x: float, y: float, z: float) -> Dict[str, Any]:
    """The orientation of the unit quaternion (w, x, y, z), scalar first (normalized by the
    reader; a norm off 1 by more than 1e-6 is refused as a likely typo)."""
    return {
        "quaternion": [
            _number(f"quaternion.{n}", v, f"the quaternion's {n}")
            for n, v in (("w", w), ("x", x), ("y", y), ("z", z))
        ]
    }


def axis_angle(axis: Sequence[float], angle: float) -> Dict[str, Any]:
    """The rotation by ``angle`` (rad) about ``axis`` (world, any length > 0)."""
    return {
        "axis": _vector("axis_angle.axis", axis, 3, "the rotation axis [x, y, z]"),
        "angle": _number("axis_angle.angle", angle, "the angle (rad)"),
    }


def euler(angles: Sequence[float], sequence: str = "zyx") -> Dict[str, Any]:
    """Three ``angles`` (rad) about the moving axes in the order ``sequence`` names
    (intrinsic: ``"zyx"`` is yaw–pitch–roll, ``"zxz"`` the classical Euler angles)."""
    return {
        "euler": _vector("euler.angles", angles, 3, "the three angles (rad)"),
        "sequence": _text("euler.sequence", sequence, "the axis sequence (\"zyx\", \"zxz\", ...)"),
    }


def matrix(rows: Sequence[Sequence[float]]) -> Dict[str, Any]:
    """The rotation matrix body → world by its three ``rows`` (orthonormal to 1e-6 with
    determinant +1, checked by the reader)."""
    if rows is None or isinstance(rows, (str, bytes)):
        raise FieldError(
            f"{rows!r} is not a 3 × 3 matrix; give its three rows",
            field="matrix.rows",
            where=_caller(),
        )
    if hasattr(rows, "tolist"):
        rows = rows.tolist()
    if not isinstance(rows, Sequence) or len(rows) != 3:
        raise FieldError(
            f"{rows!r} is not three rows; give the 3 × 3 matrix by rows",
            field="matrix.rows",
            where=_caller(),
        )
    return {
        "matrix": [
            _vector(f"matrix.rows[{k}]", r, 3, "a row of three numbers")
            for k, r in enumerate(rows)
        ]
    }
