"""Sequences: frames read lazily by index, with optional ground truth.

:class:`Sequence` is the common interface; :class:`ImageSequence` (a list of
image files), :class:`smtmvt.data.video.VideoSequence` (a video file) and
:class:`ArraySequence` (frames in memory) implement it. Use
:func:`smtmvt.data.open_sequence` to get one from a path.

Ground truth is held in the API's **0-based** coordinates, one row per frame.
"""

from __future__ import annotations

import operator
import warnings
from functools import cached_property
from pathlib import Path

import numpy as np

from .errors import SequenceError, SequenceWarning
from .frames import is_grayscale_frame, read_frame

__all__ = ["Sequence", "ImageSequence", "ArraySequence", "align_groundtruth"]


class Sequence:
    """Frames of one video, read on demand, and their ground truth.

    Subclasses implement ``_read(i)`` (return frame ``i``, ``0 <= i < len``)
    and may override ``__iter__`` for faster sequential reading.

    Parameters
    ----------
    name : str
        Sequence name (e.g. ``"David"``), used in messages and result files.
    source : str or Path
        Where the frames come from (folder, video file, glob pattern).
    frame_names : sequence of str
        One human-readable name per frame (image file name, ``"frame 17"``),
        used in error messages; its length is the sequence length.
    groundtruth : array_like, shape (len, 4), optional
        **0-based** ``(x, y, w, h)`` boxes, one row per frame. Rows with a NaN
        or a width/height ``<= 0`` mean "not annotated" and are stored as NaN.
    groundtruth_file : str or Path, optional
        The file the ground truth was read from (for messages).

    Attributes
    ----------
    name, source, frame_names, groundtruth_file
        As given (``source`` and ``groundtruth_file`` as ``Path``).
    """

    def __init__(self, name, source, frame_names, groundtruth=None, *, groundtruth_file=None) -> None:
        self.name = str(name)
        self.source = Path(source)
        self.frame_names = [str(n) for n in frame_names]
        self.groundtruth_file = None if groundtruth_file is None else Path(groundtruth_file)
        self._groundtruth = None
        self._frame_size: tuple | None = None  # (H, W) of frame 0, once read
        if groundtruth is not None:
            gt = np.array(groundtruth, dtype=np.float64)  # a copy
            if gt.shape != (len(self.frame_names), 4):
                raise ValueError(
                    f"ground truth of {self.name!r} must have shape ({len(self.frame_names)}, 4), got {gt.shape}"
                )
            gt[~_valid_rows(gt)] = np.nan
            gt.flags.writeable = False
            self._groundtruth = gt

    # -- frames ---------------------------------------------------------------
    def __len__(self) -> int:
        return len(self.frame_names)

    def __getitem__(self, index) -> np.ndarray:
        """Frame ``index`` (0-based; negative counts from the end): ``uint8``/``uint16``,
        ``(H, W)`` or ``(H, W, 3)`` RGB. Read from disk on each call."""
        if isinstance(index, slice):
            raise TypeError(f"{type(self).__name__} indices must be integers, not slices; use range()")
        i = operator.index(index)
        n = len(self)
        if i < 0:
            i += n
        if not 0 <= i < n:
            raise IndexError(f"frame index {index} out of range for {self.name!r} ({n} frames)")
        return self._same_size(i, self._read(i))

    def __iter__(self):
        """Frames in order, read one at a time."""
        for i in range(len(self)):
            yield self._same_size(i, self._read(i))

    def _read(self, i: int) -> np.ndarray:  # pragma: no cover - abstract
        raise NotImplementedError

    def _frame_path(self, i: int) -> Path:
        """The file frame ``i`` comes from (for messages)."""
        return self.source

    def _same_size(self, i: int, frame: np.ndarray) -> np.ndarray:
        """``frame`` (frame ``i``) if it has frame 0's height and width, else SequenceError.

        Boxes refer to one pixel grid; a frame of another size would silently move every box
        on it. The reference is frame 0 (read once more if it was not read first).
        """
        size = tuple(frame.shape[:2])
        if self._frame_size is None:
            self._frame_size = size if i == 0 else tuple(self._read(0).shape[:2])
        if size == self._frame_size:
            return frame
        (h, w), (h0, w0) = size, self._frame_size
        raise SequenceError(
            f"sequence {self.name!r}: frame {i} ({self.frame_names[i]}) is {w}x{h} pixels but frame 0 "
            f"({self.frame_names[0]}) is {w0}x{h0}: all frames of a sequence must have one size",
            path=self._frame_path(i),
            frame=i,
            sequence=self.name,
        )

    @cached_property
    def is_grayscale(self) -> bool:
        """True when frame 0 is ``(H, W)`` or has three identical channels (reads frame 0 once)."""
        return is_grayscale_frame(self[0])

    # -- ground truth -----------------------------------------------------------
    @property
    def groundtruth(self):
        """``(len, 4) float64`` read-only, 0-based ``(x, y, w, h)``; NaN rows where a
        frame is not annotated (no line, NaN, or w/h <= 0). None without ground truth."""
        return self._groundtruth

    @property
    def annotated(self) -> np.ndarray:
        """``(len,) bool``: True where the frame has a valid ground-truth box."""
        if self._groundtruth is None:
            return np.zeros(len(self), dtype=bool)
        return ~np.isnan(self._groundtruth[:, 0])

    @property
    def first_box(self) -> tuple:
        """0-based ``(x, y, w, h)`` floats of frame 0; ValueError if frame 0 has no valid box."""
        if self._groundtruth is None:
            raise ValueError(f"sequence {self.name!r} ({self.source}) has no ground truth")
        if not self.annotated[0]:
            where = self.groundtruth_file or self.source
            raise ValueError(f"frame 0 of {self.name!r} is not annotated (no valid box on line 1 of {where})")
        return tuple(float(v) for v in self._groundtruth[0])

    def __repr__(self) -> str:
        gt = "no ground truth" if self._groundtruth is None else f"{int(self.annotated.sum())} annotated"
        return f"<{type(self).__name__} {self.name!r}: {len(self)} frames, {gt}, from {self.source}>"


def _valid_rows(boxes: np.ndarray) -> np.ndarray:
    with np.errstate(invalid="ignore"):
        return np.isfinite(boxes).all(axis=1) & (boxes[:, 2] > 0) & (boxes[:, 3] > 0)


class ImageSequence(Sequence):
    """A sequence stored as one image file per frame.

    Parameters
    ----------
    files : sequence of path
        Image files in frame order (frame ``i`` is ``files[i]``).
    name, groundtruth, groundtruth_file
        See :class:`Sequence`.
    source : str or Path, optional
        Folder or pattern the files came from (default: the folder of the first file).
    """

    def __init__(self, files, name, groundtruth=None, *, source=None, groundtruth_file=None):
        self.files = [Path(f) for f in files]
        if not self.files:
            raise SequenceError(f"no image files for sequence {name!r} ({source})", path=source, sequence=name)
        if source is None:
            source = self.files[0].parent
        super().__init__(name, source, _short_names(self.files), groundtruth, groundtruth_file=groundtruth_file)

    def _frame_path(self, i: int) -> Path:
        return self.files[i]

    def _read(self, i: int) -> np.ndarray:
        try:
            return read_frame(self.files[i])
        except SequenceError as exc:
            raise SequenceError(
                f"sequence {self.name!r}, frame {i}: {exc}", path=self.files[i], frame=i, sequence=self.name
            ) from None


def _short_names(files) -> list:
    """File names, or paths relative to the common folder when names repeat."""
    names = [f.name for f in files]
    if len(set(names)) == len(names):
        return names
    common = Path(*_common_parts([f.parent.parts for f in files]))
    return [str(f.relative_to(common)) if common.parts else str(f) for f in files]


def _common_parts(parts_list):
    first = parts_list[0]
    n = len(first)
    for parts in parts_list[1:]:
        n = min(n, len(parts))
        for k in range(n):
            if parts[k] != first[k]:
                n = k
                break
    return first[:n]


class ArraySequence(Sequence):
    """A sequence of frames already in memory (e.g. generated, or for tests).

    Parameters
    ----------
    frames : sequence of ndarray or ndarray (n, H, W[, 3])
        ``uint8``/``uint16`` frames, RGB when colour.
    name : str
    groundtruth : array_like (n, 4), optional
        0-based boxes, see :class:`Sequence`.
    """

    def __init__(self, frames, name="array", groundtruth=None):
        self._frames = frames
        super().__init__(name, "<memory>", [f"frame {i}" for i in range(len(frames))], groundtruth)

    def _read(self, i: int) -> np.ndarray:
        return self._frames[i]


def align_groundtruth(boxes, n_frames: int, *, groundtruth_file, sequence: str, source) -> np.ndarray:
    """Fit ground-truth boxes (one per line, line ``k`` = frame ``k``) to ``n_frames`` frames.

    Parameters
    ----------
    boxes : ndarray (m, 4)
        0-based boxes, line order.
    n_frames : int
    groundtruth_file, sequence, source
        For messages: the box file, the sequence name and its frames' origin.

    Returns
    -------
    ndarray (n_frames, 4)
        ``m == n_frames``: ``boxes``. ``m < n_frames``: the annotation is taken to
        cover the first ``m`` frames; the rest are NaN (not annotated) and a
        :class:`SequenceWarning` names the file and both counts.

    Raises
    ------
    SequenceError
        ``m > n_frames``: more boxes than frames means frames are missing (or the
        file belongs elsewhere); which boxes go with which frame cannot be
        known, so nothing is truncated.
    """
    m = len(boxes)
    if m == n_frames:
        return boxes
    if m > n_frames:
        raise SequenceError(
            f"{groundtruth_file}: {m} boxes but sequence {sequence!r} has only {n_frames} frames "
            f"({source}); frames are missing or the file belongs to another sequence",
            path=groundtruth_file,
            sequence=sequence,
        )
    warnings.warn(
        f"{groundtruth_file}: {m} boxes for {n_frames} frames of {sequence!r}; boxes are matched to "
        f"frames 0..{m - 1}, frames {m}..{n_frames - 1} are treated as not annotated",
        SequenceWarning,
        stacklevel=3,
    )
    out = np.full((n_frames, 4), np.nan)
    out[:m] = boxes
    return out
