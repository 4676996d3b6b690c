"""Contact shapes from Python: `Model.shape` (`[[shape]]`), the geometries of `clr_sim.shapes` and
`Model.contact` (`[[clearance]] type = "contact"`).

References:
- rebound heights of a ball dropped on a plane with a restitution-exact law ("hc-exact"):
  free flight gives v² = 2 g h and each impact multiplies the rebound speed by e exactly
  (contact-laws.md §1.3), so the k-th apex is h_k = e^(2k)·h₀. Gravity acts during the ~0.1 ms
  contact and shifts the exit speed by about g·t_c/v ≈ 1e-3 relative; the apex is read from
  0.1 ms samples as the vertex of the parabola through the three samples around each maximum
  (as crates/clr-mbd/tests/shape_contact.rs does). Tolerance 3e-3 relative.
- the model file form of the same model (BALL_DROP_TOML below, the TOML of
  crates/clr-mbd/tests/shape_contact.rs), read by the Rust reader: the model built in Python
  must be the same description and give the same numbers bit for bit;
- the Rust reader's own lists of geometry types and of each type's fields: every helper of
  `clr_sim.shapes` must write exactly those.
"""

import inspect
import math

import numpy as np
import pytest

import clr_sim
from clr_sim import shapes
from clr_sim.shapes import GEOMETRIES

H0 = 0.1  # m, drop height of the ball's lowest point above the floor
E = 0.8  # –, coefficient of restitution
R = 0.01  # m, ball radius

BALL_DROP_TOML = """
[model]
name = "ball_drop"
gravity = [0.0, -9.81]

[[body]]
name = "ball"
mass = 0.0327
inertia = 1.308e-6
position = [0.0, 0.11]
angle = 0.0
velocity = [0.0, 0.0]
angular_velocity = 0.0

[[shape]]
name = "floor"
at = { body = "ground", at = [0.0, -0.05] }
geometry = { type = "cuboid", half_extents = [0.5, 0.05] }

[[shape]]
name = "sphere"
at = { body = "ball", at = [0.0, 0.0] }
geometry = { type = "ball", radius = 0.01 }

[[clearance]]
name = "drop"
type = "contact"
shapes = ["floor", "sphere"]
normal = { law = "hertz", stiffness = 1.5e10, damping = "hc-exact", restitution = 0.8 }

[solver]
rtol = 1e-9
atol = 1e-12

[output]
t_end = 0.9
intervals = 9000
"""


def ball_drop(h0=H0, restitution=E, sphere=None, shapes_pair=("floor", "sphere")) -> clr_sim.Model:
    """A steel ball (r = 10 mm, m = 32.7 g) dropped from h0 above a ground block."""
    m = clr_sim.Model("ball_drop", gravity=(0.0, -9.81))
    m.body("ball", mass=0.0327, inertia=1.308e-6, position=(0.0, R + h0), angle=0.0,
           velocity=(0.0, 0.0), angular_velocity=0.0)
    m.shape("floor", at=clr_sim.at("ground", 0.0, -0.05), geometry=shapes.cuboid(0.5, 0.05))
    m.shape("sphere", at=clr_sim.at("ball"), geometry=sphere or shapes.ball(R))
    m.contact(
        "drop",
        shapes=list(shapes_pair),
        normal=clr_sim.normal("hertz", restitution, stiffness=1.5e10, damping="hc-exact"),
    )
    m.solver(rtol=1e-9, atol=1e-12)
    m.output(t_end=0.9, intervals=9000)
    return m


def apexes(t, y, after=0.01):
    """Heights of the local maxima of y(t) after `after` (s), each the vertex of the parabola
    through the three samples around it."""
    out = []
    for k in range(1, len(y) - 1):
        if y[k] > y[k - 1] and y[k] >= y[k + 1] and t[k] > after:
            a, b, c = y[k - 1], y[k], y[k + 1]
            out.append(b + (a - c) ** 2 / (8.0 * (2.0 * b - a - c)))
    return out


@pytest.fixture(scope="module")
def drop_run():
    return clr_sim.simulate(ball_drop())


def test_ball_drop_rebounds_follow_the_restitution(drop_run):
    r = drop_run
    assert r.ok and r.time[-1] == pytest.approx(0.9, abs=1e-12) and len(r) == 9001
    tops = [h - R for h in apexes(r.time, r["ball.y"])]
    assert len(tops) >= 3, (tops, r.impacts)
    errors = []
    for k, h in enumerate(tops[:3], start=1):
        expected = E ** (2 * k) * H0
        rel = abs(h - expected) / expected
        errors.append(rel)
        assert rel < 3e-3, f"bounce {k}: {h} m vs e^(2k)·h0 = {expected} m (rel {rel:.2e})"
    print("rebound apex relative errors:", ", ".join(f"{e:.2e}" for e in errors))
    # the impacts are located and reported under the element's name, the first at the speed of
    # the free fall from h0
    assert len(r.impacts) >= 3 and all(i["joint"] == "drop" for i in r.impacts)
    v0 = math.sqrt(2.0 * 9.81 * H0)
    assert abs(abs(r.impacts[0]["impact_velocity_m_per_s"]) / v0 - 1.0) < 1e-3


def test_the_python_model_is_its_model_file_bit_for_bit(drop_run):
    m = ball_drop()
    text = m.to_toml()
    assert "[[shape]]" in text and 'type = "contact"' in text
    # the same description as the model file written by hand, and as its own text read back
    assert clr_sim.Model.from_toml(BALL_DROP_TOML).to_toml() == text
    again = clr_sim.Model.from_toml(text)
    assert again.to_toml() == text
    for other in (again, clr_sim.Model.from_dict(m.to_dict())):
        r = clr_sim.simulate(other)
        assert r.column_names() == drop_run.column_names()
        for name in r.column_names():
            assert np.array_equal(r[name], drop_run[name]), name
        assert r.metrics == drop_run.metrics and r.impacts == drop_run.impacts


# every geometry helper with all its arguments (m, rad)
SAMPLES = {
    "ball": lambda: shapes.ball(0.01),
    "capsule": lambda: shapes.capsule(0.02, 0.005),
    "cuboid": lambda: shapes.cuboid(0.03, 0.01),
    "convex_polygon": lambda: shapes.convex_polygon([(0.0, 0.0), (0.02, 0.0), (0.0, 0.02)]),
    "polyline": lambda: shapes.polyline(np.array([[-0.05, 0.0], [0.0, 0.01], [0.05, 0.0]])),
    "compound": lambda: shapes.compound(
        [shapes.part(shapes.cuboid(0.02, 0.005), at=(0.0, 0.01), angle=0.1), shapes.ball(0.005)]
    ),
    "involute_gear": lambda: shapes.involute_gear(
        0.002, 20, pressure_angle=math.radians(20.0), backlash=1e-5, addendum=1.0,
        dedendum=1.25, points_per_flank=12,
    ),
    "beam_face": lambda: shapes.beam_face("rail", "upper", samples_per_element=3),
}


def test_every_geometry_type_has_a_helper_writing_the_fields_of_the_file():
    """The Rust reader lists the geometry types and each type's fields; each helper of
    clr_sim.shapes writes exactly those, and every one is accepted by the reader."""
    kinds = dict(clr_sim._native.element_kinds())["shape.geometry"]
    assert set(kinds) == set(GEOMETRIES) == set(SAMPLES), set(kinds) ^ set(GEOMETRIES)
    for kind in kinds:
        assert callable(getattr(shapes, GEOMETRIES[kind]))
        g = SAMPLES[kind]()
        assert g["type"] == kind
        fields = set(clr_sim._native.kind_fields("shape.geometry", kind))
        assert set(g) - {"type"} == fields, (kind, (set(g) - {"type"}) ^ fields)
    # a part of a compound: part() takes exactly its fields
    part_fields = set(clr_sim._native.kind_fields("shape.geometry.parts"))
    assert set(inspect.signature(shapes.part).parameters) == part_fields
    assert set(SAMPLES["compound"]()["parts"][0]) == part_fields


@pytest.mark.parametrize("kind", sorted(set(SAMPLES) - {"beam_face"}))
def test_every_geometry_reads_and_round_trips(kind):
    tomllib = pytest.importorskip("tomllib")
    m = clr_sim.Model("one_shape")
    m.body("b", mass=1.0, inertia=1e-3, position=(0.0, 0.5), angle=0.0,
           velocity=(0.0, 0.0), angular_velocity=0.0)
    m.shape("probe", at=clr_sim.at("b", 0.001, 0.002), angle=0.3, geometry=SAMPLES[kind]())
    m.shape("ground_ball", at=clr_sim.at("ground"), geometry=shapes.ball(0.01))
    m.contact("pair", shapes=["ground_ball", "probe"],
              normal=clr_sim.normal("hertz", 0.8, stiffness=1e9, damping="hc-exact"))
    m.output(t_end=0.01)
    assert m.check() == []
    text = m.to_toml()
    assert clr_sim.Model.from_toml(text).to_toml() == text
    written = tomllib.loads(text)["shape"][0]
    assert written["angle"] == 0.3 and written["at"] == {"body": "b", "at": [0.001, 0.002]}
    given = SAMPLES[kind]()
    if kind == "compound":
        # the file writes each part's pose, the defaults included
        given["parts"][1] = {"at": [0.0, 0.0], "angle": 0.0, **given["parts"][1]}
    assert written["geometry"] == given


def test_involute_gear_defaults_are_the_files():
    """Arguments left at None are not written: the file's defaults (20°, 0, 1, 1.25, 24)."""
    tomllib = pytest.importorskip("tomllib")
    g = shapes.involute_gear(0.002, 20)
    assert g == {"type": "involute_gear", "module": 0.002, "teeth": 20}
    m = ball_drop(sphere=g)
    geometry = tomllib.loads(m.to_toml())["shape"][1]["geometry"]
    assert geometry == {
        "type": "involute_gear", "module": 0.002, "teeth": 20,
        "pressure_angle": math.radians(20.0), "backlash": 0.0, "addendum": 1.0,
        "dedendum": 1.25, "points_per_flank": 24,
    }


def test_a_misspelt_geometry_field_names_its_path():
    # refused at the m.shape(...) call inside ball_drop (test_errors_at_call.py)
    with pytest.raises(clr_sim.FieldError) as e:
        ball_drop(sphere={"type": "ball", "radiuss": R})
    assert e.value.field == "shape[1].geometry.radiuss"
    assert "did you mean `radius`" in e.value.message and e.value.line is None

    with pytest.raises(clr_sim.FieldError) as e:
        ball_drop(sphere={"type": "bal", "radius": R})
    assert e.value.field == "shape[1].geometry.type" and "did you mean `ball`" in e.value.message

    # the same in model-file text: with its line
    text = BALL_DROP_TOML.replace("radius = 0.01", "radiuss = 0.01")
    with pytest.raises(clr_sim.FieldError) as e:
        clr_sim.Model.from_toml(text).check()
    assert e.value.field == "shape[1].geometry.radiuss"
    assert e.value.line == 1 + text.splitlines().index(
        'geometry = { type = "ball", radiuss = 0.01 }'
    )

    # a misspelt field of the contact element
    d = ball_drop().to_dict()
    d["clearance"][0]["max_point"] = 2
    with pytest.raises(clr_sim.FieldError) as e:
        clr_sim.Model.from_dict(d).check()
    assert e.value.field == "clearance[0].max_point" and "max_points" in e.value.message


def test_an_unknown_shape_name_names_its_path_and_the_known_shapes():
    with pytest.raises(clr_sim.FieldError) as e:
        ball_drop(shapes_pair=("floor", "spher")).check()
    assert e.value.field == "clearance[0].shapes[1]"
    assert "`spher`" in e.value.message and "floor, sphere" in e.value.message
    with pytest.raises(clr_sim.FieldError) as e:
        ball_drop(shapes_pair=("flor", "sphere")).check()
    assert e.value.field == "clearance[0].shapes[0]"


def test_invalid_geometry_values_are_refused():
    with pytest.raises(clr_sim.FieldError) as e:
        ball_drop(sphere=shapes.ball(-0.01)).check()
    assert "ball radius" in e.value.message and "-0.01" in e.value.message
    with pytest.raises(clr_sim.FieldError) as e:
        ball_drop(sphere=shapes.involute_gear(0.002, 20.5)).check()
    assert e.value.field.startswith("shape[1].geometry") and "expected u32" in e.value.message
    with pytest.raises(clr_sim.FieldError) as e:
        ball_drop(sphere={"type": "ball"}).check()
    assert e.value.field == "shape[1].geometry.radius" and "give `radius`" in e.value.message


# Each shape error at its field. The last two are still placed at `shape[1].geometry` (the
# geometry is an internally tagged table, and serde loses the path inside it): strict xfail,
# to be unmarked once the reader re-reads the geometry for its path.
_FIELD_NOT_YET = pytest.mark.xfail(strict=True, reason="the path inside a geometry is not kept")


@pytest.mark.parametrize(
    "change, path",
    [
        (lambda m: m._doc["shape"][1].update(geometry=shapes.ball(-0.01)), "shape[1].geometry"),
        (lambda m: m._doc["shape"][1].update(at=clr_sim.at("bal")), "shape[1].at.body"),
        pytest.param(
            lambda m: m._doc["shape"][1].update(
                geometry=shapes.compound([{"type": "ball", "radiuss": 0.01}])
            ),
            "shape[1].geometry.parts[0].geometry.radiuss",
            marks=_FIELD_NOT_YET,
        ),
        pytest.param(
            lambda m: m._doc["shape"][1].update(geometry=shapes.involute_gear(0.002, 20.5)),
            "shape[1].geometry.teeth",
            marks=_FIELD_NOT_YET,
        ),
    ],
    ids=["bad-radius", "unknown-body", "compound-part-field", "wrong-type"],
)
def test_shape_errors_name_the_shape_item(change, path):
    m = ball_drop()
    change(m)
    with pytest.raises(clr_sim.FieldError) as e:
        m.check()
    assert e.value.field == path, e.value.field
