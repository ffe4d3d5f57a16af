"""A built-in test sequence made from photographs shipped with scikit-image.

No download is needed: the target is the face of the cat in
``skimage.data.chelsea()``, pasted onto a crop of ``skimage.data.astronaut()``
that pans slowly like a hand-held camera. Over the sequence the target moves
on a smooth path and undergoes the hard parts of real video, each on a known
frame range:

- scale change (up to 1.45x and back),
- in-plane rotation (up to +/-12 degrees),
- illumination change (a global gain from 0.55 to 1.3 and a moving shadow),
- partial occlusion (a block cut from ``skimage.data.coffee()`` slides over up
  to ~45% of the target),
- blur (a horizontal motion-blur kernel of 9 px during fast motion).

The ground truth is exact: the axis-aligned box of the pasted target in each
frame, 0-based ``(x, y, w, h)``.
"""

from __future__ import annotations

from dataclasses import dataclass

import cv2
import numpy as np

__all__ = ["DemoSequence", "make_demo_sequence"]


@dataclass(frozen=True)
class DemoSequence:
    """Frames ``(n, H, W, 3) uint8`` RGB and ground truth ``(n, 4)`` 0-based boxes.

    ``events``: each event's first and last frame (0-based). ``occluded_share``:
    ``(n,)`` the share of each frame's ground-truth box that the occluder covers, in
    [0, 1] (0 outside the occlusion).
    """

    frames: np.ndarray
    groundtruth: np.ndarray
    events: dict
    name: str = "demo"
    occluded_share: np.ndarray | None = None

    def __len__(self) -> int:
        return len(self.frames)


def _smooth_bump(t, start, end):
    """0 outside [start, end], a raised-cosine bump peaking at the middle."""
    x = np.clip((t - start) / max(end - start, 1e-9), 0.0, 1.0)
    return 0.5 - 0.5 * np.cos(2 * np.pi * x)


def make_demo_sequence(n_frames: int = 120, size=(240, 320), seed: int = 0) -> DemoSequence:
    """Generate the demo sequence.

    Parameters
    ----------
    n_frames : number of frames (the events are placed proportionally).
    size : (H, W) of the frames in pixels.
    seed : seed of the camera-shake noise.
    """
    from skimage import data

    H, W = size
    rng = np.random.default_rng(seed)
    background = data.astronaut()  # (512, 512, 3)
    cat = data.chelsea()  # (300, 451, 3)
    target = cat[20:250, 110:350]  # the cat's head, (230, 240, 3)
    occluder = data.coffee()[100:260, 200:300]  # (160, 100, 3)
    th, tw = 44, 48  # target size at scale 1, pixels
    target = cv2.resize(target, (tw, th), interpolation=cv2.INTER_AREA)
    occluder = cv2.resize(occluder, (30, 60), interpolation=cv2.INTER_AREA)

    T = n_frames
    t = np.arange(T, dtype=np.float64)
    f = t / max(T - 1, 1)
    # Events as fractions of the sequence.
    ev = {
        "scale": (0.10, 0.55),
        "rotation": (0.30, 0.80),
        "illumination": (0.45, 0.95),
        "occlusion": (0.58, 0.74),
        "blur": (0.80, 0.90),
    }
    scale = 1.0 + 0.45 * _smooth_bump(f, *ev["scale"])
    angle = 12.0 * np.sin(2 * np.pi * np.clip((f - ev["rotation"][0]) / (ev["rotation"][1] - ev["rotation"][0]), 0, 1))
    gain = 1.0 - 0.45 * _smooth_bump(f, ev["illumination"][0], 0.7) + 0.3 * _smooth_bump(f, 0.7, ev["illumination"][1])
    cx = W / 2 + 0.30 * W * np.sin(2 * np.pi * f)
    cy = H / 2 + 0.22 * H * np.sin(4 * np.pi * f + 0.5)

    frames = np.empty((T, H, W, 3), np.uint8)
    gt = np.empty((T, 4))
    occluded = np.zeros(T)
    yy, xx = np.mgrid[0:H, 0:W]
    for i in range(T):
        # Background: a slowly panning crop with a little camera shake.
        ox = int(round(60 + 80 * f[i] + rng.normal(0, 0.7)))
        oy = int(round(120 + 40 * np.sin(np.pi * f[i]) + rng.normal(0, 0.7)))
        img = background[oy : oy + H, ox : ox + W].astype(np.float32)

        # Target: rotate + scale about its centre, paste at (cx, cy).
        M = cv2.getRotationMatrix2D(((tw - 1) / 2, (th - 1) / 2), angle[i], scale[i])
        M[0, 2] += cx[i] - (tw - 1) / 2
        M[1, 2] += cy[i] - (th - 1) / 2
        warped = cv2.warpAffine(target.astype(np.float32), M, (W, H), flags=cv2.INTER_LINEAR)
        mask = cv2.warpAffine(np.ones((th, tw), np.float32), M, (W, H), flags=cv2.INTER_LINEAR)[..., None]
        img = img * (1 - mask) + warped * mask
        corners = np.array([[-0.5, -0.5], [tw - 0.5, -0.5], [tw - 0.5, th - 0.5], [-0.5, th - 0.5]])
        pts = corners @ M[:, :2].T + M[:, 2]
        x0, y0 = pts.min(axis=0)
        x1, y1 = pts.max(axis=0)
        gt[i] = (x0 + 0.5, y0 + 0.5, x1 - x0, y1 - y0)

        # Partial occlusion: a block sliding from the left over the target.
        if ev["occlusion"][0] <= f[i] <= ev["occlusion"][1]:
            k = (f[i] - ev["occlusion"][0]) / (ev["occlusion"][1] - ev["occlusion"][0])
            left = cx[i] - tw * scale[i] * 0.5
            corner = (int(round(left - 30 + 0.45 * tw * scale[i] * np.sin(np.pi * k))), int(round(cy[i] - 30)))
            occluded[i] = _paste_occluder(img, occluder, corner, gt[i])

        # Illumination: global gain and a soft shadow sweeping across.
        shadow = 1.0 - 0.35 * np.exp(-(((xx - W * f[i] * 1.2) / (0.25 * W)) ** 2))
        img = img * gain[i] * shadow[..., None]

        # Blur: horizontal motion blur.
        if ev["blur"][0] <= f[i] <= ev["blur"][1]:
            kernel = np.zeros((9, 9), np.float32)
            kernel[4, :] = 1.0 / 9
            img = cv2.filter2D(img, -1, kernel, borderType=cv2.BORDER_REFLECT)
        frames[i] = np.clip(img, 0, 255).astype(np.uint8)
    events = {k: (int(round(a * (T - 1))), int(round(b * (T - 1)))) for k, (a, b) in ev.items()}
    return DemoSequence(frames=frames, groundtruth=gt, events=events, occluded_share=occluded)


def _paste_occluder(img: np.ndarray, occluder: np.ndarray, corner: tuple[int, int], box) -> float:
    """Paste ``occluder`` ``(h, w, 3)`` into ``img`` ``(H, W, 3)`` with its top-left pixel at
    ``corner`` ``(x, y)`` (clipped to the image); the share of the 0-based ``box`` it covers."""
    H, W = img.shape[:2]
    oh, ow = occluder.shape[:2]
    ox0, oy0 = corner
    xs, ys = max(ox0, 0), max(oy0, 0)
    xe, ye = min(ox0 + ow, W), min(oy0 + oh, H)
    if not (xe > xs and ye > ys):
        return 0.0
    img[ys:ye, xs:xe] = occluder[ys - oy0 : ye - oy0, xs - ox0 : xe - ox0]
    return _covered_share(np.asarray(box) - (0.5, 0.5, 0, 0), (xs - 0.5, ys - 0.5, xe - xs, ye - ys))


def _covered_share(box, cover) -> float:
    """The share of ``box``'s area inside ``cover``; both ``(x, y, w, h)`` in pixel edges."""
    w = min(box[0] + box[2], cover[0] + cover[2]) - max(box[0], cover[0])
    h = min(box[1] + box[3], cover[1] + cover[3]) - max(box[1], cover[1])
    return float(max(w, 0.0) * max(h, 0.0) / (box[2] * box[3]))
