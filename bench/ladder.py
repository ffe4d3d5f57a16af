"""The ladder from the paper's tracker to the default, one departure at a time.

Usage::

    python bench/ladder.py steps
    python bench/ladder.py run --dataset DIR --runs RUNS [--repeat 3] [--workers 2]
                           [--sequences A,B] [--max-frames N] [--only 0,3]
    python bench/ladder.py write --runs RUNS [--split bench/split.json] [--out docs/reproduction.md]

``steps`` prints the ladder: :data:`STEPS` in order, each with the fields it
changes from the step before and what the paper's text says of it. Step 0
is :meth:`smtmvt.TrackerConfig.paper`; each later step adds its fields at
their :class:`~smtmvt.TrackerConfig` defaults to the fields of the steps
before, so the last step is the default, field for field
(:func:`ladder_options` checks it, and refuses a default that departs from
the paper in a field no step names: add the field to a step).

``run`` measures each step with the evaluation toolkit: an ``smtmvt
evaluate`` run folder ``RUNS/NN-name`` per step (tracker ``smtmvt-paper``
with the step's fields as tracker options, ``--repeat`` seeds; a folder
resumes as any run folder does). The seeds are the evaluation's, so step 0
is ``smtmvt-paper``'s run and the last step the default's, box for box.
The data folder is an argument (a folder of OTB sequences; for the 29
measuring sequences, a folder of links to the ones ``shared/data/otb``,
``shared/data/extra/build.sh`` and ``bench/validation/build.sh`` give).

``write`` reads each step's ``report/summary.json`` and writes the table
(mean average overlap over the sequences, the mean of the per-sequence
spread over the seeds, the two halves of ``bench/split.json``, AUC, fps)
and a plot of the mean per step beside it (``reproduction.png``). Not a
test: it measures.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
from pathlib import Path

import numpy as np

from smtmvt import TrackerConfig

TRACKER = "smtmvt-paper"

#: ``(name, fields, what the paper's text says)`` in the ladder's order: sampling fixes,
#: then views, then the motion model, then each cue, then the reporting.
STEPS: list[tuple[str, tuple[str, ...], str]] = [
    ("paper", (), "the paper's tracker (TrackerConfig.paper())"),
    ("frames-as-given", ("frame_size",), "contradicts: the paper resizes every frame to 320x240"),
    ("scale-normalized", ("scale_normalize", "antialias"), "silent: how candidates are sampled"),
    ("cropped-planes", ("crop_planes", "crop_refresh"), "silent: planes computed on the candidates' window"),
    ("gray-hog-lbp", ("hog_plane", "lbp_plane"), "contradicts: the paper computes every view after Tan-Triggs"),
    ("color-grid", ("color_grid", "histogram_power"), "silent: the color histogram's layout and comparison"),
    ("coarse-view", ("views", "deferred_views"), "contradicts: the paper has four views"),
    ("velocity", ("velocity",), "silent: the paper's motion model is a random walk; it names no dynamics"),
    ("motion-cue", ("motion_weight",), "adds: a term the paper's likelihood does not have"),
    ("anchor-cue", ("anchor_weight",), "adds: a term the paper's likelihood does not have"),
    ("foreground-cue", ("foreground_weight",), "adds: a term the paper's likelihood does not have"),
    (
        "correlation-cue",
        ("correlation_weight", "correlation_particles", "correlation_learn_gate", "correlation_usual_peak"),
        "adds: a term and a proposal the paper does not have",
    ),
    ("camera-motion", ("camera_motion",), "adds: a second prediction, moved with the camera, the filter chooses"),
    ("template-gate", ("template_learn_gate",), "adds: a test before the paper's template update"),
    ("redetect", ("redetect_after",), "adds: a wider search the paper does not have"),
    ("report-box", ("report_aspect", "report_scale"), "silent: the box reported for the state"),
    ("report-size", ("report_read_size",), "adds: the reported size read by the correlation filter"),
]


def _departures() -> dict:
    """``{field: default value}`` of every field where the default differs from the paper (seed aside)."""
    paper, default = TrackerConfig.paper().to_flat(), TrackerConfig().to_flat()
    return {name: value for name, value in default.items() if name != "seed" and paper[name] != value}


def ladder_options() -> list[dict]:
    """The tracker options of each step (cumulative ``{field: value}``, step 0 empty).

    Raises ValueError when a default departs from the paper in a field no step names, or a
    step names a field where they agree (the ladder would no longer end at the default).
    """
    departures = _departures()
    named = [f for _, fields, _ in STEPS for f in fields]
    missing = sorted(set(departures) - set(named))
    if missing:
        raise ValueError(f"the default departs from the paper in {missing}: name them in a step of STEPS")
    options, out = {}, []
    for _, fields, _ in STEPS:
        options.update({f: departures[f] for f in fields if f in departures})
        out.append(dict(options))
    last = TrackerConfig.paper(**out[-1])
    if last.replace(seed=0) != TrackerConfig(seed=0):
        raise ValueError("the ladder's last step is not the default")
    return out


def step_dir(runs: Path, k: int) -> Path:
    """The run folder of step ``k``: ``RUNS/NN-name``."""
    return runs / f"{k:02d}-{STEPS[k][0]}"


def cmd_steps(_args) -> int:
    for k, (opts, (name, fields, paper)) in enumerate(zip(ladder_options(), STEPS)):
        changes = ", ".join(f"{f}={opts[f]!r}" for f in fields if f in opts) or "-"
        print(f"{k:2d} {name:<18} {changes}\n   {paper}")
    return 0


def cmd_run(args) -> int:
    from smtmvt.evaluation.runner import run_evaluation

    steps = ladder_options()
    only = range(len(steps)) if args.only is None else [int(v) for v in args.only.split(",")]
    for k in only:
        out = step_dir(Path(args.runs), k)
        print(f"step {k} ({STEPS[k][0]}) -> {out}", flush=True)
        result = run_evaluation(
            args.dataset,
            [TRACKER],
            out,
            sequences=args.sequences,
            workers=args.workers,
            tracker_options={TRACKER: steps[k]},
            progress=not args.quiet,
            max_frames=args.max_frames,
            repeat=args.repeat,
        )
        if not result.ok:
            print(f"step {k}: the run has errors, see {out / 'errors.json'}", file=sys.stderr)
            return 1
    return 0


def step_figures(summary: dict, split: dict | None) -> dict:
    """One step's figures from its ``summary.json``: ``ao`` (mean over the sequences of the
    per-sequence average overlap, over the repeats), ``spread`` (mean per-sequence std over
    the repeats), ``tune`` / ``check`` (``ao`` over each half of ``split``; None without it
    or when a half has no sequence in the run), ``auc``, ``fps``, ``n`` (sequences)."""
    entry = summary["trackers"][TRACKER]
    per_seq = entry["sequences"]
    ao = {s: v["avg_overlap"] for s, v in per_seq.items() if v.get("avg_overlap") is not None}
    spreads = [v["avg_overlap_std"] for v in per_seq.values() if v.get("avg_overlap_std") is not None]

    def half(names):
        values = [ao[s] for s in names if s in ao]
        return float(np.mean(values)) if values else None

    return {
        "ao": float(np.mean(list(ao.values()))) if ao else None,
        "spread": float(np.mean(spreads)) if spreads else None,
        "tune": half(split["tune"]) if split else None,
        "check": half(split["check"]) if split else None,
        "auc": entry.get("auc"),
        "fps": entry.get("fps"),
        "n": len(ao),
    }


def _cell(value, spec: str = ".3f") -> str:
    return "-" if value is None else format(value, spec)


def ladder_table(rows: list[tuple[int, dict]]) -> str:
    """The markdown table of the measured steps ``[(k, step_figures)]``."""
    lines = [
        "| step | changes | the paper's text | mean AO | seed std | tune | check | AUC | fps | sequences |",
        "| ---: | --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |",
    ]
    options = ladder_options()
    for k, fig in rows:
        name, fields, paper = STEPS[k]
        changes = ", ".join(f"`{f}={options[k][f]!r}`" for f in fields if f in options[k]) or "-"
        lines.append(
            f"| {k} {name} | {changes} | {paper} | {_cell(fig['ao'])} | {_cell(fig['spread'])} | "
            f"{_cell(fig['tune'])} | {_cell(fig['check'])} | {_cell(fig['auc'])} | {_cell(fig['fps'], '.1f')} | "
            f"{fig['n']} |"
        )
    return "\n".join(lines)


def plot_ladder(rows: list[tuple[int, dict]], path: Path) -> None:
    """The mean average overlap (and each half) per step, as a PNG at ``path``."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    ks = [k for k, _ in rows]
    fig, ax = plt.subplots(figsize=(8, 4))
    for key, style in (("ao", "o-"), ("tune", "s--"), ("check", "^--")):
        ys = [f[key] for _, f in rows]
        if any(y is not None for y in ys):
            ax.plot(ks, [np.nan if y is None else y for y in ys], style, label=key)
    ax.set_xticks(ks, [STEPS[k][0] for k in ks], rotation=45, ha="right")
    ax.set_ylabel("mean average overlap")
    ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def cmd_write(args) -> int:
    split = json.loads(Path(args.split).read_text()) if args.split else None
    rows = []
    for k in range(len(STEPS)):
        summary = step_dir(Path(args.runs), k) / "report" / "summary.json"
        if summary.is_file():
            rows.append((k, step_figures(json.loads(summary.read_text()), split)))
    if not rows:
        print(f"ladder: no step of {args.runs} has a report/summary.json yet", file=sys.stderr)
        return 1
    out = Path(args.out)
    plot_ladder(rows, out.with_suffix(".png"))
    table = ladder_table(rows)
    text = out.read_text() if out.is_file() else ""
    begin, end = "<!-- ladder: begin -->", "<!-- ladder: end -->"
    block = f"{begin}\n{table}\n\n![mean average overlap per step]({out.with_suffix('.png').name})\n{end}"
    if begin in text and end in text:
        text = text[: text.index(begin)] + block + text[text.index(end) + len(end) :]
    else:
        text = (text + "\n\n" if text else "") + block + "\n"
    out.write_text(text)
    print(table)
    return 0


def main(argv=None) -> int:
    os.environ.setdefault("OMP_NUM_THREADS", "1")
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    sub = p.add_subparsers(dest="cmd", required=True)
    sub.add_parser("steps").set_defaults(func=cmd_steps)
    r = sub.add_parser("run")
    r.add_argument("--dataset", required=True)
    r.add_argument("--runs", required=True)
    r.add_argument("--repeat", type=int, default=3)
    r.add_argument("--workers", type=int, default=1)
    r.add_argument("--sequences", default=None)
    r.add_argument("--max-frames", type=int, default=None)
    r.add_argument("--only", default=None, help="comma-separated step numbers")
    r.add_argument("--quiet", action="store_true")
    r.set_defaults(func=cmd_run)
    w = sub.add_parser("write")
    w.add_argument("--runs", required=True)
    w.add_argument("--split", default=None)
    w.add_argument("--out", default="docs/reproduction.md")
    w.set_defaults(func=cmd_write)
    args = p.parse_args(argv)
    return args.func(args)


if __name__ == "__main__":
    sys.exit(main())
