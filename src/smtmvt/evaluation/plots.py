"""OTB-style success and precision plots (PNG + SVG), drawn off-screen.

Styling follows the OTB toolkit: titles "Success plots of OPE" / "Precision plots of OPE"
(with " - <attribute> (<n>)" for attribute subsets), x axes "Overlap threshold" /
"Location error threshold", legend sorted by score with the score in brackets. Published
curves (computed by the benchmark on its own sequence set) are drawn dashed and labelled with
their benchmark, e.g. ``SCM [0.498, OTB-2013 published]``.

Figures are built with ``matplotlib.figure.Figure`` directly (Agg canvas for PNG), so no
display and no global pyplot state are involved.
"""

from __future__ import annotations

import io
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..data import write_bytes_atomic
from .metrics import PRECISION_THRESHOLDS, SUCCESS_THRESHOLDS

__all__ = ["Curve", "select_curves", "plot_curves", "render_curves", "TITLES"]

TITLES = {
    "success": ("Success plots of OPE", "Overlap threshold", "Success rate"),
    "precision": ("Precision plots of OPE", "Location error threshold", "Precision"),
}  # "OPE" becomes the protocol's name (TRE, SRE) in their reports

# MATLAB toolkit's plotDrawStyle colours (first ten), then matplotlib's cycle
_COLORS = [
    "#ff0000",
    "#00ff00",
    "#0000ff",
    "#000000",
    "#ff00ff",
    "#00ffff",
    "#888888",
    "#884400",
    "#880088",
    "#ff8800",
    "#1f77b4",
    "#2ca02c",
    "#d62728",
    "#9467bd",
    "#8c564b",
]
_PUBLISHED_COLORS = [
    "#7f7f7f",
    "#bcbd22",
    "#17becf",
    "#8c564b",
    "#e377c2",
    "#9467bd",
    "#aec7e8",
    "#ffbb78",
    "#98df8a",
    "#c5b0d5",
]


@dataclass
class Curve:
    name: str
    values: np.ndarray
    score: float
    published: str | None = None  #: benchmark label (e.g. "OTB-2013") for published curves

    @property
    def label(self) -> str:
        if self.published:
            return f"{self.name} [{self.score:.3f}, {self.published} published]"
        return f"{self.name} [{self.score:.3f}]"


def select_curves(ours: Sequence[Curve], published: Sequence[Curve] = (), top: int = 10) -> list[Curve]:
    """Curves to draw, best first: our trackers (the best ``top`` of them), then the best
    published curves filling the legend up to ``top`` entries in all."""
    ours = sorted(ours, key=lambda c: -c.score)[: max(top, 0)]
    room = max(top - len(ours), 0)
    pub = sorted(published, key=lambda c: -c.score)[:room]
    return sorted(list(ours) + list(pub), key=lambda c: -c.score)


def plot_curves(
    kind: str,
    curves: Sequence[Curve],
    out_stem,
    subtitle: str | None = None,
    formats: Sequence[str] = ("png", "svg"),
    dpi: int = 120,
) -> list[Path]:
    """Draw ``curves`` (already selected) and save ``<out_stem>.<fmt>`` for each format,
    each atomically. ``kind`` is ``"success"`` or ``"precision"``. Returns the written paths."""
    out_stem = Path(out_stem)
    written = []
    for fmt, data in render_curves(kind, curves, subtitle, formats, dpi).items():
        written.append(write_bytes_atomic(out_stem.with_name(f"{out_stem.name}.{fmt}"), data))
    return written


def render_curves(
    kind: str,
    curves: Sequence[Curve],
    subtitle: str | None = None,
    formats: Sequence[str] = ("png", "svg"),
    dpi: int = 120,
    protocol: str = "ope",
) -> dict[str, bytes]:
    """The plot of ``curves`` as ``{format: file bytes}`` (nothing is written); ``protocol``
    names the evaluation in the title ("Success plots of TRE")."""
    import matplotlib

    fig = _figure(kind, curves, subtitle, protocol)
    out = {}
    # SVG text stays text (searchable, editable), not glyph outlines
    with matplotlib.rc_context({"svg.fonttype": "none", "svg.hashsalt": "smtmvt"}):
        for fmt in formats:
            buf = io.BytesIO()
            fig.savefig(buf, format=fmt, dpi=dpi, bbox_inches="tight")
            out[fmt] = buf.getvalue()
    return out


def _figure(kind: str, curves: Sequence[Curve], subtitle: str | None, protocol: str = "ope"):
    from matplotlib.figure import Figure

    if kind not in TITLES:
        raise ValueError(f"plot kind {kind!r}: expected 'success' or 'precision'")
    title, xlabel, ylabel = TITLES[kind]
    title = title.replace("OPE", protocol.upper())
    if subtitle:
        title = f"{title} - {subtitle}"
    x = SUCCESS_THRESHOLDS if kind == "success" else PRECISION_THRESHOLDS
    fig = Figure(figsize=(7.2, 4.8))
    ax = fig.add_subplot(1, 1, 1)
    i_ours = i_pub = 0
    for c in sorted(curves, key=lambda c: -c.score):
        y = np.asarray(c.values, dtype=float)
        if y.shape != x.shape:
            raise ValueError(f"curve {c.name!r}: {y.size} values, expected {x.size}")
        if c.published:
            color = _PUBLISHED_COLORS[i_pub % len(_PUBLISHED_COLORS)]
            i_pub += 1
            ax.plot(x, y, linestyle="--", linewidth=1.4, color=color, label=c.label)
        else:
            color = _COLORS[i_ours % len(_COLORS)]
            i_ours += 1
            ax.plot(x, y, linestyle="-", linewidth=2.2, color=color, label=c.label)
    ax.set_xlim(0, x.max())
    ax.set_ylim(0, 1)
    ax.set_title(title)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.grid(True, alpha=0.4)
    if curves:
        ax.legend(loc="center left", bbox_to_anchor=(1.01, 0.5), fontsize=8, frameon=False)
    fig.tight_layout()
    return fig
