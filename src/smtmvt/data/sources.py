"""``open_sequence``: one entry point for every kind of sequence source."""

from __future__ import annotations

import glob
import os
from pathlib import Path

from .boxes import read_boxes
from .errors import SequenceError
from .frames import IMAGE_EXTENSIONS, is_image_file, list_images
from .names import natural_key
from .otb import find_groundtruth, is_otb_folder, open_otb_sequence
from .sequence import ImageSequence, Sequence, align_groundtruth
from .video import VIDEO_EXTENSIONS, VideoSequence, count_video_frames

__all__ = ["open_sequence"]

_GLOB_CHARS = set("*?[")


def open_sequence(source, groundtruth=None, name=None, *, target=None) -> Sequence:
    """Open a sequence from a path, deciding from what the path is.

    Parameters
    ----------
    source : str or os.PathLike
        One of, checked in this order:

        - an **OTB folder** (has ``img/``): frames ``img/*``, ground truth
          ``groundtruth_rect.txt`` (or ``groundtruth_rect.<k>.txt``), see
          :func:`smtmvt.data.otb.open_otb_sequence` for the OTB quirks handled;
        - a **folder of images** (``*.jpg``, ``*.png``, ...), natural order; a
          ``groundtruth_rect.txt`` / ``groundtruth.txt`` beside them is used;
        - a **video file** (``.avi``, ``.mp4``, ... see ``VIDEO_EXTENSIONS``);
        - a single **image file** (a one-frame sequence);
        - a **glob pattern** (``"frames/*.png"``, ``**`` allowed) that is not
          an existing path: the matching image files in natural order
          (``img2`` before ``img10``).
    groundtruth : str or os.PathLike, optional
        Box file (1-based ``x,y,w,h`` lines, OTB format) to use as ground truth,
        replacing the folder's own. Line ``k`` is frame ``k``.
    name : str, optional
        Sequence name. Default: the folder name (OTB: ``<folder>-<k>`` for
        target ``k``), the video file's stem, or for a pattern the folder
        above the first wildcard (skipping a folder named ``img``).
    target : int, optional
        OTB folders with several annotated targets: which
        ``groundtruth_rect.<target>.txt`` to use.

    Returns
    -------
    Sequence
        Frames are read lazily; ``groundtruth`` is 0-based, ``(len, 4)``.

    Raises
    ------
    SequenceError
        Source does not exist, a folder or pattern with no images, an unknown
        file extension, or bad ground truth; the message names the path.

    Warns
    -----
    SequenceWarning
        Fewer ground-truth lines than frames, several targets, and the OTB
        quirks listed in :mod:`smtmvt.data.otb`.
    """
    text = os.fspath(source)
    path = Path(text)
    if path.is_dir():
        if is_otb_folder(path):
            return open_otb_sequence(path, groundtruth, name, target=target)
        return _open_image_folder(path, groundtruth, name, target)
    if path.is_file():
        return _open_file(path, groundtruth, name)
    if _GLOB_CHARS & set(text):
        matches = [Path(p) for p in glob.glob(text, recursive=True)]
        files = sorted((p for p in matches if p.is_file() and is_image_file(p)), key=lambda p: natural_key(str(p)))
        if not files:
            others = f" ({len(matches)} non-image matches)" if matches else ""
            raise SequenceError(f"no image files match the pattern {text}{others}", path=text)
        return _with_groundtruth(ImageSequence, files, name or _pattern_name(text), groundtruth, source=text)
    raise SequenceError(f"no such file or folder: {text}", path=text)


def _open_image_folder(path: Path, groundtruth, name, target) -> Sequence:
    """A folder of images (not OTB's ``img/`` layout), natural order, with the ground truth
    given or found beside them (:func:`open_sequence`)."""
    files = list_images(path)
    if not files:
        raise SequenceError(
            f"no image files in folder {path} (looked for {', '.join(IMAGE_EXTENSIONS)}; "
            f"an OTB sequence folder has them in img/)",
            path=path,
        )
    gt_file, k = (groundtruth, None) if groundtruth is not None else find_groundtruth(path, target)
    if name is None:
        name = path.name if k is None else f"{path.name}-{k}"
    return _with_groundtruth(ImageSequence, files, name, gt_file, source=path)


def _open_file(path: Path, groundtruth, name) -> Sequence:
    """A video file or a single image (a one-frame sequence); SequenceError naming the file
    for another type (:func:`open_sequence`)."""
    suffix = path.suffix.lower()
    if suffix in VIDEO_EXTENSIONS:
        n = count_video_frames(path)
        name = name or path.stem
        gt = None if groundtruth is None else _load_groundtruth(groundtruth, n, name, path)
        return VideoSequence(path, name, gt, groundtruth_file=groundtruth, n_frames=n)
    if is_image_file(path):
        return _with_groundtruth(ImageSequence, [path], name or path.stem, groundtruth, source=path)
    raise SequenceError(
        f"unknown file type {path.suffix!r}: {path} (expected a video {', '.join(VIDEO_EXTENSIONS)}, "
        f"an image, a folder or a glob pattern)",
        path=path,
    )


def _load_groundtruth(gt_file, n_frames: int, name: str, source):
    boxes = read_boxes(gt_file)
    return align_groundtruth(boxes, n_frames, groundtruth_file=gt_file, sequence=name, source=source)


def _with_groundtruth(cls, files, name, gt_file, *, source) -> Sequence:
    if gt_file is None:
        return cls(files, name, source=source)
    gt = _load_groundtruth(gt_file, len(files), name, source)
    return cls(files, name, gt, source=source, groundtruth_file=gt_file)


def _pattern_name(pattern: str) -> str:
    parts = Path(pattern).parts
    fixed = []
    for part in parts:
        if _GLOB_CHARS & set(part):
            break
        fixed.append(part)
    while fixed and fixed[-1].lower() == "img":
        fixed.pop()
    return fixed[-1] if fixed and fixed[-1] not in ("/", ".", "..") else "sequence"
