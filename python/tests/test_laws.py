"""Checks of the Python bindings against contact-laws.md §7 (steel, E = 207 GPa, nu = 0.3).

Tolerances: the §7 tables print 7-8 significant digits, so closed forms are compared with
rel = 1e-7; values printed with 6 decimals with abs = 1e-6.
"""

import numpy as np
import pytest

import clr_contact as cc

E, NU = 207e9, 0.3
RI, RJ, L, C = 10e-3, 9.9e-3, 15e-3, 0.1e-3
E_STAR = 1.0 / (2.0 * (1.0 - NU**2) / E)  # composite modulus, contact-laws.md §0
INTERNAL = [E, NU, RI, E, NU, RJ]


def law(damping, c_e=0.5):
    return cc.NormalLaw("hertz-internal-cylinder", INTERNAL, damping, c_e)


# §7.2: delta = 10 um, delta_dot_minus = 0.5 m/s, c_e = 0.5; F at delta_dot = +0.25 and -0.25.
SECTION_7_2 = [
    ("lankarani-nikravesh", 0.5625, 6113.4895, 3429.5185),
    ("flores", 1.6, 8588.7072, 954.3008),
    ("hunt-crossley", 0.75, 6560.8180, 2982.1900),
    ("gonthier", 1.5, 8350.1320, 1192.8760),
    ("hu-guo", 1.5, 8350.1320, 1192.8760),
    ("zhiying-qishao", 1.5290340, 8419.3988, 1123.6092),
    ("herbert-mcwhannell", 1.0, 7157.2560, 2385.7520),
    ("gharib-hurmuzlu", 1.0, 7157.2560, 2385.7520),
    ("lee-wang", 0.375, 5666.1610, 3876.8470),
]


@pytest.mark.parametrize("damping,chi,f_plus,f_minus", SECTION_7_2)
def test_dissipative_laws_section_7_2(damping, chi, f_plus, f_minus):
    n = law(damping)
    # chi of Zhiying-Qishao is printed to 6 decimals only (0.5625 e = 1.52903353).
    assert n.chi == pytest.approx(chi, abs=1e-6)
    f = n.force(10e-6, np.array([0.25, -0.25]), 0.5)
    assert f.shape == (2,)
    np.testing.assert_allclose(f, [f_plus, f_minus], rtol=1e-7)


def test_stiffness_section_7_1():
    ss = cc.NormalLaw("hertz-sphere-sphere", [E, NU, 10e-3, E, NU, 10e-3], "none", 1.0)
    assert ss.elastic_force(10e-6) == pytest.approx(339.0960, rel=1e-7)
    n = law("none")
    assert n.elastic_force(10e-6) == pytest.approx(4771.5040, rel=1e-7)
    # K = 1.50888205e11 N/m^1.5 from F_e = K delta^1.5 at delta = 1 m (a pure power law).
    assert n.elastic_force(1.0) == pytest.approx(1.50888205e11, rel=1e-8)
    sp = cc.NormalLaw("hertz-sphere-plane", [E, NU, 10e-3, E, NU], "none", 1.0)
    assert sp.elastic_force(1.0) == pytest.approx(1.5164835e10, rel=1e-7)


def test_clamp_zero_penetration_and_broadcasting():
    n = law("flores")
    assert n.force(-1e-6, 0.25, 0.5) == 0.0
    assert n.force(10e-6, -0.5, 0.5) == 0.0  # 1 + chi*dd/ddm < 0: clamped
    delta = np.linspace(0.0, 20e-6, 5).reshape(5, 1)
    rate = np.array([[0.25, -0.25, 0.0]])
    f = n.force(delta, rate, 0.5)
    assert f.shape == (5, 3)
    # closed form K delta^1.5 (1 + chi rate/0.5) from the §7.1 K
    k = 1.50888205e11
    expected = np.maximum(0.0, k * delta**1.5 * (1.0 + 1.6 * rate / 0.5))
    np.testing.assert_allclose(f, expected, rtol=1e-8)
    assert isinstance(n.force(10e-6, 0.25, 0.5), float)


def test_presets_and_restitution_section_7_3():
    ln = cc.NormalLaw.preset("LN", 0.5)
    assert ln.force(10e-6, 0.25, 0.5) == pytest.approx(6113.4895, rel=1e-7)
    assert ln.effective_restitution == pytest.approx(0.725241, abs=1e-6)
    # Flap paper: Bai -> Zhiying-Qishao 0.4826, Modified -> Gonthier 0.4877 (contact-laws.md §1.3).
    assert cc.NormalLaw.preset("bai", 0.5).effective_restitution == pytest.approx(0.4826, abs=5e-5)
    assert cc.NormalLaw.preset("Modified", 0.5).effective_restitution == pytest.approx(
        0.4877, abs=5e-5
    )
    assert cc.damping_chi("exact", 0.5) == pytest.approx(1.432751, abs=1e-6)
    assert cc.damping_chi("exact", 0.9) == pytest.approx(0.166482, abs=1e-6)
    ce = np.array([0.1, 0.3, 0.5, 0.7, 0.9, 0.95])
    np.testing.assert_allclose(cc.effective_restitution(cc.damping_chi("exact", ce)), ce,
                               atol=1e-9)
    # §1.3 table, L-N and Flores rows at c_e = 0.1, 0.5, 0.9 (printed to 4 decimals).
    ce = np.array([0.1, 0.5, 0.9])
    np.testing.assert_allclose(cc.effective_restitution(cc.damping_chi("ln", ce)),
                               [0.6653, 0.7252, 0.9132], atol=5e-5)
    np.testing.assert_allclose(cc.effective_restitution(cc.damping_chi("flores", ce)),
                               [0.0694, 0.4704, 0.8939], atol=5e-5)


def test_floor_of_impact_velocity():
    n = cc.NormalLaw("hertz-internal-cylinder", INTERNAL, "ln", 0.5, min_impact_velocity=0.5)
    assert n.min_impact_velocity == 0.5
    assert n.force(10e-6, 0.25, 1e-6) == pytest.approx(6113.4895, rel=1e-7)


def test_cylinder_laws_section_7_5():
    liu = cc.NormalLaw("liu", [E_STAR, C, L], "none", 1.0)
    np.testing.assert_allclose(liu.elastic_force([1e-6, 10e-6, 100e-6]),
                               [188.55342, 5713.4542, 133992.38], rtol=1e-7)
    bz = cc.NormalLaw("bai-zhao", [E_STAR, C], "ln", 0.5)
    assert bz.elastic_force(10e-6) == pytest.approx(1752.0028, rel=1e-7)
    assert bz.force(10e-6, 0.25, 0.5) == pytest.approx(2244.7536, rel=1e-7)
    per = cc.NormalLaw("pereira-internal", [E_STAR, C, L], "none", 1.0)
    np.testing.assert_allclose(per.elastic_force([1e-6, 10e-6]), [756.5402, 12351.997], rtol=1e-6)
    ext = cc.NormalLaw("pereira-external", [E_STAR, 7.5e-3, 7.5e-3, L], "none", 1.0)
    assert ext.elastic_force(1e-6) == pytest.approx(398.0831, rel=1e-6)
    j = cc.NormalLaw("johnson", [E_STAR, C, L], "none", 1.0)
    assert j.elastic_force(1e-6) == pytest.approx(773.7539, rel=1e-6)
    with pytest.raises(cc.ContactError, match="validity range"):
        cc.NormalLaw("pereira-internal", [E_STAR, 11e-3, L], "none", 1.0)


def test_friction_section_7_6():
    coulomb = cc.FrictionLaw("coulomb", [0.1, 1e-3])
    assert coulomb.force(0.02, 1000.0) == pytest.approx(-100.0, rel=1e-12)
    amb = cc.FrictionLaw("ambrosio", [0.1, 1e-4, 1e-3])
    np.testing.assert_allclose(amb.force([5e-5, 5.5e-4, -5.5e-4, 2e-3], 1000.0),
                               [0.0, -50.0, 50.0, -100.0], rtol=1e-9, atol=1e-12)
    thr = cc.FrictionLaw("threlfall", [0.1, 0.01])
    np.testing.assert_allclose(thr.force([0.01, 0.001], 1000.0), [-95.02129, -25.91818],
                               rtol=1e-7)
    stb = cc.FrictionLaw("stribeck", [0.2, 0.1, 0.01, 0.1])
    v = [0.0, 0.005, -0.005, 0.01, 0.055, 0.1, 0.2]
    np.testing.assert_allclose(stb.coefficient(v), [0.0, -0.1375, 0.1375, -0.2, -0.15, -0.1, -0.1],
                               atol=1e-12)
    assert stb.mu_max == 0.2
    assert amb.force(1.0, -5.0) == 0.0  # no friction without a normal force


def test_revolute_section_7_7():
    joint = cc.RevoluteJoint(RI, RJ)
    assert joint.clearance == pytest.approx(C, rel=1e-12)
    e = C + 10e-6
    journal = [e * 0.6, e * 0.8, 0.0, 0.3, 0.4, 10.0]
    out = joint.forces(cc.NormalLaw.preset("LN", 0.5), cc.FrictionLaw("ambrosio", [0.1, 1e-4, 1e-3]),
                       np.zeros(6), journal, 0.5)
    assert out["penetration"] == pytest.approx(10e-6, rel=1e-9)
    assert out["normal_velocity"] == pytest.approx(0.5, rel=1e-12)
    assert out["tangential_velocity"] == pytest.approx(0.099, rel=1e-12)
    assert out["normal_force"] == pytest.approx(7455.4750, rel=1e-7)
    assert out["tangential_force"] == pytest.approx(-745.5475, rel=1e-7)
    np.testing.assert_allclose(out["normal"], [0.6, 0.8], rtol=1e-12)
    np.testing.assert_allclose(out["journal"][:2], [-3876.8470, -6411.7085], rtol=1e-7)
    assert out["journal"][2] == pytest.approx(-7.380920, abs=1e-6)
    np.testing.assert_allclose(out["bearing"][:2], [3876.8470, 6411.7085], rtol=1e-7)
    assert out["bearing"][2] == pytest.approx(7.455475, abs=1e-6)


def test_revolute_vectorized_and_out_of_contact():
    joint = cc.RevoluteJoint(RI, RJ)
    e = C + 10e-6
    # Journal rotated around the bearing: the same contact seen in 8 directions. F_N depends on
    # delta and v_N only, so it is the same in every direction (frictionless: m_j = 0).
    ang = np.linspace(0.0, 2 * np.pi, 8, endpoint=False)
    n = np.stack([np.cos(ang), np.sin(ang)], axis=1)
    journal = np.zeros((8, 6))
    journal[:, :2] = e * n
    journal[:, 3:5] = 0.5 * n
    out = joint.forces(cc.NormalLaw.preset("LN", 0.5), None, np.zeros(6), journal, 0.5)
    assert out["journal"].shape == (8, 3)
    np.testing.assert_allclose(out["normal_force"], 7455.4750, rtol=1e-7)
    np.testing.assert_allclose(out["journal"][:, :2], -7455.4750 * n, rtol=1e-7, atol=1e-9)
    np.testing.assert_allclose(out["journal"][:, 2], 0.0, atol=1e-9)
    centred = joint.forces(cc.NormalLaw.preset("LN", 0.5), None, np.zeros(6), np.zeros(6), 0.5)
    assert centred["penetration"] == pytest.approx(-C, rel=1e-12)
    assert centred["normal_force"] == 0.0 and not centred["journal"].any()


def test_errors_say_what_to_change():
    with pytest.raises(cc.ContactError, match="c_e"):
        law("ln", c_e=1.5)
    with pytest.raises(cc.ContactError, match="valid names"):
        cc.NormalLaw.preset("Foo", 0.5)
    with pytest.raises(cc.ContactError, match="R_journal"):
        cc.NormalLaw("hertz-internal-cylinder", INTERNAL[:5], "ln", 0.5)
    with pytest.raises(cc.ContactError, match="valid names"):
        cc.NormalLaw("hertz", [1e9], "nope", 0.5)
    with pytest.raises(cc.ContactError, match="finite"):
        law("ln").force([1e-5, np.nan], 0.0, 0.5)
    with pytest.raises(cc.ContactError, match="greater than"):
        cc.FrictionLaw("ambrosio", [0.1, 1e-3, 1e-4])
    with pytest.raises(cc.ContactError, match="last axis of 6"):
        cc.RevoluteJoint(RI, RJ).forces(law("ln"), None, np.zeros(5), np.zeros(6), 0.5)
    with pytest.raises(cc.ContactError, match="smaller than the bearing radius"):
        cc.RevoluteJoint(RJ, RI)
    assert issubclass(cc.ContactError, ValueError)


def test_name_tables():
    assert "lankarani-nikravesh" in cc.damping_names()
    assert dict(cc.elastic_kinds())["liu"] == ["E* (Pa)", "clearance (m)", "length (m)"]
    assert [k for k, _ in cc.friction_kinds()] == ["coulomb", "ambrosio", "threlfall", "stribeck"]
    assert cc.preset_names() == ["Hertz", "LN", "Gonthier", "Bai", "Wang", "Modified"]


def test_journal_without_tilt_is_the_planar_joint():
    """The spatial journal joint with its axis along the bore's z axis and no axial motion equals
    the planar revolute clearance joint of contact-laws.md §7.7 (the distributed line contact
    integrates to F_N(δ) at zero tilt, docs/contact.md): normal force and force on the journal
    to 1e-12 relative; a tilted journal turns part of the load into a moment."""
    joint = cc.JournalJoint(RI, L, RJ, L, axial_clearance=1e-4)
    assert joint.clearance == pytest.approx(C, rel=1e-12)
    e = C + 10e-6
    normal = cc.NormalLaw.preset("LN", 0.5)
    friction = cc.FrictionLaw("ambrosio", [0.1, 1e-4, 1e-3])
    planar = cc.RevoluteJoint(RI, RJ).forces(
        normal, friction, np.zeros(6), [e * 0.6, e * 0.8, 0.0, 0.3, 0.4, 10.0], 0.5
    )
    state = np.zeros(24)
    state[3:6] = [0.0, 0.0, 1.0]  # bore axis
    state[12:15] = [e * 0.6, e * 0.8, 0.0]  # journal centre
    state[15:18] = [0.0, 0.0, 1.0]  # journal axis
    state[18:21] = [0.3, 0.4, 0.0]  # journal velocity
    state[21:24] = [0.0, 0.0, 10.0]  # journal angular velocity
    out = joint.forces(normal, friction, state, [0.5] * 4)
    assert out["normal_force"][:2].sum() == pytest.approx(planar["normal_force"], rel=1e-12)
    np.testing.assert_allclose(out["force"][:2], planar["journal"][:2], rtol=1e-12)
    assert out["force"][2] == 0.0 and out["tilt"] == 0.0
    tilted = state.copy()
    tilted[15:18] = [np.sin(2e-3), 0.0, np.cos(2e-3)]
    both = joint.forces(normal, None, np.stack([state, tilted]), [0.5] * 4)
    assert both["tilt"][1] == pytest.approx(2e-3, rel=1e-12)
    assert np.abs(both["journal_moment"][1]).max() > 1e-3 * both["normal_force"][1].sum() * L
    with pytest.raises(cc.ContactError, match="last axis of 24"):
        joint.forces(normal, None, np.zeros(6), [0.5] * 4)
    with pytest.raises(cc.ContactError, match="axial_clearance"):
        cc.JournalJoint(RI, L, RJ, L, thrust_radius=RJ)
