"""``evaluate --repeat N``: N seeds per stochastic tracker, mean ± std in the report (issue 6)."""

from __future__ import annotations

import json

import numpy as np
import pytest

from smtmvt.cli import main
from smtmvt.data import open_otb_sequence, read_boxes
from smtmvt.evaluation import register_tracker, run_evaluation, sequence_seed, unregister_tracker
from smtmvt.evaluation.metrics import aggregate, score_sequence
from test_runner import evaluate_cli, make_otb_dataset

SEQS = ["SquareA", "SquareB"]


class Jitter:
    """A stochastic toy tracker: the square's true step plus noise drawn from its seed."""

    seeds: list = []

    def __init__(self, seed=None):
        self.seed = seed
        self.rng = np.random.default_rng(seed)

    def init(self, frame, box):
        Jitter.seeds.append(self.seed)
        self.box = np.array(box, float)

    def update(self, frame):
        self.box[:2] += np.array([2.0, 1.0]) + self.rng.normal(0, 1.5, 2)
        return tuple(self.box)


@pytest.fixture(scope="module")
def dataset(tmp_path_factory):
    return make_otb_dataset(tmp_path_factory.mktemp("otb"), n_frames=15)


@pytest.fixture
def jitter():
    register_tracker("test-jitter", Jitter, replace=True)
    Jitter.seeds.clear()
    yield "test-jitter"
    unregister_tracker("test-jitter")


def _run(dataset, run_dir, **kw):
    return run_evaluation(dataset, ["test-jitter", "opencv-kcf"], run_dir, sequences=SEQS, progress=False, **kw)


def test_each_repeat_has_its_seed_and_its_folder(dataset, tmp_path, jitter):
    run_dir = tmp_path / "run"
    run = _run(dataset, run_dir, repeat=3, report=False)
    assert run.ok and len(run.done) == 2 * 3 + 2  # kcf is deterministic: once
    assert sorted(Jitter.seeds) == sorted(sequence_seed(s, 0, r) for s in SEQS for r in range(3))
    texts = {}
    for r in range(3):
        sub = "" if r == 0 else f"repeat-{r}/"
        for s in SEQS:
            path = run_dir / "results" / "test-jitter" / f"{sub}{s}.txt"
            assert len(path.read_text().splitlines()) == 15
            assert (run_dir / "results" / "test-jitter" / f"{sub}times" / f"{s}_time.txt").is_file()
            texts[r, s] = path.read_text()
    assert len(set(texts.values())) == 6  # every repeat tracked differently
    assert not (run_dir / "results" / "opencv-kcf" / "repeat-1").exists()
    assert json.loads((run_dir / "run.json").read_text())["repeat"] == 3


def test_repeats_resume_per_pair_grow_and_shrink(dataset, tmp_path, jitter):
    run_dir = tmp_path / "run"
    _run(dataset, run_dir, repeat=2, report=False)
    kept = (run_dir / "results" / "test-jitter" / "repeat-1" / "SquareB.txt").read_text()
    (run_dir / "results" / "test-jitter" / "repeat-1" / "SquareB.txt").unlink()
    run = _run(dataset, run_dir, report=False)  # no --repeat: the folder's count
    assert run.done == [("test-jitter", "SquareB", 1)] and len(run.skipped) == 5
    assert (run_dir / "results" / "test-jitter" / "repeat-1" / "SquareB.txt").read_text() == kept
    run = _run(dataset, run_dir, repeat=3, report=False)  # a larger count adds repeats
    assert sorted(run.done) == [("test-jitter", s, 2) for s in SEQS]
    run = _run(dataset, run_dir, repeat=2)  # a smaller one uses the first ones
    assert run.done == [] and any("holds 3 repeats; this command uses the first 2" in n for n in run.notes)
    assert run.report["settings"]["repeat"] == 2 and run.report["trackers"]["test-jitter"]["n_runs"] == 2
    assert json.loads((run_dir / "run.json").read_text())["repeat"] == 3


def test_report_gives_mean_and_spread_over_repeats(dataset, tmp_path, jitter):
    run_dir = tmp_path / "run"
    run = _run(dataset, run_dir, repeat=3)
    s = run.report
    gts = {q: open_otb_sequence(dataset / q).groundtruth for q in SEQS}
    scores = {
        (r, q): score_sequence(read_boxes(run_dir / "results" / "test-jitter" / (f"repeat-{r}/" if r else "")
                                          / f"{q}.txt"), gts[q])
        for r in range(3) for q in SEQS
    }  # fmt: skip
    jit = s["trackers"]["test-jitter"]
    for q in SEQS:
        ov = [scores[r, q].avg_overlap for r in range(3)]
        auc = [scores[r, q].auc for r in range(3)]
        assert jit["sequences"][q]["avg_overlap"] == pytest.approx(np.mean(ov), abs=1e-12)
        assert jit["sequences"][q]["avg_overlap_std"] == pytest.approx(np.std(ov, ddof=1), abs=1e-12)
        assert jit["sequences"][q]["auc_std"] == pytest.approx(np.std(auc, ddof=1), abs=1e-12)
        assert jit["sequences"][q]["avg_overlap_std"] > 0.005  # the seeds do matter
    per_run = [aggregate([scores[r, q] for q in SEQS]).auc for r in range(3)]
    assert jit["auc"] == pytest.approx(np.mean(per_run), abs=1e-12)
    assert jit["auc_std"] == pytest.approx(np.std(per_run, ddof=1), abs=1e-12)
    overall = [np.mean([scores[r, q].avg_overlap for q in SEQS]) for r in range(3)]
    assert jit["avg_overlap_std"] == pytest.approx(np.std(overall, ddof=1), abs=1e-12)
    kcf = s["trackers"]["opencv-kcf"]
    assert (kcf["n_runs"], kcf["deterministic"], kcf["auc_std"], kcf["avg_overlap_std"]) == (1, True, 0.0, 0.0)
    md = (run_dir / "report" / "table.md").read_text()
    row = next(line for line in md.splitlines() if line.startswith("| SquareA |"))
    cell = f"{jit['sequences']['SquareA']['avg_overlap']:.2f} ± {jit['sequences']['SquareA']['avg_overlap_std']:.2f}"
    assert cell in row and " ± 0.00" in row
    header = (run_dir / "report" / "table.csv").read_text().splitlines()[0]
    assert header == "sequence,test-jitter,test-jitter_std,opencv-kcf,opencv-kcf_std"


def test_one_repeat_reports_as_before(dataset, tmp_path, jitter):
    run = _run(dataset, tmp_path / "run")
    jit = run.report["trackers"]["test-jitter"]
    assert jit["n_runs"] == 1 and jit["auc_std"] is None  # one seed: spread unknown
    md = (tmp_path / "run" / "report" / "table.md").read_text()
    assert "±" not in md


def test_cli_repeat(dataset, tmp_path, capsys):
    run_dir = tmp_path / "run"
    assert (
        evaluate_cli(dataset, run_dir, "--trackers", "opencv-kcf", "--sequences", "SquareA", "--repeat", "2", "--quiet")
        == 0
    )
    assert json.loads((run_dir / "run.json").read_text())["repeat"] == 2
    assert main(["report", str(run_dir), "--repeat", "3"]) == 2
    assert "holds 2 repeat(s)" in capsys.readouterr().err
