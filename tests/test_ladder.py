"""bench/ladder.py: the ladder starts at the paper's tracker, ends at the default, and its
table reads each step's figures from an evaluation's summary."""

import importlib.util
import json
from pathlib import Path

import pytest

from smtmvt import TrackerConfig

_BENCH = Path(__file__).resolve().parents[1] / "bench"
_spec = importlib.util.spec_from_file_location("ladder", _BENCH / "ladder.py")
assert _spec is not None and _spec.loader is not None
ladder = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(ladder)


def test_the_ladder_starts_at_the_paper_and_ends_at_the_default():
    options = ladder.ladder_options()
    assert len(options) == len(ladder.STEPS)
    assert options[0] == {}
    assert TrackerConfig.paper(**options[-1]) == TrackerConfig().replace(seed=TrackerConfig.paper().seed)
    # each step adds to the one before and changes something
    for before, after in zip(options, options[1:]):
        assert set(before) < set(after)
        assert all(after[k] == v for k, v in before.items())


def test_a_departure_no_step_names_is_refused(monkeypatch):
    steps = [(name, tuple(f for f in fields if f != "velocity"), text) for name, fields, text in ladder.STEPS]
    monkeypatch.setattr(ladder, "STEPS", steps)
    with pytest.raises(ValueError, match="velocity"):
        ladder.ladder_options()


def _summary(per_seq: dict) -> dict:
    sequences = {s: {"avg_overlap": ao, "avg_overlap_std": sd} for s, (ao, sd) in per_seq.items()}
    return {"trackers": {ladder.TRACKER: {"sequences": sequences, "auc": 0.5, "fps": 12.0}}}


def test_step_figures_mean_over_sequences_and_halves():
    summary = _summary({"A": (0.2, 0.02), "B": (0.6, 0.04), "C": (0.7, 0.0)})
    fig = ladder.step_figures(summary, {"tune": ["A", "B"], "check": ["C", "D"]})
    assert fig["ao"] == pytest.approx(0.5)
    assert fig["spread"] == pytest.approx(0.02)
    assert fig["tune"] == pytest.approx(0.4)
    assert fig["check"] == pytest.approx(0.7)
    assert fig["n"] == 3
    assert ladder.step_figures(summary, None)["tune"] is None


def test_write_keeps_the_text_around_the_table(tmp_path):
    runs = tmp_path / "runs"
    for k, ao in ((0, 0.3), (2, 0.5)):
        report = ladder.step_dir(runs, k) / "report"
        report.mkdir(parents=True)
        (report / "summary.json").write_text(json.dumps(_summary({"A": (ao, 0.01)})))
    out = tmp_path / "reproduction.md"
    out.write_text("# intro\n\n<!-- ladder: begin -->\nold\n<!-- ladder: end -->\n\nafter\n")
    assert ladder.main(["write", "--runs", str(runs), "--out", str(out)]) == 0
    text = out.read_text()
    assert text.startswith("# intro") and text.rstrip().endswith("after")
    assert "old" not in text
    assert "| 0 paper |" in text and "| 2 scale-normalized |" in text and "frames-as-given" not in text
    assert "0.300" in text and "0.500" in text
    assert (tmp_path / "reproduction.png").stat().st_size > 0
