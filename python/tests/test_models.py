"""Whole clr models from Python (run_model, list_models) against closed forms and the CLI.

References:
- slider-crank kinematics: with crank angle θ, crank r and rod l, the ideal slider position is
  x_ideal(θ) = r cos θ + √(l² − r² sin² θ) (e.g. Shigley & Uicker, Theory of Machines, §4).
  With a journal offset e = journal − bearing in the clearance joint, the slider sits at
  x = r cos θ + √(l² − (r sin θ − e_y)²) − e_x, so |x − x_ideal| ≤ |e| (1 + r/√(l² − r²)) to first
  order in |e|, and |e| = c + δ with radial clearance c and penetration δ (δ < 0: free flight).
- compound pendulum: small-amplitude period T₀ = 2π √(I_O / (m g d)) (Thornton & Marion,
  Classical Dynamics, §4.4); the amplitude correction is T/T₀ − 1 ≈ θ₀²/16.
"""

import math
import os
import pathlib
import subprocess

import numpy as np
import pytest

import clr_contact as cc

ROOT = pathlib.Path(__file__).resolve().parents[2]

# the built-in slider_crank (crates/clr-models: SliderCrankParams::flores)
R_CRANK, L_ROD, OMEGA = 0.05, 0.3, 5000.0 * 2.0 * math.pi / 60.0
CLEARANCE = 0.01 - 0.0095  # m, bearing minus journal radius
JOURNAL_ON_ROD = 0.15  # m, journal centre from the rod's centre of mass


def test_list_models_names_every_builtin():
    pairs = cc.list_models()
    models = dict(pairs)
    assert len(models) == len(pairs) and all(models.values())
    assert {"slider_crank", "wan_slider_crank", "flap", "manipulator"} <= set(models)
    assert "5000 rpm" in models["slider_crank"]


def test_slider_crank_follows_the_ideal_kinematics_within_the_clearance():
    r = cc.run_model("slider_crank", t_end=0.02)
    t, th = r["time"], r["crank.theta"]
    assert t[0] == 0.0 and t[-1] == pytest.approx(0.02, abs=1e-15)
    assert r["units"]["time"] == "s" and r["units"]["slider.x"] == "m"
    assert r["parameters"]["crank_speed_rpm"] == 5000.0
    # the motor drives θ = ω t (a constraint, satisfied to the integrator's projection)
    assert np.max(np.abs(th - OMEGA * t)) < 1e-9
    # eccentricity of the clearance joint from the rigid-body columns (journal 0.15 m along
    # the rod from its centre, bearing at the slider's origin) equals the recorded one, and
    # the recorded penetration is |e| − c
    ex = r["rod.x"] + JOURNAL_ON_ROD * np.cos(r["rod.theta"]) - r["slider.x"]
    ey = r["rod.y"] + JOURNAL_ON_ROD * np.sin(r["rod.theta"]) - r["slider.y"]
    np.testing.assert_allclose(ex, r["B.ex"], rtol=0, atol=1e-12)
    np.testing.assert_allclose(ey, r["B.ey"], rtol=0, atol=1e-12)
    np.testing.assert_allclose(np.hypot(ex, ey) - CLEARANCE, r["B.penetration"], rtol=0, atol=1e-12)
    # the slider stays within the clearance bound of the ideal slider-crank
    x_ideal = R_CRANK * np.cos(th) + np.sqrt(L_ROD**2 - (R_CRANK * np.sin(th)) ** 2)
    dev = np.abs(r["slider.x"] - x_ideal)
    e_max = CLEARANCE + max(r["B.penetration"].max(), 0.0)
    bound = e_max * (1.0 + R_CRANK / math.sqrt(L_ROD**2 - R_CRANK**2)) * 1.01
    assert dev.max() <= bound, f"deviation {dev.max()} m > bound {bound} m"
    # and leaves the ideal path (the clearance is actually used: free flight after release)
    assert dev.max() > 0.5 * CLEARANCE
    # while the journal flies freely (δ < 0) it is inside the bearing: |x − x_ideal| ≤ 1.2 c
    free = r["B.penetration"] < 0
    assert free.any() and dev[free].max() <= 1.2 * CLEARANCE
    # the model's own slider.error column is the same deviation, taken from the ideal-joint twin
    # (a run at clearance 0, 2000 rows per revolution, interpolated linearly): within 2e-7 m of
    # the closed form (the interpolation error of 2000 rows per revolution is ~7e-8 m; measured
    # 8.1e-8 m on the default run)
    np.testing.assert_allclose(r["slider.error"], r["slider.x"] - x_ideal, rtol=0, atol=2e-7)


def _clr_binary():
    exe = os.environ.get("CLR_BIN") or str(ROOT / "target" / "debug" / "clr")
    return exe if os.path.isfile(exe) else None


def _read_csv(path):
    lines = path.read_text().splitlines()
    names = [h.rsplit(" [", 1)[0] for h in lines[0].split(",")]
    rows = np.array([[float(v) for v in line.split(",")] for line in lines[1:] if line])
    return names, rows


@pytest.mark.skipif(_clr_binary() is None, reason="no clr binary (cargo test builds target/debug/clr)")
def test_slider_crank_equals_clr_run_bit_for_bit(tmp_path):
    """An independent path: the CLI binary writes results.csv in shortest round-trip form."""
    subprocess.run(
        [_clr_binary(), "run", "slider_crank", "--t-end", "0.004", "--set", "restitution=0.5",
         "--out", str(tmp_path), "--quiet", "--no-figures"],
        check=True,
    )
    names, rows = _read_csv(tmp_path / "results.csv")
    r = cc.run_model("slider_crank", set={"restitution": 0.5}, t_end=0.004)
    assert r["parameters"]["restitution"] == 0.5
    assert rows.shape == (len(r["time"]), len(names))
    for k, n in enumerate(names):
        key = "time" if n == "t" else n
        assert np.array_equal(rows[:, k], r[key]), n


PENDULUM = """
[model]
name = "pendulum"
gravity = [0.0, -9.81]

[[body]]
name = "rod"
mass = {m}
inertia = {ic}
position = [{x}, {y}]
angle = {angle}
velocity = [0.0, 0.0]
angular_velocity = 0.0

[[joint]]
name = "pin"
type = "revolute"
a = {{ body = "ground", at = [0.0, 0.0] }}
b = {{ body = "rod", at = [{minus_d}, 0.0] }}

[solver]
method = "ndf"
rtol = 1e-10
atol = 1e-12

[output]
t_end = 3.0
intervals = 3000
"""


def _pendulum(tmp_path, m=2.0, length=0.6, theta0=0.02):
    d = length / 2.0
    text = PENDULUM.format(
        m=m,
        ic=m * length**2 / 12.0,
        x=d * math.sin(theta0),
        y=-d * math.cos(theta0),
        angle=-math.pi / 2.0 + theta0,
        minus_d=-d,
    )
    path = tmp_path / "pendulum.toml"
    path.write_text(text)
    return path


def _period(t, phi):
    """Mean period from successive upward zero crossings of φ (linear interpolation)."""
    k = np.nonzero((phi[:-1] < 0) & (phi[1:] >= 0))[0]
    tc = t[k] - phi[k] * (t[k + 1] - t[k]) / (phi[k + 1] - phi[k])
    assert len(tc) >= 2, tc
    return (tc[-1] - tc[0]) / (len(tc) - 1)


def test_pendulum_file_small_amplitude_period(tmp_path):
    m, length, theta0, g = 2.0, 0.6, 0.02, 9.81
    r = cc.run_model(_pendulum(tmp_path, m, length, theta0))
    assert r["source"].endswith("pendulum.toml")
    d = length / 2.0
    period0 = 2.0 * math.pi * math.sqrt((m * length**2 / 3.0) / (m * g * d))
    # θ₀ = 0.02 rad: amplitude correction θ₀²/16 = 2.5e-5; tolerance 1e-4 relative
    period = _period(r["time"], r["rod.theta"] + math.pi / 2.0)
    assert abs(period / period0 - 1.0) < 1e-4, (period, period0)


def test_pendulum_set_overrides_the_file(tmp_path):
    """set {"body.rod.inertia": I_c} changes I_O = I_c + m d² and the period with it."""
    m, length, g, ic = 2.0, 0.6, 9.81, 0.2
    d = length / 2.0
    r = cc.run_model(_pendulum(tmp_path, m, length), set={"body.rod.inertia": ic}, t_end=4.0)
    assert r["time"][-1] == pytest.approx(4.0, abs=1e-12)
    period0 = 2.0 * math.pi * math.sqrt((ic + m * d * d) / (m * g * d))
    period = _period(r["time"], r["rod.theta"] + math.pi / 2.0)
    assert abs(period / period0 - 1.0) < 1e-4, (period, period0)


def test_unknown_model_lists_the_valid_names():
    with pytest.raises(cc.ModelError) as e:
        cc.run_model("no_such_model")
    for name, _ in cc.list_models():
        assert f"{name}," in str(e.value) or f"{name} (" in str(e.value), name


def test_malformed_file_names_file_line_and_field(tmp_path):
    path = _pendulum(tmp_path)
    path.write_text(path.read_text().replace("mass = 2.0", "mass = -2.0"))
    with pytest.raises(cc.ModelError) as e:
        cc.run_model(path)
    msg = str(e.value)
    line = 1 + path.read_text().splitlines().index("mass = -2.0")
    assert msg.startswith(f"{path}:{line}:"), msg
    assert "mass" in msg


def test_bad_overrides_and_settings_raise():
    with pytest.raises(cc.ModelError, match="restitution"):
        cc.run_model("slider_crank", set={"restitutio": 0.5})
    with pytest.raises(cc.ModelError, match="must be > 0"):
        cc.run_model("slider_crank", t_end=-1.0)
    with pytest.raises(cc.ModelError, match="expected a number"):
        cc.run_model("slider_crank", set={"restitution": {"a": 1}})
    assert issubclass(cc.ModelError, ValueError)


def test_solver_failure_keeps_partial_results(tmp_path):
    with pytest.raises(cc.SimulationError, match="max_steps") as e:
        cc.run_model(_pendulum(tmp_path), set={"solver.max_steps": 5})
    t = e.value.result["time"]
    assert len(t) >= 1 and t[-1] < 3.0


def test_left_out_velocity_is_solved_and_reported(tmp_path):
    """Issue 14: a rod angular velocity left out of a model file is solved from the constraints
    (closed form ω_rod = −ω_crank·r/L at θ = 0) and reported in `notes` and
    `initial_conditions`, as `clr run` reports it."""
    repo = pathlib.Path(__file__).resolve().parents[2]
    text = (repo / "models" / "slider_crank.toml").read_text()
    line = "angular_velocity = -87.26646259971649\n"
    assert line in text
    f = tmp_path / "sc.toml"
    f.write_text(text.replace(line, "", 1))
    r = cc.run_model(str(f), t_end=0.001)
    assert any("rod.omega" in n for n in r["notes"]), r["notes"]
    import json

    ic = json.loads(r["initial_conditions"])
    omega = ic["bodies"]["rod"]["omega"]
    assert omega["status"] == "solved"
    expect = -5000.0 * 2.0 * math.pi / 60.0 * 0.05 / 0.3
    assert abs(omega["assembled"] - expect) <= 1e-9 * abs(expect)


def test_plausibility_warnings_and_strict(tmp_path):
    """Issue 29: radii written in mm run with a warning naming the field (in
    `Result.warnings` and as a `clr_sim.PlausibilityWarning`); `strict=True` refuses the run."""
    import warnings

    import clr_sim

    repo = pathlib.Path(__file__).resolve().parents[2]
    text = (repo / "models" / "slider_crank.toml").read_text()
    for old, new in (
        ("\nbearing_radius = 0.01\n", "\nbearing_radius = 10.0\n"),
        ("\njournal_radius = 0.0095\n", "\njournal_radius = 9.5\n"),
    ):
        assert old in text
        text = text.replace(old, new, 1)
    f = tmp_path / "mm.toml"
    f.write_text(text)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        r = clr_sim.simulate(str(f), t_end=0.0005)
    fields = [w["field"] for w in r.warnings]
    assert "B.bearing_radius" in fields, r.warnings
    assert any(issubclass(w.category, clr_sim.PlausibilityWarning) for w in caught)
    with pytest.raises(clr_sim.ClrError, match="strict"):
        clr_sim.simulate(str(f), t_end=0.0005, strict=True)
    # the shipped file itself gives no warning
    assert clr_sim.simulate(str(repo / "models" / "slider_crank.toml"), t_end=0.0005).warnings == []
