"""``TrackerConfig.threads`` (issue 49 item 4): the per-candidate work on several
threads gives the same numbers, bit for bit, as on one; how ``threads=None``
resolves; and ``smtmvt evaluate``'s workers keep one thread."""

from __future__ import annotations

import numpy as np
import pytest

from smtmvt import Tracker, TrackerConfig, threads
from smtmvt.demo import make_demo_sequence
from smtmvt.evaluation.workers import WORKER_ENV
from smtmvt.solvers import smtmvt as solver
from smtmvt.solvers._admm_kernel import PARALLEL_MIN


def _problem(n: int, seed: int = 0):
    rng = np.random.default_rng(seed)
    D = [np.abs(rng.standard_normal((d, 8))) for d in (60, 27, 16, 31)]
    X = [Dk @ np.abs(rng.standard_normal((8, n))) * 0.2 + 0.05 * rng.standard_normal((Dk.shape[0], n)) for Dk in D]
    return X, D


def test_solver_same_bits_on_two_threads():
    X, D = _problem(2 * PARALLEL_MIN + 7)
    with threads.limit(1):
        C1, E1 = solver.solve_smtmvt(X, D, tol=1e-5, max_iter=300)
    with threads.limit(2) as n:
        C2, E2 = solver.solve_smtmvt(X, D, tol=1e-5, max_iter=300)
    assert n == min(2, threads.resolve(2))
    assert np.array_equal(C1, C2)
    assert all(np.array_equal(a, b) for a, b in zip(E1, E2, strict=True))


def test_tracker_same_boxes_on_one_and_two_threads(monkeypatch):
    # prune_eps=0 codes every particle, so the threaded kernel runs every frame (the
    # bounded coding's batches, tens of candidates, stay on one thread: PARALLEL_MIN)
    from smtmvt.solvers import _admm_kernel

    seq = make_demo_sequence(n_frames=4)
    boxes = {}
    for n in (1, 2):
        runs = {"parallel": 0}
        parallel = _admm_kernel._run_parallel

        def counted(*args, _parallel=parallel, _runs=runs):
            _runs["parallel"] += 1
            return _parallel(*args)

        monkeypatch.setattr(_admm_kernel, "_run_parallel", counted)
        config = TrackerConfig.paper(seed=0, threads=n, prune_eps=0.0, n_particles=2 * PARALLEL_MIN + 8)
        tracker = Tracker(config)
        tracker.init(seq.frames[0], seq.groundtruth[0])
        boxes[n] = [tracker.update(f).box for f in seq.frames[1:]]
        assert (runs["parallel"] > 0) == (threads.resolve(n) > 1)
    assert boxes[1] == boxes[2]


def test_threads_resolve(monkeypatch):
    monkeypatch.delenv(threads.ENV, raising=False)
    assert threads.resolve(1) == 1
    assert 1 <= threads.resolve(None) <= threads.numba.config.NUMBA_NUM_THREADS
    monkeypatch.setenv(threads.ENV, "1")
    assert threads.resolve(None) == 1
    assert threads.resolve(2) == min(2, threads.numba.config.NUMBA_NUM_THREADS)  # an explicit count wins
    monkeypatch.setenv(threads.ENV, "zero")
    with pytest.raises(ValueError, match="SMTMVT_THREADS"):
        threads.resolve(None)
    monkeypatch.setenv(threads.ENV, "3")
    threads.set_default(1)
    try:
        assert threads.resolve(None) == 1
    finally:
        threads.set_default(None)
    assert threads.current() == 1
    with threads.limit(1):
        assert threads.current() == 1
    assert threads.current() == 1


def test_workers_keep_one_thread():
    assert WORKER_ENV[threads.ENV] == "1"
    assert TrackerConfig().threads is None
    with pytest.raises(ValueError, match="threads"):
        TrackerConfig(threads=0)


def test_color_histograms_same_on_two_threads():
    from smtmvt.features.color import _grid_histograms

    rng = np.random.default_rng(3)
    colors = rng.random((201, 12, 10, 3)).astype(np.float32)
    with threads.limit(1):
        one = _grid_histograms(colors, 2, 8)
    with threads.limit(2):
        two = _grid_histograms(colors, 2, 8)
    assert np.array_equal(one, two)


def test_run_blocks_covers_and_raises():
    seen = []
    with threads.limit(2) as n:
        threads.run_blocks(lambda b: seen.append((b.start, b.stop)), 300, per=64)
        assert sorted(seen) == ([(0, 150), (150, 300)] if n == 2 else [(0, 300)])

        def fail(b):
            if b.start:
                raise RuntimeError("block")

        if n == 2:
            with pytest.raises(RuntimeError, match="block"):
                threads.run_blocks(fail, 300, per=64)
