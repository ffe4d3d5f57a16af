"""The average-overlap table of a report (the paper's table) as Markdown, CSV and HTML.

Rows are sequences, columns trackers, then Average / AUC / Precision / FPS rows; the best
value of each row is bold (compared at the digits shown). With repeats (``repeat > 1``) a
cell shows ``mean ± std`` over the repeats and the CSV has a ``<tracker>_std`` column beside
each tracker.

``table.csv`` is opened by spreadsheets, which run a cell starting with ``=``, ``+``, ``-``,
``@``, a tab or a carriage return as a formula: such a text cell (a sequence named
``=HYPERLINK(...)``) is written with a leading ``'`` (OWASP's advice on CSV injection), so it
shows as the text it is. Numbers are ours, written as numbers (``-0.5`` stays ``-0.5``).
"""

from __future__ import annotations

import html
import re
from dataclasses import dataclass

from .protocols import PROTOCOL_TITLES
from .scoring import Summary

__all__ = ["markdown_table", "csv_table", "html_table", "protocols_markdown", "protocols_html"]

_DIGITS = 2
#: first characters that make a spreadsheet read a cell as a formula (OWASP, CSV injection)
_FORMULA_START = ("=", "+", "-", "@", "\t", "\r")
_PLAIN_NUMBER = re.compile(r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?")


@dataclass
class _Cell:
    text: str
    bold: bool = False


def _shows_std(summary: Summary) -> bool:
    return int(summary.settings.get("repeat") or 1) > 1


def _best(values: dict[str, float | None], digits: int) -> set[str]:
    shown = {k: round(v, digits) for k, v in values.items() if v is not None}
    if not shown:
        return set()
    top = max(shown.values())
    return {k for k, v in shown.items() if v == top}


def _row(summary: Summary, pick, digits: int, bold: bool = True, empty: str = "–") -> list[_Cell]:
    """One row: ``pick(entry) -> (mean, std)`` for each tracker."""
    values = {t: pick(e) for t, e in summary.trackers.items()}
    best = _best({t: v[0] for t, v in values.items()}, digits) if bold else set()
    cells = []
    for t, (mean, std) in values.items():
        if mean is None:
            cells.append(_Cell(empty))
            continue
        text = f"{mean:.{digits}f}"
        if std is not None and _shows_std(summary):
            text += f" ± {std:.{digits}f}"
        cells.append(_Cell(text, t in best))
    return cells


def _rows(summary: Summary) -> list[tuple[str, str, list[_Cell]]]:
    """``(Markdown label, plain label, cells)`` of every row."""
    rows = []
    for seq in summary.table_sequences:
        if seq not in summary.sequences:
            rows.append((_md(seq), seq, [_Cell("error") for _ in summary.trackers]))
            continue

        def per_seq(e, seq=seq):
            s = e["sequences"].get(seq, {})
            return s.get("avg_overlap"), s.get("avg_overlap_std")

        rows.append((_md(seq), seq, _row(summary, per_seq, _DIGITS, empty="error")))
    rows.append(("**Average**", "Average", _row(summary, lambda e: (e["avg_overlap"], e["avg_overlap_std"]), _DIGITS)))
    rows.append(("AUC (success)", "AUC (success)", _row(summary, lambda e: (e["auc"], e["auc_std"]), 3)))
    pick_prec = lambda e: (e["precision20"], e["precision20_std"])  # noqa: E731
    rows.append(("Precision (20 px)", "Precision (20 px)", _row(summary, pick_prec, 3)))
    rows.append(("FPS", "FPS", _row(summary, lambda e: (e["fps"], None), 1, bold=False)))
    return rows


def _md(text: str) -> str:
    """Text for a Markdown table cell: ``|`` and line breaks would break the row."""
    return text.replace("\\", "\\\\").replace("|", "\\|").replace("\n", " ")


def markdown_table(summary: Summary) -> str:
    """``table.md``: the table, a note on differing sequence counts, and the errors."""
    invalid = summary.settings.get("invalid", "otb")
    lines = [
        f"# Average overlap per sequence ({PROTOCOL_TITLES[summary.protocol]})",
        "",
        f"Best of each row in **bold** (compared at the {_DIGITS} decimals shown). `error`: no usable "
        f"result (see below). Invalid ground-truth frames: `{invalid}` rule.",
    ]
    if _shows_std(summary):
        lines.append(f"Cells: mean ± sample standard deviation over {summary.settings['repeat']} repeats.")
    lines.append(
        "FPS: frames over the tracker's own wall time in this run; it measures the machine as it was "
        "(other workers or jobs share it), not the tracker alone: compare speeds with `bench/`."
    )
    trackers = list(summary.trackers)
    lines += [
        "",
        "| Sequence | " + " | ".join(trackers) + " |",
        "| --- | " + " | ".join("---:" for _ in trackers) + " |",
    ]
    for label, _, cells in _rows(summary):
        shown = [f"**{c.text}**" if c.bold else c.text for c in cells]
        lines.append(f"| {label} | " + " | ".join(shown) + " |")
    lines.append("")
    n_seq = {t: e["n_sequences"] for t, e in summary.trackers.items()}
    if len(set(n_seq.values())) > 1:
        counts = ", ".join(f"{t} {n}" for t, n in n_seq.items())
        lines += [f"Averages are over the sequences each tracker has results for: {counts}.", ""]
    errs = [(t, s, m) for t, e in summary.trackers.items() for s, m in e["errors"].items()]
    if errs:
        lines += ["## Errors", ""] + [f"- {t} / {s}: {m}" for t, s, m in errs] + [""]
    if summary.protocols:
        lines += [protocols_markdown(summary)]
    return "\n".join(lines)


def _protocol_rows(summary: Summary) -> tuple[list[str], list[tuple[str, list[str]]]]:
    """``(header, rows)`` of the AUC and precision of each tracker under each protocol the
    summary holds (OPE's own entries, then ``summary.protocols``); ``–`` where none."""
    held = ({"ope": summary.trackers} if summary.trackers else {}) | {
        p: d["trackers"] for p, d in summary.protocols.items()
    }
    header = [f"{p.upper()} {what}" for p in held for what in ("AUC", "precision")]
    names = list(dict.fromkeys(t for entries in held.values() for t in entries))
    rows = []
    for t in names:
        cells = []
        for entries in held.values():
            e = entries.get(t) or {}
            cells += ["–" if e.get(k) is None else f"{e[k]:.3f}" for k in ("auc", "precision20")]
        rows.append((t, cells))
    return header, rows


def protocols_markdown(summary: Summary) -> str:
    """The AUC (success) and precision (20 px) of each tracker under each protocol, Markdown;
    each protocol's full report is in ``report/<protocol>/``."""
    header, rows = _protocol_rows(summary)
    lines = [
        "## Protocols",
        "",
        "AUC of the success plot and precision at 20 px of each protocol the run holds "
        "(TRE and SRE: their full reports are in `tre/` and `sre/`).",
        "",
        "| Tracker | " + " | ".join(header) + " |",
        "| --- | " + " | ".join("---:" for _ in header) + " |",
    ]
    lines += [f"| {_md(t)} | " + " | ".join(cells) + " |" for t, cells in rows]
    return "\n".join(lines + [""])


def protocols_html(summary: Summary) -> str:
    """:func:`protocols_markdown`'s table as HTML (escaped), each protocol linked to its page."""
    e = html.escape
    header, rows = _protocol_rows(summary)
    out = ["<table>", "<tr><th>Tracker</th>" + "".join(f"<th>{e(h)}</th>" for h in header) + "</tr>"]
    out += [f"<tr><td>{e(t)}</td>" + "".join(f"<td>{e(c)}</td>" for c in cells) + "</tr>" for t, cells in rows]
    out.append("</table>")
    return "\n".join(out)


def csv_table(summary: Summary) -> str:
    """``table.csv``: full-precision numbers (empty where there is none), text cells escaped
    (:func:`_csv_text`), one ``\\n``-ended line per row."""
    std = _shows_std(summary)
    trackers = list(summary.trackers)
    header = [c for t in trackers for c in ([t, f"{t}_std"] if std else [t])]
    lines = [_csv_line([_csv_text(c) for c in ["sequence", *header]])]

    def cells(pairs):
        return [_csv(v) for mean, sd in pairs for v in ([mean, sd] if std else [mean])]

    for seq in summary.table_sequences:
        got = [summary.trackers[t]["sequences"].get(seq, {}) for t in trackers]
        lines.append(_csv_line([_csv_text(seq), *cells((g.get("avg_overlap"), g.get("avg_overlap_std")) for g in got)]))
    for label, key in (("average", "avg_overlap"), ("auc", "auc"), ("precision20", "precision20")):
        pairs = ((summary.trackers[t][key], summary.trackers[t][f"{key}_std"]) for t in trackers)
        lines.append(_csv_line([label, *cells(pairs)]))
    lines.append(_csv_line(["fps", *cells((summary.trackers[t]["fps"], None) for t in trackers)]))
    return "".join(lines)


def _csv_line(cells: list[str]) -> str:
    """One CSV row. A cell holding ``,``, ``"``, ``\\r`` or ``\\n`` is quoted and its quotes
    doubled (RFC 4180); ``csv.writer`` leaves a lone ``\\r`` unquoted, which splits the row."""

    def quoted(cell: str) -> str:
        return '"' + cell.replace('"', '""') + '"' if any(ch in cell for ch in ',"\r\n') else cell

    return ",".join(quoted(c) for c in cells) + "\n"


def _csv(v) -> str:
    """A number's cell (6 decimals), empty for None."""
    return "" if v is None else f"{v:.6f}"


def _csv_text(text: str) -> str:
    """A text cell that no spreadsheet runs as a formula: ``'`` before a leading ``= + - @``,
    tab or carriage return (a plain number such as ``-1`` is no formula and is kept)."""
    if text.startswith(_FORMULA_START) and not _PLAIN_NUMBER.fullmatch(text):
        return "'" + text
    return text


def html_table(summary: Summary) -> str:
    """The table as an HTML ``<table>`` (every text escaped)."""
    e = html.escape
    out = ["<table>", "<tr><th>Sequence</th>" + "".join(f"<th>{e(t)}</th>" for t in summary.trackers) + "</tr>"]
    for _, label, cells in _rows(summary):
        tds = "".join(f"<td><b>{e(c.text)}</b></td>" if c.bold else f"<td>{e(c.text)}</td>" for c in cells)
        out.append(f"<tr><td>{e(label)}</td>{tds}</tr>")
    out.append("</table>")
    return "\n".join(out)
