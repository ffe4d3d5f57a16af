"""Per-frame preprocessing: validate a frame, make its gray and color planes.

A frame is ``(H, W)`` (grayscale) or ``(H, W, 3)`` (RGB; a 4th alpha channel is
dropped), of dtype ``uint8``, ``uint16`` or float. Floats are taken as values in
``[0, 1]`` when their maximum is at most 1 and as ``[0, 255]`` otherwise. The
Tan-Triggs normalization (:func:`smtmvt.features.tan_triggs`) runs here, before
any candidate is cropped: on the whole frame, or on a *window* of it that holds
every pixel the frame's candidates can read (:func:`crop_window`). Its filters
are local, so inside the window the planes are those of the whole frame except
for Tan-Triggs' two contrast-equalization constants, which are then means over
the window instead of over the frame (a positive scale of the plane, which the
intensity view's normalization removes, and where the tanh compression bites).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import cv2
import numpy as np

from .features import tan_triggs

__all__ = [
    "PreparedFrame",
    "color_channels",
    "crop_window",
    "prepare_frame",
    "resize_frame",
    "smooth",
    "smooth_reach",
    "to_unit_range",
]

#: Pixels of a plane that Tan-Triggs' difference of Gaussians reads on each side (its
#: outer Gaussian: sigma 2, truncated at 4 sigma).
TAN_TRIGGS_REACH = 8


@dataclass(frozen=True)
class PreparedFrame:
    """A frame (or a window of it) ready for candidate extraction.

    Attributes
    ----------
    normalized : (h, w) float32 Tan-Triggs output (values in [-10, 10]).
    color : (h, w, C) float32 in [0, 1]; C = 3 (RGB) or 1 (grayscale frame).
    gray : (h, w) float32 gray frame in [0, 1] (before Tan-Triggs).
    origin : (x0, y0) int, the frame pixel at the planes' top-left pixel (0, 0
        for the whole frame).
    scale : (sx, sy) float, plane pixels per frame pixel (1 unless the window was resized).
    """

    normalized: np.ndarray
    color: np.ndarray
    gray: np.ndarray
    origin: tuple[int, int] = (0, 0)
    scale: tuple[float, float] = (1.0, 1.0)

    @property
    def shape(self) -> tuple:
        """(h, w) of the planes."""
        return self.normalized.shape

    def to_plane(self, params: np.ndarray) -> np.ndarray:
        """Affine states in frame coordinates -> the same states in the planes' coordinates, ``(m, 6)``.

        Pixel edges map to pixel edges, ``x' = (x - x0 + 0.5) sx - 0.5``: an
        affine map of the sample points, so it is applied to the states (a
        patch sampled from the new state on the planes reads the points the
        old one reads on the frame).
        """
        p = np.array(params, dtype=np.float64, copy=True, ndmin=2)
        (x0, y0), (sx, sy) = self.origin, self.scale
        if (sx, sy) == (1.0, 1.0):
            p[:, 4] -= x0
            p[:, 5] -= y0
            return p
        p[:, [0, 1, 4]] *= sx
        p[:, [2, 3, 5]] *= sy
        p[:, 4] += (0.5 - x0) * sx - 0.5
        p[:, 5] += (0.5 - y0) * sy - 0.5
        return p


def _as_image(frame: np.ndarray, where: str) -> np.ndarray:
    """``frame`` as an (H, W) or (H, W, 3) array of a supported dtype (a view; alpha dropped)."""
    a = np.asarray(frame)
    if a.ndim == 3 and a.shape[2] == 4:
        a = a[:, :, :3]
    if a.ndim == 3 and a.shape[2] == 1:
        a = a[:, :, 0]
    if not (a.ndim == 2 or (a.ndim == 3 and a.shape[2] == 3)):
        raise ValueError(f"{where}: expected an (H, W) or (H, W, 3) image, got shape {a.shape}")
    if a.shape[0] < 2 or a.shape[1] < 2:
        raise ValueError(f"{where}: image of shape {a.shape} is too small")
    if a.dtype in (np.uint8, np.uint16) or np.issubdtype(a.dtype, np.floating):
        return a
    if a.dtype == np.bool_ or np.issubdtype(a.dtype, np.integer):
        raise ValueError(f"{where}: unsupported integer dtype {a.dtype} (use uint8 or uint16)")
    raise ValueError(f"{where}: unsupported dtype {a.dtype}")


def to_unit_range(frame: np.ndarray, where: str = "frame") -> np.ndarray:
    """Validate ``frame`` and return it as float32 in [0, 1], ``(H, W)`` or ``(H, W, 3)``."""
    a = _as_image(frame, where)
    if a.dtype == np.uint8:
        return a.astype(np.float32) / 255.0
    if a.dtype == np.uint16:
        return a.astype(np.float32) / 65535.0
    f = a.astype(np.float32)
    if not np.all(np.isfinite(f)):
        raise ValueError(f"{where}: image contains NaN or infinite values")
    if f.max(initial=0.0) > 1.0:
        f = f / 255.0
    return np.clip(f, 0.0, 1.0)


def color_channels(frame: np.ndarray, where: str = "frame") -> int:
    """3 for a color frame, 1 for a gray one (``(H, W)``, or three identical channels)."""
    a = _as_image(frame, where)
    if a.ndim == 2 or (np.array_equal(a[..., 0], a[..., 1]) and np.array_equal(a[..., 0], a[..., 2])):
        return 1
    return 3


def smooth_reach(sigma: float) -> int:
    """Pixels :func:`smooth` reads on each side of a pixel (0 below its threshold)."""
    if sigma < 0.3:
        return 0
    # OpenCV's kernel for float planes: size round(8 sigma + 1), made odd
    return (int(round(8.0 * sigma + 1.0)) | 1) // 2


def crop_window(extent, margin: float, shape) -> tuple[int, int, int, int]:
    """The pixels a set of samples can read: ``extent`` grown by ``margin``, inside the frame.

    Parameters
    ----------
    extent : (x0, y0, x1, y1) float, frame coordinates (0-based pixel centres)
        bounding every sample point.
    margin : float >= 0, pixels added on each side (filters' reach, bilinear
        neighbours).
    shape : (H, W) of the frame.

    Returns
    -------
    (x0, y0, x1, y1) int: the window ``[x0, x1) x [y0, y1)``, at least 2 pixels
    wide and high. Where the samples leave the frame the window reaches the
    frame's border, so that samples outside read the border pixels as they
    would in the whole frame.
    """
    H, W = int(shape[0]), int(shape[1])
    ex0, ey0, ex1, ey1 = (float(v) for v in extent)
    if not all(math.isfinite(v) for v in (ex0, ey0, ex1, ey1)):
        raise ValueError(f"crop_window: extent {extent} is not finite")

    def axis(lo: float, hi: float, size: int) -> tuple[int, int]:
        a = min(max(int(math.floor(lo - margin)), 0), size - 2)
        b = max(min(int(math.ceil(hi + margin)) + 1, size), a + 2)
        return a, b

    x0, x1 = axis(ex0, ex1, W)
    y0, y1 = axis(ey0, ey1, H)
    return x0, y0, x1, y1


def prepare_frame(
    frame: np.ndarray,
    where: str = "frame",
    channels: int | None = None,
    window=None,
    plane_scale: float = 1.0,
) -> PreparedFrame:
    """Validate ``frame`` and compute its Tan-Triggs gray plane and color plane.

    Parameters
    ----------
    frame : (H, W) or (H, W, 3) image.
    where : name of the frame for error messages.
    channels : number of color channels to produce, 1 or 3, or None to decide
        from the frame (:func:`color_channels`): a color frame whose three
        channels are identical is then treated as grayscale, so gray sequences
        stored as RGB files use the color view's gray fallback. The tracker
        decides once, on its first frame, and passes the answer for every
        later frame so that the color view keeps one dimension through the
        sequence.
    window : optional (x0, y0, x1, y1) int (:func:`crop_window`): the planes are
        made of ``frame[y0:y1, x0:x1]`` only. None: the whole frame.
    plane_scale : the planes are the window resized by this factor (area
        averaging when shrinking); ``PreparedFrame.scale`` holds the exact
        factors after rounding the size.
    """
    image = _as_image(frame, where)
    if channels is None:
        channels = color_channels(image, where)
    if channels not in (1, 3):
        raise ValueError(f"{where}: channels must be 1 or 3, got {channels!r}")
    H, W = image.shape[:2]
    x0, y0, x1, y1 = (0, 0, W, H) if window is None else (int(v) for v in window)
    if not (0 <= x0 < x1 <= W and 0 <= y0 < y1 <= H):
        raise ValueError(f"{where}: window {(x0, y0, x1, y1)} is not inside the {W}x{H} frame")
    if np.issubdtype(image.dtype, np.floating):
        f = to_unit_range(image, where)[y0:y1, x0:x1]  # the [0, 255] test is on the whole frame
    else:
        f = to_unit_range(image[y0:y1, x0:x1], where)
    scale = (1.0, 1.0)
    if plane_scale != 1.0:
        size = (max(2, int(round((x1 - x0) * plane_scale))), max(2, int(round((y1 - y0) * plane_scale))))
        f = resize_frame(f, size)
        scale = (size[0] / (x1 - x0), size[1] / (y1 - y0))
    gray = f if f.ndim == 2 else cv2.cvtColor(f, cv2.COLOR_RGB2GRAY)
    if channels == 1:
        color = gray[:, :, None]
    else:
        color = f if f.ndim == 3 else np.repeat(f[:, :, None], 3, axis=2)
    return PreparedFrame(
        normalized=tan_triggs(gray),
        color=np.ascontiguousarray(color),
        gray=np.ascontiguousarray(gray),
        origin=(x0, y0),
        scale=scale,
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


def smooth(plane: np.ndarray, sigma: float) -> np.ndarray:
    """Gaussian smoothing of an (H, W) or (H, W, C) float32 plane (``sigma`` pixels).

    Below 0.3 pixels the plane is returned as it is (the kernel would be a delta).
    """
    if sigma < 0.3:
        return plane
    return cv2.GaussianBlur(plane, (0, 0), float(sigma), borderType=cv2.BORDER_REFLECT)
