"""``clr_sim.sweep(..., executor=...)``: the points sent to any
``concurrent.futures.Executor`` as plain descriptions come back as the same ``SweepResult``
as the threaded sweep, value for value (every column and metric, bit for bit): a process pool
(spawn), a thread pool, and dask.distributed's ``LocalCluster`` when dask is installed
(.ci/run installs it)."""

import math
import multiprocessing
import pathlib
from concurrent.futures import ProcessPoolExecutor, ThreadPoolExecutor

import numpy as np
import pytest

import clr_sim

ROOT = pathlib.Path(__file__).resolve().parents[2]
SLIDER_CRANK = ROOT / "tests" / "data" / "slider_crank.toml"
VARY = {"clearance.B.journal_radius": [0.0095, 0.0098], "solver.rtol": [1e-6, 1e-7]}


def same(a: clr_sim.SweepResult, b: clr_sim.SweepResult) -> None:
    assert a.names == b.names and len(a) == len(b) == 4
    for (ka, va, ra), (kb, vb, rb) in zip(a, b):
        assert ka == kb and va == vb
        assert ra.error == rb.error is None
        assert set(ra.columns) == set(rb.columns)
        for c in ra.columns:
            assert np.array_equal(ra.columns[c], rb.columns[c], equal_nan=True), (ka, c)
        assert ra.metrics.keys() == rb.metrics.keys()
        for m, x in ra.metrics.items():
            y = rb.metrics[m]
            assert x == y or (math.isnan(x) and math.isnan(y)), (ka, m, x, y)


@pytest.fixture(scope="module")
def threaded():
    return clr_sim.sweep(SLIDER_CRANK, VARY, t_end=0.004, jobs=2, progress=False)


def test_a_process_pool_sweep_equals_the_threaded_sweep(threaded):
    spawn = multiprocessing.get_context("spawn")
    with ProcessPoolExecutor(max_workers=2, mp_context=spawn) as ex:
        s = clr_sim.sweep(SLIDER_CRANK, VARY, t_end=0.004, executor=ex, progress=False)
    same(threaded, s)


def test_a_model_sent_to_threads_equals_the_threaded_sweep(threaded):
    # a Model goes out as its TOML text
    model = clr_sim.Model.from_file(SLIDER_CRANK)
    with ThreadPoolExecutor(max_workers=2) as ex:
        s = clr_sim.sweep(model, VARY, t_end=0.004, executor=ex, progress=False)
    same(threaded, s)
    # a bad value is refused before anything is submitted
    with ThreadPoolExecutor(max_workers=1) as ex:
        with pytest.raises(clr_sim.ModelError):
            clr_sim.sweep(model, {"clearance.B.journal_radius": [-1.0]}, executor=ex)
        with pytest.raises(clr_sim.ModelError, match="executor"):
            clr_sim.sweep(model, VARY, executor=ex, jobs=2)


def test_a_dask_local_cluster_sweep_equals_the_threaded_sweep(threaded):
    distributed = pytest.importorskip("dask.distributed")
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster, distributed.Client(cluster) as client:
        s = clr_sim.sweep(
            SLIDER_CRANK, VARY, t_end=0.004, executor=client.get_executor(), progress=False
        )
    same(threaded, s)


class _Job:
    """A submitit-like job: ``done()`` and ``result()``, not a ``concurrent.futures.Future``;
    done only from its second ``done()`` call, so the sweep has to poll."""

    def __init__(self, value):
        self.value, self.polls = value, 0

    def done(self):
        self.polls += 1
        return self.polls > 1

    def result(self):
        assert self.polls > 1, "result() before done()"
        return self.value


class _SubmititLike:
    """Runs each point at submit and hands back a :class:`_Job` (the shape of submitit's
    ``AutoExecutor``, which cluster-check tests on Slurm itself)."""

    def __init__(self):
        self.jobs = []

    def submit(self, fn, *args):
        self.jobs.append(_Job(fn(*args)))
        return self.jobs[-1]


def test_an_executor_of_polled_jobs_equals_the_threaded_sweep(threaded):
    ex = _SubmititLike()
    s = clr_sim.sweep(SLIDER_CRANK, VARY, t_end=0.004, executor=ex, progress=False)
    same(threaded, s)
    assert len(ex.jobs) == 4 and all(j.polls >= 2 for j in ex.jobs)
