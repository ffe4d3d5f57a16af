"""Per-frame preprocessing: validate a frame, make its gray and color planes.

A frame is ``(H, W)`` (grayscale) or ``(H, W, 3)`` (RGB; a 4th alpha channel is
dropped), of dtype ``uint8``, ``uint16`` or float. Floats are taken as values in
``[0, 1]`` when their maximum is at most 1 and as ``[0, 255]`` otherwise. The
Tan-Triggs normalization (:func:`smtmvt.features.tan_triggs`) runs once here on
the whole gray frame, before any candidate is cropped.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import cv2
import numpy as np

from .features import tan_triggs

__all__ = ["PreparedFrame", "prepare_frame", "resize_frame", "sample_window", "smooth", "smooth_reach", "to_unit_range"]


@dataclass(frozen=True)
class PreparedFrame:
    """A frame ready for candidate extraction.

    Attributes
    ----------
    normalized : (H, W) float32 Tan-Triggs output (values in [-10, 10]).
    color : (H, W, C) float32 in [0, 1]; C = 3 (RGB) or 1 (grayscale frame).
    gray : (H, W) float32 gray frame in [0, 1] (before Tan-Triggs).
    """

    normalized: np.ndarray
    color: np.ndarray
    gray: np.ndarray

    @property
    def shape(self) -> tuple:
        return self.normalized.shape


def to_unit_range(frame: np.ndarray, where: str = "frame") -> np.ndarray:
    """Validate ``frame`` and return it as float32 in [0, 1], ``(H, W)`` or ``(H, W, 3)``."""
    a = np.asarray(frame)
    if a.ndim == 3 and a.shape[2] == 4:
        a = a[:, :, :3]
    if a.ndim == 3 and a.shape[2] == 1:
        a = a[:, :, 0]
    if not (a.ndim == 2 or (a.ndim == 3 and a.shape[2] == 3)):
        raise ValueError(f"{where}: expected an (H, W) or (H, W, 3) image, got shape {a.shape}")
    if a.shape[0] < 2 or a.shape[1] < 2:
        raise ValueError(f"{where}: image of shape {a.shape} is too small")
    if a.dtype == np.uint8:
        return a.astype(np.float32) / 255.0
    if a.dtype == np.uint16:
        return a.astype(np.float32) / 65535.0
    if a.dtype == np.bool_ or np.issubdtype(a.dtype, np.integer):
        raise ValueError(f"{where}: unsupported integer dtype {a.dtype} (use uint8 or uint16)")
    if not np.issubdtype(a.dtype, np.floating):
        raise ValueError(f"{where}: unsupported dtype {a.dtype}")
    f = a.astype(np.float32)
    if not np.all(np.isfinite(f)):
        raise ValueError(f"{where}: image contains NaN or infinite values")
    if f.max(initial=0.0) > 1.0:
        f = f / 255.0
    return np.clip(f, 0.0, 1.0)


def prepare_frame(frame: np.ndarray, where: str = "frame", channels: int | None = None) -> PreparedFrame:
    """Validate ``frame`` and compute its Tan-Triggs gray plane and color plane.

    Parameters
    ----------
    frame : (H, W) or (H, W, 3) image.
    where : name of the frame for error messages.
    channels : number of color channels to produce, 1 or 3, or None to decide
        from the frame: a color frame whose three channels are identical is
        then treated as grayscale, so gray sequences stored as RGB files use the
        color view's gray fallback. The tracker decides once, on its first
        frame, and passes the answer for every later frame so that the color
        view keeps one dimension through the sequence.
    """
    f = to_unit_range(frame, where)
    if channels is None:
        gray_input = f.ndim == 2 or (np.array_equal(f[..., 0], f[..., 1]) and np.array_equal(f[..., 0], f[..., 2]))
        channels = 1 if gray_input else 3
    if channels not in (1, 3):
        raise ValueError(f"{where}: channels must be 1 or 3, got {channels!r}")
    gray = f if f.ndim == 2 else cv2.cvtColor(f, cv2.COLOR_RGB2GRAY)
    if channels == 1:
        color = gray[:, :, None]
    else:
        color = f if f.ndim == 3 else np.repeat(f[:, :, None], 3, axis=2)
    return PreparedFrame(
        normalized=tan_triggs(gray), color=np.ascontiguousarray(color), gray=np.ascontiguousarray(gray)
    )


def resize_frame(frame: np.ndarray, size) -> np.ndarray:
    """``frame`` resized to ``size = (width, height)`` pixels (area averaging when shrinking).

    Pixel edges map to pixel edges: a 0-based box ``(x, y, w, h)`` becomes
    ``(x sx, y sy, w sx, h sy)`` with ``sx = width / W``, ``sy = height / H``.
    """
    a = np.asarray(frame)
    W, H = int(size[0]), int(size[1])
    if (a.shape[1], a.shape[0]) == (W, H):
        return a
    shrink = W * H < a.shape[0] * a.shape[1]
    return cv2.resize(a, (W, H), interpolation=cv2.INTER_AREA if shrink else cv2.INTER_LINEAR)


#: Below this sigma (pixels) :func:`smooth` returns the plane as it is (the kernel would be a delta).
SMOOTH_MIN_SIGMA = 0.3


def smooth_reach(sigma: float) -> int:
    """Pixels :func:`smooth` reads on each side of a pixel (0 below ``SMOOTH_MIN_SIGMA``)."""
    if sigma < SMOOTH_MIN_SIGMA:
        return 0
    # OpenCV's kernel for float planes: size round(8 sigma + 1), made odd
    return (int(round(8.0 * sigma + 1.0)) | 1) // 2


def sample_window(extent, shape) -> tuple[int, int, int, int]:
    """The pixels that bilinear samples inside ``extent`` read, within the plane.

    Parameters
    ----------
    extent : (x0, y0, x1, y1) float, plane coordinates (0-based pixel
        centres) bounding every sample point.
    shape : (H, W) of the plane.

    Returns
    -------
    (x0, y0, x1, y1) int: the window ``[x0, x1) x [y0, y1)``, at least 2
    pixels wide and high, holding both neighbours of every sample along each
    axis. Where samples leave the plane the window reaches its border, whose
    pixels the samples then read (``BORDER_REPLICATE``).
    """
    H, W = int(shape[0]), int(shape[1])
    ex0, ey0, ex1, ey1 = (float(v) for v in extent)
    if not all(math.isfinite(v) for v in (ex0, ey0, ex1, ey1)):
        raise ValueError(f"sample_window: extent {extent} is not finite")

    def axis(lo: float, hi: float, size: int) -> tuple[int, int]:
        a = min(max(math.floor(lo) - 1, 0), size - 2)
        b = max(min(math.floor(hi) + 3, size), a + 2)
        return a, b

    x0, x1 = axis(ex0, ex1, W)
    y0, y1 = axis(ey0, ey1, H)
    return x0, y0, x1, y1


_ALIGN = 32  # columns; a multiple of every SIMD width of float32 rows (AVX-512: 16)


def smooth(plane: np.ndarray, sigma: float, window=None) -> np.ndarray:
    """Gaussian smoothing of an (H, W) or (H, W, C) float32 plane (``sigma`` pixels).

    Below ``SMOOTH_MIN_SIGMA`` pixels the plane is returned as it is.

    ``window`` : optional ``(x0, y0, x1, y1)`` int (see :func:`sample_window`):
    only the pixels ``[y0:y1, x0:x1]`` are computed, from the window grown by
    the kernel's reach (:func:`smooth_reach`, clipped to the plane), so they
    equal the whole plane's smoothing bit for bit; the other pixels of the
    returned plane are zero. The result has the plane's shape (also
    ``(H, W, 1)``).
    """
    if sigma < SMOOTH_MIN_SIGMA:
        return plane
    if window is None:
        return cv2.GaussianBlur(plane, (0, 0), float(sigma), borderType=cv2.BORDER_REFLECT).reshape(plane.shape)
    H, W = plane.shape[:2]
    x0, y0, x1, y1 = (int(v) for v in window)
    if not (0 <= x0 < x1 <= W and 0 <= y0 < y1 <= H):
        raise ValueError(f"smooth: window {(x0, y0, x1, y1)} is not inside the {W}x{H} plane")
    r = smooth_reach(sigma) + 1  # one more than the kernel's radius: safe from its rounding
    # The crop's columns start and end on multiples of _ALIGN (or at the plane's edges), so
    # that OpenCV's vectorized row filter treats each pixel as in the whole plane (a
    # pixel in the scalar tail of a row is rounded otherwise). cv2 reflects at the
    # crop's edges: only those on the plane's own edges keep pixels within r of them.
    gx0 = (max(x0 - r, 0) // _ALIGN) * _ALIGN
    gx1 = min(-(-(x1 + r) // _ALIGN) * _ALIGN, W)
    gy0, gy1 = max(y0 - r, 0), min(y1 + r, H)
    part = cv2.GaussianBlur(
        np.ascontiguousarray(plane[gy0:gy1, gx0:gx1]), (0, 0), float(sigma), borderType=cv2.BORDER_REFLECT
    )
    part = part.reshape(part.shape[:2] + plane.shape[2:])  # cv2 drops a single channel's axis
    out = np.zeros_like(plane)
    out[y0:y1, x0:x1] = part[y0 - gy0 : y1 - gy0, x0 - gx0 : x1 - gx0]
    return out
