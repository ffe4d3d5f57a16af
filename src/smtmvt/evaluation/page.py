"""``index.html`` of a report: settings, the table, every plot and the errors (all escaped).

One page per protocol (``report/index.html`` for OPE, ``report/tre/index.html``, ...); the
top page links the others and shows each tracker's AUC and precision under each protocol.
"""

from __future__ import annotations

import html

from .protocols import PROTOCOL_TITLES
from .scoring import Summary
from .tables import html_table, protocols_html

__all__ = ["index_html"]

_STYLE = (
    "<style>body{font-family:sans-serif;margin:2em;max-width:1400px}table{border-collapse:collapse}"
    "td,th{border:1px solid #bbb;padding:3px 8px;text-align:right}td:first-child,th:first-child{text-align:left}"
    ".plots{display:flex;flex-wrap:wrap;gap:1em}.plots figure{margin:0}.plots img{max-width:640px}"
    ".err{color:#a00}</style>"
)


def index_html(summary: Summary) -> str:
    """The report page; links the files named in ``summary.plots``."""
    e = html.escape
    s = summary.settings
    parts = [
        "<!DOCTYPE html>",
        f"<html><head><meta charset='utf-8'><title>OTB evaluation report</title>{_STYLE}</head><body>",
        f"<h1>{e(PROTOCOL_TITLES[summary.protocol] if summary.trackers else 'OTB evaluation')}</h1>",
        f"<p>Run: <code>{e(s['run_dir'])}</code><br>Dataset: <code>{e(s['dataset'])}</code><br>"
        f"Invalid ground-truth rule: <code>{e(s['invalid'])}</code>. {e(s['protocol'])}.</p>",
    ]
    if s.get("max_frames"):
        parts.append(
            f"<p class='err'>Sequences were cut to {int(s['max_frames'])} frames (max_frames): "
            "these numbers are not OTB-compliant.</p>"
        )
    if int(s.get("repeat") or 1) > 1:
        parts.append(
            f"<p>Stochastic trackers were run {int(s['repeat'])} times per sequence with different seeds: "
            "numbers are means over the repeats, ± their sample standard deviation.</p>"
        )
    parts += _protocol_section(summary)
    if summary.trackers or not summary.protocols:
        parts.append(
            "<p>Files: <a href='summary.json'>summary.json</a>, <a href='table.md'>table.md</a>, "
            "<a href='table.csv'>table.csv</a></p>"
        )
        parts += ["<h2>Average overlap per sequence</h2>", html_table(summary)]
        if summary.published:
            pub = summary.published
            parts.append(f"<p>Dashed curves: {e(pub['note'])} (<code>{e(pub['source'])}</code>).</p>")
        parts += _plot_sections(summary)
    parts += _error_list(summary)
    parts.append("</body></html>")
    return "\n".join(parts) + "\n"


def _protocol_section(summary: Summary) -> list[str]:
    """Links to the TRE / SRE pages and the AUC of every protocol (top page only)."""
    if not summary.protocols:
        return []
    links = ", ".join(f"<a href='{p}/index.html'>{p.upper()}</a>" for p in summary.protocols)
    return ["<h2>Protocols</h2>", f"<p>Full reports: {links}.</p>", protocols_html(summary)]


def _figures(summary: Summary, subset: str) -> str:
    e = html.escape
    items = []
    for p in (p for p in summary.plots if p["subset"] == subset):
        first = next((f for f in p["files"] if f.endswith(".png")), p["files"][0])
        links = " ".join(f"<a href='{e(f)}'>{e(f.rsplit('.', 1)[1].upper())}</a>" for f in p["files"])
        if first.endswith(".png"):
            img = f"<img src='{e(first)}' alt='{e(p['kind'])} {e(subset)}'>"
        else:
            img = f"<object data='{e(first)}' type='image/svg+xml'></object>"
        items.append(f"<figure>{img}<figcaption>{links}</figcaption></figure>")
    return "<div class='plots'>" + "".join(items) + "</div>"


def _plot_sections(summary: Summary) -> list[str]:
    e = html.escape
    if not summary.plots:
        return ["<p class='err'>No tracker has a usable result: no plots.</p>"]
    parts = [f"<h2>All sequences ({len(summary.sequences)})</h2>", _figures(summary, "ALL")]
    for a, info in summary.attributes.items():
        parts.append(f"<h2>{e(a)}: {e(info['name'])} ({len(info['sequences'])} sequences)</h2>")
        parts.append(f"<p>{e(', '.join(info['sequences']))}</p>")
        parts.append(_figures(summary, a))
    return parts


def _error_list(summary: Summary) -> list[str]:
    e = html.escape
    if not summary.errors:
        return []
    parts = [f"<h2 class='err'>Errors ({len(summary.errors)})</h2><ul>"]
    for err in summary.errors:
        who = " / ".join(x for x in (err.get("protocol", "").upper(), err.get("tracker"), err.get("sequence")) if x)
        parts.append(
            f"<li><b>{e(who or 'general')}</b> [{e(err.get('stage', ''))}]: <code>{e(err['error'])}</code></li>"
        )
    parts.append("</ul>")
    return parts
