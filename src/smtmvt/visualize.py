"""Drawing boxes on frames and writing annotated videos (MP4/AVI or GIF)."""

from __future__ import annotations

import io
import os
from pathlib import Path
from typing import Any

import cv2
import numpy as np

from .data import write_bytes_atomic

__all__ = ["draw_box", "VideoSink", "VIDEO_OUTPUTS", "to_display_rgb"]


def to_display_rgb(frame: np.ndarray) -> np.ndarray:
    """Any frame accepted by the tracker as ``(H, W, 3) uint8`` RGB for drawing."""
    a = np.asarray(frame)
    if a.dtype == np.uint16:
        a = (a // 257).astype(np.uint8)
    elif a.dtype != np.uint8:
        a = np.clip(a * (255.0 if a.max(initial=0) <= 1 else 1.0), 0, 255).astype(np.uint8)
    if a.ndim == 2:
        a = np.repeat(a[:, :, None], 3, axis=2)
    return np.ascontiguousarray(a[:, :, :3])


def draw_box(frame: np.ndarray, box, color=(255, 0, 0), label: str | None = None, thickness: int = 2) -> np.ndarray:
    """Draw a 0-based ``(x, y, w, h)`` box (RGB ``color``) on a copy of ``frame``."""
    img = to_display_rgb(frame).copy()
    x, y, w, h = (float(v) for v in box)
    if np.all(np.isfinite([x, y, w, h])):
        p0 = (int(round(x)), int(round(y)))
        p1 = (int(round(x + w - 1)), int(round(y + h - 1)))
        cv2.rectangle(img, p0, p1, color, thickness)
        if label:
            cv2.putText(img, label, (p0[0], max(p0[1] - 4, 10)), cv2.FONT_HERSHEY_SIMPLEX, 0.4, color, 1, cv2.LINE_AA)
    return img


#: File types :class:`VideoSink` writes (``.gif`` by imageio, the others by OpenCV).
VIDEO_OUTPUTS = (".mp4", ".avi", ".gif")


class VideoSink:
    """Write RGB frames to ``path``: ``.gif`` via imageio, ``.mp4``/``.avi`` via OpenCV.

    Frames go to a temporary file beside ``path`` that :meth:`close` renames to ``path``,
    so ``path`` holds either its old content or the whole new video, never a part;
    :meth:`discard` drops what was added. As a context manager: ``close`` on success,
    ``discard`` on an exception. Every frame must have the first frame's size (OpenCV's
    writer would silently drop the others).
    """

    def __init__(self, path, fps: float = 20.0):
        self.path = Path(path)
        if self.path.suffix.lower() not in VIDEO_OUTPUTS:
            raise ValueError(
                f"video {self.path}: unsupported type {self.path.suffix!r} (use {', '.join(VIDEO_OUTPUTS)})"
            )
        self.fps = fps
        self._writer: cv2.VideoWriter | None = None
        self._gif_frames: list[Any] = []  # (H, W, 3) uint8 RGB frames
        self._size: tuple | None = None  # (H, W) of frame 0
        self._count = 0
        self._tmp = self.path.with_name(f".{self.path.stem}.partial{self.path.suffix}")

    def add(self, frame_rgb: np.ndarray) -> None:
        img = to_display_rgb(frame_rgb)
        size = img.shape[:2]
        if self._size is None:
            self._size = size
        elif size != self._size:
            raise ValueError(
                f"video {self.path}: frame {self._count} is {size[1]}x{size[0]} pixels, "
                f"frame 0 is {self._size[1]}x{self._size[0]}: all frames of a video must have one size"
            )
        self._count += 1
        if self.path.suffix.lower() == ".gif":
            self._gif_frames.append(img)
            return
        if self._writer is None:
            self._tmp.parent.mkdir(parents=True, exist_ok=True)
            fourcc = cv2.VideoWriter.fourcc(*("mp4v" if self.path.suffix.lower() == ".mp4" else "MJPG"))
            h, w = img.shape[:2]
            self._writer = cv2.VideoWriter(str(self._tmp), fourcc, self.fps, (w, h))
            if not self._writer.isOpened():
                raise OSError(f"cannot open video writer for {self.path}")
        self._writer.write(img[:, :, ::-1])

    def close(self) -> None:
        """Finish the video and put it at ``path`` (nothing is written without frames)."""
        if self._gif_frames:
            import imageio.v2 as imageio

            buf = io.BytesIO()
            imageio.mimsave(buf, self._gif_frames, format="GIF", duration=1.0 / self.fps, loop=0)
            self._gif_frames = []
            write_bytes_atomic(self.path, buf.getvalue())
        if self._writer is not None:
            self._writer.release()
            self._writer = None
            os.replace(self._tmp, self.path)

    def discard(self) -> None:
        """Drop the frames added so far; ``path`` is left as it was."""
        self._gif_frames = []
        if self._writer is not None:
            self._writer.release()
            self._writer = None
        self._tmp.unlink(missing_ok=True)

    def __enter__(self):
        return self

    def __exit__(self, exc_type, *exc):
        if exc_type is None:
            self.close()
        else:
            self.discard()
