"""Reading one image file into a frame array.

A frame is a numpy array of dtype ``uint8`` or ``uint16`` (16-bit PNG/TIFF keep
their depth), shape ``(H, W)`` for a one-channel image or ``(H, W, 3)`` in
**RGB** order for a colour one. Alpha channels are dropped. Pixels are exactly
as stored: no EXIF rotation is applied, so that ground-truth boxes, which
refer to the stored pixel grid, stay valid.
"""

from __future__ import annotations

import os
from pathlib import Path

import cv2
import numpy as np

from .errors import SequenceError
from .files import read_regular_bytes

__all__ = ["IMAGE_EXTENSIONS", "read_frame", "is_grayscale_frame", "is_image_file"]

#: Lower-case file extensions read as images (by OpenCV).
IMAGE_EXTENSIONS = (".jpg", ".jpeg", ".png", ".bmp", ".tif", ".tiff", ".pgm", ".ppm", ".pbm", ".webp")


def is_image_file(path) -> bool:
    """True when ``path``'s extension is one of :data:`IMAGE_EXTENSIONS` (any case)."""
    return Path(path).suffix.lower() in IMAGE_EXTENSIONS


def read_frame(path) -> np.ndarray:
    """Read one image file (JPEG, PNG, BMP, TIFF, ...) as a frame.

    Parameters
    ----------
    path : str or os.PathLike
        The image file.

    Returns
    -------
    ndarray
        ``uint8`` or ``uint16``; shape ``(H, W)`` for grayscale files,
        ``(H, W, 3)`` RGB for colour files (BGR from OpenCV is converted, an
        alpha channel is dropped). A colour file whose three channels happen
        to be equal stays ``(H, W, 3)``.

    Raises
    ------
    SequenceError
        The file is missing, empty, cannot be decoded, or holds a pixel type
        other than 8 or 16 bit unsigned; the message names the path.
    """
    path = os.fspath(path)
    try:
        # imdecode on the bytes (rather than cv2.imread) gives a clear error for a
        # missing file and works with non-ASCII paths on every platform.
        data = np.frombuffer(read_regular_bytes(path), dtype=np.uint8)
    except FileNotFoundError:
        raise SequenceError(f"image file not found: {path}", path=path) from None
    except OSError as exc:
        raise SequenceError(f"cannot read image file {path}: {exc.strerror or exc}", path=path) from None
    if data.size == 0:
        raise SequenceError(f"image file is empty: {path}", path=path)
    image = cv2.imdecode(data, cv2.IMREAD_UNCHANGED)
    if image is None:
        raise SequenceError(f"cannot decode image file (corrupt or unsupported format): {path}", path=path)
    if image.dtype not in (np.uint8, np.uint16):
        raise SequenceError(
            f"unsupported pixel type {image.dtype} in {path}: frames must be 8- or 16-bit unsigned",
            path=path,
        )
    return _to_rgb(image, path)


def _to_rgb(image: np.ndarray, path: str) -> np.ndarray:
    """OpenCV channel layout -> ``(H, W)`` or ``(H, W, 3)`` RGB, alpha dropped."""
    if image.ndim == 2:
        return image
    channels = image.shape[2]
    if channels == 1:
        return image[:, :, 0]
    if channels == 2:  # gray + alpha
        return np.ascontiguousarray(image[:, :, 0])
    if channels == 3:
        return cv2.cvtColor(image, cv2.COLOR_BGR2RGB)
    if channels == 4:
        return cv2.cvtColor(image, cv2.COLOR_BGRA2RGB)
    raise SequenceError(f"unsupported number of channels ({channels}) in {path}", path=path)


def is_grayscale_frame(frame: np.ndarray) -> bool:
    """True for an ``(H, W)`` frame or an ``(H, W, 3)`` one with three identical channels."""
    if frame.ndim == 2:
        return True
    return bool(np.array_equal(frame[..., 0], frame[..., 1]) and np.array_equal(frame[..., 0], frame[..., 2]))


def list_images(folder) -> list:
    """Image files directly in ``folder``, in natural order (``img2`` before ``img10``).

    Hidden files (``.name``, e.g. macOS ``._0001.jpg``) are skipped. ``.jpg`` and
    ``.jpeg`` count as one type, as do ``.tif`` and ``.tiff``.

    Returns
    -------
    list of Path
        Possibly empty.

    Raises
    ------
    SequenceError
        ``folder`` is not a folder, or it holds images of more than one type (e.g. ``.jpg`` frames and a
        stray ``.png``): which are the frames is not guessed; the message lists
        the counts and suggests a glob pattern.
    """
    from .names import natural_key

    folder = Path(folder)
    if not folder.is_dir():
        raise SequenceError(f"image folder not found: {folder}", path=folder)
    files = [p for p in folder.iterdir() if not p.name.startswith(".") and is_image_file(p) and p.is_file()]
    kinds: dict[str, list[Path]] = {}
    for p in files:
        kinds.setdefault(_EXTENSION_KIND.get(p.suffix.lower(), p.suffix.lower()), []).append(p)
    if len(kinds) > 1:
        counts = ", ".join(f"{len(v)} {k}" for k, v in sorted(kinds.items()))
        main = max(kinds, key=lambda k: len(kinds[k]))
        raise SequenceError(
            f"{folder}: mixed image types ({counts}); give a glob pattern such as "
            f"'{folder / ('*' + main)}' to say which files are the frames",
            path=folder,
        )
    return sorted(files, key=lambda p: natural_key(p.name))


_EXTENSION_KIND = {".jpeg": ".jpg", ".tiff": ".tif"}
