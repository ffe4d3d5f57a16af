"""A synthetic sequence whose target jumps out of the tracker's reach, shared by
the correlation and re-detection tests."""

import cv2
import numpy as np


def jump_sequence(jump, n, at, width, seed=3):
    """A textured background ``(200, width)`` and a bright checkered 28x32
    target that jumps ``jump`` pixels to the right at frame ``at``, then stays:
    (frames, the first box, 0-based ``(x, y, w, h)`` pixels)."""
    rng = np.random.default_rng(seed)
    bg = cv2.GaussianBlur(rng.random((200, width, 3)).astype(np.float32), (0, 0), 3.0)
    bg = (0.2 + 0.3 * (bg - bg.min()) / np.ptp(bg) * 255).astype(np.uint8)
    yy, xx = np.mgrid[0:32, 0:28]
    target = np.where(((yy // 8) + (xx // 7)) % 2 == 0, 250, 30).astype(np.uint8)
    target = np.stack([target, 255 - target // 2, target // 3], axis=2)
    frames = []
    for i in range(n):
        f = bg.copy()
        x = 60 + (jump if i >= at else 0)
        f[80:112, x : x + 28] = target
        frames.append(f)
    return frames, np.array([60.0, 80.0, 28.0, 32.0])
