r"""Observation models of the trackers SMTMVT is compared with.

Every solver has the calling convention of :func:`solve_smtmvt`::

    C, E = solve_xxx(X, D, **params)            # or C, E, info with return_info

``X``, ``D``: lists of K arrays (d_k, n) and (d_k, N); ``C``: float64 array
(K, N, n); ``E``: list of K float64 arrays (d_k, n), zeros where the model
has no outlier term. All are solved exactly (to ``tol``) by the ADMM of
:mod:`smtmvt.solvers._admm`, whatever solver the original papers used (APG,
Nesterov smoothing), so that the comparison is between models, not solvers.

Scaling convention: every fit term is written without a factor 1/2, as in the
SMTMVT objective; a paper written as ``1/2 ||.||^2 + lam' R`` corresponds to
``lam = 2 lam'`` here. Default weights are placeholders of the right order
for unit-norm features, not values taken from the papers, and are not tuned.

Single-view models (L1T, MTT) are applied to every given view independently
(the views share nothing); pass one view (``[X[0]], [D[0]]``) for the original
single-view trackers.

Models
------
L1T (Mei & Ling, "Robust visual tracking and vehicle classification via
sparse representation", TPAMI 33(11), 2011): each candidate ``x`` is coded
over ``[D, I, -I]`` with nonnegative coefficients and an L1 penalty. With
``e = e+ - e-`` (trivial templates) this is, per view and candidate,
``min_{c >= 0, e} ||x - D c - e||^2 + lam (1'c + ||e||_1)``.

MTT (Zhang, Ghanem, Liu & Ahuja, "Robust visual tracking via multi-task sparse
learning", CVPR 2012; IJCV 101(2), 2013), L21 variant: all candidates are coded
jointly over ``B = [D, I]``, with the mixed norm ``||.||_{2,1}`` (sum over the
rows of B's coefficients of the L2 norm across candidates)::

    min_{Z, E} ||X - D Z - E||_F^2 + lam (sum_j ||Z_{j,:}||_2 + sum_p ||E_{p,:}||_2)

(no nonnegativity). Row p of E is pixel p's trivial coefficient in all
candidates.

MTMVT-LS (Hong, Mei, Prokhorov & Tao, "Tracking via robust multi-task
multi-view joint sparse representation", ICCV 2013): the coefficients
``W = P + Q`` of all views and candidates split into a row-sparse part P
(template j is used or not by every view and candidate together) and a
column-sparse part Q (outlier candidates, in all their views)::

    min_{P, Q} sum_k ||X^k - D^k (P^k + Q^k)||_F^2
               + lam_p sum_j ||P[:, j, :]||_F + lam_q sum_i ||Q[:, :, i]||_F

with P, Q (K, N, n) (``P[:, j, :]``: template j in all K views and n
candidates; ``Q[:, :, i]``: candidate i in all views). Returned ``C = P + Q``;
P and Q are in ``info.parts``. Trivial templates are not modelled (E = 0).

MTMVT-LAD (Mei, Hong, Prokhorov & Tao, "Robust multitask multiview tracking in
videos", IEEE TNNLS 26(11), 2015): the same model with the least absolute
deviation loss ``sum_k ||X^k - D^k (P^k + Q^k)||_1`` (entrywise) instead of
least squares. The paper minimizes a Nesterov-smoothed approximation; here the
exact LAD problem is solved, by the same ADMM with a fixed rho (residual
balancing, which the other models use, drives rho away from progress on
the LAD loss: on a tracker-size instance it stalled 47% above the optimum).
Small instances need ~10^4 iterations to reach tol 1e-9; in the tracker the
paper's 200 iterations a frame (``solver_max_iter``) leave the objective
within about 0.2% of the optimum (``tests/test_solvers_baselines.py``), at
about 1.3 frames a second on Crossing.
"""

from __future__ import annotations

import numpy as np

from ._admm import admm_blocks
from ._inputs import check_params, check_views
from .prox import group_huber_prox, group_shrink, huber_prox, nonneg_shrink, soft_threshold
from .smtmvt import SolverInfo

__all__ = [
    "solve_l1t",
    "solve_mtt",
    "solve_mtmvt_ls",
    "solve_mtmvt_lad",
    "l1t_objective",
    "mtt_objective",
    "mtmvt_objective",
]


def _check_run(tol, max_iter):
    if not (np.isfinite(tol) and tol > 0):
        raise ValueError(f"tol must be > 0, got {tol!r}")
    if int(max_iter) != max_iter or max_iter < 1:
        raise ValueError(f"max_iter must be an integer >= 1, got {max_iter!r}")


def _residuals(X, D, C):
    return [X[k] - D[k] @ C[k] for k in range(len(X))]


def _finish(method, C, E, info, objective, return_info, parts=None):
    if not return_info:
        return C, E
    return C, E, SolverInfo(method=method, objective=objective, parts=parts, **info)


# ---------------------------------------------------------------- L1T
def l1t_objective(X, D, C, E, lam: float) -> float:
    """``sum_k ||X^k - D^k C^k - E^k||_F^2 + lam (1'C1 + ||E||_1)`` (C >= 0 assumed)."""
    X, D, K, N, n = check_views(X, D)
    fit = sum(float(np.sum((X[k] - D[k] @ C[k] - E[k]) ** 2)) for k in range(K))
    return fit + lam * (float(np.sum(C)) + sum(float(np.abs(e).sum()) for e in E))


def solve_l1t(X, D, lam: float = 0.01, tol: float = 1e-6, max_iter: int = 1000, return_info: bool = False):
    """L1T observation model (nonnegative lasso with trivial templates), see the module docstring.

    E is eliminated exactly (``min_e ||r - e||^2 + lam |e|`` is the Huber
    function of r) and recovered as ``E = S_{lam/2}(X - D C)``.

    Returns ``C`` (K, N, n) >= 0 and ``E`` (list of (d_k, n)), float64.
    """
    X, D, K, N, n = check_views(X, D)
    check_params(lam=lam)
    _check_run(tol, max_iter)
    lam = float(lam)
    (C,), info = admm_blocks(
        X,
        D,
        loss_prox=lambda V, rho: huber_prox(V, lam, rho),
        block_proxes=[lambda V, t: nonneg_shrink(V, lam * t)],
        tol=tol,
        max_iter=int(max_iter),
    )
    E = [soft_threshold(r, lam / 2.0) for r in _residuals(X, D, C)]
    obj = l1t_objective(X, D, C, E, lam) if return_info else None
    return _finish("l1t", C, E, info, obj, return_info)


# ---------------------------------------------------------------- MTT
def mtt_objective(X, D, C, E, lam: float) -> float:
    """``sum_k ||X^k - D^k C^k - E^k||_F^2 + lam (sum_{k,j} ||C^k_{j,:}||_2 + sum_{k,p} ||E^k_{p,:}||_2)``."""
    X, D, K, N, n = check_views(X, D)
    fit = sum(float(np.sum((X[k] - D[k] @ C[k] - E[k]) ** 2)) for k in range(K))
    rows = float(np.linalg.norm(C, axis=2).sum()) + sum(float(np.linalg.norm(e, axis=1).sum()) for e in E)
    return fit + lam * rows


def solve_mtt(X, D, lam: float = 0.01, tol: float = 1e-6, max_iter: int = 1000, return_info: bool = False):
    """MTT (L21) observation model, per view; see the module docstring.

    E is eliminated exactly per pixel row (a group Huber function of the
    residual row) and recovered as the row-wise group shrinkage of
    ``X - D C`` by ``lam/2``.

    Returns ``C`` (K, N, n) and ``E`` (list of (d_k, n)), float64.
    """
    X, D, K, N, n = check_views(X, D)
    check_params(lam=lam)
    _check_run(tol, max_iter)
    lam = float(lam)
    (C,), info = admm_blocks(
        X,
        D,
        loss_prox=lambda V, rho: group_huber_prox(V, lam, rho, axis=1),
        block_proxes=[lambda V, t: group_shrink(V, lam * t, axis=2)],
        tol=tol,
        max_iter=int(max_iter),
    )
    E = [group_shrink(r, lam / 2.0, axis=1) for r in _residuals(X, D, C)]
    obj = mtt_objective(X, D, C, E, lam) if return_info else None
    return _finish("mtt", C, E, info, obj, return_info)


# ---------------------------------------------------------------- MTMVT
def mtmvt_objective(X, D, P, Q, lam_p: float, lam_q: float, loss: str = "ls") -> float:
    """MTMVT objective at (P, Q): ``loss(X - D (P + Q)) + lam_p sum_j ||P[:, j, :]||_F
    + lam_q sum_i ||Q[:, :, i]||_F`` with ``loss`` "ls" (squared Frobenius) or
    "lad" (entrywise absolute values)."""
    X, D, K, N, n = check_views(X, D)
    R = _residuals(X, D, np.asarray(P) + np.asarray(Q))
    if loss == "ls":
        fit = sum(float(np.sum(r * r)) for r in R)
    elif loss == "lad":
        fit = sum(float(np.abs(r).sum()) for r in R)
    else:
        raise ValueError(f"loss must be 'ls' or 'lad', got {loss!r}")
    rows = float(np.sqrt(np.sum(np.asarray(P) ** 2, axis=(0, 2))).sum())
    cols = float(np.sqrt(np.sum(np.asarray(Q) ** 2, axis=(0, 1))).sum())
    return fit + lam_p * rows + lam_q * cols


def _solve_mtmvt(X, D, lam_p, lam_q, loss, tol, max_iter, return_info):
    X, D, K, N, n = check_views(X, D)
    check_params(lam_p=lam_p, lam_q=lam_q)
    _check_run(tol, max_iter)
    lam_p, lam_q = float(lam_p), float(lam_q)
    if loss == "ls":

        def loss_prox(V, rho):  # argmin ||R||^2 + rho/2 ||R - V||^2
            return V * (rho / (2.0 + rho))
    else:

        def loss_prox(V, rho):  # argmin ||R||_1 + rho/2 ||R - V||^2
            return soft_threshold(V, 1.0 / rho)

    (P, Q), info = admm_blocks(
        X,
        D,
        loss_prox=loss_prox,
        block_proxes=[
            lambda V, t: group_shrink(V, lam_p * t, axis=(0, 2)),
            lambda V, t: group_shrink(V, lam_q * t, axis=(0, 1)),
        ],
        tol=tol,
        max_iter=int(max_iter),
        adapt=loss == "ls",
    )
    C = P + Q
    E = [np.zeros_like(x) for x in X]
    obj = mtmvt_objective(X, D, P, Q, lam_p, lam_q, loss) if return_info else None
    return _finish(f"mtmvt-{loss}", C, E, info, obj, return_info, parts={"P": P, "Q": Q})


def solve_mtmvt_ls(
    X, D, lam_p: float = 0.1, lam_q: float = 0.5, tol: float = 1e-6, max_iter: int = 1000, return_info: bool = False
):
    """MTMVT-LS observation model (Hong et al. 2013); see the module docstring.

    Returns ``C = P + Q`` (K, N, n) and ``E`` = zeros (list of (d_k, n)),
    float64; with ``return_info`` the :class:`SolverInfo` holds P and Q in
    ``parts``.
    """
    return _solve_mtmvt(X, D, lam_p, lam_q, "ls", tol, max_iter, return_info)


def solve_mtmvt_lad(
    X, D, lam_p: float = 0.1, lam_q: float = 0.5, tol: float = 1e-6, max_iter: int = 1000, return_info: bool = False
):
    """MTMVT-LAD observation model (Mei et al. 2015), exact LAD; see the module docstring.

    Returns ``C = P + Q`` (K, N, n) and ``E`` = zeros (list of (d_k, n)),
    float64; with ``return_info`` the :class:`SolverInfo` holds P and Q in
    ``parts``.
    """
    return _solve_mtmvt(X, D, lam_p, lam_q, "lad", tol, max_iter, return_info)
