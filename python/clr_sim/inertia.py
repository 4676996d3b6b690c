"""Mass properties of common parts from their dimensions and material, as a model file's
``[[body]]`` ``shape``, ``material``/``density`` and ``between`` give them (docs/model-file.md,
"Bodies from dimensions"; the formulas and sources in docs/mbd.md). Computed in Rust by the
model-file reader's own code, so the numbers are the file's bit for bit.

Each function returns a :class:`Part`: a dict of ``mass`` (kg), ``inertia`` (kg·m², about the
centre of mass and the body z axis, normal to the plane) and ``centre_of_mass`` (m, in the body
frame: the part's centre, ``[0, 0]``), plus ``position`` (m) and ``angle`` (rad) when placed
``between`` two points. It unpacks straight into :meth:`clr_sim.Model.body`:

>>> import clr_sim
>>> m = clr_sim.Model("four_bar", gravity=(0.0, -9.81))
>>> crank = clr_sim.inertia.bar(width=0.02, thickness=0.01, material="steel",
...                             between=((0.0, 0.0), (0.0, 0.1)))
>>> m.body("crank", **crank)  # mass, inertia, centre_of_mass, position, angle

Give ``material`` (a name of :data:`MATERIALS`) or ``density`` (kg/m³), not both. ``between``
places the body frame at the midpoint of the two points (m, world coordinates) with its x axis
from the first to the second, so the ends are at ``[-L/2, 0]`` and ``[L/2, 0]`` in the body
frame; a bar, plate, rod or tube takes its length from them when ``length`` is left out (a
given length must agree to 1e-9 relative). Refusals raise :class:`clr_sim.errors.FieldError`
naming the argument (``width``, ``material``).
"""

from __future__ import annotations

from typing import Any, Dict, Optional, Sequence, Tuple

from . import _native

__all__ = ["Part", "bar", "plate", "box", "rod", "tube", "disc", "MATERIALS"]

#: The named materials: name → density (kg/m³). Sources in :func:`material_sources`.
MATERIALS: Dict[str, float] = {name: rho for name, rho, _ in _native.materials()}

Point = Tuple[float, float]


def material_sources() -> Dict[str, str]:
    """The grade and source of each named material's density."""
    return {name: source for name, _, source in _native.materials()}


class Part(dict):
    """Mass properties of a part: the keys ``mass``, ``inertia``, ``centre_of_mass`` (and with
    ``between``, ``position`` and ``angle``), also readable as attributes; ``length`` (m, the
    length used; ``None`` for a box or disc) is an attribute only, as it is no body field."""

    def __init__(self, values: Dict[str, Any]):
        self.length: Optional[float] = values.pop("length")
        super().__init__(values)

    def __getattr__(self, name: str) -> Any:
        try:
            return self[name]
        except KeyError:
            raise AttributeError(name) from None


def _part(
    kind: str,
    dims: Dict[str, Any],
    material: Optional[str],
    density: Optional[float],
    between: Optional[Sequence[Sequence[float]]],
) -> Part:
    table: Dict[str, Any] = {"shape": {kind: {k: v for k, v in dims.items() if v is not None}}}
    if material is not None:
        table["material"] = material
    if density is not None:
        table["density"] = density
    if between is not None:
        table["between"] = [list(p) for p in between]
    return Part(dict(_native.part(table)))


def _prism(kind: str, doc: str):
    """The function of a rectangular prism named ``kind`` (``bar``, ``plate``)."""

    def prism(
        length: Optional[float] = None,
        width: Optional[float] = None,
        thickness: Optional[float] = None,
        *,
        material: Optional[str] = None,
        density: Optional[float] = None,
        between: Optional[Tuple[Point, Point]] = None,
    ) -> Part:
        return _part(kind, dict(length=length, width=width, thickness=thickness), material,
                     density, between)

    prism.__name__ = prism.__qualname__ = kind
    prism.__doc__ = doc
    return prism


bar = _prism(
    "bar",
    """A rectangular bar: ``length`` along body x, ``width`` along body y, ``thickness`` along z
    (m). m = ρ·L·w·t, I = m(L² + w²)/12.""",
)

plate = _prism(
    "plate",
    """A plate lying in the plane of motion: ``length`` along body x, ``width`` along body y,
    ``thickness`` normal to the plane (m); the same solid as :func:`bar`.""",
)


def box(
    size: Sequence[float],
    *,
    material: Optional[str] = None,
    density: Optional[float] = None,
    between: Optional[Tuple[Point, Point]] = None,
) -> Part:
    """A box (cuboid) of sides ``size = (x, y, z)`` (m) along body x, y and z.
    m = ρ·x·y·z, I = m(x² + y²)/12."""
    return _part("box", dict(size=list(size)), material, density, between)


def rod(
    length: Optional[float] = None,
    diameter: Optional[float] = None,
    *,
    material: Optional[str] = None,
    density: Optional[float] = None,
    between: Optional[Tuple[Point, Point]] = None,
) -> Part:
    """A round rod: ``length`` along body x, ``diameter`` (m). m = ρπr²L,
    I = m(3r² + L²)/12."""
    return _part("rod", dict(length=length, diameter=diameter), material, density, between)


def tube(
    length: Optional[float] = None,
    outer_diameter: Optional[float] = None,
    inner_diameter: Optional[float] = None,
    *,
    material: Optional[str] = None,
    density: Optional[float] = None,
    between: Optional[Tuple[Point, Point]] = None,
) -> Part:
    """A tube: ``length`` along body x, ``outer_diameter`` and ``inner_diameter`` (m).
    m = ρπ(R² − r²)L, I = m(3(R² + r²) + L²)/12."""
    return _part(
        "tube",
        dict(length=length, outer_diameter=outer_diameter, inner_diameter=inner_diameter),
        material,
        density,
        between,
    )


def disc(
    diameter: float,
    thickness: float,
    *,
    material: Optional[str] = None,
    density: Optional[float] = None,
    between: Optional[Tuple[Point, Point]] = None,
) -> Part:
    """A disc with its axis normal to the plane: ``diameter``, ``thickness`` (m).
    m = ρπr²t, I = m r²/2."""
    return _part("disc", dict(diameter=diameter, thickness=thickness), material, density,
                 between)
