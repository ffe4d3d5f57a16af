"""Helpers for names: natural sort order and case-insensitive look-up.

OTB names differ in case between sources (``BasketBall`` in published results,
``Basketball`` in the data), and frame files are numbered with or without zero
padding (``img2`` must come before ``img10``).
"""

from __future__ import annotations

import re
from collections.abc import Mapping

__all__ = ["natural_key", "lookup"]

_DIGITS = re.compile(r"(\d+)")


def natural_key(text: str) -> tuple:
    """Sort key ordering digit runs by value and letters case-insensitively.

    ``sorted(names, key=natural_key)`` puts ``img2`` before ``img10``. Ties
    (``img01`` vs ``img1``, ``A`` vs ``a``) are broken by the plain string so
    the order is total and reproducible.
    """
    parts = _DIGITS.split(str(text))
    key = tuple(int(p) if i % 2 else p.lower() for i, p in enumerate(parts))
    return (key, str(text))


def lookup(mapping: Mapping, name: str):
    """``mapping[name]`` with the key matched case-insensitively.

    An exact match wins. Raises ``KeyError`` listing the available keys when
    nothing matches, ``ValueError`` when several keys differ only in case.
    """
    if name in mapping:
        return mapping[name]
    folded = str(name).casefold()
    hits = [k for k in mapping if str(k).casefold() == folded]
    if len(hits) == 1:
        return mapping[hits[0]]
    if hits:
        raise ValueError(f"name {name!r} is ambiguous: matches {sorted(hits)} (differ only in case)")
    raise KeyError(
        f"{name!r} not found (case-insensitive); available: {', '.join(sorted(map(str, mapping), key=natural_key))}"
    )
