"""Load inputs given as Python callables f(t, measures) (``clr_sim.simulate(..., inputs=...)``):

- a disc on a pin under a PD torque u = −k θ − c ω from its measured angle and rate: the closed
  form of the damped oscillator I θ̈ + c θ̇ + k θ = 0 from θ(0) = 0, ω(0) = ω0 (tolerance 1e-6 rad
  at rtol 1e-9);
- the cost of one call, measured and bounded loosely (documented in docs/fmu.md);
- mistakes: an unknown input, a driver's motion, a callable that raises (the run stops and the
  exception is the cause), a value that is not a callable.
"""

from __future__ import annotations

import math
import time

import numpy as np
import pytest

import clr_sim


def _disc(omega0=2.0):
    m = clr_sim.Model("disc")
    m.body("disc", mass=2.0, inertia=0.5, position=(0, 0), angle=0.0,
           velocity=(0, 0), angular_velocity=omega0)
    m.revolute("pin", a=clr_sim.at("ground"), b=clr_sim.at("disc"))
    m.input("u", description="controller torque, N·m")
    m.torque("motor", body="disc", torque=clr_sim.motion("input", name="u"))
    m.measure_angle("disc_angle", body="disc")
    m.measure_angular_velocity("disc_rate", body="disc")
    m.solver(rtol=1e-9)
    m.output(t_end=2.0, intervals=200)
    return m


def test_pd_torque_from_python_matches_the_damped_oscillator():
    k, c, inertia, w0 = 8.0, 0.6, 0.5, 2.0
    calls = []

    def pd(t, meas):
        calls.append(t)
        return -k * meas["disc_angle.angle"] - c * meas["disc_rate.omega"]

    t0 = time.perf_counter()
    r = clr_sim.simulate(_disc(w0), inputs={"u": pd})
    wall = time.perf_counter() - t0
    print(f"PD run: {len(calls)} calls in {wall * 1e3:.1f} ms, {1e6 * wall / len(calls):.1f} µs per call "
          "including the integration")
    t, th = r["t"], r["disc.theta"]
    # I θ̈ + c θ̇ + k θ = 0, θ(0) = 0, θ̇(0) = ω0: θ = (ω0/ωd) e^{−ζωn t} sin ωd t
    wn = math.sqrt(k / inertia)
    zeta = c / (2 * math.sqrt(k * inertia))
    wd = wn * math.sqrt(1 - zeta**2)
    ref = (w0 / wd) * np.exp(-zeta * wn * t) * np.sin(wd * t)
    assert np.max(np.abs(th - ref)) < 1e-6, np.max(np.abs(th - ref))
    assert len(calls) > 100
    assert any("functions of the state" in n for n in r.notes), r.notes


def test_cost_of_a_python_input_call_is_microseconds():
    # one run with a trivial callable and one with the same torque as a constant: the extra
    # time per call is the cost of calling Python from the right-hand side (docs/fmu.md quotes
    # it); a loose bound only (tests do not time things tightly)
    n = []

    def zero(t, meas):
        n.append(1)
        return 0.0

    m = _disc()
    t0 = time.perf_counter()
    clr_sim.simulate(m, inputs={"u": zero})
    per_call = (time.perf_counter() - t0) / len(n)
    print(f"{len(n)} calls, {1e6 * per_call:.1f} µs per call including the integration")
    assert per_call < 1e-3


def test_input_function_mistakes():
    m = _disc()
    with pytest.raises(clr_sim.ModelError, match="no input `v`"):
        clr_sim.simulate(m, inputs={"v": lambda t, s: 0.0})
    with pytest.raises(clr_sim.ModelError, match="callable"):
        clr_sim.simulate(m, inputs={"u": 3.0})

    def broken(t, meas):
        return meas["no.such"]

    with pytest.raises(clr_sim.SimulationError, match="KeyError") as e:
        clr_sim.simulate(m, inputs={"u": broken})
    assert isinstance(e.value.__cause__, KeyError)
    with pytest.raises(clr_sim.ModelError, match="built-in"):
        clr_sim.simulate("slider_crank", inputs={"u": lambda t, s: 0.0})
