"""The tracker as a `got10k <https://github.com/got-10k/toolkit>`_ ``Tracker``: :class:`SMTMVTGot10k`.

got10k's experiments (``ExperimentOTB``, ``ExperimentGOT10k``, ``ExperimentVOT``, ...)
run it unchanged::

    from got10k.experiments import ExperimentOTB
    from smtmvt.got10k import SMTMVTGot10k

    experiment = ExperimentOTB("path/to/OTB", version=2015)
    experiment.run(SMTMVTGot10k())
    experiment.report(["SMTMVT"])

got10k is not a dependency of smtmvt (it is pinned in ``requirements-dev.txt``
for the tests): it is imported by this module only, which ``import smtmvt``
does not load until ``smtmvt.SMTMVTGot10k`` is first used.

got10k hands ``init`` and ``update`` RGB ``PIL.Image`` frames and the
annotation files' boxes unchanged: OTB's are 1-based, so by default
(``one_based=True``) the box given to ``init`` is made 0-based for
:class:`smtmvt.Tracker` and the boxes returned are 1-based again, as
:func:`smtmvt.data.write_boxes` writes them; ``one_based=False`` passes boxes
as they are (a dataset with 0-based annotations).
"""

from __future__ import annotations

import numpy as np
from got10k.trackers import Tracker as _Got10kTracker

from .config import TrackerConfig
from .data.boxes import ONE_BASED_OFFSET
from .tracker import Tracker, TrackResult

__all__ = ["SMTMVTGot10k"]


class SMTMVTGot10k(_Got10kTracker):
    """:class:`smtmvt.Tracker` as a ``got10k.trackers.Tracker``.

    Parameters
    ----------
    config : TrackerConfig, optional; the defaults when None. A config with a
        seed is deterministic (got10k then runs it once per sequence where it
        repeats stochastic trackers, as on VOT).
    name : the tracker's name in got10k's result and report folders.
    one_based : whether got10k's boxes are 1-based (OTB's annotations), see the module.

    :attr:`tracker` is the :class:`smtmvt.Tracker`, :attr:`result` the last
    :class:`smtmvt.TrackResult` (None before the first ``update``).
    """

    def __init__(self, config: TrackerConfig | None = None, name: str = "SMTMVT", one_based: bool = True) -> None:
        self.tracker = Tracker(config)
        super().__init__(name=name, is_deterministic=self.tracker.config.seed is not None)
        self.offset = ONE_BASED_OFFSET if one_based else np.zeros(4)
        self.result: TrackResult | None = None

    def init(self, image, box) -> None:
        """Start on ``box`` ``(4,)`` ``(x, y, w, h)`` (got10k's: 1-based with
        ``one_based``) of ``image`` (an RGB ``PIL.Image`` or ``(H, W, 3)`` array)."""
        b = np.asarray(box, dtype=np.float64).reshape(-1)
        if b.size != 4:
            raise ValueError(f"SMTMVTGot10k.init: box must be (x, y, w, h), got {box!r}")
        self.result = None
        self.tracker.init(np.asarray(image), b - self.offset)

    def update(self, image) -> np.ndarray:
        """The box ``(4,)`` float64 ``(x, y, w, h)`` in ``image`` (1-based with ``one_based``)."""
        self.result = self.tracker.update(np.asarray(image))
        return np.asarray(self.result.box, dtype=np.float64) + self.offset
