"""The report of a run folder: numbers, tables, plots, index.html, bad result files."""

from __future__ import annotations

import json
import math
import re
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

from smtmvt.evaluation.report import build_report

# ----------------------------------------------------------------------------- independent scoring


def _iou(a, b):
    """IoU with inclusive pixel extents, written out per box (not the code under test)."""
    ax2, ay2 = a[0] + a[2] - 1, a[1] + a[3] - 1
    bx2, by2 = b[0] + b[2] - 1, b[1] + b[3] - 1
    iw = max(0.0, min(ax2, bx2) - max(a[0], b[0]) + 1)
    ih = max(0.0, min(ay2, by2) - max(a[1], b[1]) + 1)
    inter = iw * ih
    return inter / (a[2] * a[3] + b[2] * b[3] - inter)


def _err(a, b):
    return math.hypot(a[0] + (a[2] - 1) / 2 - b[0] - (b[2] - 1) / 2, a[1] + (a[3] - 1) / 2 - b[1] - (b[3] - 1) / 2)


def expected_scores(pred, gt):
    pred = [list(p) for p in pred]
    pred[0] = list(gt[0])
    ious = [_iou(p, g) for p, g in zip(pred, gt)]
    errs = [_err(p, g) for p, g in zip(pred, gt)]
    succ = [sum(i > t for i in ious) / len(ious) for t in [k * 0.05 for k in range(21)]]
    prec = [sum(e <= t for e in errs) / len(errs) for t in range(51)]
    return {
        "avg_overlap": sum(ious) / len(ious),
        "auc": sum(succ) / 21,
        "precision20": prec[20],
        "success": succ,
        "precision": prec,
    }


# ----------------------------------------------------------------------------- synthetic run


SEQS = {"SeqA": 10, "SeqB": 8, "SeqC": 6}
ATTRS = {"SeqA": "IV, OCC", "SeqB": "OCC", "SeqC": ""}


def _gt(n, k):
    return [[11 + 3 * i + k, 21 + 2 * i, 20 + k, 30] for i in range(n)]


def _shifted(gt, dx, every=1):
    return [[b[0] + (dx * (i % 3) if i % every == 0 else 0), b[1] + dx / 2, b[2], b[3]] for i, b in enumerate(gt)]


def _write(path: Path, rows, sep=","):
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text("".join(sep.join(f"{v:g}" for v in r) + "\n" for r in rows))


@pytest.fixture()
def run(tmp_path):
    import matplotlib.image

    ds = tmp_path / "otb"
    gts = {}
    for k, (name, n) in enumerate(SEQS.items()):
        gts[name] = _gt(n, k)
        _write(ds / name / "groundtruth_rect.txt", gts[name], sep="\t" if k == 1 else ",")
        (ds / name / "img").mkdir(parents=True)
        for i in range(n):
            matplotlib.image.imsave(ds / name / "img" / f"{i + 1:04d}.png", np.zeros((64, 96)), cmap="gray")
    (tmp_path / "attrs.txt").write_text("".join(f"{s}\t{a}\n" for s, a in ATTRS.items()))

    rd = tmp_path / "run"
    preds = {
        "alpha": {
            "SeqA": _shifted(gts["SeqA"], 4),
            "SeqB": _shifted(gts["SeqB"], 12),
            "SeqC": _shifted(gts["SeqC"], 2),
        },
        "beta": {
            "SeqA": _shifted(gts["SeqA"], 9, 2),
            "SeqB": _shifted(gts["SeqB"], 3),
            "SeqC": _shifted(gts["SeqC"], 1)[:5],
        },
    }
    for t, by_seq in preds.items():
        for s, rows in by_seq.items():
            _write(rd / "results" / t / f"{s}.txt", rows)
    for s, n in SEQS.items():  # alpha: 0.02 s per frame -> 50 fps; beta: no times
        _write(rd / "results" / "alpha" / "times" / f"{s}_time.txt", [[0.02]] * n)
    (rd / "run.json").write_text(
        json.dumps(
            {
                "dataset": str(ds),
                "trackers": ["alpha", "beta", "gamma"],
                "sequences": list(SEQS),
                "attributes": str(tmp_path / "attrs.txt"),
                "published": None,
            }
        )
    )
    (rd / "errors.json").write_text(
        json.dumps([{"tracker": "gamma", "sequence": None, "error": "unknown tracker 'gamma'"}])
    )
    return {"dir": rd, "gts": gts, "preds": preds, "tmp": tmp_path}


def test_summary_numbers(run):
    s = build_report(run["dir"], formats=("png",))
    on_disk = json.loads((run["dir"] / "report" / "summary.json").read_text())
    assert on_disk["trackers"]["alpha"]["auc"] == s["trackers"]["alpha"]["auc"]
    for t in ("alpha", "beta"):
        exp_seq = {}
        for seq, rows in run["preds"][t].items():
            if len(rows) != SEQS[seq]:
                continue
            e = expected_scores(rows, run["gts"][seq])
            got = on_disk["trackers"][t]["sequences"][seq]
            for key in ("avg_overlap", "auc", "precision20"):
                assert got[key] == pytest.approx(e[key], abs=1e-12), (t, seq, key)
            exp_seq[seq] = e
        tr = on_disk["trackers"][t]
        assert set(tr["sequences"]) == set(exp_seq)
        mean_succ = np.mean([e["success"] for e in exp_seq.values()], axis=0)
        mean_prec = np.mean([e["precision"] for e in exp_seq.values()], axis=0)
        assert tr["auc"] == pytest.approx(mean_succ.mean(), abs=1e-12)
        assert tr["precision20"] == pytest.approx(mean_prec[20], abs=1e-12)
        np.testing.assert_allclose(tr["success"], mean_succ, atol=1e-12)
    # a non-trivial case: the two trackers differ and are not perfect
    assert (
        0.2 < on_disk["trackers"]["beta"]["auc"] < on_disk["trackers"]["alpha"]["auc"] < 0.95
        or 0.2 < on_disk["trackers"]["alpha"]["auc"] < on_disk["trackers"]["beta"]["auc"] < 0.95
    )
    # fps: frames / total time
    assert on_disk["trackers"]["alpha"]["sequences"]["SeqA"]["fps"] == pytest.approx(50.0)
    assert on_disk["trackers"]["alpha"]["fps"] == pytest.approx(50.0)
    assert on_disk["trackers"]["beta"]["sequences"]["SeqA"]["fps"] is None
    # attributes: IV = {SeqA}, OCC = {SeqA, SeqB}
    assert on_disk["attributes"] == {
        "IV": {"name": "Illumination Variation", "sequences": ["SeqA"]},
        "OCC": {"name": "Occlusion", "sequences": ["SeqA", "SeqB"]},
    }
    occ = on_disk["trackers"]["alpha"]["attributes"]["OCC"]
    e_a = expected_scores(run["preds"]["alpha"]["SeqA"], run["gts"]["SeqA"])
    e_b = expected_scores(run["preds"]["alpha"]["SeqB"], run["gts"]["SeqB"])
    assert occ["auc"] == pytest.approx((e_a["auc"] + e_b["auc"]) / 2, abs=1e-12)
    assert occ["n_sequences"] == 2
    assert on_disk["published"] is None


def test_short_result_file_is_an_error_and_the_rest_is_reported(run):
    s = build_report(run["dir"], formats=("png",))
    beta = s["trackers"]["beta"]
    assert set(beta["sequences"]) == {"SeqA", "SeqB"} and beta["auc"] is not None
    msg = beta["errors"]["SeqC"]
    assert "results/beta/SeqC.txt" in msg and "shorter" in msg and "5 lines" in msg and "6 frames" in msg
    assert any(e["tracker"] == "beta" and e["sequence"] == "SeqC" and e["stage"] == "report" for e in s["errors"])
    # the runner's errors are carried over
    assert any(e["tracker"] == "gamma" and e["stage"] == "run" and "unknown tracker" in e["error"] for e in s["errors"])
    assert s["trackers"]["gamma"]["auc"] is None
    html = (run["dir"] / "report" / "index.html").read_text()
    assert "results/beta/SeqC.txt" in html and "unknown tracker" in html
    md = (run["dir"] / "report" / "table.md").read_text()
    row = next(l for l in md.splitlines() if l.startswith("| SeqC |"))
    assert row.split("|")[3].strip() == "error"
    assert "results/beta/SeqC.txt" in md

    # a malformed line names the file and the line
    (run["dir"] / "results" / "alpha" / "SeqB.txt").write_text("1,2,3,4\n1,2,oops,4\n" + "1,2,3,4\n" * 6)
    s2 = build_report(run["dir"], formats=("png",))
    assert "results/alpha/SeqB.txt, line 2" in s2["trackers"]["alpha"]["errors"]["SeqB"]
    assert set(s2["trackers"]["alpha"]["sequences"]) == {"SeqA", "SeqC"}


def test_table_bolds_best_per_row(run):
    s = build_report(run["dir"], formats=("png",))
    md = (run["dir"] / "report" / "table.md").read_text()
    lines = md.splitlines()
    header = next(l for l in lines if l.startswith("| Sequence |"))
    cols = [c.strip() for c in header.strip("|").split("|")][1:]
    assert cols == ["alpha", "beta", "gamma"]
    checked = 0
    for seq in SEQS:
        row = next(l for l in lines if l.startswith(f"| {seq} |"))
        cells = [c.strip() for c in row.strip("|").split("|")][1:]
        vals = {t: s["trackers"][t]["sequences"].get(seq, {}).get("avg_overlap") for t in cols}
        best = max(round(v, 2) for v in vals.values() if v is not None)
        for t, c in zip(cols, cells):
            v = vals[t]
            if v is None:
                assert c == "error"
            elif round(v, 2) == best:
                assert c == f"**{v:.2f}**", (seq, t, c)
                checked += 1
            else:
                assert c == f"{v:.2f}", (seq, t, c)
    assert checked >= 3
    csv_lines = (run["dir"] / "report" / "table.csv").read_text().splitlines()
    assert csv_lines[0] == "sequence,alpha,beta,gamma"
    a_row = next(l for l in csv_lines if l.startswith("SeqA,")).split(",")
    assert float(a_row[1]) == pytest.approx(s["trackers"]["alpha"]["sequences"]["SeqA"]["avg_overlap"], abs=1e-6)
    assert next(l for l in csv_lines if l.startswith("SeqC,")).split(",")[2] == ""


def test_plots_and_index(run):
    build_report(run["dir"])
    rep = run["dir"] / "report"
    import matplotlib.image

    expected = [f"{k}{suffix}" for k in ("success", "precision") for suffix in ("", "_IV", "_OCC")]
    for stem in expected:
        png, svg = rep / f"{stem}.png", rep / f"{stem}.svg"
        assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
        img = matplotlib.image.imread(png)
        assert img.shape[0] > 100 and img.shape[1] > 100 and img.std() > 0
        root = ET.parse(svg).getroot()
        assert root.tag.endswith("svg")
    # attributes no sequence has get no plot
    plotted = {p.stem for p in rep.glob("*.png")}
    assert plotted == set(expected)
    # styling: titles, axes, legend sorted by score with the score in brackets
    svg_text = (rep / "success.svg").read_text()
    assert "Success plots of OPE" in svg_text and "Overlap threshold" in svg_text
    labels = re.findall(r"(alpha|beta) \[(0\.\d{3})\]", svg_text)
    assert [t for t, _ in labels] == sorted({t for t, _ in labels}, key=lambda t: -float(dict(labels)[t]))
    assert "Precision plots of OPE" in (rep / "precision.svg").read_text()
    assert "Location error threshold" in (rep / "precision.svg").read_text()
    assert "Occlusion (2)" in (rep / "success_OCC.svg").read_text()
    # index.html shows every image
    html = (rep / "index.html").read_text()
    for f in list(rep.glob("*.png")) + list(rep.glob("*.svg")):
        assert f"'{f.name}'" in html, f.name
    for f in ("summary.json", "table.md", "table.csv"):
        assert f in html


def test_published_curves_are_labelled_and_kept_out_of_the_table(run):
    pub = run["tmp"] / "otb-results"
    curve = np.linspace(1, 0, 21)
    prec = np.linspace(0, 1, 51)
    for subset in ("ALL", "IV", "OCC"):
        d = pub / "OPE" / "FAKE" / "scores_cvpr13"
        d.mkdir(parents=True, exist_ok=True)
        (d / f"{subset}.json").write_text(
            json.dumps(
                {
                    "seqs": ["SeqA", "Other"],
                    "overlapScores": [0.9, 0.1],
                    "successRateList": curve.tolist(),
                    "precisionList": prec.tolist(),
                }
            )
        )
    s = build_report(run["dir"], published=pub, benchmark="cvpr13")
    assert s["published"]["trackers"]["FAKE"]["auc"] == pytest.approx(0.5)
    assert s["published"]["label"] == "OTB-2013"
    assert "FAKE" not in s["trackers"]
    rep = run["dir"] / "report"
    assert "FAKE" not in (rep / "table.md").read_text() and "FAKE" not in (rep / "table.csv").read_text()
    assert "FAKE [0.500, OTB-2013 published]" in (rep / "success.svg").read_text()
    assert "FAKE [0.400, OTB-2013 published]" in (rep / "precision_IV.svg").read_text()
    # top=2: our two scored trackers fill the legend, no published curve
    build_report(run["dir"], published=pub, benchmark="cvpr13", top=2, formats=("svg",))
    assert "FAKE" not in (rep / "success.svg").read_text()


def test_max_frames_run_is_scored_on_its_frames_and_flagged(run):
    rd = run["dir"]
    meta = json.loads((rd / "run.json").read_text())
    meta["max_frames"] = 4
    (rd / "run.json").write_text(json.dumps(meta))
    for t in ("alpha", "beta"):
        for seq in SEQS:
            _write(rd / "results" / t / f"{seq}.txt", run["preds"][t][seq][:4])
    s = build_report(rd, formats=("png",))
    e = expected_scores(run["preds"]["beta"]["SeqC"][:4], run["gts"]["SeqC"][:4])
    assert s["trackers"]["beta"]["sequences"]["SeqC"]["auc"] == pytest.approx(e["auc"], abs=1e-12)
    assert s["settings"]["max_frames"] == 4
    assert "not OTB-compliant" in (rd / "report" / "index.html").read_text()


def test_report_rebuilds_from_stored_results_only(run):
    first = build_report(run["dir"], formats=("png",))
    second = build_report(run["dir"], formats=("png",))
    assert first["trackers"] == second["trackers"]
    with pytest.raises(FileNotFoundError):
        build_report(run["tmp"] / "nope")


def test_imported_mat_results_scored_on_our_sequences(otb_dir, otb_results_dir, tmp_path):
    """Import the toolkit's CSK .mat files into a run: they are scored by our metrics on our
    sequences (table) and reproduce the published OTB-100 per-sequence overlaps."""
    from smtmvt.evaluation.imports import import_into_run
    from smtmvt.evaluation.published import load_published_scores

    rd = tmp_path / "run"
    rd.mkdir()
    (rd / "run.json").write_text(json.dumps({"dataset": str(otb_dir), "sequences": ["Crossing", "Girl"]}))
    # only the run's sequences (run.json), in the run's spelling
    assert import_into_run(rd, otb_results_dir / "OPE-OTB100-mat", trackers=["CSK"]) == {"CSK": ["Crossing", "Girl"]}
    s = build_report(rd, published=otb_results_dir, formats=("png",), top=4)
    pub = load_published_scores(otb_results_dir, "tb100", trackers=["CSK"])["CSK"]["sequences"]
    for seq, name in (("Crossing", "Crossing"), ("Girl", "Girl")):
        assert s["trackers"]["CSK"]["sequences"][seq]["avg_overlap"] == pytest.approx(pub[name], abs=1e-9)
        assert s["trackers"]["CSK"]["sequences"][seq]["fps"] > 0  # from the .mat's fps
    assert "CSK" in (rd / "report" / "table.md").read_text()
    assert set(s["attributes"]) >= {"SV", "DEF", "OCC"}
    assert s["published"]["label"] == "OTB-100" and len(s["published"]["trackers"]) == 34


# ----------------------------------------------------------------------------- issue 8: writes nowhere else


def test_report_on_a_folder_that_is_not_a_run_creates_nothing(tmp_path, capsys):
    from smtmvt.cli import main

    folder = tmp_path / "photos"
    folder.mkdir()
    (folder / "a.jpg").write_bytes(b"x")
    assert main(["report", str(folder)]) == 2
    assert "not a run folder" in capsys.readouterr().err
    assert [p.name for p in folder.iterdir()] == ["a.jpg"]
    with pytest.raises(ValueError, match="not a run folder"):
        build_report(folder)
    assert [p.name for p in folder.iterdir()] == ["a.jpg"]


def test_a_link_in_the_report_folder_is_replaced_not_written_through(run):
    build_report(run["dir"], formats=("png",))
    outside = run["tmp"] / "my-paper-table.md"
    outside.write_text("my own table")
    table = run["dir"] / "report" / "table.md"
    table.unlink()
    table.symlink_to(outside)
    build_report(run["dir"], formats=("png",))
    assert outside.read_text() == "my own table"
    assert not table.is_symlink() and "Average overlap per sequence" in table.read_text()


def test_a_pipe_in_a_sequence_name_keeps_the_markdown_table_whole(run):
    import matplotlib.image

    ds = Path(json.loads((run["dir"] / "run.json").read_text())["dataset"])
    name = "Left|Right"
    gt = _gt(5, 0)
    _write(ds / name / "groundtruth_rect.txt", gt)
    (ds / name / "img").mkdir()
    for i in range(5):
        matplotlib.image.imsave(ds / name / "img" / f"{i + 1:04d}.png", np.zeros((64, 96)), cmap="gray")
    _write(run["dir"] / "results" / "alpha" / f"{name}.txt", _shifted(gt, 3))
    meta = json.loads((run["dir"] / "run.json").read_text())
    meta["sequences"].append(name)
    (run["dir"] / "run.json").write_text(json.dumps(meta))
    s = build_report(run["dir"], formats=("png",))
    assert name in s["trackers"]["alpha"]["sequences"]
    md = (run["dir"] / "report" / "table.md").read_text()
    rows = [line for line in md.splitlines() if line.startswith("| ")]
    for line in rows:  # every row has the header's number of columns
        assert len(re.findall(r"(?<!\\)\|", line)) == 5, line
    assert any(line.startswith("| Left\\|Right | ") for line in rows)
    assert "<td>Left|Right</td>" in (run["dir"] / "report" / "index.html").read_text()


def test_our_result_files_are_read_strictly(run):
    """A blank line in the middle of a result file would shift every later box by a frame:
    our own files are read by the strict reader, which names the line."""
    rows = run["preds"]["alpha"]["SeqC"]
    path = run["dir"] / "results" / "alpha" / "SeqC.txt"
    path.write_text(
        "".join(",".join(f"{v:g}" for v in r) + "\n" + ("\n" if i == 1 else "") for i, r in enumerate(rows))
    )
    s = build_report(run["dir"], formats=("png",))
    assert "SeqC" not in s["trackers"]["alpha"]["sequences"]
    assert "results/alpha/SeqC.txt, line 3: blank line" in s["trackers"]["alpha"]["errors"]["SeqC"]


# ----------------------------------------------------------------------------- issue 46: formula injection


def _add_sequence(run, name: str, n: int = 5) -> None:
    """A sequence ``name`` in the run's dataset and ``run.json``, with a result of alpha."""
    import matplotlib.image

    ds = Path(json.loads((run["dir"] / "run.json").read_text())["dataset"])
    gt = _gt(n, 0)
    _write(ds / name / "groundtruth_rect.txt", gt)
    (ds / name / "img").mkdir()
    for i in range(n):
        matplotlib.image.imsave(ds / name / "img" / f"{i + 1:04d}.png", np.zeros((64, 96)), cmap="gray")
    _write(run["dir"] / "results" / "alpha" / f"{name}.txt", _shifted(gt, 3))
    meta = json.loads((run["dir"] / "run.json").read_text())
    meta["sequences"].append(name)
    (run["dir"] / "run.json").write_text(json.dumps(meta))


FORMULAS = ['=HYPERLINK("http:x","y")', "+1+1", "@SUM(1)", "-2+3", "\t=1+2", "\r=3+4"]


def test_csv_cells_a_spreadsheet_would_run_as_formulas_are_escaped(run):
    """OWASP's advice on CSV injection: a text cell starting with = + - @, tab or carriage
    return gets a leading quote; names that are plain text or plain numbers are kept."""
    import csv

    for name in [*FORMULAS, "-1", "Plain"]:
        _add_sequence(run, name)
    s = build_report(run["dir"], formats=("png",))
    with open(run["dir"] / "report" / "table.csv", encoding="utf-8", newline="") as fh:
        rows = list(csv.reader(fh))
    first = {r[0]: r for r in rows if r}
    for name in FORMULAS:
        assert "'" + name in first and name not in first, name
        got = float(first["'" + name][1])
        assert got == pytest.approx(s["trackers"]["alpha"]["sequences"][name]["avg_overlap"], abs=1e-6)
    assert "-1" in first and "Plain" in first and "SeqA" in first
    assert rows[0][:2] == ["sequence", "alpha"]


def test_csv_numbers_stay_numbers_even_when_negative(run):
    from smtmvt.evaluation.scoring import Summary
    from smtmvt.evaluation.tables import csv_table

    s = build_report(run["dir"], formats=("png",))
    summary = Summary(**s)
    summary.trackers["alpha"]["avg_overlap"] = -0.5
    summary.trackers["alpha"]["sequences"]["SeqA"]["avg_overlap"] = -0.25
    lines = csv_table(summary).splitlines()
    assert next(line for line in lines if line.startswith("average,")).split(",")[1] == "-0.500000"
    assert next(line for line in lines if line.startswith("SeqA,")).split(",")[1] == "-0.250000"


# ----------------------------------------------------------------------------- issue 46: the collision's own message


def test_a_name_collision_is_reported_as_one_not_as_missing_ground_truth(run):
    for name in ("Seq_1", "Seq-1"):
        _add_sequence(run, name)
    s = build_report(run["dir"], formats=("png",))
    (row,) = [seq for seq in s["table_sequences"] if seq in ("Seq_1", "Seq-1")]  # one row: the names match
    message = s["trackers"]["alpha"]["errors"][row]
    assert "name collision: sequences 'Seq-1' and 'Seq_1' differ only in case or separators" in message
    assert "rename one" in message and "no ground truth" not in message
    md = (run["dir"] / "report" / "table.md").read_text()
    assert f"- alpha / {row}: " in md and "no ground truth" not in md
