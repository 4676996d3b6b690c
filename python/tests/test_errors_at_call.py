"""Errors at the call: each `clr_sim.Model` method checks its element with the model-file reader
when it is called, and its error names the element (`clearance 'B'`), the field and the line of
this file that made the call; names not defined yet are checked when the model is used, with
the element's name and the line that added it. `None` or a wrong type for a required value is a
FieldError naming the field, in the helpers as in the methods. Result columns answer to the
names of results.csv (`r["t"]`).

References: the line numbers of this file (taken with `sys._getframe` on the line before the
call), and the header of results.csv written by the `clr` binary for the same model.
"""

import os
import pathlib
import subprocess
import sys

import numpy as np
import pytest

import clr_sim
from clr_sim import at, normal

ROOT = pathlib.Path(__file__).resolve().parents[2]
HERE = os.path.basename(__file__)


def pendulum() -> clr_sim.Model:
    m = clr_sim.Model("pendulum", gravity=(0.0, -9.81))
    m.body("rod", mass=1.0, inertia=1.0 / 12.0, position=(0.5, 0.0), angle=0.0,
           velocity=(0.0, 0.0), angular_velocity=0.0)
    m.revolute("O", a=at("ground"), b=at("rod", -0.5, 0.0))
    m.output(t_end=0.05, intervals=10)
    return m


def test_a_clearance_is_refused_at_its_call_with_its_name_field_and_line():
    m = pendulum()
    m.body("slider", mass=0.3, inertia=1e-4, position=(1.0, 0.0))
    with pytest.raises(clr_sim.FieldError) as e:
        line = sys._getframe().f_lineno + 1
        m.revolute_clearance("B", bearing=at("slider"), journal=at("rod", 0.5, 0.0), bearing_radius=0.01, journal_radius=0.0095, normal={"law": "hertz", "stiffness": 1e10})  # noqa: E501
    err = e.value
    assert err.element == "clearance 'B'"
    assert err.field == "clearance[0].normal.restitution"
    assert err.where == f"{__file__}:{line}"
    text = str(err)
    assert text.startswith(f"{__file__}:{line}: clearance 'B': field `clearance[0].normal.restitution`")
    assert "restitution" in err.message
    # the refused element is not added: the model still reads
    assert "clearance" not in m.to_dict()
    m.check()


def test_a_value_out_of_range_is_refused_at_the_call():
    m = pendulum()
    with pytest.raises(clr_sim.FieldError) as e:
        line = sys._getframe().f_lineno + 1
        m.body("crank", mass=-1.0, inertia=1e-3)
    assert e.value.element == "body 'crank'" and e.value.field == "body[1].mass"
    assert f"{HERE}:{line}: body 'crank': field `body[1].mass`: mass" in str(e.value)
    assert "positive" in e.value.message
    with pytest.raises(clr_sim.FieldError) as e:
        m.solver(method="dopri5", max_order=2)
    assert e.value.element == "[solver]" and e.value.field == "solver.max_order"


def test_none_and_wrong_types_in_methods_are_field_errors_at_the_call():
    m = pendulum()
    with pytest.raises(clr_sim.FieldError) as e:
        m.body("crank", mass=None, inertia=1e-3)
    assert e.value.field == "body[1].mass" and "missing value" in e.value.message
    with pytest.raises(clr_sim.FieldError) as e:
        m.body("crank", mass="heavy", inertia=1e-3)
    assert e.value.field == "body[1].mass"
    with pytest.raises(clr_sim.FieldError) as e:
        m.body("crank", mass=1.0, inertia=1e-3, position=(0.0, None))
    assert e.value.field == "body[1].position[1]"
    with pytest.raises(clr_sim.FieldError) as e:
        m.body("crank", mass=1.0, inertia=object())
    assert e.value.field == "body[1].inertia"
    assert [b["name"] for b in m.to_dict()["body"]] == ["rod"]


@pytest.mark.parametrize(
    "call, field",
    [
        (lambda: normal("preset", None, preset="LN"), "normal.restitution"),
        (lambda: normal("hertz", restitution=None, stiffness=1e10), "normal.restitution"),
        (lambda: normal("hertz", "0.9", stiffness=1e10), "normal.restitution"),
        (lambda: normal(None, 0.9), "normal.law"),
        (lambda: clr_sim.friction(None), "friction.law"),
        (lambda: clr_sim.motion(None, value=1.0), "motion.type"),
        (lambda: clr_sim.material(None, 0.3), "material.youngs_modulus"),
        (lambda: clr_sim.material(207e9, "0.3"), "material.poisson_ratio"),
        (lambda: at("rod", None, 0.0), "at.x"),
        (lambda: at("rod", 0.0, "1"), "at.y"),
        (lambda: at(None), "at.body"),
        (lambda: clr_sim.node("cant", 1.5), "node.node"),
        (lambda: clr_sim.node(3, 1), "node.beam"),
        (lambda: clr_sim.shapes.compound(None), "compound.parts"),
        (lambda: clr_sim.shapes.compound([None]), "compound.parts[0]"),
        (lambda: clr_sim.shapes.part(None), "part.geometry"),
    ],
)
def test_none_or_a_wrong_type_in_a_helper_is_a_field_error(call, field):
    with pytest.raises(clr_sim.FieldError) as e:
        call()
    assert e.value.field == field
    # the line of the lambda above, in this file
    assert e.value.where is not None and e.value.where.startswith(f"{__file__}:")


def test_helpers_take_numpy_scalars():
    assert normal("hertz", np.float32(0.5), stiffness=1e10)["restitution"] == 0.5
    assert at("rod", np.array(0.25), np.int64(1))["at"] == [0.25, 1.0]
    assert clr_sim.node("cant", np.int64(3))["node"] == 3


def test_a_name_defined_later_is_accepted_and_checked_when_the_model_is_used():
    m = clr_sim.Model("later", gravity=(0.0, -9.81))
    # the joint comes first, as a file may write it: accepted at the call
    m.revolute("O", a=at("ground"), b=at("rod", -0.5, 0.0))
    m.body("rod", mass=1.0, inertia=1.0 / 12.0, position=(0.5, 0.0), angle=0.0)
    m.output(t_end=0.01)
    m.check()

    m.revolute("P", a=at("rod", 0.5, 0.0), b=at("tip"))  # `tip` never defined
    with pytest.raises(clr_sim.FieldError) as e:
        line = sys._getframe().f_lineno + 1
        m.check()
    err = e.value
    assert err.element == "joint 'P'" and err.field.startswith("joint[1].b")
    assert err.added_at == f"{__file__}:{line - 3}"
    assert str(err).startswith(f"clr_sim.Model 'later': joint 'P' (added at {__file__}:{line - 3}):")
    assert "`tip`" in err.message
    with pytest.raises(clr_sim.FieldError) as e:
        clr_sim.simulate(m)
    assert e.value.element == "joint 'P'"


def test_an_error_found_by_the_run_names_the_element():
    m = clr_sim.Model("free")
    m.body("rod", mass=1.0, inertia=0.1, position=(0.0, 0.0), angle=0.0)  # no velocity given
    line = sys._getframe().f_lineno - 1
    m.output(t_end=0.01)
    with pytest.raises(clr_sim.FieldError) as e:
        clr_sim.simulate(m)
    assert e.value.element == "body 'rod'" and e.value.field == "body[0].velocity"
    assert e.value.added_at == f"{__file__}:{line}"


def test_own_fields_are_checked_at_the_call_while_a_name_is_still_missing():
    m = clr_sim.Model("later")
    m.revolute("O", a=at("ground"), b=at("rod", -0.5, 0.0))  # `rod` not yet defined
    with pytest.raises(clr_sim.FieldError) as e:
        m.translational("A", a=at("rod"), b=at("ground"), axis="x")
    assert e.value.element == "joint 'A'" and e.value.field == "joint[1].axis"
    with pytest.raises(clr_sim.FieldError) as e:
        m.body("crank", mass=-1.0, inertia=1e-3)
    assert e.value.element == "body 'crank'" and e.value.field == "body[0].mass"
    with pytest.raises(clr_sim.FieldError) as e:
        m.body("O", mass=1.0, inertia=1e-3)  # the joint's name
    assert e.value.element == "body 'O'" and "duplicate name" in e.value.message
    m.body("rod", mass=1.0, inertia=1e-3)
    # with `rod` defined, a joint from `rod` to itself is refused at the call
    with pytest.raises(clr_sim.FieldError) as e:
        m.revolute("self", a=at("rod"), b=at("rod", 0.1, 0.0))
    assert e.value.element == "joint 'self'" and "itself" in e.value.message
    assert e.value.field.startswith("joint[1]")


def test_an_earlier_element_waiting_for_a_name_does_not_hide_the_checks_of_later_ones():
    """The reader stops at the first error; an earlier element that names something not yet
    defined is left out of the checked copy, so a later element's compiled checks still run at
    its call, placed at its own index."""
    m = clr_sim.Model("waiting")
    m.body("rod", mass=1.0, inertia=1e-3)
    m.body("slider", mass=0.3, inertia=1e-4)
    m.revolute("P", a=at("rod", 0.5, 0.0), b=at("tip"))  # `tip` not yet defined: joint[0]
    with pytest.raises(clr_sim.FieldError) as e:
        m.revolute("self", a=at("rod"), b=at("rod", 0.1, 0.0))  # joint[1]
    assert e.value.element == "joint 'self'" and e.value.field.startswith("joint[1]")
    assert "itself" in e.value.message
    with pytest.raises(clr_sim.FieldError) as e:
        m.revolute_clearance("B", bearing=at("slider"), journal=at("rod", 0.5, 0.0), bearing_radius=0.01, journal_radius=0.011, normal=normal("hertz", 0.9, stiffness=1e10))  # noqa: E501
    assert e.value.element == "clearance 'B'" and e.value.field == "clearance[0].journal_radius"
    # an element naming the waiting one is itself left to the run
    m.point("tip_point", body="tip", at=(0.0, 0.0))
    m.body("tip", mass=0.1, inertia=1e-5)
    m.output(t_end=0.01)
    assert [j["name"] for j in m.to_dict()["joint"]] == ["P"]
    assert "clearance" not in m.to_dict()


def test_result_columns_answer_to_the_names_of_results_csv():
    r = clr_sim.simulate(pendulum())
    assert r["t"] is r.time and "t" in r and r["t [s]"] is r.time
    assert r["rod.x [m]"] is r["rod.x"]
    assert r.csv_names()[0] == "t" and r.csv_names()[1:] == r.column_names()[1:]
    with pytest.raises(KeyError) as e:
        r["rod.xx"]
    assert "did you mean 'rod.x'" in str(e.value)
    with pytest.raises(KeyError) as e:
        r["rod.x [rad]"]  # the unit of the header must be the column's
    assert "did you mean" in str(e.value)
    with pytest.raises(KeyError) as e:
        r["zzzz"]
    assert "column_names()" in str(e.value)


def _clr_binary():
    exe = os.environ.get("CLR_BIN") or str(ROOT / "target" / "debug" / "clr")
    return exe if os.path.isfile(exe) else None


@pytest.mark.skipif(_clr_binary() is None, reason="no clr binary (cargo test builds target/debug/clr)")
def test_every_results_csv_header_indexes_the_result(tmp_path):
    model = tmp_path / "pendulum.toml"
    model.write_text(pendulum().to_toml())
    subprocess.run(
        [_clr_binary(), "run", str(model), "--out", str(tmp_path / "out"), "--quiet",
         "--no-figures"],
        check=True,
    )
    header = (tmp_path / "out" / "results.csv").read_text().splitlines()[0].split(",")
    r = clr_sim.simulate(model)
    assert [h.rsplit(" [", 1)[0] for h in header] == r.csv_names()
    for h in header:
        name = h.rsplit(" [", 1)[0]
        assert np.array_equal(r[h], r[name])



def _generic_model_files():
    """The generic model files of tests/data and models/ (not the built-in forms)."""
    files = sorted((ROOT / "tests" / "data").glob("*.toml")) + sorted(
        (ROOT / "models").rglob("*.toml")
    )
    return [f for f in files if "builtin" not in f.read_text()]


_ITEMS = ("body", "point", "beam", "flexible_body", "input", "joint", "driver", "force",
          "shape", "clearance", "measure", "metric")
_TAGGED = ("joint", "driver", "force", "clearance", "measure")


@pytest.mark.parametrize("path", _generic_model_files(), ids=lambda p: p.name)
def test_every_model_file_rebuilt_call_by_call_is_accepted_and_the_same(path):
    """Each model file's checked form, rebuilt item by item through the Model methods (each
    call checked on its own), is accepted at every call and gives the same checked text:
    the check at the call refuses nothing a file accepts, in the file's order or reversed.
    A spatial file (`[model] space = "spatial"`) is rebuilt by the SpatialModel that
    `Model(space="spatial")` makes, through its own methods (`m.METHODS`)."""
    reference = clr_sim.Model.from_file(path)
    text = reference.to_toml()
    try:
        import tomllib
    except ImportError:  # Python < 3.11
        tomllib = pytest.importorskip("tomli")
    doc = tomllib.loads(text)
    for order in (1, -1):
        m = clr_sim.Model(**doc.get("model", {}))
        sections = _ITEMS if order == 1 else tuple(reversed(_ITEMS))
        for section in sections:
            for item in doc.get(section, [])[::order]:
                item = dict(item)
                kind = item.pop("type") if section in _TAGGED else None
                getattr(m, m.METHODS[(section, kind)])(**item)
        for table in ("twin", "solver", "output"):
            if table in doc:
                getattr(m, table)(**doc[table])
        if order == 1:
            assert m.to_toml() == text
        else:
            m.check()  # the same items in another order still read
