"""How many threads the tracker's per-candidate work uses (``TrackerConfig.threads``).

The coding's compiled kernel (:mod:`smtmvt.solvers._admm_kernel`) runs its
per-candidate loops, and its products with each view's dictionary, on numba's
threads; a compiled feature kernel that treats each candidate on its own (the
color view's histograms) runs on blocks of candidates, one per thread
(:func:`run_blocks`). Every candidate's arithmetic is the same for any number
of threads, so the boxes are too (``tests/test_threads.py``).

``threads=None`` (the default) means :func:`default_threads`: the
``SMTMVT_THREADS`` environment variable where set, else every core this
process may run on. ``smtmvt evaluate``'s workers set it to 1
(:data:`smtmvt.evaluation.workers.WORKER_ENV`, and :func:`set_default` in a
pair run among others), so that workers and threads do not oversubscribe the
cores; a tracker option ``threads=N`` still wins there.
"""

from __future__ import annotations

import contextlib
import os
import threading
from collections.abc import Callable, Iterator
from concurrent.futures import ThreadPoolExecutor

import numba

__all__ = ["ENV", "default_threads", "resolve", "set_default", "limit", "current", "run_blocks"]

#: The environment variable read by :func:`default_threads`.
ENV = "SMTMVT_THREADS"

_default: int | None = None  # set_default's
_local = threading.local()  # .threads: limit's, in this thread


def _cores() -> int:
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # not on Linux
        return os.cpu_count() or 1


def default_threads() -> int:
    """The threads of ``threads=None``: :func:`set_default`'s, else ``SMTMVT_THREADS``,
    else the cores this process may use."""
    if _default is not None:
        return _default
    text = os.environ.get(ENV, "").strip()
    if text:
        try:
            value = int(text)
        except ValueError:
            raise ValueError(f"{ENV}={text!r}: expected a whole number >= 1") from None
        if value < 1:
            raise ValueError(f"{ENV}={text!r}: expected a whole number >= 1")
        return value
    return _cores()


def set_default(threads: int | None) -> None:
    """Make ``threads=None`` mean ``threads`` in this process (None: back to
    ``SMTMVT_THREADS`` or the cores)."""
    global _default
    _default = None if threads is None else max(1, int(threads))


def resolve(threads: int | None) -> int:
    """``TrackerConfig.threads`` -> the threads used: at most numba's pool
    (``NUMBA_NUM_THREADS``, by default the machine's cores)."""
    wanted = default_threads() if threads is None else int(threads)
    return max(1, min(wanted, numba.config.NUMBA_NUM_THREADS))  # type: ignore[attr-defined]


def current() -> int:
    """The threads the per-candidate work of this thread may use now: :func:`limit`'s
    inside one, else 1 (a solver called outside a tracker runs on one thread)."""
    return getattr(_local, "threads", 1)


@contextlib.contextmanager
def limit(threads: int | None) -> Iterator[int]:
    """Run the block with :func:`resolve`'s threads (:func:`current`; numba's setting
    for this thread, restored after); yields the number. At one thread numba's pool
    is left alone (never started)."""
    n = resolve(threads)
    before = current()
    _local.threads = n
    try:
        if n == 1:
            yield n
            return
        pool = numba.get_num_threads()
        numba.set_num_threads(n)
        try:
            yield n
        finally:
            numba.set_num_threads(pool)
    finally:
        _local.threads = before


_pool: ThreadPoolExecutor | None = None
_pool_key: tuple[int, int] = (0, 0)  # (process id, workers) of _pool


def _executor(workers: int) -> ThreadPoolExecutor:
    """The process's pool of at least ``workers`` threads (made again after a fork)."""
    global _pool, _pool_key
    if _pool is None or _pool_key[0] != os.getpid() or _pool_key[1] < workers:
        _pool = ThreadPoolExecutor(max_workers=workers, thread_name_prefix="smtmvt")
        _pool_key = (os.getpid(), workers)
    return _pool


def run_blocks(fn: Callable[[slice], object], n: int, per: int = 64) -> None:
    """``fn(block)`` for consecutive blocks of ``range(n)`` covering it, one per
    thread of :func:`current` and at least ``per`` long (all of it in one call
    on one thread): for a compiled kernel that releases the GIL and treats each
    item on its own, writing its results in place. The first block runs in this
    thread; an exception of any block is raised here."""
    k = max(1, min(current(), n // max(1, per)))
    if k == 1:
        fn(slice(0, n))
        return
    cuts = [i * n // k for i in range(k + 1)]
    blocks = [slice(a, b) for a, b in zip(cuts, cuts[1:])]
    futures = [_executor(k - 1).submit(fn, b) for b in blocks[1:]]
    try:
        fn(blocks[0])
    finally:
        for f in futures:
            f.result()
