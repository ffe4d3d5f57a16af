"""The library's layering: it never imports its command line, and the run folder's paths are
spelled once, in :mod:`smtmvt.evaluation.rundir`."""

import ast
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[1] / "src" / "smtmvt"
#: the command line: the entry point and the command layer
COMMAND_LINE = {SRC / "cli.py", *(SRC / "commands").glob("*.py")}
#: names of the run folder's files and folders, owned by RunDir ("report" is left out: it is
#: also the sub-command's name and an error's stage, spelled as such in many places)
RUN_FOLDER_NAMES = {
    "run.json",
    "errors.json",
    ".lock",
    "results",
    "table.md",
    "table.csv",
    "index.html",
    "summary.json",
}
#: (file, name) spelled for another reason: a MATLAB result file's variable; the demo's own
#: output folder (not a run folder)
NOT_RUN_PATHS = {("evaluation/published.py", "results"), ("commands/demo.py", "summary.json")}


def _imported_modules(path: Path) -> list[str]:
    """Absolute names of what ``path`` imports (relative imports resolved against its package)."""
    package = path.relative_to(SRC.parent).with_suffix("").parts[:-1]
    names = []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            names += [a.name for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = list(package[: len(package) - node.level + 1]) if node.level else []
            module = ".".join([*base, *(node.module.split(".") if node.module else [])])
            names += [module] + [f"{module}.{a.name}" for a in node.names]
    return names


@pytest.mark.parametrize("path", sorted(p for p in SRC.rglob("*.py") if p not in COMMAND_LINE), ids=str)
def test_the_library_never_imports_its_command_line(path):
    bad = [m for m in _imported_modules(path) if m == "smtmvt.commands" or m.startswith("smtmvt.commands.")]
    bad += [m for m in _imported_modules(path) if m == "smtmvt.cli"]
    assert not bad, f"{path.relative_to(SRC)} imports {bad}"


def test_the_import_check_sees_a_relative_import_of_the_commands():
    # the check above must be able to fail: evaluation/cli.py's old import resolves to the commands
    tree = "from ..commands.args import positive_int\n"
    fake = SRC / "evaluation" / "cli.py"
    package = fake.relative_to(SRC.parent).with_suffix("").parts[:-1]
    node = ast.parse(tree).body[0]
    assert isinstance(node, ast.ImportFrom)
    base = list(package[: len(package) - node.level + 1])
    assert ".".join([*base, *node.module.split(".")]) == "smtmvt.commands.args"


def _spelled_names(path: Path) -> set[str]:
    return {
        node.value
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8")))
        if isinstance(node, ast.Constant) and isinstance(node.value, str) and node.value in RUN_FOLDER_NAMES
    }


@pytest.mark.parametrize(
    "path",
    sorted(p for p in [*(SRC / "evaluation").glob("*.py"), *(SRC / "commands").glob("*.py")] if p.name != "rundir.py"),
    ids=str,
)
def test_run_folder_paths_are_spelled_only_by_rundir(path):
    rel = path.relative_to(SRC).as_posix()
    spelled = {name for name in _spelled_names(path) if (rel, name) not in NOT_RUN_PATHS}
    assert not spelled, f"{rel} spells {sorted(spelled)} itself; use RunDir's paths"


def test_rundir_spells_them():
    assert {"errors.json", "results", "table.md", "summary.json"} <= _spelled_names(SRC / "evaluation" / "rundir.py")
