"""Tan-Triggs illumination normalization of a gray frame.

Reference: X. Tan and B. Triggs, "Enhanced local texture feature sets for face
recognition under difficult lighting conditions", IEEE TIP 19(6), 2010. The
SMTMVT paper applies it once per frame, before cropping the candidates.

The chain is::

    I  <- clip(I, 0) scaled to [0, 1] by dtype      (uint8 /255, uint16 /65535)
    I  <- I ** gamma                                  (gamma correction)
    I  <- G(sigma0) * I - G(sigma1) * I               (difference of Gaussians)
    I  <- I / mean(|I| ** alpha) ** (1 / alpha)       (contrast equalization 1)
    I  <- I / mean(min(tau, |I|) ** alpha) ** (1 / alpha)   (contrast equalization 2)
    I  <- tau * tanh(I / tau)                         (compress into (-tau, tau))

Gaussian filtering uses ``cv2.GaussianBlur`` (about 6x faster than
``scipy.ndimage.gaussian_filter`` on a 640x480 frame) with the kernel that
scipy would use: radius ``int(4 * sigma + 0.5)`` (scipy's ``truncate=4``) and
the border mode ``cv2.BORDER_REFLECT`` (``dcba|abcd``, scipy's ``'reflect'``),
so :func:`difference_of_gaussians` equals
``gaussian_filter(I, sigma0) - gaussian_filter(I, sigma1)`` up to float32
rounding. The DoG of a constant image is returned as exact zeros (filtering
would leave rounding noise of order 1e-17, which contrast equalization would
blow up to O(1) values); other images are centred on their mean before
filtering, which the unit-gain Gaussians make a no-op mathematically.

The whole chain is invariant to a positive scale of the input (gamma turns a
scale into a scale, DoG is linear, and contrast equalization divides it out),
so a uint8 frame and the same frame as uint16 (times 257) or as float give the
same output up to rounding.

The computation runs in float64 (about 6 ms for a 640x480 frame on one core;
float32 throughout is 4 ms but its DoG, a difference of nearly equal blurred
values that contrast equalization then scales up, is off by up to 3e-4 in the
output) and the result is returned as float32.
"""

from __future__ import annotations

import cv2
import numpy as np

__all__ = ["tan_triggs", "tan_triggs_scales", "difference_of_gaussians", "to_unit_float", "TAN_TRIGGS_REACH"]

_TRUNCATE = 4.0  # scipy.ndimage.gaussian_filter's default kernel truncation


def _gaussian_radius(sigma: float) -> int:
    """Pixels the Gaussian of :func:`difference_of_gaussians` reads on each side."""
    return int(_TRUNCATE * float(sigma) + 0.5)


#: Pixels the default chain (outer sigma 2) reads on each side of a pixel.
TAN_TRIGGS_REACH = _gaussian_radius(2.0)

#: Tan-Triggs' gamma correction exponent (their paper's 0.2; :func:`tan_triggs`'s default).
TAN_TRIGGS_GAMMA = 0.2


def to_unit_float(image: np.ndarray) -> np.ndarray:
    """Scale a gray image to float64 in [0, inf) by its dtype.

    Parameters
    ----------
    image : (H, W) ndarray of uint8, uint16 or float
        uint8 is divided by 255, uint16 by 65535; floats are taken as they are
        (so [0, 1] float frames stay in [0, 1]) and negative values clipped to 0.

    Returns
    -------
    (H, W) float64 ndarray, C-contiguous.
    """
    image = np.asarray(image)
    if image.ndim != 2:
        raise ValueError(f"expected a (H, W) gray image, got shape {image.shape}")
    if image.dtype == np.uint8:
        return image / 255.0
    if image.dtype == np.uint16:
        # v * 257 / 65535 == v / 255 exactly; both divisions are correctly rounded,
        # so a uint8 frame and the same frame times 257 as uint16 agree bit for bit.
        return image / 65535.0
    if np.issubdtype(image.dtype, np.floating):
        return np.maximum(np.ascontiguousarray(image, dtype=np.float64), 0.0)
    raise TypeError(f"unsupported image dtype {image.dtype}; expected uint8, uint16 or a float type")


def _gaussian(image: np.ndarray, sigma: float) -> np.ndarray:
    """Gaussian blur (float32 or float64) with scipy's kernel and 'reflect' border."""
    if sigma == 0:
        return image
    radius = _gaussian_radius(sigma)
    ksize = 2 * radius + 1
    return cv2.GaussianBlur(
        image,
        (ksize, ksize),
        sigmaX=float(sigma),
        sigmaY=float(sigma),
        borderType=cv2.BORDER_REFLECT,
    )


def difference_of_gaussians(image: np.ndarray, sigma0: float = 1.0, sigma1: float = 2.0) -> np.ndarray:
    """Band-pass a float image: ``G(sigma0) * I - G(sigma1) * I``.

    Parameters
    ----------
    image : (H, W) float ndarray
        Filtered in its own precision (float32 or float64; other types as float64).
    sigma0, sigma1 : float
        Standard deviations in pixels, ``0 <= sigma0 < sigma1``; ``sigma0 = 0``
        means no inner smoothing.

    Returns
    -------
    (H, W) ndarray of the input's float type. Equals
    ``scipy.ndimage.gaussian_filter(I, sigma0) - scipy.ndimage.gaussian_filter(I, sigma1)``
    (``mode='reflect'``, ``truncate=4``) up to rounding, and is exactly zero on a
    constant image.
    """
    image = np.asarray(image)
    if image.dtype != np.float32:
        image = image.astype(np.float64)
    if image.ndim != 2:
        raise ValueError(f"expected a (H, W) image, got shape {image.shape}")
    if not 0 <= sigma0 < sigma1:
        raise ValueError(f"need 0 <= sigma0 < sigma1, got sigma0={sigma0}, sigma1={sigma1}")
    low, high = image.min(initial=np.inf), image.max(initial=-np.inf)
    if not low < high:  # constant (or empty): the band-pass response is exactly zero
        return np.zeros_like(image)
    # Centring improves the conditioning of the subtraction; unit-gain filters ignore it.
    centred = np.ascontiguousarray(image - image.dtype.type(image.mean(dtype=np.float64)))
    return _gaussian(centred, sigma0) - _gaussian(centred, sigma1)


def _equalize(image: np.ndarray, alpha: float, tau: float | None, region=None, scale=None):
    """One contrast-equalization stage: ``(image / scale, scale)``, the statistic
    ``scale`` taken over ``image[region]`` (``region`` a pair of slices, or None:
    the whole image) unless it is given; an all-zero region (or a scale that is
    not positive) leaves the image all zero, with scale 0."""
    if scale is None:
        mag = np.abs(image if region is None else image[region])
        if tau is not None:
            np.minimum(mag, tau, out=mag)
        scale = float(np.mean(np.power(mag, alpha, out=mag))) ** (1.0 / alpha)
    if not scale > 0:  # all-zero image (or underflow): nothing to equalize
        return np.zeros_like(image), 0.0
    return image / scale, float(scale)


def tan_triggs(
    image: np.ndarray,
    gamma: float = TAN_TRIGGS_GAMMA,
    sigma0: float = 1.0,
    sigma1: float = 2.0,
    alpha: float = 0.1,
    tau: float = 10.0,
    region=None,
    scales=None,
) -> np.ndarray:
    """Tan-Triggs illumination normalization of a whole gray frame, or of a region of it.

    Parameters
    ----------
    image : (H, W) ndarray of uint8, uint16 or float
        Gray frame. Scaled to [0, 1] by dtype (see :func:`to_unit_float`).
    gamma : float
        Gamma correction exponent, ``0 < gamma <= 1`` (Tan-Triggs: 0.2).
    sigma0, sigma1 : float
        Inner and outer DoG standard deviations in pixels (1 and 2).
    alpha : float
        Exponent of the robust contrast-equalization means (0.1).
    tau : float
        Saturation level (10); the output lies in [-tau, tau].
    region : optional ``(slice, slice)`` (rows, columns) of ``image``: the
        contrast equalization takes its two means over these pixels only (a
        crop around the target then normalizes as if it were the frame).
        None: over the whole image. A crop should reach
        :data:`TAN_TRIGGS_REACH` pixels beyond the region on every side that
        is not the frame's border, so that the region's difference of
        Gaussians equals the frame's.
    scales : optional ``(s1, s2)`` float: the two equalizations' divisors,
        used as given instead of being measured (``region`` is then unused):
        those :func:`tan_triggs_scales` returned for another image (the whole
        frame) make a crop of it normalize as that image did.

    Returns
    -------
    (H, W) float32 ndarray in [-tau, tau]. A constant image gives all zeros.
    """
    return _chain(image, gamma, sigma0, sigma1, alpha, tau, region, scales)[0]


def tan_triggs_scales(image: np.ndarray, region=None, scales=None) -> tuple[np.ndarray, tuple[float, float]]:
    """:func:`tan_triggs` with its default parameters, and its two equalization
    divisors: ``(out, (s1, s2))``.

    ``s1 = mean(|D| ** alpha) ** (1 / alpha)`` of the difference of Gaussians
    ``D`` (over ``region``), ``s2`` the same of ``min(tau, |D / s1|)``; 0 where
    the stage met an all-zero statistic (the output is then all zero). With
    ``scales`` given they are returned as used.
    """
    return _chain(image, 0.2, 1.0, 2.0, 0.1, 10.0, region, scales)


def _chain(image, gamma, sigma0, sigma1, alpha, tau, region, scales) -> tuple[np.ndarray, tuple[float, float]]:
    """The normalization of :func:`tan_triggs` and its two divisors."""
    if not 0 < gamma <= 1:
        raise ValueError(f"gamma must be in (0, 1], got {gamma}")
    if not alpha > 0:
        raise ValueError(f"alpha must be > 0, got {alpha}")
    if not tau > 0:
        raise ValueError(f"tau must be > 0, got {tau}")
    given = (None, None) if scales is None else (float(scales[0]), float(scales[1]))
    img = to_unit_float(image)
    img = np.power(img, gamma, out=img)
    img = difference_of_gaussians(img, sigma0, sigma1)
    img, s1 = _equalize(img, alpha, None, region, given[0])
    img, s2 = _equalize(img, alpha, tau, region, given[1])
    out = np.tanh(img / tau, out=img)
    out *= tau
    # |tanh| <= 1 and rounding to float32 is monotone, so the result stays in [-tau, tau].
    return out.astype(np.float32), (s1, s2)
