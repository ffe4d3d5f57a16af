"""The observation model as cues (smtmvt.cues): which cues a configuration
turns on, and a cue added from outside the package with no change elsewhere."""

from __future__ import annotations

import numpy as np
import pytest

from smtmvt import Tracker, TrackerConfig
from smtmvt.cues import CUES, Cue, Scene, cue_names, register_cue, unregister_cue
from smtmvt.demo import make_demo_sequence
from smtmvt.geometry import box_to_affine


class Rightward(Cue):
    """A toy cue: the further right a candidate's centre, the lower its cost
    (``weight`` per working-frame pixel behind the rightmost candidate)."""

    name = "rightward"

    def __init__(self, weight: float) -> None:
        self.weight = weight
        self.learned = 0

    def cost(self, scene: Scene) -> np.ndarray:
        x = scene.states[:, 4]
        return self.weight * (x.max() - x)

    def learn(self, scene, choice) -> None:
        self.learned += 1


@pytest.fixture
def rightward():
    register_cue("rightward", lambda config, weight: Rightward(weight) if weight else None)
    yield
    unregister_cue("rightward")


@pytest.fixture(scope="module")
def demo():
    return make_demo_sequence(n_frames=4)


def test_the_default_cues_and_the_papers_sparse_cue_alone():
    assert list(CUES)[:7] == ["sparse", "background", "anchor", "motion", "scale_push", "foreground", "correlation"]
    assert cue_names(TrackerConfig()) == ["sparse", "anchor", "motion", "foreground", "correlation"]
    assert cue_names(TrackerConfig.paper()) == ["sparse"]
    on = TrackerConfig(background_weight=0.5, scale_push=0.1, anchor_weight=0.0)
    assert cue_names(on) == ["sparse", "background", "motion", "scale_push", "foreground", "correlation"]
    # the correlation filter is a cue for either of its uses (its cost, its particles)
    assert "correlation" in cue_names(TrackerConfig(correlation_weight=0.0, correlation_particles=0.1))
    assert "correlation" not in cue_names(TrackerConfig(correlation_weight=0.0, correlation_particles=0.0))


def test_a_tracker_lists_its_cues_after_init(demo):
    t = Tracker(TrackerConfig.paper(n_particles=20, seed=0))
    with pytest.raises(RuntimeError, match="not initialized"):
        _ = t.cues
    t.init(demo.frames[0], demo.groundtruth[0])
    assert [c.name for c in t.cues] == ["sparse"]


def test_a_cue_registered_from_outside_changes_the_chosen_box(demo, rightward):
    """Registered (no weight: off), the toy cue changes nothing; weighted, it
    enters every candidate's likelihood, the chosen boxes move right, and it
    learns after each frame."""
    cfg = TrackerConfig(n_particles=60, seed=0, report_read_size=0)  # the chosen state's own box
    assert cue_names(cfg) == cue_names(cfg, {"rightward": 0.0})  # off unless weighted

    def run(**kwargs):
        t = Tracker(cfg, **kwargs)
        t.init(demo.frames[0], demo.groundtruth[0])
        results = [t.update_detailed(f) for f in demo.frames[1:]]
        return t, np.array([r.box for r, _ in results]), [d for _, d in results]

    _, plain, _ = run()
    t, pushed, details = run(cue_weights={"rightward": 1.0})
    assert [c.name for c in t.cues][-1] == "rightward"
    assert t.cues[-1].learned == len(demo.frames) - 1
    assert np.all(pushed[:, 0] > plain[:, 0])  # every box further right
    # its cost is in the likelihood: among the coded particles, the rightmost is favoured
    d = details[0]
    p, x = d.observation.likelihood[: len(d.particles)], d.particles[:, 4]
    assert x[int(np.argmax(p))] > np.median(x)


def test_cue_weights_name_registered_cues_outside_the_configuration(rightward):
    with pytest.raises(ValueError, match="no cue named"):
        Tracker(TrackerConfig(), cue_weights={"leftward": 1.0})
    with pytest.raises(ValueError, match="weighted by the configuration"):
        Tracker(TrackerConfig(), cue_weights={"anchor": 1.0})
    with pytest.raises(ValueError, match="built-in"):
        unregister_cue("anchor")


def test_the_frame_detail_holds_each_cues_costs_of_particles_and_probes(demo, rightward):
    """``FrameDetail.cue_costs``: every cue but the sparse one, in the tracker's order,
    each cost over the particles then the probes, the value the cue computed."""
    t = Tracker(TrackerConfig(n_particles=30, seed=0), cue_weights={"rightward": 0.5})
    t.init(demo.frames[0], demo.groundtruth[0])
    probes = np.array([demo.groundtruth[1], demo.groundtruth[1] + [5.0, 0.0, 0.0, 0.0]])
    _, d = t.update_detailed(demo.frames[1], probes)
    assert list(d.cue_costs) == [c.name for c in t.cues if c.name != "sparse"]
    n = len(d.particles)
    x = np.concatenate([d.particles[:, 4], box_to_affine(probes * np.tile(d.scale, 2))[:, 4]])
    np.testing.assert_allclose(d.cue_costs["rightward"], 0.5 * (x.max() - x))
    assert all(c is None or np.shape(c) == (n + 2,) for c in d.cue_costs.values())
