"""Co-simulation FMUs (FMI 3.0) checked with FMPy (docs/fmu.md):

- `fmpy validate` passes on the FMUs of three models (the slider–crank with a gas-force input,
  the four-bar with measures, the flap with a motion input and a parameter), written by
  `clr fmu` and by `clr_sim.fmu.export`;
- FMPy's simulation of the slider–crank FMU with a constant input reproduces `clr run` of the
  same model (the input's default set to that constant) at the communication points, within the
  solver's tolerance: the FMU's difference from the run is of the order of the run's own error
  against a run at rtol 1e-11 (the clearance's impacts make a tighter comparison meaningless);
- bad input gives FMI error states with a logged message, never a crash: a NaN input, a step
  size of zero, calls out of order, an output set, a wrong instantiation token, a parameter set
  after initialization;
- the closed-loop flap example (docs/examples/flap_pi_fmu.py) runs.

The FMUs need the runtime library libclr_fmu.so next to the `clr` used (`$CLR_BIN`, else
target/release or target/debug): `.ci/run` builds it; without it these tests are skipped.
"""

from __future__ import annotations

import csv
import os
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import clr_sim

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "models" / "examples"

fmpy = pytest.importorskip("fmpy")


def _clr() -> str:
    for exe in (
        os.environ.get("CLR_BIN"),
        str(ROOT / "target" / "release" / "clr"),
        str(ROOT / "target" / "debug" / "clr"),
    ):
        if exe and Path(exe).is_file() and (Path(exe).parent / "libclr_fmu.so").is_file():
            return exe
    pytest.skip("no clr with libclr_fmu.so next to it (cargo build --release -p clr-fmu)")


def _fmu(tmp_path: Path, model: Path, *extra: str) -> Path:
    out = tmp_path / (model.stem + ".fmu")
    subprocess.run([_clr(), "fmu", str(model), "-o", str(out), *extra], check=True)
    return out


def _csv(path: Path):
    rows = list(csv.reader(open(path)))
    head = [c.split(" [")[0] for c in rows[0]]
    a = np.array([[float(x) for x in r] for r in rows[1:]])
    return {k: a[:, i] for i, k in enumerate(head)}


@pytest.mark.parametrize(
    "model, extra",
    [
        ("slider_crank_fmu.toml", ()),
        ("four_bar_measures.toml", ()),
        ("flap_fmu.toml", ("--parameter", "clearance.J4.journal_radius")),
    ],
)
def test_fmpy_validates_the_fmus(tmp_path, model, extra):
    fmu = _fmu(tmp_path, EXAMPLES / model, *extra)
    from fmpy.validation import validate_fmu

    assert validate_fmu(str(fmu)) == []
    md = fmpy.read_model_description(str(fmu))
    assert md.fmiVersion == "3.0" and md.coSimulation is not None


def test_fmi2_fmu_validates_and_steps_as_the_fmi3_one(tmp_path):
    from fmpy.validation import validate_fmu

    model = EXAMPLES / "flap_fmu.toml"
    v2 = tmp_path / "v2"
    v2.mkdir()
    f2 = _fmu(v2, model, "--fmi-version", "2")
    f3 = _fmu(tmp_path, model)
    assert validate_fmu(str(f2)) == []
    assert fmpy.read_model_description(str(f2)).fmiVersion == "2.0"
    runs = [
        fmpy.simulate_fmu(str(f), stop_time=0.05, output_interval=1e-3,
                          start_values={"actuator_position": 0.251})
        for f in (f2, f3)
    ]
    # the same runtime and instance behind both: equal numbers
    assert np.array_equal(runs[0]["flap.angle"], runs[1]["flap.angle"])
    # a NaN input is an fmi2Error with a message
    from fmpy.fmi1 import FMICallException
    from fmpy import fmi2

    md = fmpy.read_model_description(str(f2))
    s = fmi2.FMU2Slave(guid=md.guid, unzipDirectory=fmpy.extract(str(f2)),
                       modelIdentifier=md.coSimulation.modelIdentifier, instanceName="v2")
    messages = []
    callbacks = fmi2.fmi2CallbackFunctions()
    callbacks.logger = fmi2.fmi2CallbackLoggerTYPE(lambda *a: messages.append(a))
    callbacks.allocateMemory = fmi2.defaultCallbacks.allocateMemory
    callbacks.freeMemory = fmi2.defaultCallbacks.freeMemory
    s.instantiate(callbacks=callbacks, loggingOn=True)
    s.setupExperiment(startTime=0.0)
    s.enterInitializationMode()
    s.exitInitializationMode()
    vr = {v.name: v.valueReference for v in md.modelVariables}
    with pytest.raises(FMICallException) as e:
        s.setReal([vr["actuator_position"]], [float("nan")])
    assert e.value.status == 3
    assert any(b"must be finite" in m[-1] for m in messages), messages
    s.doStep(0.0, 1e-3)
    s.terminate()
    s.freeInstance()


def test_python_export_writes_the_same_fmu_as_the_command(tmp_path):
    _clr()  # skips without the library
    os.environ.setdefault("CLR_BIN", _clr())
    m = clr_sim.Model.from_file(EXAMPLES / "flap_fmu.toml")
    config = clr_sim.fmu.export(
        m, tmp_path / "flap.fmu", parameters=["clearance.J4.journal_radius"]
    )
    assert [v["name"] for v in config["inputs"]] == ["actuator_position"]
    assert [v["name"] for v in config["outputs"]] == ["flap.angle", "flap_rate.omega"]
    from fmpy.validation import validate_fmu

    assert validate_fmu(str(tmp_path / "flap.fmu")) == []
    with pytest.raises(clr_sim.ModelError, match="no output column `flap.angel`"):
        clr_sim.fmu.export(m, tmp_path / "x.fmu", outputs=["flap.angel"])
    with pytest.raises(clr_sim.ModelError, match="not written in the model file"):
        clr_sim.fmu.export(m, tmp_path / "x.fmu", parameters=["body.piston.damping"])
    with pytest.raises(FileNotFoundError, match="cargo build --release -p clr-fmu"):
        clr_sim.fmu.export(m, tmp_path / "x.fmu", library=tmp_path / "missing.so")


def test_slider_crank_fmu_with_constant_input_reproduces_clr_run(tmp_path):
    fmu = _fmu(tmp_path, EXAMPLES / "slider_crank_fmu.toml")
    # the same model with the input's default at the constant the master sets
    text = (EXAMPLES / "slider_crank_fmu.toml").read_text().replace(
        'name = "gas_force"\n', 'name = "gas_force"\ndefault = { type = "constant", value = 50.0 }\n'
    )
    model = tmp_path / "sc50.toml"
    model.write_text(text)
    exe = _clr()
    subprocess.run([exe, "run", str(model), "--out", str(tmp_path / "run")], check=True)
    subprocess.run(
        [exe, "run", str(model), "--rtol", "1e-11", "--out", str(tmp_path / "ref")], check=True
    )
    run, ref = _csv(tmp_path / "run" / "results.csv"), _csv(tmp_path / "ref" / "results.csv")
    inp = np.array([(0.0, 50.0)], dtype=[("time", np.float64), ("gas_force", np.float64)])
    r = fmpy.simulate_fmu(str(fmu), stop_time=0.1, output_interval=1e-3, input=inp)
    assert np.allclose(r["time"], run["t"], rtol=0, atol=1e-12)
    # the first 0.03 s (a crank turn and a half, the journal's first flights and impacts):
    # |FMU − run| within 3× |run − reference| (measured 1.1× for the slider position)
    n = 31
    for col in ("slider_pos.x", "slider_vel.vx"):
        fmu_err = np.max(np.abs(r[col][:n] - run[col][:n]))
        run_err = np.max(np.abs(run[col][:n] - ref[col][:n]))
        assert fmu_err <= 3.0 * run_err + 1e-12, (col, fmu_err, run_err)


def _slave(fmu: Path, log):
    from fmpy.fmi3 import FMU3Slave

    md = fmpy.read_model_description(str(fmu))
    unzipped = fmpy.extract(str(fmu))
    s = FMU3Slave(
        guid=md.guid,
        unzipDirectory=unzipped,
        modelIdentifier=md.coSimulation.modelIdentifier,
        instanceName="test",
    )
    vr = {v.name: v.valueReference for v in md.modelVariables}
    return s, vr, md


def test_bad_calls_give_fmi_errors_with_a_logged_message(tmp_path):
    from fmpy.fmi1 import FMICallException

    fmu = _fmu(tmp_path, EXAMPLES / "flap_fmu.toml", "--parameter", "clearance.J4.journal_radius")
    messages = []
    s, vr, md = _slave(fmu, messages)
    s.instantiate(loggingOn=True, logMessage=lambda *a: messages.append(a))

    def refused(call, *args, match):
        messages.clear()
        with pytest.raises(FMICallException) as e:
            call(*args)
        assert e.value.status == 3, e.value  # fmi3Error, not fatal: the instance goes on
        text = " ".join(str(m[-1]) for m in messages)
        assert match in text, text

    # out of order: a step before initialization
    refused(s.doStep, 0.0, 1e-3, match="fmi3DoStep is not allowed in the Instantiated state")
    s.enterInitializationMode(startTime=0.0)
    s.exitInitializationMode()
    # a NaN input, a zero step, a step from the wrong time, an output set, a fixed parameter
    refused(s.setFloat64, [vr["actuator_position"]], [float("nan")], match="must be finite")
    refused(s.doStep, 0.0, 0.0, match="must be positive and finite")
    refused(s.doStep, 0.5, 1e-3, match="is not the FMU's time")
    refused(s.setFloat64, [vr["flap.angle"]], [0.1], match="is an output")
    refused(
        s.setFloat64, [vr["clearance.J4.journal_radius"]], [0.01], match="set it before"
    )
    refused(s.getFloat64, [999], match="value reference 999 does not exist")
    # after all that the instance still steps, and a saved state restores
    s.doStep(0.0, 1e-3)
    state = s.getFMUState()
    a = s.getFloat64([vr["flap.angle"]])[0]
    s.doStep(1e-3, 1e-3)
    s.setFMUState(state)
    assert s.getFloat64([vr["time"]])[0] == pytest.approx(1e-3)
    assert s.getFloat64([vr["flap.angle"]])[0] == a
    blob = s.serializeFMUState(state)
    s.setFMUState(s.deserializeFMUState(blob))
    s.freeFMUState(state)
    s.terminate()
    refused(s.doStep, 1e-3, 1e-3, match="not allowed in the Terminated state")
    s.freeInstance()


def test_a_wrong_token_is_refused_at_instantiation(tmp_path):
    from fmpy.fmi3 import FMU3Slave

    fmu = _fmu(tmp_path, EXAMPLES / "four_bar_measures.toml")
    md = fmpy.read_model_description(str(fmu))
    s = FMU3Slave(
        guid="{not-this-fmu}",
        unzipDirectory=fmpy.extract(str(fmu)),
        modelIdentifier=md.coSimulation.modelIdentifier,
        instanceName="test",
    )
    messages = []
    with pytest.raises(Exception, match="Failed to instantiate"):
        s.instantiate(logMessage=lambda *a: messages.append(a))
    assert any("instantiation token" in str(m[-1]) for m in messages), messages


def test_closed_loop_flap_example_runs(tmp_path):
    os.environ.setdefault("CLR_BIN", _clr())
    sys.path.insert(0, str(ROOT / "docs" / "examples"))
    try:
        import flap_pi_fmu
    finally:
        sys.path.pop(0)
    numbers = flap_pi_fmu.main(["--out", str(tmp_path / "flap_pi_fmu")])
    assert (tmp_path / "flap_pi_fmu.png").is_file()
    ideal = numbers["ideal joints"]
    worn = numbers["0.1 mm clearance in J4"]
    # without clearance the PI loop settles on the reference (error below 1 mrad RMS after
    # 0.25 s); the clearance leaves a sustained oscillation several times larger
    assert ideal["rms_error_rad"] < 1e-3
    assert worn["rms_error_rad"] > 3 * ideal["rms_error_rad"]
