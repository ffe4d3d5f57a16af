"""Observation likelihood of the candidates.

The paper: ``p_i = exp(-alpha * sum_k ||D^k c_i^k - x_i^k||^2)`` (the outlier term
E is left out of the residual, as L1-APG leaves out its trivial templates).
"""

from __future__ import annotations

import numpy as np

__all__ = ["likelihoods"]


def likelihoods(residual, alpha: float, valid=None) -> np.ndarray:
    """Likelihoods ``exp(-alpha * residual)`` of the candidates, ``(n,)`` float64.

    Non-finite residuals and candidates with ``valid == False`` get 0. The values
    are the paper's unnormalized likelihoods (they underflow to 0 only for
    residuals beyond about 700 / alpha); the particle filter normalizes them.
    """
    r = np.asarray(residual, dtype=np.float64)
    ok = np.isfinite(r)
    if valid is not None:
        ok &= np.asarray(valid, dtype=bool)
    p = np.zeros_like(r)
    p[ok] = np.exp(-alpha * r[ok])
    return p
