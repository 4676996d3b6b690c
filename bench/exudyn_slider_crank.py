#!/usr/bin/env python3
"""Exudyn peer of `cargo xtask bench mbd`: the clearance slider-crank of issue 5 in Exudyn.

Model (shared/spec/verification.md, "Peers for side-by-side benchmarks"): three RigidBody2D
(crank 0.05 m / 0.343 kg / 0.000216 kg m^2, rod 0.30 m / 1.072 kg / 0.034 kg m^2, slider
0.347 kg / 0.000115 kg m^2, centres of mass at the link mid-points and the slider pin), ideal
revolute joints ground-crank and crank-rod, a prismatic joint ground-slider along x (rotation
locked), the crank driven at a constant 5000 rpm by a velocity-level coordinate constraint on its
rotation, gravity 9.81 m/s^2 along -y. The rod-slider joint is a clearance joint: an
ObjectContactSphereSphere between the journal (sphere 0, radius 9.5 mm, on the rod end) and the
bearing (sphere 1, radius 10 mm, hollow: isHollowSphere1=True, on the slider), all in z = 0, so
the gap is r1 - r0 - |p1 - p0| as in the planar journal bearing. Normal law: stiffness
K = (4/3) E* sqrt(R_i R_j / (R_i - R_j)) (Hertz internal cylinder, Flores et al. 2004, steel
E = 207 GPa, nu = 0.3), exponent 1.5, impact model 1 (Hunt-Crossley, damping 1.5 (1 - e) K / v-)
with e = (1 + c_e^2) / 2, which is Lankarani-Nikravesh with c_e = 0.9; no friction, no linear
damping. Initial state: theta = 0, ideal-joint velocities, journal centred.

Solver: generalized-alpha with a fixed step h (default 1e-5 and 1e-6),
timeIntegration.discontinuous.useRecommendedStepSize = False.

Prints one JSON object per line: {"solver", "h", "wall_s", "repeats", "steps", "times", "x"}
with the slider position at --times and at t_end. Only exu.SolveDynamic is timed.
"""

import argparse
import json
import math
import statistics
import sys
import time
import warnings

import exudyn as exu

# the settings names used here work in 1.13 with a DeprecationWarning (renamed since 1.12)
warnings.filterwarnings("ignore", category=DeprecationWarning)
from exudyn.itemInterface import (
    MarkerBodyMass,
    MarkerBodyPosition,
    MarkerBodyRigid,
    MarkerNodeCoordinate,
    NodeGenericData,
    NodePointGround,
    NodeRigidBody2D,
    ObjectConnectorCoordinate,
    ObjectContactSphereSphere,
    ObjectGround,
    ObjectJointPrismatic2D,
    ObjectJointRevolute2D,
    ObjectRigidBody2D,
    LoadMassProportional,
)

CRANK, ROD = 0.05, 0.30
M_CRANK, M_ROD, M_SLIDER = 0.343, 1.072, 0.347
I_CRANK, I_ROD, I_SLIDER = 0.000216, 0.034, 0.000115
R_BEARING, R_JOURNAL = 10.0e-3, 9.5e-3
G = 9.81
E, NU = 207e9, 0.3


def build(omega, c_e):
    """The Exudyn system; returns (SystemContainer, MainSystem, slider node)."""
    sc = exu.SystemContainer()
    mbs = sc.AddSystem()
    ground = mbs.AddObject(ObjectGround())
    r, l = CRANK, ROD

    def body(m, j, pos, vel):
        n = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=pos, initialVelocities=vel))
        o = mbs.AddObject(ObjectRigidBody2D(mass=m, inertia=j, nodeNumber=n))
        mm = mbs.AddMarker(MarkerBodyMass(bodyNumber=o))
        mbs.AddLoad(LoadMassProportional(markerNumber=mm, loadVector=[0.0, -G, 0.0]))
        return n, o

    n_crank, crank = body(M_CRANK, I_CRANK, [r / 2, 0, 0], [0, omega * r / 2, omega])
    _, rod = body(M_ROD, I_ROD, [r + l / 2, 0, 0], [0, omega * r / 2, -omega * r / l])
    n_slider, slider = body(M_SLIDER, I_SLIDER, [r + l, 0, 0], [0, 0, 0])

    def pos(o, p):
        return mbs.AddMarker(MarkerBodyPosition(bodyNumber=o, localPosition=p))

    mbs.AddObject(ObjectJointRevolute2D(markerNumbers=[pos(ground, [0, 0, 0]),
                                                       pos(crank, [-r / 2, 0, 0])]))
    mbs.AddObject(ObjectJointRevolute2D(markerNumbers=[pos(crank, [r / 2, 0, 0]),
                                                       pos(rod, [-l / 2, 0, 0])]))
    def rigid(o, p):
        return mbs.AddMarker(MarkerBodyRigid(bodyNumber=o, localPosition=p))

    mbs.AddObject(ObjectJointPrismatic2D(markerNumbers=[rigid(ground, [0, 0, 0]),
                                                        rigid(slider, [0, 0, 0])],
                                         axisMarker0=[1, 0, 0], normalMarker1=[0, 1, 0],
                                         constrainRotation=True))
    # crank drive: d(theta_crank)/dt - d(0)/dt = omega
    n_ground = mbs.AddNode(NodePointGround())
    m_g = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=n_ground, coordinate=0))
    m_th = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=n_crank, coordinate=2))
    mbs.AddObject(ObjectConnectorCoordinate(markerNumbers=[m_g, m_th], offset=omega,
                                            velocityLevel=True))
    # clearance joint: journal (sphere 0) on the rod end, hollow bearing (sphere 1) on the slider
    e_star = 1.0 / (2.0 * (1.0 - NU * NU) / E)
    k = 4.0 / 3.0 * e_star * math.sqrt(R_BEARING * R_JOURNAL / (R_BEARING - R_JOURNAL))
    m_j = rigid(rod, [l / 2, 0, 0])
    m_b = rigid(slider, [0, 0, 0])
    n_data = mbs.AddNode(NodeGenericData(numberOfDataCoordinates=4,
                                         initialCoordinates=[0.0, 0.0, 0.0, 0.0]))
    mbs.AddObject(ObjectContactSphereSphere(
        markerNumbers=[m_j, m_b], nodeNumber=n_data,
        spheresRadii=[R_JOURNAL, R_BEARING], isHollowSphere1=True,
        contactStiffness=k, contactDamping=0.0, contactStiffnessExponent=1.5,
        restitutionCoefficient=0.5 * (1.0 + c_e * c_e), impactModel=1,
        dynamicFriction=0.0))
    mbs.Assemble()
    return sc, mbs, n_slider


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


def run(h, omega, c_e, t_end, times):
    """One solve; returns (wall time of SolveDynamic, slider x at times, steps)."""
    from exudyn.itemInterface import SensorNode

    sc, mbs, n_slider = build(omega, c_e)
    sens = mbs.AddSensor(SensorNode(nodeNumber=n_slider, storeInternal=True,
                                    outputVariableType=exu.OutputVariableType.Position))
    mbs.Assemble()
    # output times on the step grid: the stored sample at the step (written every 1e-4 s);
    # otherwise (e.g. h = 3e-6) every step is stored and the value interpolated linearly between
    # the two steps around t (error ~ h^2/8 |x''|, below 1e-9 m here)
    on_grid = all(abs(t / h - round(t / h)) < 1e-6 for t in times)
    s = settings(h, t_end, max(h, 1e-4) if on_grid else h)
    start = time.perf_counter()
    ok = mbs.SolveDynamic(s, solverType=exu.DynamicSolverType.GeneralizedAlpha)
    wall = time.perf_counter() - start
    if ok is False:
        raise RuntimeError("SolveDynamic reported failure")
    data = mbs.GetSensorStoredData(sens)
    ts, xs = data[:, 0], data[:, 1]
    out = []
    for t in times:
        i = int(abs(ts - t).argmin())
        if on_grid or abs(ts[i] - t) <= 1e-3 * h:
            if abs(ts[i] - t) > 0.5 * h:
                raise RuntimeError(f"no stored sensor value at t = {t} (nearest {ts[i]})")
            out.append(float(xs[i]))
            continue
        j = i if ts[i] < t else i - 1
        if j < 0 or j + 1 >= len(ts) or not (ts[j] <= t <= ts[j + 1]):
            raise RuntimeError(f"no stored sensor values around t = {t}")
        w = (t - ts[j]) / (ts[j + 1] - ts[j])
        out.append(float((1.0 - w) * xs[j] + w * xs[j + 1]))
    return wall, out, s.timeIntegration.numberOfSteps


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--h", default="1e-5,1e-6")
    ap.add_argument("--t-end", type=float, default=0.1)
    ap.add_argument("--times", default="0.005,0.01")
    ap.add_argument("--rpm", type=float, default=5000.0)
    ap.add_argument("--restitution", type=float, default=0.9)
    ap.add_argument("--min-time", type=float, default=2.0)
    ap.add_argument("--max-repeats", type=int, default=5)
    a = ap.parse_args()
    omega = a.rpm * math.pi / 30.0
    times = [float(s) for s in a.times.split(",")] + [a.t_end]
    for h in [float(s) for s in a.h.split(",")]:
        walls, out = [], None
        try:
            while True:
                wall, xs, steps = run(h, omega, a.restitution, a.t_end, times)
                walls.append(wall)
                out = (xs, steps)
                if len(walls) >= a.max_repeats or sum(walls) >= a.min_time:
                    break
        except Exception as e:  # report and go on with the next step size
            print(f"exudyn_slider_crank: h = {h} failed: {e}", file=sys.stderr)
            continue
        xs, steps = out
        print(json.dumps({
            "solver": "exudyn-genalpha", "h": h, "exudyn_version": exu.__version__,
            "wall_s": statistics.median(walls), "repeats": len(walls), "steps": int(steps),
            "times": times, "x": xs,
        }), flush=True)


if __name__ == "__main__":
    main()
