"""Observation likelihood of the candidates, and coding only the candidates that matter.

The paper: ``p_i = exp(-alpha * sum_k ||D^k c_i^k - x_i^k||^2)`` (the outlier term
E is left out of the residual, as L1-APG leaves out its trivial templates).

Bounded coding (:func:`observe`)
--------------------------------
Coding all n candidates with the exact solver is the most expensive stage of
a frame, yet most candidates end with likelihoods many orders of magnitude
below the best one and cannot change anything. Following L1-APG's bounded
particle resampling (Mei et al., CVPR 2011), each candidate's likelihood is
bounded from above by ``u_i = exp(-alpha b_i)``, ``b_i`` its nonnegative
least-squares residual (:func:`smtmvt.solvers.bounds.nonnegative_residuals`, a
lower bound on its residual under any model with nonnegative codes, as
SMTMVT's; L1-APG used the plain least-squares one). The rule:

1. code the ``FIRST_PASS`` (8) valid candidates of smallest bound; let
   ``p*`` be the best likelihood found;
2. leave out the candidates of largest bound whose bounds sum to at most
   ``eps * p*`` (``sum_{i skipped} u_i <= eps p*``), and code all the others.

Every candidate left out then has ``p_i <= u_i <= eps * p*``: the chosen
(best) candidate is the one that coding all of them would choose, and its code
is the same (the SMTMVT solver runs one independent ADMM per candidate, whose
result does not depend on the other candidates in the batch). The skipped
candidates get likelihood 0. With ``eps < 1 / n`` each of them would have been
resampled ``floor(n p_i / sum_j p_j) = 0`` times anyway, and the sum of all
weights changes by a relative ``eps`` at most (1e-3 at the default), so
resampling copies every particle the same number of times except where that
relative change moves ``n p_j / sum`` across an integer.

An additive term known for every candidate before coding (``offset``, for
example the background term of :mod:`smtmvt.background`) enters the rule as
part of the bound: ``u_i = exp(-alpha (b_i + o_i))`` bounds ``p_i = exp(-alpha
(r_i + o_i))``, and everything above holds for those likelihoods.

Deferred views. The bound of a candidate is a sum over the views of
nonnegative terms, so the terms of some views alone are a (looser) lower
bound too. With ``deferred`` (:func:`observe`), the last views are computed
one at a time, each only for the candidates that still need it: the bounds
start as the sums over the views at hand; the ``FIRST_PASS`` candidates of
smallest bound get every deferred view (hence full bounds) and are coded;
then, until no candidate outside the skipped tail lacks a deferred view, the
tail is taken again over the current bounds (full where known, partial
elsewhere) and each candidate outside it gets its next deferred view. The
skipped tail's bounds, each a true lower bound of its residual, still sum to
at most ``eps * p*``, so everything above holds; only the bounds of the
skipped candidates are looser than with every view computed (a few more
candidates are coded). A term of the offset that is itself a sum of
nonnegative parts over the views (the anchor term of :mod:`smtmvt.anchor`)
is deferred the same way: each deferred view brings its part. With the
tracker's default (the coarse view, HOG, then LBP deferred; 120 frames, seed
0, stop 26) the coarse view is computed for a mean of 252 of the 400
candidates a frame on Crossing, 357 on David, 383 on Basketball; HOG for 70,
247 and 293; LBP for 12, 22 and 27 (stop 22, HOG then LBP: HOG for all 400
on Bolt and Soccer, whose intensity and color bounds settle nothing).
"""

from __future__ import annotations

from collections.abc import Callable
from contextlib import contextmanager
from dataclasses import dataclass

import numpy as np

from .solvers.bounds import gram_matrices, least_squares_residuals, nonnegative_residuals, range_basis
from .solvers.smtmvt import reconstruction_residual

__all__ = ["likelihoods", "Observation", "observe", "FIRST_PASS"]

#: Candidates coded first (smallest bounds) to find the best likelihood. 8, not
#: 16 (stop 26): the rule's final set is a median of 4-8 candidates on Crossing,
#: David and Basketball, so 16 coded twice the needed columns on most frames;
#: 8 codes 26-40% fewer (a second, small batch on a fifth to a third of frames),
#: with the same boxes (docs/stops.md#stop26).
FIRST_PASS = 8


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


@dataclass(frozen=True)
class Observation:
    """The candidates of one frame, coded over the templates.

    Attributes
    ----------
    likelihood : (n,) float64, ``exp(-alpha * residual)``; 0 for invalid and
        for skipped candidates.
    residual : (n,) float64 reconstruction residual; NaN where not coded.
    bound : (n,) float64 lower bound of the residual: nonnegative least squares
        when ``eps > 0`` (the coded model must have nonnegative codes), plain
        least squares when every candidate is coded.
    coded : (n,) bool, the candidates that were coded.
    C : (K, N, n) float64 codes (zero where not coded).
    E : list of K (d_k, n) float64 outliers (zero where not coded).
    views : list of K (d_k, n) candidate views: ``X`` with the deferred views
        filled in where computed (zero columns elsewhere).
    complete : (n,) bool, the candidates whose every view is in ``views``
        (all of them without ``deferred``; always the coded ones).
    """

    likelihood: np.ndarray
    residual: np.ndarray
    bound: np.ndarray
    coded: np.ndarray
    C: np.ndarray
    E: list
    views: list
    complete: np.ndarray


@contextmanager
def _untimed(stage: str):
    yield


def observe(
    X,
    D,
    code: Callable,
    alpha: float,
    valid=None,
    eps: float = 1e-3,
    always=None,
    timed=None,
    deferred=None,
    bases=None,
    offset=None,
) -> Observation:
    """Code the candidates that can matter and compute their likelihoods.

    Parameters
    ----------
    X : list of K (d_k, n) candidate views; D : list of K (d_k, N) dictionaries.
    code : ``code(X_sub, D) -> (C_sub, E_sub)``, the observation model's
        solver on a subset of the candidates (columns).
    alpha : likelihood sharpness.
    valid : (n,) bool, candidates that may be chosen (others get likelihood 0
        and are not coded); all when None.
    eps : the skipped candidates' likelihood bounds sum to at most ``eps``
        times the best likelihood (see the module docstring); 0 codes every
        valid candidate. With ``eps > 0`` the model must have nonnegative codes
        (the bound) and code each candidate independently of the others.
    always : (n,) bool, candidates coded whatever their bound, e.g. probes
        scored for diagnosis; their likelihood is reported (valid or not) but
        they take no part in the rule (pass them with ``valid`` False so that
        they cannot change which other candidates are coded).
    timed : optional ``timed(stage)`` context manager factory; the solver's
        time is reported as ``"solve"``, the rest (bounds, residuals,
        likelihoods, the rule's bookkeeping) as ``"likelihood"``. Blocks of one
        stage may nest (a factory that adds up times should count the outer
        one only, as :class:`smtmvt.Tracker`'s does).
    deferred : optional list of ``K - len(X)`` callables, one per view after
        ``X``'s (in ``D``'s order), for views computed only where needed (see
        the module docstring; ``X`` then holds the first views only, ``D`` all
        K dictionaries): ``deferred[j](idx) -> (view, offset)``, view
        ``len(X) + j`` of the candidates ``idx`` (int array), ``(d_k,
        len(idx))``, and the part of their offset that comes with it,
        ``(len(idx),)`` float >= 0, or None for none. View j is asked only
        for candidates that have views ``0 .. j - 1``. Its time is reported
        as ``"features"``. The computed columns are returned in
        :attr:`Observation.views`.
    bases : optional list of the K :func:`smtmvt.solvers.bounds.range_basis`
        of ``D`` (they change only with the templates: the tracker keeps them),
        computed from ``D`` when omitted.
    offset : optional (n,) float >= 0 added to each candidate's residual in
        its likelihood, ``exp(-alpha (residual + offset))``, and in the rule
        (its bound is ``bound + offset``): a term known for every candidate
        before coding, such as the background term of
        :func:`smtmvt.background.background_offsets`. None: 0.
    """
    timed = timed or _untimed
    n = X[0].shape[1]
    valid = np.ones(n, dtype=bool) if valid is None else np.asarray(valid, dtype=bool)
    always = np.zeros(n, dtype=bool) if always is None else np.asarray(always, dtype=bool)
    shift = np.zeros(n) if offset is None else np.asarray(offset, dtype=np.float64).reshape(n)
    with timed("likelihood"):
        coding = _Coding(X, D, code, eps, timed, deferred, bases, shift)
    if eps <= 0 or not valid.any():
        coding.run(valid | always)
    else:
        _code_bounded(coding, valid, always, alpha, eps)
    with timed("likelihood"):
        p = likelihoods(coding.residual + coding.shift, alpha, valid | always)
    return Observation(
        likelihood=p,
        residual=coding.residual,
        bound=coding.bound,
        coded=coding.coded,
        C=coding.C,
        E=coding.E,
        views=coding.X,
        complete=coding.have,
    )


def _code_bounded(coding: _Coding, valid, always, alpha: float, eps: float) -> None:
    """The rule of the module docstring: code the ``FIRST_PASS`` candidates of
    smallest bound (and ``always``), then every candidate outside the tail of
    largest bounds whose likelihood bounds sum to at most ``eps`` times the best
    likelihood found, computing the deferred views (one at a time) until that
    tail is stable."""
    with coding.timed("likelihood"):
        first = np.zeros(len(valid), dtype=bool)
        first[_by_bound(coding, valid)[:FIRST_PASS]] = True
    coding.run(first | always)
    best = np.nanmin(np.where(valid & coding.coded, coding.residual + coding.shift, np.nan))
    while True:
        with coding.timed("likelihood"):
            needed = _outside_tail(coding, valid, alpha, eps, best)
        if coding.have[needed].all():
            break
        coding.advance(needed)  # their bounds rise: take the tail again
    coding.run(needed)


def _by_bound(coding: _Coding, valid) -> np.ndarray:
    """The valid candidates' indices by increasing bound (with the offset), ties in index order."""
    return np.flatnonzero(valid)[np.argsort((coding.bound + coding.shift)[valid], kind="stable")]


def _outside_tail(coding: _Coding, valid, alpha: float, eps: float, best: float) -> np.ndarray:
    """(n,) bool, the uncoded valid candidates outside the tail of largest bounds
    whose likelihood bounds sum to at most ``eps`` times the best likelihood
    ``exp(-alpha best)`` (bounds as they are now, partial where views are deferred)."""
    order = _by_bound(coding, valid)
    rest = order[~coding.coded[order]]
    # bounds relative to the best likelihood: u_i / p* = exp(-alpha (b_i - r*))
    u = np.exp(-alpha * (coding.bound[rest] + coding.shift[rest] - best))
    skipped_mass = np.cumsum(u[::-1])[::-1]  # sum of the bounds from each position to the end
    needed = np.zeros(len(valid), dtype=bool)
    needed[rest[skipped_mass > eps]] = True
    return needed


class _Coding:
    """What :func:`observe` fills in for the n candidates (views, bounds, offsets,
    codes, residuals), and its two steps: computing the next deferred view of
    some candidates and coding some candidates."""

    def __init__(self, X, D, code: Callable, eps: float, timed, deferred, bases, shift) -> None:
        n = X[0].shape[1]
        K, N = len(D), D[0].shape[1]
        self.K0 = len(X)
        self.stages = list(deferred or [])
        if len(self.stages) != K - self.K0:
            raise ValueError(f"{K} dictionaries but {self.K0} views and {len(self.stages)} deferred ones")
        self.D, self.code, self.eps, self.timed = D, code, eps, timed
        self.shift = shift.copy()
        self.X = list(X) + [np.zeros((Dk.shape[0], n), dtype=np.asarray(X[0]).dtype) for Dk in D[self.K0 :]]
        self.level = np.zeros(n, dtype=np.intp)  # deferred views computed, in order
        self.bases = [range_basis(Dk) for Dk in D] if bases is None else bases
        with timed("likelihood"):
            # the dictionaries in float64 and their Gram matrices, once for every batch bounded
            self._D64 = [np.asarray(Dk, dtype=np.float64) for Dk in D]
            self._grams = gram_matrices(self._D64) if eps > 0 else []
            self.bound = self._lower_bounds(self.X[: self.K0], slice(0, self.K0))
        self.coded = np.zeros(n, dtype=bool)
        self.C = np.zeros((K, N, n))
        self.E = [np.zeros((Dk.shape[0], n)) for Dk in D]
        self.residual = np.full(n, np.nan)

    @property
    def have(self) -> np.ndarray:
        """(n,) bool, the candidates whose every view is at hand."""
        return self.level == len(self.stages)

    def _lower_bounds(self, Xs, views: slice) -> np.ndarray:
        """The bounds of the candidates ``Xs`` (their views ``views``) over those views."""
        Ds, Bs = self._D64[views], self.bases[views]
        if self.eps > 0:
            return nonnegative_residuals(Xs, Ds, Bs, self._grams[views])
        return least_squares_residuals(Xs, Ds, Bs)

    def advance(self, mask) -> None:
        """Compute the next deferred view of each candidate in ``mask`` lacking one."""
        level = np.where(mask, self.level, len(self.stages))
        for j, stage in enumerate(self.stages):
            idx = np.flatnonzero(level == j)
            if idx.size == 0:
                continue
            k = self.K0 + j
            with self.timed("features"):
                view, offset = stage(idx)
            with self.timed("likelihood"):
                self.X[k][:, idx] = view
                self.bound[idx] += self._lower_bounds([view], slice(k, k + 1))
                if offset is not None:
                    self.shift[idx] += offset
                self.level[idx] = j + 1

    def complete(self, mask) -> None:
        """Compute every deferred view of the candidates in ``mask`` lacking them."""
        for _ in range(len(self.stages)):  # each advance moves every one of them on by a view
            self.advance(mask)

    def run(self, mask) -> None:
        """Code the candidates in ``mask`` (their deferred views completed first)."""
        idx = np.flatnonzero(mask)
        if idx.size == 0:
            return
        self.complete(mask)
        Xs = [Xk[:, idx] for Xk in self.X]
        with self.timed("solve"):
            Cs, Es = self.code(Xs, self.D)
        with self.timed("likelihood"):
            self.C[:, :, idx] = Cs
            for k in range(len(self.D)):
                self.E[k][:, idx] = Es[k]
            self.residual[idx] = reconstruction_residual(Xs, self.D, Cs)
            self.coded[idx] = True
