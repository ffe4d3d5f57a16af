"""OTB's three protocols: where each run of a tracker starts, with which box, and how the
runs of one sequence are pooled. Functions of the ground truth (no images; the one file read
is the toolkit's table of omitted start frames shipped with the package, :func:`init_omit`).

OTB (Wu, Lim, Yang, CVPR 2013; TPAMI 2015) evaluates a tracker three ways:

* **OPE** (one-pass evaluation): one run from frame 1 with its ground-truth box.
* **TRE** (temporal robustness): 20 runs, each from a start frame spread over the sequence
  with that frame's ground-truth box, each tracked to the end of the sequence.
* **SRE** (spatial robustness): 12 runs from the first frame with the ground-truth box
  shifted or scaled.

The rules below are those of the OTB MATLAB toolkit (``tracker_benchmark_v1.0``: the
files named are in its ``util/`` folder and its root; the Python port of the same toolkit,
``scripts/butil/split_seq.py`` and ``shift_bbox.py``, follows them but has bugs there
— its ``down`` shift moves the width, its shifts round instead of ceil — so the MATLAB code
is the reference; it was read in the copy redistributed as
``zhangzheng0131/Tracker_Benchmark_tb100``, whose local edits, marked "by zz", are outside
the lines used here). All frame numbers in the toolkit are 1-based; here start frames are
**0-based indices** and boxes are **1-based ``(x, y, w, h)`` in pixels**, as in OTB's files.

TRE segments (``splitSeqTRE.m``, ``segNum = 20``, ``minNum = 20``)
    1. Candidate start frames are all frames ``1..len``, less the frames listed in the
       toolkit's ``initOmit/<seq>.txt`` (inclusive ranges of frames where the target is
       occluded or out of view; ``omit`` here), less every frame whose ground truth is not
       valid (``x <= 0 | y <= 0 | w <= 0 | h <= 0 | isnan``).
    2. ``E`` is the position (1-based, in the candidate list) of the last candidate ``f``
       with ``len - f + 1 >= minNum``: every segment has at least 20 frames.
    3. The chosen positions are ``[floor(1 : E/(segNum-1) : E), E]``: MATLAB's colon from 1
       in steps of ``E/19`` up to ``E``, floored, then ``E`` itself. For ``E >= 19`` that is
       19 + 1 = 20 positions, fewer for a smaller ``E`` (``E = 7``: 18); for ``E <= 19``
       positions repeat (``E = 7``: 1, 1, 1, 2, 2, 2, 3, ...; ``E = 19``: 1 ... 19, 19) and
       the toolkit runs the repeats as separate segments: so do we. Exactly:
       position ``1 + floor(k * E / (segNum - 1))`` for ``k = 0 .. floor((segNum - 1)
       (E - 1) / E)`` (integer arithmetic, as MATLAB's colon gives for these values), then ``E``.
    4. Segment ``i`` starts at the candidate at that position, with that frame's ground-truth
       box, and runs to the last frame of the sequence.
    A sequence with no candidate 20 frames before its end has no segment (MATLAB fails
    there: ``endSegIdx`` undefined); :func:`tre_starts` raises ``ValueError``.
    The toolkit's ``initOmit/`` files (27 OTB sequences: Basketball, Coke, ... Woman) are
    shipped as ``data/tre_init_omit.json`` and applied to the sequences of those names in an
    OTB-layout folder (:func:`init_omit`); they are frame numbers from 1, and each of those
    sequences starts at image 1 in the toolkit and here.

SRE boxes (``shiftInitBB.m``; ``main_running.m``'s ``shiftTypeSet`` gives the order)
    The run starts on the first TRE start (frame 1 unless it is omitted or its ground truth
    is invalid: ``main_running.m`` uses ``subSeqs{1}``), once per shift, in this order:
    ``left, right, up, down, topLeft, topRight, bottomLeft, bottomRight, scale_8, scale_9,
    scale_11, scale_12``. With ``r = [x y w h]``, ``br = (x + w - 1, y + h - 1)``, ``round``
    MATLAB's (half away from zero) and ``ceil`` upwards:

    * ``left`` / ``right``: ``x -/+= ceil(0.1 w)``; ``up`` / ``down``: ``y -/+= ceil(0.1 h)``
      (the size is kept).
    * ``topLeft``: ``x = round(x - 0.1 w)``, ``y = round(y - 0.1 h)``; ``topRight``:
      ``br_x = round(br_x + 0.1 w)``, ``y = round(y - 0.1 h)``; ``bottomLeft``:
      ``x = round(x - 0.1 w)``, ``br_y = round(br_y + 0.1 h)``; ``bottomRight``:
      ``br_x = round(br_x + 0.1 w)``, ``br_y = round(br_y + 0.1 h)``. The other corner stays,
      so the box *grows* by about 10 % in each direction moved: ``w = br_x - x + 1``,
      ``h = br_y - y + 1``.
    * ``scale_8`` ... ``scale_12`` (ratios 0.8, 0.9, 1.1, 1.2) about the centre
      ``c = (x + w/2, y + h/2)``: ``round([c_x - s w/2, c_y - s h/2, s w, s h])``.
    * Then the box is clipped to the image (``W x H`` pixels, 1-based): ``x = max(x, 1)``,
      ``y = max(y, 1)`` (the width is **not** changed then), and ``w = W - x + 1`` when
      ``x + w - 1 > W``, ``h = H - y + 1`` when ``y + h - 1 > H``.

Scoring (``genPerfMat.m``, ``calcSeqErrRobust.m``)
    Each segment is scored like an OPE result against the ground truth of its own frames
    (start to end), its first frame's box set to that frame's ground truth (so an SRE run's
    perturbed first box is not scored). For each sequence the segments are **pooled**: the
    success count at each threshold is summed over the segments and divided by the summed
    segment lengths (``sum(successNumOverlap) / lenALL``), the same for precision; the
    sequences' curves are then averaged as for OPE (:func:`.metrics.aggregate`), AUC = mean of
    the success curve. :func:`pool_scores` does the pooling.
"""

from __future__ import annotations

import functools
import json
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from importlib import resources

import numpy as np

from ..data import canonical_name
from .metrics import PRECISION_INDEX, SequenceScore

__all__ = [
    "PROTOCOLS",
    "PROTOCOL_TITLES",
    "TRE_SEGMENTS",
    "TRE_MIN_LENGTH",
    "SRE_SHIFTS",
    "Segment",
    "tre_starts",
    "init_omit",
    "shift_box",
    "segments",
    "start_box",
    "pool_scores",
    "parse_protocols",
]

#: the protocols, in report order
PROTOCOLS = ("ope", "tre", "sre")
#: their names in the report's titles
PROTOCOL_TITLES = {
    "ope": "OTB one-pass evaluation",
    "tre": "OTB temporal robustness evaluation, TRE",
    "sre": "OTB spatial robustness evaluation, SRE",
}
#: ``segNum`` of ``main_running.m`` / ``splitSeqTRE.m``
TRE_SEGMENTS = 20
#: ``minNum`` of ``splitSeqTRE.m``: the fewest frames a TRE segment has
TRE_MIN_LENGTH = 20
#: ``shiftTypeSet`` of ``main_running.m``, in its order
SRE_SHIFTS = (
    "left",
    "right",
    "up",
    "down",
    "topLeft",
    "topRight",
    "bottomLeft",
    "bottomRight",
    "scale_8",
    "scale_9",
    "scale_11",
    "scale_12",
)
_SCALES = {"scale_8": 0.8, "scale_9": 0.9, "scale_11": 1.1, "scale_12": 1.2}


@dataclass(frozen=True)
class Segment:
    """One run of a tracker on a sequence.

    ``protocol``: ``"ope"``, ``"tre"`` or ``"sre"``; ``name``: ``""`` for OPE, ``"seg-01"``
    ... ``"seg-20"`` for TRE, the shift name for SRE (the file name of its result);
    ``start``: 0-based first frame; ``shift``: the SRE shift, None otherwise.
    """

    protocol: str
    name: str
    start: int
    shift: str | None = None

    @property
    def label(self) -> str:
        """``"tre seg-03 (from frame 41)"`` (1-based frame), ``""`` for OPE; for messages."""
        if self.protocol == "ope":
            return ""
        return f"{self.protocol} {self.name} (from frame {self.start + 1})"


def parse_protocols(value: str | Iterable[str]) -> list[str]:
    """``"ope,tre"`` or ``["TRE"]`` -> the named protocols in :data:`PROTOCOLS` order;
    ValueError naming an unknown one."""
    names = value.split(",") if isinstance(value, str) else list(value)
    wanted = {n.strip().lower() for n in names if n.strip()}
    unknown = sorted(wanted - set(PROTOCOLS))
    if unknown or not wanted:
        what = ", ".join(unknown) if unknown else repr(value)
        raise ValueError(f"protocol {what}: expected one or more of {', '.join(PROTOCOLS)}")
    return [p for p in PROTOCOLS if p in wanted]


def _valid_rows(gt: np.ndarray) -> np.ndarray:
    """``splitSeqTRE.m``'s test: no NaN and all four numbers > 0 (1-based boxes)."""
    with np.errstate(invalid="ignore"):
        return np.isfinite(gt).all(axis=1) & (gt > 0).all(axis=1)


def tre_starts(
    gt,
    omit: Iterable[tuple[int, int]] = (),
    n_segments: int = TRE_SEGMENTS,
    min_length: int = TRE_MIN_LENGTH,
) -> list[int]:
    """0-based start frames of the TRE segments of a sequence (``splitSeqTRE.m``).

    ``gt``: ``(n, 4)`` 1-based ground truth of the whole sequence; ``omit``: inclusive
    ``(first, last)`` 1-based frame ranges not to start from (the toolkit's
    ``initOmit/<seq>.txt``). Returns ``n_segments`` starts in frame order, repeats included
    (see the module docstring). ValueError when no valid start leaves ``min_length`` frames.
    """
    gt = np.asarray(gt, dtype=np.float64)
    if gt.ndim != 2 or gt.shape[1] != 4:
        raise ValueError(f"ground truth: expected an (n, 4) array of x, y, w, h boxes, got shape {gt.shape}")
    n = gt.shape[0]
    ok = _valid_rows(gt)
    for first, last in omit:
        ok[max(int(first) - 1, 0) : max(int(last), 0)] = False
    candidates = np.flatnonzero(ok)  # 0-based frames
    usable = candidates[n - candidates >= min_length]  # len - f + 1 >= minNum with f 1-based
    if usable.size == 0:
        raise ValueError(
            f"no TRE segment: no frame with valid ground truth (and not omitted) is {min_length} or more "
            f"frames from the end of the sequence ({n} frames, {candidates.size} valid starts)"
        )
    end = int(usable.size)  # E: 1-based position of the last usable candidate (usable is a prefix)
    steps = n_segments - 1
    positions = [1 + (k * end) // steps for k in range((steps * (end - 1)) // end + 1)] + [end]
    return [int(candidates[p - 1]) for p in positions]


@functools.cache
def _omit_table() -> dict[str, tuple[tuple[int, int], ...]]:
    text = resources.files(__package__).joinpath("data/tre_init_omit.json").read_text(encoding="utf-8")
    table = json.loads(text)["sequences"]
    return {canonical_name(name): tuple((int(a), int(b)) for a, b in ranges) for name, ranges in table.items()}


def init_omit(sequence: str, layout: str = "otb") -> tuple[tuple[int, int], ...]:
    """The OTB toolkit's ``initOmit/<seq>.txt`` ranges of ``sequence`` (inclusive 1-based
    frames that are no TRE start; ``data/tre_init_omit.json``), matched by
    :func:`~smtmvt.data.canonical_name`; ``()`` for other sequences and for folders of
    another ``layout`` than ``"otb"`` (VOT's "basketball" is not OTB's)."""
    if layout != "otb":
        return ()
    return _omit_table().get(canonical_name(sequence), ())


def _mround(v: float) -> float:
    """MATLAB's ``round``: halves away from zero (Python's ``round`` takes halves to even)."""
    return float(np.sign(v) * np.floor(abs(v) + 0.5))


def shift_box(box, shift: str, image_size: tuple[int, int]) -> np.ndarray:
    """The SRE start box: ``box`` (1-based ``x, y, w, h``) moved or scaled by ``shift`` (one
    of :data:`SRE_SHIFTS`) and clipped to an image of ``image_size = (H, W)`` pixels, as
    ``shiftInitBB.m`` (rules in the module docstring). Returns a ``(4,)`` float array."""
    x, y, w, h = (float(v) for v in np.asarray(box, dtype=np.float64).reshape(4))
    img_h, img_w = image_size
    br_x, br_y = x + w - 1, y + h - 1
    if shift in _SCALES:
        s = _SCALES[shift]
        cx, cy, sw, sh = x + w / 2, y + h / 2, s * w, s * h
        x, y, w, h = (_mround(v) for v in (cx - sw / 2, cy - sh / 2, sw, sh))
    elif shift in ("left", "right"):
        x += (-1 if shift == "left" else 1) * np.ceil(0.1 * w)
    elif shift in ("up", "down"):
        y += (-1 if shift == "up" else 1) * np.ceil(0.1 * h)
    elif shift in ("topLeft", "topRight", "bottomLeft", "bottomRight"):
        if shift.endswith("Left"):
            x = _mround(x - 0.1 * w)
        else:
            br_x = _mround(br_x + 0.1 * w)
        if shift.startswith("top"):
            y = _mround(y - 0.1 * h)
        else:
            br_y = _mround(br_y + 0.1 * h)
        w, h = br_x - x + 1, br_y - y + 1
    else:
        raise ValueError(f"SRE shift {shift!r}: expected one of {', '.join(SRE_SHIFTS)}")
    x, y = max(x, 1.0), max(y, 1.0)
    if x + w - 1 > img_w:
        w = img_w - x + 1
    if y + h - 1 > img_h:
        h = img_h - y + 1
    return np.array([x, y, w, h], dtype=np.float64)


def segments(protocol: str, gt, omit: Iterable[tuple[int, int]] = ()) -> list[Segment]:
    """The runs of ``protocol`` on a sequence of 1-based ground truth ``gt`` ``(n, 4)``.

    OPE: one run from frame 0 (our runner's rule: the toolkit's OPE starts on the first TRE
    start, which is frame 0 whenever frame 1 is annotated). TRE: :func:`tre_starts`, named
    ``seg-01`` ... SRE: the 12 :data:`SRE_SHIFTS` from the first TRE start. ``omit``: the
    sequence's :func:`init_omit`. ValueError when TRE or SRE has no start (:func:`tre_starts`)."""
    if protocol == "ope":
        return [Segment("ope", "", 0)]
    starts = tre_starts(gt, omit)
    if protocol == "tre":
        return [Segment("tre", f"seg-{i + 1:02d}", s) for i, s in enumerate(starts)]
    if protocol == "sre":
        return [Segment("sre", shift, starts[0], shift) for shift in SRE_SHIFTS]
    raise ValueError(f"protocol {protocol!r}: expected one of {', '.join(PROTOCOLS)}")


def start_box(segment: Segment, gt, image_size: tuple[int, int] | None = None) -> np.ndarray:
    """The box a run of ``segment`` is initialised with (1-based ``(4,)``): the ground truth
    of its first frame, shifted for SRE (which needs ``image_size = (H, W)``)."""
    box = np.asarray(gt, dtype=np.float64)[segment.start]
    if segment.shift is None:
        return box.copy()
    if image_size is None:
        raise ValueError("an SRE start box needs the image size (H, W)")
    return shift_box(box, segment.shift, image_size)


def pool_scores(scores: Sequence[SequenceScore], invalid: str = "otb") -> SequenceScore:
    """One sequence's score from its segments' scores (``genPerfMat.m``): each curve is the
    sum of the segments' hit counts over the sum of their denominators (all frames, or the
    valid frames for ``invalid="pytracking"``, as :func:`.metrics.score_sequence`).
    ``avg_overlap`` is the mean overlap over all valid frames of all segments; the per-frame
    arrays are concatenated in segment order."""
    if not scores:
        raise ValueError("pool_scores: no segment to pool")
    denom = np.array([s.n_valid if invalid == "pytracking" else s.n_frames for s in scores], dtype=np.float64)
    total = denom.sum()
    weights = denom / total if total else np.zeros_like(denom)
    succ = weights @ np.vstack([s.success for s in scores])
    prec = weights @ np.vstack([s.precision for s in scores])
    n_valid = sum(s.n_valid for s in scores)
    avg = sum(s.avg_overlap * s.n_valid for s in scores) / n_valid if n_valid else 0.0
    return SequenceScore(
        overlaps=np.concatenate([s.overlaps for s in scores]),
        errors=np.concatenate([s.errors for s in scores]),
        success=np.asarray(succ, dtype=np.float64),
        precision=np.asarray(prec, dtype=np.float64),
        auc=float(np.mean(succ)),
        precision20=float(prec[PRECISION_INDEX]),
        avg_overlap=float(avg),
        n_frames=sum(s.n_frames for s in scores),
        n_valid=n_valid,
        valid=np.concatenate([s.valid for s in scores]),
    )
