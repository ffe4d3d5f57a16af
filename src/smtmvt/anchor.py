"""Anchor term: keep the box on what the first frame showed.

The templates follow the target's appearance (:mod:`smtmvt.templates`), and
so they also follow the box when it slides off the target: once a few of
them hold background, the dictionary explains the wrong box better than the
true one. ``bench/diagnose.py`` calls such frames *drift*: scored over the
first frame's templates the true box still wins (measured on Singer2's lost
seed: 29 of the 44 first frames, from frame 17 on).

The anchor term adds to each candidate's residual its nonnegative
least-squares residual over the first template alone (the exact first-frame
target, never replaced): for unit views ``x^k`` and ``t^k``,
``min_{c >= 0} ||c t^k - x^k||^2 = 1 - max(x^k . t^k, 0)^2``, summed over the
views computed for every candidate. With weight ``mu`` the likelihood becomes
``exp(-alpha (r_i + mu a_i))`` (:func:`anchor_offsets`), known before coding
like the background term (:func:`smtmvt.likelihood.observe`'s ``offset``).
"""

from __future__ import annotations

import numpy as np

__all__ = ["anchor_residuals", "anchor_offsets"]


def anchor_residuals(X, T) -> np.ndarray:
    """``sum_k min_{c >= 0} ||c t^k - x_i^k||^2`` for every candidate, ``(n,)`` float64 >= 0.

    Parameters
    ----------
    X : list of K (d_k, n) candidate views.
    T : list of K (d_k,) views of the first template (nonzero).

    Each term is ``||x||^2 - max(x . t, 0)^2 / ||t||^2``: for unit views
    ``1 - max(cos, 0)^2`` (clipped at 0 against rounding).
    """
    a = np.zeros(X[0].shape[1])
    for Xk, tk in zip(X, T):
        x = np.asarray(Xk, dtype=np.float64)
        t = np.asarray(tk, dtype=np.float64)
        a += np.einsum("ij,ij->j", x, x) - np.maximum(t @ x, 0.0) ** 2 / (t @ t)
    return np.maximum(a, 0.0)


def anchor_offsets(X, T, mu: float) -> np.ndarray:
    """The anchor term ``mu a_i`` of every candidate, ``(n,)`` float64 >= 0 (``mu >= 0``)."""
    if not mu >= 0:
        raise ValueError(f"anchor weight must be >= 0, got {mu!r}")
    return mu * anchor_residuals(X, T)
