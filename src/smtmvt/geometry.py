"""Boxes and affine states.

Coordinates
-----------
Boxes in the API are ``(x, y, w, h)`` floats in 0-based pixel coordinates: a box
with ``x = 0, w = 10`` covers pixel columns 0..9. Pixel *centres* sit at integer
coordinates, so that box spans the continuous interval ``[-0.5, 9.5]`` and its
centre is ``x + (w - 1) / 2`` (the OTB convention, shifted by one).

Affine state
------------
A particle is 6 numbers ``[a11, a12, a21, a22, tx, ty]`` mapping template
coordinates ``(u, v)`` to image coordinates (pixel centres)::

    X = a11 * u + a12 * v + tx
    Y = a21 * u + a22 * v + ty

Template coordinates are centred on the target and measured in a reference
frame of ``REF`` x ``REF`` units spanning the whole target (``u, v`` in
``[-REF/2, REF/2]``), as in L1-APG / MTT whose templates are 32 x 32 pixels. So an
axis-aligned box has ``a11 = w / REF``, ``a22 = h / REF``, ``a12 = a21 = 0`` and
``(tx, ty)`` at its centre, and the scale ``sc`` of the reference notes is about
the target size over 32.
"""

from __future__ import annotations

import numpy as np

__all__ = [
    "REF",
    "box_to_affine",
    "affine_to_box",
    "affine_extent",
    "affine_scale",
    "box_inside_fraction",
    "box_with_aspect",
    "box_scaled",
    "checked_box",
]

#: Size of the template reference frame, in template units.
REF = 32.0


def box_to_affine(box) -> np.ndarray:
    """Affine state of an axis-aligned 0-based box.

    Parameters
    ----------
    box : (4,) or (m, 4) array-like, ``(x, y, w, h)`` pixels, 0-based.

    Returns
    -------
    (6,) or (m, 6) float64 ``[a11, a12, a21, a22, tx, ty]``.
    """
    b = np.asarray(box, dtype=np.float64)
    single = b.ndim == 1
    b = np.atleast_2d(b)
    x, y, w, h = b.T
    p = np.zeros((len(b), 6))
    p[:, 0] = w / REF
    p[:, 3] = h / REF
    p[:, 4] = x + (w - 1.0) / 2.0
    p[:, 5] = y + (h - 1.0) / 2.0
    return p[0] if single else p


def affine_to_box(params) -> np.ndarray:
    """Axis-aligned box of an affine state.

    The box is centred on ``(tx, ty)``; its width and height are the lengths of
    the images of the template's horizontal and vertical sides (so a rotated or
    sheared state gives the box of the same size, not the bounding box of the
    rotated quadrilateral, which would grow with rotation).

    Parameters
    ----------
    params : (6,) or (m, 6) affine states.

    Returns
    -------
    (4,) or (m, 4) float64 boxes ``(x, y, w, h)``, 0-based pixels.
    """
    p = np.asarray(params, dtype=np.float64)
    single = p.ndim == 1
    p = np.atleast_2d(p)
    w = REF * np.hypot(p[:, 0], p[:, 2])
    h = REF * np.hypot(p[:, 1], p[:, 3])
    x = p[:, 4] - (w - 1.0) / 2.0
    y = p[:, 5] - (h - 1.0) / 2.0
    out = np.stack([x, y, w, h], axis=1)
    return out[0] if single else out


def affine_extent(params) -> tuple[float, float, float, float]:
    """Bounding box ``(x0, y0, x1, y1)`` (pixel coordinates) of the template squares of all states.

    The corners ``u, v = +-REF/2`` of each state's template frame are mapped by
    its affine transform; every point a patch samples (see
    :func:`smtmvt.warp.sampling_grid`) lies inside this box.

    Parameters
    ----------
    params : (6,) or (m, 6) affine states, m >= 1.
    """
    p = np.atleast_2d(np.asarray(params, dtype=np.float64))
    if len(p) == 0:
        raise ValueError("affine_extent needs at least one state")
    half = REF / 2.0
    # |a u + b v| <= (|a| + |b|) REF/2 over the square, reached at a corner
    rx = (np.abs(p[:, 0]) + np.abs(p[:, 1])) * half
    ry = (np.abs(p[:, 2]) + np.abs(p[:, 3])) * half
    return (
        float(np.min(p[:, 4] - rx)),
        float(np.min(p[:, 5] - ry)),
        float(np.max(p[:, 4] + rx)),
        float(np.max(p[:, 5] + ry)),
    )


def affine_scale(params) -> np.ndarray:
    """Scale ``sc = sqrt((a11^2 + a12^2 + a21^2 + a22^2) / 2)`` of each state, ``(m,)``."""
    p = np.atleast_2d(np.asarray(params, dtype=np.float64))
    return np.sqrt((p[:, :4] ** 2).sum(axis=1) / 2.0)


def box_inside_fraction(box, shape) -> float:
    """Fraction of the area of a 0-based box ``(x, y, w, h)`` inside an image of ``shape`` (H, W[, C]).

    0 for a box of zero or negative size; used to reject boxes mostly outside.
    """
    x, y, w, h = (float(v) for v in box)
    H, W = shape[:2]
    ix = max(0.0, min(x + w, W) - max(x, 0.0))
    iy = max(0.0, min(y + h, H) - max(y, 0.0))
    return ix * iy / (w * h) if w > 0 and h > 0 else 0.0


def box_with_aspect(box, aspect: float, fraction: float = 1.0) -> np.ndarray:
    """The box of the same centre and area with its aspect ratio moved toward ``aspect``.

    Parameters
    ----------
    box : (4,) or (m, 4) array-like, ``(x, y, w, h)`` pixels, 0-based, ``w, h > 0``.
    aspect : float > 0, the target aspect ratio ``h / w``.
    fraction : float in [0, 1], how far the log aspect ratio moves:
        ``log(h' / w') = (1 - fraction) log(h / w) + fraction log(aspect)``;
        0 returns the box, 1 gives it ``aspect`` exactly.

    Returns
    -------
    (4,) or (m, 4) float64 boxes with ``w' h' = w h`` and the centre
    ``(x + (w - 1) / 2, y + (h - 1) / 2)`` unchanged.
    """
    b = np.asarray(box, dtype=np.float64)
    single = b.ndim == 1
    b = np.atleast_2d(b)
    if not aspect > 0 or not 0 <= fraction <= 1:
        raise ValueError(f"box_with_aspect: need aspect > 0 and fraction in [0, 1], got {aspect!r}, {fraction!r}")
    x, y, w, h = b.T
    if fraction == 0:
        out = b.copy()
    else:
        log_aspect = (1.0 - fraction) * np.log(h / w) + fraction * np.log(aspect)
        area = w * h
        w2 = np.sqrt(area / np.exp(log_aspect))
        h2 = np.sqrt(area * np.exp(log_aspect))
        out = np.stack([x + (w - w2) / 2.0, y + (h - h2) / 2.0, w2, h2], axis=1)
    return out[0] if single else out


def box_scaled(box, factor: float) -> np.ndarray:
    """The box of the same centre with its width and height times ``factor``.

    Parameters
    ----------
    box : (4,) or (m, 4) array-like, ``(x, y, w, h)`` pixels, 0-based.
    factor : float > 0.

    Returns
    -------
    (4,) or (m, 4) float64 boxes ``(x', y', factor w, factor h)`` with the
    centre ``(x + (w - 1) / 2, y + (h - 1) / 2)`` unchanged.
    """
    if not factor > 0:
        raise ValueError(f"box_scaled: need factor > 0, got {factor!r}")
    b = np.array(box, dtype=np.float64)
    b[..., :2] += b[..., 2:] * (1.0 - factor) / 2.0
    b[..., 2:] *= factor
    return b


def checked_box(box, where: str) -> np.ndarray:
    """``box`` as a (4,) float64 ``(x, y, w, h)``; ValueError naming ``where``
    unless it is 4 finite numbers with a positive width and height."""
    b = np.asarray(box, dtype=np.float64).reshape(-1)
    shown = tuple(b.tolist())  # plain numbers in messages, not np.float64(...)
    if b.size != 4 or not np.all(np.isfinite(b)):
        raise ValueError(f"{where}: box must be 4 finite numbers (x, y, w, h), got {shown}")
    if b[2] <= 0 or b[3] <= 0:
        raise ValueError(f"{where}: box {shown} has zero or negative size")
    return b
