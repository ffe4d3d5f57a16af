"""A cheap lower bound on every candidate's reconstruction residual.

For any codes ``C``, candidate i's reconstruction residual
``r_i = sum_k ||D^k c_i^k - x_i^k||^2`` (the residual of the likelihood
``exp(-alpha r_i)``) is at least its least-squares residual over the same
templates, ``b_i = sum_k min_c ||D^k c - x_i^k||^2``: the least-squares code
has no sign constraint and no penalty, so no code of any model reconstructs
better. Hence ``exp(-alpha b_i)`` bounds the candidate's likelihood from above
(the bound of L1-APG's bounded particle resampling, Mei et al., CVPR 2011).

``b_i = sum_k ||x_i^k||^2 - ||Q_k' x_i^k||^2`` with ``Q_k`` an orthonormal basis
of the range of ``D^k``: one (r_k x d_k) by (d_k x n) product per view for all
candidates.
"""

from __future__ import annotations

import numpy as np

__all__ = ["least_squares_residuals", "range_basis"]


def range_basis(Dk: np.ndarray, rtol: float = 1e-10) -> np.ndarray:
    """Orthonormal basis ``(d, r)`` float64 of the range of ``Dk (d, N)``.

    Singular directions below ``rtol * s_max`` are dropped (duplicate or
    zero templates), so ``r <= N``; a zero dictionary gives ``r = 0``.
    """
    U, s, _ = np.linalg.svd(np.asarray(Dk, dtype=np.float64), full_matrices=False)
    keep = s > rtol * (s[0] if s.size else 0.0)
    return U[:, keep]


def least_squares_residuals(X, D, bases=None) -> np.ndarray:
    """``b_i = sum_k min_c ||D^k c - x_i^k||^2`` for every candidate, ``(n,)`` float64 >= 0.

    Parameters
    ----------
    X : list of K arrays (d_k, n), the candidates' views.
    D : list of K arrays (d_k, N), the dictionaries.
    bases : optional list of K arrays from :func:`range_basis` of each ``D^k``
        (computed when omitted).
    """
    if bases is None:
        bases = [range_basis(Dk) for Dk in D]
    total = np.zeros(np.asarray(X[0]).shape[1])
    for Xk, Qk in zip(X, bases):
        Xk = np.asarray(Xk, dtype=np.float64)
        proj = Qk.T @ Xk
        total += np.einsum("ij,ij->j", Xk, Xk) - np.einsum("ij,ij->j", proj, proj)
    return np.maximum(total, 0.0)
