"""The flap under a PI position controller written in Python, run as an FMU by FMPy's master.

The FMU is the flap actuation linkage of models/examples/flap_fmu.toml (Wan et al. 2022, rigid,
0.1 mm radial clearance in joint J4) with the actuator's extension as an input and the flap
angle as an output. A PI controller (in the `step_finished` callback of `fmpy.simulate_fmu`,
i.e. between communication points of FMPy's own master) commands the extension from the error
between a reference angle and the measured one. The same FMU runs twice: with the clearance, and
with the journal radius set to the bearing's (the FMU parameter `clearance.J4.journal_radius`):
J4 is then an ideal joint.

    python docs/examples/flap_pi_fmu.py [--fmu flap.fmu] [--out docs/figures/flap_pi_fmu]

writes the figure (SVG and PNG) and prints the tracking errors. CI runs it
(python/tests/test_fmu.py). docs/fmu.md shows the figure.
"""

from __future__ import annotations

import argparse
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
MODEL = ROOT / "models" / "examples" / "flap_fmu.toml"

#: Controller: extension = x0 − (KP·e + KI·∫e dt), e = reference − flap angle (a longer
#: actuator turns the flap the other way, hence the minus). m/rad and m/(rad·s).
KP, KI = 0.05, 2.0
#: Nominal extension (the assembled length), m; communication step, s; run length, s.
X0, STEP, DURATION = 0.25, 1e-3, 0.5
#: Journal radii of J4: the model's 0.1 mm clearance, and the bearing's radius (ideal joint).
RADII = {"0.1 mm clearance in J4": 0.0099, "ideal joints": 0.01}


def reference(t: float) -> float:
    """The commanded flap angle, rad: a 0.1 s ramp to 0.1 rad, then held."""
    return 0.1 * min(1.0, t / 0.1)


def build_fmu(path: Path) -> None:
    """`clr fmu` of the model, with J4's journal radius as a parameter."""
    exe = os.environ.get("CLR_BIN") or shutil.which("clr") or str(ROOT / "target" / "release" / "clr")
    subprocess.run(
        [exe, "fmu", str(MODEL), "-o", str(path), "--parameter", "clearance.J4.journal_radius"],
        check=True,
    )


def closed_loop(fmu: Path, radius: float):
    """One closed-loop run under FMPy's master; returns (t, angle, reference, command)."""
    import fmpy
    from fmpy import instantiate_fmu, read_model_description

    md = read_model_description(str(fmu))
    vr = {v.name: v.valueReference for v in md.modelVariables}
    unzipped = fmpy.extract(str(fmu))
    instance = instantiate_fmu(unzipped, md, fmi_type="CoSimulation")
    state = {"integral": 0.0, "rows": []}

    def controller(t: float, recorder) -> bool:
        # called by FMPy's master after each doStep: read the angle, set the next command
        angle = instance.getFloat64([vr["flap.angle"]])[0]
        error = reference(t) - angle
        state["integral"] += error * STEP
        command = X0 - (KP * error + KI * state["integral"])
        instance.setFloat64([vr["actuator_position"]], [command])
        state["rows"].append((t, angle, reference(t), command))
        return True

    try:
        fmpy.simulate_fmu(
            unzipped,
            model_description=md,
            fmu_instance=instance,
            start_time=0.0,
            stop_time=DURATION,
            step_size=STEP,
            output_interval=STEP,
            start_values={"clearance.J4.journal_radius": radius},
            step_finished=controller,
        )
    finally:
        instance.freeInstance()
        shutil.rmtree(unzipped, ignore_errors=True)
    return np.array(state["rows"])


def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--fmu", type=Path, help="an FMU of flap_fmu.toml (default: built here)")
    ap.add_argument("--out", type=Path, default=ROOT / "docs" / "figures" / "flap_pi_fmu")
    args = ap.parse_args(argv)
    tmp = Path(tempfile.mkdtemp())
    fmu = args.fmu or tmp / "flap.fmu"
    if args.fmu is None:
        build_fmu(fmu)
    runs, numbers = {}, {}
    for label, radius in RADII.items():
        t0 = time.perf_counter()
        rows = closed_loop(fmu, radius)
        wall = time.perf_counter() - t0
        runs[label] = rows
        late = rows[rows[:, 0] >= 0.25]
        err = late[:, 1] - late[:, 2]
        # the dominant frequency of the error's oscillation about its mean (Hz)
        spectrum = np.abs(np.fft.rfft(err - err.mean()))
        freq = np.fft.rfftfreq(len(err), STEP)[int(np.argmax(spectrum[1:])) + 1]
        numbers[label] = {
            "rms_error_rad": float(np.sqrt(np.mean(err**2))),
            "peak_to_peak_error_rad": float(np.ptp(err)),
            "dominant_frequency_hz": float(freq),
            "wall_s": wall,
        }
        print(
            f"{label}: tracking error over 0.25-0.5 s: RMS {numbers[label]['rms_error_rad']:.3e} "
            f"rad, peak to peak {numbers[label]['peak_to_peak_error_rad']:.3e} rad, dominant "
            f"frequency {freq:.0f} Hz ({len(rows)} communication steps in {wall:.2f} s)"
        )
    plot(runs, args.out)
    shutil.rmtree(tmp, ignore_errors=True)
    return numbers


def plot(runs, out: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(7.5, 5.5), sharex=True)
    for label, rows in runs.items():
        ax1.plot(rows[:, 0], rows[:, 1], label=label)
        ax2.plot(rows[:, 0], 1e3 * (rows[:, 1] - rows[:, 2]), label=label)
    first = next(iter(runs.values()))
    ax1.plot(first[:, 0], first[:, 2], "k--", lw=0.8, label="reference")
    ax1.set_ylabel("flap angle (rad)")
    ax1.legend(loc="lower right")
    ax2.set_ylabel("tracking error (mrad)")
    ax2.set_xlabel("time (s)")
    ax2.set_ylim(-30, 10)
    ax1.set_title(f"Flap under a PI position controller in Python (FMPy master, step {STEP} s)")
    fig.tight_layout()
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out.with_suffix(".svg"))
    fig.savefig(out.with_suffix(".png"), dpi=110)
    plt.close(fig)


if __name__ == "__main__":
    main(sys.argv[1:])
