"""How the configuration's fields are declared: a default, a check and a line of doc each.

A group of :class:`~smtmvt.config.TrackerConfig` (:mod:`smtmvt.config.groups`) is a frozen
dataclass deriving from :class:`Group` whose fields are made by :func:`option`::

    weight: float = option(0.5, Real(ge=0), "Weight of the term; 0 turns it off.", flat="correlation_weight")

The check both validates and normalizes the value (a JSON list becomes a tuple, a numpy
integer an int) and says what it expects; :class:`Group` runs the checks after ``__init__``,
:func:`group` writes each field's entry (type and range from the check, default, doc) into the class's
docstring, so the documented range is the one enforced. An error names the field's flat name,
the bad value, what was expected and the grouped name::

    TrackerConfig: invalid correlation_weight=-1.0: expected a finite number >= 0 (correlation.weight)
"""

from __future__ import annotations

import dataclasses
import math
import numbers
from collections.abc import Callable, Collection
from typing import Any, ClassVar, TypeVar

import numpy as np

__all__ = [
    "Check",
    "CheckError",
    "Choice",
    "Flag",
    "Group",
    "Numbers",
    "Real",
    "Sizes",
    "Views",
    "Whole",
    "flat_name",
    "group",
    "invalid",
    "option",
]

_G = TypeVar("_G", bound="Group")


class CheckError(ValueError):
    """A value a check refuses; ``expected`` says what the check wants."""

    def __init__(self, expected: str) -> None:
        super().__init__(expected)
        self.expected = expected


def invalid(flat: str, value: Any, expected: str, where: str = "") -> ValueError:
    """The error of a refused value: the flat name, the value, what was expected, the grouped name."""
    return ValueError(
        f"TrackerConfig: invalid {flat}={value!r}: expected {expected}" + (f" ({where})" if where else "")
    )


def _is_whole(value: Any) -> bool:
    return isinstance(value, numbers.Integral) and not isinstance(value, bool)


def _is_finite(value: Any) -> bool:
    return isinstance(value, numbers.Real) and not isinstance(value, bool) and math.isfinite(value)


def _pair(value: Any) -> bool:
    return isinstance(value, (tuple, list)) and len(value) == 2


class Check:
    """Base of the checks: ``check(value)`` gives the normalized value or raises :class:`CheckError`.
    ``none``: None is allowed too (the field's "off" or "automatic")."""

    none = False

    @property
    def expected(self) -> str:
        raise NotImplementedError

    def normalize(self, value: Any) -> Any:
        raise NotImplementedError

    def __call__(self, value: Any) -> Any:
        if value is None and self.none:
            return None
        try:
            return self.normalize(value)
        except (TypeError, ValueError) as exc:
            raise CheckError(self.expected + (" or None" if self.none else "")) from exc


class Real(Check):
    """A finite number (not a bool) within ``[ge, le]`` / ``(gt, lt)``; stored as a float."""

    def __init__(self, ge=None, le=None, *, gt=None, lt=None, none: bool = False) -> None:
        self.ge, self.le, self.gt, self.lt, self.none = ge, le, gt, lt, none

    @property
    def expected(self) -> str:
        if self.ge is not None and self.le is not None:
            return f"a finite number in [{self.ge:g}, {self.le:g}]"
        if self.ge is not None and self.lt is not None:
            return f"a finite number in [{self.ge:g}, {self.lt:g})"
        if self.gt is not None and self.le is not None:
            return f"a finite number in ({self.gt:g}, {self.le:g}]"
        bounds = [
            f"{op} {b:g}"
            for op, b in ((">=", self.ge), (">", self.gt), ("<=", self.le), ("<", self.lt))
            if b is not None
        ]
        return " ".join(["a finite number", *bounds])

    def normalize(self, value: Any) -> float:
        if not _is_finite(value):
            raise ValueError
        ok = (
            (self.ge is None or value >= self.ge)
            and (self.gt is None or value > self.gt)
            and (self.le is None or value <= self.le)
            and (self.lt is None or value < self.lt)
        )
        if not ok:
            raise ValueError
        return float(value)


class Whole(Check):
    """A whole number (a numpy integer too; a float, even 200.0, is refused, never rounded)
    within ``[lo, hi]`` (``hi`` None: no upper bound); stored as an int. Beyond the bounds a
    run only grows in memory and time (``n_particles=1e9`` grew to 24 GB)."""

    def __init__(self, lo: int, hi: int | None = None, *, none: bool = False) -> None:
        self.lo, self.hi, self.none = lo, hi, none

    @property
    def expected(self) -> str:
        return f"a whole number from {self.lo} to {self.hi}" if self.hi is not None else f"a whole number >= {self.lo}"

    def normalize(self, value: Any) -> int:
        if not (_is_whole(value) and self.lo <= value and (self.hi is None or value <= self.hi)):
            raise ValueError
        return int(value)


class Sizes(Check):
    """Two whole numbers, each within ``[lo, hi]`` pixels; stored as a tuple of ints."""

    def __init__(self, lo: int, hi: int, *, none: bool = False) -> None:
        self.lo, self.hi, self.none = lo, hi, none

    @property
    def expected(self) -> str:
        return f"two whole numbers from {self.lo} to {self.hi}"

    def normalize(self, value: Any) -> tuple[int, int]:
        if not (_pair(value) and all(_is_whole(v) and self.lo <= v <= self.hi for v in value)):
            raise ValueError
        return (int(value[0]), int(value[1]))


class Numbers(Check):
    """A tuple (or list) of ``length`` finite numbers (any length when None), each ``>= ge``
    or ``> gt``; stored as a tuple of floats."""

    def __init__(self, length: int | None = None, *, ge=None, gt=None, none: bool = False) -> None:
        self.length, self.ge, self.gt, self.none = length, ge, gt, none

    @property
    def expected(self) -> str:
        count = {None: "a tuple of", 2: "two"}.get(self.length, f"{self.length}")
        bound = f" >= {self.ge:g}" if self.ge is not None else f" > {self.gt:g}" if self.gt is not None else ""
        return f"{count} finite numbers{bound}"

    def normalize(self, value: Any) -> tuple[float, ...]:
        if not isinstance(value, (tuple, list)) or (self.length is not None and len(value) != self.length):
            raise ValueError
        if not all(_is_finite(v) for v in value):
            raise ValueError
        if self.ge is not None and not all(v >= self.ge for v in value):
            raise ValueError
        if self.gt is not None and not all(v > self.gt for v in value):
            raise ValueError
        return tuple(float(v) for v in value)


class Choice(Check):
    """One of ``choices`` (a collection, read at each check: a registry may grow)."""

    def __init__(self, choices: Collection[str]) -> None:
        self.choices = choices

    @property
    def expected(self) -> str:
        return "one of " + ", ".join(repr(c) for c in self.choices)

    def normalize(self, value: Any) -> str:
        if not (isinstance(value, str) and value in self.choices):
            raise ValueError
        return value


class Flag(Check):
    """True or False (a numpy bool too); stored as a bool. 1 and "yes" are refused."""

    expected = "True or False"

    def normalize(self, value: Any) -> bool:
        if not isinstance(value, (bool, np.bool_)):
            raise ValueError
        return bool(value)


class Views(Check):
    """A tuple (or list) of distinct names of registered views
    (:func:`smtmvt.features.available_views`, read at each check); ``empty``: () allowed."""

    def __init__(self, *, empty: bool) -> None:
        self.empty = empty

    @property
    def expected(self) -> str:
        from ..features import available_views

        names = ", ".join(repr(v) for v in available_views())
        return f"a tuple of distinct view names{'' if self.empty else ', at least one'} among {names}"

    def normalize(self, value: Any) -> tuple[str, ...]:
        from ..features import available_views

        if not isinstance(value, (tuple, list)) or (not value and not self.empty):
            raise ValueError
        if len(set(value)) != len(value) or not all(isinstance(v, str) and v in available_views() for v in value):
            raise ValueError
        return tuple(value)


def option(default: Any, check: Check, doc: str, *, flat: str | None = None, neutral: Any = None) -> Any:
    """A field of a group: its ``default``, its ``check``, its ``doc`` (one to three lines:
    what, unit, evidence) and its ``flat`` name (``TrackerConfig(flat=...)``, ``cfg.flat``,
    the JSON key) when that is not the field's own name. ``neutral``: where given, the value
    at which the tracker is as it was before the field existed (a run folder recorded
    before it resumes with the field at that value: :mod:`smtmvt.evaluation.settings`)."""
    metadata = {"check": check, "doc": doc, "flat": flat}
    if neutral is not None:
        metadata["neutral"] = neutral
    return dataclasses.field(default=default, metadata=metadata)


def flat_name(field: dataclasses.Field) -> str:
    """The field's flat name: ``flat`` where :func:`option` gave one, else its own name."""
    return field.metadata.get("flat") or field.name


class Group:
    """Base of the groups: runs each field's check after ``__init__``, storing the normalized
    value, then :meth:`_check_together` (the checks of fields that depend on each other)."""

    GROUP: ClassVar[str] = ""  # its name in TrackerConfig (``cfg.<GROUP>``), set by :func:`group`

    def __post_init__(self) -> None:
        for f in dataclasses.fields(self):  # type: ignore[arg-type]
            value = getattr(self, f.name)
            try:
                normalized = f.metadata["check"](value)
            except CheckError as exc:
                raise invalid(flat_name(f), value, exc.expected, f"{self.GROUP}.{f.name}") from None
            object.__setattr__(self, f.name, normalized)
        self._check_together()

    def _check_together(self) -> None:
        pass


def _entry(f: dataclasses.Field) -> str:
    """The field's entry in its group's docstring (numpydoc's Attributes)."""
    check: Check = f.metadata["check"]
    also = f", flat name ``{flat_name(f)}``" if flat_name(f) != f.name else ""
    expected = check.expected + (" or None" if check.none else "")
    doc = f.metadata["doc"].replace("\n", "\n        ")
    return f"    {f.name} : {expected}; default {f.default!r}{also}\n        {doc}"


def group(name: str) -> Callable[[type[_G]], type[_G]]:
    """Name a group (a frozen dataclass deriving from :class:`Group`) ``name`` and list its
    fields, with their ranges and defaults, in its docstring (numpydoc's Attributes)."""

    def decorate(cls: type[_G]) -> type[_G]:
        cls.GROUP = name
        entries = "\n".join(_entry(f) for f in dataclasses.fields(cls))  # type: ignore[arg-type]
        cls.__doc__ = f"{(cls.__doc__ or '').rstrip()}\n\n    Attributes\n    ----------\n{entries}\n"
        return cls

    return decorate
