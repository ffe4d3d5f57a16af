"""Sparse-coding solvers of the observation model.

Calling convention of every solver::

    C, E = solve_xxx(X, D, **params)

``X`` and ``D`` are lists of K arrays (one per view) of shapes (d_k, n) and
(d_k, N); ``C`` is an ndarray (K, N, n) and ``E`` a list of K arrays (d_k, n).
Outputs are float64.

``SOLVERS`` maps a model name to its solver: ``"smtmvt"`` (this paper, see
:mod:`smtmvt.solvers.smtmvt`) and the comparison models ``"l1t"``, ``"mtt"``,
``"mtmvt-ls"``, ``"mtmvt-lad"`` (see :mod:`smtmvt.solvers.baselines`). Their
parameters differ (``lam``/``gamma``, ``lam``, ``lam_p``/``lam_q``); every one
also takes ``tol``, ``max_iter`` and ``return_info``.
"""

from collections.abc import Callable
from typing import Any

from .baselines import solve_l1t, solve_mtmvt_lad, solve_mtmvt_ls, solve_mtt
from .smtmvt import (
    METHODS,
    SolverInfo,
    lipschitz_constant,
    reconstruction_residual,
    smtmvt_objective,
    solve_smtmvt,
)

#: Models whose problem separates over candidates, each solved by its own ADMM
#: (so a candidate's code does not depend on the batch), with nonnegative codes:
#: bounded coding (:func:`smtmvt.likelihood.observe`) is exact for them. The
#: comparison models couple the candidates (MTT, MTMVT) or share one stopping
#: rule over the batch (L1T on the shared engine), so they code every candidate.
BOUNDED_CODING = frozenset({"smtmvt"})

#: Model name -> its solver ``(X, D, ..., tol, max_iter, return_info)``; their other
#: keywords differ, hence ``...``.
SOLVERS: dict[str, Callable[..., Any]] = {
    "smtmvt": solve_smtmvt,
    "l1t": solve_l1t,
    "mtt": solve_mtt,
    "mtmvt-ls": solve_mtmvt_ls,
    "mtmvt-lad": solve_mtmvt_lad,
}

__all__ = [
    "BOUNDED_CODING",
    "METHODS",
    "SOLVERS",
    "SolverInfo",
    "lipschitz_constant",
    "reconstruction_residual",
    "smtmvt_objective",
    "solve_l1t",
    "solve_mtmvt_lad",
    "solve_mtmvt_ls",
    "solve_mtt",
    "solve_smtmvt",
]
