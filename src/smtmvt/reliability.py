"""Cue reliability: each cue's weight scaled by how well it agrees with the choices on this sequence.

The likelihood adds the cues' costs with fixed weights (:mod:`smtmvt.cues`);
the best weight of a cue differs from sequence to sequence (issue 48). In the
spirit of democratic integration (Triesch and von der Malsburg, Neural
Computation 2001), each cue's cost is multiplied by its *reliability*, read
from how the cue ranked the states chosen so far on this sequence: its
*agreement* at a frame is the share of the candidates it scores worse than
the chosen one (:func:`agreement`; 0.5 is chance), and its reliability is the
mean agreement over the track above chance, ``clip(2 mean - 1, 0, 1)``. A cue
that keeps ranking the chosen states high keeps its weight; one that ranks
them no better than chance stops deciding. The measure does not depend on the
cue's weight or sharpness, the mean runs over the whole track (no time
constant to set), and before the first choice every reliability is 1.
"""

from __future__ import annotations

import numpy as np

__all__ = ["agreement", "Reliability", "Scaled"]


def agreement(cost: np.ndarray, best: int) -> float | None:
    """How highly one cue's ``(n,)`` cost ranks the chosen candidate ``best``:
    the share of the other candidates it finds worse (a tie counts half), in
    [0, 1] (1: the cue's favourite; 0.5: what a cue that knows nothing gives
    on average). None for a flat cost (it cannot rank) or a non-finite one at
    ``best``."""
    c = np.asarray(cost, dtype=np.float64)
    if c.size < 2 or not np.isfinite(c[best]) or np.ptp(c[np.isfinite(c)]) <= 0:
        return None
    worse = np.count_nonzero(c > c[best])
    ties = np.count_nonzero(c == c[best]) - 1
    return float((worse + 0.5 * ties) / (c.size - 1))


class Reliability:
    """The running mean agreement of ``n`` cues (:func:`agreement`).

    :meth:`factors` gives the ``(n,)`` multipliers of their costs (1 for a
    cue not yet observed); :meth:`observe` adds one frame's agreements (a cue
    with no cost that frame, None, is not counted).
    """

    def __init__(self, n: int) -> None:
        self._sum = np.zeros(n)
        self._count = np.zeros(n)

    def factors(self) -> np.ndarray:
        """(n,) float64 in [0, 1]: each cue's mean agreement so far above
        chance, ``clip(2 mean - 1, 0, 1)`` (1 before any)."""
        out = np.ones_like(self._sum)
        seen = self._count > 0
        out[seen] = np.clip(2 * self._sum[seen] / self._count[seen] - 1, 0, 1)
        return out

    def observe(self, costs: list, best: int) -> None:
        """One frame: ``costs[c]`` the cue's ``(n + m,)`` cost (its own weight,
        not scaled by :meth:`factors`) or None, ``best`` the chosen candidate
        (a cue whose cost cannot rank it, :func:`agreement`, is not counted)."""
        for c, cost in enumerate(costs):
            q = None if cost is None else agreement(cost, best)
            if q is not None:
                self._sum[c] += q
                self._count[c] += 1


class Scaled:
    """A cue whose late view costs (:meth:`smtmvt.cues.Cue.view_cost`) are
    multiplied by ``factor`` (what :meth:`smtmvt.cues.sparse.SparseCue.observe`
    reads of the other cues)."""

    def __init__(self, cue, factor: float) -> None:
        self.cue = cue
        self.factor = float(factor)

    def view_cost(self, scene, k: int, view: np.ndarray):
        part = self.cue.view_cost(scene, k, view)
        if part is None or self.factor == 1.0:
            return part
        return part * self.factor
