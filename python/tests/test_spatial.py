"""Spatial models built in Python: ``clr_sim.Model(space="spatial")`` and ``clr_sim.spatial``.

References (independent formulations):
- the model file models/examples/heavy_top.toml read by the Rust model-file reader, and the
  `clr` binary's results.csv for it (an independent process, shortest round-trip form): the top
  built in Python must give the same checked text and the same numbers bit for bit;
- the heavy symmetric top's first integrals (Goldstein, Classical Mechanics, 3rd ed., §5.7,
  eqs. 5.59–5.61): the energy E, the vertical component L_z of the angular momentum about the
  fixed point and its component p_ψ = I₃ω₃ along the spin axis are constant, recomputed here from
  the position, quaternion and angular-velocity columns (not the engine's energy columns);
- the spatial reader's own lists of sections, kinds and fields: every `SpatialModel` method
  takes exactly the fields of its kind.
"""

import inspect
import os
import pathlib
import re
import subprocess

import numpy as np
import pytest

import clr_sim
from clr_sim import spatial
from clr_sim.model import SPATIAL_METHODS, SpatialModel

ROOT = pathlib.Path(__file__).resolve().parents[2]
HEAVY_TOP = ROOT / "models" / "examples" / "heavy_top.toml"

# the top of heavy_top.toml: kg, m, kg·m², rad/s
MASS, COM, I1, I3, SPIN, TILT, G = 0.5, 0.04, 1.2e-4, 2.0e-4, 120.0, 0.3, 9.81


def heavy_top_in_python() -> clr_sim.Model:
    """models/examples/heavy_top.toml, written with the builder."""
    m = clr_sim.Model("heavy_top", space="spatial", gravity=(0.0, 0.0, -G))
    m.body("top", mass=MASS, principal_inertia=(I1, I1, I3), centre_of_mass=(0.0, 0.0, COM),
           position=(0.0, 0.0, 0.0), orientation=spatial.axis_angle((1.0, 0.0, 0.0), TILT),
           angular_velocity=(0.0, 0.0, SPIN), angular_velocity_frame="body")
    m.spherical("tip", a=spatial.at("ground"), b=spatial.at("top"))
    m.solver(rtol=1e-8)
    m.output(t_end=2.0, intervals=400)
    return m


def assert_same_run(a: clr_sim.Result, b: clr_sim.Result) -> None:
    assert a.csv_names() == b.csv_names()
    for c in a.csv_names():
        assert np.array_equal(a[c], b[c]), c


def test_the_heavy_top_built_in_python_is_the_model_file():
    m = heavy_top_in_python()
    assert isinstance(m, SpatialModel) and isinstance(m, clr_sim.Model)
    assert m.space == "spatial" and clr_sim.Model("p").space == "planar"
    assert m.to_toml() == clr_sim.Model.from_file(HEAVY_TOP).to_toml()
    runs = [clr_sim.simulate(x, t_end=0.05) for x in (m, HEAVY_TOP)]
    assert_same_run(*runs)
    # the dict form reads back as a spatial model
    again = clr_sim.Model.from_dict(m.to_dict())
    assert isinstance(again, SpatialModel) and again.to_toml() == m.to_toml()


def _clr_binary():
    exe = os.environ.get("CLR_BIN") or str(ROOT / "target" / "debug" / "clr")
    return exe if os.path.isfile(exe) else None


@pytest.mark.skipif(_clr_binary() is None, reason="no clr binary (cargo test builds target/debug/clr)")
def test_the_heavy_top_built_in_python_equals_clr_run_bit_for_bit(tmp_path):
    """The `clr` binary runs the shipped file; results.csv holds every value in shortest
    round-trip form, so float() of it is the binary's number."""
    model = tmp_path / "top.toml"
    model.write_text(heavy_top_in_python().to_toml())
    subprocess.run(
        [_clr_binary(), "run", str(HEAVY_TOP), "--t-end", "0.5", "--out", str(tmp_path / "out"),
         "--quiet", "--no-figures"],
        check=True,
    )
    lines = (tmp_path / "out" / "results.csv").read_text().splitlines()
    names = [h.rsplit(" [", 1)[0] for h in lines[0].split(",")]
    rows = np.array([[float(v) for v in line.split(",")] for line in lines[1:] if line])
    r = clr_sim.simulate(heavy_top_in_python(), t_end=0.5)
    assert names == r.csv_names() and rows.shape == (len(r.time), len(names))
    for k, n in enumerate(names):
        assert np.array_equal(rows[:, k], r[n]), n


def _rotation(qw, qx, qy, qz):
    """Rotation matrices body → world of unit quaternions (scalar first), shape (n, 3, 3)."""
    return np.stack([
        np.stack([1 - 2 * (qy**2 + qz**2), 2 * (qx * qy - qw * qz), 2 * (qx * qz + qw * qy)], -1),
        np.stack([2 * (qx * qy + qw * qz), 1 - 2 * (qx**2 + qz**2), 2 * (qy * qz - qw * qx)], -1),
        np.stack([2 * (qx * qz - qw * qy), 2 * (qy * qz + qw * qx), 1 - 2 * (qx**2 + qy**2)], -1),
    ], -2)


def test_the_heavy_top_keeps_its_three_first_integrals():
    """Goldstein §5.7: E, L_z and p_ψ = I₃ω₃ are constant (the top's tip is fixed, gravity
    has no moment about the vertical through it nor about the spin axis). Recomputed from the
    columns: position of the centre of mass (m), quaternion, ω in the body frame (rad/s).
    Over 0.5 s (the tilt swings from 0.3 to 1.09 rad) at rtol = 1e-8 the measured drifts are
    7.4e-8 (E) and 4.5e-7 (L_z) relative, and they shrink with the tolerance (2.4e-9 and
    1.2e-8 at rtol = 1e-10): the integrator's error. I₃ω₃ stays exactly constant (Euler's
    third equation has no term for a symmetric top). Tolerance 2e-6 (4 times the largest
    drift); a missing gyroscopic or gravity term changes them by order one."""
    r = clr_sim.simulate(heavy_top_in_python(), t_end=0.5)
    R = _rotation(r["top.qw"], r["top.qx"], r["top.qy"], r["top.qz"])
    w = np.stack([r["top.wx"], r["top.wy"], r["top.wz"]], -1)            # body frame
    c = np.stack([r["top.x"], r["top.y"], r["top.z"]], -1)               # centre of mass
    v = np.stack([r["top.vx"], r["top.vy"], r["top.vz"]], -1)
    Ic = np.diag([I1, I1, I3])
    energy = 0.5 * MASS * (v**2).sum(-1) + 0.5 * np.einsum("ni,ij,nj->n", w, Ic, w) \
        + MASS * G * c[:, 2]
    L = MASS * np.cross(c, v) + np.einsum("nij,jk,nk->ni", R, Ic, w)   # about the tip
    p_psi = I3 * w[:, 2]
    # at t = 0: spin only, the axis tilted by TILT about x
    e0 = 0.5 * I3 * SPIN**2 + MASS * G * COM * np.cos(TILT)
    assert abs(energy[0] - e0) <= 1e-12 * e0
    for name, q in (("E", energy), ("L_z", L[:, 2]), ("p_psi", p_psi)):
        drift = np.max(np.abs(q - q[0])) / abs(q[0])
        assert drift <= 2e-6, (name, drift)
    # the top does move: it nutates (the tilt changes) while it precesses
    tilt = np.arccos(R[:, 2, 2])
    assert tilt.max() - tilt.min() > 1e-3


def test_every_spatial_kind_has_its_method_with_the_fields_of_the_file():
    """The spatial reader lists its sections and each kind's fields; each SpatialModel method
    takes exactly those (`type` is the method's own). `clearance_force_application` is the
    one parameter more, of the shared constructor: the spatial reader refuses it."""
    kinds = set()
    for section, names in clr_sim._native.element_kinds(space="spatial"):
        kinds |= {(section, k) for k in names} if names else {(section, None)}
    assert kinds == set(SPATIAL_METHODS), kinds ^ set(SPATIAL_METHODS)
    for (section, kind), method in SPATIAL_METHODS.items():
        params = set(inspect.signature(getattr(SpatialModel, method)).parameters) - {"self"}
        fields = set(clr_sim._native.kind_fields(section, kind, space="spatial"))
        if method == "__init__":
            assert params - fields == {"clearance_force_application"}, params ^ fields
            params -= {"clearance_force_application"}
        assert params == fields, (section, kind, params ^ fields)
    with pytest.raises(clr_sim.FieldError) as e:
        clr_sim.Model("x", space="spatial", clearance_force_application="contact_points")
    assert e.value.field.startswith("model") and "clearance_force_application" in str(e.value)


def every_kind() -> clr_sim.Model:
    """One item of every spatial element kind: seven bodies, each on its own joint to the
    ground, the drivers, forces and a ball in a socket between them; every orientation form."""
    m = clr_sim.Model("every_kind", space="spatial", gravity=(0.0, 0.0, -9.81),
                      description="every element kind of a spatial model")
    x, y, z = (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)
    forms = [
        None,
        spatial.quaternion(1.0, 0.0, 0.0, 0.0),
        spatial.axis_angle(z, 0.0),
        spatial.euler((0.0, 0.0, 0.0), "zyx"),
        spatial.matrix([x, y, z]),
        spatial.euler((0.0, 0.0, 0.0), "zxz"),
        None,
    ]
    joints = ["spherical", "revolute", "universal", "cylindrical", "prismatic", "planar_joint",
              "fixed"]
    for k, (joint, form) in enumerate(zip(joints, forms)):
        body = f"b{k}"
        m.body(body, mass=1.0, inertia=[[0.01, 0, 0], [0, 0.01, 0], [0, 0, 0.01]]
               if k == 6 else None, principal_inertia=None if k == 6 else (0.01, 0.02, 0.02),
               principal_axes=[x, y, z] if k == 1 else None, centre_of_mass=(0.1, 0.0, 0.0),
               position=(0.0, 2.0 * k, 0.0), orientation=form,
               velocity=(0.0, 0.0, 0.0) if k == 0 else None,
               velocity_frame="world" if k == 0 else None,
               angular_velocity=(0.0, 0.0, 0.0) if k == 0 else None,
               angular_velocity_frame="body" if k == 0 else None)
        axis = None if joint in ("spherical", "fixed") else z
        b_axis = x if joint == "universal" else None
        getattr(m, joint)(f"j{k}", a=spatial.at("ground", 0.0, 2.0 * k, 0.0, axis=axis),
                          b=spatial.at(body, axis=b_axis))
    m.drive_revolute_angle("spin", joint="j1", motion=clr_sim.motion("linear", initial=0.0,
                                                                     rate=1.0))
    m.drive_prismatic_displacement("push", joint="j4", motion=clr_sim.motion("constant",
                                                                             value=0.0))
    m.spring_damper("spring", a=spatial.at("b0", 0.1), b=spatial.at("b2", 0.1),
                    stiffness=100.0, damping=1.0, free_length=2.0)
    m.actuator("act", a=spatial.at("b2"), b=spatial.at("b3"),
               force=clr_sim.motion("constant", value=1.0))
    m.rotational_spring_damper("coil", joint="j3", stiffness=1.0, damping=0.1, free_angle=0.0)
    m.bushing("bush", a=spatial.at("b5"), b=spatial.at("b6"), stiffness=(1.0, 1.0, 1.0),
              damping=(0.1, 0.1, 0.1), rotational_stiffness=(1.0, 1.0, 1.0),
              rotational_damping=(0.0, 0.0, 0.0))
    m.force("push_b0", at=spatial.at("b0", 0.1), frame="world",
            fz=clr_sim.motion("constant", value=1.0))
    m.torque("twist", body="b3", frame="body", mz=clr_sim.motion("constant", value=0.01))
    m.body("ball", mass=0.1, principal_inertia=(1e-5, 1e-5, 1e-5), position=(0.0, -2.0, 0.0))
    m.spherical_clearance("socket", socket=spatial.at("ground", 0.0, -2.0, 0.0),
                          ball=spatial.at("ball"),
                          socket_radius=0.01, ball_radius=0.0099,
                          normal=clr_sim.normal("hertz", 0.9, stiffness=1e9,
                                                damping="lankarani-nikravesh"),
                          friction=clr_sim.friction("coulomb", mu=0.1, v_reg=1e-4))
    # journals centred in their bores, axes along z (gravity axial: the revolute one rests on a
    # thrust face, the cylindrical one slides)
    steel = {"youngs_modulus": 207e9, "poisson_ratio": 0.3}
    journal_law = clr_sim.normal("liu", 0.9, damping="lankarani-nikravesh",
                                 bearing_material=steel, journal_material=steel)
    for kind, y0 in (("revolute", -4.0), ("cylindrical", -6.0)):
        m.body(f"{kind}_pin", mass=0.1, principal_inertia=(1e-5, 1e-5, 1e-5),
               position=(0.0, y0, 0.0))
        getattr(m, f"{kind}_clearance")(
            f"{kind}_joint", bearing=spatial.at("ground", 0.0, y0, 0.0, axis=z),
            journal=spatial.at(f"{kind}_pin", axis=z), bearing_radius=0.01,
            bearing_length=0.015, journal_radius=0.0099, journal_length=0.015,
            normal=journal_law, **({"axial_clearance": 1e-4} if kind == "revolute" else {}))
    # a ball dropped onto a ground box (shape contact)
    m.body("drop", mass=0.03, principal_inertia=(1e-6, 1e-6, 1e-6), position=(0.0, -8.0, 0.0102))
    m.shape("floor", at=spatial.at("ground", 0.0, -8.0, -0.05),
            geometry={"type": "cuboid", "half_extents": [0.1, 0.1, 0.05]})
    m.shape("bead", at=spatial.at("drop"), orientation=spatial.axis_angle(z, 0.0),
            geometry={"type": "ball", "radius": 0.01})
    m.contact("drop_contact", shapes=["floor", "bead"],
              normal=clr_sim.normal("hertz", 0.9, stiffness=1e10, damping="flores"),
              friction=clr_sim.friction("coulomb", mu=0.1, v_reg=1e-4))
    # a [[measure]] of each kind and a [[metric]] of a spatial column
    m.measure_position("bead_top", at=spatial.at("drop", 0.0, 0.0, 0.01))
    m.measure_velocity("bead_top", at=spatial.at("drop", 0.0, 0.0, 0.01), frame="b1")
    m.measure_acceleration("bead_top", at=spatial.at("drop", 0.0, 0.0, 0.01))
    m.measure_distance("bead_floor", a=spatial.at("ground", 0.0, -8.0, 0.0),
                       b=spatial.at("drop"))
    m.metric("drop_peak_speed", of="drop.vz", statistic="peak")
    m.solver(rtol=1e-6)
    m.output(t_end=0.01, intervals=10)
    return m


def test_every_spatial_element_kind_is_reachable_and_runs():
    m = every_kind()
    doc = m.to_dict()
    used = {(s, i.get("type")) for s in ("joint", "driver", "force", "clearance", "shape",
                                         "measure", "metric") for i in doc.get(s, [])}
    assert used | {("model", None), ("solver", None), ("output", None), ("body", None)} == \
        set(SPATIAL_METHODS)
    text = m.to_toml()
    assert 'type = "planar"' in text and "quaternion" in text and "matrix" in text
    r = clr_sim.simulate(m)
    assert r.ok, r.error
    for k in range(7):
        assert f"j{k}.Fx" in r.columns and f"b{k}.qw" in r.columns
    assert "socket.penetration" in r.columns
    # closed forms of the driven and locked bodies: b1 turns about the world z axis by the
    # driven angle θ = t (quaternion (cos θ/2, 0, 0, sin θ/2)); b4's prismatic displacement is
    # held at 0 and b6 is welded, so their centres of mass stay where they started. Tolerance
    # 1e-6: the constraints hold to the integrator's tolerance (rtol = 1e-6) and better.
    t = r.time
    np.testing.assert_allclose(r["b1.qw"], np.cos(t / 2), rtol=0, atol=1e-6)
    np.testing.assert_allclose(r["b1.qz"], np.sin(t / 2), rtol=0, atol=1e-6)
    for body, y in (("b4", 8.0), ("b6", 12.0)):
        for c, v in (("x", 0.1), ("y", y), ("z", 0.0)):
            np.testing.assert_allclose(r[f"{body}.{c}"], v, rtol=0, atol=1e-6)
    # the ball falls into its socket: contact within the 0.01 s
    assert r["socket.penetration"].max() > 0
    # the dropped ball (0.2 mm above the box) lands after √(2h/g) = 6.4 ms, within the 0.01 s
    # (the contact lasts less than an output interval: its rebound shows in the velocity, up
    # at 0.01 s where a free fall would be at −g·0.01 s)
    assert r["drop.vz"][-1] > 0
    assert r.metrics["drop_peak_speed"] == np.max(np.abs(r["drop.vz"]))
    # the ball does not turn before it lands, and its landing turns it by less than 1e-7 rad:
    # its top stays 10 mm above its centre (1e-9 m = 10 mm × 1e-7); before it lands, its
    # distance from the floor point below it is its height (1e-12 m: rounding of the subtraction)
    np.testing.assert_allclose(r["bead_top.z"], r["drop.z"] + 0.01, rtol=0, atol=1e-9)
    np.testing.assert_allclose(r["bead_floor.distance"][:3], r["drop.z"][:3], rtol=0, atol=1e-12)


def _line_of(marker: str) -> str:
    """``file:line`` of the line of this file that contains ``marker`` (a call under test)."""
    for k, line in enumerate(pathlib.Path(__file__).read_text().splitlines(), start=1):
        if marker in line and "_line_of" not in line:
            return f"{__file__}:{k}"
    raise AssertionError(marker)


def test_errors_are_refused_at_the_call_with_element_field_and_line():
    m = heavy_top_in_python()
    before = m.to_dict()
    with pytest.raises(clr_sim.FieldError) as e:
        m.body("heavy", mass="0.5", principal_inertia=(1.0, 1.0, 1.0))  # call: wrong type
    assert e.value.field == "body[1].mass" and e.value.element == "body 'heavy'"
    assert e.value.where == _line_of("call: wrong type")
    with pytest.raises(clr_sim.FieldError) as e:
        m.body("nothing", mass=None)  # call: None for a required value
    assert e.value.field.startswith("body[1]") and "mass" in str(e.value)
    assert e.value.where == _line_of("call: None for a required")
    with pytest.raises(clr_sim.FieldError) as e:
        m.revolute("hinge", a={"body": "ground", "axs": [0.0, 0.0, 1.0]},  # call: unknown field
                   b=spatial.at("top"))
    assert e.value.field == "joint[1].a.axs" and e.value.element == "joint 'hinge'"
    assert e.value.where == _line_of("call: unknown field")
    with pytest.raises(clr_sim.FieldError) as e:
        m.spherical_clearance("cup", socket=spatial.at("ground"), ball=spatial.at("top"),
                              socket_radius=0.01, ball_radius=0.02,  # call: out of range
                              normal=clr_sim.normal("hertz", 0.9, stiffness=1e9))
    assert e.value.field.startswith("clearance[0]") and e.value.element == "clearance 'cup'"
    with pytest.raises(clr_sim.FieldError) as e:
        m.spherical("tip", a=spatial.at("ground"), b=spatial.at("top"))  # call: name taken
    assert "tip" in str(e.value)
    with pytest.raises(clr_sim.FieldError) as e:
        m.solver(method="no_such_method")
    assert e.value.element == "[solver]"
    # nothing refused was added
    assert m.to_dict() == before


def test_names_defined_later_are_checked_when_the_model_is_used():
    m = clr_sim.Model("later", space="spatial")
    m.spherical("tip", a=spatial.at("ground"), b=spatial.at("top"))  # added: body later
    m.drive_revolute_angle("motor", joint="hinge",  # added: joint later
                           motion=clr_sim.motion("linear", initial=0.0, rate=1.0))
    m.body("top", mass=0.5, principal_inertia=(1e-4, 1e-4, 2e-4))
    m.output(t_end=0.1)
    with pytest.raises(clr_sim.FieldError) as e:
        m.check()
    assert e.value.element == "driver 'motor'" and e.value.field == "driver[0].joint"
    assert e.value.added_at == _line_of("added: joint later") and "hinge" in str(e.value)
    m2 = clr_sim.Model("typo", space="spatial")
    m2.body("top", mass=0.5, principal_inertia=(1e-4, 1e-4, 2e-4))
    m2.spherical("tip", a=spatial.at("ground"), b=spatial.at("toop"))  # added: misspelt
    m2.output(t_end=0.1)
    with pytest.raises(clr_sim.FieldError) as e:
        m2.check()
    assert e.value.element == "joint 'tip'" and e.value.field == "joint[0].b.body"
    assert e.value.added_at == _line_of("added: misspelt") and "toop" in str(e.value)


def test_a_method_of_the_other_space_names_the_one_to_use():
    m = heavy_top_in_python()
    with pytest.raises(clr_sim.FieldError) as e:
        m.translational("slide", a=spatial.at("ground"), b=spatial.at("top"), axis=(1, 0))
    assert e.value.field == "model.space" and "prismatic()" in str(e.value)
    assert e.value.where.startswith(__file__)
    with pytest.raises(clr_sim.FieldError, match="drive_revolute_angle"):
        m.drive_angle("motor", body="top", motion=clr_sim.motion("constant", value=0.0))
    with pytest.raises(clr_sim.FieldError, match="translational_clearance"):
        m.translational_clearance("B")
    planar = clr_sim.Model("p", gravity=(0.0, -9.81))
    with pytest.raises(clr_sim.FieldError, match="revolute_clearance") as e:
        planar.spherical_clearance("cup")
    assert 'space="spatial"' in str(e.value)
    with pytest.raises(clr_sim.FieldError, match="translational"):
        planar.prismatic("slide", a=clr_sim.at("ground"), b=clr_sim.at("ground"))
    # the planar at() is refused by the spatial reader: a point has three coordinates
    with pytest.raises(clr_sim.FieldError) as e:
        m.spherical("tip2", a=clr_sim.at("ground"), b=spatial.at("top"))
    assert e.value.field.startswith("joint[1].a")


def test_the_spatial_helpers_write_the_file_forms_and_refuse_bad_arguments():
    assert spatial.at("top", 1, 2, 3, axis=np.array([0.0, 0.0, 2.0])) == \
        {"body": "top", "at": [1.0, 2.0, 3.0], "axis": [0.0, 0.0, 2.0]}
    assert spatial.quaternion(1, 0, 0, 0) == {"quaternion": [1.0, 0.0, 0.0, 0.0]}
    assert spatial.axis_angle((0, 0, 1), 0.5) == {"axis": [0.0, 0.0, 1.0], "angle": 0.5}
    assert spatial.euler((0.1, 0.2, 0.3)) == {"euler": [0.1, 0.2, 0.3], "sequence": "zyx"}
    assert spatial.matrix(np.eye(3)) == {"matrix": np.eye(3).tolist()}
    cases = [
        (lambda: spatial.at("top", "0.1"), "at.x"),
        (lambda: spatial.at(None), "at.body"),
        (lambda: spatial.at("top", axis=(0, 1)), "at.axis"),
        (lambda: spatial.quaternion(1, 0, None, 0), "quaternion.y"),
        (lambda: spatial.axis_angle(None, 0.3), "axis_angle.axis"),
        (lambda: spatial.axis_angle((1, 0, 0), None), "axis_angle.angle"),
        (lambda: spatial.euler((1, 2), "zyx"), "euler.angles"),
        (lambda: spatial.euler((1, 2, 3), 3), "euler.sequence"),
        (lambda: spatial.matrix([[1, 0, 0], [0, 1, 0]]), "matrix.rows"),
        (lambda: spatial.matrix([[1, 0, 0], [0, 1, 0], [0, "1", 0]]), "matrix.rows[2][1]"),
    ]
    for call, field in cases:
        with pytest.raises(clr_sim.FieldError) as e:
            call()
        assert e.value.field == field, (field, str(e.value))
        assert e.value.where.startswith(__file__)
    # a bad orientation is refused by the reader at the body's call
    m = clr_sim.Model("o", space="spatial")
    with pytest.raises(clr_sim.FieldError) as e:
        m.body("b", mass=1.0, principal_inertia=(1, 1, 1),
               orientation=spatial.quaternion(1.0, 0.1, 0.0, 0.0))  # norm off 1
    assert e.value.field.startswith("body[0]")


def test_the_spatial_example_of_the_docs_runs():
    """docs/python.md, section "Spatial models": its Python block runs as written."""
    text = (ROOT / "docs" / "python.md").read_text()
    section = text.split("## Spatial models", 1)[1].split("\n## ", 1)[0]
    blocks = re.findall(r"```python\n(.*?)```", section, re.S)
    assert blocks
    scope: dict = {}
    exec(compile(blocks[0], "docs/python.md", "exec"), scope)
    r = scope["r"]
    assert r.ok and len(r.time) > 1


def lubricated_journal(film) -> clr_sim.Model:
    """The journal of crates/clr-mbd/tests/spatial.rs (lubricated_journal_carries_its_weight_...):
    a 2 kg pin spinning at 200 rad/s in a short-bearing film, 50 ms."""
    m = clr_sim.Model("film", space="spatial", gravity=(0.0, -9.81, 0.0))
    m.body("pin", mass=2.0, principal_inertia=(0.5, 0.5, 1.0), position=(0.0, 0.0, 0.0),
           angular_velocity=(0.0, 0.0, 200.0), angular_velocity_frame="body")
    m.cylindrical_clearance("J", bearing=spatial.at("ground", axis=(0.0, 0.0, 1.0)),
                            journal=spatial.at("pin", axis=(0.0, 0.0, 1.0)),
                            bearing_radius=0.010, bearing_length=0.02, journal_radius=0.0095,
                            journal_length=0.02,
                            normal=clr_sim.normal("linear", 0.5, stiffness=1e8,
                                                  damping="hunt-crossley"),
                            lubrication=film)
    m.output(t_end=0.05, intervals=10)
    return m


def test_a_lubricated_journal_writes_its_film_columns():
    # only the field and its columns here (the closed forms are checked in Rust): the film takes
    # up the weight 19.62 N, so its force is positive and below 1.5 times the weight during the
    # squeeze transient, the minimum film thickness within the clearance 0.5 mm; `length` is
    # refused (the film length is the overlap of journal and bore)
    film = {"model": "short_bearing", "viscosity": 0.05, "film_threshold": 1e-6}
    r = clr_sim.simulate(lubricated_journal(film))
    assert r.ok, r.error
    assert 0.0 < r["J.film_force"][-1] < 1.5 * 2.0 * 9.81
    assert 0.0 < r["J.film_thickness"][-1] <= 5e-4
    with pytest.raises(clr_sim.FieldError, match="overlap"):
        clr_sim.simulate(lubricated_journal(dict(film, length=0.02)))


def test_spatial_metrics_against_free_fall_and_the_columns():
    """``SpatialModel.metric``: a body thrown up at v0 under gravity g, no joint. The final
    velocity and the rise against the closed form v0 − g·T and v0·T − g·T²/2 (1e-8 relative,
    the integrator at rtol 1e-10), and the peak height against numpy on the recorded column
    (exactly: the same rows)."""
    g, v0, t_end = 9.81, 2.0, 0.5
    m = clr_sim.Model("throw", space="spatial", gravity=(0.0, 0.0, -g))
    m.body("ball", mass=0.2, principal_inertia=(1e-4, 1e-4, 1e-4), velocity=(0.0, 0.0, v0),
           velocity_frame="world")
    m.metric("vz_end", of="ball.vz", statistic="final")
    m.metric("rise", of="ball.z", statistic="change")
    m.metric("top", of="ball.z", statistic="max", t_start=0.1)
    m.solver(rtol=1e-10)
    m.output(t_end=t_end, intervals=500)
    r = clr_sim.simulate(m)
    assert r.metrics["vz_end"] == pytest.approx(v0 - g * t_end, rel=1e-8)
    assert r.metrics["rise"] == pytest.approx(v0 * t_end - g * t_end**2 / 2, rel=1e-8)
    z, t = r["ball.z"], r["t"]
    assert r.metrics["top"] == np.max(z[t >= 0.1])
    with pytest.raises(clr_sim.FieldError, match="twin"):
        m.twin(reference_interval=1e-3)
    with pytest.raises(clr_sim.ModelError, match="ball.vz"):
        m.metric("typo", of="ball.vzz", statistic="peak").check()


def test_spatial_measures_of_a_spinning_rotor():
    """``SpatialModel.measure_position`` / ``measure_velocity`` / ``measure_distance``: a rotor
    spinning freely at ω about its symmetry axis; the point L along its x axis moves on the
    circle (L cos ωt, L sin ωt, 0) at speed L·ω, and its distance from the ground point
    (0, 0, 1) is √(L² + 1), constant. Tolerances: 1e-7 m on positions (the integrator at rtol
    1e-10 over 5 rad of rotation, as the Rust closed-form test), and ω times that, 1e-6 m/s, on the
    velocities and the distance rate."""
    w, l = 10.0, 0.5
    m = clr_sim.Model("rotor", space="spatial")
    m.body("rotor", mass=1.0, principal_inertia=(1e-3, 1e-3, 2e-3),
           velocity=(0.0, 0.0, 0.0), velocity_frame="world",
           angular_velocity=(0.0, 0.0, w), angular_velocity_frame="world")
    m.measure_position("tip", at=spatial.at("rotor", l, 0.0, 0.0))
    m.measure_velocity("tip", at=spatial.at("rotor", l, 0.0, 0.0))
    m.measure_distance("gap", a=spatial.at("ground", 0.0, 0.0, 1.0),
                       b=spatial.at("rotor", l, 0.0, 0.0))
    m.solver(rtol=1e-10)
    m.output(t_end=0.5, intervals=100)
    r = clr_sim.simulate(m)
    t = r["t"]
    np.testing.assert_allclose(r["tip.x"], l * np.cos(w * t), rtol=0, atol=1e-7)
    np.testing.assert_allclose(r["tip.y"], l * np.sin(w * t), rtol=0, atol=1e-7)
    np.testing.assert_allclose(np.hypot(r["tip.vx"], r["tip.vy"]), l * w, rtol=0, atol=1e-6)
    np.testing.assert_allclose(r["gap.distance"], np.sqrt(l * l + 1.0), rtol=0, atol=1e-7)
    np.testing.assert_allclose(r["gap.distance_rate"], 0.0, rtol=0, atol=1e-6)
    assert r.units["tip.vz"] == "m/s"
    with pytest.raises(clr_sim.FieldError, match="measure_position"):
        m.measure_angle("a", body="rotor")
