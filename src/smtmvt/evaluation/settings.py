"""What a tracker's results in a run folder are made with (issue 46).

A run folder records, per tracker, the settings its results were made with
(``run.json``'s ``tracker_settings``; :meth:`.rundir.RunDir.settle` refuses a command whose
settings differ), and, per result, what the result started from
(``results/<tracker>/meta/<seq>.json``; :meth:`.rundir.RunDir.record_problem`)::

    {"tracker": "smtmvt.evaluation.trackers.SmtmvtAdapter",   # class of the tracker object
     "options": {"n_particles": 200},   # the options given (--tracker-option), seed included
     "config": {...},                   # its full resolved configuration, or None
     "versions": {"smtmvt": "0.1.0", "opencv": "4.10.0"}}

``config`` is the tracker's ``config`` attribute when it is a dataclass (our trackers'
:class:`~smtmvt.config.TrackerConfig`, by its flat names: :meth:`~smtmvt.config.TrackerConfig.to_flat`,
the form of the records made before it had groups) without its ``seed`` (each pair has its own); an
OpenCV tracker has none (its options and OpenCV's version settle it). Every value is JSON
(a value JSON cannot hold is kept as its ``repr``), so a record read back from ``run.json``
compares equal to a new one exactly when the settings are the same.

One exception (:func:`settings_difference`): an experimental option
(:class:`~smtmvt.config.ExperimentalConfig`) at its default is the tracker without that
option, so a record that lacks it (made before the option existed) and one that holds it at
its default are the same settings: adding an experimental option does not stop the run
folders made before it from resuming. Any other field that one record lacks is a difference.
"""

from __future__ import annotations

import dataclasses
import hashlib
import json

__all__ = ["tracker_settings", "settings_digest", "settings_difference"]


def _as_json(value):
    """``value`` as JSON would give it back (sorted keys; tuples as lists; others as repr)."""
    return json.loads(json.dumps(value, sort_keys=True, default=repr))


def tracker_settings(tracker, options: dict) -> dict:
    """The settings record of results made by ``tracker`` (a built tracker object), built
    with ``options`` (the user's options of that tracker, ``seed`` included)."""
    from .. import __version__
    from .trackers import OpenCVTracker

    config = getattr(tracker, "config", None)
    to_flat = getattr(config, "to_flat", None)  # TrackerConfig: its flat form, as before its groups
    if callable(to_flat):
        fields = {k: v for k, v in to_flat().items() if k != "seed"}
    elif dataclasses.is_dataclass(config) and not isinstance(config, type):
        fields = {k: v for k, v in dataclasses.asdict(config).items() if k != "seed"}
    else:
        fields = None
    versions = {"smtmvt": __version__}
    if isinstance(tracker, OpenCVTracker):
        import cv2

        versions["opencv"] = cv2.__version__
    cls = type(tracker)
    record = {"tracker": f"{cls.__module__}.{cls.__qualname__}", "options": options, "config": fields}
    return _as_json({**record, "versions": versions})


def settings_digest(record: dict) -> str:
    """16 hex digits of the SHA-256 of ``record``'s canonical JSON (for per-result records)."""
    text = json.dumps(_as_json(record), sort_keys=True, separators=(",", ":"))
    return hashlib.sha256(text.encode("utf-8")).hexdigest()[:16]


def settings_difference(old: dict, new: dict, limit: int = 6) -> str | None:
    """None when ``old`` and ``new`` are the same settings; otherwise what differs, as
    ``"options.detect_thresh: 0.3 -> 0.2; versions.opencv: 4.9.0 -> 4.10.0"`` (at most
    ``limit`` items; ``(unset)`` for a key one side lacks). Experimental options at their
    defaults are left out of both before comparing (see the module docstring)."""
    old, new = _without_neutral(_as_json(old)), _without_neutral(_as_json(new))
    if old == new:
        return None
    items = [f"{key}: {a} -> {b}" for key, a, b in _leaves_that_differ(old, new, "")]
    more = len(items) - limit
    return "; ".join(items[:limit]) + (f"; and {more} more" if more > 0 else "")


def _neutral_options() -> dict:
    """``{flat name: value}`` (as JSON) of the options at whose value the tracker is as it was
    before they existed: the experimental options' defaults (which turn them off), and each
    other option's ``neutral`` value where :func:`smtmvt.config.checks.option` gives one."""
    from ..config import GROUPS, ExperimentalConfig
    from ..config.checks import flat_name

    neutral = {flat_name(f): _as_json(f.default) for f in dataclasses.fields(ExperimentalConfig)}
    for group in GROUPS.values():
        for f in dataclasses.fields(group):
            if "neutral" in f.metadata:
                neutral[flat_name(f)] = _as_json(f.metadata["neutral"])
    return neutral


def _without_neutral(record):
    """``record`` (JSON) with its ``config``'s experimental options at their defaults left out."""
    config = record.get("config") if isinstance(record, dict) else None
    if not isinstance(config, dict):
        return record
    neutral = _neutral_options()
    kept = {k: v for k, v in config.items() if not (k in neutral and v == neutral[k])}
    return {**record, "config": kept}


def _leaves_that_differ(old, new, prefix: str):
    """``(dotted key, old, new)`` of every differing leaf of two JSON values."""
    if isinstance(old, dict) and isinstance(new, dict):
        for key in sorted(set(old) | set(new)):
            a, b = old.get(key, _UNSET), new.get(key, _UNSET)
            if a != b:
                yield from _leaves_that_differ(a, b, f"{prefix}.{key}" if prefix else key)
    else:
        yield prefix or "settings", _shown(old), _shown(new)


class _Unset:
    def __repr__(self) -> str:
        return "(unset)"


_UNSET = _Unset()


def _shown(value) -> str:
    return "(unset)" if value is _UNSET else json.dumps(value)
