#!/usr/bin/env python3
"""SciPy peer of `cargo xtask bench mbd`: the clearance slider-crank of issue 5 in minimal
coordinates, integrated with `scipy.integrate.solve_ivp` (LSODA and BDF) with located
contact-onset and separation events.

This is the same independent formulation as xtask/src/minimal_slider_crank.rs, written again
here: y = (phi, x, phi_dot, x_dot), phi the rod angle and x the slider position; the crank pin
A(t) = r (cos wt, sin wt) is prescribed; the rod is pinned at the moving point A
(J_A phi'' = -m2 (l/2) u_perp . A'' + m2 (l/2) u_perp . g + l u_perp . F_j, J_A = I2 + m2 l^2/4)
and the slider obeys m3 x'' = F_N n_x. Contact force by hand: Hertz internal cylinder
K = (4/3) E* sqrt(R_i R_j / (R_i - R_j)) (Flores et al. 2004) with the Lankarani-Nikravesh
hysteresis factor chi = 3 (1 - c_e^2) / 4, F_N = max(0, K delta^1.5 (1 + chi delta_dot / v_minus)),
v_minus the penetration rate at the located onset (at least 1e-4 m/s, clr-contact's floor).

With --rtols R1,R2,... (a work-precision sweep) every method runs at each rtol with
atol = --atol-ratio * rtol (default 1e-3) instead of the single --rtol/--atol pair.

Prints one JSON object per line: {"solver", "rtol", "atol", "wall_s", "repeats", "nfev",
"steps"(null: solve_ivp does not report them), "onsets", "x": [slider x at each --times]}.
Only the solve is timed (median over repeats), not the interpreter start-up.
"""

import argparse
import json
import math
import statistics
import sys
import time

from scipy.integrate import solve_ivp

CRANK, ROD = 0.05, 0.30
M_ROD, M_SLIDER = 1.072, 0.347
I_ROD = 0.034
R_BEARING, R_JOURNAL = 10.0e-3, 9.5e-3
G = 9.81
E, NU = 207e9, 0.3
V_FLOOR = 1e-4


class Minimal:
    def __init__(self, omega, c_e):
        e_star = 1.0 / (2.0 * (1.0 - NU * NU) / E)
        self.omega = omega
        self.k = 4.0 / 3.0 * e_star * math.sqrt(R_BEARING * R_JOURNAL / (R_BEARING - R_JOURNAL))
        self.chi = 0.75 * (1.0 - c_e * c_e)
        self.clearance = R_BEARING - R_JOURNAL
        self.active = False
        self.v_minus = 0.0
        self.j_a = I_ROD + M_ROD * ROD * ROD / 4.0

    def contact(self, t, y):
        """(delta, delta_dot, n) at (t, y)."""
        w = self.omega
        st, ct = math.sin(w * t), math.cos(w * t)
        sp, cp = math.sin(y[0]), math.cos(y[0])
        bx = CRANK * ct + ROD * cp - y[1]
        by = CRANK * st + ROD * sp
        bdx = -CRANK * w * st - ROD * y[2] * sp - y[3]
        bdy = CRANK * w * ct + ROD * y[2] * cp
        e = math.hypot(bx, by)
        nx, ny = (bx / e, by / e) if e > 0.0 else (1.0, 0.0)
        return e - self.clearance, nx * bdx + ny * bdy, nx, ny

    def rhs(self, t, y):
        delta, rate, nx, ny = self.contact(t, y)
        f_n = 0.0
        if delta > 0.0:
            vm = self.v_minus if self.active else max(rate, V_FLOOR)
            f_n = max(0.0, self.k * delta**1.5 * (1.0 + self.chi * rate / vm))
        w2 = CRANK * self.omega * self.omega
        th = self.omega * t
        ax, ay = -w2 * math.cos(th), -w2 * math.sin(th)
        sp, cp = math.sin(y[0]), math.cos(y[0])
        upx, upy = -sp, cp
        fjx, fjy = -f_n * nx, -f_n * ny
        moment = (
            -M_ROD * ROD / 2.0 * (upx * ax + upy * ay)
            + M_ROD * ROD / 2.0 * (-G * upy)
            + ROD * (upx * fjx + upy * fjy)
        )
        return [y[2], y[3], moment / self.j_a, f_n * nx / M_SLIDER]


def solve(method, omega, c_e, rtol, atol, t_end, times):
    """One run from the initial state; returns (x at times, nfev, onsets)."""
    sys_ = Minimal(omega, c_e)

    def gap(t, y):
        return sys_.contact(t, y)[0]

    onset = lambda t, y: gap(t, y)  # noqa: E731
    onset.terminal, onset.direction = True, 1.0
    separation = lambda t, y: gap(t, y)  # noqa: E731
    separation.terminal, separation.direction = True, -1.0

    t, y = 0.0, [0.0, CRANK + ROD, -omega * CRANK / ROD, 0.0]
    xs, nfev, onsets = [], 0, 0
    pending = list(times)
    while t < t_end:
        ev = separation if sys_.active else onset
        t_eval = [s for s in pending if s >= t]
        sol = solve_ivp(sys_.rhs, (t, t_end), y, method=method, rtol=rtol, atol=atol,
                        events=[ev], t_eval=t_eval)
        if not sol.success:
            raise RuntimeError(f"{method}: {sol.message} at t = {sol.t[-1] if len(sol.t) else t}")
        nfev += sol.nfev
        if len(sol.t) > 0:
            xs.extend(sol.y[1, :].tolist())
            pending = pending[len(sol.t):]
        if sol.status == 1 and len(sol.t_events[0]) > 0:
            t = float(sol.t_events[0][-1])
            y = sol.y_events[0][-1].tolist()
            if sys_.active:
                sys_.active = False
            else:
                _, rate, _, _ = sys_.contact(t, y)
                sys_.active = True
                sys_.v_minus = max(rate, V_FLOOR)
                onsets += 1
        else:
            break
    return xs, nfev, onsets


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--methods", default="LSODA,BDF")
    ap.add_argument("--rtol", type=float, default=1e-6)
    ap.add_argument("--atol", type=float, default=1e-9)
    ap.add_argument("--rtols", default=None,
                    help="comma-separated rtols of a sweep (atol = --atol-ratio * rtol)")
    ap.add_argument("--atol-ratio", type=float, default=1e-3)
    ap.add_argument("--t-end", type=float, default=0.1)
    ap.add_argument("--times", default="0.005,0.01")
    ap.add_argument("--rpm", type=float, default=5000.0)
    ap.add_argument("--restitution", type=float, default=0.9)
    ap.add_argument("--min-time", type=float, default=2.0)
    ap.add_argument("--max-repeats", type=int, default=3)
    a = ap.parse_args()
    omega = a.rpm * math.pi / 30.0
    times = [float(s) for s in a.times.split(",")] + [a.t_end]
    if a.rtols:
        pairs = [(r, a.atol_ratio * r) for r in (float(s) for s in a.rtols.split(","))]
    else:
        pairs = [(a.rtol, a.atol)]
    for rtol, atol in pairs:
        for method in a.methods.split(","):
            walls, out = [], None
            while True:
                start = time.perf_counter()
                try:
                    out = solve(method, omega, a.restitution, rtol, atol, a.t_end, times)
                except Exception as e:  # report and go on with the next method
                    print(f"scipy_slider_crank: {method} at rtol {rtol:g} failed: {e}",
                          file=sys.stderr)
                    out = None
                    break
                walls.append(time.perf_counter() - start)
                if len(walls) >= a.max_repeats or sum(walls) >= a.min_time:
                    break
            if out is None:
                continue
            xs, nfev, onsets = out
            print(json.dumps({
                "solver": f"scipy-{method.lower()}", "rtol": rtol, "atol": atol,
                "wall_s": statistics.median(walls), "repeats": len(walls), "nfev": nfev,
                "steps": None, "onsets": onsets, "times": times, "x": xs,
            }), flush=True)


if __name__ == "__main__":
    main()
