"""The paper's table (smtmvt.evaluation.paper_table): its transcription against the paper's
LaTeX source, and the report's paper_table.md/.csv on a tiny real run."""

import re
from pathlib import Path

import pytest

from smtmvt.evaluation.paper_table import PAPER_SEQUENCES, load_paper_table

PAPER_TEX = Path(__file__).resolve().parents[1].parent / "shared" / "paper" / "smtmvt-icme2018.tex"


def _tex_row(tex: str, name: str) -> list[float]:
    found = re.search(r"\\textbf\{" + name + r"\}(.*?)\\\\", tex)
    assert found is not None, name
    return [float(re.findall(r"\d\.\d+", cell)[0]) for cell in found.group(1).split("&")[1:]]


def test_transcription_matches_the_tex():
    if not PAPER_TEX.is_file():
        pytest.skip(f"{PAPER_TEX.name} not found beside the project")
    tex = PAPER_TEX.read_text(encoding="utf-8")
    table = load_paper_table()
    assert table["source"]["label"] == "tab:cap" and "\\label{tab:cap}" in tex
    assert table["source"]["caption"].split(".")[0] in tex
    header = re.search(r"& \\textbf\{L1T\}.*?\\\\", tex).group(0)
    assert [m.replace(" ", "") for m in re.findall(r"\\textbf\{([^}]*)\}", header)] == table["methods"]
    for name in ("crossing", "carDark", "walking", "Average"):
        expected = table["average"] if name == "Average" else table["sequences"][name]
        assert _tex_row(tex, name) == expected, name
    assert set(table["sequences"]) == set(PAPER_SEQUENCES) and len(PAPER_SEQUENCES) == 15


def test_report_writes_the_paper_table(tmp_path, otb_dir, otb_results_dir):
    from smtmvt.cli import main

    data = tmp_path / "otb"
    data.mkdir()
    for seq in ("Crossing", "Girl"):
        (data / seq).symlink_to(otb_dir / seq)
    run = tmp_path / "run"
    argv = ["evaluate", "--dataset", str(data), "--trackers", "smtmvt-paper,opencv-kcf", "--out", str(run)]
    assert main([*argv, "--max-frames", "10"]) == 0
    assert main(["report", str(run), "--published", str(otb_results_dir), "--paper-table"]) == 0
    md = (run / "report" / "paper_table.md").read_text()
    rows = {tuple(c.strip() for c in line.split("|")[1:3]): line for line in md.splitlines() if line.startswith("| ")}
    ours = rows[("Crossing (crossing)", "SMTMVT")].split("|")[3].strip()
    assert re.fullmatch(r"0\.\d\d|1\.00", ours)  # our run's figure
    assert rows[("Crossing (crossing)", "SMTMVT")].split("|")[5].strip() == "0.78"  # the paper's
    ivt = [c.strip() for c in rows[("Crossing (crossing)", "IVT")].split("|")[3:6]]
    assert ivt[0] == "not in this run" and re.fullmatch(r"0\.\d\d", ivt[1]) and ivt[2] == "0.29"
    assert "no published OTB run" in rows[("Girl (girl)", "MTMVTLAD")]
    assert "no tracker of ours" in rows[("Girl (girl)", "VTD")]
    assert "david1" in md.split("not in this run:")[-1]
    csv = (run / "report" / "paper_table.csv").read_text().splitlines()
    assert csv[0] == "sequence,paper_name,method,ours,otb,paper" and len(csv) == 1 + 18 + 13


def test_csv_cells_cannot_run_as_formulas():
    from smtmvt.evaluation.paper_table import _csv

    row = dict(
        sequence="=HYPERLINK(1)", paper_name="girl", method="MIL", ours=0.5, otb="no published OTB run", paper=0.39
    )
    assert _csv([row], []).splitlines()[1].startswith("'=HYPERLINK(1),girl,MIL,0.500000,")
