"""The camera's own motion between two frames: the background's translation.

A hand-held or panning camera moves every pixel of the frame at once; a jerk
of a few tens of pixels carries a small target out of the correlation
filter's window (the target moved with the background, not by itself). The
translation of the whole frame is found by phase correlation (Kuglin and
Hines 1975; ``cv2.phaseCorrelate``, with a Hann window) of the two frames in
gray, reduced by a whole factor so that the longer side is at most
``SIDE`` pixels (the shift is needed to a fraction of a box, not to a
pixel).

It is a hypothesis, not a fact: where the camera follows the target (a
runner filmed by a panning camera) the background moves and the target does
not. The tracker therefore lets the correlation filter choose between the
prediction and the prediction moved by the camera (``config.camera_motion``):
:class:`CameraMotion` proposes the move, the tracker asks the filter.
"""

from __future__ import annotations

import cv2
import numpy as np

__all__ = ["SIDE", "reduced_gray", "frame_shift", "CameraMotion"]

#: The longer side, in pixels, of the reduced frames that are compared (at most).
SIDE = 160


def reduced_gray(frame: np.ndarray) -> tuple[np.ndarray, int]:
    """The frame reduced by a whole factor so that its longer side is at most
    ``SIDE`` (area averaging), then in gray: ``(image (h, w) float32, factor)``.

    ``frame`` : (H, W) or (H, W, 3) RGB, any numeric type.
    """
    f = np.asarray(frame)
    if f.dtype not in (np.uint8, np.uint16, np.float32):
        f = f.astype(np.float32)
    factor = max(1, -(-max(f.shape[:2]) // SIDE))
    if factor > 1:
        size = (max(1, f.shape[1] // factor), max(1, f.shape[0] // factor))
        f = cv2.resize(f, size, interpolation=cv2.INTER_AREA)
    if f.ndim == 3:
        f = cv2.cvtColor(f, cv2.COLOR_RGB2GRAY)
    return np.ascontiguousarray(f, dtype=np.float32), factor


def frame_shift(before: np.ndarray, after: np.ndarray, factor: int) -> np.ndarray:
    """The translation ``(dx, dy)`` of the content from ``before`` to ``after``
    (two :func:`reduced_gray` images of one size), in the frames' pixels
    (``factor`` times the reduced images'), float64."""
    if before.shape != after.shape:
        raise ValueError(f"frame_shift: reduced frames of different shapes {before.shape} and {after.shape}")
    if min(before.shape) < 8:
        return np.zeros(2)
    window = cv2.createHanningWindow((before.shape[1], before.shape[0]), cv2.CV_32F)
    (dx, dy), _ = cv2.phaseCorrelate(before, after, window)
    return np.array([dx, dy], dtype=np.float64) * factor


class CameraMotion:
    """The camera's move since the last frame, proposed when it is large.

    Keeps the last frame reduced (:func:`reduced_gray`). :meth:`propose`
    compares a new frame with it; :meth:`taken` makes the new frame the last
    one (after the frame was read whole), :meth:`dropped` forgets it (a frame
    that could not be read leaves the object as it was).
    """

    def __init__(self, frame: np.ndarray) -> None:
        self.last = reduced_gray(frame)
        self.pending: tuple[np.ndarray, int] | None = None
        #: the move the track followed on the last frame (``(2,)`` frame pixels), or None
        self.followed: np.ndarray | None = None
        self._following: np.ndarray | None = None  # this frame's, until taken

    def propose(self, frame: np.ndarray, box) -> np.ndarray | None:
        """The camera's move ``(dx, dy)`` (frame pixels, float64) since the last
        frame where it is longer than half the square root of ``box``'s area
        (``(x, y, w, h)``, frame pixels; the half of the correlation cue's
        ``near_peak``), else None."""
        small, factor = self.pending = reduced_gray(frame)
        before, before_factor = self.last
        if before.shape != small.shape or before_factor != factor:
            return None
        shift = frame_shift(before, small, factor)
        b = np.asarray(box, dtype=np.float64)
        return shift if np.hypot(*shift) > 0.5 * np.sqrt(b[2] * b[3]) else None

    def hypotheses(self, frame: np.ndarray, box) -> list[np.ndarray]:
        """The moves to try for this frame, in order: :meth:`propose`'s (where
        large), then the last frame's followed move undone (a shake swings back,
        and the blurred frame of the swing can hide it from the phase
        correlation)."""
        shift = self.propose(frame, box)
        out = [] if shift is None else [shift]
        if self.followed is not None:
            out.append(-self.followed)
        return out

    def follow(self, shift: np.ndarray) -> None:
        """The track follows ``shift`` on this frame (:attr:`followed` once taken)."""
        self._following = np.asarray(shift, dtype=np.float64)

    def taken(self) -> None:
        """The frame of the last :meth:`propose` becomes the last frame, and its
        followed move (or None) :attr:`followed`."""
        if self.pending is not None:
            self.last, self.pending = self.pending, None
        self.followed, self._following = self._following, None

    def dropped(self) -> None:
        """Forget the frame of the last :meth:`propose` and any move followed on it."""
        self.pending = None
        self._following = None
