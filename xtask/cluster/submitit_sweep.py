"""Run by `cargo xtask cluster-check`: ``clr_sim.sweep(..., executor=submitit.AutoExecutor)``
on the check's single-node Slurm cluster equals the threaded ``clr_sim.sweep`` of the same
points, every column and metric bit for bit (issue 34's "Done when").

Arguments: the submitit folder (job scripts, pickles and logs). Exit code 0 when equal, 1 with
the first difference otherwise. The cluster has no accounting, so submitit's status calls to
``sacct`` fail (it logs "Bypassing sacct error" and goes on); a job is done when its result
pickle appears."""

import logging
import math
import pathlib
import sys
import time

import numpy as np
import submitit

import clr_sim

ROOT = pathlib.Path(__file__).resolve().parents[2]
MODEL = ROOT / "tests" / "data" / "slider_crank.toml"
VARY = {"clearance.B.journal_radius": [0.0095, 0.0098], "solver.rtol": [1e-6, 1e-7]}
T_END = 0.004


def main(folder: str) -> int:
    logging.getLogger("submitit").setLevel(logging.ERROR)  # the sacct warnings
    executor = submitit.AutoExecutor(folder=folder, cluster="slurm")
    executor.update_parameters(timeout_min=5, cpus_per_task=1, slurm_job_name="clr-submitit")
    start = time.monotonic()
    remote = clr_sim.sweep(MODEL, VARY, t_end=T_END, executor=executor, progress=False)
    wall = time.monotonic() - start
    local = clr_sim.sweep(MODEL, VARY, t_end=T_END, jobs=2, progress=False)
    if remote.names != local.names or len(remote) != len(local):
        print(f"submitit sweep: {len(remote)} points {remote.names}, threads: {len(local)}")
        return 1
    for (ka, va, ra), (kb, vb, rb) in zip(remote, local):
        if (ka, va) != (kb, vb) or ra.error or rb.error:
            print(f"point {ka} {va}: {ra.error} / {kb} {vb}: {rb.error}")
            return 1
        if set(ra.columns) != set(rb.columns):
            print(f"point {ka}: other columns")
            return 1
        for c in ra.columns:
            if not np.array_equal(ra.columns[c], rb.columns[c], equal_nan=True):
                print(f"point {ka}: column {c} differs")
                return 1
        for m, x in ra.metrics.items():
            y = rb.metrics.get(m)
            if y is None or not (x == y or (math.isnan(x) and math.isnan(y))):
                print(f"point {ka}: metric {m} {x} against {y}")
                return 1
    print(f"{len(remote)} points through submitit on Slurm in {wall:.1f} s = threaded sweep")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
