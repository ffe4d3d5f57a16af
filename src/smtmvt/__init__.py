"""smtmvt: the SMTMVT tracker (ICME 2018) and an OTB evaluation toolkit.

Public API::

    from smtmvt import Tracker, TrackerConfig, open_sequence
    tracker = Tracker(TrackerConfig(seed=0))
    tracker.init(frame, (x, y, w, h))       # 0-based pixel box
    result = tracker.update(next_frame)     # TrackResult(box, confidence, lost, ...)

OpenCV's tracker interface (BGR frames, int boxes): ``TrackerSMTMVT.create()``;
got10k's (``got10k`` installed): ``SMTMVTGot10k``, imported on first use.
"""

__version__ = "0.1.0"

from .config import TrackerConfig
from .data import Sequence, SequenceError, open_sequence, read_boxes, write_boxes
from .opencv_api import TrackerSMTMVT
from .solvers import solve_smtmvt
from .tracker import Tracker, TrackResult

__all__ = [
    "SMTMVTGot10k",
    "Sequence",
    "SequenceError",
    "TrackResult",
    "Tracker",
    "TrackerConfig",
    "TrackerSMTMVT",
    "__version__",
    "open_sequence",
    "read_boxes",
    "solve_smtmvt",
    "write_boxes",
]


def __getattr__(name: str):
    """``SMTMVTGot10k`` from :mod:`smtmvt.got10k`, imported on first use: got10k is
    not a dependency of the library."""
    if name == "SMTMVTGot10k":
        from .got10k import SMTMVTGot10k

        return SMTMVTGot10k
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
