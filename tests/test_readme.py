"""The README's Layout table names every module of the package, so it matches the tree."""

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "src" / "smtmvt"


def _layout_section() -> str:
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    start = text.index("## Layout")
    end = text.index("\n## ", start + 1)
    return text[start:end]


def _named(section: str) -> set[str]:
    """Every module (`name.py`) and package (`name/`) the table's rows name, a path's parts each."""
    named = set()
    for row in (line for line in section.splitlines() if line.startswith("|")):
        for token in re.findall(r"`([\w/.]+)`", row):
            parts = token.split("/")
            named |= {part + "/" for part in parts[:-1]} | ({parts[-1]} if parts[-1] else set())
    return {name for name in named if name.endswith((".py", "/"))}


def test_every_module_and_subpackage_is_in_the_layout_table():
    named = _named(_layout_section())
    modules = {p.name for p in PACKAGE.glob("*.py") if p.name != "__init__.py"}
    packages = {p.name + "/" for p in PACKAGE.iterdir() if (p / "__init__.py").is_file()}
    evaluation = {p.name for p in (PACKAGE / "evaluation").glob("*.py") if p.name != "__init__.py"}
    missing = sorted((modules | packages | evaluation) - named)
    assert not missing, f"README's Layout table does not name {missing}"


def test_the_layout_table_names_no_module_that_is_not_there():
    named = _named(_layout_section())
    present = {p.name for p in PACKAGE.rglob("*.py")} | {p.name + "/" for p in PACKAGE.rglob("*") if p.is_dir()}
    assert not sorted(named - present), f"README's Layout table names {sorted(named - present)}"
