"""The `clr_sim` package: models built in Python, from dicts and from TOML; simulate and sweep;
typed errors with their field paths.

References (independent formulations, docs/verification.md):
- the model file `tests/data/slider_crank.toml`, read by the Rust model-file reader: a model
  built in Python must give the same numbers bit for bit (same description, same code);
- `clr sweep` (the command-line binary, an independent process writing sweep.csv in shortest
  round-trip form): `clr_sim.sweep` must give the same metrics bit for bit;
- the Rust model-file reader's own list of fields per element kind: every `clr_sim.Model` method
  must take exactly those fields.
"""

import inspect
import math
import os
import pathlib
import subprocess

import numpy as np
import pytest

import clr_sim
from clr_sim.model import _LISTS, _TABLES, METHODS

ROOT = pathlib.Path(__file__).resolve().parents[2]
SLIDER_CRANK = ROOT / "tests" / "data" / "slider_crank.toml"
OMEGA = 5000.0 * 2.0 * math.pi / 60.0  # rad/s, crank speed


def slider_crank_in_python() -> clr_sim.Model:
    """tests/data/slider_crank.toml, written with the builder."""
    steel = clr_sim.material(207e9, 0.3)
    m = clr_sim.Model(
        "slider_crank",
        description="slider-crank with a revolute clearance joint between rod and slider",
        gravity=(0.0, -9.81),
    )
    m.body("crank", mass=0.343, inertia=0.000216, position=(0.025, 0.0), angle=0.0,
           velocity=(0.0, 13.089969389957473), angular_velocity=523.5987755982989)
    m.body("rod", mass=1.072, inertia=0.034, position=(0.2, 0.0), angle=0.0,
           velocity=(0.0, 13.089969389957473), angular_velocity=-87.26646259971649)
    m.body("slider", mass=0.347, inertia=0.000115, position=(0.35, 0.0))
    m.revolute("O", a=clr_sim.at("ground"), b=clr_sim.at("crank", -0.025, 0.0))
    m.revolute("A", a=clr_sim.at("crank", 0.025, 0.0), b=clr_sim.at("rod", -0.15, 0.0))
    m.translational("guide", a=clr_sim.at("ground"), b=clr_sim.at("slider"), axis=(1.0, 0.0))
    m.drive_angle("motor", body="crank",
                  motion=clr_sim.motion("linear", initial=0.0, rate=523.5987755982989))
    m.revolute_clearance(
        "B", bearing=clr_sim.at("slider"), journal=clr_sim.at("rod", 0.15, 0.0),
        bearing_radius=0.01, journal_radius=0.0095,
        normal=clr_sim.normal("preset", 0.9, preset="LN", bearing_material=steel,
                          journal_material=steel),
        friction=clr_sim.friction("none"),
    )
    m.solver(method="dopri5", rtol=1e-7, atol=1e-10)
    m.output(t_end=0.1, intervals=0, every_step=True)
    return m


def assert_same_run(a: clr_sim.Result, b: clr_sim.Result):
    assert a.column_names() == b.column_names()
    for name in a.column_names():
        assert np.array_equal(a[name], b[name]), name
    assert a.metrics == b.metrics
    assert a.impacts == b.impacts


def test_a_slider_crank_built_in_python_equals_its_model_file_bit_for_bit():
    py = clr_sim.simulate(slider_crank_in_python(), t_end=0.01)
    toml = clr_sim.simulate(SLIDER_CRANK, t_end=0.01)
    assert len(py) > 100 and py.ok
    assert_same_run(py, toml)
    assert py.units["B.normal_force"] == "N" and py.units["time"] == "s"


def test_to_toml_from_toml_and_from_dict_give_the_same_model():
    m = slider_crank_in_python()
    text = m.to_toml()
    assert "[[clearance]]" in text and 'law = "preset"' in text
    again = clr_sim.Model.from_toml(text)
    from_dict = clr_sim.Model.from_dict(m.to_dict())
    from_file = clr_sim.Model.from_file(SLIDER_CRANK)
    runs = [clr_sim.simulate(x, t_end=0.004) for x in (m, again, from_dict, from_file)]
    for r in runs[1:]:
        assert_same_run(runs[0], r)
    # the checked text of the file is the text of the Python model
    assert from_file.to_toml() == text


def test_every_element_kind_has_a_builder_method_with_the_fields_of_the_file():
    """The Rust reader lists its sections and each kind's fields; each method takes exactly
    those (a section without `type` is one kind, None)."""
    kinds = set()
    sections = []
    for section, names in clr_sim._native.element_kinds():
        if "." in section:  # a tagged table inside items (shape.geometry): test_shapes.py
            continue
        sections.append(section)
        kinds |= {(section, k) for k in names} if names else {(section, None)}
    assert kinds == set(METHODS), kinds ^ set(METHODS)
    # the builder knows every section, in the order `clr export` writes the lists
    assert set(sections) == set(_LISTS) | set(_TABLES), set(sections) ^ (set(_LISTS) | set(_TABLES))
    assert [s for s in sections if s in _LISTS] == list(_LISTS)
    for (section, kind), method in METHODS.items():
        params = set(inspect.signature(getattr(clr_sim.Model, method)).parameters) - {"self"}
        fields = set(clr_sim._native.kind_fields(section, kind))
        assert params == fields, (section, kind, params ^ fields)


def test_builtin_models_and_files_run_by_name():
    r = clr_sim.simulate("slider_crank", 0.002, set={"restitution": 0.5})
    assert r.parameters["restitution"] == 0.5 and r.source == "builtin"
    assert "slider_crank" in dict(clr_sim.list_models())
    assert any(s[1] == "flap" for s in clr_sim.list_studies())
    with pytest.raises(clr_sim.UnknownModelError) as e:
        clr_sim.run_study("no_such_study", "/tmp/none")
    assert e.value.field == "model"


def test_every_error_type_carries_its_field_path():
    m = slider_crank_in_python()
    with pytest.raises(clr_sim.FieldError) as e:
        m.body("bad", mass=-1.0, inertia=1.0)  # refused at the call (test_errors_at_call.py)
    assert e.value.field == "body[3].mass" and "positive" in str(e.value)
    assert e.value.line is None  # no line numbers of a generated text
    assert e.value.element == "body 'bad'" and e.value.where.startswith(__file__)

    m = clr_sim.Model.from_dict({"body": [{"name": "rod", "mas": 1.0, "inertia": 1.0}]})
    with pytest.raises(clr_sim.FieldError) as e:
        m.check()
    assert e.value.field == "body[0].mas" and "did you mean `mass`" in e.value.message

    bad_text = SLIDER_CRANK.read_text().replace("mass = 1.072", "mass = -1.072")
    with pytest.raises(clr_sim.FieldError) as e:
        clr_sim.Model.from_toml(bad_text).check()
    line = bad_text.splitlines().index("mass = -1.072") + 1
    assert e.value.field == "body[1].mass" and e.value.line == line
    assert str(e.value).startswith(f"<toml text>:{line}:")

    with pytest.raises(clr_sim.OverrideError) as e:
        clr_sim.simulate(SLIDER_CRANK, set={"body.rdo.mass": 2.0})
    assert e.value.field == "body.rdo.mass" and "rod" in e.value.message

    with pytest.raises(clr_sim.UnknownModelError) as e:
        clr_sim.simulate("slider_crnk")
    assert e.value.field == "model" and "slider_crank" in e.value.message

    with pytest.raises(clr_sim.ModelError) as e:
        clr_sim.simulate("slider_crank", t_end=-1.0)
    assert e.value.field == "t_end"

    with pytest.raises(clr_sim.ContactError) as e:
        clr_sim.NormalLaw("power", [-1.0, 1.5], "none", 1.0)
    assert e.value.field == "parameters"
    with pytest.raises(clr_sim.ContactError) as e:
        clr_sim.NormalLaw("power", [1e9, 1.5], "none", 1.0).force([1e-5, float("nan")], 0.0, 1.0)
    assert e.value.field == "delta[1]"

    m = slider_crank_in_python()
    m.solver(max_steps=20)
    with pytest.raises(clr_sim.SimulationError) as e:
        clr_sim.simulate(m, t_end=0.01)
    assert e.value.field == "solver" and "max_steps" in e.value.message
    partial = e.value.result
    assert isinstance(partial, clr_sim.Result) and 0 < partial.time[-1] < 0.01
    # every error is a ClrError; input errors are ValueErrors
    for cls in (clr_sim.FieldError, clr_sim.OverrideError, clr_sim.UnknownModelError, clr_sim.ContactError):
        assert issubclass(cls, clr_sim.ClrError) and issubclass(cls, ValueError)


def test_a_failed_run_can_be_returned_instead_of_raised():
    m = slider_crank_in_python().solver(max_steps=20)
    r = clr_sim.simulate(m, t_end=0.01, check=False)
    assert not r.ok and "max_steps" in r.error


def _clr_binary():
    exe = os.environ.get("CLR_BIN") or str(ROOT / "target" / "debug" / "clr")
    return exe if os.path.isfile(exe) else None


def _read_sweep_csv(path):
    lines = path.read_text().splitlines()
    names = [h.rsplit(" [", 1)[0] for h in lines[0].split(",")]
    return names, [line.split(",") for line in lines[1:] if line]


@pytest.mark.skipif(_clr_binary() is None, reason="no clr binary (cargo test builds target/debug/clr)")
def test_a_sweep_from_python_equals_clr_sweep(tmp_path):
    radii = [0.0095, 0.0098]
    rtols = [1e-6, 1e-7]
    subprocess.run(
        [_clr_binary(), "sweep", str(SLIDER_CRANK), "--t-end", "0.005",
         "--vary", "clearance.B.journal_radius=" + ",".join(map(str, radii)),
         "--vary", "solver.rtol=" + ",".join(map(str, rtols)),
         "--out", str(tmp_path), "--quiet", "--no-figures", "--jobs", "2"],
        check=True,
    )
    names, rows = _read_sweep_csv(tmp_path / "sweep.csv")
    s = clr_sim.sweep(clr_sim.Model.from_file(SLIDER_CRANK),
                  {"clearance.B.journal_radius": radii, "solver.rtol": rtols},
                  t_end=0.005, jobs=2, progress=False)
    assert len(s) == len(rows) == 4 and not s.failed
    table = s.table()
    metrics = [n for n in names if n not in ("point", "folder", "clearance.B.journal_radius",
                                             "solver.rtol", "status", "wall_s")]
    assert metrics and set(metrics) == set(s.metric_names())
    for i, row in enumerate(rows):
        k, values, result = s[i]
        assert int(row[0]) == k == i
        assert [float(row[2]), float(row[3])] == values
        for m in metrics:
            assert float(row[names.index(m)]) == result.metrics[m], (k, m)
            assert table[m][i] == result.metrics[m]


def test_sweep_threads_do_not_change_numbers_and_progress_is_shown(capsys):
    model = slider_crank_in_python()
    vary = {"clearance.B.normal.restitution": [0.5, 0.9]}
    one = clr_sim.sweep(model, vary, t_end=0.002, jobs=1, progress=True)
    two = clr_sim.sweep(model, vary, t_end=0.002, jobs=2, progress=False)
    for (_, _, a), (_, _, b) in zip(one, two):
        assert_same_run(a, b)
    err = capsys.readouterr().err
    assert "2/2 points" in err  # stderr is not a terminal under pytest: plain lines
    with pytest.raises(clr_sim.OverrideError) as e:
        clr_sim.sweep(model, {"clearance.B.journal_radius": 0.0095})
    assert e.value.field == "clearance.B.journal_radius"
    with pytest.raises(clr_sim.OverrideError) as e:
        clr_sim.sweep(model, {"body.rdo.mass": [1.0]})
    assert e.value.field == "body.rdo.mass"


def test_results_convert_to_pandas():
    pd = pytest.importorskip("pandas")
    r = clr_sim.simulate(SLIDER_CRANK, t_end=0.004)
    df = r.to_pandas()
    assert isinstance(df, pd.DataFrame) and df.index.name == "time"
    assert np.array_equal(df["B.normal_force"].to_numpy(), r["B.normal_force"])
    assert df.attrs["units"]["B.normal_force"] == "N"
    s = clr_sim.sweep(SLIDER_CRANK, {"solver.rtol": [1e-6, 1e-7]}, t_end=0.002, progress=False)
    sdf = s.to_pandas()
    assert list(sdf["status"]) == ["ok", "ok"] and "solver.rtol" in sdf


def test_the_type_stubs_list_exactly_what_the_extension_has():
    """_native.pyi declares every public name of the extension (and nothing else), with the
    same methods per class, so editors complete what exists."""
    import ast

    stub = ast.parse((pathlib.Path(clr_sim.__file__).parent / "_native.pyi").read_text())
    declared = {}
    for node in stub.body:
        if isinstance(node, ast.ClassDef):
            declared[node.name] = {n.name for n in node.body if isinstance(n, ast.FunctionDef)}
        elif isinstance(node, ast.FunctionDef):
            declared[node.name] = None
    public = {n for n in dir(clr_sim._native) if not n.startswith("_")}
    assert set(declared) == public, set(declared) ^ public
    for name, methods in declared.items():
        if methods is not None:
            have = {m for m in dir(getattr(clr_sim._native, name)) if not m.startswith("_")}
            assert methods - {"__init__"} == have, (name, methods ^ have)


def test_clr_sim_installs_beside_pythonnet():
    """`import clr` is pythonnet's: with pythonnet installed, `clr` resolves to its module (not
    to anything of this package) and `import clr_sim` works beside it. pythonnet's `clr` itself
    is not imported (that needs a .NET runtime)."""
    import importlib.util

    if importlib.util.find_spec("pythonnet") is None:
        pytest.skip("pythonnet is not installed (pip install pythonnet to run this check)")
    spec = importlib.util.find_spec("clr")
    assert spec is not None and spec.origin is not None, "pythonnet installed but no `clr`"
    ours = pathlib.Path(clr_sim.__file__).resolve().parent
    theirs = pathlib.Path(spec.origin).resolve()
    assert ours not in theirs.parents, (theirs, ours)
    pythonnet = pathlib.Path(importlib.util.find_spec("pythonnet").origin).resolve().parent
    assert theirs.parent == pythonnet.parent, (theirs, pythonnet)  # both in one site-packages
    import clr_sim as again

    assert again.Model is clr_sim.Model and callable(again.simulate)


def test_the_installed_package_has_no_top_level_clr():
    """The files of the installed distribution `clr-sim` (its RECORD, the wheel's file list)
    hold the packages clr_sim and clr_contact and no top-level `clr`."""
    import importlib.metadata as md

    files = md.files("clr-sim")
    assert files, "clr-sim is not installed with a file list (RECORD)"
    tops = {f.parts[0] for f in files}
    assert not any(t == "clr" or t.startswith("clr.") for t in tops), sorted(tops)
    if not any(t.endswith(".pth") for t in tops):  # not an editable install
        assert {"clr_sim", "clr_contact"} <= tops, sorted(tops)
