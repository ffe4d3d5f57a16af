"""Live sources: a camera, a stream, anything ``cv2.VideoCapture`` opens, read as frames arrive.

A live source has no length and no ground truth; its frames are read once, in order,
as :class:`LiveCapture` gives them (RGB, as every frame of this package). What counts as
live (:func:`is_live_source`): a camera index (``"0"``), a URL (``rtsp://``,
``http(s)://``, any ``scheme://``), or an existing path that is neither a regular file nor
a folder (a device such as ``/dev/video0``, a named pipe). Any other string is opened as
a live source only when asked (``smtmvt track --live``): a recorded video played as if it
came from a camera, a GStreamer pipeline, an image pattern such as ``img_%04d.jpg``.
"""

from __future__ import annotations

import re
from pathlib import Path

import cv2
import numpy as np

from .frames import _to_rgb

__all__ = ["is_live_source", "capture_argument", "describe_source", "LiveCapture"]

_URL = re.compile(r"[A-Za-z][A-Za-z0-9+.-]*://")


def is_live_source(text: str) -> bool:
    """True for a camera index (digits), a URL (``scheme://...``) or an existing path
    that is neither a regular file nor a folder (a device, a pipe). An existing file or
    folder is never live here, even one named ``0``: ``smtmvt track --live`` says so."""
    path = Path(text)
    if path.is_file() or path.is_dir():
        return False
    if text.isdigit() or _URL.match(text):
        return True
    return path.exists()


def capture_argument(text: str) -> int | str:
    """What ``cv2.VideoCapture`` is given for ``text``: an int for a camera index, else the text."""
    return int(text) if text.isdigit() else text


def describe_source(text: str) -> str:
    """``"camera 0"``, ``"stream rtsp://..."`` or ``"live source <text>"``, for messages."""
    if text.isdigit():
        return f"camera {int(text)}"
    if _URL.match(text):
        return f"stream {text}"
    return f"live source {text}"


class LiveCapture:
    """Frames of a live source, read one at a time.

    Parameters
    ----------
    source : str
        Camera index, URL or any string ``cv2.VideoCapture`` accepts.
    factory : callable, optional
        Builds the capture from :func:`capture_argument` (default ``cv2.VideoCapture``);
        the result needs ``isOpened``, ``read`` and ``release``.

    Raises
    ------
    OSError
        The source cannot be opened; the message names it.
    """

    def __init__(self, source: str, factory=None) -> None:
        self.source = source
        self.name = describe_source(source)
        self._cap = (factory or cv2.VideoCapture)(capture_argument(source))
        if not self._cap.isOpened():
            self._cap.release()
            raise OSError(f"cannot open {self.name} (no such camera, unreachable stream or unsupported format)")

    def read(self) -> np.ndarray | None:
        """The next frame, ``(H, W, 3)`` RGB (or ``(H, W)``), or None when the source has ended."""
        ok, frame = self._cap.read()
        if not ok or frame is None:
            return None
        return _to_rgb(frame, self.name)

    def release(self) -> None:
        """Close the source (idempotent)."""
        if self._cap is not None:
            self._cap.release()
            self._cap = None

    def __enter__(self) -> LiveCapture:
        return self

    def __exit__(self, *exc) -> None:
        self.release()
