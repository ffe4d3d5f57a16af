"""A pair whose files cannot be written is an error of that pair; the rest run (issue 46, fault 6).

A legal sequence folder name close to the file system's name limit gives ``ENAMETOOLONG``
on the pair's times file (its temporary name is longer) or on its result file itself.
"""

from __future__ import annotations

import errno
import json
import os

from test_runner import evaluate_cli, make_otb_dataset


def test_a_pair_that_cannot_be_written_does_not_stop_the_run(tmp_path, capsys):
    name_max = os.pathconf(tmp_path, "PC_NAME_MAX")  # 255 on Linux and macOS
    temp_too_long = "M" + "x" * (name_max - 16)  # 240: <name>_time.txt fits, its temporary file does not
    result_too_long = "N" + "y" * (name_max - 4)  # 252: <name>.txt does not fit
    names = ["Alpha", temp_too_long, result_too_long, "Zulu"]
    spec = dict(start=(30, 40), step=(2.0, 1.0), side=(28, 24))
    dataset = make_otb_dataset(tmp_path / "otb", specs=dict.fromkeys(names, spec), n_frames=6)
    run_dir = tmp_path / "run"
    for attempt in range(2):  # the first run, then a resumed one
        rc = evaluate_cli(dataset, run_dir, "--trackers", "opencv-kcf", "--quiet")
        out, err = capsys.readouterr()
        assert rc == 1, err
        errors = {e["sequence"]: e["error"] for e in json.loads((run_dir / "errors.json").read_text())}
        assert sorted(errors) == sorted([temp_too_long, result_too_long])
        for name, message in errors.items():
            assert message.startswith(f"opencv-kcf on {name}: cannot ")
            assert f"[Errno {errno.ENAMETOOLONG}]" in message
        results = sorted(p.name for p in (run_dir / "results" / "opencv-kcf").glob("*.txt"))
        assert results == ["Alpha.txt", "Zulu.txt"]  # sorted before and after the long names
        assert ("2 pair(s) run" if attempt == 0 else "2 already done") in out
        assert "(2 sequences)" in out and (run_dir / "report" / "table.md").is_file()  # the report is built
