"""Shared test fixtures.

Real OTB data lives in ``../shared/data`` beside the project root (present in CI,
absent in a user's clone). Tests that need it use the fixtures below, which skip
with a clear reason when it is missing.
"""

from pathlib import Path

import pytest

PROJECT_ROOT = Path(__file__).resolve().parents[1]
SHARED_DATA = (PROJECT_ROOT / ".." / "shared" / "data").resolve()
OTB_DIR = SHARED_DATA / "otb"
OTB_RESULTS_DIR = SHARED_DATA / "otb-results"


def _require(path: Path) -> Path:
    if not path.exists():
        pytest.skip(f"real benchmark data not found at {path} (../shared/data is absent in this clone)")
    return path


@pytest.fixture(scope="session")
def otb_dir() -> Path:
    """``../shared/data/otb``: OTB-format sequences (skips when absent)."""
    return _require(OTB_DIR)


@pytest.fixture(scope="session")
def otb_results_dir() -> Path:
    """``../shared/data/otb-results``: published OTB results (skips when absent)."""
    return _require(OTB_RESULTS_DIR)
