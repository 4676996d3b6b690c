"""Build a model in Python: :class:`Model` mirrors the model file (docs/model-file.md) section
by section, one method per element kind, and holds plain data (the dict of the file). It is
read by the same Rust code as a model file, so a model built here and the same model written
as TOML give the same numbers bit for bit.

SI units everywhere (m, kg, s, N, Pa, J), angles in rad, angular rates in rad/s. An argument
left at ``None`` is not written (the file's default applies); every argument given is used or
refused with a :class:`clr_sim.errors.FieldError` naming its field (``joint[1].axis``).

Each method checks its element when it is called, with the model-file reader, in the context
of the model so far, and refuses it (the element is not added) with a
:class:`clr_sim.errors.FieldError` that names the element (``clearance 'B'``), the field and
the script line of the call (``script.py:12``). A name of a body, point, beam or shape that is
not defined yet is accepted (a model file may define its items in any order) and checked when
the model is used (:meth:`Model.check`, :func:`clr_sim.simulate`); errors found then name the
element and the line that added it. ``None`` for a required value, or a value of the wrong type
(a string where a number is required), is a :class:`clr_sim.errors.FieldError` naming the field,
in the helpers (:func:`at`, :func:`normal`, ...) as in the methods.

Attachment points (``a``, ``b``, ``bearing``, ``journal``, ``guide``, ``slider``, ``at``) are a
point name (``"O"``), a body and local coordinates (:func:`at`) or a beam node (:func:`node`).
Laws and time functions are dicts as in the file; :func:`normal`, :func:`friction`,
:func:`material` and :func:`motion` write them, and :mod:`clr_sim.shapes` the geometries of
contact shapes (:meth:`Model.shape`).
"""

from __future__ import annotations

import copy
import numbers
import os
import re
import sys
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union

from . import _native
from .errors import FieldError, ModelError

__all__ = ["Model", "SpatialModel", "at", "node", "material", "normal", "friction", "motion"]

#: A 2-vector (m, m/s or N): a tuple, list or numpy array of two numbers.
Vec2 = Union[Sequence[float], Tuple[float, float]]
#: Where an element attaches: a point name, ``at(body, x, y)`` or ``node(beam, k)``.
Anchor = Union[str, Mapping[str, Any]]
#: A law or time function as its file table (``{"law": "hertz", ...}``).
Table = Mapping[str, Any]

# The sections of a model file, in the order `clr export` writes them.
_LISTS = (
    "body", "point", "beam", "flexible_body", "joint", "driver", "force", "shape", "clearance",
    "input", "measure", "metric",
)
_TABLES = ("model", "twin", "solver", "output")


_PACKAGE_DIR = os.path.dirname(os.path.abspath(__file__))


def _caller() -> Optional[str]:
    """``file:line`` of the innermost frame outside the clr_sim package: the user's line."""
    f = sys._getframe(1)
    while f is not None:
        name = os.path.abspath(f.f_code.co_filename)
        if os.path.dirname(name) != _PACKAGE_DIR:
            return f"{f.f_code.co_filename}:{f.f_lineno}"
        f = f.f_back
    return None


def _refuse(field: str, message: str) -> FieldError:
    return FieldError(message, field=field, where=_caller())


def _number(field: str, v: Any, what: str) -> float:
    """``v`` as a float, or a FieldError naming ``field`` for None, a bool, a string, ..."""
    if v is None:
        raise _refuse(field, f"missing value: give {what} (a number), not None")
    if getattr(v, "ndim", None) == 0:  # a 0-d numpy array
        v = v.item()
    if isinstance(v, (bool, str, bytes)) or not isinstance(v, numbers.Real):
        raise _refuse(field, f"{v!r} is a {type(v).__name__}; give {what} as a number")
    return float(v)


def _integer(field: str, v: Any, what: str) -> int:
    if v is None:
        raise _refuse(field, f"missing value: give {what} (an integer), not None")
    if getattr(v, "ndim", None) == 0:  # a 0-d numpy array
        v = v.item()
    if isinstance(v, bool) or not isinstance(v, numbers.Integral):
        raise _refuse(field, f"{v!r} is a {type(v).__name__}; give {what} as an integer")
    return int(v)


def _text(field: str, v: Any, what: str) -> str:
    if v is None:
        raise _refuse(field, f"missing value: give {what} (a string), not None")
    if not isinstance(v, str):
        raise _refuse(field, f"{v!r} is a {type(v).__name__}; give {what} as a string")
    return v


def at(body: str, x: float = 0.0, y: float = 0.0) -> Dict[str, Any]:
    """The point (x, y) (m) in the frame of ``body`` (``"ground"`` for the fixed frame)."""
    return {
        "body": _text("at.body", body, "the body name (\"ground\" for the fixed frame)"),
        "at": [_number("at.x", x, "x (m)"), _number("at.y", y, "y (m)")],
    }


def node(beam: str, k: int) -> Dict[str, Any]:
    """Node ``k`` (0 at the beam's start) of the beam or flexible body ``beam``."""
    return {
        "beam": _text("node.beam", beam, "the beam or flexible body name"),
        "node": _integer("node.node", k, "the node index k (0 at the beam's start)"),
    }


def material(youngs_modulus: float, poisson_ratio: float) -> Dict[str, float]:
    """An elastic material: Young's modulus E (Pa) and Poisson's ratio ν (–)."""
    return {
        "youngs_modulus": _number(
            "material.youngs_modulus", youngs_modulus, "Young's modulus E (Pa)"
        ),
        "poisson_ratio": _number("material.poisson_ratio", poisson_ratio, "Poisson's ratio ν"),
    }


def normal(law: str, restitution: float, **params: Any) -> Dict[str, Any]:
    """A normal-force law (``[clearance.normal]``): ``law`` (``hertz``, ``lankarani-nikravesh``,
    ``flores``, ``preset``, ...; docs/model-file.md), the coefficient of restitution c_e (–) and
    the law's parameters (``stiffness`` in N/m^n, ``exponent``, ``bearing_material`` and
    ``journal_material`` from :func:`material`, ``preset``, ``length`` in m, ...)."""
    return {
        "law": _text("normal.law", law, "the law (hertz, preset, ...; docs/model-file.md)"),
        "restitution": _number(
            "normal.restitution", restitution, "the coefficient of restitution c_e"
        ),
        **params,
    }


def friction(law: str = "none", **params: Any) -> Dict[str, Any]:
    """A friction law (``[clearance.friction]``): ``none``, ``coulomb`` (``mu``, ``v_reg`` in
    m/s), ``ambrosio`` (``mu``, ``v0``, ``v1`` in m/s), ``threlfall``, ``stribeck``, ``lugre``
    (``sigma0`` N/m, ``sigma1`` N·s/m, ``sigma2`` N·s/m, ...)."""
    return {"law": _text("friction.law", law, "the law (none, coulomb, ambrosio, ...)"), **params}


def motion(kind: str, **params: Any) -> Dict[str, Any]:
    """A time function (drivers' ``motion``, actuators' ``force``, torques): ``constant``
    (``value``), ``linear`` (``initial``, ``rate``), ``ramp``, ``sine``, ``polynomial``,
    ``table``, ``sum``, ``product``, or ``input`` (``name``: the value of an
    :meth:`Model.input`, set by a co-simulation master) (docs/model-file.md, "Time
    functions")."""
    return {"type": _text("motion.type", kind, "the kind (constant, linear, sine, ...)"), **params}


def _element(doc: Mapping[str, Any], section: str, k: Optional[int]) -> str:
    """``clearance 'B'`` for the item ``k`` of ``section`` in ``doc`` (``clearance[0]`` without
    a name), ``[solver]`` for a table."""
    if k is None:
        return f"[{section}]"
    items = doc.get(section)
    item = items[k] if isinstance(items, list) and k < len(items) else None
    name = item.get("name") if isinstance(item, Mapping) else None
    if isinstance(name, str):
        return f"{section} {name!r}"
    return f"{section}[{k}]"


def _without_name(message: str, section: str, element: str) -> str:
    """The reader's message without its own ``body `crank`: `` prefix when the element is
    named already."""
    m = re.match(r"^(\w+) '(.*)'$", element)
    if m is None:
        return message
    name = m.group(2)
    for prefix in (f"{section} `{name}`: ", f"{name}: "):
        if message.startswith(prefix):
            return message[len(prefix):]
    return message


def _vec(v: Any) -> Any:
    """Two-vectors and other sequences as lists of floats (numpy arrays included)."""
    if v is None or isinstance(v, (str, dict)):
        return v
    if hasattr(v, "tolist"):
        v = v.tolist()
    if isinstance(v, (list, tuple)):
        return [_vec(x) for x in v]
    return v


class Model:
    """A model under construction: the dict of a model file, filled by one method per element.

    >>> m = Model("pendulum", gravity=(0.0, -9.81))
    >>> m.body("rod", mass=1.0, inertia=0.0833, position=(0.5, 0.0))
    >>> m.revolute("O", a=at("ground"), b=at("rod", -0.5, 0.0))
    >>> m.output(t_end=1.0)

    Every method returns the model, so calls can be chained. Each call checks its element with
    the model-file reader in the context of the model so far and refuses it with a
    :class:`clr_sim.errors.FieldError` naming the element, the field and the script line
    (``script.py:12: clearance 'B': field `clearance[0].normal.restitution`: ...``); a refused
    element is not added. Names of bodies, points, beams and shapes not defined yet are checked
    when the model is used (:meth:`check`, :meth:`to_toml`, :func:`clr_sim.simulate`), with the
    element's name and the line that added it.
    """

    #: ``"planar"`` or ``"spatial"``: the engine the model is for.
    space = "planar"

    def __new__(cls, name: Optional[str] = None, *, space: Optional[str] = None, **_: Any):
        # `Model(space="spatial")` is a SpatialModel: the same plumbing, the spatial methods
        if cls is Model and space == "spatial":
            cls = SpatialModel
        return super().__new__(cls)

    def __init__(
        self,
        name: Optional[str] = None,
        *,
        space: Optional[str] = None,
        description: Optional[str] = None,
        gravity: Optional[Vec2] = None,
        clearance_force_application: Optional[str] = None,
    ):
        """``name`` and ``description`` for reports, ``space`` (``"planar"``, the default, or
        ``"spatial"``: then the model is a :class:`SpatialModel` with the methods of a spatial
        model file), ``gravity`` [g_x, g_y] (m/s²; default none; [g_x, g_y, g_z] for a spatial
        model), ``clearance_force_application`` (``common_point`` or ``contact_points``; planar
        only)."""
        self._doc: Dict[str, Any] = {}
        # (section, index) → the script line that added the item
        self._sites: Dict[Tuple[str, int], str] = {}
        self._label = f"<clr_sim.Model {name!r}>" if name else "<clr_sim.Model>"
        self._set_table(
            "model",
            name=name,
            description=description,
            space=space,
            gravity=gravity,
            clearance_force_application=clearance_force_application,
        )

    # ----- reading and writing -----------------------------------------------------------

    @classmethod
    def from_dict(cls, doc: Mapping[str, Any]) -> "Model":
        """A model from the dict of a model file (``{"model": {...}, "body": [{...}], ...}``),
        e.g. ``tomllib.load`` of a file or :meth:`to_dict` of another model (copied)."""
        info = doc.get("model")
        spatial = isinstance(info, Mapping) and info.get("space") == "spatial"
        m = SpatialModel() if spatial else Model()
        m._doc = copy.deepcopy(dict(doc))
        m._sites = {}
        name = m._doc.get("model", {}).get("name")
        m._label = f"<clr_sim.Model {name!r}>" if name else "<clr_sim.Model>"
        return m

    @classmethod
    def from_toml(cls, text: str) -> "Model":
        """A model from the text of a model file (either form: generic, or ``[model] builtin``
        with ``[parameters]``). Errors name the line and column of ``text``."""
        m = cls()
        m._doc = {}
        m._text = text
        m._label = "<toml text>"
        return m

    @classmethod
    def from_file(cls, path: Union[str, "os.PathLike[str]"]) -> "Model":
        """A model from a model file; errors name the file, line and field."""
        m = cls()
        m._doc = {}
        m._path = os.fspath(path)
        m._label = m._path
        return m

    def to_dict(self) -> Dict[str, Any]:
        """The model-file dict (a deep copy) of a model built in Python or from a dict."""
        if self._source() is not None:
            raise ModelError(
                "a model read from TOML is held as text; use to_toml() for its checked form",
                field="",
            )
        return copy.deepcopy(self._doc)

    def to_toml(self) -> str:
        """The checked model as model-file text, every section written as ``clr export`` writes
        it (a built-in model file: its ``[model] builtin`` form with every parameter).

        Raises :class:`clr_sim.errors.FieldError` for anything the model file would refuse."""
        return self._job().to_toml()

    def check(self) -> List[str]:
        """Check the model as ``clr run`` would read it; returns the notes (what reading it
        changed on its own, one sentence each). Raises :class:`clr_sim.errors.FieldError`."""
        return list(self._job().notes)

    def _source(self) -> Optional[Tuple[str, str]]:
        if getattr(self, "_text", None) is not None:
            return ("text", self._text)
        if getattr(self, "_path", None) is not None:
            return ("path", self._path)
        return None

    def _job(
        self,
        set: Optional[Mapping[str, Any]] = None,
        t_end: Optional[float] = None,
        rtol: Optional[float] = None,
    ) -> "_native.JobCore":
        sets = None if set is None else dict(set)
        src = self._source()
        if src is None:
            try:
                return _native.JobCore.from_dict(self._doc, self._label, sets, t_end, rtol)
            except FieldError as e:
                raise self._named(e) from None
        kind, value = src
        if kind == "text":
            return _native.JobCore.from_text(value, self._label, sets, t_end, rtol)
        return _native.JobCore.from_target(value, sets, t_end, rtol)

    def __repr__(self) -> str:
        src = self._source()
        if src is not None:
            return f"Model.from_{'toml' if src[0] == 'text' else 'file'}({self._label!r})"
        counts = ", ".join(
            f"{len(self._doc[s])} {s}" for s in _LISTS if self._doc.get(s)
        )
        return f"Model({self._doc.get('model', {}).get('name')!r}: {counts or 'empty'})"

    # ----- plumbing ----------------------------------------------------------------------

    def _builder(self) -> Dict[str, Any]:
        if self._source() is not None:
            raise ModelError(
                "this model was read from TOML; build in Python with Model() or "
                "Model.from_dict(), or edit the file",
                field="",
            )
        return self._doc

    def _named(self, e: FieldError) -> FieldError:
        """``e`` (from the reader, placed at ``clearance[0].…``) with the element's name and
        the script line that added it."""
        m = re.match(r"^(\w+)(?:\[(\d+)\])?(?:[.\[]|$)", e.field or "")
        if m is None or e.element is not None or e.file != self._label:
            return e
        section, k = m.group(1), m.group(2)
        index = None if k is None else int(k)
        if index is None and section not in _TABLES:
            return e
        element = _element(self._doc, section, index)
        return type(e)(
            _without_name(e.message, section, element),
            field=e.field,
            file=e.file,
            element=element,
            added_at=self._sites.get((section, -1 if index is None else index)) or None,
        )

    def _check(self, doc: Dict[str, Any], section: str, k: Optional[int]) -> None:
        """Check the element ``k`` of ``section`` (a table when ``k`` is None) in ``doc``, the
        model so far with it (see :meth:`_native.JobCore._check_element`); raise its
        FieldError with the element's name and the caller's line."""
        path = section if k is None else f"{section}[{k}]"
        try:
            _native.JobCore._check_element(doc, path, self._label)
        except FieldError as e:
            element = _element(doc, section, k)
            raise FieldError(
                _without_name(e.message, section, element),
                field=e.field,
                file=e.file,
                element=element,
                where=_caller(),
            ) from None

    def _set_table(self, section: str, **fields: Any) -> "Model":
        builder = self._builder()
        table = dict(builder.get(section, {}))
        for k, v in fields.items():
            if v is not None:
                table[k] = _vec(v)
        doc = dict(builder)
        if table:
            doc[section] = table
            self._check(doc, section, None)
            builder[section] = table
            self._sites[(section, -1)] = _caller() or ""  # "" when called from the package
        else:
            builder.pop(section, None)
        return self

    def _add(
        self, section: str, kind: Optional[str], name: Any = None, /, **fields: Any
    ) -> "Model":
        # positional-only: `section` is also a field (a beam's cross-section), and the methods
        # that pass their locals() give `name` as a keyword
        name = fields.pop("name", name)
        item: Dict[str, Any] = {"name": name}
        if kind is not None:
            item["type"] = kind
        item.update({k: _vec(v) for k, v in fields.items() if v is not None})
        builder = self._builder()
        items = list(builder.get(section, []))
        items.append(item)
        doc = dict(builder)
        doc[section] = items
        self._check(doc, section, len(items) - 1)
        builder[section] = items
        self._sites[(section, len(items) - 1)] = _caller() or ""
        return self

    # ----- [model], [solver], [output] ---------------------------------------------------

    def solver(
        self,
        *,
        method: Optional[str] = None,
        rtol: Optional[float] = None,
        atol: Optional[float] = None,
        h_max: Optional[float] = None,
        max_steps: Optional[int] = None,
        baumgarte_alpha: Optional[float] = None,
        baumgarte_beta: Optional[float] = None,
        projection: Optional[bool] = None,
        contact_events: Optional[bool] = None,
        jacobian: Optional[str] = None,
        max_order: Optional[int] = None,
        linear_solver: Optional[str] = None,
        scale_velocity_error: Optional[bool] = None,
        newton_rate_reuse: Optional[bool] = None,
        initial_conditions: Optional[str] = None,
        initial_state: Optional[str] = None,
        free_bodies: Optional[Sequence[str]] = None,
        strict: Optional[bool] = None,
    ) -> "Model":
        """``[solver]``: ``method`` (``ndf`` or ``dopri5``), ``rtol`` (–), ``atol`` (mixed
        units; default 1e-3·rtol), ``h_max`` (s), ``max_steps``, Baumgarte ``baumgarte_alpha``
        (1/s) and ``baumgarte_beta`` (1/s²), ``projection``, ``contact_events``, NDF settings
        (``jacobian``, ``max_order``, ``linear_solver``, ``scale_velocity_error``,
        ``newton_rate_reuse``), ``initial_conditions`` (``assemble`` or ``exact``),
        ``initial_state`` (``ideal``: clearance joints start as their ideal joints, or
        ``as_given``), ``free_bodies`` (bodies deliberately left free) and ``strict`` (refuse
        plausibility warnings); docs/model-file.md#initial-conditions."""
        return self._set_table("solver", **{k: v for k, v in locals().items() if k != "self"})

    def output(
        self,
        *,
        t_end: Optional[float] = None,
        t_start: Optional[float] = None,
        intervals: Optional[int] = None,
        every_step: Optional[bool] = None,
        nodes: Optional[Table] = None,
    ) -> "Model":
        """``[output]``: the span [``t_start``, ``t_end``] (s), recorded at ``intervals`` equal
        intervals and/or after ``every_step`` accepted step; ``nodes`` (``[output.nodes]``)
        records nodes of flexible bodies and beams, ``{"rod": [4, 8], "cant": "all"}``
        (columns ``rod.node4.ux``, ``.uy`` m, ``.rz`` rad, ``.x``, ``.y`` m)."""
        return self._set_table("output", **{k: v for k, v in locals().items() if k != "self"})

    # ----- bodies, points, beams ---------------------------------------------------------

    def body(
        self,
        name: str,
        *,
        mass: Optional[float] = None,
        inertia: Optional[float] = None,
        shape: Optional[Table] = None,
        material: Optional[str] = None,
        density: Optional[float] = None,
        between: Optional[Sequence[Vec2]] = None,
        position: Optional[Vec2] = None,
        angle: Optional[float] = None,
        velocity: Optional[Vec2] = None,
        angular_velocity: Optional[float] = None,
        centre_of_mass: Optional[Vec2] = None,
    ) -> "Model":
        """``[[body]]``: a rigid body of ``mass`` (kg) and ``inertia`` (kg·m², about its centre
        of mass); its frame at ``position`` (m) and ``angle`` (rad) moving with ``velocity``
        (m/s) and ``angular_velocity`` (rad/s); ``centre_of_mass`` (m) in the body frame. An
        initial coordinate left out is solved by the assembly of consistent initial
        conditions; one given is kept (docs/model-file.md, "Initial conditions"). Instead of
        ``mass`` and ``inertia``: ``shape`` (``{"bar": {...}}``) with ``material`` or ``density``
        (kg/m³); instead of ``position`` and ``angle``: ``between`` two points (m); see
        :mod:`clr_sim.inertia`."""
        return self._add("body", None, **{k: v for k, v in locals().items() if k != "self"})

    def point(
        self,
        name: str,
        *,
        body: Optional[str] = None,
        at: Optional[Vec2] = None,
        beam: Optional[str] = None,
        node: Optional[int] = None,
    ) -> "Model":
        """``[[point]]``: a named point, (``at``, m) on ``body``, or ``node`` of ``beam``."""
        return self._add("point", None, **{k: v for k, v in locals().items() if k != "self"})

    def beam(
        self,
        name: str,
        *,
        start: Vec2,
        end: Vec2,
        elements: int,
        material: Table,
        section: Table,
        supports: Optional[Sequence[Table]] = None,
        rayleigh: Optional[Vec2] = None,
        mass: Optional[str] = None,
    ) -> "Model":
        """``[[beam]]``: a ground-fixed planar Euler–Bernoulli beam from ``start`` to ``end``
        (m) with ``elements`` elements; ``material`` ``{youngs_modulus (Pa), density (kg/m³)}``,
        ``section`` (e.g. ``{"shape": "rectangular", "width": m, "depth": m}``), ``supports``
        (``[{"node": 0, "type": "clamped"}]``), ``rayleigh`` damping [α (1/s), β (s)],
        ``mass`` (``consistent`` or ``lumped``); as in tests/data/cantilever.toml."""
        return self._add("beam", None, **{k: v for k, v in locals().items() if k != "self"})

    def flexible_body(
        self,
        name: str,
        *,
        beam: Table,
        reduction: Table,
        pose: Optional[Sequence[float]] = None,
        velocity: Optional[Sequence[float]] = None,
    ) -> "Model":
        """``[[flexible_body]]``: a floating-frame flexible body: its ``beam`` mesh (as
        :meth:`beam` without name), the modal ``reduction``, the frame ``pose`` [x, y, θ] (m,
        rad) and ``velocity`` [vx, vy, ω] (m/s, rad/s); left at ``None`` they are solved by the
        assembly (the elastic coordinates always start undeformed and at rest)."""
        return self._add(
            "flexible_body", None, **{k: v for k, v in locals().items() if k != "self"}
        )

    # ----- [[joint]] ---------------------------------------------------------------------

    def revolute(self, name: str, *, a: Anchor, b: Anchor) -> "Model":
        """Ideal revolute joint: anchors ``a`` and ``b`` coincide."""
        return self._add("joint", "revolute", name, a=a, b=b)

    def fixed(self, name: str, *, a: Anchor, b: Anchor) -> "Model":
        """Fixed joint: the two frames keep their initial relative pose."""
        return self._add("joint", "fixed", name, a=a, b=b)

    def translational(self, name: str, *, a: Anchor, b: Anchor, axis: Vec2) -> "Model":
        """Ideal translational joint: ``b`` slides along ``axis`` (in the frame of ``a``'s
        body) without relative rotation."""
        return self._add("joint", "translational", name, a=a, b=b, axis=axis)

    # ----- [[driver]] --------------------------------------------------------------------

    def drive_angle(self, name: str, *, body: str, motion: Table) -> "Model":
        """Prescribed absolute angle θ(t) (rad) of ``body`` (``motion``: :func:`motion`)."""
        return self._add("driver", "angle", name, body=body, motion=motion)

    def drive_relative_angle(
        self, name: str, *, body_i: str, body_j: str, motion: Table
    ) -> "Model":
        """Prescribed relative angle θ_j − θ_i (rad) of time."""
        return self._add(
            "driver", "relative_angle", name, body_i=body_i, body_j=body_j, motion=motion
        )

    def drive_displacement(
        self, name: str, *, a: Anchor, b: Anchor, axis: Vec2, motion: Table
    ) -> "Model":
        """Prescribed displacement (m) of ``b`` from ``a`` along ``axis`` (frame of ``a``)."""
        return self._add(
            "driver", "displacement", name, a=a, b=b, axis=axis, motion=motion
        )

    # ----- [[force]] ---------------------------------------------------------------------

    def spring_damper(
        self,
        name: str,
        *,
        a: Anchor,
        b: Anchor,
        stiffness: Optional[float] = None,
        damping: Optional[float] = None,
        free_length: Optional[float] = None,
    ) -> "Model":
        """Translational spring–damper between ``a`` and ``b``: ``stiffness`` (N/m),
        ``damping`` (N·s/m), ``free_length`` (m; default the initial distance)."""
        return self._add(
            "force", "spring_damper", name, a=a, b=b, stiffness=stiffness, damping=damping,
            free_length=free_length,
        )

    def rotational_spring_damper(
        self,
        name: str,
        *,
        body_i: str,
        body_j: str,
        stiffness: Optional[float] = None,
        damping: Optional[float] = None,
        free_angle: Optional[float] = None,
    ) -> "Model":
        """Rotational spring–damper: ``stiffness`` (N·m/rad), ``damping`` (N·m·s/rad),
        ``free_angle`` (rad; default the initial relative angle)."""
        return self._add(
            "force", "rotational_spring_damper", name, body_i=body_i, body_j=body_j,
            stiffness=stiffness, damping=damping, free_angle=free_angle,
        )

    def actuator(
        self,
        name: str,
        *,
        a: Anchor,
        b: Anchor,
        force: Table,
        damping: Optional[float] = None,
    ) -> "Model":
        """Point-to-point actuator: axial ``force`` (N) of time (:func:`motion`), pushing ``b``
        away from ``a`` when positive, with ``damping`` (N·s/m)."""
        return self._add("force", "actuator", name, a=a, b=b, force=force, damping=damping)

    def bushing(
        self,
        name: str,
        *,
        a: Anchor,
        b: Anchor,
        stiffness: Optional[Any] = None,
        damping: Optional[Any] = None,
    ) -> "Model":
        """Linear bushing from ``a`` to ``b``: ``stiffness`` (N/m) and ``damping`` (N·s/m)."""
        return self._add("force", "bushing", name, a=a, b=b, stiffness=stiffness, damping=damping)

    def force(
        self,
        name: str,
        *,
        at: Anchor,
        fx: Optional[Table] = None,
        fy: Optional[Table] = None,
    ) -> "Model":
        """Applied force (N) at ``at``, components ``fx`` and ``fy`` of time (world frame)."""
        return self._add("force", "force", name, at=at, fx=fx, fy=fy)

    def torque(self, name: str, *, body: str, torque: Table) -> "Model":
        """Applied torque (N·m) of time on ``body``."""
        return self._add("force", "torque", name, body=body, torque=torque)

    def torque_between(
        self, name: str, *, body_i: str, body_j: str, torque: Table
    ) -> "Model":
        """Torque (N·m) of time on ``body_j``, its reaction on ``body_i``."""
        return self._add(
            "force", "torque_between", name, body_i=body_i, body_j=body_j, torque=torque
        )

    def nodal_load(
        self,
        name: str,
        *,
        beam: str,
        node: int,
        fx: Optional[Table] = None,
        fy: Optional[Table] = None,
        moment: Optional[Table] = None,
    ) -> "Model":
        """Load on ``node`` of ``beam``: ``fx``, ``fy`` (N) and ``moment`` (N·m) of time."""
        return self._add(
            "force", "nodal_load", name, beam=beam, node=node, fx=fx, fy=fy, moment=moment
        )

    # ----- [[shape]] ---------------------------------------------------------------------

    def shape(
        self,
        name: str,
        *,
        geometry: Table,
        at: Optional[Anchor] = None,
        angle: Optional[float] = None,
    ) -> "Model":
        """``[[shape]]``: a named contact shape. Its frame has its origin at ``at`` (a point
        name, :func:`at` on a body or ``"ground"``, or :func:`node` of a beam: the shape then
        moves with the node's small-rotation frame) and is turned by ``angle`` (rad, from the
        body's x axis; default 0). ``geometry`` (m, in the shape frame) is written by
        :mod:`clr_sim.shapes`: ``ball``, ``capsule``, ``cuboid``, ``convex_polygon``, ``polyline``,
        ``compound``, ``involute_gear``, or ``beam_face`` (the deformed face of a flexible beam:
        then without ``at`` and ``angle``; ``at`` is required for every other geometry). A shape
        does nothing on its own; :meth:`contact` puts two in contact."""
        return self._add("shape", None, name, at=at, angle=angle, geometry=geometry)

    # ----- [[clearance]] -----------------------------------------------------------------

    def contact(
        self,
        name: str,
        *,
        shapes: Sequence[str],
        normal: Table,
        friction: Optional[Table] = None,
        prediction: Optional[float] = None,
        merge_distance: Optional[float] = None,
        max_points: Optional[int] = None,
    ) -> "Model":
        """Contact between two :meth:`shape` s on different bodies (``[[clearance]] type =
        "contact"``): ``shapes`` = [A, B] (their names; the contact normal points from A to
        B), the ``normal`` law of each contact point (:func:`normal`: ``hertz``, ``power`` or
        ``linear`` with ``stiffness`` in N/m^n; the element gives no radii to material-based
        laws), ``friction`` (:func:`friction`; default none, LuGre refused), ``prediction``: the
        gap within which points are tracked before they touch (m; default a tenth of the smaller
        shape's bounding radius), ``merge_distance``: points of one patch closer than this merge
        into the deepest (m; default twice the longest segment of a polyline in the pair, else
        0), ``max_points``: most contact points at once (1–64, default 4). Onsets are located as
        events and impacts reported as for the clearance joints."""
        return self._add(
            "clearance", "contact", name, shapes=shapes, normal=normal, friction=friction,
            prediction=prediction, merge_distance=merge_distance, max_points=max_points,
        )


    def revolute_clearance(
        self,
        name: str,
        *,
        bearing: Anchor,
        journal: Anchor,
        bearing_radius: float,
        journal_radius: float,
        normal: Table,
        friction: Optional[Table] = None,
        force_application: Optional[str] = None,
        bearing_wear: Optional[Sequence[float]] = None,
        lubrication: Optional[Table] = None,
        initial_eccentricity: Optional[Any] = None,
    ) -> "Model":
        """Revolute clearance joint: a journal of radius ``journal_radius`` (m) centred at
        ``journal`` inside a bearing of radius ``bearing_radius`` (m) centred at ``bearing``;
        contact by the ``normal`` law (:func:`normal`), ``friction`` (:func:`friction`; default
        none), ``force_application`` (``common_point`` or ``contact_points``), ``bearing_wear``:
        the worn bearing's radial wear depth (m) at N ≥ 8 equally spaced angles in the bearing
        body frame (docs/wear.md), ``lubrication``: an oil film ``{"model": "short_bearing" |
        "long_bearing", "viscosity": Pa·s, "length": m, "film_threshold": m, "dry_threshold":
        m}`` (docs/lubrication.md), ``initial_eccentricity``: where the journal starts from the
        bearing centre, ``(e_x, e_y)`` m in the bearing body frame or ``{"magnitude": m,
        "angle": rad}``."""
        return self._add(
            "clearance", "revolute", name, bearing=bearing, journal=journal,
            bearing_radius=bearing_radius, journal_radius=journal_radius, normal=normal,
            friction=friction, force_application=force_application, bearing_wear=bearing_wear,
            lubrication=lubrication, initial_eccentricity=initial_eccentricity,
        )

    def translational_clearance(
        self,
        name: str,
        *,
        guide: Anchor,
        slider: Anchor,
        guide_width: float,
        slider_length: float,
        slider_height: float,
        normal: Table,
        guide_angle: Optional[float] = None,
        slider_angle: Optional[float] = None,
        friction: Optional[Table] = None,
        initial_offset: Optional[float] = None,
    ) -> "Model":
        """Translational clearance joint: a rectangular slider (``slider_length`` ×
        ``slider_height``, m, at ``slider``, tilted ``slider_angle`` rad) between two parallel
        guide faces ``guide_width`` (m) apart (centre line through ``guide`` at ``guide_angle``
        rad); corner contacts by ``normal``, ``friction``; ``initial_offset`` (m): where the
        slider centre starts across the guide."""
        return self._add(
            "clearance", "translational", name, guide=guide, slider=slider,
            guide_width=guide_width, guide_angle=guide_angle, slider_length=slider_length,
            slider_height=slider_height, slider_angle=slider_angle, normal=normal,
            friction=friction, initial_offset=initial_offset,
        )

    def slider_on_beam(
        self,
        name: str,
        *,
        beam: str,
        slider: Anchor,
        face: Any,
        slider_length: float,
        slider_height: float,
        face_points: int,
        normal: Table,
        slider_angle: Optional[float] = None,
        guide_samples: Optional[int] = None,
        area_normal: Optional[Table] = None,
        friction: Optional[Table] = None,
    ) -> "Model":
        """A rectangular slider (m) on a face of the flexible ``beam`` (``face``), with
        multipoint contact at ``face_points`` points per face, ``guide_samples`` samples of the
        deformed guide, the ``normal`` law (and ``area_normal`` for area contact), ``friction``."""
        return self._add(
            "clearance", "slider_on_beam", name, beam=beam, slider=slider, face=face,
            slider_length=slider_length, slider_height=slider_height, slider_angle=slider_angle,
            face_points=face_points, guide_samples=guide_samples, normal=normal,
            area_normal=area_normal, friction=friction,
        )

    # ----- [[measure]]: named outputs (docs/model-file.md "Measures") --------------------

    def measure_position(self, name: str, *, at: Anchor, frame: Optional[str] = None) -> "Model":
        """Columns ``<name>.x``, ``<name>.y`` (m; and ``<name>.z`` in a spatial model, ``at``
        then a :func:`clr_sim.spatial.at`): the point ``at`` in the world, or its coordinates in
        the frame of body ``frame``."""
        return self._add("measure", "position", name, at=at, frame=frame)

    def measure_velocity(self, name: str, *, at: Anchor, frame: Optional[str] = None) -> "Model":
        """Columns ``<name>.vx``, ``<name>.vy`` (m/s; and ``.vz`` in a spatial model): the
        velocity of the point ``at``, or the rate of its coordinates in the frame of body
        ``frame``."""
        return self._add("measure", "velocity", name, at=at, frame=frame)

    def measure_acceleration(
        self, name: str, *, at: Anchor, frame: Optional[str] = None
    ) -> "Model":
        """Columns ``<name>.ax``, ``<name>.ay`` (m/s²; and ``.az`` in a spatial model): as
        :meth:`measure_velocity`, once more differentiated."""
        return self._add("measure", "acceleration", name, at=at, frame=frame)

    def measure_angle(
        self,
        name: str,
        *,
        body: str,
        relative_to: Optional[str] = None,
        offset: Optional[float] = None,
    ) -> "Model":
        """Column ``<name>.angle`` (rad): θ of ``body`` − θ of ``relative_to`` (default the
        ground) − ``offset`` (rad)."""
        return self._add(
            "measure", "angle", name, body=body, relative_to=relative_to, offset=offset
        )

    def measure_angular_velocity(
        self, name: str, *, body: str, relative_to: Optional[str] = None
    ) -> "Model":
        """Column ``<name>.omega`` (rad/s), relative to ``relative_to`` (default the ground)."""
        return self._add("measure", "angular_velocity", name, body=body, relative_to=relative_to)

    def measure_angular_acceleration(
        self, name: str, *, body: str, relative_to: Optional[str] = None
    ) -> "Model":
        """Column ``<name>.alpha`` (rad/s²), relative to ``relative_to`` (default the ground)."""
        return self._add(
            "measure", "angular_acceleration", name, body=body, relative_to=relative_to
        )

    def measure_distance(self, name: str, *, a: Anchor, b: Anchor) -> "Model":
        """Columns ``<name>.distance`` (m) and ``<name>.distance_rate`` (m/s) between two
        points (planar or spatial)."""
        return self._add("measure", "distance", name, a=a, b=b)

    def measure_reaction(self, name: str, *, joint: str, frame: Optional[str] = None) -> "Model":
        """Columns ``<name>.Fx``, ``<name>.Fy`` (N) and ``<name>.M`` (N·m): the reaction of
        ``joint`` (or a driver), in the world axes or those of body ``frame``."""
        return self._add("measure", "reaction", name, joint=joint, frame=frame)

    def measure_contact(self, name: str, *, element: str, quantity: str) -> "Model":
        """Column ``<name>.<quantity>``: one quantity (``normal_force``, ``penetration``, ...)
        of the contact element ``element``."""
        return self._add("measure", "contact", name, element=element, quantity=quantity)

    def measure_energy(self, name: str, *, term: str) -> "Model":
        """Column ``<name>.energy`` (J): the energy ``term`` (``kinetic``, ``total``, ...)."""
        return self._add("measure", "energy", name, term=term)

    def measure_momentum(
        self,
        name: str,
        *,
        bodies: Optional[Sequence[str]] = None,
        about: Optional[Vec2] = None,
        scales: Optional[bool] = None,
    ) -> "Model":
        """Columns ``<name>.px``, ``<name>.py`` (kg·m/s) and ``<name>.L`` (kg·m²/s, about the
        world point ``about``, m) of the rigid ``bodies`` (default all, in a model without
        flexible parts); with ``scales=True`` also ``<name>.p_scale`` = Σ m|v| (kg·m/s) and
        ``<name>.L_scale`` = Σ (|Iω| + m|r × v|) (kg·m²/s), the sizes a drift is judged
        against."""
        bodies = None if bodies is None else list(bodies)
        return self._add("measure", "momentum", name, bodies=bodies, about=about, scales=scales)

    def measure_combination(
        self, name: str, *, terms: Sequence[Dict[str, Any]], unit: Optional[str] = None
    ) -> "Model":
        """Column ``<name>.value`` = Σ factor · x over the ``terms``, each a dict
        ``{"of": column or [columns multiplied], "factor": 1.0, "abs": False}`` reading the
        run's columns and those of earlier measures (the total normal force of several pads,
        |friction| summed, a power F·v); ``unit`` (``"N"``, ``"W"``, ...) is needed when the
        terms' units differ or a term is a product."""
        return self._add("measure", "combination", name, terms=[dict(t) for t in terms], unit=unit)

    def measure_deviation(
        self, name: str, *, of: Sequence[str], suffix: Optional[str] = None
    ) -> "Model":
        """Column ``<name>.error`` (or ``<name>.<suffix>``): the columns ``of`` minus those of
        the ideal-joint twin (every clearance joint made ideal, run alongside): a signed
        difference for one column, the distance for several (an end-effector's ``.x`` and
        ``.y``); :meth:`twin` sets how the twin records."""
        return self._add("measure", "deviation", name, of=list(of), suffix=suffix)

    def input(
        self, name: str, *, default: Optional[Table] = None, description: Optional[str] = None
    ) -> "Model":
        """``[[input]]``: a named real input that forces, torques, actuators and drivers take
        as ``motion("input", name=...)``; its value is the time function ``default``
        (default constant 0, in the unit of what it drives: N, N·m, m or rad) until a
        co-simulation master sets it (an FMU of the model, :func:`clr_sim.fmu.export`).
        ``description`` is written into the FMU."""
        return self._add("input", None, name, default=default, description=description)

    def twin(self, *, intervals: Optional[int] = None) -> "Model":
        """``[twin]``: the ideal-joint twin of the deviation measures records at ``intervals``
        equal intervals (default: those of :meth:`output`, 1000 with ``every_step`` only)."""
        return self._set_table("twin", intervals=intervals)

    def metric(
        self,
        name: str,
        *,
        statistic: str,
        of: Optional[Union[str, Sequence[str]]] = None,
        metrics: Optional[Sequence[str]] = None,
        t_start: Optional[float] = None,
        t_end: Optional[float] = None,
        window: Optional[float] = None,
        period: Optional[float] = None,
        phases: Optional[int] = None,
        per: Optional[Union[float, str]] = None,
        twin: Optional[bool] = None,
        unit: Optional[str] = None,
        description: Optional[str] = None,
    ) -> "Model":
        """``[[metric]]``: ``statistic`` of column ``of`` (or of several columns taken
        together, or of the earlier ``metrics``) over [``t_start``, ``t_end``] (s; default the
        whole run), in ``Result.metrics``. Statistics: ``peak``, ``max``, ``min``, ``mean``,
        ``rms``, ``final``, ``time_of_peak``, ``time_of_max``, ``time_of_min``, ``change``,
        ``drift``, ``integral``, ``onsets``, ``oscillation`` (about a running mean over
        ``window`` s), ``spread`` (stroboscopic, every ``period`` s at ``phases`` phases) and,
        of metrics, ``sum``. ``per`` divides by a number or an earlier metric; ``twin=True``
        takes the column of the ideal-joint twin; ``unit`` overrides the unit; ``description``
        replaces the generated one in summary.json and the report (docs/model-file.md)."""
        return self._add(
            "metric",
            None,
            name,
            of=of if of is None or isinstance(of, str) else list(of),
            metrics=None if metrics is None else list(metrics),
            statistic=statistic,
            t_start=t_start,
            t_end=t_end,
            window=window,
            period=period,
            phases=phases,
            per=per,
            twin=twin,
            unit=unit,
            description=description,
        )


#: A 3-vector (m, m/s, rad/s or N): a tuple, list or numpy array of three numbers.
Vec3 = Union[Sequence[float], Tuple[float, float, float]]
#: Rows of a 3 × 3 matrix.
Rows3 = Sequence[Vec3]


class SpatialModel(Model):
    """A spatial model under construction (``[model] space = "spatial"``,
    docs/model-file.md "Spatial models"): what ``Model(space="spatial")`` returns.

    >>> from clr_sim import spatial
    >>> m = Model("top", space="spatial", gravity=(0.0, 0.0, -9.81))
    >>> m.body("top", mass=0.5, principal_inertia=(1.2e-4, 1.2e-4, 2e-4),
    ...        centre_of_mass=(0.0, 0.0, 0.04), orientation=spatial.axis_angle((1, 0, 0), 0.3))
    >>> m.spherical("tip", a=spatial.at("ground"), b=spatial.at("top"))

    The same plumbing as :class:`Model` (each call checked by the spatial model-file reader,
    errors naming the element, the field and the script line; names of bodies and joints not
    defined yet checked when the model is used), with one method per element kind of a spatial
    file. Ends (``a``, ``b``, ``at``, ``socket``, ``ball``) are :func:`clr_sim.spatial.at`
    dicts: a body (``"ground"`` for the fixed frame), a point in its frame (m) and, for joints,
    an ``axis``; orientations are written by :func:`clr_sim.spatial.quaternion`,
    :func:`~clr_sim.spatial.axis_angle`, :func:`~clr_sim.spatial.euler` and
    :func:`~clr_sim.spatial.matrix`. A planar method (``translational``, ``drive_angle``,
    ``translational_clearance``, ...) raises :class:`clr_sim.errors.ModelError` naming the spatial
    one to use. The planar joint kind (``type = "planar"``) is :meth:`planar_joint`: ``planar``
    alone would read as the space.
    """

    space = "spatial"

    def __init__(
        self,
        name: Optional[str] = None,
        *,
        space: Optional[str] = None,
        description: Optional[str] = None,
        gravity: Optional[Vec3] = None,
        clearance_force_application: Optional[str] = None,
    ):
        """As :class:`Model`; ``space`` is ``"spatial"`` (the default here), ``gravity``
        [g_x, g_y, g_z] (m/s²; default none). ``clearance_force_application`` is refused (the
        spherical clearance joint's force pair acts at the midpoint of the contact points)."""
        if space not in (None, "spatial"):
            raise _refuse("model.space", f"a SpatialModel is spatial; for space={space!r} use Model")
        super().__init__(
            name,
            space="spatial",
            description=description,
            gravity=gravity,
            clearance_force_application=clearance_force_application,
        )

    # ----- [[body]] ----------------------------------------------------------------------

    def body(
        self,
        name: str,
        *,
        mass: float,
        inertia: Optional[Rows3] = None,
        principal_inertia: Optional[Vec3] = None,
        principal_axes: Optional[Rows3] = None,
        centre_of_mass: Optional[Vec3] = None,
        position: Optional[Vec3] = None,
        orientation: Optional[Table] = None,
        velocity: Optional[Vec3] = None,
        velocity_frame: Optional[str] = None,
        angular_velocity: Optional[Vec3] = None,
        angular_velocity_frame: Optional[str] = None,
    ) -> "Model":
        """``[[body]]``: a rigid body of ``mass`` (kg) with the ``inertia`` tensor at its
        centre of mass in the body frame (kg·m², rows of a symmetric positive definite matrix)
        or ``principal_inertia`` (kg·m²) along ``principal_axes`` (rows, unit vectors in the
        body frame; default the body axes); ``centre_of_mass`` (m) in the body frame. Its frame
        starts at ``position`` (m, world) with ``orientation`` (:mod:`clr_sim.spatial`:
        ``quaternion``, ``axis_angle``, ``euler``, ``matrix``; default aligned with the world),
        moving with ``velocity`` (m/s, of the frame origin) in ``velocity_frame`` and
        ``angular_velocity`` (rad/s) in ``angular_velocity_frame`` (``"world"`` or ``"body"``,
        required with the vector). An initial value left out is solved by the assembly."""
        return self._add("body", None, **{k: v for k, v in locals().items() if k != "self"})

    # ----- [[joint]] ---------------------------------------------------------------------

    def spherical(self, name: str, *, a: Anchor, b: Anchor) -> "Model":
        """Spherical joint: the points of ``a`` and ``b`` coincide (no ``axis``)."""
        return self._add("joint", "spherical", name, a=a, b=b)

    def revolute(self, name: str, *, a: Anchor, b: Anchor) -> "Model":
        """Revolute joint: the points coincide and ``b`` turns about ``a``'s ``axis`` (``b``'s
        axis defaults to ``a``'s at the initial poses)."""
        return self._add("joint", "revolute", name, a=a, b=b)

    def universal(self, name: str, *, a: Anchor, b: Anchor) -> "Model":
        """Universal (Cardan) joint: the points coincide; ``a``'s ``axis`` on a and ``b``'s
        ``axis`` on b stay perpendicular."""
        return self._add("joint", "universal", name, a=a, b=b)

    def cylindrical(self, name: str, *, a: Anchor, b: Anchor) -> "Model":
        """Cylindrical joint: ``b`` slides along and turns about ``a``'s ``axis`` through
        ``a``'s point."""
        return self._add("joint", "cylindrical", name, a=a, b=b)

    def prismatic(self, name: str, *, a: Anchor, b: Anchor) -> "Model":
        """Prismatic joint: ``b`` slides along ``a``'s ``axis`` without turning."""
        return self._add("joint", "prismatic", name, a=a, b=b)

    def planar_joint(self, name: str, *, a: Anchor, b: Anchor) -> "Model":
        """Planar joint (``type = "planar"``): ``b`` moves in the plane through ``a``'s point
        with normal ``a``'s ``axis``."""
        return self._add("joint", "planar", name, a=a, b=b)

    def fixed(self, name: str, *, a: Anchor, b: Anchor) -> "Model":
        """Fixed joint: ``b`` is welded to ``a`` at the initial poses (no ``axis``)."""
        return self._add("joint", "fixed", name, a=a, b=b)

    # ----- [[driver]] --------------------------------------------------------------------

    def drive_revolute_angle(self, name: str, *, joint: str, motion: Table) -> "Model":
        """Prescribed angle (rad) of a revolute or cylindrical ``joint``: ``b``'s turn about
        the axis relative to ``a``, zero at the initial poses (``motion``: :func:`motion`)."""
        return self._add("driver", "revolute_angle", name, joint=joint, motion=motion)

    def drive_prismatic_displacement(self, name: str, *, joint: str, motion: Table) -> "Model":
        """Prescribed displacement (m) of a prismatic or cylindrical ``joint`` along its axis,
        zero at the initial poses (``motion``: :func:`motion`)."""
        return self._add("driver", "prismatic_displacement", name, joint=joint, motion=motion)

    # ----- [[force]] ---------------------------------------------------------------------

    def spring_damper(
        self,
        name: str,
        *,
        a: Anchor,
        b: Anchor,
        stiffness: Optional[float] = None,
        damping: Optional[float] = None,
        free_length: Optional[float] = None,
    ) -> "Model":
        """Point-to-point spring–damper, tension k(ℓ − ℓ₀) + c ℓ̇: ``stiffness`` k (N/m),
        ``damping`` c (N·s/m), ``free_length`` ℓ₀ (m; default 0)."""
        return self._add(
            "force", "spring_damper", name, a=a, b=b, stiffness=stiffness, damping=damping,
            free_length=free_length,
        )

    def actuator(self, name: str, *, a: Anchor, b: Anchor, force: Table) -> "Model":
        """Point-to-point actuator: ``force`` (N) of time (:func:`motion`), positive pushing
        ``a`` and ``b`` apart."""
        return self._add("force", "actuator", name, a=a, b=b, force=force)

    def rotational_spring_damper(
        self,
        name: str,
        *,
        joint: str,
        stiffness: Optional[float] = None,
        damping: Optional[float] = None,
        free_angle: Optional[float] = None,
    ) -> "Model":
        """Rotational spring–damper about the axis of a revolute or cylindrical ``joint``:
        torque −k(θ − θ₀) − c θ̇ on b, ``stiffness`` k (N·m/rad), ``damping`` c (N·m·s/rad),
        ``free_angle`` θ₀ (rad; θ is zero at the initial poses)."""
        return self._add(
            "force", "rotational_spring_damper", name, joint=joint, stiffness=stiffness,
            damping=damping, free_angle=free_angle,
        )

    def bushing(
        self,
        name: str,
        *,
        a: Anchor,
        b: Anchor,
        stiffness: Optional[Vec3] = None,
        damping: Optional[Vec3] = None,
        rotational_stiffness: Optional[Vec3] = None,
        rotational_damping: Optional[Vec3] = None,
    ) -> "Model":
        """Six-axis bushing from ``a``'s frame to ``b``'s point, in ``a``'s axes:
        ``stiffness`` (N/m) and ``damping`` (N·s/m) along x, y, z, ``rotational_stiffness``
        (N·m/rad) and ``rotational_damping`` (N·m·s/rad) about them (default 0)."""
        return self._add(
            "force", "bushing", name, a=a, b=b, stiffness=stiffness, damping=damping,
            rotational_stiffness=rotational_stiffness, rotational_damping=rotational_damping,
        )

    def force(
        self,
        name: str,
        *,
        at: Anchor,
        frame: str,
        fx: Optional[Table] = None,
        fy: Optional[Table] = None,
        fz: Optional[Table] = None,
    ) -> "Model":
        """Applied force (N) at ``at`` (a point on a body), components ``fx``, ``fy``, ``fz``
        of time (:func:`motion`; default 0) in ``frame`` (``"world"`` or ``"body"``)."""
        return self._add("force", "force", name, at=at, frame=frame, fx=fx, fy=fy, fz=fz)

    def torque(
        self,
        name: str,
        *,
        body: str,
        frame: str,
        mx: Optional[Table] = None,
        my: Optional[Table] = None,
        mz: Optional[Table] = None,
    ) -> "Model":
        """Applied torque (N·m) on ``body``, components ``mx``, ``my``, ``mz`` of time
        (:func:`motion`; default 0) in ``frame`` (``"world"`` or ``"body"``)."""
        return self._add("force", "torque", name, body=body, frame=frame, mx=mx, my=my, mz=mz)

    # ----- [[shape]] ---------------------------------------------------------------------

    def shape(  # type: ignore[override]
        self,
        name: str,
        *,
        at: Anchor,
        geometry: Table,
        orientation: Optional[Table] = None,
    ) -> "SpatialModel":
        """``[[shape]]`` of a spatial model: a named contact shape whose frame sits at ``at``
        (:func:`clr_sim.spatial.at` on a body or ``"ground"``, without ``axis``), turned by
        ``orientation`` (:mod:`clr_sim.spatial` forms; default the body axes). ``geometry`` (m,
        in the shape frame) is a table with ``type`` = ``ball`` (``radius``), ``capsule``,
        ``cylinder``, ``cone`` (``half_length``, ``radius``, along the shape x axis), ``cuboid``
        (``half_extents`` = [hx, hy, hz]), ``convex_polyhedron`` (``points``), ``trimesh``
        (``vertices``, ``indices`` from 0) or ``compound`` (``parts`` = [{``at``,
        ``orientation``, ``geometry``}, ...]). :meth:`contact` puts two shapes in contact
        (docs/spatial.md "Shape contact")."""
        return self._add("shape", None, name, at=at, orientation=orientation, geometry=geometry)

    # ----- [[clearance]] -----------------------------------------------------------------

    def spherical_clearance(
        self,
        name: str,
        *,
        socket: Anchor,
        ball: Anchor,
        socket_radius: float,
        ball_radius: float,
        normal: Table,
        friction: Optional[Table] = None,
    ) -> "Model":
        """Spherical clearance joint (``[[clearance]] type = "spherical"``): a ball of radius
        ``ball_radius`` (m) centred at ``ball`` in a socket of radius ``socket_radius`` (m)
        centred at ``socket``; contact by the ``normal`` law (:func:`normal`: ``hertz``,
        ``power``, ``linear`` with their stiffness, or ``hertz-internal-sphere`` from
        ``bearing_material`` (socket) and ``journal_material`` (ball)) and ``friction``
        (:func:`friction`; default none; LuGre with vector bristles)."""
        return self._add(
            "clearance", "spherical", name, socket=socket, ball=ball,
            socket_radius=socket_radius, ball_radius=ball_radius, normal=normal,
            friction=friction,
        )

    def revolute_clearance(
        self,
        name: str,
        *,
        bearing: Anchor,
        journal: Anchor,
        bearing_radius: float,
        bearing_length: float,
        journal_radius: float,
        journal_length: float,
        axial_clearance: float,
        normal: Table,
        thrust_radius: Optional[float] = None,
        thrust_normal: Optional[Table] = None,
        quadrature_order: Optional[int] = None,
        friction: Optional[Table] = None,
        lubrication: Optional[Table] = None,
    ) -> "Model":
        """Spatial revolute clearance joint (``[[clearance]] type = "revolute"``): a journal of
        radius ``journal_radius`` and length ``journal_length`` (m) about the axis of the anchor
        ``journal`` in a bore of ``bearing_radius`` and ``bearing_length`` (m) about the axis of
        ``bearing`` (both anchors need ``axis``; a misaligned bearing is a tilted axis), tilting
        and sliding; thrust faces with the total end play ``axial_clearance`` (m) at
        ``thrust_radius`` (m; default the journal radius). ``normal`` is the law of the whole
        contact length min(L_b, L_j) (laws that take a length get it), ``thrust_normal`` that of a
        thrust face (default ``normal``), ``friction`` a stateless law (LuGre refused);
        ``quadrature_order`` of the line contact (default 10); ``lubrication`` an oil film
        (``{"model": "short_bearing"|"long_bearing", "viscosity", "film_threshold",
        "dry_threshold"}``, no ``length``: the overlap of journal and bore; docs/lubrication.md
        §13). docs/spatial.md."""
        return self._add(
            "clearance", "revolute", name, bearing=bearing, journal=journal,
            bearing_radius=bearing_radius, bearing_length=bearing_length,
            journal_radius=journal_radius, journal_length=journal_length,
            axial_clearance=axial_clearance, thrust_radius=thrust_radius,
            quadrature_order=quadrature_order, normal=normal, thrust_normal=thrust_normal,
            friction=friction, lubrication=lubrication,
        )

    def cylindrical_clearance(
        self,
        name: str,
        *,
        bearing: Anchor,
        journal: Anchor,
        bearing_radius: float,
        bearing_length: float,
        journal_radius: float,
        journal_length: float,
        normal: Table,
        quadrature_order: Optional[int] = None,
        friction: Optional[Table] = None,
        axial_clearance: Optional[float] = None,
        thrust_radius: Optional[float] = None,
        thrust_normal: Optional[Table] = None,
        lubrication: Optional[Table] = None,
    ) -> "Model":
        """Spatial cylindrical clearance joint (``[[clearance]] type = "cylindrical"``): as
        :meth:`revolute_clearance` without thrust faces (the journal slides and turns freely
        along the bore); ``axial_clearance``, ``thrust_radius`` and ``thrust_normal`` are
        refused (they are listed because the file's table accepts them for the revolute kind);
        ``lubrication`` as for :meth:`revolute_clearance`."""
        return self._add(
            "clearance", "cylindrical", name, bearing=bearing, journal=journal,
            bearing_radius=bearing_radius, bearing_length=bearing_length,
            journal_radius=journal_radius, journal_length=journal_length,
            axial_clearance=axial_clearance, thrust_radius=thrust_radius,
            quadrature_order=quadrature_order, normal=normal, thrust_normal=thrust_normal,
            friction=friction, lubrication=lubrication,
        )


def _elsewhere(method: str, space: str, use: str):
    """A method of the other space's builder: raises a ModelError that names the one to use."""

    def refused(self: Model, *args: Any, **kwargs: Any) -> Model:
        raise FieldError(
            f"{method}() adds an element of a {space} model, and this model is "
            f"{self.space}: {use}",
            field="model.space",
            where=_caller(),
        )

    refused.__name__ = method
    refused.__qualname__ = f"{'SpatialModel' if space == 'planar' else 'Model'}.{method}"
    refused.__doc__ = f"Not in a {'spatial' if space == 'planar' else 'planar'} model: {use}"
    return refused


#: The planar builder's methods a spatial model refuses, with what to use instead.
_PLANAR_ONLY = {
    "point": "name no points; give each end as spatial.at(body, x, y, z)",
    "beam": "spatial models have no flexible beams yet",
    "flexible_body": "spatial models have no flexible bodies yet",
    "translational": "use prismatic() (a joint of a spatial model, with spatial.at(..., axis=))",
    "drive_angle": "use drive_revolute_angle(joint=...) on a revolute or cylindrical joint",
    "drive_relative_angle": "use drive_revolute_angle(joint=...) on the joint between the bodies",
    "drive_displacement": "use drive_prismatic_displacement(joint=...) on a prismatic joint",
    "torque_between": "use torque() on each body, or rotational_spring_damper(joint=...)",
    "nodal_load": "spatial models have no flexible beams yet",
    "translational_clearance": "spatial models have no translational clearance joint yet",
    "slider_on_beam": "spatial models have no flexible beams yet",
    **{
        m: "a spatial [[measure]] is a point's position, velocity or acceleration, or a "
        "distance (measure_position, measure_velocity, measure_acceleration, measure_distance); "
        "the other quantities are columns every spatial run writes"
        for m in (
            "measure_angle", "measure_angular_velocity", "measure_angular_acceleration",
            "measure_reaction", "measure_contact", "measure_energy", "measure_momentum",
            "measure_deviation", "measure_combination",
        )
    },
    "twin": "spatial models have no ideal-joint twin yet",
    "input": "spatial models have no [[input]] yet; drive them with time functions",
}

#: The spatial builder's methods a planar model refuses, with what to use instead.
_SPATIAL_ONLY = {
    "spherical": "build the model with Model(..., space=\"spatial\"); planar joints are "
    "revolute(), translational() and fixed()",
    "universal": "build the model with Model(..., space=\"spatial\")",
    "cylindrical": "build the model with Model(..., space=\"spatial\")",
    "prismatic": "use translational() (the planar sliding joint), or build the model with "
    "Model(..., space=\"spatial\")",
    "planar_joint": "every joint of a planar model is planar; use revolute() or "
    "translational(), or build the model with Model(..., space=\"spatial\")",
    "drive_revolute_angle": "use drive_angle(body=...) or drive_relative_angle(), or build "
    "the model with Model(..., space=\"spatial\")",
    "drive_prismatic_displacement": "use drive_displacement(), or build the model with "
    "Model(..., space=\"spatial\")",
    "spherical_clearance": "use revolute_clearance() (a journal in a bearing), or build the "
    "model with Model(..., space=\"spatial\")",
    "cylindrical_clearance": "use revolute_clearance() (a journal in a bearing), or build the "
    "model with Model(..., space=\"spatial\")",
}

for _name, _use in _PLANAR_ONLY.items():
    setattr(SpatialModel, _name, _elsewhere(_name, "planar", _use))
for _name, _use in _SPATIAL_ONLY.items():
    setattr(Model, _name, _elsewhere(_name, "spatial", _use))
del _name, _use


#: For each ``(section, type)`` of a model file, the :class:`Model` method that adds it (the
#: tests check that every kind the Rust reader knows has its method, with the same fields).
METHODS: Dict[Tuple[str, Optional[str]], str] = {
    ("model", None): "__init__",
    ("solver", None): "solver",
    ("output", None): "output",
    ("body", None): "body",
    ("point", None): "point",
    ("beam", None): "beam",
    ("flexible_body", None): "flexible_body",
    ("joint", "revolute"): "revolute",
    ("joint", "fixed"): "fixed",
    ("joint", "translational"): "translational",
    ("driver", "angle"): "drive_angle",
    ("driver", "relative_angle"): "drive_relative_angle",
    ("driver", "displacement"): "drive_displacement",
    ("force", "spring_damper"): "spring_damper",
    ("force", "rotational_spring_damper"): "rotational_spring_damper",
    ("force", "actuator"): "actuator",
    ("force", "bushing"): "bushing",
    ("force", "force"): "force",
    ("force", "torque"): "torque",
    ("force", "torque_between"): "torque_between",
    ("force", "nodal_load"): "nodal_load",
    ("shape", None): "shape",
    ("clearance", "revolute"): "revolute_clearance",
    ("clearance", "translational"): "translational_clearance",
    ("clearance", "slider_on_beam"): "slider_on_beam",
    ("clearance", "contact"): "contact",
    ("measure", "position"): "measure_position",
    ("measure", "velocity"): "measure_velocity",
    ("measure", "acceleration"): "measure_acceleration",
    ("measure", "angle"): "measure_angle",
    ("measure", "angular_velocity"): "measure_angular_velocity",
    ("measure", "angular_acceleration"): "measure_angular_acceleration",
    ("measure", "distance"): "measure_distance",
    ("measure", "reaction"): "measure_reaction",
    ("measure", "contact"): "measure_contact",
    ("measure", "combination"): "measure_combination",
    ("measure", "energy"): "measure_energy",
    ("measure", "momentum"): "measure_momentum",
    ("measure", "deviation"): "measure_deviation",
    ("metric", None): "metric",
    ("twin", None): "twin",
    ("input", None): "input",
}


#: For each ``(section, type)`` of a spatial model file, the :class:`SpatialModel` method that
#: adds it (checked against the spatial reader's kinds and fields like :data:`METHODS`).
SPATIAL_METHODS: Dict[Tuple[str, Optional[str]], str] = {
    ("model", None): "__init__",
    ("solver", None): "solver",
    ("output", None): "output",
    ("body", None): "body",
    ("joint", "spherical"): "spherical",
    ("joint", "revolute"): "revolute",
    ("joint", "universal"): "universal",
    ("joint", "cylindrical"): "cylindrical",
    ("joint", "prismatic"): "prismatic",
    ("joint", "planar"): "planar_joint",
    ("joint", "fixed"): "fixed",
    ("driver", "revolute_angle"): "drive_revolute_angle",
    ("driver", "prismatic_displacement"): "drive_prismatic_displacement",
    ("force", "spring_damper"): "spring_damper",
    ("force", "actuator"): "actuator",
    ("force", "rotational_spring_damper"): "rotational_spring_damper",
    ("force", "bushing"): "bushing",
    ("force", "force"): "force",
    ("force", "torque"): "torque",
    ("clearance", "spherical"): "spherical_clearance",
    ("clearance", "revolute"): "revolute_clearance",
    ("clearance", "cylindrical"): "cylindrical_clearance",
    ("shape", None): "shape",
    ("clearance", "contact"): "contact",
    ("measure", "position"): "measure_position",
    ("measure", "velocity"): "measure_velocity",
    ("measure", "acceleration"): "measure_acceleration",
    ("measure", "distance"): "measure_distance",
    ("metric", None): "metric",
}

#: The table of element methods of each kind of builder.
Model.METHODS = METHODS
SpatialModel.METHODS = SPATIAL_METHODS
