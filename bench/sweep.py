"""Accuracy sweep: one configuration over many sequences and seeds, as ``smtmvt evaluate`` run folders.

Usage::

    python bench/sweep.py run --tag T --data DIR [DIR ...] [--config JSON | --config FILE.json]
                          [--seeds 3 | 3-8 | 0,4] [--workers 2] [--out RUNS] [--sequences A,B]
    python bench/sweep.py show TAG [TAG ...] [--out RUNS] [--seeds K | a-b | i,j] [--complete]
                          [--split bench/split.json]
    python bench/sweep.py errors TAG [--out RUNS] [--seeds ...] [--data DIR ...]
    python bench/sweep.py losses TAG [--out RUNS] [--seeds ...] [--data DIR ...]

``run`` is ``smtmvt evaluate`` (:func:`smtmvt.evaluation.runner.run_evaluation`) of the
tracker ``smtmvt`` with the configuration as its tracker options (``TrackerConfig``
fields as JSON, or a JSON file of them), once per ``--data`` folder (the folders of
sequences are arguments: ``shared/data/otb``, and the folders that
``shared/data/extra/build.sh`` and ``bench/validation/build.sh`` build for the 29
measuring sequences), into the run folder ``RUNS/TAG/<data folder's name>/``
(``RUNS`` is ``--out``, default ``runs/`` in the project, which git ignores). So a
sweep's folders have the toolkit's guarantees: the lock, atomic writes, and the settings
check (another configuration under the same tag is refused, naming what differs); a run
started again skips finished pairs, and a larger ``--seeds`` adds repeats. Seed index
``k`` is evaluate's repeat ``k`` (:func:`smtmvt.evaluation.pairs.sequence_seed`):
``--seeds N`` is ``--repeat N``; a range or list (``3-8``, ``0,4``) runs every repeat up
to its largest (evaluate's repeats are a count), and ``show --seeds`` picks the listed
ones. Runs the source tree the interpreter imports ``smtmvt`` from: to compare against
older code, run with ``PYTHONPATH=<copy of src>``. ``smtmvt report RUNS/TAG/<folder>``
gives a tag's full report.

``show`` scores the run folders' results as the report does
(:func:`smtmvt.evaluation.scoring.score_result`: average overlap per sequence and
repeat) and prints per-sequence means over the seeds for each tag side by side, the mean
per seed index, and the means over all sequences and per data folder (``fps``: frames
per second of tracking, from the times files). It also reads the sweep folders of
before (``RUNS/TAG/<seq>#<k>.json``, one file per sequence and seed), so the baseline
tags of the notes compare with new ones.
Compare tags on the same seeds, and not only on the seeds a default was
chosen on: those favour it (the default's seeds 0-2 average 0.626, its seeds
0-8 0.594), so any change that reshuffles the outcomes looks worse there.
While a sweep runs, ``--complete`` keeps only the sequences every tag has
finished on every seed (:func:`complete_only`): a mean over the sequences done
first misleads.
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
or offset (Bolt, Football). A run folder knows its dataset; ``--data`` is needed
only for a sweep folder of before.
``losses`` lists where each run loses the target (:func:`loss_spans`: spans
of 5 or more frames with overlap under 0.1) and how many runs end lost: a
loss that lasts to the end is a failure to recover, one that ends a recovery
(issue 48 item 5, docs/experiments.md#n55).
Not a test: it measures.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
DEFAULT_OUT = str(ROOT / "runs")
#: the tracker a sweep runs (evaluate's name for smtmvt.Tracker)
TRACKER = "smtmvt"


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


def read_config(text: str) -> dict:
    """``--config``: ``TrackerConfig`` fields as JSON text, or the path of a JSON file of them."""
    path = Path(text)
    source = f"--config {text}"
    if text.strip().endswith(".json") or path.is_file():
        try:
            text = path.read_text(encoding="utf-8")
        except OSError as exc:
            sys.exit(f"sweep: {source}: cannot read it: {exc}")
    try:
        config = json.loads(text)
    except json.JSONDecodeError as exc:
        sys.exit(f"sweep: {source}: not JSON: {exc}")
    if not isinstance(config, dict):
        sys.exit(f"sweep: {source}: expected an object of TrackerConfig fields, got {type(config).__name__}")
    if "seed" in config:
        sys.exit(f"sweep: {source}: no 'seed' in a sweep's configuration; --seeds chooses the seeds")
    return config


def _run_folders(data: list[str], tag_dir: Path) -> list[tuple[Path, Path]]:
    """``[(data folder, its run folder RUNS/TAG/<folder name>)]``; two data folders of one
    name would share a run folder: refused."""
    pairs, seen = [], {}
    for d in data:
        root = Path(d)
        if not root.is_dir():
            sys.exit(f"sweep: data folder {root} does not exist")
        if root.resolve().name in seen:
            sys.exit(f"sweep: data folders {seen[root.resolve().name]} and {root} have one name; rename one")
        seen[root.resolve().name] = root
        pairs.append((root, tag_dir / root.resolve().name))
    return pairs


def run(args) -> None:
    """``smtmvt evaluate`` of the configuration, one run folder per ``--data`` folder."""
    from smtmvt.evaluation.rundir import RunDirError
    from smtmvt.evaluation.runner import run_evaluation

    config = read_config(args.config)
    tag_dir = Path(args.out) / args.tag
    if _old_records(tag_dir):
        sys.exit(f"sweep: {tag_dir} is a sweep folder of before (<seq>#<k>.json); choose another tag")
    repeat = max(seed_indices(args.seeds)) + 1
    only = set(args.sequences.split(",")) if args.sequences else None
    for data, run_dir in _run_folders(args.data, tag_dir):
        names = [name for _, name, _ in _sequences([str(data)], only)] if only is not None else None
        if names == []:
            continue
        try:
            result = run_evaluation(
                data,
                [TRACKER],
                run_dir,
                sequences=names,
                workers=args.workers,
                tracker_options={TRACKER: config},
                progress=not args.quiet,
                repeat=repeat,
                report=False,
            )
        except (RunDirError, ValueError, OSError) as exc:
            sys.exit(f"sweep: {args.tag}: {exc}")
        print(
            f"{args.tag} / {run_dir.name}: {len(result.done)} run(s) done, {len(result.skipped)} already done, "
            f"{len(result.errors)} error(s)",
            flush=True,
        )
        for e in result.errors:
            print(f"  error: {e['sequence']} #{e.get('repeat', 0)}: {e['error']}", file=sys.stderr)
    show(argparse.Namespace(tags=[args.tag], out=args.out, seeds=args.seeds, complete=False, split=None))


def seed_indices(text: str) -> list[int]:
    """Seed indices of ``--seeds``: ``"3"`` is 0, 1, 2; ``"3-8"`` is 3..8; ``"0,4"`` is 0 and 4."""
    if "," in text:
        return [int(v) for v in text.split(",")]
    if "-" in text:
        lo, hi = (int(v) for v in text.split("-"))
        return list(range(lo, hi + 1))
    return list(range(int(text)))


def _old_records(tag_dir: Path) -> list[Path]:
    """The record files of a sweep folder of before (``<seq>#<k>.json``)."""
    return sorted(tag_dir.glob("*#*.json")) if tag_dir.is_dir() else []


def _load(tag_dir: Path, seeds: str | None) -> dict:
    """{(sequence, k): record} of a tag's finished runs (seed indices of ``seeds``, all when None).

    A record: ``sequence``, ``k``, ``avg_overlap``, ``auc``, ``fps``, ``boxes`` ((n, 4)
    pixels: 1-based from a run folder, 0-based from a sweep folder of before), ``folder`` (the
    data folder's name) and, from a run folder, ``run_dir``."""
    keep = None if seeds is None else set(seed_indices(seeds))
    old = _old_records(tag_dir)
    if old:
        recs = {}
        for f in old:
            rec = json.loads(f.read_text())
            if keep is None or rec["k"] in keep:
                recs[(rec["sequence"], rec["k"])] = rec
        return recs
    if not tag_dir.is_dir():
        sys.exit(f"sweep: no tag folder {tag_dir}")
    recs = {}
    for run_dir in sorted(p for p in tag_dir.iterdir() if p.is_dir()):
        for (seq, k), rec in _load_run(run_dir, keep).items():
            if (seq, k) in recs:
                sys.exit(f"sweep: {seq} is in two run folders of {tag_dir}: {recs[seq, k]['folder']}, {run_dir.name}")
            recs[(seq, k)] = rec
    return recs


def _load_run(run_dir: Path, keep: set[int] | None) -> dict:
    """{(sequence, k): record} of one evaluate run folder's finished ``smtmvt`` results, scored
    as the report scores them (the dataset's invalid-frame rule, ``run.json``'s frame limit)."""
    import numpy as np

    from smtmvt.evaluation.groundtruth import GroundTruth
    from smtmvt.evaluation.rundir import RunDir
    from smtmvt.evaluation.scoring import score_result

    run = RunDir(run_dir)
    info = run.info()  # not a run folder: RunDirError naming it
    gt_source = GroundTruth(info.dataset)
    recs = {}
    for seq in info.sequences:
        ks = [k for k in range(info.repeat) if keep is None or k in keep]
        done = [k for k in ks if run.result_path(TRACKER, seq, k).is_file()]
        if not done:
            continue
        gt = gt_source.load(seq)[: info.max_frames]
        for k in done:
            score = score_result(run, TRACKER, seq, k, gt, gt_source.absent_rule)
            times = run.read_times(TRACKER, seq, k)
            fps = float(times.size / times.sum()) if times is not None and times.sum() > 0 else float("nan")
            recs[(seq, k)] = {
                "sequence": seq,
                "k": k,
                "avg_overlap": score.avg_overlap,
                "auc": score.auc,
                "fps": fps,
                "boxes": np.asarray(run.read_result(TRACKER, seq, k)),
                "folder": run_dir.name,
                "run_dir": str(run_dir),
            }
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


def loss_spans(boxes, gt, below: float = 0.1, least: int = 5) -> list[tuple[int, int, bool]]:
    """Where one run loses the target: each span of at least ``least`` frames in a
    row whose overlap with the truth is under ``below`` (the toolkit's rule for
    a lost frame, issue 51), as ``(first frame, 1-based; frames; whether it
    lasts to the last frame)``. ``boxes``, ``gt`` as for :func:`error_split`
    (prepared the same way; frames with invalid truth neither count nor break
    a span)."""
    import numpy as np

    from smtmvt.evaluation.metrics import overlap_ratio, prepare_predictions

    b, g, keep = prepare_predictions(boxes, gt)
    frames = np.flatnonzero(keep)
    lost = np.nan_to_num(overlap_ratio(b[keep], g[keep]), nan=0.0) < below
    spans, start = [], None
    for i, is_lost in enumerate([*lost, False]):
        if is_lost and start is None:
            start = i
        elif not is_lost and start is not None:
            if i - start >= least:
                spans.append((int(frames[start]) + 1, i - start, i == len(lost)))
            start = None
    return spans


def losses(args) -> None:
    """Print :func:`loss_spans` per sequence and seed, and how many runs end lost."""
    paths = {name: path for _, name, path in _sequences(args.data or [], None)}
    recs = _load(Path(args.out) / args.tag, args.seeds)
    ended = 0
    for (s, k), rec in sorted(recs.items(), key=lambda kv: (kv[0][0].lower(), kv[0][1])):
        spans = loss_spans(rec["boxes"], _groundtruth(rec, paths, args.data or []))
        ended += any(to_end for _, _, to_end in spans)
        if spans:
            shown = ", ".join(f"{a}+{n}{' (to the end)' if to_end else ''}" for a, n, to_end in spans)
            print(f"{s:<14}#{k}  {shown}")
    print(f"{args.tag}: {len(recs)} runs, {ended} lost to the end (frame+frames: overlap < 0.1 for 5 or more frames)")


def _groundtruth(rec: dict, paths: dict, data: list[str]):
    """The ground truth of a record, in its boxes' origin: a run folder's dataset (1-based, as
    its result files), or the ``--data`` folder of a record of before (0-based)."""
    from smtmvt import open_sequence

    if "run_dir" in rec:
        from smtmvt.evaluation.groundtruth import GroundTruth
        from smtmvt.evaluation.rundir import RunDir

        info = RunDir(rec["run_dir"]).info()
        return GroundTruth(info.dataset).load(rec["sequence"])[: info.max_frames]
    s = rec["sequence"]
    if s not in paths:
        sys.exit(f"sweep: no data folder holds {s} (--data {' '.join(data) or 'not given'})")
    return open_sequence(paths[s]).groundtruth


def errors(args) -> None:
    """Print :func:`error_split` per sequence, the mean over the tag's seeds, and over all."""
    paths = {name: path for _, name, path in _sequences(args.data or [], None)}
    recs = _load(Path(args.out) / args.tag, args.seeds)
    keys = ["ao", "ao_true_size", "ao_true_centre", "log_area", "dx", "dy"]
    print(f"{'sequence':<12}{'ao':>8}{'true size':>11}{'true ctr':>10}{'log area':>10}{'dx/w':>8}{'dy/h':>8}")
    rows = []
    for s in sorted({q for q, _ in recs}, key=str.lower):
        mine = [r for (q, _), r in recs.items() if q == s]
        gt = _groundtruth(mine[0], paths, args.data or [])
        splits = [error_split(r["boxes"], gt) for r in mine]
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
    r.add_argument("--data", nargs="+", required=True, metavar="DIR", help="folders of OTB sequences")
    r.add_argument("--config", default="{}", help="TrackerConfig fields as JSON, or a .json file of them")
    r.add_argument("--seeds", default="3", help="a count N (0..N-1), a range a-b or a list i,j")
    r.add_argument("--workers", type=int, default=2)
    r.add_argument("--out", default=DEFAULT_OUT)
    r.add_argument("--sequences", default=None, help="comma-separated names (default: all)")
    r.add_argument("--quiet", action="store_true", help="no progress bars")
    s = sub.add_parser("show")
    s.add_argument("tags", nargs="+")
    s.add_argument("--out", default=DEFAULT_OUT)
    s.add_argument("--seeds", default=None, help="as for run (default: every seed run)")
    s.add_argument("--complete", action="store_true", help="only the sequences every tag has finished for every seed")
    s.add_argument("--split", default=None, help="a split JSON (bench/split.json): each half's mean too")
    for name in ("errors", "losses"):  # one tag's runs, read against the truth
        e = sub.add_parser(name)
        e.add_argument("tag")
        e.add_argument("--out", default=DEFAULT_OUT)
        e.add_argument("--seeds", default=None, help="as for run (default: every seed run)")
        e.add_argument("--data", nargs="+", default=None, help="data folders (only for a sweep folder of before)")
    args = ap.parse_args()
    {"run": run, "show": show, "errors": errors, "losses": losses}[args.cmd](args)


if __name__ == "__main__":
    main()
