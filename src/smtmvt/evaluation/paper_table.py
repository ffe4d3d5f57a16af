"""The paper's table ``tab:cap`` (average overlap of nine methods on 15 sequences) beside ours.

For each of the paper's sequences that a run holds and each of its nine methods, three
figures: **ours** (the run's average overlap of the tracker that implements the method),
**OTB** (the method's published OTB-2013 run: its per-sequence average overlap,
``overlapScores`` of ``OPE/<TRACKER>/scores_cvpr13/ALL.json``, over the whole sequence)
and **paper** (the figure printed in the paper, ``data/paper_table.json``, transcribed
once from the paper's LaTeX source with the table's label and caption). A figure that
does not exist is a reason, never a blank. Written as ``report/paper_table.md`` and
``.csv`` by :func:`write_paper_table`.
"""

from __future__ import annotations

import json
from importlib import resources

from ..data.names import canonical_name
from .published import load_published_scores
from .tables import _csv_line, _csv_text

__all__ = ["PAPER_SEQUENCES", "METHODS", "load_paper_table", "paper_rows", "paper_table_files"]

#: The paper's sequence names -> OTB's (matched case-insensitively, canonical_name).
PAPER_SEQUENCES = {
    "basketball": "Basketball",
    "david1": "David",  # OTB's David (frames 300-770); the paper's name, likely this one, is not certain
    "david2": "David2",
    "girl": "Girl",
    "subway": "Subway",
    "singer2": "Singer2",
    "doll": "Doll",
    "dog1": "Dog1",
    "faceocc2": "FaceOcc2",
    "fleetface": "FleetFace",
    "football": "Football",
    "carDark": "CarDark",  # the paper's camel case
    "crossing": "Crossing",
    "jumping": "Jumping",
    "walking": "Walking",
}

#: Method -> (our tracker, OTB's published tracker); None: there is none.
METHODS = {
    "L1T": ("smtmvt-l1t", None),  # OTB has L1APG (L1 with an APG solver), not Mei & Ling's L1T
    "MTT": ("smtmvt-mtt", "MTT"),
    "Struck": (None, "STRUCK"),
    "MIL": ("opencv-mil", "MIL"),  # OpenCV's MIL, not Babenko's code
    "IVT": ("smtmvt-ivt", "IVT"),
    "VTD": (None, "VTD"),
    "MTMVTLS": ("smtmvt-mtmvt-ls", None),
    "MTMVTLAD": ("smtmvt-mtmvt-lad", None),
    "SMTMVT": ("smtmvt-paper", None),
}

NOT_IN_RUN = "not in this run"
NO_OURS = "no tracker of ours"
NO_OTB = "no published OTB run"
NO_PAPER = "the paper gives none"


def load_paper_table() -> dict:
    """``data/paper_table.json``: ``source`` (file, label, caption), ``methods`` (9 names),
    ``sequences`` ({paper name: 9 figures}), ``average`` (9 figures)."""
    text = resources.files(__package__).joinpath("data/paper_table.json").read_text(encoding="utf-8")
    return json.loads(text)


def _ours(trackers: dict, tracker: str | None, seq: str):
    if tracker is None:
        return NO_OURS
    entry = trackers.get(tracker)
    value = None if entry is None else entry["sequences"].get(seq, {}).get("avg_overlap")
    return NOT_IN_RUN if value is None else value


def _otb(published: dict, tracker: str | None, otb_name: str):
    if tracker is None or tracker not in published:
        return NO_OTB
    by_key = {canonical_name(s): v for s, v in published[tracker]["sequences"].items()}
    return by_key.get(canonical_name(otb_name), NO_OTB)


def paper_rows(trackers: dict, sequences, published_dir=None) -> tuple[list[dict], list[str]]:
    """Rows ``{sequence, paper_name, method, ours, otb, paper}`` (a float or a reason) for
    the paper's sequences the run scored, and the paper's sequences it does not hold.
    ``trackers``, ``sequences``: a report :class:`~.scoring.Summary`'s; ``published_dir``:
    the folder of ``OPE/`` (None: no OTB figure)."""
    table = load_paper_table()
    run_seqs = {canonical_name(s): s for s in sequences}
    wanted = {m for _, m in METHODS.values() if m}
    published = load_published_scores(published_dir, "cvpr13", trackers=wanted) if published_dir else {}
    rows, absent = [], []
    for paper_name, figures in table["sequences"].items():
        seq = run_seqs.get(canonical_name(PAPER_SEQUENCES[paper_name]))
        if seq is None:
            absent.append(paper_name)
            continue
        for method, paper_value in zip(table["methods"], figures):
            ours, otb = METHODS[method]
            rows.append(
                dict(
                    sequence=seq,
                    paper_name=paper_name,
                    method=method,
                    ours=_ours(trackers, ours, seq),
                    otb=_otb(published, otb, PAPER_SEQUENCES[paper_name]) if published_dir else NO_OTB,
                    paper=NO_PAPER if paper_value is None else paper_value,
                )
            )
    return rows, absent


def _shown(v) -> str:
    return f"{v:.2f}" if isinstance(v, float) else v


def _markdown(rows: list[dict], absent: list[str], source: dict, frames) -> str:
    lines = [
        "# The paper's table, ours beside it",
        "",
        f'Source: `{source["label"]}` of {source["file"]}: "{source["caption"]}"',
        "",
        "ours: this run's average overlap"
        + (f" (first {frames} frames)" if frames else "")
        + "; OTB: the method's published OTB-2013 run, whole sequence; paper: the printed figure.",
        "",
        "| sequence | method | ours | OTB | paper |",
        "| --- | --- | --- | --- | --- |",
    ]
    for r in rows:
        name = r["sequence"] + ("" if r["paper_name"] == r["sequence"] else f" ({r['paper_name']})")
        lines.append(f"| {name} | {r['method']} | {_shown(r['ours'])} | {_shown(r['otb'])} | {_shown(r['paper'])} |")
    if absent:
        lines += ["", "The paper's sequences not in this run: " + ", ".join(absent) + f" ({NOT_IN_RUN})."]
    return "\n".join(lines) + "\n"


def _csv(rows: list[dict], absent: list[str]) -> str:
    def cell(v) -> str:
        return f"{v:.6f}" if isinstance(v, float) else _csv_text(str(v))

    out = [_csv_line(["sequence", "paper_name", "method", "ours", "otb", "paper"])]
    for r in rows:
        out.append(
            _csv_line(
                [_csv_text(r["sequence"]), r["paper_name"], r["method"], *map(cell, (r["ours"], r["otb"], r["paper"]))]
            )
        )
    for name in absent:
        out.append(_csv_line(["", name, "", NOT_IN_RUN, NOT_IN_RUN, NOT_IN_RUN]))
    return "".join(out)


def paper_table_files(trackers: dict, sequences, published_dir=None, frames=None) -> dict[str, str]:
    """``{"paper_table.md": text, "paper_table.csv": text}``, or ``{}`` when the run holds
    none of the paper's sequences. ``frames``: the run's frame limit (said in the table)."""
    rows, absent = paper_rows(trackers, sequences, published_dir)
    if not rows:
        return {}
    source = load_paper_table()["source"]
    return {"paper_table.md": _markdown(rows, absent, source, frames), "paper_table.csv": _csv(rows, absent)}
