"""The tuning / checking split of the measuring sequences, made from their OTB attributes only.

Usage::

    python bench/split.py --att ../shared/data/otb-results/anno/att SEQ [SEQ ...]

Draws 200,000 random halves (15 sequences to tune on, the rest to check,
``random.Random(0)``) and keeps the first with the lowest cost: for each of
the 11 OTB attributes, the difference between its counts in the two halves
(100 more when an attribute held by two or more sequences is missing from a
half), plus how far the tuning half's share of ``shared/data/otb`` is from
half. Sequences cut from the same video (``Jogging-1``, ``Jogging-2``) stay
in one half. No score enters: the split is fixed before any change is
measured on it. Prints the JSON that ``bench/split.json`` holds.
Not a test: it measures.
"""

from __future__ import annotations

import argparse
import json
import random
import re
from pathlib import Path

#: The sequences of ``shared/data/otb`` (the tuning half should hold about half of them).
OTB_SHARED = {"Basketball", "CarDark", "Crossing", "David", "Dog1", "Girl", "Jumping", "Singer2", "Subway"}
TUNE_SIZE = 15
DRAWS = 200_000


def attributes(att_dir: Path, name: str) -> list[int]:
    """The 11 OTB attribute flags of sequence ``name`` (``Jogging-1`` reads ``Jogging``'s file)."""
    files = {p.name.lower(): p for p in att_dir.glob("*.txt")}
    for key in (name.lower(), re.sub(r"-\d+$", "", name).lower()):
        if f"{key}.txt" in files:
            return [int(float(v)) for v in re.split(r"[,\s]+", files[f"{key}.txt"].read_text().strip())]
    raise SystemExit(f"split: no attribute file for {name} in {att_dir}")


def cost(tune: set[str], flags: dict[str, list[int]]) -> float:
    """How unevenly ``tune`` and the rest share the attributes (see the module docstring)."""
    total = 0.0
    for a in range(11):
        t = sum(flags[n][a] for n in tune)
        c = sum(flags[n][a] for n in flags if n not in tune)
        if t + c >= 2 and (t == 0 or c == 0):
            total += 100
        total += abs(t - c)
    return total + abs(len(tune & OTB_SHARED) - len(OTB_SHARED) / 2)


def split(flags: dict[str, list[int]]) -> dict[str, list[str]]:
    names = sorted(flags)
    rng = random.Random(0)
    best: tuple[float, set[str]] | None = None
    for _ in range(DRAWS):
        tune = set(rng.sample(names, TUNE_SIZE))
        if ("Jogging-1" in tune) != ("Jogging-2" in tune):
            continue
        c = cost(tune, flags)
        if best is None or c < best[0]:
            best = (c, tune)
    assert best is not None
    return {"tune": sorted(best[1]), "check": sorted(set(names) - best[1])}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--att", required=True, type=Path, help="the OTB attribute folder (otb-results/anno/att)")
    ap.add_argument("sequences", nargs="+")
    args = ap.parse_args()
    print(json.dumps(split({n: attributes(args.att, n) for n in args.sequences}), indent=1))


if __name__ == "__main__":
    main()
