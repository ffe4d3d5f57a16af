"""Whether the template update's occlusion test finds occlusions (issue 50 item 4).

Usage::

    python bench/occlusion.py [--config default|paper] [--seeds 8]
    python bench/occlusion.py --data DIR [--att ATT_DIR] [--config default|paper] [--seed 0]

On the demo (default): the demo knows the share of its ground-truth box its
occluder covers in each frame (``DemoSequence.occluded_share``); a frame is
occluded when that share is at least a quarter (L1-APG's threshold). For each
seed it tracks the demo and compares with that truth, over the occluded
frames and the frames the occluder never touches (frames it covers by less
than a quarter count for neither):

* ``TrackResult.occluded`` (today's test: the share of the best candidate's
  intensity outliers ``e`` that are non-zero, above ``occlusion_fraction``);
* L1-APG's own test on the same ``e`` (``L1TrackingBPR_APGup.m``): the map of
  its non-zero entries at the intensity template's shape, closed with the
  3x3 cross, its largest 8-connected blob at least a quarter of the template;
* the correlation response's test (the default's gate on the template update,
  ``template_learn_gate``): the frame's ``TrackResult.evidence`` fails it when
  its peak or its APCE is below the gate's factor times its mean before;
* the mean share of non-zero entries of ``e`` in occluded and in untouched
  frames (how much occlusion signal ``e`` carries at all).

With ``--data``: for each OTB sequence of ``DIR``, the share of frames whose
``TrackResult.occluded`` fires, and with ``--att`` (a folder of OTB attribute
files, or a table) grouped by whether the sequence is tagged OCC.
Not a test: it measures.
"""

from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path

import numpy as np
from scipy import ndimage

os.environ.setdefault("OMP_NUM_THREADS", "1")

from boxes_md5 import config_of  # a script beside this one: bench/ is on the path

from smtmvt import Tracker, open_sequence
from smtmvt.demo import make_demo_sequence

#: L1-APG's structuring element for closing the outlier map (a 3x3 cross).
CROSS = np.array([[0, 1, 0], [1, 1, 1], [0, 1, 0]], dtype=bool)
#: L1-APG's occlusion threshold: the largest blob's share of the template, and the occluded share of the box.
QUARTER = 0.25


def largest_closed_blob(e: np.ndarray, shape: tuple[int, int]) -> float:
    """L1-APG's occlusion measure: the share of the template ``shape`` ``(h, w)`` in the
    largest 8-connected blob of the non-zero entries of ``e`` ``(h * w,)`` (row-major),
    after closing with :data:`CROSS` (padded, so the border is not eroded, as MATLAB's
    ``imclose`` does)."""
    mask = np.pad((np.abs(e) > 0).reshape(shape), 1)
    mask = ndimage.binary_erosion(ndimage.binary_dilation(mask, CROSS), CROSS)[1:-1, 1:-1]
    labels, n = ndimage.label(mask, structure=np.ones((3, 3), dtype=bool))
    return 0.0 if n == 0 else float(np.bincount(labels.ravel())[1:].max() / mask.size)


def track_outliers(tracker: Tracker, frames, box) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Track ``frames`` from ``box``: per frame after the first, ``occluded`` (bool), the
    share of non-zero intensity outliers and L1-APG's blob share of the best candidate
    (NaN where no candidate was chosen), and whether the response fails the template
    gate (:func:`fails_gate`)."""
    tracker.init(frames[0], box)
    k = tracker.config.views.index("intensity")
    gate = tracker.config.template_learn_gate
    flags, shares, blobs, failed = [], [], [], []
    for i in range(1, len(frames)):
        result, detail = tracker.update_detailed(frames[i])
        flags.append(result.occluded)
        failed.append(fails_gate(result.evidence, gate))
        if detail.best is None:
            shares.append(np.nan)
            blobs.append(np.nan)
            continue
        e = detail.observation.E[k][:, detail.best]
        shares.append(float(np.mean(np.abs(e) > 0)))
        blobs.append(largest_closed_blob(e, tracker._sampler.intensity_size))
    return np.array(flags), np.array(shares), np.array(blobs), np.array(failed)


def fails_gate(evidence, gate: tuple[float, float]) -> bool:
    """Whether the frame's response peak or APCE (``evidence``, ratios to their means
    before) is below the gate's factors ``(b1, b2)``; False without a response or gate."""
    if evidence is None or not any(gate):
        return False
    return bool(evidence.peak_ratio < gate[0] or evidence.apce_ratio < gate[1])


def recall_precision(flags: np.ndarray, occluded: np.ndarray, untouched: np.ndarray) -> str:
    tp, fn = int(np.sum(flags & occluded)), int(np.sum(~flags & occluded))
    fp = int(np.sum(flags & untouched))
    precision = f"{tp / (tp + fp):.2f}" if tp + fp else "-"
    return f"recall {tp / max(tp + fn, 1):.2f} precision {precision} (fires on {tp} occluded, {fp} untouched frames)"


def demo(args) -> None:
    seq = make_demo_sequence()
    assert seq.occluded_share is not None
    share = seq.occluded_share[1:]
    occluded, untouched = share >= QUARTER, share == 0
    runs = [
        track_outliers(Tracker(config_of(args.config, s)), seq.frames, seq.groundtruth[0]) for s in range(args.seeds)
    ]
    flags, shares, blobs, failed = (np.concatenate(parts) for parts in zip(*runs))
    occ, free = np.tile(occluded, args.seeds), np.tile(untouched, args.seeds)
    print(f"demo, {args.config}, {args.seeds} seeds: {occ.sum()} occluded frames, {free.sum()} untouched")
    print(f"  TrackResult.occluded:        {recall_precision(flags, occ, free)}")
    print(f"  L1-APG blob >= a quarter:    {recall_precision(blobs >= QUARTER, occ, free)}")
    print(f"  response fails the gate:     {recall_precision(failed, occ, free)}")
    print(
        f"  non-zero share of e:         occluded {np.nanmean(shares[occ]):.3f}, untouched {np.nanmean(shares[free]):.3f}"
    )
    print(
        f"  largest closed blob:         occluded {np.nanmean(blobs[occ]):.3f}, untouched {np.nanmean(blobs[free]):.3f}"
    )


def dataset(args) -> None:
    from smtmvt.data.attributes import attributes_of, load_attributes

    table = load_attributes(args.att) if args.att else None
    groups: dict[str, list[float]] = {"OCC": [], "not OCC": [], "untagged": []}
    for folder in sorted(p for p in Path(args.data).iterdir() if (p / "groundtruth_rect.txt").is_file()):
        seq = open_sequence(folder)
        flags, shares, _, _ = track_outliers(Tracker(config_of(args.config, args.seed)), seq, seq.first_box)
        rate = float(np.mean(flags))
        try:
            tags = None if table is None else attributes_of(table, seq.name)
        except KeyError:
            tags = None
        key = "untagged" if tags is None else ("OCC" if "OCC" in tags else "not OCC")
        groups[key].append(rate)
        print(
            f"  {seq.name:<14} occluded on {rate:.3f} of frames; non-zero share of e {np.nanmean(shares):.3f}  [{key}]"
        )
    for key, rates in groups.items():
        if rates:
            print(f"{key}: {len(rates)} sequences, occluded on {np.mean(rates):.3f} of frames on average")


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--config", choices=("default", "paper"), default="default")
    p.add_argument("--seeds", type=int, default=8, help="demo: seeds 0..N-1")
    p.add_argument("--data", default=None, help="a folder of OTB sequences instead of the demo")
    p.add_argument("--att", default=None, help="OTB attribute files (folder or table) for --data")
    p.add_argument("--seed", type=int, default=0, help="--data: the seed")
    args = p.parse_args(argv)
    (dataset if args.data else demo)(args)
    return 0


if __name__ == "__main__":
    sys.exit(main())
