"""How many threads the tracker's per-candidate work uses (``TrackerConfig.threads``).

The coding's compiled kernel (:mod:`smtmvt.solvers._admm_kernel`) runs its
per-candidate loops, and its products with each view's dictionary, on numba's
threads; every candidate's arithmetic is the same for any number of threads,
so the boxes are too (``tests/test_threads.py``).

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
from collections.abc import Iterator

import numba

__all__ = ["ENV", "default_threads", "resolve", "set_default", "limit", "current"]

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
