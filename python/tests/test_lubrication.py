"""The lubricated journal bearing from Python (clr_sim.contact.FilmLaw and a lubricated clearance
joint in clr_sim.Model) against the short-bearing closed forms.

Reference (closed form): the Ocvirk short bearing under a steady load, journal spinning at ω
in a fixed bearing (ε̇ = γ̇ = 0): load W = μ U L³ ε / (4c²(1 − ε²)²) · √(16ε² + π²(1 − ε²))
with U = ω r, attitude angle tan φ = π √(1 − ε²) / (4ε) (Hamrock, Schmid & Jacobson,
Fundamentals of Fluid Film Lubrication, 2004, §12.3). The film law's own evaluation uses the
Sommerfeld integrals (docs/lubrication.md), so agreement to rounding is an independent check.
"""

import math

import numpy as np
import pytest

import clr_sim

R, r, L, MU, OMEGA = 0.01, 0.0099, 0.01, 0.05, 200.0
C = R - r


def ocvirk(eps):
    u = OMEGA * r
    s = 1.0 - eps * eps
    load = MU * u * L**3 * eps / (4 * C * C * s * s) * math.sqrt(16 * eps * eps + math.pi**2 * s)
    return load, math.atan(math.pi * math.sqrt(s) / (4 * eps))


def test_film_law_carries_the_ocvirk_load_at_the_ocvirk_attitude():
    law = clr_sim.contact.FilmLaw(R, r, L, MU, "short")
    eps = np.array([0.1, 0.3, 0.5, 0.7, 0.9])
    fr, ft = law.force(eps, 0.0, 0.0, OMEGA)
    for k, e in enumerate(eps):
        load, phi = ocvirk(e)
        assert math.hypot(fr[k], ft[k]) == pytest.approx(load, rel=1e-12)
        # F_r < 0 pushes the journal back; the attitude angle is between the load line and
        # the line of centres
        assert math.atan2(ft[k], -fr[k]) == pytest.approx(phi, rel=1e-12)
    scalar = law.force(0.5, 0.0, 0.0, OMEGA)
    assert isinstance(scalar[0], float)
    with pytest.raises(clr_sim.ContactError) as e:
        law.force([0.5, 1.0], 0.0, 0.0, OMEGA)
    assert e.value.field == "eps[1]"
    with pytest.raises(clr_sim.ContactError):
        clr_sim.contact.FilmLaw(R, 0.011, L, MU)


def test_a_lubricated_joint_built_in_python_settles_at_the_ocvirk_equilibrium():
    """The same rig as the verify case lubrication.mbd.steady_load, built with clr_sim.Model."""
    m = clr_sim.Model("lubricated_journal")
    m.body("journal", mass=1.0, inertia=1e-4, position=(0, 0), angle=0.0,
           velocity=(0, 0), angular_velocity=OMEGA)
    m.drive_angle("spin", body="journal", motion=clr_sim.motion("linear", initial=0.0, rate=OMEGA))
    m.force("load", at=clr_sim.at("journal"), fy=clr_sim.motion("constant", value=-60.0))
    m.revolute_clearance(
        "J", bearing=clr_sim.at("ground"), journal=clr_sim.at("journal"), bearing_radius=R,
        journal_radius=r,
        normal=clr_sim.normal("hertz", 0.9, stiffness=1e10, damping="lankarani-nikravesh"),
        lubrication={"model": "short_bearing", "viscosity": MU, "length": L,
                     "film_threshold": 1e-6},
    )
    m.solver(method="ndf", rtol=1e-9)
    m.output(t_end=0.3, intervals=300)
    res = clr_sim.simulate(m)
    ex, ey = res["J.ex"][-1], res["J.ey"][-1]
    eps = math.hypot(ex, ey) / C
    lo, hi = 0.0, 1.0 - 1e-12
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if ocvirk(mid)[0] < 60.0 else (lo, mid)
    assert eps == pytest.approx(lo, rel=1e-3)
    assert res.units["J.film_force"] == "N" and res["J.film_force"][-1] == pytest.approx(60.0, rel=1e-3)
    assert res["J.film_thickness"][-1] == pytest.approx(C * (1 - eps), rel=1e-9)
