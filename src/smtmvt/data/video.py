"""Video files as sequences (via ``cv2.VideoCapture``).

Frames are decoded by OpenCV (usually FFmpeg), returned as ``(H, W, 3) uint8``
RGB. The length is counted by decoding the whole video once when the
sequence is opened: ``CAP_PROP_FRAME_COUNT`` comes from the container header
and is wrong for some files (variable frame rate, truncated files), and a
ground-truth file must be matched against the true count.
"""

from __future__ import annotations

import os
from pathlib import Path

import cv2
import numpy as np

from .errors import SequenceError
from .frames import _to_rgb
from .sequence import Sequence

__all__ = ["VIDEO_EXTENSIONS", "VideoSequence", "count_video_frames"]

#: Lower-case extensions opened as videos.
VIDEO_EXTENSIONS = (".avi", ".mp4", ".m4v", ".mov", ".mkv", ".mpg", ".mpeg", ".wmv", ".webm", ".ogv")


def _open_capture(path: str) -> cv2.VideoCapture:
    cap = cv2.VideoCapture(path)
    if not cap.isOpened():
        cap.release()
        raise SequenceError(f"cannot open video file (missing codec or not a video): {path}", path=path)
    return cap


def count_video_frames(path) -> int:
    """Number of frames that actually decode in ``path`` (reads the whole file once)."""
    path = os.fspath(path)
    cap = _open_capture(path)
    try:
        n = 0
        while cap.grab():
            n += 1
    finally:
        cap.release()
    return n


class VideoSequence(Sequence):
    """Frames of a video file.

    Parameters
    ----------
    path : str or Path
        The video file.
    name : str, optional
        Default: the file name without extension.
    groundtruth, groundtruth_file
        See :class:`smtmvt.data.Sequence` (0-based, one row per frame).

    Notes
    -----
    Iteration opens its own capture and decodes sequentially (fast).
    ``seq[i]`` keeps one capture open and moves forward by decoding
    (``grab``) to frame ``i``; going backwards reopens the file. This is exact
    for every codec, unlike seeking with ``CAP_PROP_POS_FRAMES`` which lands
    on key frames for some; the cost is O(i) for a backward jump, nothing
    extra for the usual forward access. Frame names are ``"frame <i>"``
    (0-based). A sequence can be pickled; the open capture is not carried.
    """

    def __init__(self, path, name=None, groundtruth=None, *, groundtruth_file=None, n_frames=None):
        path = Path(path)
        if not path.is_file():
            raise SequenceError(f"video file not found: {path}", path=path)
        n = count_video_frames(path) if n_frames is None else int(n_frames)
        if n == 0:
            raise SequenceError(f"no frame could be decoded from video file {path}", path=path)
        super().__init__(
            name or path.stem, path, [f"frame {i}" for i in range(n)], groundtruth, groundtruth_file=groundtruth_file
        )
        self._cap = None
        self._next = 0  # index of the frame the open capture will decode next

    def _decode_error(self, i: int) -> SequenceError:
        return SequenceError(
            f"sequence {self.name!r}: cannot decode frame {i} of video file {self.source} "
            f"({len(self)} frames were counted when it was opened)",
            path=self.source,
            frame=i,
            sequence=self.name,
        )

    def _read(self, i: int) -> np.ndarray:
        if self._cap is None or i < self._next:
            self.close()
            self._cap = _open_capture(os.fspath(self.source))
            self._next = 0
        while self._next < i:
            if not self._cap.grab():
                raise self._decode_error(self._next)
            self._next += 1
        ok, frame = self._cap.read()
        if not ok or frame is None:
            raise self._decode_error(i)
        self._next += 1
        return _to_rgb(frame, os.fspath(self.source))

    def __iter__(self):
        cap = _open_capture(os.fspath(self.source))
        try:
            for i in range(len(self)):
                ok, frame = cap.read()
                if not ok or frame is None:
                    raise self._decode_error(i)
                yield self._same_size(i, _to_rgb(frame, os.fspath(self.source)))
        finally:
            cap.release()

    def close(self) -> None:
        """Release the capture used by ``seq[i]`` (reopened on the next access)."""
        if self._cap is not None:
            self._cap.release()
            self._cap = None
            self._next = 0

    def __getstate__(self):
        state = self.__dict__.copy()
        state["_cap"] = None
        state["_next"] = 0
        return state

    def __del__(self):
        try:
            self.close()
        except Exception:  # noqa: BLE001  # pragma: no cover - interpreter shutdown
            pass
