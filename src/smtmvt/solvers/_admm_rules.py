r"""Stopping rule and penalty balancing shared by the ADMM solvers.

Both engines (:mod:`smtmvt.solvers.smtmvt` for SMTMVT, :mod:`smtmvt.solvers._admm`
for the comparison models) run scaled-form two-block ADMM (Boyd et al. 2011)
and use these rules, written for scalars (one ADMM over the whole problem) or
arrays (one independent ADMM per candidate) alike:

*Stopping* (Boyd et al. 2011, sec. 3.3): stop when
``r_pri <= tol * scale_pri + ABS_FLOOR`` **and** ``r_dual <= tol * scale_dual + ABS_FLOOR``.

*Residual balancing* (He, Yang & Wang 2000; Boyd et al. sec. 3.4.1) on the
residuals normalized by their tolerances: every ``ADAPT_EVERY`` iterations,
during the first ``ADAPT_UNTIL`` iterations and at most ``ADAPT_MAX`` times,
rho is doubled when the primal residual is ``ADAPT_RATIO`` times further from
its tolerance than the dual one, halved in the opposite case. After that rho is
constant, so the convergence theorem of ADMM (any fixed rho > 0) applies from
that iteration on.
"""

from __future__ import annotations

import numpy as np

__all__ = [
    "ABS_FLOOR",
    "ADAPT_UNTIL",
    "ADAPT_EVERY",
    "ADAPT_MAX",
    "ADAPT_RATIO",
    "tolerances",
    "penalty_factor",
]

ABS_FLOOR = 1e-14  # absolute floor of both tolerances
ADAPT_UNTIL = 200  # iterations during which rho may change
ADAPT_EVERY = 5
ADAPT_MAX = 30
ADAPT_RATIO = 5.0


def tolerances(tol: float, scale_pri, scale_dual):
    """``(eps_pri, eps_dual) = tol * scale + ABS_FLOOR`` (scalars or arrays)."""
    return tol * scale_pri + ABS_FLOOR, tol * scale_dual + ABS_FLOOR


def penalty_factor(it: int, n_adapt, r_pri, eps_pri, r_dual, eps_dual):
    """Factor (2, 0.5 or 1) to multiply rho by after iteration ``it``.

    ``n_adapt`` counts the changes made so far; all arguments but ``it`` may be
    arrays of one shape (one ADMM per entry). Returns a float or a float64
    array of that shape.
    """
    if it > ADAPT_UNTIL or it % ADAPT_EVERY:
        return np.ones(np.shape(r_pri)) if np.ndim(r_pri) else 1.0
    ratio = (np.asarray(r_pri) / eps_pri) / np.maximum(np.asarray(r_dual) / eps_dual, 1e-300)
    factor = np.where(ratio > ADAPT_RATIO, 2.0, np.where(ratio < 1.0 / ADAPT_RATIO, 0.5, 1.0))
    factor = np.where(np.asarray(n_adapt) < ADAPT_MAX, factor, 1.0)
    return factor if factor.ndim else float(factor)
