"""Drawing boxes on frames and writing annotated videos (MP4/AVI or GIF)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import cv2
import numpy as np

__all__ = ["draw_box", "VideoSink", "to_display_rgb"]


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


class VideoSink:
    """Write RGB frames to ``path``: ``.gif`` via imageio, anything else via OpenCV.

    Use as a context manager; frames may be added one at a time.
    """

    def __init__(self, path, fps: float = 20.0):
        self.path = Path(path)
        self.fps = fps
        self._writer: cv2.VideoWriter | None = None
        self._gif_frames: list[Any] = []  # (H, W, 3) uint8 RGB frames
        self.path.parent.mkdir(parents=True, exist_ok=True)

    def add(self, frame_rgb: np.ndarray) -> None:
        img = to_display_rgb(frame_rgb)
        if self.path.suffix.lower() == ".gif":
            self._gif_frames.append(img)
            return
        if self._writer is None:
            fourcc = cv2.VideoWriter.fourcc(*("mp4v" if self.path.suffix.lower() == ".mp4" else "MJPG"))
            h, w = img.shape[:2]
            self._writer = cv2.VideoWriter(str(self.path), fourcc, self.fps, (w, h))
            if not self._writer.isOpened():
                raise OSError(f"cannot open video writer for {self.path}")
        self._writer.write(img[:, :, ::-1])

    def close(self) -> None:
        if self._gif_frames:
            import imageio.v2 as imageio

            imageio.mimsave(self.path, self._gif_frames, duration=1.0 / self.fps, loop=0)
            self._gif_frames = []
        if self._writer is not None:
            self._writer.release()
            self._writer = None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
