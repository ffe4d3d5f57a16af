"""Accuracy sweep: one configuration over many sequences and seeds, resumable.

Usage::

    python bench/sweep.py run --tag T [--config JSON] [--seeds 3 | 3-8 | 0,4] [--workers 2]
                          [--data DIR ...] [--out RUNS] [--sequences A,B]
    python bench/sweep.py show TAG [TAG ...] [--out RUNS] [--seeds K | a-b | i,j] [--complete]
    python bench/sweep.py errors TAG [--out RUNS] [--seeds ...] [--data DIR ...]

``run`` tracks every sequence of every ``--data`` folder (default
``../shared/data/otb``; add the folders that ``../shared/data/extra/build.sh``
and ``bench/validation/build.sh`` build for the 29 measuring sequences) with
``TrackerConfig(**config)``, once per seed index ``k`` in ``0..seeds-1``
(or the listed ones: ``3-8``, ``0,4``). Seed ``k`` is the one ``smtmvt
evaluate --repeat`` gives repeat ``k``
(:func:`smtmvt.evaluation.pairs.sequence_seed`), and the score is the
evaluation's (:func:`smtmvt.evaluation.metrics.score_sequence`), so a sweep's
figures equal an evaluate run's. Each (sequence, seed) writes
``RUNS/TAG/<seq>#<k>.json`` (``RUNS`` is ``--out``, default ``runs/`` in the
project, which git ignores; average overlap, AUC, fps, boxes) once it is
done; a run started again skips finished ones, and a larger ``--seeds`` adds
seeds. ``run.json`` keeps the configuration: another one under the same tag is
refused. Runs the source tree the interpreter imports ``smtmvt`` from: to
compare against older code, run with ``PYTHONPATH=<copy of src>``.

``show`` prints per-sequence means over the seeds for each tag side by side,
the mean per seed index, and the means over all sequences and per data folder.
Compare tags on the same seeds, and not only on the seeds a default was
chosen on: those favour it (the default's seeds 0-2 average 0.626, its seeds
0-8 0.594), so any change that reshuffles the outcomes looks worse there.
While a sweep runs, ``--complete`` keeps only the sequences every tag has
finished on every seed (:func:`complete_only`): a sweep runs the longest
sequences first, and a mean over those misleads.
``show --split bench/split.json`` adds each half's mean (the tuning and the
checking half of ``docs/split.md``): a change is kept only when it helps the
first and does not hurt the second.
``errors`` splits a tag's error per sequence into size and position
(:func:`error_split`): the average overlap as scored, and as it would be with
the true box's size at the tracker's centre, and with the tracker's size at
the true centre; the median log ratio of the box's area to the truth's, and
the median offset of its centre in the truth's widths and heights. Where
"true size" gains much and "true centre" little, the box is on the target at
the wrong size (stop 31: Basketball, Girl); the other way round, it is lost
or offset (Bolt, Football).
Not a test: it measures.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
from concurrent.futures import ProcessPoolExecutor, as_completed
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
DEFAULT_DATA = [str(ROOT / ".." / "shared" / "data" / "otb")]
DEFAULT_OUT = str(ROOT / "runs")


def _sequences(data: list[str], only: set[str] | None) -> list[tuple[str, str, str]]:
    """(folder label, sequence name, path) of every OTB sequence folder under ``data``."""
    out = []
    for d in data:
        root = Path(d)
        if not root.is_dir():
            sys.exit(f"sweep: data folder {root} does not exist")
        for p in sorted(root.iterdir()):
            if (p / "groundtruth_rect.txt").is_file() and (only is None or p.name in only):
                out.append((root.name, p.name, str(p)))
    return out


def _job(path: str, config: dict, k: int) -> dict:
    """Track one sequence with seed index ``k``; returns the record written to disk."""
    os.environ.setdefault("OMP_NUM_THREADS", "1")
    import numpy as np

    from smtmvt import Tracker, TrackerConfig, open_sequence
    from smtmvt.evaluation.metrics import score_sequence
    from smtmvt.evaluation.pairs import sequence_seed

    seq = open_sequence(path)
    seed = sequence_seed(seq.name, 0, k)
    tracker = Tracker(TrackerConfig(**config, seed=seed))
    boxes = np.empty((len(seq), 4))
    t0 = time.perf_counter()
    tracker.init(seq[0], seq.first_box)
    boxes[0] = seq.first_box
    for i in range(1, len(seq)):
        boxes[i] = tracker.update(seq[i]).box
    wall = time.perf_counter() - t0
    score = score_sequence(boxes, np.asarray(seq.groundtruth))
    return {
        "sequence": seq.name,
        "k": k,
        "seed": seed,
        "avg_overlap": score.avg_overlap,
        "auc": score.auc,
        "fps": (len(seq) - 1) / wall,
        "boxes": boxes.round(4).tolist(),
    }


def run(args) -> None:
    config = json.loads(args.config)
    tag_dir = Path(args.out) / args.tag
    tag_dir.mkdir(parents=True, exist_ok=True)
    meta = tag_dir / "run.json"
    if meta.exists() and json.loads(meta.read_text())["config"] != config:
        sys.exit(f"sweep: {tag_dir} was run with another configuration: {meta.read_text()}")
    meta.write_text(json.dumps({"config": config, "data": args.data}, indent=1))
    only = set(args.sequences.split(",")) if args.sequences else None
    jobs = [
        (label, name, path, k)
        for k in seed_indices(args.seeds)
        for label, name, path in _sequences(args.data, only)
        if not (tag_dir / f"{name}#{k}.json").exists()
    ]
    # the longest sequences first, so that the pool's tail is short
    jobs.sort(key=lambda j: -len(os.listdir(Path(j[2]) / "img")))
    print(f"{args.tag}: {len(jobs)} runs to do", flush=True)
    with ProcessPoolExecutor(args.workers) as pool:
        futures = {pool.submit(_job, path, config, k): (label, name, k) for label, name, path, k in jobs}
        for fut in as_completed(futures):
            label, name, k = futures[fut]
            rec = fut.result()
            rec["folder"] = label
            tmp = tag_dir / f".{name}#{k}.json.tmp"
            tmp.write_text(json.dumps(rec))
            tmp.replace(tag_dir / f"{name}#{k}.json")
            print(f"  {name:<12} #{k}  {rec['avg_overlap']:.3f}  {rec['fps']:.1f} fps", flush=True)
    show(argparse.Namespace(tags=[args.tag], out=args.out, seeds=args.seeds, complete=False, split=None))


def seed_indices(text: str) -> list[int]:
    """Seed indices of ``--seeds``: ``"3"`` is 0, 1, 2; ``"3-8"`` is 3..8; ``"0,4"`` is 0 and 4."""
    if "," in text:
        return [int(v) for v in text.split(",")]
    if "-" in text:
        lo, hi = (int(v) for v in text.split("-"))
        return list(range(lo, hi + 1))
    return list(range(int(text)))


def _load(tag_dir: Path, seeds: str | None) -> dict:
    """{(sequence, k): record} of a tag's finished runs (seed indices of ``seeds``, all when None)."""
    recs = {}
    keep = None if seeds is None else set(seed_indices(seeds))
    for f in tag_dir.glob("*#*.json"):
        rec = json.loads(f.read_text())
        if keep is None or rec["k"] in keep:
            recs[(rec["sequence"], rec["k"])] = rec
    return recs


def _mean(values) -> float:
    values = list(values)
    return sum(values) / len(values) if values else float("nan")


def complete_only(runs: dict, seeds: list[int] | None = None) -> dict:
    """``runs`` ({tag: {(sequence, k): record}}) kept to the sequences every tag
    has finished for every seed: those of ``seeds``, or when None every seed
    index any tag has run. A sweep runs its longest sequences first, so a
    partial mean is over those and misleads (stop 32: +0.028 after 42 runs,
    level after 324)."""
    ks = set(seeds) if seeds is not None else {k for recs in runs.values() for _, k in recs}
    seqs = {s for recs in runs.values() for s, _ in recs}
    whole = {s for s in seqs if all((s, k) in recs for recs in runs.values() for k in ks)}
    return {tag: {key: r for key, r in recs.items() if key[0] in whole} for tag, recs in runs.items()}


def show(args) -> None:
    runs = {tag: _load(Path(args.out) / tag, args.seeds) for tag in args.tags}
    if args.complete:
        runs = complete_only(runs, None if args.seeds is None else seed_indices(args.seeds))
    seqs = sorted({s for recs in runs.values() for s, _ in recs}, key=str.lower)
    folders = {rec["sequence"]: rec.get("folder", "?") for recs in runs.values() for rec in recs.values()}
    print(f"{'sequence':<12}" + "".join(f"{tag[:16]:>18}" for tag in args.tags))
    for s in seqs:
        cells = []
        for tag in args.tags:
            vals = [r["avg_overlap"] for (q, _), r in runs[tag].items() if q == s]
            cells.append(f"{_mean(vals):.3f} ({len(vals)})" if vals else "-")
        print(f"{s:<12}" + "".join(f"{c:>18}" for c in cells))
    for tag in args.tags:
        recs = runs[tag]
        per_seq = {s: _mean(r["avg_overlap"] for (q, _), r in recs.items() if q == s) for s in seqs}
        done = [s for s in seqs if any(q == s for q, _ in recs)]
        ks = sorted({k for _, k in recs})
        per_k = [_mean(r["avg_overlap"] for (_, kk), r in recs.items() if kk == k) for k in ks]
        by_folder = {}
        for s in done:
            by_folder.setdefault(folders[s], []).append(per_seq[s])
        parts = " ".join(f"{f} {_mean(v):.3f} ({len(v)})" for f, v in sorted(by_folder.items()))
        fps = _mean(r["fps"] for r in recs.values())
        print(
            f"{tag}: mean {_mean(per_seq[s] for s in done):.3f} over {len(done)} sequences; "
            f"per seed {' / '.join(f'{v:.3f}' for v in per_k)}; {parts}; {fps:.1f} fps"
        )
        if args.split:
            halves = json.loads(Path(args.split).read_text())
            print("  " + "; ".join(_half(per_seq, done, h, halves[h]) for h in ("tune", "check")))


def _half(per_seq: dict, done: list, label: str, names: list) -> str:
    """``label mean (n of N)`` over the sequences of one half of the split that are done."""
    have = [per_seq[s] for s in names if s in done]
    return f"{label} {_mean(have):.3f} ({len(have)} of {len(names)})"


def error_split(boxes, gt) -> dict:
    """Where one run's overlap is lost: its size or its position.

    ``boxes``, ``gt`` : ``(n, 4)`` ``(x, y, w, h)`` boxes, same origin. The
    boxes are prepared and the frames chosen by
    :func:`smtmvt.evaluation.metrics.prepare_predictions`, as
    ``score_sequence`` does (frame 1 the truth, failed boxes repaired, frames
    with invalid truth left out). Returns
    ``ao`` (the scored average overlap), ``ao_true_size`` (each box given the
    truth's width and height about its own centre), ``ao_true_centre`` (each
    box moved to the truth's centre), ``log_area`` (median of ``log(w h / (w_gt
    h_gt))``) and ``dx``, ``dy`` (median offset of the box's centre from the
    truth's, in the truth's width and height).
    """
    import numpy as np

    from smtmvt.evaluation.metrics import overlap_ratio, prepare_predictions

    b, g, keep = prepare_predictions(boxes, gt)
    b, g = b[keep], g[keep]
    cb, cg = b[:, :2] + b[:, 2:] / 2, g[:, :2] + g[:, 2:] / 2
    true_size = np.concatenate([cb - g[:, 2:] / 2, g[:, 2:]], axis=1)
    true_centre = np.concatenate([cg - b[:, 2:] / 2, b[:, 2:]], axis=1)

    def mean_overlap(x):
        return float(np.mean(np.nan_to_num(overlap_ratio(x, g), nan=0.0)))

    with np.errstate(invalid="ignore", divide="ignore"):
        log_area = np.log(b[:, 2] * b[:, 3] / (g[:, 2] * g[:, 3]))
    return {
        "ao": mean_overlap(b),
        "ao_true_size": mean_overlap(true_size),
        "ao_true_centre": mean_overlap(true_centre),
        "log_area": float(np.nanmedian(log_area)),
        "dx": float(np.nanmedian((cb[:, 0] - cg[:, 0]) / g[:, 2])),
        "dy": float(np.nanmedian((cb[:, 1] - cg[:, 1]) / g[:, 3])),
    }


def errors(args) -> None:
    """Print :func:`error_split` per sequence, the mean over the tag's seeds, and over all."""
    from smtmvt import open_sequence

    paths = {name: path for _, name, path in _sequences(args.data, None)}
    recs = _load(Path(args.out) / args.tag, args.seeds)
    keys = ["ao", "ao_true_size", "ao_true_centre", "log_area", "dx", "dy"]
    print(f"{'sequence':<12}{'ao':>8}{'true size':>11}{'true ctr':>10}{'log area':>10}{'dx/w':>8}{'dy/h':>8}")
    rows = []
    for s in sorted({q for q, _ in recs}, key=str.lower):
        if s not in paths:
            sys.exit(f"sweep: no data folder holds {s} (--data {' '.join(args.data)})")
        gt = open_sequence(paths[s]).groundtruth
        splits = [error_split(r["boxes"], gt) for (q, _), r in recs.items() if q == s]
        row = [_mean(d[k] for d in splits) for k in keys]
        rows.append(row)
        print(f"{s:<12}{row[0]:>8.3f}{row[1]:>11.3f}{row[2]:>10.3f}{row[3]:>+10.2f}{row[4]:>+8.3f}{row[5]:>+8.3f}")
    means = [_mean(r[i] for r in rows) for i in range(3)]
    print(f"{args.tag}: mean {means[0]:.3f}, with the true size {means[1]:.3f}, at the true centre {means[2]:.3f}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = ap.add_subparsers(dest="cmd", required=True)
    r = sub.add_parser("run")
    r.add_argument("--tag", required=True)
    r.add_argument("--config", default="{}", help="TrackerConfig fields as JSON")
    r.add_argument("--seeds", default="3", help="a count N (0..N-1), a range a-b or a list i,j")
    r.add_argument("--workers", type=int, default=2)
    r.add_argument("--data", nargs="+", default=DEFAULT_DATA)
    r.add_argument("--out", default=DEFAULT_OUT)
    r.add_argument("--sequences", default=None, help="comma-separated names (default: all)")
    s = sub.add_parser("show")
    s.add_argument("tags", nargs="+")
    s.add_argument("--out", default=DEFAULT_OUT)
    s.add_argument("--seeds", default=None, help="as for run (default: every seed run)")
    s.add_argument("--complete", action="store_true", help="only the sequences every tag has finished for every seed")
    s.add_argument("--split", default=None, help="a split JSON (bench/split.json): each half's mean too")
    e = sub.add_parser("errors")
    e.add_argument("tag")
    e.add_argument("--out", default=DEFAULT_OUT)
    e.add_argument("--seeds", default=None, help="as for run (default: every seed run)")
    e.add_argument("--data", nargs="+", default=DEFAULT_DATA)
    args = ap.parse_args()
    {"run": run, "show": show, "errors": errors}[args.cmd](args)


if __name__ == "__main__":
    main()
