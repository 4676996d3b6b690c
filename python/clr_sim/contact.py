"""Contact force laws, friction laws, the planar revolute clearance joint and the spatial
journal-in-bearing joint of clr-contact
(``clr_sim.contact``; also importable under its former name ``clr_contact``).

Every law is evaluated in Rust; the functions and methods here accept scalars or numpy arrays
(anything ``numpy.asarray`` takes), broadcast them against each other with numpy's rules, and
return a ``float`` for scalar inputs or a ``float64`` array of the broadcast shape. SI units
throughout (m, m/s, N, Pa, rad). Invalid parameters and non-finite inputs raise
:class:`ContactError` (a ``ValueError``) whose message says what to change.

Conventions (contact-laws.md §0): δ is the penetration (> 0 in contact), δ̇ its rate (> 0
approaching), δ̇⁻ the rate at the onset of the current contact; F_T opposes the slip v_T.
"""

from __future__ import annotations

from typing import Optional, Sequence

import numpy as np

from . import _native
from ._native import (
    damping_names,
    elastic_kinds,
    friction_kinds,
    preset_names,
)
from .errors import ContactError

__version__ = _native.__version__

__all__ = [
    "ContactError",
    "NormalLaw",
    "FrictionLaw",
    "RevoluteJoint",
    "JournalJoint",
    "FilmLaw",
    "damping_chi",
    "effective_restitution",
    "damping_names",
    "elastic_kinds",
    "friction_kinds",
    "preset_names",
    "STEEL",
]

#: Steel of the contact-laws.md tests: (Young's modulus in Pa, Poisson ratio).
STEEL = (207e9, 0.3)


def _apply(fn, *args):
    """Broadcast ``args`` to one shape, call ``fn`` on flat contiguous float64 copies, reshape."""
    arrays = np.broadcast_arrays(*[np.asarray(a, dtype=np.float64) for a in args])
    shape = arrays[0].shape
    out = fn(*[np.ascontiguousarray(a).ravel() for a in arrays])
    if shape == ():
        return float(out[0])
    return out.reshape(shape)


class NormalLaw:
    """A normal-force law F_N = F_e(δ)·(1 + χ δ̇/δ̇⁻), clamped at F_N ≥ 0 and 0 for δ ≤ 0.

    ``NormalLaw(elastic, params, damping, c_e)`` combines an elastic part (a name from
    :func:`elastic_kinds`, with its parameters in SI in the listed order) with a damping factor
    (a name from :func:`damping_names`, e.g. ``"lankarani-nikravesh"`` or ``"ln"``) for the input
    coefficient of restitution ``c_e`` in (0, 1]. ``min_impact_velocity`` (m/s, default 1e-4)
    floors δ̇⁻ for contacts that start at rest.
    """

    __slots__ = ("_core",)

    def __init__(
        self,
        elastic: str,
        params: Sequence[float],
        damping: str,
        c_e: float,
        min_impact_velocity: Optional[float] = None,
    ):
        self._core = _native.NormalLawCore(
            elastic, [float(p) for p in params], damping, float(c_e), min_impact_velocity
        )

    @classmethod
    def preset(
        cls,
        name: str,
        c_e: float,
        *,
        bearing_radius: float = 10e-3,
        journal_radius: float = 9.9e-3,
        length: float = 15e-3,
        bearing_material: tuple = STEEL,
        journal_material: tuple = STEEL,
        min_impact_velocity: Optional[float] = None,
    ) -> "NormalLaw":
        """A journal–bearing law of the flap paper by label: ``"Hertz"``, ``"LN"``,
        ``"Gonthier"``, ``"Bai"``, ``"Wang"`` or ``"Modified"`` (case-insensitive). The default
        geometry is the paper's impact test: steel, R_i = 10 mm, R_j = 9.9 mm, L = 15 mm."""
        law = cls.__new__(cls)
        law._core = _native.NormalLawCore.preset(
            name,
            float(c_e),
            float(bearing_material[0]),
            float(bearing_material[1]),
            float(journal_material[0]),
            float(journal_material[1]),
            float(bearing_radius),
            float(journal_radius),
            float(length),
            min_impact_velocity,
        )
        return law

    def force(self, delta, delta_dot, delta_dot_minus):
        """Normal force F_N (N) for δ (m), δ̇ (m/s) and δ̇⁻ (m/s), broadcast elementwise."""
        return _apply(self._core.force, delta, delta_dot, delta_dot_minus)

    def elastic_force(self, delta):
        """Elastic part F_e(δ) (N) for δ (m)."""
        return _apply(self._core.elastic_force, delta)

    @property
    def chi(self) -> float:
        """Damping factor χ (–)."""
        return self._core.chi

    @property
    def c_e(self) -> float:
        """Input coefficient of restitution (–)."""
        return self._core.c_e

    @property
    def damping(self) -> str:
        """Name of the damping factor."""
        return self._core.damping

    @property
    def elastic(self) -> str:
        """Name of the elastic part."""
        return self._core.elastic

    @property
    def min_impact_velocity(self) -> float:
        """Floor of δ̇⁻ (m/s)."""
        return self._core.min_impact_velocity

    @property
    def effective_restitution(self) -> float:
        """Restitution this law produces in a free impact (exact, independent of the elastic
        part, the mass and the impact velocity; contact-laws.md §1.3)."""
        return self._core.effective_restitution

    def __repr__(self) -> str:
        return (
            f"NormalLaw(elastic={self.elastic!r}, damping={self.damping!r}, "
            f"c_e={self.c_e}, chi={self.chi:.6g})"
        )


class FrictionLaw:
    """A stateless friction law F_T = μ(v_T)·F_N opposing the slip.

    ``FrictionLaw(kind, params)`` with a kind from :func:`friction_kinds`: ``"coulomb"``
    (μ, v_reg), ``"ambrosio"`` (μ, v0, v1), ``"threlfall"`` (μ, v0), ``"stribeck"``
    (μ_s, μ_d, v_s, v_d); velocities in m/s.
    """

    __slots__ = ("_core", "kind")

    def __init__(self, kind: str, params: Sequence[float]):
        self._core = _native.FrictionLawCore(kind, [float(p) for p in params])
        self.kind = kind

    def force(self, v_t, f_n):
        """Friction force F_T (N) along the tangent for slip v_T (m/s) and normal force F_N (N);
        0 where F_N ≤ 0."""
        return _apply(self._core.force, v_t, f_n)

    def coefficient(self, v_t):
        """Signed friction coefficient μ(v_T) (–), with μ·v_T ≤ 0."""
        return _apply(self._core.coefficient, v_t)

    @property
    def mu_max(self) -> float:
        """Largest |μ| the law produces (–)."""
        return self._core.mu_max

    def __repr__(self) -> str:
        return f"FrictionLaw({self.kind!r})"


class FilmLaw:
    """The oil film of a lubricated journal bearing (docs/lubrication.md): the hydrodynamic
    force on the journal from the closed-form solutions of the Reynolds equation, ``model``
    ``"short"`` (Ocvirk) or ``"long"`` (Sommerfeld), half-Sommerfeld cavitation, wedge and
    squeeze terms. Radii and length in m, viscosity in Pa·s.
    """

    __slots__ = ("_core", "model")

    def __init__(self, bearing_radius: float, journal_radius: float, length: float,
                 viscosity: float, model: str = "short"):
        self._core = _native.FilmLawCore(float(bearing_radius), float(journal_radius),
                                         float(length), float(viscosity), model)
        self.model = model

    def force(self, eps, eps_dot, gamma_dot, omega_sum):
        """(F_r, F_t) in N on the journal in the frame of the line of centres (F_r < 0 pushes
        it back to the bearing centre) for the eccentricity ratio ε ∈ [0, 1), its rate ε̇
        (1/s), the line of centres' angular velocity γ̇ (rad/s) and ω_i + ω_j (rad/s),
        broadcast elementwise."""
        arrays = np.broadcast_arrays(*[np.asarray(a, dtype=np.float64)
                                       for a in (eps, eps_dot, gamma_dot, omega_sum)])
        shape = arrays[0].shape
        fr, ft = self._core.force(*[np.ascontiguousarray(a).ravel() for a in arrays])
        if shape == ():
            return float(fr[0]), float(ft[0])
        return fr.reshape(shape), ft.reshape(shape)

    def __repr__(self) -> str:
        return f"FilmLaw({self.model!r})"


class RevoluteJoint:
    """A planar revolute clearance joint: a journal (radius R_j) in a bearing (R_i > R_j).

    ``bearing_centre`` and ``journal_centre`` are the local coordinates (m) of the joint centres
    on the bearing body i and the journal body j (Flores et al., Comput. Struct. 82 (2004) 1359).
    """

    __slots__ = ("_core",)

    def __init__(
        self,
        bearing_radius: float,
        journal_radius: float,
        bearing_centre=(0.0, 0.0),
        journal_centre=(0.0, 0.0),
    ):
        self._core = _native.RevoluteJointCore(
            float(bearing_radius),
            float(journal_radius),
            (float(bearing_centre[0]), float(bearing_centre[1])),
            (float(journal_centre[0]), float(journal_centre[1])),
        )

    @property
    def clearance(self) -> float:
        """Radial clearance c = R_i − R_j (m)."""
        return self._core.clearance

    def forces(self, normal: NormalLaw, friction: Optional[FrictionLaw], bearing, journal,
               impact_velocity):
        """Contact quantities and generalized forces for body states ``bearing`` and ``journal``
        of shape (..., 6) = (x, y, θ, ẋ, ẏ, ω) and the impact velocity δ̇⁻ (m/s, shape (...));
        the leading shapes broadcast. ``friction=None`` is frictionless.

        Returns a dict of arrays with the broadcast leading shape: ``penetration`` (m),
        ``normal`` (..., 2), ``normal_velocity`` and ``tangential_velocity`` (m/s),
        ``normal_force`` and ``tangential_force`` (N), ``bearing`` and ``journal``
        (..., 3) = (f_x, f_y, moment about the body's reference point) in N, N, N·m.
        All forces are zero where δ ≤ 0.
        """
        bi = np.asarray(bearing, dtype=np.float64)
        bj = np.asarray(journal, dtype=np.float64)
        v0 = np.asarray(impact_velocity, dtype=np.float64)
        for name, s in (("bearing", bi), ("journal", bj)):
            if s.ndim == 0 or s.shape[-1] != 6:
                raise ContactError(
                    f"`{name}` must have a last axis of 6 (x, y, theta, vx, vy, omega), "
                    f"got shape {s.shape}"
                )
        lead = np.broadcast_shapes(bi.shape[:-1], bj.shape[:-1], v0.shape)
        flat = lambda a, tail: np.ascontiguousarray(np.broadcast_to(a, lead + tail)).reshape(
            (-1,) + tail
        )
        out = self._core.forces(
            normal._core,
            None if friction is None else friction._core,
            flat(bi, (6,)),
            flat(bj, (6,)),
            flat(v0, ()),
        )
        return {k: (v.reshape(lead + v.shape[1:]) if lead else v[0]) for k, v in out.items()}


class JournalJoint:
    """A spatial revolute or cylindrical clearance joint: a journal of radius R_j and length L_j
    in a bore of radius R_b > R_j and length L_b (m), tilted and sliding axially
    (docs/contact.md, "Spatial journal in bearing").

    With ``axial_clearance`` (m, total end play) it is a revolute joint with thrust faces of
    radius ``thrust_radius`` (m; None: R_j); without, a cylindrical joint.
    """

    __slots__ = ("_core",)

    STATE_FIELDS = (
        "bearing_centre", "bearing_axis", "bearing_velocity", "bearing_angular_velocity",
        "journal_centre", "journal_axis", "journal_velocity", "journal_angular_velocity",
    )

    def __init__(self, bearing_radius: float, bearing_length: float, journal_radius: float,
                 journal_length: float, axial_clearance: Optional[float] = None,
                 thrust_radius: Optional[float] = None):
        self._core = _native.JournalJointCore(
            float(bearing_radius), float(bearing_length), float(journal_radius),
            float(journal_length),
            None if axial_clearance is None else float(axial_clearance),
            None if thrust_radius is None else float(thrust_radius),
        )

    @property
    def clearance(self) -> float:
        """Radial clearance R_b − R_j (m)."""
        return self._core.clearance

    def forces(self, radial: NormalLaw, friction: Optional[FrictionLaw], state,
               impact_velocities, thrust: Optional[NormalLaw] = None):
        """Forces for the world-frame ``state`` of shape (..., 24): the bore centre (m), bore
        axis, velocity of the bearing body at the bore centre (m/s) and its angular velocity
        (rad/s), then the same four for the journal (``STATE_FIELDS``, 3 each), and the four
        contact groups' impact velocities δ̇⁻ (m/s, shape (..., 4): radial end A, radial end B,
        thrust −, thrust +; the caller keeps them). ``radial`` is the normal law of the whole
        contact length min(L_b, L_j), ``thrust`` that of a thrust face (None: ``radial``),
        ``friction`` a stateless law (None: frictionless).

        Returns a dict of arrays with the leading shape: ``force`` on the journal (N, (..., 3);
        the bearing gets the opposite), ``journal_moment`` about the journal centre and
        ``bearing_moment`` about the bore centre (N·m, (..., 3)), ``penetration`` (m),
        ``rate`` (m/s) and ``normal_force`` (N) per group (..., 4), ``tilt`` (rad),
        ``dissipated`` (W) and ``elastic_energy`` (J).
        """
        st = np.asarray(state, dtype=np.float64)
        v0 = np.asarray(impact_velocities, dtype=np.float64)
        if st.ndim == 0 or st.shape[-1] != 24:
            raise ContactError(
                f"`state` must have a last axis of 24 ({', '.join(self.STATE_FIELDS)}, 3 each), "
                f"got shape {st.shape}"
            )
        if v0.ndim == 0 or v0.shape[-1] != 4:
            raise ContactError(
                f"`impact_velocities` must have a last axis of 4 (radial A, radial B, thrust -, "
                f"thrust +), got shape {v0.shape}"
            )
        lead = np.broadcast_shapes(st.shape[:-1], v0.shape[:-1])
        flat = lambda a, tail: np.ascontiguousarray(np.broadcast_to(a, lead + tail)).reshape(
            (-1,) + tail
        )
        out = self._core.forces(
            radial._core,
            None if thrust is None else thrust._core,
            None if friction is None else friction._core,
            flat(st, (24,)),
            flat(v0, (4,)),
        )
        return {k: (v.reshape(lead + v.shape[1:]) if lead else v[0]) for k, v in out.items()}


def damping_chi(name: str, c_e):
    """Damping factor χ(c_e) (–) of the factor ``name`` (see :func:`damping_names`)."""
    return _apply(lambda c: _native.damping_chi(name, c), c_e)


def effective_restitution(chi):
    """Restitution e (–) a multiplicative law with damping factor χ ≥ 0 produces in a free
    impact: the root of (1 + e)χ = ln[(1 + χ)/(1 − χe)] (contact-laws.md §1.3)."""
    return _apply(_native.effective_restitution, chi)
