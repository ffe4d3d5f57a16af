"""Validation of the multi-view inputs shared by all solvers.

Every solver takes ``X`` and ``D`` as sequences of K two-dimensional arrays
(view k: ``X[k]`` of shape (d_k, n), ``D[k]`` of shape (d_k, N)). The checks
raise ``ValueError`` naming the offending argument.
"""

from __future__ import annotations

import numpy as np

__all__ = ["check_views", "check_params", "check_warm_start"]


def _as_view_list(arg, name: str) -> list:
    if isinstance(arg, np.ndarray) and arg.ndim == 2:
        raise ValueError(
            f"{name} must be a list of K 2-D arrays (one per view), got a single 2-D array; "
            f"wrap it as [{name}] for one view"
        )
    try:
        views = list(arg)
    except TypeError:
        raise ValueError(f"{name} must be a list of K 2-D arrays, got {type(arg).__name__}") from None
    if len(views) == 0:
        raise ValueError(f"{name} must hold at least one view, got an empty sequence")
    out = []
    for k, v in enumerate(views):
        a = np.asarray(v)
        if a.ndim != 2:
            raise ValueError(f"{name}[{k}] must be 2-D, got shape {a.shape}")
        if not (np.issubdtype(a.dtype, np.floating) or np.issubdtype(a.dtype, np.integer)):
            raise ValueError(f"{name}[{k}] must be a real float or integer array, got dtype {a.dtype}")
        a = a.astype(np.float64, copy=False)
        if not np.all(np.isfinite(a)):
            raise ValueError(f"{name}[{k}] contains NaN or infinite values")
        out.append(a)
    return out


def check_views(X, D):
    """Validate and convert ``X``, ``D`` to lists of float64 arrays.

    Returns
    -------
    X : list of K float64 arrays (d_k, n)
    D : list of K float64 arrays (d_k, N)
    K, N, n : ints
    """
    X = _as_view_list(X, "X")
    D = _as_view_list(D, "D")
    if len(X) != len(D):
        raise ValueError(f"X has {len(X)} views but D has {len(D)}; they must match")
    n = X[0].shape[1]
    N = D[0].shape[1]
    for k, (Xk, Dk) in enumerate(zip(X, D)):
        if Xk.shape[0] != Dk.shape[0]:
            raise ValueError(
                f"X[{k}] has {Xk.shape[0]} rows but D[{k}] has {Dk.shape[0]}: "
                "the feature dimension d_k of a view must match"
            )
        if Xk.shape[1] != n:
            raise ValueError(
                f"X[{k}] has {Xk.shape[1]} columns (candidates) but X[0] has {n}: "
                "every view must hold the same n candidates"
            )
        if Dk.shape[1] != N:
            raise ValueError(
                f"D[{k}] has {Dk.shape[1]} columns (templates) but D[0] has {N}: "
                "every view must hold the same N templates"
            )
        if Xk.shape[0] == 0:
            raise ValueError(f"X[{k}] has zero rows (d_k = 0)")
    if n == 0:
        raise ValueError("X has zero columns: there must be at least one candidate")
    if N == 0:
        raise ValueError("D has zero columns: there must be at least one template")
    return X, D, len(X), N, n


def check_params(**params) -> None:
    """Check that every given parameter is a finite number >= 0."""
    for name, value in params.items():
        try:
            v = float(value)
        except (TypeError, ValueError):
            raise ValueError(f"{name} must be a number, got {value!r}") from None
        if not np.isfinite(v) or v < 0:
            raise ValueError(f"{name} must be finite and >= 0, got {value!r}")


def check_warm_start(C0, E0, K: int, N: int, n: int, X: list):
    """Validate optional warm starts; returns float64 copies (or None)."""
    if C0 is not None:
        C0 = np.array(C0, dtype=np.float64)
        if C0.shape != (K, N, n):
            raise ValueError(f"C0 must have shape (K, N, n) = {(K, N, n)}, got {C0.shape}")
        if not np.all(np.isfinite(C0)):
            raise ValueError("C0 contains NaN or infinite values")
    if E0 is not None:
        try:
            E0 = [np.array(e, dtype=np.float64) for e in E0]
        except TypeError:
            raise ValueError("E0 must be a list of K arrays shaped like X") from None
        if len(E0) != K:
            raise ValueError(f"E0 must hold K={K} arrays, got {len(E0)}")
        for k, (e, x) in enumerate(zip(E0, X)):
            if e.shape != x.shape:
                raise ValueError(f"E0[{k}] must have the shape of X[{k}], {x.shape}, got {e.shape}")
            if not np.all(np.isfinite(e)):
                raise ValueError(f"E0[{k}] contains NaN or infinite values")
    return C0, E0
