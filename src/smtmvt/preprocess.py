"""Per-frame preprocessing: validate a frame, make its gray and color planes.

A frame is ``(H, W)`` (grayscale) or ``(H, W, 3)`` (RGB; a 4th alpha channel is
dropped), of dtype ``uint8``, ``uint16`` or float. Floats are taken as values in
``[0, 1]`` when their maximum is at most 1 and as ``[0, 255]`` otherwise. The
Tan-Triggs normalization (:func:`smtmvt.features.tan_triggs`) runs once here on
the whole gray frame (:func:`prepare_frame`, the paper), or on the window of it
that the frame's candidates read (:func:`prepare_crop`), before any candidate
is cropped.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import cv2
import numpy as np

from .features.tan_triggs import TAN_TRIGGS_REACH, tan_triggs_scales

__all__ = [
    "PreparedFrame",
    "check_frame",
    "check_same_size",
    "plane_window",
    "prepare_crop",
    "prepare_frame",
    "resize_frame",
    "sample_window",
    "smooth",
    "smooth_reach",
    "to_unit_range",
    "white_level",
]


@dataclass(frozen=True)
class PreparedFrame:
    """A frame ready for candidate extraction.

    Attributes
    ----------
    normalized : (H, W) float32 Tan-Triggs output (values in [-10, 10]).
    color : (H, W, C) float32 in [0, 1]; C = 3 (RGB) or 1 (grayscale frame).
    gray : (H, W) float32 gray frame in [0, 1] (before Tan-Triggs).
    origin : (x, y) float, where the planes' pixel (0, 0) sits in the whole
        plane (pixel-centre coordinates): a crop holds the point ``(u, v)`` of
        the whole plane at ``(u - x, v - y)``. (0, 0) for a whole frame.
    full_shape : (H, W) of the whole plane, or None when the planes are it.
    contrast : (s1, s2) float, the two divisors of Tan-Triggs' contrast
        equalization that made ``normalized``
        (:func:`~smtmvt.features.tan_triggs.tan_triggs_scales`).
    """

    normalized: np.ndarray
    color: np.ndarray
    gray: np.ndarray
    origin: tuple = (0.0, 0.0)
    full_shape: tuple | None = None
    contrast: tuple = (0.0, 0.0)

    @property
    def shape(self) -> tuple:
        """(H, W) of the planes held."""
        return self.normalized.shape

    @property
    def plane_shape(self) -> tuple:
        """(H, W) of the whole plane the planes held are a crop of."""
        return self.full_shape if self.full_shape is not None else self.shape


def to_unit_range(frame: np.ndarray, where: str = "frame", crop=None) -> np.ndarray:
    """Validate ``frame`` and return it as float32 in [0, 1], ``(H, W)`` or ``(H, W, 3)``.

    ``crop`` : optional ``(x0, y0, x1, y1)`` int: return only the pixels
    ``[y0:y1, x0:x1]``, the same values as cropping the whole result (an
    8- or 16-bit frame is converted there only; a float frame is checked and
    scaled as a whole).
    """
    a = _checked_image(frame, where)
    if crop is not None:
        x0, y0, x1, y1 = _inside(crop, a.shape, f"{where}: crop", "image")
        if a.dtype in (np.uint8, np.uint16):
            return _unit_float(a[y0:y1, x0:x1], where)
        return _unit_float(a, where)[y0:y1, x0:x1]
    return _unit_float(a, where)


def _inside(window, shape, what: str, of: str) -> tuple[int, int, int, int]:
    """``window (x0, y0, x1, y1)`` as ints, checked to be a non-empty part of
    an array of ``shape (H, W, ...)``; the error names ``what`` and ``of``."""
    x0, y0, x1, y1 = (int(v) for v in window)
    H, W = int(shape[0]), int(shape[1])
    if not (0 <= x0 < x1 <= W and 0 <= y0 < y1 <= H):
        raise ValueError(f"{what} {(x0, y0, x1, y1)} is not inside the {W}x{H} {of}")
    return x0, y0, x1, y1


def _checked_image(frame, where: str) -> np.ndarray:
    """``frame`` as an (H, W) or (H, W, 3) array (alpha or a single channel
    dropped); any other shape, or a side under 2 pixels, raises ValueError
    naming ``where``."""
    a = np.asarray(frame)
    if a.ndim == 3 and a.shape[2] == 4:
        a = a[:, :, :3]
    if a.ndim == 3 and a.shape[2] == 1:
        a = a[:, :, 0]
    if not (a.ndim == 2 or (a.ndim == 3 and a.shape[2] == 3)):
        raise ValueError(f"{where}: expected an (H, W) or (H, W, 3) image, got shape {a.shape}")
    if a.shape[0] < 2 or a.shape[1] < 2:
        raise ValueError(f"{where}: image of shape {a.shape} is too small")
    return a


def white_level(a: np.ndarray) -> float:
    """The value of white in an image of uint8 (255), uint16 (65535) or float
    values: 1 when the floats' maximum is at most 1, 255 otherwise (the
    convention of this module's docstring)."""
    if a.dtype == np.uint8:
        return 255.0
    if a.dtype == np.uint16:
        return 65535.0
    return 255.0 if float(np.max(a, initial=0.0)) > 1.0 else 1.0


def check_frame(frame, where: str) -> np.ndarray:
    """``frame`` checked as :func:`to_unit_range` checks it, not converted:
    returned as an (H, W) or (H, W, 3) array (alpha or a single channel
    dropped); any other shape, a side under 2 pixels, a dtype other than
    uint8, uint16 or float, or NaN or infinite values (as float32) raise
    ValueError naming ``where``."""
    a = _checked_image(frame, where)
    _check_values(a, where)
    return a


def check_same_size(frame, where: str, shape) -> None:
    """:func:`check_frame`, and ValueError when ``frame``'s height and width are
    not ``shape`` ``(H, W)``, the first frame's (boxes refer to one pixel grid)."""
    h, w = check_frame(frame, where).shape[:2]
    h0, w0 = shape
    if (h, w) != (h0, w0):
        raise ValueError(
            f"update: {where} is {w}x{h} pixels but init's frame was {w0}x{h0}: "
            "every frame must have the first frame's size (call init again for another size)"
        )


def _check_values(a: np.ndarray, where: str) -> None:
    """Raise ValueError naming ``where`` for a dtype other than uint8, uint16
    or float, or for NaN or infinite values (as float32)."""
    if a.dtype in (np.uint8, np.uint16):
        return
    if a.dtype == np.bool_ or np.issubdtype(a.dtype, np.integer):
        raise ValueError(f"{where}: unsupported integer dtype {a.dtype} (use uint8 or uint16)")
    if not np.issubdtype(a.dtype, np.floating):
        raise ValueError(f"{where}: unsupported dtype {a.dtype}")
    with np.errstate(over="ignore"):  # a value beyond float32 becomes inf, refused below
        finite = np.all(np.isfinite(a.astype(np.float32, copy=False)))
    if not finite:
        raise ValueError(f"{where}: image contains NaN or infinite values")


def _unit_float(a: np.ndarray, where: str) -> np.ndarray:
    """A checked image as float32 in [0, 1] by its dtype (:func:`white_level`)."""
    _check_values(a, where)
    if a.dtype in (np.uint8, np.uint16):
        return a.astype(np.float32) / white_level(a)
    f = a.astype(np.float32)
    white = white_level(f)
    if white != 1.0:
        f = f / white
    return np.clip(f, 0.0, 1.0)


def prepare_frame(
    frame: np.ndarray, where: str = "frame", channels: int | None = None, region=None, contrast=None
) -> PreparedFrame:
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
    region : optional ``(x0, y0, x1, y1)`` int, the pixels ``[y0:y1, x0:x1]``
        over which Tan-Triggs takes its contrast statistics (a crop of a
        frame, normalized like the region of the frame it will be read in);
        None: the whole frame.
    contrast : optional ``(s1, s2)``: Tan-Triggs' equalization divisors to use
        instead of measuring them (``region`` is then unused): the
        ``contrast`` of another prepared frame, for example the whole frame
        this one is a crop of.
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
    stats = None
    if region is not None:
        x0, y0, x1, y1 = _inside(region, f.shape, f"{where}: region", "frame")
        stats = (slice(y0, y1), slice(x0, x1))
    normalized, scales = tan_triggs_scales(gray, region=stats, scales=contrast)
    return PreparedFrame(
        normalized=normalized,
        color=np.ascontiguousarray(color),
        gray=np.ascontiguousarray(gray),
        contrast=scales,
    )


def prepare_crop(
    frame: np.ndarray, where: str, channels: int, window, scale, plane_shape, stats=None, contrast=None
) -> PreparedFrame:
    """The planes of :func:`prepare_frame` on a window of the whole plane only.

    The whole plane is ``frame`` resized by ``scale = (sx, sy)`` plane pixels
    per frame pixel (pixel edges to pixel edges), of shape ``plane_shape (H,
    W)``; ``window (x0, y0, x1, y1)`` int are the plane pixels that will be read
    (:func:`plane_window`), ``stats`` (the same form; None: ``window``) those
    Tan-Triggs takes its contrast statistics over, unless ``contrast (s1,
    s2)`` gives them (:func:`prepare_frame`). Only the frame pixels under
    both, plus a margin for Tan-Triggs' filters
    (:data:`~smtmvt.features.tan_triggs.TAN_TRIGGS_REACH`) and the
    interpolation, are converted and resized by exactly ``scale``. The result
    holds the crop, with its ``origin`` in the whole plane and ``full_shape =
    plane_shape``; inside the window its gray and color planes equal the whole
    plane's up to the resize's rounding (exactly, at scale 1).
    """
    a = _checked_image(frame, where)
    H, W = a.shape[:2]
    sx, sy = float(scale[0]), float(scale[1])
    stats = window if stats is None else stats
    x0, y0 = min(int(window[0]), int(stats[0])), min(int(window[1]), int(stats[1]))
    x1, y1 = max(int(window[2]), int(stats[2])), max(int(window[3]), int(stats[3]))
    r = TAN_TRIGGS_REACH + 2  # plane pixels: the filters' reach, and the resize's
    ix0, iy0 = max(math.floor((x0 - r) / sx), 0), max(math.floor((y0 - r) / sy), 0)
    ix1, iy1 = min(math.ceil((x1 + r) / sx), W), min(math.ceil((y1 + r) / sy), H)
    f = to_unit_range(a, where, crop=(ix0, iy0, ix1, iy1))
    if (sx, sy) != (1.0, 1.0):
        shrink = sx * sy < 1.0
        f = cv2.resize(f, None, fx=sx, fy=sy, interpolation=cv2.INTER_AREA if shrink else cv2.INTER_LINEAR)
    ox, oy = ix0 * sx, iy0 * sy  # the crop's pixel (0, 0) in the whole plane (pixel centres)
    h, w = f.shape[:2]
    sx0, sy0, sx1, sy1 = (int(v) for v in stats)
    region = (
        min(max(int(math.floor(sx0 - ox)), 0), w - 1),
        min(max(int(math.floor(sy0 - oy)), 0), h - 1),
        max(min(int(math.ceil(sx1 - ox)), w), 1),
        max(min(int(math.ceil(sy1 - oy)), h), 1),
    )
    prepared = prepare_frame(f, where, channels, region, contrast)
    return replace(prepared, origin=(ox, oy), full_shape=(int(plane_shape[0]), int(plane_shape[1])))


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


def plane_window(extent, shape, reach: int = 0) -> tuple[int, int, int, int]:
    """The pixels of a plane that sampling inside ``extent`` after smoothing reads.

    :func:`sample_window` of ``extent (x0, y0, x1, y1)`` (plane coordinates)
    grown by ``reach`` pixels on each side (:func:`smooth_reach` of the largest
    smoothing, plus one as :func:`smooth` itself), within the plane of
    ``shape (H, W)``: the ``window`` of :func:`prepare_crop` for those samples.
    """
    H, W = int(shape[0]), int(shape[1])
    x0, y0, x1, y1 = sample_window(extent, shape)
    r = int(reach)
    return max(x0 - r, 0), max(y0 - r, 0), min(x1 + r, W), min(y1 + r, H)


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
    x0, y0, x1, y1 = _inside(window, plane.shape, "smooth: window", "plane")
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
