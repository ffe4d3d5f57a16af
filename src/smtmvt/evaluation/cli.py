"""``smtmvt evaluate`` and ``smtmvt report``.

``smtmvt evaluate --dataset DIR --trackers smtmvt,opencv-csrt --out RUN_DIR``
    Runs every tracker on every sequence (OTB one-pass evaluation), resumable: run it again
    after an interruption and finished pairs are skipped. Then builds the report
    (``RUN_DIR/report/``) unless ``--no-report``.

    Exit status: 0 when every (tracker, sequence) pair is complete and the report has no
    gap, **1 when any pair failed, a tracker/sequence name was unknown or the report has
    gaps** (the other pairs still ran, the errors are printed and kept in
    ``RUN_DIR/errors.json``, and the report is still built), 2 for a problem with the whole
    command (no dataset folder, a run folder of another dataset or frame limit, a folder that
    is neither empty nor a run folder, a folder in use by another command, an unreachable
    scheduler), printed as one ``error:`` line;
    130 after Ctrl-C, 143 after SIGTERM (the run stops cleanly, its workers with it).

    ``--protocol tre`` (or ``sre``, or ``ope,tre,sre``) runs OTB's temporal or spatial
    robustness evaluation instead of (or beside) OPE: 20 runs per sequence from start frames
    spread over it, or 12 runs from shifted and scaled first boxes (:mod:`.protocols`), each
    resumable on its own; their report is in ``RUN_DIR/report/tre/`` and ``.../sre/``.

``smtmvt report RUN_DIR``
    Rebuilds ``RUN_DIR/report/`` from the stored results (nothing is re-run); ``--import``
    adds foreign per-frame results (published trackers) to the run first. Exit status 0 when
    every pair was scored, 1 when the report has gaps (errors of the run, or result files
    that cannot be used; printed, and listed in the report), 2 when no report could be built
    (for instance RUN_DIR is not a run folder, or it has no tracker to report).
"""

from __future__ import annotations

import ast
import sys
from pathlib import Path

from ..argtypes import bounded_int, positive_int
from .rundir import MAX_REPEAT, RunDir

__all__ = ["add_parsers", "cmd_evaluate", "cmd_report", "parse_tracker_options"]


def add_parsers(subparsers) -> None:
    """Register ``evaluate`` and ``report`` on an argparse sub-parsers object."""
    _add_evaluate(subparsers)
    _add_report(subparsers)


def _add_evaluate(subparsers) -> None:
    from .trackers import available_trackers

    p = subparsers.add_parser(
        "evaluate",
        help="run trackers over an OTB-format dataset (one-pass evaluation) and report",
        description=(
            "One-pass evaluation: each tracker starts from the first ground-truth box and runs "
            "over the whole sequence. Results go to RUN_DIR/results/<tracker>/<sequence>.txt "
            "(1-based x,y,w,h per frame) with per-frame times; a restarted run skips finished "
            "pairs. Exit status 0: all pairs complete; 1: some pair failed, a name was "
            "unknown or the report has gaps (the rest ran; see RUN_DIR/errors.json); 2: the "
            "command itself failed."
        ),
    )
    add = p.add_argument
    add("--dataset", required=True, metavar="DIR", help="folder of OTB sequences (<Seq>/img, groundtruth_rect.txt)")
    add(
        "--trackers",
        required=True,
        metavar="NAMES",
        help=f"comma-separated names; available: {', '.join(available_trackers())}",
    )
    add("--out", required=True, metavar="RUN_DIR", help="run folder: a new or empty folder, or a run folder to resume")
    add("--sequences", metavar="NAMES", help="comma-separated sequence names (default: all; case-insensitive)")
    add(
        "--protocol",
        default="ope",
        type=_protocols_arg,
        metavar="ope|tre|sre",
        help="OTB protocol(s), comma-separated: ope (one pass, default), tre (20 runs from start frames "
        "spread over each sequence), sre (12 runs from shifted/scaled first boxes); results of each are "
        "kept side by side in RUN_DIR and reported in report/, report/tre/, report/sre/",
    )
    add("--workers", type=positive_int, default=1, metavar="N", help="local worker processes (default 1)")
    add(
        "--scheduler",
        metavar="ADDRESS",
        help="Dask scheduler address (tcp://host:8786): run the pairs on that cluster; "
        "workers must see the dataset at the same path",
    )
    add(
        "--max-frames",
        type=positive_int,
        metavar="N",
        help="run only the first N frames of each sequence (quick checks; NOT OTB-compliant). "
        "A run folder keeps the limit it was made with",
    )
    add(
        "--repeat",
        type=bounded_int(1, MAX_REPEAT),
        metavar="N",
        help=f"run each stochastic tracker N times per sequence with N seeds, N <= {MAX_REPEAT} (deterministic ones once); "
        "the report gives mean and std. Default: the run folder's count (1 for a new one)",
    )
    add(
        "--overwrite",
        action="store_true",
        help="discard RUN_DIR's results if it was made with another --max-frames, "
        "or a tracker's results if they were made with other tracker settings",
    )
    add(
        "--tracker-option",
        action="append",
        default=[],
        metavar="TRACKER:KEY=VALUE",
        help="option for one tracker's constructor, repeatable (smtmvt:n_particles=200, opencv-kcf:detect_thresh=0.2)",
    )
    add("--attributes", metavar="PATH", help="attribute table for the report (stored in run.json)")
    add("--published", metavar="DIR", help="published OTB results folder for the report (stored in run.json)")
    add("--no-report", action="store_true", help="do not build RUN_DIR/report at the end")
    add("--quiet", action="store_true", help="no progress bars")
    p.set_defaults(func=cmd_evaluate)


def _add_report(subparsers) -> None:
    r = subparsers.add_parser(
        "report",
        help="rebuild RUN_DIR/report from stored results (nothing is re-run)",
        description="Score the stored results of a run folder and write RUN_DIR/report/ "
        "(table.md, table.csv, success/precision plots, summary.json, index.html).",
    )
    add = r.add_argument
    add("run_dir", metavar="RUN_DIR")
    add("--dataset", metavar="DIR", help="OTB dataset (default: the one in RUN_DIR/run.json)")
    add("--published", metavar="DIR", help="published OTB results folder (curves drawn beside ours)")
    add("--attributes", metavar="PATH", help="attribute table or anno/att folder")
    add(
        "--import",
        dest="imports",
        action="append",
        default=[],
        metavar="PATH[:NAME]",
        help="import per-frame results (a tracker's folder or file) into the run first, as tracker NAME; "
        "repeatable. A name the run computed itself is imported as NAME-imported",
    )
    add("--benchmark", default="tb100", choices=["tb100", "cvpr13", "tb50"], help="published score set (default tb100)")
    add("--top", type=positive_int, default=10, metavar="N", help="curves per plot (default 10)")
    add(
        "--paper-table",
        action="store_true",
        help="write report/paper_table.md and .csv: the paper's table beside ours and OTB's published runs "
        "(written anyway when the run holds a sequence of the paper's table)",
    )
    add(
        "--repeat",
        type=bounded_int(1, MAX_REPEAT),
        metavar="N",
        help="report the first N repeats (default: all the run holds)",
    )
    add(
        "--invalid",
        default=None,
        choices=["otb", "pytracking", "fail"],
        help="invalid ground-truth frames: otb (MATLAB toolkit), pytracking, fail "
        "(default: the dataset layout's own rule, otb for OTB folders)",
    )
    r.set_defaults(func=cmd_report)


def _protocols_arg(text: str) -> list[str]:
    """``--protocol``'s value: ``"tre"``, ``"ope,sre"`` -> the protocols (argparse error otherwise)."""
    import argparse

    from .protocols import parse_protocols

    try:
        return parse_protocols(text)
    except ValueError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None


def _parse_value(text: str):
    try:
        return ast.literal_eval(text)
    except (ValueError, SyntaxError):
        return text


def parse_tracker_options(items) -> dict:
    """``["smtmvt:n_particles=200", ...]`` -> ``{"smtmvt": {"n_particles": 200}}``."""
    options: dict = {}
    for item in items or []:
        tracker, sep, rest = item.partition(":")
        key, eq, value = rest.partition("=")
        if not sep or not eq or not tracker or not key:
            raise ValueError(f"--tracker-option {item!r}: expected TRACKER:KEY=VALUE")
        options.setdefault(tracker.strip(), {})[key.strip()] = _parse_value(value.strip())
    return options


def _print_errors(errors, run_dir: Path) -> None:
    if not errors:
        return
    print(f"{len(errors)} error(s) (kept in {RunDir(run_dir).errors_json}):", file=sys.stderr)
    for e in errors:
        where = e["tracker"] if e["sequence"] is None else f"{e['tracker']} / {e['sequence']}"
        if e.get("part"):
            where += f" ({e['part'].replace('/', ' ')})"
        if e.get("repeat"):
            where += f" (repeat {e['repeat']})"
        print(f"  error: {where}: {e['error']}", file=sys.stderr)


def _print_trackers(trackers: dict, indent: str = "  ") -> None:
    def fmt(v, spec):
        return "-" if v is None else format(v, spec)

    for name, t in trackers.items():
        auc = fmt(t.get("auc"), ".3f") + ("" if t.get("auc_std") in (None, 0.0) else f" ± {t['auc_std']:.3f}")
        print(
            f"{indent}{name:<22} AUC {auc}  precision@20 {fmt(t.get('precision20'), '.3f')}  "
            f"FPS {fmt(t.get('fps'), '.1f')}  ({t.get('n_sequences', '?')} sequences)"
        )


def _print_report(summary, run_dir: Path) -> None:
    summary = summary or {}
    protocols = summary.get("protocols") or {}
    if protocols and summary.get("trackers"):
        print("OPE:")
    _print_trackers(summary.get("trackers", {}))
    for protocol, sub in protocols.items():
        print(f"{protocol.upper()}:")
        _print_trackers(sub.get("trackers", {}))
    run = RunDir(run_dir)
    for protocol in ("ope", *protocols):
        for path in (run.report_table(protocol), run.report_page(protocol)):
            if path.exists():
                print(f"report: {path}")


def _print_gaps(summary) -> list:
    """Print the report's own gaps (unusable results; run errors are printed already)."""
    gaps = [e for e in (summary or {}).get("errors", []) if e.get("stage") == "report"]
    for e in gaps:
        where = " / ".join(str(x) for x in (e.get("protocol", "").upper(), e.get("tracker"), e.get("sequence")) if x)
        print(f"  report gap: {where or 'general'}: {e.get('error')}", file=sys.stderr)
    return gaps


def cmd_evaluate(args) -> int:
    from .runner import run_evaluation

    run = run_evaluation(
        args.dataset,
        args.trackers,
        args.out,
        sequences=args.sequences,
        workers=args.workers,
        scheduler=args.scheduler,
        tracker_options=parse_tracker_options(args.tracker_option),
        progress=not args.quiet,
        max_frames=args.max_frames,
        report=not args.no_report,
        attributes=args.attributes,
        published=args.published,
        repeat=args.repeat,
        overwrite=args.overwrite,
        protocols=args.protocol,
    )
    print(
        f"evaluate: {len(run.done)} pair(s) run ({run.frames} frames), {len(run.skipped)} already "
        f"done, {len(run.errors)} error(s); {run.seconds:.1f} s"
    )
    for note in run.notes:
        print(f"note: {note}")
    if run.cut_short:  # only when some sequence is longer than the limit
        names = ", ".join(run.cut_short[:5]) + (", ..." if len(run.cut_short) > 5 else "")
        n_cut = len(run.cut_short)
        print(f"note: --max-frames {args.max_frames}: {n_cut} sequence(s) cut short ({names}): not OTB-compliant")
    print(f"results: {RunDir(run.run_dir).results_dir}")
    _print_errors(run.errors, run.run_dir)
    if args.no_report:
        return 0 if run.ok else 1
    if run.report is None:
        print(f"report not built: {run.report_error} (run: smtmvt report {run.run_dir})", file=sys.stderr)
        return 1
    _print_report(run.report, run.run_dir)
    gaps = _print_gaps(run.report)
    return 0 if run.ok and not gaps else 1


def _split_import(item: str):
    """``PATH[:NAME]``: the whole string when it is an existing path, else split at the last ':'."""
    if Path(item).exists():
        return item, None
    path, sep, name = item.rpartition(":")
    if sep and path and name:
        return path, name
    return item, None


def cmd_report(args) -> int:
    from .imports import import_into_run
    from .report import build_report

    run = RunDir(args.run_dir)
    run.info()  # not a run folder: one clear error, nothing created
    for item in args.imports:
        source, name = _split_import(item)
        if not Path(source).exists():
            raise FileNotFoundError(f"--import {item}: {source} not found")
        notes: list[str] = []
        written = import_into_run(run.root, source, tracker_name=name, notes=notes)
        for note in notes:
            print(f"note: {note}")
        for tracker, seqs in written.items():
            print(f"imported {tracker}: {len(seqs)} sequence(s) from {source}")
    summary = build_report(
        run,
        dataset=args.dataset,
        published=args.published,
        benchmark=args.benchmark,
        attributes=args.attributes,
        top=args.top,
        invalid=args.invalid,
        repeat=args.repeat,
        paper_table=args.paper_table,
    )
    _print_report(summary, run.root)
    errors = summary.get("errors", [])
    for e in errors:
        where = " / ".join(str(x) for x in (e.get("protocol", "").upper(), e.get("tracker"), e.get("sequence")) if x)
        print(f"  error: {where}: {e.get('error')}", file=sys.stderr)
    return 1 if errors else 0
