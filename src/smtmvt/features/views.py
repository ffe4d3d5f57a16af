"""Candidate patches, the view registry, and column normalization.

A *view* is a pure function ``fn(patches: Patches) -> (n, d) float32`` that
turns every candidate (or template) patch into one feature vector.
:func:`extract_views` runs the requested views and returns one ``(d_k, n)``
matrix per view, columns normalized by :func:`normalize_columns`, ready to be
used as the SMTMVT observation matrices ``X^k`` or, built from template
patches, as the dictionaries ``D^k``.

The registry is the module-level dict ``VIEW_REGISTRY`` (name -> function),
filled with the paper's four views and the coarse view at import and extended only through
:func:`register_view`; it is the only mutable module state in
:mod:`smtmvt.features`.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass

import numpy as np
from numba import njit

from .coarse import coarse_view
from .color import color_view
from .hog import hog_view
from .intensity import intensity_view
from .lbp import lbp_view

__all__ = [
    "Patches",
    "ViewFn",
    "VIEW_REGISTRY",
    "DEFAULT_VIEWS",
    "register_view",
    "available_views",
    "extract_views",
    "normalize_columns",
]

ViewFn = Callable[["Patches"], np.ndarray]


def _as_float32(name: str, value, ndim: int, layout: str) -> np.ndarray:
    array = np.asarray(value)
    if array.ndim != ndim:
        raise ValueError(f"Patches.{name} must be {layout}, got shape {array.shape}")
    if not (np.issubdtype(array.dtype, np.floating) or np.issubdtype(array.dtype, np.integer)):
        raise TypeError(f"Patches.{name} must be a real-valued array, got dtype {array.dtype}")
    return np.asarray(array, dtype=np.float32)


#: each array of Patches: its number of dimensions and layout
_LAYOUTS = {
    "intensity": (3, "(n, th, tw)"),
    "gray": (3, "(n, fh, fw)"),
    "color": (4, "(n, fh, fw, C)"),
    "raw": (3, "(n, fh, fw)"),
}


@dataclass(frozen=True)
class Patches:
    """The warped image patches of ``n`` candidates (or templates).

    Attributes
    ----------
    intensity : (n, th, tw) float32 or None
        Tan-Triggs normalized gray, warped at the intensity template size
        (:func:`smtmvt.features.intensity_template_size`); input of the
        intensity view.
    gray : (n, fh, fw) float32 or None
        Tan-Triggs normalized gray, warped at the feature size (default 32x32);
        input of the HOG and LBP views asked for ``plane="tan_triggs"`` (the
        paper). HOG needs ``fh, fw >= 16``.
    color : (n, ch, cw, C) float32 or None
        Raw frame colors scaled to [0, 1], C = 3 (RGB) or C = 1 (gray frames),
        at the color view's size (the feature size unless
        ``TrackerConfig.color_size`` says otherwise); input of the color view.
    raw : (n, fh, fw) float32 or None
        The gray frame *before* Tan-Triggs, at the feature size; input of the
        HOG and LBP views when they are asked for ``plane="gray"``, and of the
        coarse view.

    An array no view reads may be None (a view that reads it says so); at
    least one is given. Arrays are converted to float32 (no copy when they
    already are, whatever their memory layout: a view that needs C order makes
    it); shapes are checked, values are not.
    """

    intensity: np.ndarray | None
    gray: np.ndarray | None
    color: np.ndarray | None
    raw: np.ndarray | None = None

    def __post_init__(self):
        given = {}
        for name, (ndim, layout) in _LAYOUTS.items():
            value = getattr(self, name)
            if value is not None:
                given[name] = _as_float32(name, value, ndim, layout)
                object.__setattr__(self, name, given[name])
        if not given:
            raise ValueError("Patches need at least one array of patches")
        first, n = next((name, a.shape[0]) for name, a in given.items())
        if n < 1:
            raise ValueError("Patches need at least one patch (n >= 1)")
        for name, a in given.items():
            if a.shape[0] != n:
                raise ValueError(
                    f"Patches arrays disagree on the number of patches n: {first} {n}, {name} {a.shape[0]} "
                    "(one patch per candidate)"
                )
            if min(a.shape[1:3]) < 1:
                raise ValueError(f"empty patches: Patches.{name} has shape {a.shape}")
        if "color" in given and given["color"].shape[3] not in (1, 3):
            raise ValueError(
                f"Patches.color must have C = 3 (RGB) or C = 1 (gray) channels, got {given['color'].shape[3]}"
            )
        if "gray" in given and "raw" in given and given["raw"].shape != given["gray"].shape:
            raise ValueError(
                f"Patches.raw has shape {given['raw'].shape} but Patches.gray {given['gray'].shape}; "
                "both are warped at the feature size"
            )

    @property
    def n(self) -> int:
        """Number of patches."""
        return next(a for a in (self.intensity, self.gray, self.color, self.raw) if a is not None).shape[0]

    def subset(self, index, keep=None) -> Patches:
        """The patches selected by ``index`` (an int, slice, mask or index array),
        of the arrays named in ``keep`` only (the others None; all when None)."""
        index = np.atleast_1d(np.arange(self.n)[index])
        arrays = {}
        for name in _LAYOUTS:
            value = getattr(self, name)
            arrays[name] = None if value is None or (keep is not None and name not in keep) else value[index]
        return Patches(**arrays)

    def joined(self, other: Patches) -> Patches:
        """These patches followed by ``other``'s (the same sizes)."""

        def cat(a, b):
            return None if a is None or b is None else np.concatenate([a, b])

        return Patches(
            cat(self.intensity, other.intensity),
            cat(self.gray, other.gray),
            cat(self.color, other.color),
            cat(self.raw, other.raw),
        )

    def plane(self, name: str) -> np.ndarray:
        """The feature-size gray patches of ``name``: ``"tan_triggs"`` (``gray``) or ``"gray"`` (``raw``)."""
        if name == "tan_triggs":
            if self.gray is None:
                raise ValueError("Patches.gray (the Tan-Triggs plane at the feature size) was not given")
            return self.gray
        if name == "gray":
            if self.raw is None:
                raise ValueError("Patches.raw (the gray plane before Tan-Triggs) was not given")
            return self.raw
        raise ValueError(f"unknown plane {name!r}: use 'tan_triggs' or 'gray'")


DEFAULT_VIEWS = ("intensity", "color", "hog", "lbp")

#: name -> view function; the only mutable module state (see module docstring).
VIEW_REGISTRY: dict[str, ViewFn] = {
    "intensity": intensity_view,
    "color": color_view,
    "hog": hog_view,
    "lbp": lbp_view,
    "coarse": coarse_view,
}


def register_view(name: str, fn: ViewFn, *, replace: bool = False) -> None:
    """Add a view ``fn(patches) -> (n, d) float32`` under ``name``.

    Raises ``ValueError`` if ``name`` is taken, unless ``replace=True``.
    """
    if not isinstance(name, str) or not name:
        raise ValueError(f"view name must be a non-empty string, got {name!r}")
    if not callable(fn):
        raise TypeError(f"view function for {name!r} must be callable, got {type(fn).__name__}")
    if name in VIEW_REGISTRY and not replace:
        raise ValueError(f"view {name!r} is already registered; pass replace=True to override it")
    VIEW_REGISTRY[name] = fn


def available_views() -> tuple[str, ...]:
    """Names of the registered views, in registration order (defaults first)."""
    return tuple(VIEW_REGISTRY)


# Columns whose centred norm is below this fraction of their own scale are
# treated as constant (see normalize_columns).
_CONSTANT_RTOL = 1e-9


def normalize_columns(V: np.ndarray) -> np.ndarray:
    """Zero-mean, unit-L2 columns, as L1-APG / MTT normalize templates and candidates.

    Parameters
    ----------
    V : (d, n) real ndarray
        One feature vector per column.

    Returns
    -------
    (d, n) float32 ndarray. Each column minus its mean, divided by its L2 norm.

    A constant column has no direction to keep; it becomes the **zero vector**
    (never NaN): a zero candidate column is coded by all-zero coefficients and
    gets the lowest likelihood, and a zero template column is never selected.
    The arithmetic is done in float64, where centring a constant column of
    float32 values is exact; a column counts as constant when its centred norm
    is at most ``1e-9 * sqrt(d) * max|column|`` (float64 rounding level), far
    below any real float32 variation (relative 6e-8).
    """
    V = np.asarray(V)
    if V.ndim != 2:
        raise ValueError(f"expected a (d, n) matrix, got shape {V.shape}")
    if V.shape[0] == 0:
        return np.zeros(V.shape, dtype=np.float32)
    if not np.isrealobj(V) or V.dtype.kind not in "fiub":
        raise TypeError(f"expected a real (d, n) matrix, got dtype {V.dtype}")
    V = np.ascontiguousarray(V, dtype=np.float32 if V.dtype == np.float32 else np.float64)
    return _normalize_kernel(V, _CONSTANT_RTOL, np.empty(V.shape, dtype=np.float32))


@njit(cache=True, nogil=True, boundscheck=False)
def _normalize_kernel(V, rtol, out):  # pragma: no cover - compiled
    """:func:`normalize_columns` in one pass per step, in the operation order of its
    float64 array expression (mean of the rows summed in order, squares of the
    centred values summed in row order, times ``1 / norm``): the same float32
    result bit for bit, without the (d, n) float64 temporaries."""
    d, n = V.shape
    mean = np.empty(n)
    ss = np.zeros(n)
    top = np.empty(n)
    for j in range(n):
        mean[j] = np.float64(V[0, j])
        top[j] = abs(np.float64(V[0, j]))
    for i in range(1, d):
        for j in range(n):
            x = np.float64(V[i, j])
            mean[j] += x
            top[j] = max(top[j], abs(x))
    for j in range(n):
        mean[j] = mean[j] / d
    for i in range(d):
        for j in range(n):
            x = np.float64(V[i, j]) - mean[j]
            ss[j] += x * x
    root_d = math.sqrt(d)
    for j in range(n):
        norm = math.sqrt(ss[j])
        ss[j] = 0.0 if norm <= rtol * (top[j] * root_d) else 1.0 / norm
    for i in range(d):
        for j in range(n):
            out[i, j] = np.float32((np.float64(V[i, j]) - mean[j]) * ss[j])
    return out


def extract_views(
    patches: Patches, names: Sequence[str] = DEFAULT_VIEWS, options: Mapping[str, Mapping] | None = None
) -> list[np.ndarray]:
    """Feature matrices of the patches, one per view.

    Parameters
    ----------
    patches : Patches
        ``n`` candidate (or template) patches.
    names : sequence of str
        View names, from :func:`available_views`.
    options : mapping of view name -> keyword arguments, optional
        Passed to that view's function (e.g. ``{"color": {"grid": 4}}``).

    Returns
    -------
    list of (d_k, n) float32 ndarrays, C-contiguous, in the order of ``names``;
    column ``i`` is the normalized (:func:`normalize_columns`) feature vector of
    patch ``i``. Defaults at a 32x32 feature size: intensity ``th * tw``,
    color 48 (RGB) or 16 (gray), hog 324, lbp 160, coarse 256.
    """
    if not isinstance(patches, Patches):
        raise TypeError(f"expected a Patches object, got {type(patches).__name__}")
    if isinstance(names, str):
        names = (names,)
    unknown = [name for name in names if name not in VIEW_REGISTRY]
    if unknown:
        raise ValueError(f"unknown view(s) {unknown}; available views: {', '.join(available_views())}")
    options = options or {}
    out = []
    for name in names:
        F = np.asarray(VIEW_REGISTRY[name](patches, **options.get(name, {})))
        if F.ndim != 2 or F.shape[0] != patches.n:
            raise ValueError(f"view {name!r} returned shape {F.shape}, expected ({patches.n}, d)")
        out.append(np.ascontiguousarray(normalize_columns(F.T)))
    return out
