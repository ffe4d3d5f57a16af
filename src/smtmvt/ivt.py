r"""IVT (Ross, Lim, Lin & Yang, "Incremental learning for robust visual tracking", IJCV 77, 2008).

The appearance model is a PCA subspace of the target's gray patches (32x32
pixels, values in [0, 1]): a mean ``mu`` (d,), an orthonormal basis ``U``
(d, r) and its singular values ``s`` (r,). A candidate patch ``x`` (d,) is
scored by its distance to the subspace, ``p = exp(-||(x - mu) - U U'(x - mu)||^2
/ sigma)``; the best candidate is the result, and every ``batch`` frames the
results of those frames update the subspace incrementally
(:func:`incremental_svd`, the sequential Karhunen-Loeve update with mean update
and forgetting factor ``f``), truncated to ``max_basis`` vectors.

The particle filter is IVT's own (:func:`geom_to_affine`): the state is
``(x, y, s, theta, r, phi)`` (centre in pixels, width over the 32-pixel
template, rotation, aspect h/w, skew), each frame resampled from the last
weights and moved by Gaussian noise of ``affine_std`` per parameter (OTB's
setting ``[4, 4, 0.01, 0, 0.005, 0]``, 600 particles). Parameters not given by
the OTB setting are IVT's code defaults (``sigma`` 0.25 as IVT's demos,
``batch`` 5, ``max_basis`` 16, ``f`` 1.0); frames are resized to 320x240 as
the paper's table ran every tracker.
"""

from __future__ import annotations

import dataclasses
import math

import cv2
import numpy as np

from .geometry import affine_to_box, box_to_affine
from .preprocess import resize_frame, to_unit_range
from .warp import warp_patches

__all__ = ["IVTConfig", "IVTTracker", "incremental_svd", "geom_to_affine", "subspace_distance"]


def incremental_svd(data, U=None, s=None, mean=None, n: float = 0.0, forgetting: float = 1.0, max_basis=None):
    """Add the columns of ``data`` to a PCA subspace (Ross et al. 2008, Algorithm 1).

    Parameters
    ----------
    data : (d, m) array, m >= 1 new samples (columns).
    U, s, mean : the current basis (d, r), singular values (r,) and mean (d,);
        ``U = None`` starts a new subspace from ``data`` alone (batch SVD).
    n : the (effective) number of samples seen so far.
    forgetting : f in (0, 1]: the old singular values are multiplied by f and
        the old samples count f times in the new mean.
    max_basis : keep at most this many basis vectors (None: all above 1e-6 of
        the total energy).

    Returns
    -------
    (U, s, mean, n): the basis (d, r'), singular values (r',) in decreasing order,
    mean (d,), and ``f n + m``. With f = 1 they are the batch SVD of all samples
    less their mean; with f < 1 that of the samples of the k-th update from the
    last weighted by f**k (with the mean-shift column of each update).
    """
    A = np.asarray(data, dtype=np.float64)
    if A.ndim != 2 or A.shape[1] < 1:
        raise ValueError(f"incremental_svd: data must be (d, m) with m >= 1, got shape {A.shape}")
    if not 0.0 < forgetting <= 1.0:
        raise ValueError(f"incremental_svd: forgetting must be in (0, 1], got {forgetting!r}")
    m = A.shape[1]
    mean_b = A.mean(axis=1)
    B = A - mean_b[:, None]
    if U is None:  # a new subspace: the batch SVD of the centred data
        Uf, sf, _ = np.linalg.svd(B, full_matrices=False)
        return _truncated(Uf, sf, max_basis) + (mean_b, float(m))
    r = U.shape[1]
    shift = math.sqrt(n * m / (n + m)) * (np.asarray(mean, dtype=np.float64) - mean_b)
    B = np.column_stack([B, shift])
    proj = U.T @ B
    Qn = _range(B - U @ proj)
    R = np.zeros((r + Qn.shape[1], r + B.shape[1]))
    R[:r, :r] = forgetting * np.diag(s)
    R[:r, r:] = proj
    R[r:, r:] = Qn.T @ B
    Ur, sf, _ = np.linalg.svd(R, full_matrices=False)
    new_mean = (forgetting * n * np.asarray(mean) + m * mean_b) / (forgetting * n + m)
    return _truncated(np.column_stack([U, Qn]) @ Ur, sf, max_basis) + (new_mean, forgetting * n + m)


def _range(M) -> np.ndarray:
    """An orthonormal basis (d, q) of the range of ``M`` (d, c). Not a QR: the new
    samples are often rank-deficient (a batch of m centred samples has rank m - 1),
    and QR's columns beyond the rank would not be orthogonal to the old basis."""
    Um, sm, _ = np.linalg.svd(M, full_matrices=False)
    tol = (sm[0] if len(sm) else 0.0) * max(M.shape) * np.finfo(np.float64).eps
    return Um[:, sm > tol]


def _truncated(U, s, max_basis) -> tuple:
    """The basis vectors above 1e-6 of the energy, at most ``max_basis`` of them."""
    keep = s**2 > 1e-6 * float(np.sum(s**2))
    if max_basis is not None:
        keep &= np.arange(len(s)) < int(max_basis)
    return U[:, keep], s[keep]


def subspace_distance(X, U, mean) -> np.ndarray:
    """Squared distance of each column of ``X`` (d, n) to the affine subspace
    ``mean + span(U)``: ``||(x - mean) - U U'(x - mean)||^2``, (n,) float64."""
    diff = np.asarray(X, dtype=np.float64) - np.asarray(mean)[:, None]
    if U is not None and U.shape[1]:
        diff = diff - U @ (U.T @ diff)
    return np.einsum("ij,ij->j", diff, diff)


def geom_to_affine(geom) -> np.ndarray:
    """IVT's geometric state ``(x, y, s, theta, r, phi)`` (n, 6) as our affine
    states ``[a11, a12, a21, a22, tx, ty]`` (n, 6) (:mod:`smtmvt.geometry`):
    the 2x2 part is ``s R(theta) R(-phi) diag(1, r) R(phi)`` (IVT's
    parameterization: a box of width ``32 s`` and height ``32 s r`` rotated by
    theta, sheared by phi), the translation the centre ``(x, y)``."""
    g = np.atleast_2d(np.asarray(geom, dtype=np.float64))
    x, y, s, th, r, ph = g.T

    def rot(a):
        c, n = np.cos(a), np.sin(a)
        return np.stack([np.stack([c, -n], -1), np.stack([n, c], -1)], -2)

    scale = np.zeros((len(g), 2, 2))
    scale[:, 0, 0], scale[:, 1, 1] = 1.0, r
    M = s[:, None, None] * rot(th) @ rot(-ph) @ scale @ rot(ph)
    return np.column_stack([M[:, 0, 0], M[:, 0, 1], M[:, 1, 0], M[:, 1, 1], x, y])


@dataclasses.dataclass(frozen=True)
class IVTConfig:
    """IVT's parameters (see the module docstring). ``affine_std``: the random
    walk's std of ``(x px, y px, s, theta rad, r, phi rad)`` per frame."""

    n_particles: int = 600
    affine_std: tuple = (4.0, 4.0, 0.01, 0.0, 0.005, 0.0)
    template_size: tuple = (32, 32)
    sigma: float = 0.25
    batch: int = 5
    max_basis: int = 16
    forgetting: float = 1.0
    frame_size: tuple | None = (320, 240)
    seed: int | None = 0

    def __post_init__(self):
        checks = {
            "n_particles": isinstance(self.n_particles, int) and 1 <= self.n_particles <= 10000,
            "affine_std": len(self.affine_std) == 6 and all(v >= 0 and math.isfinite(v) for v in self.affine_std),
            "sigma": self.sigma > 0 and math.isfinite(self.sigma),
            "batch": isinstance(self.batch, int) and self.batch >= 1,
            "max_basis": isinstance(self.max_basis, int) and self.max_basis >= 1,
            "forgetting": 0.0 < self.forgetting <= 1.0,
        }
        for name, ok in checks.items():
            if not ok:
                raise ValueError(f"IVTConfig: invalid {name}={getattr(self, name)!r}")


class IVTTracker:
    """IVT on frames as :mod:`smtmvt.data` yields them; boxes 0-based ``(x, y, w, h)``.

    ``init(frame, box)`` then ``update(frame) -> box`` per frame (the
    evaluation's protocol). Frames: (H, W) gray or (H, W, 3) RGB, any dtype
    :func:`smtmvt.preprocess.to_unit_range` accepts.
    """

    def __init__(self, config: IVTConfig | None = None):
        self.config = config if config is not None else IVTConfig()

    def _gray(self, frame) -> np.ndarray:
        a: np.ndarray = to_unit_range(np.asarray(frame), "frame").astype(np.float32)
        if a.ndim == 3:
            a = cv2.cvtColor(a, cv2.COLOR_RGB2GRAY)
        if self.config.frame_size is not None:
            a = resize_frame(a, self.config.frame_size)
        return a

    def _patches(self, gray, geom) -> np.ndarray:
        """The candidates' patches as columns, (d, n) float64, d = template pixels."""
        p = warp_patches(gray, geom_to_affine(geom), self.config.template_size)
        return p.reshape(len(p), -1).T.astype(np.float64)

    def init(self, frame, box) -> None:
        b = np.asarray(box, dtype=np.float64)
        if b.shape != (4,) or not np.all(np.isfinite(b)) or b[2] <= 0 or b[3] <= 0:
            raise ValueError(f"IVT init: box must be 4 finite numbers with w, h > 0, got {tuple(b.tolist())}")
        shape = np.shape(frame)
        size = self.config.frame_size
        self._factor = np.ones(2) if size is None else np.array([size[0] / shape[1], size[1] / shape[0]])
        a = box_to_affine(np.concatenate([b[:2] * self._factor, b[2:] * self._factor]))
        self._geom = np.array([a[4], a[5], a[0], 0.0, a[3] / a[0], 0.0])
        self._rng = np.random.default_rng(self.config.seed)
        gray = self._gray(frame)
        first = self._patches(gray, self._geom[None])
        self._U, self._s, self._mean, self._n = None, None, first[:, 0], 0.0
        self._batch = [first[:, 0]]
        self._particles = np.repeat(self._geom[None], self.config.n_particles, axis=0)
        self._weights = np.full(self.config.n_particles, 1.0 / self.config.n_particles)

    def update(self, frame) -> tuple:
        cfg = self.config
        gray = self._gray(frame)
        idx = self._rng.choice(len(self._particles), size=cfg.n_particles, p=self._weights)
        particles = self._particles[idx] + self._rng.standard_normal((cfg.n_particles, 6)) * np.asarray(cfg.affine_std)
        particles[:, 2] = np.maximum(particles[:, 2], 1e-3)  # a positive size
        particles[:, 4] = np.maximum(particles[:, 4], 1e-3)
        X = self._patches(gray, particles)
        err = subspace_distance(X, self._U, self._mean)
        weights = np.exp(-(err - err.min()) / cfg.sigma)
        self._weights = weights / weights.sum()
        best = int(np.argmax(weights))
        self._particles, self._geom = particles, particles[best].copy()
        self._batch.append(X[:, best])
        if len(self._batch) >= cfg.batch:
            data = np.column_stack(self._batch)
            self._U, self._s, self._mean, self._n = incremental_svd(
                data, self._U, self._s, self._mean, self._n, cfg.forgetting, cfg.max_basis
            )
            self._batch = []
        return self.box

    @property
    def box(self) -> tuple:
        """The last result, 0-based ``(x, y, w, h)`` in the given frame's pixels."""
        b = affine_to_box(geom_to_affine(self._geom[None]))[0]
        return tuple(float(v) for v in np.concatenate([b[:2] / self._factor, b[2:] / self._factor]))
