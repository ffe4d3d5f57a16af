"""The observation model as cues: each term of the likelihood one module.

A candidate's likelihood is ``exp(-alpha (r_i + sum_c cost_c(i)))``: ``r_i``
the sparse cue's residual (:mod:`.sparse`, the paper's model), and one cost
per other cue the configuration turns on, in the order of :data:`CUES`:

========================  ==========================  ==================================
cue                       module                      on when
========================  ==========================  ==================================
``sparse``                :mod:`.sparse`              always (the paper's tracker alone)
``background``            :mod:`.background`          ``config.background_weight``
``anchor``                :mod:`.anchor`              ``config.anchor_weight``
``motion``                :mod:`.motion`              ``config.motion_weight``
``scale_push``            :mod:`.scale_push`          ``config.scale_push``
``foreground``            :mod:`.foreground`          ``config.foreground_weight``
``correlation``           :mod:`.correlation`         ``config.correlation_weight`` or
                                                      ``config.correlation_particles``
========================  ==========================  ==================================

What a cue is, and how one is added from outside the package (a test's, an
experiment's), is in :mod:`.base`.
"""

from .anchor import AnchorCue
from .background import BackgroundCue
from .base import BUILT_IN, CUES, Choice, Cue, CueFactory, Scene, Start, make_cues, register_cue, unregister_cue
from .correlation import CorrelationCue
from .foreground import ForegroundCue
from .motion import MotionCue
from .scale_push import ScalePushCue
from .sparse import SparseCue

__all__ = [
    "BUILT_IN",
    "CUES",
    "AnchorCue",
    "BackgroundCue",
    "Choice",
    "CorrelationCue",
    "Cue",
    "CueFactory",
    "ForegroundCue",
    "MotionCue",
    "ScalePushCue",
    "Scene",
    "SparseCue",
    "Start",
    "cue_names",
    "make_cues",
    "register_cue",
    "unregister_cue",
]

for _cue in (SparseCue, BackgroundCue, AnchorCue, MotionCue, ScalePushCue, ForegroundCue, CorrelationCue):
    register_cue(_cue.name, _cue.from_config, built_in=True)


def cue_names(config, cue_weights=None) -> list[str]:
    """The names of the cues ``config`` (and ``cue_weights``) turns on, in order."""
    return [cue.name for cue in make_cues(config, cue_weights)]
