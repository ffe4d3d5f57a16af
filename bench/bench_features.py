"""Benchmark of smtmvt.features: Tan-Triggs on a frame, each view on a batch.

Usage::

    .venv/bin/python bench/bench_features.py [--n 400] [--repeat 30] [--threads 1]

Times ``tan_triggs`` on a 640x480 uint8 frame and each view (plus the whole
``extract_views`` call, normalization included) on ``n`` candidates with a
20x20 intensity template and 32x32 feature patches cut from a Tan-Triggs
normalized natural image. Prints the minimum and the median over ``repeat``
runs of the wall-clock time and of the calling thread's CPU time (the CPU
time is the robust figure on a shared machine; the wall median shows load).
OpenCV is limited to ``--threads`` threads (default 1: the one-core target);
numpy's element-wise code is single-threaded.
"""

from __future__ import annotations

import argparse
import time

import cv2
import numpy as np
from skimage import data

from smtmvt.features import Patches, available_views, extract_views, tan_triggs
from smtmvt.features.views import VIEW_REGISTRY


def _time(fn, repeat: int) -> tuple[float, float, float, float]:
    """(wall min, wall median, CPU min, CPU median) in ms over ``repeat`` runs."""
    fn()  # warm-up
    wall, cpu = [], []
    for _ in range(repeat):
        t0, c0 = time.perf_counter(), time.thread_time()
        fn()
        cpu.append(time.thread_time() - c0)
        wall.append(time.perf_counter() - t0)
    wall.sort()
    cpu.sort()
    mid = repeat // 2
    return wall[0] * 1e3, wall[mid] * 1e3, cpu[0] * 1e3, cpu[mid] * 1e3


def _patches(n: int, rng: np.random.Generator) -> Patches:
    rgb = data.astronaut()  # (512, 512, 3) uint8
    gray = cv2.cvtColor(rgb, cv2.COLOR_RGB2GRAY)
    normalized = tan_triggs(gray)
    color = rgb.astype(np.float32) / 255.0
    rows = rng.integers(0, 512 - 60, n)
    cols = rng.integers(0, 512 - 60, n)

    def cut(image, size):
        return np.stack(
            [
                cv2.resize(image[r : r + 60, c : c + 60], (size, size), interpolation=cv2.INTER_LINEAR)
                for r, c in zip(rows, cols)
            ]
        )

    return Patches(intensity=cut(normalized, 20), gray=cut(normalized, 32), color=cut(color, 32))


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=400, help="number of candidates")
    parser.add_argument("--repeat", type=int, default=30, help="timed runs per item")
    parser.add_argument("--threads", type=int, default=1, help="OpenCV threads")
    args = parser.parse_args(argv)
    cv2.setNumThreads(args.threads)
    rng = np.random.default_rng(0)

    frame = cv2.resize(cv2.cvtColor(data.astronaut(), cv2.COLOR_RGB2GRAY), (640, 480))
    rows = [("tan_triggs 640x480 uint8", *_time(lambda: tan_triggs(frame), args.repeat))]
    patches = _patches(args.n, rng)
    views = available_views()
    for name in views:
        fn = VIEW_REGISTRY[name]
        d = fn(patches).shape[1]
        rows.append((f"view {name} (n={args.n}, d={d})", *_time(lambda fn=fn: fn(patches), args.repeat)))
    rows.append(
        (f"extract_views all {len(views)} (n={args.n})", *_time(lambda: extract_views(patches, views), args.repeat))
    )

    width = max(len(r[0]) for r in rows)
    print(f"{'item':<{width}}  {'wall min':>8}  {'wall med':>8}  {'cpu min':>8}  {'cpu med':>8}  (ms)")
    for name, *times in rows:
        print(f"{name:<{width}}  " + "  ".join(f"{t:8.2f}" for t in times))


if __name__ == "__main__":
    main()
