"""The tracker behind OpenCV's tracker interface: :class:`TrackerSMTMVT`.

Code written for ``cv2.TrackerCSRT`` runs unchanged with ours::

    tracker = smtmvt.TrackerSMTMVT.create()      # like cv2.TrackerCSRT.create()
    tracker.init(frame, (x, y, w, h))            # BGR frame as cv2.imread / VideoCapture give it; returns None
    ok, (x, y, w, h) = tracker.update(frame)     # ok False when the tracker believes the target lost

Frames are OpenCV's: BGR ``(H, W, 3)`` (or gray ``(H, W)``) images, uint8
(uint16 and float as :class:`smtmvt.Tracker` takes them); they are turned to
RGB for :class:`smtmvt.Tracker`. Boxes are OpenCV's ``Rect``: ``(x, y, w, h)``
0-based pixels, a tuple of ints (the tracker's float box rounded to the
nearest, half to even as OpenCV's ``cvRound``).
"""

from __future__ import annotations

import numpy as np

from .config import TrackerConfig
from .tracker import Tracker, TrackResult

__all__ = ["TrackerSMTMVT"]


class TrackerSMTMVT:
    """:class:`smtmvt.Tracker` with the interface of OpenCV's ``cv2.Tracker`` (OpenCV >= 4.5).

    Build it with :meth:`create`. :attr:`tracker` is the underlying
    :class:`smtmvt.Tracker` and :attr:`result` the last
    :class:`smtmvt.TrackResult` (None before the first :meth:`update`), for
    the float box, ``confidence`` and the rest.
    """

    def __init__(self, config: TrackerConfig | None = None) -> None:
        self.tracker = Tracker(config)
        self.result: TrackResult | None = None

    @classmethod
    def create(cls, config: TrackerConfig | None = None) -> TrackerSMTMVT:
        """A new tracker (``config``: a :class:`smtmvt.TrackerConfig`, the defaults when None),
        as ``cv2.TrackerCSRT.create()``."""
        if config is not None and not isinstance(config, TrackerConfig):
            raise TypeError(f"TrackerSMTMVT.create: config must be a TrackerConfig or None, got {config!r}")
        return cls(config)

    def init(self, image: np.ndarray, boundingBox) -> None:
        """Start tracking the object in ``boundingBox`` ``(x, y, w, h)`` (0-based
        pixels; ints as OpenCV's, floats are taken too) of the BGR ``image``
        ``(H, W, 3)`` or gray ``(H, W)``. Returns None, as OpenCV 4.5+'s ``init``;
        a box of zero size or mostly outside the image raises ValueError."""
        box = np.asarray(boundingBox, dtype=np.float64).reshape(-1)
        if box.size != 4:
            raise ValueError(f"TrackerSMTMVT.init: boundingBox must be (x, y, w, h), got {boundingBox!r}")
        self.result = None
        self.tracker.init(_to_rgb(image), box)

    def update(self, image: np.ndarray) -> tuple[bool, tuple[int, int, int, int]]:
        """Track into the BGR ``image``: ``(ok, (x, y, w, h))``, ``ok`` False when
        the tracker believes the target lost (``TrackResult.lost``; the box is
        then its best guess still), the box 0-based ints."""
        self.result = self.tracker.update(_to_rgb(image))
        return (not self.result.lost), _rect(self.result.box)


def _to_rgb(image) -> np.ndarray:
    """An OpenCV BGR ``(H, W, 3)`` image as RGB (a gray ``(H, W)`` or other
    shape as it is: :class:`smtmvt.Tracker` names what it refuses)."""
    arr = np.asarray(image)
    if arr.ndim == 3 and arr.shape[2] == 3:
        return np.ascontiguousarray(arr[:, :, ::-1])
    return arr


def _rect(box) -> tuple[int, int, int, int]:
    """A float box ``(x, y, w, h)`` as OpenCV's ``Rect``: four ints, each rounded to the nearest."""
    x, y, w, h = (int(round(float(v))) for v in box)
    return x, y, w, h
