"""smtmvt: the SMTMVT tracker (ICME 2018) and an OTB evaluation toolkit.

Public API::

    from smtmvt import Tracker, TrackerConfig, open_sequence
    tracker = Tracker(TrackerConfig(seed=0))
    tracker.init(frame, (x, y, w, h))       # 0-based pixel box
    result = tracker.update(next_frame)     # TrackResult(box, score, ...)
"""

__version__ = "0.1.0"

from .config import TrackerConfig  # noqa: E402

__all__ = ["TrackerConfig", "__version__"]
