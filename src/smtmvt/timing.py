"""Seconds spent per stage of the tracker (``Tracker.timings``, read by ``bench/``)."""

from __future__ import annotations

import time
from collections import defaultdict
from collections.abc import Iterator
from contextlib import contextmanager

__all__ = ["StageTimer"]


class StageTimer:
    """Adds up the time of blocks, per stage name, in :attr:`seconds`."""

    def __init__(self) -> None:
        #: stage name -> seconds
        self.seconds: defaultdict[str, float] = defaultdict(float)
        self._open: set[str] = set()  # the stages being timed now

    @contextmanager
    def timed(self, stage: str) -> Iterator[None]:
        """Add the block's time to ``seconds[stage]``, once: a block of a stage
        already being timed (a deferred view's features inside the coding's)
        is not counted again."""
        if stage in self._open:
            yield
            return
        self._open.add(stage)
        t0 = time.perf_counter()
        try:
            yield
        finally:
            self.seconds[stage] += time.perf_counter() - t0
            self._open.discard(stage)
