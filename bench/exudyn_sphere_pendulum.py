#!/usr/bin/env python3
"""Exudyn peer of `cargo xtask bench spatial`: a pendulum hanging in a spherical clearance joint.

Model (issue 31; SI units): one rigid body (ObjectRigidBody on a NodeRigidBodyEP, Euler
parameters) of mass 1.0 kg with principal inertia (0.004, 0.004, 0.0002) kg m^2 at its centre of
mass along the body axes. Its reference point B (the ball centre) lies L = 0.2 m from the centre of
mass along the body's +z axis (the centre of mass is 0.2 m along -z from B); the Exudyn node sits
at the centre of mass and the ball marker at local position (0, 0, L). Initial pose: the body
rotated +30 deg about the world x axis, B at the origin (ball centred in the socket), so the
centre of mass is at (0, 0.2 sin 30, -0.2 cos 30); initial world angular velocity (0, 0, 3) rad/s
with B at rest, so v_CoM = omega x (r_CoM - r_B) = (-0.3, 0, 0) m/s. Gravity (0, 0, -9.81) m/s^2.

Clearance joint: an ObjectContactSphereSphere between the ball (sphere 0, radius R_b = 9.5 mm, on
the body at B) and the socket (sphere 1, radius R_s = 10 mm, hollow: isHollowSphere1=True, on the
ground, centre at the origin). No other joint, no friction, no linear contact damping.
Gap convention (Exudyn docs, ObjectContactSphereSphere, "Connector Forces"): with h1 = -1 for a
hollow sphere 1, g = h1 |p1 - p0| - (r0 + h1 r1) = (R_s - R_b) - |p_ball - p_socket|, the
overlap is delta = -g = |ecc| - (R_s - R_b) and the elastic force K delta^1.5 pushes the ball back
towards the socket centre. Checked (--check static): at rest the ball hangs below the socket
centre by (R_s - R_b) + delta with K delta^1.5 = m g (see exudyn_notes.md).
Normal law: K = (4/3) E* sqrt(R*), R* = R_b R_s / (R_s - R_b) (Hertz sphere in a concave sphere),
E* = E / (2 (1 - nu^2)), E = 207 GPa, nu = 0.3; exponent 1.5; impact model 1 (Hunt-Crossley,
damping 1.5 (1 - e) K delta^1.5 v / v-) with e = (1 + c_e^2) / 2, i.e. Lankarani-Nikravesh with
restitution c_e (default 0.9), written as in exudyn_slider_crank.py.

Solver: generalized-alpha (Exudyn defaults, spectral radius 0.9) with step h (default 1e-4, 1e-5
and 1e-6), t_end = 1.0, timeIntegration.discontinuous.useRecommendedStepSize = False. The step is
fixed except that Exudyn halves it where Newton fails (timeIntegration.adaptiveStep, default on,
left on as in exudyn_slider_crank.py: with it off h = 1e-4 aborts) and doubles it back later;
"steps" is the number of steps Exudyn took, "steps_nominal" t_end / h.

Prints one JSON object per line and step size:
{"solver", "h", "exudyn_version", "wall_s", "cpu_s", "repeats", "steps", "steps_nominal",
 "sensor_every_step", "min_impact_velocity", "times", "com", "ecc"[, "onsets"]}
with the centre-of-mass position (x, y, z) and the eccentricity ecc = ball centre - socket centre
(x, y, z) at --times (and t_end), in m. Values are the sensor sample at the step ending at t;
where no step ends at t (a reduced step shifted the grid, or t is not a multiple of h) they are
interpolated linearly between the two steps around t (error <= h^2/8 |y''|), and then the sensors
are written after every step ("sensor_every_step": true) instead of every 1e-4 s.
Only exu.SolveDynamic is timed; wall_s (perf_counter) and cpu_s (process_time, robust on a loaded
machine) are medians over repeats.
With --onsets, "onsets" is the number of contact onsets (steps after which the gap, Exudyn's data
coordinate 0, is < 0 while it was >= 0 after the step before), counted in one extra untimed
solve with a gap sensor written after every step.

--check static | energy | rigid runs a sanity check instead (see exudyn_notes.md) and prints one
JSON line with its result.
"""

import argparse
import json
import math
import statistics
import sys
import time
import warnings

import numpy as np

import exudyn as exu

# the settings names used here work in 1.13 with a DeprecationWarning (renamed since 1.12)
warnings.filterwarnings("ignore", category=DeprecationWarning)
from exudyn.itemInterface import (  # noqa: E402
    MarkerBodyRigid,
    NodeGenericData,
    ObjectContactSphereSphere,
    ObjectGround,
    SensorBody,
    SensorNode,
)
from exudyn.rigidBodyUtilities import RigidBodyInertia, RotationMatrixX  # noqa: E402

MASS, L = 1.0, 0.2
INERTIA_COM = (0.004, 0.004, 0.0002)
R_SOCKET, R_BALL = 10.0e-3, 9.5e-3
G = 9.81
E, NU = 207e9, 0.3
TILT = math.radians(30.0)
OMEGA0 = (0.0, 0.0, 3.0)


def hertz_stiffness():
    """K = (4/3) E* sqrt(R*) in N/m^1.5 for a ball of R_BALL in a concave sphere of R_SOCKET."""
    e_star = E / (2.0 * (1.0 - NU * NU))
    r_star = R_BALL * R_SOCKET / (R_SOCKET - R_BALL)
    return 4.0 / 3.0 * e_star * math.sqrt(r_star)


def build(c_e, tilt=TILT, omega=OMEGA0, ecc0=(0.0, 0.0, 0.0), k_scale=1.0, v_min=0.0):
    """The Exudyn system with the pendulum posed as in the docstring, B at ecc0.

    v_min (m/s) floors the impact velocity in the damping term (Exudyn's minimumImpactVelocity,
    default 0 as in exudyn_slider_crank.py). Returns (SystemContainer, MainSystem, dict of
    node/object indices)."""
    sc = exu.SystemContainer()
    mbs = sc.AddSystem()
    ground = mbs.AddObject(ObjectGround())
    rot = np.array(RotationMatrixX(tilt))
    r_b = np.array(ecc0, dtype=float)
    r_com = r_b + rot @ np.array([0.0, 0.0, -L])
    w = np.array(omega, dtype=float)
    inertia = RigidBodyInertia(mass=MASS, inertiaTensor=np.diag(INERTIA_COM),
                               com=[0.0, 0.0, 0.0], inertiaTensorAtCOM=True)
    d = mbs.CreateRigidBody(inertia=inertia, referencePosition=list(r_com),
                            referenceRotationMatrix=rot,
                            initialVelocity=list(np.cross(w, r_com - r_b)),
                            initialAngularVelocity=list(w), gravity=[0.0, 0.0, -G],
                            nodeType=exu.NodeType.RotationEulerParameters, returnDict=True)
    body, node = d["bodyNumber"], d["nodeNumber"]
    m_ball = mbs.AddMarker(MarkerBodyRigid(bodyNumber=body, localPosition=[0.0, 0.0, L]))
    m_socket = mbs.AddMarker(MarkerBodyRigid(bodyNumber=ground, localPosition=[0.0, 0.0, 0.0]))
    n_data = mbs.AddNode(NodeGenericData(numberOfDataCoordinates=4,
                                         initialCoordinates=[0.0, 0.0, 0.0, 0.0]))
    contact = mbs.AddObject(ObjectContactSphereSphere(
        markerNumbers=[m_ball, m_socket], nodeNumber=n_data,
        spheresRadii=[R_BALL, R_SOCKET], isHollowSphere1=True,
        contactStiffness=k_scale * hertz_stiffness(), contactDamping=0.0,
        contactStiffnessExponent=1.5,
        restitutionCoefficient=0.5 * (1.0 + c_e * c_e), impactModel=1,
        minimumImpactVelocity=v_min, dynamicFriction=0.0))
    mbs.Assemble()
    return sc, mbs, {"body": body, "node": node, "data": n_data, "contact": contact}


def settings(h, t_end, write_period):
    s = exu.SimulationSettings()
    ti = s.timeIntegration
    ti.numberOfSteps = int(round(t_end / h))
    ti.endTime = t_end
    ti.verboseMode = 0
    ti.discontinuous.useRecommendedStepSize = False
    s.solutionSettings.writeSolutionToFile = False
    s.solutionSettings.sensorsWritePeriod = write_period
    s.displayStatistics = False
    s.displayComputationTime = False
    return s


class ThinnedSampleError(RuntimeError):
    """An output time fell between two sensor samples more than one step apart."""


def sample(ts, ys, times, h):
    """Rows of ys at times: the stored row when a step ends at t (within 1e-3 h), else the
    linear interpolation between the two stored steps around t (error <= h^2/8 |y''|).
    Exudyn halves the step when Newton fails (timeIntegration.adaptiveStep, on by default), after
    which the steps no longer end on the output times, hence the interpolation."""
    out = []
    for t in times:
        i = int(abs(ts - t).argmin())
        if abs(ts[i] - t) <= 1e-3 * h:
            out.append([float(v) for v in ys[i]])
            continue
        j = i if ts[i] < t else i - 1
        if j < 0 or j + 1 >= len(ts) or not (ts[j] <= t <= ts[j + 1]):
            raise RuntimeError(f"no stored sensor values around t = {t}")
        if ts[j + 1] - ts[j] > h * (1.0 + 1e-3):  # h: the step Exudyn uses, t_end / steps
            raise ThinnedSampleError(f"t = {t} lies between samples {ts[j]} and {ts[j + 1]}")
        w = (t - ts[j]) / (ts[j + 1] - ts[j])
        out.append([float(v) for v in (1.0 - w) * ys[j] + w * ys[j + 1]])
    return out


def count_onsets(gaps):
    """Contact onsets: steps where the gap goes from open (>= 0) to closed (< 0)."""
    closed = gaps < 0.0
    return int(np.count_nonzero(closed[1:] & ~closed[:-1]) + (1 if closed[0] else 0))


def run(h, c_e, v_min, t_end, times, every_step=False):
    """One solve; returns (wall and CPU time of SolveDynamic, com rows, ecc rows, steps taken).

    Sensors are written every max(h, 1e-4) s when the output times are multiples of h (a step
    ends there unless Exudyn reduced the step), else (every_step) after each step."""
    _, mbs, ix = build(c_e, v_min=v_min)
    on_grid = all(abs(t / h - round(t / h)) < 1e-6 for t in times)
    period = h if every_step or not on_grid else max(h, 1e-4)
    sens = [mbs.AddSensor(SensorBody(bodyNumber=ix["body"], localPosition=p, storeInternal=True,
                                     writeToFile=False,
                                     outputVariableType=exu.OutputVariableType.Position))
            for p in ([0.0, 0.0, 0.0], [0.0, 0.0, L])]
    mbs.Assemble()
    s = settings(h, t_end, period)
    start, cpu = time.perf_counter(), time.process_time()
    ok = mbs.SolveDynamic(s, solverType=exu.DynamicSolverType.GeneralizedAlpha,
                          storeSolver=True)
    wall, cpu = time.perf_counter() - start, time.process_time() - cpu
    if ok is False:
        raise RuntimeError("SolveDynamic reported failure")
    com, ball = (mbs.GetSensorStoredData(x) for x in sens)
    return (wall, cpu, sample(com[:, 0], com[:, 1:4], times, h),
            sample(ball[:, 0], ball[:, 1:4], times, h),
            int(mbs.sys["dynamicSolver"].it.currentStepIndex))


def run_onsets(h, c_e, v_min, t_end):
    """Number of contact onsets, from a gap sensor written after every step (an extra, untimed
    solve, since storing one row per step costs 10-40 % of the solve)."""
    _, mbs, ix = build(c_e, v_min=v_min)
    s_gap = mbs.AddSensor(SensorNode(nodeNumber=ix["data"], storeInternal=True,
                                     writeToFile=False,
                                     outputVariableType=exu.OutputVariableType.Coordinates))
    (gap,) = solve_all_steps(mbs, h, t_end, [s_gap])
    return count_onsets(gap[:, 1])


def solve_all_steps(mbs, h, t_end, sensors):
    """Solve with every step stored; returns the stored arrays of the sensors."""
    mbs.Assemble()
    s = settings(h, t_end, h)
    if mbs.SolveDynamic(s, solverType=exu.DynamicSolverType.GeneralizedAlpha) is False:
        raise RuntimeError("SolveDynamic reported failure")
    return [mbs.GetSensorStoredData(x) for x in sensors]


def check_static(h):
    """Pendulum hanging straight down, ball started at the bottom of the socket with 1 um gap,
    strongly damped (c_e = 0.2), after 0.5 s: overlap delta = |ecc| - (R_s - R_b) against the
    Hertz value (m g / K)^(2/3)."""
    clear = R_SOCKET - R_BALL
    _, mbs, ix = build(0.2, tilt=0.0, omega=(0.0, 0.0, 0.0),
                       ecc0=(0.0, 0.0, -(clear - 1e-6)))
    s_ball = mbs.AddSensor(SensorBody(bodyNumber=ix["body"], localPosition=[0.0, 0.0, L],
                                      storeInternal=True, writeToFile=False,
                                      outputVariableType=exu.OutputVariableType.Position))
    (ball,) = solve_all_steps(mbs, h, 0.5, [s_ball])
    ecc = ball[-1, 1:4]
    delta = float(np.linalg.norm(ecc) - clear)
    delta_hertz = (MASS * G / hertz_stiffness()) ** (2.0 / 3.0)
    return {"check": "static", "h": h, "ecc_end": [float(v) for v in ecc], "delta": delta,
            "delta_hertz": delta_hertz, "rel_err": delta / delta_hertz - 1.0,
            "K_delta15_over_mg": hertz_stiffness() * max(delta, 0.0) ** 1.5 / (MASS * G)}


def check_energy(h, k_scale, t_end):
    """No dissipation (c_e = 1, so e = 1 and the Hunt-Crossley term vanishes): total energy
    T + m g z_com + K delta^2.5 / 2.5 along the run; returns its largest deviation from t = 0."""
    _, mbs, ix = build(1.0, k_scale=k_scale)
    k = k_scale * hertz_stiffness()
    ovt = exu.OutputVariableType
    sens = [mbs.AddSensor(SensorBody(bodyNumber=ix["body"], localPosition=p, storeInternal=True,
                                     writeToFile=False, outputVariableType=v))
            for p, v in (([0, 0, 0], ovt.Position), ([0, 0, 0], ovt.Velocity),
                         ([0, 0, 0], ovt.AngularVelocityLocal), ([0, 0, L], ovt.Position))]
    pos, vel, wl, ball = solve_all_steps(mbs, h, t_end, sens)
    kin = 0.5 * MASS * np.sum(vel[:, 1:4] ** 2, axis=1) \
        + 0.5 * np.sum(np.array(INERTIA_COM) * wl[:, 1:4] ** 2, axis=1)
    pot = MASS * G * pos[:, 3]
    delta = np.maximum(np.linalg.norm(ball[:, 1:4], axis=1) - (R_SOCKET - R_BALL), 0.0)
    ela = k * delta ** 2.5 / 2.5
    tot = kin + pot + ela
    return {"check": "energy", "h": h, "k_scale": k_scale, "t_end": t_end,
            "E0": float(tot[0]), "max_abs_dE": float(np.max(np.abs(tot - tot[0]))),
            "E_end_minus_E0": float(tot[-1] - tot[0]), "max_delta": float(np.max(delta)),
            "max_kinetic": float(np.max(kin))}


def rigid_top(t_end, times, dt=1e-5):
    """Independent reference: the same body on an ideal spherical joint at B (a heavy symmetric
    Lagrange top about a fixed point), integrated with classical RK4 in (R, omega_body) with
    Euler's equations about B, I_B = I_com + m L^2 (parallel axes), gravity torque
    r_com x m g; returns centre-of-mass positions at times."""
    i_b = np.array(INERTIA_COM) + MASS * L * L * np.array([1.0, 1.0, 0.0])
    c = np.array([0.0, 0.0, -L])  # centre of mass in body axes, from B

    def rhs(rot, wb):
        gb = rot.T @ np.array([0.0, 0.0, -MASS * G])  # gravity in body axes
        tau = np.cross(c, gb)
        dw = (tau - np.cross(wb, i_b * wb)) / i_b
        wx = np.array([[0, -wb[2], wb[1]], [wb[2], 0, -wb[0]], [-wb[1], wb[0], 0]])
        return rot @ wx, dw

    rot = np.array(RotationMatrixX(TILT))
    wb = rot.T @ np.array(OMEGA0)
    out = []
    n = int(round(t_end / dt))
    marks = {int(round(tt / dt)): tt for tt in times}
    for step in range(1, n + 1):
        k1 = rhs(rot, wb)
        k2 = rhs(rot + 0.5 * dt * k1[0], wb + 0.5 * dt * k1[1])
        k3 = rhs(rot + 0.5 * dt * k2[0], wb + 0.5 * dt * k2[1])
        k4 = rhs(rot + dt * k3[0], wb + dt * k3[1])
        rot = rot + dt / 6.0 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0])
        wb = wb + dt / 6.0 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1])
        u, _, vt = np.linalg.svd(rot)  # re-orthonormalise (drift is O(dt^4) per step anyway)
        rot = u @ vt
        if step in marks:
            out.append([float(v) for v in rot @ c])
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--h", default="1e-4,1e-5,1e-6", help="comma-separated step sizes in s")
    ap.add_argument("--t-end", type=float, default=1.0)
    ap.add_argument("--times", default="0.1,0.2,0.3,0.4,0.5,0.6,0.7,0.8,0.9,1.0")
    ap.add_argument("--restitution", type=float, default=0.9, help="c_e of Lankarani-Nikravesh")
    ap.add_argument("--min-impact-velocity", type=float, default=0.0,
                    help="floor of the impact velocity in m/s (Exudyn's minimumImpactVelocity; "
                         "clr's NormalLaw floors at 1e-4)")
    ap.add_argument("--min-time", type=float, default=2.0)
    ap.add_argument("--max-repeats", type=int, default=5)
    ap.add_argument("--onsets", action="store_true",
                    help="count contact onsets (one extra, untimed solve)")
    ap.add_argument("--check", choices=["static", "energy", "rigid"])
    ap.add_argument("--k-scale", type=float, default=1.0,
                    help="stiffness factor for --check energy")
    a = ap.parse_args()
    times = [float(s) for s in a.times.split(",")]
    if all(abs(t - a.t_end) > 1e-12 for t in times):
        times.append(a.t_end)
    hs = [float(s) for s in a.h.replace(" ", ",").split(",") if s]
    if a.check == "static":
        print(json.dumps(check_static(hs[-1])), flush=True)
        return
    if a.check == "energy":
        for h in hs:
            print(json.dumps(check_energy(h, a.k_scale, a.t_end)), flush=True)
        return
    if a.check == "rigid":
        print(json.dumps({"check": "rigid", "times": times, "com": rigid_top(a.t_end, times)}),
              flush=True)
        return
    for h in hs:
        walls, cpus, out, every_step = [], [], None, False
        try:
            while True:
                try:
                    wall, cpu, com, ecc, steps = run(h, a.restitution, a.min_impact_velocity,
                                                     a.t_end, times, every_step)
                except ThinnedSampleError:  # steps off the output times: store every step
                    if every_step:
                        raise
                    every_step, walls, cpus = True, [], []
                    continue
                walls.append(wall)
                cpus.append(cpu)
                out = (com, ecc, steps)
                if len(walls) >= a.max_repeats or sum(walls) >= a.min_time:
                    break
            onsets = None
            if a.onsets:
                onsets = run_onsets(h, a.restitution, a.min_impact_velocity, a.t_end)
        except Exception as e:  # report and go on with the next step size
            print(f"exudyn_sphere_pendulum: h = {h} failed: {e}", file=sys.stderr)
            continue
        com, ecc, steps = out
        rec = {"solver": "exudyn-genalpha", "h": h, "exudyn_version": exu.__version__,
               "wall_s": statistics.median(walls),
               "cpu_s": statistics.median(cpus), "repeats": len(walls), "steps": steps,
               "steps_nominal": int(round(a.t_end / h)), "sensor_every_step": every_step,
               "min_impact_velocity": a.min_impact_velocity,
               "times": times, "com": com, "ecc": ecc}
        if onsets is not None:
            rec["onsets"] = onsets
        print(json.dumps(rec), flush=True)

if __name__ == "__main__":
    main()
