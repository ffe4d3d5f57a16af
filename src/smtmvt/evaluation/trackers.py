"""Registry of named trackers for the evaluation, and adapters for OpenCV's peers.

Every tracker the runner drives obeys one small protocol (:class:`EvalTracker`)::

    t = make_tracker("opencv-kcf", seed=3)
    t.init(frame_rgb, (x, y, w, h))       # 0-based pixel box, floats
    x, y, w, h = t.update(frame_rgb)      # 0-based pixel box, floats

Frames are what :mod:`smtmvt.data` yields: ``uint8`` or ``uint16`` arrays, ``(H, W)``
gray or ``(H, W, 3)`` **RGB**. Each adapter converts them to what its tracker wants.

Built-in names
--------------
``smtmvt``
    Our tracker (:class:`smtmvt.Tracker`) with ``TrackerConfig()`` defaults, fed the RGB/gray
    frame unchanged. Options: ``seed``, ``config`` (a :class:`~smtmvt.config.TrackerConfig`)
    and any ``TrackerConfig`` field by its flat name (``n_particles=...``, ``correlation_weight=...``).
``smtmvt-paper``
    Our tracker as the paper describes it (``TrackerConfig.paper()``); same options.
``smtmvt-l1t``, ``smtmvt-mtt``, ``smtmvt-mtmvt-ls``, ``smtmvt-mtmvt-lad``
    The paper's comparison models as observation models of our particle filter,
    in the paper's setting (``TrackerConfig.paper(model=...)``: the views as the
    paper samples them, frames at 320x240, as its table ran every tracker).
``smtmvt-ivt``
    IVT (Ross et al. 2008, :mod:`smtmvt.ivt`) with OTB's particle-filter setting, frames
    at 320x240. Options: the fields of :class:`smtmvt.ivt.IVTConfig`.
``opencv-csrt``, ``opencv-kcf``, ``opencv-mil``
    OpenCV's current API (``cv2.TrackerXXX_create``). Options: the fields of
    ``cv2.TrackerXXX_Params`` (e.g. ``detect_thresh=0.2`` for KCF).
``opencv-mosse``, ``opencv-medianflow``, ``opencv-tld``, ``opencv-boosting``
    opencv-contrib's legacy API (``cv2.legacy.TrackerXXX_create``); no options.

How the OpenCV peers are driven (:class:`OpenCVTracker`)
-------------------------------------------------------
- **Colour**: OpenCV's trackers expect BGR (CSRT/KCF use colour-names features on it).
  RGB frames are converted to BGR, gray ones replicated to three BGR channels, ``uint16``
  mapped to ``uint8`` by ``round(v * 255 / 65535)`` (a fixed mapping, the same for every
  frame, so brightness does not jump).
- **Box type**: the current API takes an integer ``cv2.Rect``: the box is widened to
  whole pixels that *cover* it (``floor`` of the top-left, ``ceil`` of the bottom-right),
  so an integer ground-truth box passes unchanged. The legacy API takes a float
  ``cv2.Rect2d``: the box is passed as floats. The initial box is clipped to the image
  (OpenCV asserts on boxes that leave it; OTB has a few such first frames); one with less
  than a quarter of its area inside (``w = 1e308``) is refused, as :class:`smtmvt.Tracker`
  refuses it, never clipped into another box.
- **Lost (``update`` returns False)**: OpenCV then leaves the box unspecified (the current
  API returns ``(0, 0, 0, 0)``, which would score zero on every following frame). The
  adapter reports the **previous box** instead: the tracker's last known position, which is
  what the OTB protocol counts for a tracker that keeps reporting where it last saw the
  target (the MATLAB toolkit also substitutes the previous box for empty predictions). The
  flag is kept in ``tracker.lost`` / counted in ``tracker.lost_frames``. Non-finite or
  empty boxes returned with ``True`` are treated the same way.
- **TLD on small targets**: OpenCV's TLD upscales the image internally when the target's
  smaller side is below 20 px and then mixes coordinates of the upscaled and the original
  image (its detector's box is never scaled back), so its boxes drift away by the scale
  factor (mean IoU 0.03 on Crossing's first 60 frames). The adapter upscales such frames
  itself so that TLD's internal factor is 1 and scales the boxes back (0.39 there).
- **Determinism**: ``cv2.setRNGSeed(seed)`` is called before each tracker is built. CSRT,
  KCF, MOSSE, MedianFlow and Boosting are deterministic. MIL and TLD draw from an OpenCV
  random state that ``setRNGSeed`` does not reach: the same in every fresh process, but a
  second run in the same process differs. They are registered with ``fresh_process=True``:
  the runner runs each of their pairs in a new process, so their boxes do not depend on
  what a worker ran before. In a fresh process MIL's boxes depend on the seed (it is
  repeated by ``--repeat``), TLD's do not (it is registered deterministic).
- **KCF's "lost"**: OpenCV's KCF declares the target lost when its correlation peak is
  below ``detect_thresh`` (0.5) and then neither moves nor learns, so it freezes for the
  rest of the sequence. On small, low-contrast targets this happens within the first
  frames (Girl, Subway, Crossing). This is OpenCV's KCF as shipped and is kept as the
  default; ``make_tracker("opencv-kcf", detect_thresh=0.1)`` gives a KCF closer to the
  paper's (which has no such test).
"""

from __future__ import annotations

import functools
import inspect
import math
import threading
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, Protocol, runtime_checkable

import numpy as np

from ..geometry import box_inside_fraction
from .rundir import check_tracker_name

__all__ = [
    "EvalTracker",
    "OpenCVTracker",
    "SmtmvtAdapter",
    "register_tracker",
    "unregister_tracker",
    "available_trackers",
    "get_factory",
    "tracker_spec",
    "TrackerSpec",
    "make_tracker",
    "to_bgr8",
    "UnknownTrackerError",
]

Box = tuple  # (x, y, w, h) floats, 0-based


@runtime_checkable
class EvalTracker(Protocol):
    """What the runner drives: 0-based ``(x, y, w, h)`` boxes, RGB or gray frames."""

    def init(self, frame: np.ndarray, box: Box) -> None:  # pragma: no cover - protocol
        ...

    def update(self, frame: np.ndarray) -> Box:  # pragma: no cover - protocol
        ...


class UnknownTrackerError(ValueError):
    """A tracker name that is not registered; the message lists the known ones."""


@dataclass(frozen=True)
class TrackerSpec:
    """A registered tracker: its factory and how the runner must drive it.

    ``deterministic``: the same boxes for every seed, so ``--repeat`` runs it once.
    ``fresh_process``: it keeps state that the seed does not reach (OpenCV's MIL and TLD), so
    each (sequence, repeat) runs in a new process; a resumed or parallel run then equals an
    uninterrupted one.
    """

    name: str
    factory: Callable[..., EvalTracker]
    deterministic: bool = False
    fresh_process: bool = False


_REGISTRY: dict[str, TrackerSpec] = {}
_LOCK = threading.Lock()


def register_tracker(
    name: str,
    factory: Callable[..., EvalTracker],
    *,
    replace: bool = False,
    deterministic: bool | None = None,
    fresh_process: bool | None = None,
) -> None:
    """Register ``factory`` under ``name``.

    ``factory(**options)`` must return an object with ``init(frame, box)`` and
    ``update(frame) -> box`` (:class:`EvalTracker`). If it accepts a ``seed`` keyword
    (or ``**kwargs``) the runner passes a per-sequence seed. For parallel or distributed
    runs the factory must be picklable: a module-level function or class (or a
    ``functools.partial`` of one). The name is used as a directory name in run folders,
    so it may only hold letters, digits and ``_ . + -``.

    ``deterministic`` / ``fresh_process`` (see :class:`TrackerSpec`) default to the
    factory's own attributes of those names, else False: a factory can declare itself
    deterministic (``MyTracker.deterministic = True``), as got10k's ``is_deterministic``.
    """
    try:
        check_tracker_name(name)
    except ValueError as exc:
        raise ValueError(f"{exc}; the name is used as a folder name in run folders") from None
    if not callable(factory):
        raise TypeError(f"tracker factory for {name!r} is not callable")
    if deterministic is None:
        deterministic = bool(getattr(factory, "deterministic", False))
    if fresh_process is None:
        fresh_process = bool(getattr(factory, "fresh_process", False))
    with _LOCK:
        if name in _REGISTRY and not replace:
            raise ValueError(f"tracker {name!r} is already registered (pass replace=True)")
        _REGISTRY[name] = TrackerSpec(name, factory, deterministic, fresh_process)


def unregister_tracker(name: str) -> None:
    """Remove ``name`` from the registry (no error if absent)."""
    with _LOCK:
        _REGISTRY.pop(name, None)


def available_trackers() -> list[str]:
    """Registered tracker names, sorted."""
    with _LOCK:
        return sorted(_REGISTRY)


def tracker_spec(name: str) -> TrackerSpec:
    """The :class:`TrackerSpec` registered under ``name``; :class:`UnknownTrackerError` if none."""
    with _LOCK:
        spec = _REGISTRY.get(name)
    if spec is None:
        raise UnknownTrackerError(f"unknown tracker {name!r}; available: {', '.join(available_trackers())}")
    return spec


def get_factory(name: str) -> Callable[..., EvalTracker]:
    """The factory registered under ``name``; :class:`UnknownTrackerError` if none."""
    return tracker_spec(name).factory


def accepts_keyword(factory: Callable, keyword: str) -> bool:
    """Whether ``factory`` can be called with ``keyword=...``."""
    try:
        sig = inspect.signature(factory)
    except (TypeError, ValueError):  # builtins without signature
        return False
    for p in sig.parameters.values():
        if p.kind == p.VAR_KEYWORD:
            return True
        if p.name == keyword and p.kind in (p.POSITIONAL_OR_KEYWORD, p.KEYWORD_ONLY):
            return True
    return False


def make_tracker(name: str, **options) -> EvalTracker:
    """A new tracker ``name`` built with ``options`` (see the module docstring).

    A ``seed`` option is dropped for factories that do not accept one.
    """
    factory = get_factory(name)
    if "seed" in options and not accepts_keyword(factory, "seed"):
        options = {k: v for k, v in options.items() if k != "seed"}
    return factory(**options)


# --------------------------------------------------------------------------- frames


def to_bgr8(frame: np.ndarray) -> np.ndarray:
    """A contiguous ``uint8`` BGR ``(H, W, 3)`` copy of an RGB or gray frame.

    ``(H, W)`` and ``(H, W, 1)`` gray are replicated to three channels, ``(H, W, 3)`` is
    taken as RGB, ``(H, W, 4)`` as RGBA. ``uint16`` is mapped by ``round(v * 255 / 65535)``.
    """
    import cv2

    a = np.asarray(frame)
    if a.dtype == np.uint16:
        a = ((a.astype(np.uint32) * 255 + 32767) // 65535).astype(np.uint8)
    elif a.dtype != np.uint8:
        raise TypeError(f"frame dtype {a.dtype} not supported (expected uint8 or uint16)")
    if a.ndim == 3 and a.shape[2] == 1:
        a = a[:, :, 0]
    if a.ndim == 2:
        return cv2.cvtColor(np.ascontiguousarray(a), cv2.COLOR_GRAY2BGR)
    if a.ndim == 3 and a.shape[2] == 3:
        return cv2.cvtColor(np.ascontiguousarray(a), cv2.COLOR_RGB2BGR)
    if a.ndim == 3 and a.shape[2] == 4:
        return cv2.cvtColor(np.ascontiguousarray(a), cv2.COLOR_RGBA2BGR)
    raise ValueError(f"frame shape {a.shape} not supported (expected (H,W), (H,W,3) or (H,W,4))")


#: the least share of the initial box's area inside the image (as :meth:`smtmvt.Tracker.init`)
MIN_INSIDE = 0.25


def _valid_box(box) -> bool:
    return len(box) == 4 and all(math.isfinite(v) for v in box) and box[2] > 0 and box[3] > 0


def _clip_to_image(box: Box, shape) -> Box:
    """``box`` intersected with the image; the original box if they do not meet."""
    h, w = shape[:2]
    x0, y0 = max(0.0, box[0]), max(0.0, box[1])
    x1, y1 = min(float(w), box[0] + box[2]), min(float(h), box[1] + box[3])
    if x1 - x0 < 1 or y1 - y0 < 1:
        return box
    return (x0, y0, x1 - x0, y1 - y0)


def covering_rect(box: Box) -> tuple:
    """Integer ``(x, y, w, h)`` of the whole pixels covering ``box`` (at least 1x1)."""
    eps = 1e-6
    x0, y0 = math.floor(box[0] + eps), math.floor(box[1] + eps)
    x1, y1 = math.ceil(box[0] + box[2] - eps), math.ceil(box[1] + box[3] - eps)
    return (int(x0), int(y0), int(max(1, x1 - x0)), int(max(1, y1 - y0)))


# --------------------------------------------------------------------------- OpenCV


_OPENCV = {
    # name: (module path, create function, params class or None, legacy API?)
    "opencv-csrt": ("", "TrackerCSRT_create", "TrackerCSRT_Params", False),
    "opencv-kcf": ("", "TrackerKCF_create", "TrackerKCF_Params", False),
    "opencv-mil": ("", "TrackerMIL_create", "TrackerMIL_Params", False),
    "opencv-mosse": ("legacy", "TrackerMOSSE_create", None, True),
    "opencv-medianflow": ("legacy", "TrackerMedianFlow_create", None, True),
    "opencv-tld": ("legacy", "TrackerTLD_create", None, True),
    "opencv-boosting": ("legacy", "TrackerBoosting_create", None, True),
}


class OpenCVTracker:
    """Adapter driving one OpenCV tracker with the evaluation protocol.

    See the module docstring for colour, box type and lost handling.

    Parameters
    ----------
    name : one of the ``opencv-*`` names.
    seed : passed to ``cv2.setRNGSeed`` before the tracker is created.
    **params : fields of ``cv2.TrackerXXX_Params`` (current API only).
    """

    #: TLD upscales internally below this smaller side (opencv_contrib tldTracker.cpp).
    TLD_MIN_SIDE = 20.0

    def __init__(self, name: str, seed: int | None = None, **params):
        import cv2

        if name not in _OPENCV:
            raise UnknownTrackerError(f"not an OpenCV tracker: {name!r}")
        module, create, params_cls, legacy = _OPENCV[name]
        owner = getattr(cv2, module) if module else cv2
        if not hasattr(owner, create):
            raise RuntimeError(
                f"{name}: cv2{'.' + module if module else ''}.{create} is missing (opencv-contrib-python is needed)"
            )
        if params and params_cls is None:
            raise ValueError(f"{name} takes no options (got {sorted(params)})")
        self.name = name
        self.legacy = legacy
        self._create = getattr(owner, create)
        self._params = None
        if params:
            assert params_cls is not None  # checked above
            p = getattr(cv2, params_cls)()
            for key, value in params.items():
                if not hasattr(p, key):
                    fields = [f for f in dir(p) if not f.startswith("_")]
                    raise ValueError(f"{name}: unknown option {key!r}; options: {', '.join(fields)}")
                setattr(p, key, value)
            self._params = p
        self.seed = seed
        self._tracker: Any = None
        self._box: Box | None = None
        self._scale = 1.0
        self.lost = False
        self.lost_frames = 0

    def _prepare(self, frame: np.ndarray) -> np.ndarray:
        import cv2

        bgr = to_bgr8(frame)
        if self._scale != 1.0:
            h, w = bgr.shape[:2]
            size = (int(round(w * self._scale)), int(round(h * self._scale)))
            bgr = cv2.resize(bgr, size, interpolation=cv2.INTER_LINEAR)
        return bgr

    def init(self, frame: np.ndarray, box: Box) -> None:
        import cv2

        box = tuple(float(v) for v in box)
        if not _valid_box(box):
            raise ValueError(f"{self.name}: invalid initial box {box}")
        h, w = np.shape(frame)[:2]
        inside = box_inside_fraction(box, (h, w))
        if inside < MIN_INSIDE:  # clipped, such a box would silently become another one
            where = f"the {w}x{h} image ({inside:.0%} inside)"
            raise ValueError(f"{self.name}: initial box {box} is mostly outside {where}")
        box = _clip_to_image(box, (h, w))
        self._scale = 1.0
        if self.name == "opencv-tld" and min(box[2], box[3]) < self.TLD_MIN_SIDE:
            # a hair above the exact factor so TLD's own factor 20/min(w,h) is <= 1
            self._scale = self.TLD_MIN_SIDE / min(box[2], box[3]) * 1.001
        if self.seed is not None:
            cv2.setRNGSeed(int(self.seed) & 0x7FFFFFFF)
        self._tracker = self._create(self._params) if self._params is not None else self._create()
        s = self._scale
        scaled = (box[0] * s, box[1] * s, box[2] * s, box[3] * s)
        rect = scaled if self.legacy else covering_rect(scaled)
        ok = self._tracker.init(self._prepare(frame), rect)
        if ok is False:  # the legacy API reports failure; the current one raises
            raise RuntimeError(f"{self.name}: init failed for box {box}")
        self._box = box
        self.lost = False
        self.lost_frames = 0

    def update(self, frame: np.ndarray) -> Box:
        if self._tracker is None or self._box is None:
            raise RuntimeError(f"{self.name}: update() before init()")
        ok, rect = self._tracker.update(self._prepare(frame))
        s = self._scale
        box = tuple(float(v) / s for v in rect) if rect is not None else ()
        if ok and _valid_box(box):
            self._box = box
            self.lost = False
        else:  # lost: keep reporting the last known position (see module docstring)
            self.lost = True
            self.lost_frames += 1
        return self._box


def _opencv_factory(name: str, seed: int | None = None, **params) -> OpenCVTracker:
    return OpenCVTracker(name, seed=seed, **params)


# --------------------------------------------------------------------------- ours


class SmtmvtAdapter:
    """:class:`smtmvt.Tracker` in the evaluation protocol (frames passed unchanged)."""

    def __init__(self, seed: int | None = None, config=None, **fields):
        from ..config import TrackerConfig

        config = config if config is not None else TrackerConfig()
        if seed is not None:
            fields["seed"] = int(seed)
        self.config = config.replace(**fields) if fields else config
        self._tracker: Any = None
        self.last_result = None

    def init(self, frame: np.ndarray, box: Box) -> None:
        from .. import tracker as _tracker_mod  # lazy: the tracker is heavy to import

        self._tracker = _tracker_mod.Tracker(self.config)
        self._tracker.init(frame, tuple(float(v) for v in box))

    def update(self, frame: np.ndarray) -> Box:
        result = self._tracker.update(frame)
        self.last_result = result
        return tuple(float(v) for v in result.box)


def _smtmvt_factory(seed: int | None = None, **options) -> SmtmvtAdapter:
    return SmtmvtAdapter(seed=seed, **options)


def _smtmvt_paper_factory(seed: int | None = None, **fields) -> SmtmvtAdapter:
    """Our tracker as the paper describes it (:meth:`TrackerConfig.paper`), fields overridable."""
    from ..config import TrackerConfig

    return SmtmvtAdapter(seed=seed, config=TrackerConfig.paper(), **fields)


def _ivt_factory(seed: int | None = None, **fields):
    """IVT (:class:`smtmvt.ivt.IVTTracker`) with OTB's settings, fields of :class:`~smtmvt.ivt.IVTConfig` overridable."""
    from ..ivt import IVTConfig, IVTTracker

    return IVTTracker(IVTConfig(seed=None if seed is None else int(seed), **fields))


register_tracker("smtmvt", _smtmvt_factory)
register_tracker("smtmvt-paper", _smtmvt_paper_factory)
# The paper's comparison models in our particle filter (TrackerConfig.model):
# L1T and MTT code the intensity view only, MTMVT-LS and MTMVT-LAD all four views
# (MTMVT-LAD: about 1.3 frames a second on Crossing, the paper's 200 iterations a frame).
register_tracker("smtmvt-l1t", functools.partial(_smtmvt_paper_factory, model="l1t", views=("intensity",)))
register_tracker("smtmvt-mtt", functools.partial(_smtmvt_paper_factory, model="mtt", views=("intensity",)))
register_tracker("smtmvt-mtmvt-ls", functools.partial(_smtmvt_paper_factory, model="mtmvt-ls"))
register_tracker("smtmvt-mtmvt-lad", functools.partial(_smtmvt_paper_factory, model="mtmvt-lad"))
# IVT: its own appearance model (an incremental PCA subspace) and particle filter (smtmvt.ivt)
register_tracker("smtmvt-ivt", _ivt_factory)
# OpenCV: MIL and TLD run in a fresh process per pair; TLD's boxes there do not depend on the
# seed (measured: the same for seeds 1, 2, 5, 77, 123 on Girl and Crossing), MIL's do.
_DETERMINISTIC = {"opencv-csrt", "opencv-kcf", "opencv-mosse", "opencv-medianflow", "opencv-boosting", "opencv-tld"}
_FRESH_PROCESS = {"opencv-mil", "opencv-tld"}
for _name in _OPENCV:
    register_tracker(
        _name,
        functools.partial(_opencv_factory, _name),
        deterministic=_name in _DETERMINISTIC,
        fresh_process=_name in _FRESH_PROCESS,
    )
del _name
