"""[[measure]] from the builder: columns with units, and the velocity of a point against the
closed form of a crank driven at constant speed (docs/model-file.md "Measures")."""

import numpy as np
import pytest

import clr_sim


def crank_with_measures() -> clr_sim.Model:
    m = clr_sim.Model("crank")
    m.body("crank", mass=1.0, inertia=0.1, position=(0.0, 0.0), angle=0.0)
    m.revolute("O", a=clr_sim.at("ground"), b=clr_sim.at("crank"))
    m.drive_angle("motor", body="crank", motion=clr_sim.motion("linear", initial=0.0, rate=7.0))
    m.measure_velocity("tip", at=clr_sim.at("crank", 0.5, 0.0))
    m.measure_angle("turn", body="crank", offset=0.25)
    m.measure_reaction("pin", joint="O", frame="crank")
    m.measure_energy("ke", term="kinetic")
    m.solver(rtol=1e-10, atol=1e-12)
    m.output(t_end=0.2, intervals=20)
    return m


def test_measures_write_columns_with_units_and_equal_the_closed_form():
    r = clr_sim.simulate(crank_with_measures())
    t = r["t"]
    # uniform rotation at 7 rad/s: v = L ω (−sin ωt, cos ωt), to rounding (the driver is exact)
    assert np.allclose(r["tip.vx"], -0.5 * 7.0 * np.sin(7.0 * t), rtol=0, atol=1e-12)
    assert np.allclose(r["tip.vy"], 0.5 * 7.0 * np.cos(7.0 * t), rtol=0, atol=1e-12)
    assert np.allclose(r["turn.angle"], 7.0 * t - 0.25, rtol=0, atol=1e-12)
    # the centre of mass is on the pin: no force, only the driver's moment (zero at constant ω)
    assert np.allclose(r["pin.Fx"], 0.0, atol=1e-9)
    assert np.allclose(r["ke.energy"], 0.5 * 0.1 * 49.0, rtol=1e-12)
    assert r.units["tip.vx"] == "m/s" and r.units["turn.angle"] == "rad"
    assert r.units["pin.M"] == "N*m" and r.units["ke.energy"] == "J"
    # and the file round trip keeps them
    again = clr_sim.Model.from_toml(crank_with_measures().to_toml())
    assert "[[measure]]" in again.to_toml()


def test_a_measure_with_a_misspelt_body_names_its_field():
    m = crank_with_measures()
    m.measure_angle("bad", body="crnk")
    with pytest.raises(clr_sim.FieldError) as e:
        m.check()
    assert "crnk" in str(e.value)


def test_a_spatial_model_refuses_measures_with_what_to_use():
    # the planar-only kinds name the spatial ones; a spatial point measure reads its `at` as a
    # spatial end and refuses anything else at its field
    m = clr_sim.Model("top", space="spatial")
    with pytest.raises(clr_sim.errors.ModelError) as e:
        m.measure_angle("a", body="top")
    assert "spatial" in str(e.value) and "measure_position" in str(e.value)
    with pytest.raises(clr_sim.FieldError) as e:
        m.measure_position("p", at="x")
    assert "measure[0]" in str(e.value)


def test_deviation_from_the_ideal_twin_and_a_metric_of_it():
    from test_package import slider_crank_in_python

    m = slider_crank_in_python()
    m.output(t_end=0.02, intervals=0, every_step=True)
    m.measure_deviation("slider", of=["slider.x"])
    m.twin(intervals=20000)
    m.metric("slider_error_max", of="slider.error", statistic="peak", t_start=0.012)
    m.metric("B_peak", of="B.normal_force", statistic="max", t_start=0.012)
    r = clr_sim.simulate(m)
    assert r.units["slider.error"] == "m"
    # the deviation's peak after the first revolution, as the metric and from the column
    after = r["t"] >= 0.012
    assert r.metrics["slider_error_max"] == pytest.approx(np.abs(r["slider.error"][after]).max())
    # the built-in's peak contact force after its first revolution is the same located peak
    b = clr_sim.simulate("slider_crank", 0.02)
    assert r.metrics["B_peak"] == pytest.approx(b.metrics["peak_contact_force"], rel=1e-9)


def test_combination_and_metrics_over_columns_and_metrics_equal_numpy():
    """A combination of the contact columns and metrics taken of several columns, of earlier
    metrics and per another metric, against the same numbers computed with numpy from the
    recorded columns (trapezoidal rule, the onsets counted as 0 → 1 transitions)."""
    from test_package import slider_crank_in_python

    m = slider_crank_in_python()
    m.output(t_end=0.02, intervals=0, every_step=True)
    m.measure_combination(
        "load",
        terms=[{"of": "B.normal_force"}, {"of": "B.friction_force", "abs": True, "factor": 2.0}],
    )
    m.measure_combination("power", terms=[{"of": ["B.normal_force", "slider.vx"]}], unit="W")
    m.metric("load_mean", of="load.value", statistic="mean")
    m.metric("closings", of="B.contact", statistic="onsets")
    m.metric("work", of="power.value", statistic="integral")
    m.metric("peak_v", of=["slider.vx", "crank.vx"], statistic="peak")
    m.metric("both", metrics=["load_mean", "peak_v"], statistic="max")
    m.metric("ratio", of="B.friction_force", statistic="mean", per="load_mean")
    r = clr_sim.simulate(m)
    t, fn, ft = r["t"], r["B.normal_force"], r["B.friction_force"]
    assert np.array_equal(r["load.value"], fn + 2.0 * np.abs(ft))
    assert r.units["load.value"] == "N" and r.units["power.value"] == "W"

    # the same trapezoid sums in numpy's order: rounding only (rel 1e-12)
    def mean(v):
        return np.trapezoid(v, t) / (t[-1] - t[0])

    assert r.metrics["load_mean"] == pytest.approx(mean(r["load.value"]), rel=1e-12)
    c = r["B.contact"]
    assert r.metrics["closings"] == np.sum((c[:-1] < 0.5) & (c[1:] >= 0.5))
    assert r.metrics["work"] == pytest.approx(np.trapezoid(fn * r["slider.vx"], t), rel=1e-12)
    peak = max(np.abs(r["slider.vx"]).max(), np.abs(r["crank.vx"]).max())
    assert r.metrics["peak_v"] == peak
    assert r.metrics["ratio"] == pytest.approx(mean(ft) / r.metrics["load_mean"], rel=1e-12)
    assert r.metrics["closings"] > 0 and r.metrics["work"] != 0.0
    with pytest.raises(clr_sim.ModelError, match="window"):
        m.metric("osc", of="slider.x", statistic="oscillation")
        clr_sim.simulate(m)


def test_the_measures_example_of_the_docs_runs():
    """docs/python.md, section "Measures and metrics": its block runs as written on the
    slider–crank of "Build a model"."""
    import pathlib
    import re

    from test_package import slider_crank_in_python

    text = (pathlib.Path(__file__).parents[2] / "docs" / "python.md").read_text()
    section = text.split("## Measures and metrics", 1)[1].split("\n## ", 1)[0]
    block = re.findall(r"```python\n(.*?)```", section, re.S)[0]
    m = slider_crank_in_python()
    m.output(t_end=0.02, intervals=0, every_step=True)
    scope = {"m": m, "clr_sim": clr_sim}
    exec(compile(block, "docs/python.md", "exec"), scope)
    r = scope["r"]
    assert r.units["pin.M"] == "N*m" and r.units["rod.angle"] == "rad"
    assert r.metrics["slider_error_max"] > 1e-4  # the clearance of 0.5 mm shows
