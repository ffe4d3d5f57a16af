"""Sparse-coding solvers of the observation model.

Calling convention of every solver::

    C, E = solve_xxx(X, D, **params)

``X`` and ``D`` are lists of K arrays (one per view) of shapes (d_k, n) and
(d_k, N); ``C`` is an ndarray (K, N, n) and ``E`` a list of K arrays (d_k, n).
Outputs are float64.
"""

from .smtmvt import (
    METHODS,
    SolverInfo,
    lipschitz_constant,
    reconstruction_residual,
    smtmvt_objective,
    solve_smtmvt,
)

__all__ = [
    "METHODS",
    "SolverInfo",
    "lipschitz_constant",
    "reconstruction_residual",
    "smtmvt_objective",
    "solve_smtmvt",
]
