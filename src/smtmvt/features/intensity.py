"""Intensity view: the Tan-Triggs normalized gray template, flattened.

The template size follows the SMTMVT paper (after MTMVT, Hong et al. 2013): one
third of the initial target size, or one half when the target's shorter side
is under 20 pixels.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["intensity_template_size", "intensity_view"]

MIN_TEMPLATE_SIDE = 4  # pixels; below this an intensity template carries no layout


def _round_half_up(x: float) -> int:
    return int(math.floor(x + 0.5))


def intensity_template_size(w: float, h: float, factor: float | None = None) -> tuple[int, int]:
    """Size of the intensity template for an initial target of ``w x h`` pixels.

    Parameters
    ----------
    w, h : float
        Width and height of the initial target box, pixels (> 0).
    factor : optional float > 0
        Template pixels per target pixel instead of the paper's rule below.

    Returns
    -------
    (th, tw) : tuple of int
        Template height and width: ``round(h / 3)``, ``round(w / 3)``, or
        ``round(h / 2)``, ``round(w / 2)`` when ``min(w, h) < 20``; halves
        round up; each side at least 4 pixels.
    """
    w = float(w)
    h = float(h)
    if not (w > 0 and h > 0) or not (math.isfinite(w) and math.isfinite(h)):
        raise ValueError(f"target size must be positive and finite, got w={w}, h={h}")
    if factor is None:
        factor = 0.5 if min(w, h) < 20 else 1.0 / 3.0
    elif not factor > 0:
        raise ValueError(f"intensity template factor must be > 0, got {factor!r}")
    th = max(MIN_TEMPLATE_SIDE, _round_half_up(h * factor))
    tw = max(MIN_TEMPLATE_SIDE, _round_half_up(w * factor))
    return th, tw


def intensity_view(patches) -> np.ndarray:
    """Flattened intensity templates.

    Parameters
    ----------
    patches : Patches
        Uses ``patches.intensity``, ``(n, th, tw)`` float32 Tan-Triggs gray.

    Returns
    -------
    (n, th * tw) float32 ndarray, row-major pixel order.
    """
    x = patches.intensity
    if x is None:
        raise ValueError("Patches.intensity (the intensity template patches) was not given")
    return np.ascontiguousarray(x.reshape(x.shape[0], -1), dtype=np.float32)
