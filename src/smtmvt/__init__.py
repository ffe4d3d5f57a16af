"""smtmvt: the SMTMVT tracker (ICME 2018) and an OTB evaluation toolkit.

Public API::

    from smtmvt import Tracker, TrackerConfig, open_sequence
    tracker = Tracker(TrackerConfig(seed=0))
    tracker.init(frame, (x, y, w, h))       # 0-based pixel box
    result = tracker.update(next_frame)     # TrackResult(box, score, ...)
"""

__version__ = "0.1.0"

from .config import TrackerConfig
from .data import Sequence, SequenceError, open_sequence, read_boxes, write_boxes
from .solvers import solve_smtmvt
from .tracker import Tracker, TrackResult

__all__ = [
    "Sequence",
    "SequenceError",
    "TrackResult",
    "Tracker",
    "TrackerConfig",
    "__version__",
    "open_sequence",
    "read_boxes",
    "solve_smtmvt",
    "write_boxes",
]
