"""Cell layout shared by the histogram views (color, LBP): a ``grid x grid``
split of a patch into nearly equal cells."""

from __future__ import annotations

import numpy as np

__all__ = ["cell_bounds", "cell_map"]


def cell_bounds(length: int, grid: int) -> np.ndarray:
    """(grid + 1,) int edges along an axis: cell ``j`` covers pixels
    ``[j L // grid, (j + 1) L // grid)`` of an axis of ``L = length`` pixels
    (equal cells when ``grid`` divides L)."""
    return (np.arange(grid + 1) * int(length)) // int(grid)


def cell_map(height: int, width: int, grid: int) -> np.ndarray:
    """(height, width) intp cell of each pixel, numbered row-major
    (``cell_row * grid + cell_col``), with the edges of :func:`cell_bounds`."""

    def index(length):
        return np.searchsorted(cell_bounds(length, grid), np.arange(length), side="right") - 1

    return index(height)[:, None] * int(grid) + index(width)[None, :]
