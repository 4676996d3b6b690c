"""Geometries of contact shapes (``[[shape]]``, :meth:`clr_sim.Model.shape`): each function returns
the ``geometry`` table of the model file as a plain dict (``{"type": "ball", "radius": 0.01}``),
written in the shape's own frame (its origin at the shape's ``at``, turned by its ``angle``).

Lengths in m, angles in rad. As everywhere in :mod:`clr_sim.model`, nothing is checked here: the
model-file reader checks the geometry when the model is used and refuses a bad value with a
:class:`clr_sim.errors.FieldError` naming it (``shape[1].geometry.radius``). An argument left at
``None`` is not written (the file's default applies).

>>> import clr
>>> m = clr_sim.Model("ball_drop", gravity=(0.0, -9.81))
>>> m.shape("floor", at=clr_sim.at("ground", 0.0, -0.05), geometry=clr_sim.shapes.cuboid(0.5, 0.05))
"""

from __future__ import annotations

from typing import Any, Dict, Mapping, Optional, Sequence, Union

from .errors import FieldError

__all__ = [
    "ball",
    "capsule",
    "cuboid",
    "convex_polygon",
    "polyline",
    "part",
    "compound",
    "involute_gear",
    "beam_face",
    "GEOMETRIES",
]

#: A list of 2-D points (m): ``[(x0, y0), (x1, y1), ...]`` or an (n, 2) numpy array.
Points = Union[Sequence[Sequence[float]], Any]
#: A geometry table as written by the functions of this module.
Geometry = Mapping[str, Any]


def _plain(v: Any) -> Any:
    """numpy arrays and scalars as lists and Python numbers; tuples as lists."""
    if hasattr(v, "tolist"):
        v = v.tolist()
    if isinstance(v, (list, tuple)):
        return [_plain(x) for x in v]
    return v


def _table(kind: str, **fields: Any) -> Dict[str, Any]:
    out: Dict[str, Any] = {"type": kind}
    out.update({k: _plain(v) for k, v in fields.items() if v is not None})
    return out


def ball(radius: float) -> Dict[str, Any]:
    """A disc of ``radius`` (m) centred on the shape origin."""
    return _table("ball", radius=radius)


def capsule(half_length: float, radius: float) -> Dict[str, Any]:
    """A stadium: the segment from −``half_length`` to ``half_length`` (m) along the shape x
    axis, dilated by ``radius`` (m)."""
    return _table("capsule", half_length=half_length, radius=radius)


def cuboid(hx: float, hy: float) -> Dict[str, Any]:
    """A rectangle centred on the shape origin, half widths ``hx`` and ``hy`` (m) along the
    shape x and y axes (the file's ``half_extents = [hx, hy]``)."""
    return _table("cuboid", half_extents=[hx, hy])


def convex_polygon(points: Points) -> Dict[str, Any]:
    """A convex polygon: its vertices (m) counter-clockwise, the first not repeated."""
    return _table("convex_polygon", points=points)


def polyline(points: Points) -> Dict[str, Any]:
    """An open chain of segments through ``points`` (m) in order (a cam profile, a wall);
    contact from either side."""
    return _table("polyline", points=points)


def part(
    geometry: Geometry,
    at: Optional[Sequence[float]] = None,
    angle: Optional[float] = None,
) -> Dict[str, Any]:
    """One part of a :func:`compound`: a convex ``geometry`` (:func:`ball`, :func:`capsule`,
    :func:`cuboid` or :func:`convex_polygon`) with its origin ``at`` (x, y) (m; default the
    shape origin) turned by ``angle`` (rad; default 0) in the shape frame."""
    out: Dict[str, Any] = {}
    if at is not None:
        out["at"] = _plain(at)
    if angle is not None:
        out["angle"] = _plain(angle)
    out["geometry"] = dict(_geometry("part.geometry", geometry))
    return out


def _geometry(field: str, g: Any) -> Mapping[str, Any]:
    """``g`` if it is a geometry table, else a FieldError naming ``field`` (None, a number, ...)."""
    if not isinstance(g, Mapping):
        from .model import _caller  # the user's line; model imports nothing from here

        raise FieldError(
            f"{g!r} is a {type(g).__name__}; give a geometry of clr_sim.shapes "
            "(ball, capsule, cuboid or convex_polygon)",
            field=field,
            where=_caller(),
        )
    return g


def compound(parts: Sequence[Geometry]) -> Dict[str, Any]:
    """Convex parts at poses in the shape frame (an L-shaped stop, a block with a boss).

    Each item is a :func:`part` (``{"at", "angle", "geometry"}``) or a bare convex geometry,
    which is taken as a part at the shape origin (``part(geometry)``). Involute gears, polylines
    and compounds cannot be parts."""
    if isinstance(parts, (str, bytes, Mapping)) or not hasattr(parts, "__iter__"):
        from .model import _caller

        raise FieldError(
            f"{parts!r} is a {type(parts).__name__}; give compound.parts as a list of "
            "part(...) items or convex geometries",
            field="compound.parts",
            where=_caller(),
        )
    items = []
    for k, p in enumerate(parts):
        p = _geometry(f"compound.parts[{k}]", p)
        if "type" in p and "geometry" not in p:
            items.append(part(p))
        else:
            items.append(dict(p))
    return {"type": "compound", "parts": items}


def involute_gear(
    module: float,
    teeth: int,
    *,
    pressure_angle: Optional[float] = None,
    backlash: Optional[float] = None,
    addendum: Optional[float] = None,
    dedendum: Optional[float] = None,
    points_per_flank: Optional[int] = None,
) -> Dict[str, Any]:
    """A spur gear with involute teeth centred on the shape origin, tooth 0 on the shape x axis:
    a core disc of the root radius and one convex polygon per tooth.

    ``module`` m (m; pitch radius m·z/2), ``teeth`` z, ``pressure_angle`` α (rad; default 20° =
    0.3490659 rad), ``backlash``: circumferential thinning of this gear's tooth at the pitch
    circle (m; default 0; a pair with backlash j_t gives each gear j_t/2), ``addendum`` and
    ``dedendum`` coefficients (× module; defaults 1 and 1.25), ``points_per_flank``: vertices
    per involute flank (default 24; the chord error falls as its square)."""
    return _table(
        "involute_gear",
        module=module,
        teeth=teeth,
        pressure_angle=pressure_angle,
        backlash=backlash,
        addendum=addendum,
        dedendum=dedendum,
        points_per_flank=points_per_flank,
    )


def beam_face(beam: str, face: str, *, samples_per_element: Optional[int] = None) -> Dict[str, Any]:
    """The deformed ``face`` (``"upper"`` or ``"lower"``) of the flexible beam ``beam`` (a
    ``[[beam]]`` or ``[[flexible_body]]``): segments through ``samples_per_element`` samples per
    element (default 4) of the face, rebuilt at every evaluation. Give it without ``at`` and
    ``angle`` (it follows the beam), and only as the first shape of :meth:`clr_sim.Model.contact`,
    against a rigid shape."""
    return _table("beam_face", beam=beam, face=face, samples_per_element=samples_per_element)


#: For each geometry ``type`` of the file, the function of this module that writes it (the
#: tests check it against the Rust reader's list of geometry types and their fields).
GEOMETRIES: Dict[str, str] = {
    "ball": "ball",
    "capsule": "capsule",
    "cuboid": "cuboid",
    "convex_polygon": "convex_polygon",
    "polyline": "polyline",
    "compound": "compound",
    "involute_gear": "involute_gear",
    "beam_face": "beam_face",
}
