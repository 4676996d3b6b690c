"""Bad values through the Python API raise Python exceptions, never crash the interpreter.

The Python counterpart of `cargo xtask fuzz` (docs/fuzzing.md): NaN, infinities, negative radii,
zero masses, wrong lengths and kinds, missing files and malformed model text must each raise
:class:`clr_contact.ContactError` or :class:`clr_contact.ModelError` (both ``ValueError``) with
a message, or :class:`clr_contact.SimulationError` for an integrator failure.
"""

import math

import numpy as np
import pytest

import clr_contact as cc

NAN, INF = math.nan, math.inf
INTERNAL = [207e9, 0.3, 10e-3, 207e9, 0.3, 9.9e-3]


@pytest.mark.parametrize(
    "elastic, params, damping, c_e",
    [
        ("hertz-internal-cylinder", INTERNAL, "lankarani-nikravesh", NAN),
        ("hertz-internal-cylinder", INTERNAL, "lankarani-nikravesh", INF),
        ("hertz-internal-cylinder", INTERNAL, "lankarani-nikravesh", 0.0),
        ("hertz-internal-cylinder", INTERNAL, "lankarani-nikravesh", -0.5),
        ("hertz-internal-cylinder", INTERNAL, "lankarani-nikravesh", 1.5),
        ("hertz-internal-cylinder", [207e9, 0.3, -10e-3, 207e9, 0.3, 9.9e-3], "ln", 0.9),
        ("hertz-internal-cylinder", [207e9, 0.3, 10e-3, 207e9, 0.3, 10e-3], "ln", 0.9),
        ("hertz-internal-cylinder", [207e9, 0.3, 10e-3, 207e9, 0.3, NAN], "ln", 0.9),
        ("hertz-internal-cylinder", [NAN] * 6, "ln", 0.9),
        ("hertz-internal-cylinder", INTERNAL[:5], "ln", 0.9),
        ("hertz-internal-cylinder", INTERNAL + [1.0], "ln", 0.9),
        ("hertz-internal-cylinder", [], "ln", 0.9),
        ("hertz", [-1e10], "ln", 0.9),
        ("hertz", [INF], "ln", 0.9),
        ("power", [1e10, NAN], "ln", 0.9),
        ("linear", [0.0], "ln", 0.9),
        ("no-such-law", [1e10], "ln", 0.9),
        ("hertz", [1e10], "no-such-damping", 0.9),
        ("", [], "", 0.9),
    ],
)
def test_normal_law_refuses_bad_parameters(elastic, params, damping, c_e):
    with pytest.raises(cc.ContactError) as e:
        cc.NormalLaw(elastic, params, damping, c_e)
    assert str(e.value)


@pytest.mark.parametrize(
    "kwargs",
    [
        dict(bearing_radius=-10e-3),
        dict(journal_radius=-9.9e-3),
        dict(journal_radius=10e-3),
        dict(journal_radius=11e-3),
        dict(bearing_radius=NAN),
        dict(length=0.0),
        dict(length=INF),
        dict(bearing_material=(0.0, 0.3)),
        dict(journal_material=(207e9, 0.5)),
        dict(journal_material=(NAN, 0.3)),
    ],
)
def test_preset_refuses_bad_geometry(kwargs):
    with pytest.raises(cc.ContactError):
        cc.NormalLaw.preset("LN", 0.9, **kwargs)


def test_preset_refuses_unknown_names_and_bad_restitution():
    for name, c_e in [("nope", 0.9), ("", 0.9), ("LN", NAN), ("LN", 0.0), ("LN", -INF)]:
        with pytest.raises(cc.ContactError):
            cc.NormalLaw.preset(name, c_e)


def test_min_impact_velocity_must_be_positive_and_finite():
    for v in [0.0, -1.0, NAN, INF]:
        with pytest.raises(cc.ContactError):
            cc.NormalLaw("hertz", [1e10], "ln", 0.9, min_impact_velocity=v)


def test_law_evaluation_refuses_non_finite_inputs():
    law = cc.NormalLaw("hertz-internal-cylinder", INTERNAL, "ln", 0.9)
    for args in [(NAN, 0.1, 0.5), (1e-5, INF, 0.5), (1e-5, 0.1, -INF)]:
        with pytest.raises(cc.ContactError):
            law.force(*args)
    with pytest.raises(cc.ContactError):
        law.force(np.array([1e-5, NAN]), 0.1, 0.5)
    with pytest.raises(cc.ContactError):
        law.elastic_force(NAN)
    # wrong shapes are numpy's broadcasting errors
    with pytest.raises(ValueError):
        law.force(np.zeros(3), np.zeros(2), 0.5)


@pytest.mark.parametrize(
    "kind, params",
    [
        ("coulomb", [NAN, 1e-4]),
        ("coulomb", [-0.1, 1e-4]),
        ("coulomb", [0.1, 0.0]),
        ("coulomb", [0.1]),
        ("coulomb", []),
        ("ambrosio", [0.1, 1e-3, 1e-4]),
        ("threlfall", [0.1, -INF]),
        ("stribeck", [0.2, 0.1, 1e-3]),
        ("no-such-friction", [0.1, 1e-4]),
    ],
)
def test_friction_law_refuses_bad_parameters(kind, params):
    with pytest.raises(cc.ContactError):
        cc.FrictionLaw(kind, params)


def test_friction_evaluation_refuses_non_finite_inputs():
    f = cc.FrictionLaw("coulomb", [0.1, 1e-4])
    for v, n in [(NAN, 1.0), (0.1, INF), (-INF, 1.0)]:
        with pytest.raises(cc.ContactError):
            f.force(v, n)
    with pytest.raises(cc.ContactError):
        f.coefficient(NAN)


@pytest.mark.parametrize(
    "ri, rj",
    [(-10e-3, 9.9e-3), (10e-3, -9.9e-3), (10e-3, 10e-3), (9e-3, 10e-3), (0.0, 0.0),
     (NAN, 9.9e-3), (10e-3, INF)],
)
def test_revolute_joint_refuses_bad_radii(ri, rj):
    with pytest.raises(cc.ContactError):
        cc.RevoluteJoint(ri, rj)


def test_revolute_joint_refuses_bad_states():
    j = cc.RevoluteJoint(10e-3, 9.9e-3)
    law = cc.NormalLaw.preset("LN", 0.9)
    good = np.zeros(6)
    with pytest.raises(cc.ContactError):
        j.forces(law, None, np.full(6, NAN), good, 0.5)
    with pytest.raises(cc.ContactError):
        j.forces(law, None, good, good, INF)
    with pytest.raises(cc.ContactError):
        j.forces(law, None, np.zeros(5), good, 0.5)
    with pytest.raises(cc.ContactError):
        j.forces(law, None, 1.0, good, 0.5)


def test_damping_and_restitution_refuse_bad_values():
    for c in [NAN, 0.0, -1.0, 2.0]:
        with pytest.raises(cc.ContactError):
            cc.damping_chi("ln", c)
    with pytest.raises(cc.ContactError):
        cc.damping_chi("no-such-damping", 0.5)
    for chi in [NAN, -1.0, INF]:
        with pytest.raises(cc.ContactError):
            cc.effective_restitution(chi)


def test_run_model_refuses_missing_files_and_unknown_names(tmp_path):
    with pytest.raises(cc.ModelError, match="cannot read"):
        cc.run_model(str(tmp_path / "missing.toml"))
    with pytest.raises(cc.ModelError, match="unknown built-in model"):
        cc.run_model("no_such_model")


@pytest.mark.parametrize(
    "text, needle",
    [
        ("this is not toml [", "bad.toml:1"),
        ("[model]\nname = 1\n", "bad.toml:2"),
        ("[[body]]\nname = \"b\"\nmass = 0.0\ninertia = 1.0\n[output]\nt_end = 0.1\n", "mass"),
        ("[[body]]\nname = \"b\"\nmass = nan\ninertia = 1.0\n[output]\nt_end = 0.1\n", "mass"),
        ("[[body]]\nname = \"b\"\nmass = 1.0\ninertia = -inf\n[output]\nt_end = 0.1\n", "inertia"),
        ("[[body]]\nname = \"b\"\nmass = 1.0\ninertia = 1.0\n[output]\nt_end = nan\n", "t_end"),
        ("[model]\nbuiltin = \"slider_crank\"\n[parameters]\nrod_mass = \"heavy\"\n", "rod_mass"),
        ("[model]\nbuiltin = \"nope\"\n", "unknown built-in model"),
        ("", "nothing that moves"),
    ],
)
def test_run_model_refuses_bad_model_text(tmp_path, text, needle):
    path = tmp_path / "bad.toml"
    path.write_text(text)
    with pytest.raises(cc.ModelError) as e:
        cc.run_model(str(path))
    assert needle in str(e.value)


@pytest.mark.parametrize(
    "kwargs",
    [
        dict(t_end=NAN),
        dict(t_end=-1.0),
        dict(t_end=INF),
        dict(rtol=0.0),
        dict(rtol=NAN),
        dict(set={"no_such_parameter": 1.0}),
        dict(set={"crank_speed_rpm": "fast"}),
        dict(set={1: 2.0}),
    ],
)
def test_run_model_refuses_bad_settings(kwargs):
    with pytest.raises((cc.ModelError, TypeError)):
        cc.run_model("slider_crank", **kwargs)
