"""Helpers for names: natural sort order, case-insensitive look-up, the sequence key.

OTB names differ in case and separators between sources (``BasketBall`` in published
results, ``Basketball`` in the data, ``Skating2.1`` / ``Skating2-1``), and frame files are
numbered with or without zero padding (``img2`` must come before ``img10``).
"""

from __future__ import annotations

import re
from collections.abc import Mapping

__all__ = ["natural_key", "lookup", "canonical_name", "name_clashes"]

_DIGITS = re.compile(r"(\d+)")
_SEPARATORS = re.compile(r"[._\s]+")
# names that mean the same sequence once case and separators are normalised
_NAME_ALIASES = {"human4-2": "human4"}


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


def canonical_name(name: str) -> str:
    """Matching key of a sequence name: lower case, ``.``/``_``/white space -> ``-``, known
    aliases (``Human4.2`` is the only Human4 target and OTB folders call it ``Human4``).

    Results, reports, imports and attribute tables match sequences by this key.
    """
    key = _SEPARATORS.sub("-", str(name).strip().lower())
    return _NAME_ALIASES.get(key, key)


def name_clashes(names) -> dict[str, list[str]]:
    """``{key: [names]}`` for the names that share a :func:`canonical_name` with another one
    (``Seq_1`` and ``seq-1``); empty when every name has its own key."""
    groups: dict[str, list[str]] = {}
    for name in names:
        groups.setdefault(canonical_name(name), []).append(name)
    return {k: v for k, v in groups.items() if len(v) > 1}
