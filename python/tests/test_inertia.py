"""`clr_sim.inertia`: mass properties of parts from their dimensions and material.

References:
- the closed forms of Meriam & Kraige, *Engineering Mechanics: Dynamics*, Table D/4 (bar
  m = ρLwt, I = m(L² + w²)/12; rod I = m(3r² + L²)/12; disc I = m r²/2), evaluated here
  independently; equal to rounding (1e-14 relative, a different order of the products);
- the model-file reader: a pendulum whose rod is a `shape` with `material` and `between` in a
  file, and the same pendulum built in Python from `clr_sim.inertia.rod(...)`, are the same
  description and give the same numbers bit for bit (one definition, in Rust).
"""

import math

import pytest

import clr_sim
from clr_sim import inertia

STEEL = 7850.0  # kg/m³, EN 1993-1-1 §3.2.6


def close(a, b, rel=1e-14):
    return abs(a - b) <= rel * abs(b)


def test_closed_forms():
    b = inertia.bar(0.35, 0.02, 0.01, material="steel")
    m = STEEL * 0.35 * 0.02 * 0.01
    assert close(b.mass, m) and close(b.inertia, m * (0.35**2 + 0.02**2) / 12.0)
    assert b["centre_of_mass"] == [0.0, 0.0] and b.length == 0.35
    r = inertia.rod(0.3, 0.04, density=2700.0)
    m = 2700.0 * math.pi * 0.02**2 * 0.3
    assert close(r.mass, m) and close(r.inertia, m * (3 * 0.02**2 + 0.3**2) / 12.0)
    d = inertia.disc(0.1, 0.01, material="aluminium")
    m = 2700.0 * math.pi * 0.05**2 * 0.01
    assert close(d.mass, m) and close(d.inertia, 0.5 * m * 0.05**2)
    t = inertia.tube(0.25, 0.03, 0.02, material="steel")
    outer, bore = inertia.rod(0.25, 0.03, density=STEEL), inertia.rod(0.25, 0.02, density=STEEL)
    assert close(t.inertia, outer.inertia - bore.inertia, 1e-13)
    assert inertia.plate(0.2, 0.1, 0.005, material="steel") == inertia.bar(
        0.2, 0.1, 0.005, material="steel"
    )
    bx = inertia.box((0.2, 0.1, 0.005), material="steel")
    assert close(bx.inertia, inertia.bar(0.2, 0.1, 0.005, material="steel").inertia)
    assert inertia.MATERIALS["steel"] == STEEL


def test_between_places_the_link_at_the_midpoint():
    p = inertia.bar(width=0.02, thickness=0.01, material="steel", between=((0.0, 0.0), (0.0, 0.1)))
    assert p.position == [0.0, 0.05] and p.angle == math.pi / 2 and p.length == 0.1
    assert set(p) == {"mass", "inertia", "centre_of_mass", "position", "angle"}


def test_refusals_name_the_argument():
    with pytest.raises(clr_sim.FieldError) as e:
        inertia.bar(0.1, 0.02, 0.01, material="stel")
    assert e.value.field == "material" and "did you mean `steel`" in str(e.value)
    with pytest.raises(clr_sim.FieldError) as e:
        inertia.bar(0.1, -0.02, 0.01, material="steel")
    assert e.value.field == "width"
    with pytest.raises(clr_sim.FieldError) as e:
        inertia.bar(0.1, 0.02, 0.01, material="steel", density=7800.0)
    assert e.value.field == "density"
    with pytest.raises(clr_sim.FieldError) as e:
        inertia.rod(0.2, 0.02, material="steel", between=((0.0, 0.0), (0.1, 0.0)))
    assert e.value.field == "length"
    with pytest.raises(clr_sim.FieldError) as e:
        inertia.tube(0.2, 0.02, 0.03, material="steel")
    assert e.value.field == "inner_diameter"


PENDULUM = """
[model]
name = "pendulum"
gravity = [0.0, -9.81]

[[body]]
name = "rod"
shape = {{ rod = {{ diameter = 0.02 }} }}
material = "steel"
between = [[0.0, 0.0], [{x}, {y}]]
velocity = [0.0, 0.0]
angular_velocity = 0.0

[[joint]]
name = "pin"
type = "revolute"
a = {{ body = "ground", at = [0.0, 0.0] }}
b = {{ body = "rod", at = [-0.25, 0.0] }}

[output]
t_end = 0.5
intervals = 50
"""


def test_a_part_in_python_runs_as_the_same_shape_in_a_file():
    end = (0.5 * math.sin(0.5), -0.5 * math.cos(0.5))
    from_file = clr_sim.simulate(clr_sim.Model.from_toml(PENDULUM.format(x=end[0], y=end[1])))
    m = clr_sim.Model("pendulum", gravity=(0.0, -9.81))
    rod = inertia.rod(diameter=0.02, material="steel", between=((0.0, 0.0), end))
    m.body("rod", **rod, velocity=(0.0, 0.0), angular_velocity=0.0)
    m.revolute("pin", a=clr_sim.at("ground", 0.0, 0.0), b=clr_sim.at("rod", -0.25, 0.0))
    m.output(t_end=0.5, intervals=50)
    built = clr_sim.simulate(m)
    assert list(built.columns) == list(from_file.columns)
    for c in from_file.columns:
        assert list(built[c]) == list(from_file[c]), c
    assert any("body `rod`: rod, length" in n for n in from_file.notes)
