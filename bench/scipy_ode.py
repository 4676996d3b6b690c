#!/usr/bin/env python3
"""SciPy's solve_ivp(method="BDF") on the clr-ode benchmark problems, run by `cargo xtask bench ode`.

The four stiff problems of the Test Set for IVP Solvers (Mazzia, Magherini, Iavernaro; Bari) used
by clr-ode's verification: HIRES, Robertson, stiff Van der Pol (eps = 1e-6) and OREGO, each with
its analytic Jacobian (dense numpy array). Only the solve is timed (time.perf_counter around
solve_ivp), not the interpreter start-up or the imports.

Usage: scipy_ode.py [--rtol R]... [--min-time SECONDS]
For each problem and relative tolerance R the solve is repeated until at least --min-time seconds
(default 2) and 3 repetitions have passed; one JSON object per line is printed on stdout:
{"problem", "solver", "rtol", "atol", "wall_s", "f_evals", "steps", "y_end"}, wall_s being the
median solve time in seconds and steps the number of accepted steps (len(sol.t) - 1, since no
t_eval is given and solve_ivp then records every accepted step).

Absolute tolerance: atol = rtol, except Robertson where atol = 1e-6 * rtol (1e-12 at rtol 1e-6),
the same rule as the diffsol peer and clr-ode in the xtask.
"""

import argparse
import json
import statistics
import sys
import time

import numpy as np
from scipy.integrate import solve_ivp


def hires_f(t, y):
    r = 280.0 * y[5] * y[7]
    return np.array(
        [
            -1.71 * y[0] + 0.43 * y[1] + 8.32 * y[2] + 0.0007,
            1.71 * y[0] - 8.75 * y[1],
            -10.03 * y[2] + 0.43 * y[3] + 0.035 * y[4],
            8.32 * y[1] + 1.71 * y[2] - 1.12 * y[3],
            -1.745 * y[4] + 0.43 * y[5] + 0.43 * y[6],
            -r + 0.69 * y[3] + 1.71 * y[4] - 0.43 * y[5] + 0.69 * y[6],
            r - 1.81 * y[6],
            -r + 1.81 * y[6],
        ]
    )


def hires_jac(t, y):
    j = np.zeros((8, 8))
    j[0, 0], j[0, 1], j[0, 2] = -1.71, 0.43, 8.32
    j[1, 0], j[1, 1] = 1.71, -8.75
    j[2, 2], j[2, 3], j[2, 4] = -10.03, 0.43, 0.035
    j[3, 1], j[3, 2], j[3, 3] = 8.32, 1.71, -1.12
    j[4, 4], j[4, 5], j[4, 6] = -1.745, 0.43, 0.43
    a, b = 280.0 * y[7], 280.0 * y[5]
    j[5, 3], j[5, 4], j[5, 5], j[5, 6], j[5, 7] = 0.69, 1.71, -a - 0.43, 0.69, -b
    j[6, 5], j[6, 6], j[6, 7] = a, -1.81, b
    j[7, 5], j[7, 6], j[7, 7] = -a, 1.81, -b
    return j


def rober_f(t, y):
    return np.array(
        [
            -0.04 * y[0] + 1e4 * y[1] * y[2],
            0.04 * y[0] - 1e4 * y[1] * y[2] - 3e7 * y[1] * y[1],
            3e7 * y[1] * y[1],
        ]
    )


def rober_jac(t, y):
    return np.array(
        [
            [-0.04, 1e4 * y[2], 1e4 * y[1]],
            [0.04, -1e4 * y[2] - 6e7 * y[1], -1e4 * y[1]],
            [0.0, 6e7 * y[1], 0.0],
        ]
    )


VDP_EPS = 1e-6


def vdp_f(t, y):
    return np.array([y[1], ((1.0 - y[0] * y[0]) * y[1] - y[0]) / VDP_EPS])


def vdp_jac(t, y):
    return np.array(
        [
            [0.0, 1.0],
            [(-2.0 * y[0] * y[1] - 1.0) / VDP_EPS, (1.0 - y[0] * y[0]) / VDP_EPS],
        ]
    )


def orego_f(t, y):
    return np.array(
        [
            77.27 * (y[1] + y[0] * (1.0 - 8.375e-6 * y[0] - y[1])),
            (y[2] - (1.0 + y[0]) * y[1]) / 77.27,
            0.161 * (y[0] - y[2]),
        ]
    )


def orego_jac(t, y):
    return np.array(
        [
            [77.27 * (1.0 - 2.0 * 8.375e-6 * y[0] - y[1]), 77.27 * (1.0 - y[0]), 0.0],
            [-y[1] / 77.27, -(1.0 + y[0]) / 77.27, 1.0 / 77.27],
            [0.161, 0.0, -0.161],
        ]
    )


PROBLEMS = [
    ("hires", hires_f, hires_jac, [1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0057], 321.8122),
    ("robertson", rober_f, rober_jac, [1.0, 0.0, 0.0], 1e11),
    ("vdpol", vdp_f, vdp_jac, [2.0, 0.0], 2.0),
    ("orego", orego_f, orego_jac, [1.0, 2.0, 3.0], 360.0),
]


def atol_for(name, rtol):
    return rtol * 1e-6 if name == "robertson" else rtol


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rtol", type=float, action="append", help="relative tolerance (repeatable)")
    ap.add_argument("--min-time", type=float, default=2.0, help="seconds of repeated solves per row")
    args = ap.parse_args()
    rtols = args.rtol or [1e-6]
    failed = False
    for rtol in rtols:
        for name, f, jac, y0, t_end in PROBLEMS:
            atol = atol_for(name, rtol)
            times = []
            sol = None
            while len(times) < 3 or (sum(times) < args.min_time and len(times) < 1000):
                start = time.perf_counter()
                sol = solve_ivp(f, (0.0, t_end), y0, method="BDF", rtol=rtol, atol=atol, jac=jac)
                times.append(time.perf_counter() - start)
                if not sol.success:
                    break
            if not sol.success:
                print(f"scipy_ode.py: {name} at rtol {rtol}: {sol.message}", file=sys.stderr)
                failed = True
                continue
            row = {
                "problem": name,
                "solver": "scipy-bdf",
                "rtol": rtol,
                "atol": atol,
                "wall_s": statistics.median(times),
                "repeats": len(times),
                "f_evals": int(sol.nfev),
                "steps": len(sol.t) - 1,
                "y_end": [float(v) for v in sol.y[:, -1]],
            }
            print(json.dumps(row), flush=True)
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
