"""Background term: tell the target from what surrounds it.

The paper's likelihood asks only how well the target templates explain a
candidate. When a similar object passes near the target (another player,
another pedestrian) it is explained almost as well, and the box may switch
to it. Discriminative sparse trackers (SCM: Zhong, Lu and Yang, CVPR 2012)
also code each candidate over *background* templates, sampled around the
target, and score ``eps_f - eps_b``: a candidate the background explains
well is background.

Here the background dictionary of a frame is the views of ``m`` boxes of the
target's size on a ring around it (:func:`ring_states`), taken in the
previous frame around the box estimated there (where they do not overlap the
target; a ring around the *predicted* position in the current frame would
cover a fast target that outran the prediction). Each candidate's background
residual ``b_i`` (:func:`background_residuals`, on the views computed for
every candidate) is its squared distance to the nearest of them, or its
nonnegative least-squares residual over them, and its likelihood becomes
``exp(-alpha (r_i + beta (b_max - b_i)))`` (:func:`background_offsets`):
the paper's when ``beta`` is 0, and never above it (``b_max`` is the
largest ``b_i``), so a likelihood stays in (0, 1].
"""

from __future__ import annotations

import numpy as np

from .geometry import affine_to_box
from .solvers.bounds import nonnegative_residuals

__all__ = ["ring_states", "background_residuals", "background_offsets", "RING_RADII"]

#: Distances of the ring's boxes from the target's centre, in target widths
#: along x and heights along y: a box 0.75 beside the target overlaps it by
#: an IoU of 0.14 at most; at 1.25 it no longer touches it.
RING_RADII = (0.75, 1.25)


def ring_states(state, m: int, rng: np.random.Generator, radii=RING_RADII) -> np.ndarray:
    """``m`` affine states of the target's shape on a ring around it.

    Parameters
    ----------
    state : (6,) affine state of the target (its last estimate).
    m : number of states (>= 1).
    rng : the tracker's seeded generator (one rotation of the ring and ``m``
        radii drawn per call).
    radii : (lo, hi); box ``j`` is at angle ``2 pi (j + u) / m`` (``u``
        uniform in [0, 1), one per call) and at a distance drawn uniformly in
        ``[lo, hi]`` times the target's width along x and height along y.

    Returns
    -------
    (m, 6) float64 states: ``state`` with its translation moved.
    """
    if int(m) < 1:
        raise ValueError(f"ring_states: m must be >= 1, got {m}")
    lo, hi = (float(r) for r in radii)
    if not 0 < lo <= hi:
        raise ValueError(f"ring_states: radii must satisfy 0 < lo <= hi, got {radii!r}")
    m = int(m)
    s = np.asarray(state, dtype=np.float64).reshape(6)
    _, _, w, h = affine_to_box(s)
    angle = 2.0 * np.pi * (np.arange(m) + rng.random()) / m
    radius = rng.uniform(lo, hi, size=m)
    out = np.repeat(s[None], m, axis=0)
    out[:, 4] += radius * w * np.cos(angle)
    out[:, 5] += radius * h * np.sin(angle)
    return out


def background_residuals(X, B, measure: str = "nearest") -> np.ndarray:
    """Each candidate's residual over the background views, ``(n,)`` float64 >= 0.

    Parameters
    ----------
    X : list of K (d_k, n) candidate views (unit columns).
    B : list of K (d_k, m) background views (the same views of the ring's
        boxes, :func:`ring_states`).
    measure : ``"nearest"``: the squared distance to the nearest background
        box, ``min_j sum_k ||x_i^k - b_j^k||^2`` (one product per view);
        ``"nnls"``: the nonnegative least-squares residual ``sum_k min_{c >=
        0} ||B^k c - x_i^k||^2`` (a candidate explained by a mixture of
        background boxes, as SCM's sparse coding over them; about 30 times
        the cost).
    """
    if measure == "nnls":
        return nonnegative_residuals(X, B)
    if measure != "nearest":
        raise ValueError(f"background measure must be 'nearest' or 'nnls', got {measure!r}")
    d = np.zeros((B[0].shape[1], X[0].shape[1]))
    for Xk, Bk in zip(X, B):
        x = np.asarray(Xk, dtype=np.float64)
        b = np.asarray(Bk, dtype=np.float64)
        d += np.einsum("ij,ij->j", x, x)[None, :] + np.einsum("ij,ij->j", b, b)[:, None] - 2.0 * (b.T @ x)
    return np.maximum(d.min(axis=0), 0.0)


def background_offsets(X, B, beta: float, measure: str = "nearest") -> np.ndarray:
    """Each candidate's background term ``beta (b_max - b_i)``, ``(n,)`` float64 >= 0.

    ``b_i`` is :func:`background_residuals` (``X``, ``B``, ``measure`` as
    there): small for a candidate that looks like the background around the
    target. Added to the residual in the likelihood
    (:func:`smtmvt.likelihood.observe`'s ``offset``), it lowers the
    likelihood of such candidates by ``exp(-alpha beta (b_max - b_i))``
    relative to the one least like the background. ``beta >= 0``.
    """
    if not beta >= 0:
        raise ValueError(f"background weight must be >= 0, got {beta!r}")
    b = background_residuals(X, B, measure)
    return beta * (b.max() - b)
