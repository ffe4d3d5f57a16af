"""Random sparse-coding instances shared by the solver tests."""

import numpy as np


def make_instance(seed, K=3, N=5, n=4, d_range=(5, 20)):
    """Small random instance: nonnegative-ish templates with unit columns,
    candidates = nonnegative mixtures of templates + dense noise + a few outliers."""
    rng = np.random.default_rng(seed)
    ds = rng.integers(d_range[0], d_range[1] + 1, K)
    X, D = [], []
    for d in ds:
        Dk = np.abs(rng.standard_normal((d, N))) + 0.3 * rng.standard_normal((d, N))
        Dk /= np.linalg.norm(Dk, axis=0)
        Xk = 0.5 * Dk @ np.abs(rng.standard_normal((N, n))) + 0.1 * rng.standard_normal((d, n))
        Xk += (rng.random((d, n)) < 0.1) * rng.standard_normal((d, n))
        X.append(Xk)
        D.append(Dk)
    return X, D
