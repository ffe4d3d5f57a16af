"""Solver speed and accuracy at tracker size.

Usage::

    python bench/bench_solver.py [--n 400] [--N 10] [--dims 400,24,324,160]
                                 [--tol 1e-4,1e-6] [--paper-iter 1000] [--repeat 3]

Random tracker-like data: K views with dimensions ``--dims``, N templates that
are noisy copies of one pattern (pairwise correlation ~0.95, zero-mean, unit
columns, as after the tracker's normalization), n candidates = nonnegative
mixtures of templates + noise + sparse outliers, normalized the same way.

Prints, for lam in {0.1, 1} (gamma 0.25): the median solve time and the
iterations of the default method at each tolerance, the time and iterations of
the paper's iteration, and the relative objective gap of each to a
high-accuracy reference (default method at tol 1e-10). Nothing is asserted.

On a shared or busy machine run with ``OPENBLAS_NUM_THREADS=1``: the
products are small (d_k x 10 by 10 x 400) and BLAS threads contending with
other processes made the solve about 4 times slower in our measurements.
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from smtmvt.solvers import solve_smtmvt


def tracker_like_data(rng, n, N, dims, corr=0.95):
    """Lists X (d_k, n) and D (d_k, N) of unit-norm, zero-mean columns."""
    X, D = [], []
    for d in dims:
        base = rng.standard_normal((d, 1))
        Dk = corr * base + np.sqrt(1 - corr**2) * rng.standard_normal((d, N))
        Xk = Dk @ (0.3 * np.abs(rng.standard_normal((N, n)))) + 0.15 * rng.standard_normal((d, n)) / np.sqrt(d)
        Xk += (rng.random((d, n)) < 0.1) * rng.standard_normal((d, n)) * 1.5 / np.sqrt(d)
        for A in (Dk, Xk):
            A -= A.mean(axis=0)
            A /= np.linalg.norm(A, axis=0)
        X.append(Xk)
        D.append(Dk)
    return X, D


def timed(repeat, fn):
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t0)
    return float(np.median(times)), out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=400)
    ap.add_argument("--N", type=int, default=10)
    ap.add_argument("--dims", default="400,24,324,160")
    ap.add_argument("--gamma", type=float, default=0.25)
    ap.add_argument("--tol", default="1e-4,1e-6")
    ap.add_argument("--paper-iter", type=int, default=1000)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--seed", type=int, default=0)
    args = ap.parse_args()
    dims = [int(s) for s in args.dims.split(",")]
    tols = [float(s) for s in args.tol.split(",")]
    X, D = tracker_like_data(np.random.default_rng(args.seed), args.n, args.N, dims)
    print(f"n={args.n} N={args.N} K={len(dims)} d={dims} gamma={args.gamma}")
    for lam in (0.1, 1.0):
        _, _, ref = solve_smtmvt(X, D, lam=lam, gamma=args.gamma, tol=1e-10, max_iter=20000, return_info=True)
        print(f"\nlam={lam}: reference objective {ref.objective:.10g} ({ref.iterations} iterations, tol 1e-10)")
        for tol in tols:
            t, (_, _, info) = timed(
                args.repeat,
                lambda lam=lam, tol=tol: solve_smtmvt(X, D, lam=lam, gamma=args.gamma, tol=tol, return_info=True),
            )
            gap = (info.objective - ref.objective) / ref.objective
            print(
                f"  admm  tol={tol:g}: {t * 1e3:8.1f} ms  {info.iterations:5d} it  "
                f"converged={info.converged}  rel gap {gap:.2e}"
            )
        t, (_, _, info) = timed(
            1,
            lambda lam=lam: solve_smtmvt(
                X, D, lam=lam, gamma=args.gamma, method="paper", tol=1e-6, max_iter=args.paper_iter, return_info=True
            ),
        )
        gap = (info.objective - ref.objective) / ref.objective
        print(
            f"  paper tol=1e-06: {t * 1e3:8.1f} ms  {info.iterations:5d} it  "
            f"converged={info.converged}  rel gap {gap:.2e}"
        )


if __name__ == "__main__":
    main()
