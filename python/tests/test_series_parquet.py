"""``clr run --series parquet|both`` and ``clr sweep --keep series --series parquet``: the
Parquet files read back in pandas (through pyarrow) equal the CSV files value for value, bit for
bit (issue 34's "Done when"), and carry the units as the ``clr.units`` metadata.

The CSV is read with pandas' round-trip float parser, so both sides are the exact doubles that
clr wrote. .ci/run installs pyarrow; without it the test fails rather than skips."""

import json
import os
import subprocess
from pathlib import Path

import numpy as np
import pandas as pd

ROOT = Path(__file__).resolve().parents[2]


def clr() -> str:
    exe = os.environ.get("CLR_BIN") or str(ROOT / "target" / "debug" / "clr")
    assert Path(exe).is_file(), f"no clr binary at {exe} (cargo build, or set CLR_BIN)"
    return exe


def read_csv(path: Path) -> pd.DataFrame:
    # pandas 3 parses floats round-trip by default and deprecates the option
    if int(pd.__version__.split(".")[0]) >= 3:
        return pd.read_csv(path)
    return pd.read_csv(path, float_precision="round_trip")


def same_bits(a: np.ndarray, b: np.ndarray) -> bool:
    a, b = np.ascontiguousarray(a, dtype=np.float64), np.ascontiguousarray(b, dtype=np.float64)
    return a.shape == b.shape and np.array_equal(a.view(np.uint64), b.view(np.uint64))


def check_folder(d: Path) -> None:
    import pyarrow.parquet as pq

    csv = read_csv(d / "results.csv")
    par = pd.read_parquet(d / "results.parquet")
    names = [h.rsplit(" [", 1)[0] for h in csv.columns]
    units = [h.rsplit(" [", 1)[1].rstrip("]") for h in csv.columns]
    assert list(par.columns) == names
    assert same_bits(csv.to_numpy(), par.to_numpy())
    meta = pq.read_schema(d / "results.parquet").metadata
    assert json.loads(meta[b"clr.units"]) == dict(zip(names, units))
    ci, pi = read_csv(d / "impacts.csv"), pd.read_parquet(d / "impacts.parquet")
    assert list(ci.columns) == list(pi.columns) and len(ci) == len(pi) > 0
    assert list(ci["joint"].astype(str)) == list(pi["joint"].astype(str))
    num = ci.columns[1:]
    # an impact under way at the end: an empty CSV cell and a Parquet null, both NaN here
    assert same_bits(ci[num].to_numpy(), pi[num].to_numpy())


def run(out: Path, t_end: str, series: str) -> None:
    subprocess.run(
        [clr(), "run", "slider_crank", "--t-end", t_end, "--series", series,
         "--no-figures", "--no-report", "-q", "--out", str(out)],
        check=True, capture_output=True,
    )


def test_run_parquet_equals_csv(tmp_path):
    run(tmp_path / "run", "0.05", "both")
    check_folder(tmp_path / "run")


def test_parquet_only_writes_no_csv(tmp_path):
    out = tmp_path / "run"
    run(out, "0.01", "parquet")
    assert (out / "results.parquet").is_file() and not (out / "results.csv").exists()
    assert not (out / "impacts.csv").exists()


def test_sweep_points_keep_parquet_series(tmp_path):
    out = tmp_path / "sweep"
    subprocess.run(
        [clr(), "sweep", "slider_crank", "--t-end", "0.05", "--vary",
         "journal_radius=0.0095,0.0098", "--keep", "series", "--series", "both",
         "--no-figures", "--no-report", "-q", "--out", str(out)],
        check=True, capture_output=True,
    )
    points = sorted(out.glob("point-*"))
    assert len(points) == 2
    for p in points:
        check_folder(p)
