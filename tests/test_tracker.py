"""The Tracker object end to end: API, determinism, bad input, real tracking."""

import cv2
import numpy as np
import pytest

from smtmvt import Tracker, TrackerConfig
from smtmvt.demo import make_demo_sequence
from smtmvt.evaluation.metrics import overlap_ratio

FAST = TrackerConfig(n_particles=100, seed=0)


@pytest.fixture(scope="module")
def demo():
    return make_demo_sequence(n_frames=120)


def _centre(b):
    """Centres ``(m, 2)`` of 0-based boxes ``(m, 4)``, OTB's ``x + (w - 1) / 2``."""
    return np.column_stack([b[:, 0] + (b[:, 2] - 1) / 2, b[:, 1] + (b[:, 3] - 1) / 2])


def _track(frames, box, config):
    t = Tracker(config)
    t.init(frames[0], box)
    out = [tuple(box)]
    for f in frames[1:]:
        r = t.update(f)
        assert np.all(np.isfinite(r.box)) and 0.0 <= r.score <= 1.0
        out.append(r.box)
    return np.array(out)


def test_same_seed_same_boxes_other_seed_other_boxes(demo):
    a = _track(demo.frames[:8], demo.groundtruth[0], FAST)
    b = _track(demo.frames[:8], demo.groundtruth[0], FAST)
    c = _track(demo.frames[:8], demo.groundtruth[0], FAST.replace(seed=1))
    np.testing.assert_array_equal(a, b)
    assert not np.array_equal(a, c)


def test_tracks_demo_sequence(demo):
    """The built-in sequence (scale, rotation, illumination, occlusion, blur).

    Measured with the defaults (400 particles, seed 0; stop 44): mean
    overlap 0.839 (0.810 with ``report_scale`` 1) and 8 template
    replacements (frames 5, 11, 28, 52, 61, 66, 72, 76). Earlier defaults:
    stop 24's 0.767 and 8; without the coarse view (stop 24's default) 0.807
    and 11; without the motion term (stop 22's default) 0.764 (0.757 with
    report_aspect 0) and 8; thresholds set below them with margin (kept from
    the earlier 0.785 and 11: 0.72 and 5). A tracker whose template update
    never replaces a template fails the second assertion. With the defaults
    (``bench/demo_seeds.py --seeds 24``, stop 44) the mean over seeds 0-23
    is 0.822 (0.797 with ``report_scale`` 1); seed 15 loses the target at
    the occlusion (0.525), the others keep it (lowest 0.800). Stop 24's
    default kept all 24 (0.795; without the coarse view 0.778). Stop
    16's default, over seeds 0-7: 0.811, 0.747, 0.808, 0.792, 0.799, 0.791,
    0.775, 0.789: every seed keeps the target
    through the occlusion near frame 78 (without the foreground term half of
    them lose it: 0.785, 0.471, 0.786, 0.495, 0.478, 0.728, 0.471, 0.766).
    """
    t = Tracker(TrackerConfig(seed=0))
    t.init(demo.frames[0], demo.groundtruth[0])
    results = [t.update(f) for f in demo.frames[1:]]
    boxes = np.array([demo.groundtruth[0]] + [r.box for r in results])
    overlap = overlap_ratio(boxes, demo.groundtruth)
    assert overlap.mean() > 0.72, overlap.mean()
    replaced = [r.template_replaced for r in results if r.template_replaced is not None]
    assert len(replaced) >= 5, replaced
    assert 0 not in replaced  # the exact first-frame template is never replaced


def test_static_frame_stays_put(demo):
    f = demo.frames[0]
    boxes = _track([f] * 6, demo.groundtruth[0], FAST)
    assert overlap_ratio(boxes, np.repeat(demo.groundtruth[:1], 6, axis=0)).min() > 0.8


@pytest.mark.parametrize("box", [(10, 10, 0, 20), (10, 10, 20, -3), (np.nan, 1, 2, 3), (1, 2, 3)])
def test_init_rejects_bad_box(demo, box):
    with pytest.raises(ValueError, match="box"):
        Tracker(FAST).init(demo.frames[0], box)


def test_init_rejects_box_mostly_outside(demo):
    with pytest.raises(ValueError, match="mostly outside"):
        Tracker(FAST).init(demo.frames[0], (-40, -40, 50, 50))


def test_update_before_init():
    with pytest.raises(RuntimeError, match="before init"):
        Tracker(FAST).update(np.zeros((20, 20), np.uint8))


@pytest.mark.parametrize(
    "frame,match",
    [
        (np.zeros((5, 5, 2), np.uint8), "shape"),
        (np.full((30, 30), np.nan, np.float32), "NaN"),
        (np.zeros((30, 30), np.int64), "dtype"),
    ],
)
def test_bad_frames_name_the_problem(demo, frame, match):
    t = Tracker(FAST)
    t.init(demo.frames[0], demo.groundtruth[0])
    with pytest.raises(ValueError, match=match):
        t.update(frame)


@pytest.mark.parametrize("detailed", [False, True])
def test_a_frame_of_another_size_is_refused_and_changes_nothing(demo, detailed):
    """Boxes refer to init's pixel grid: a frame of another size is refused, naming both
    sizes, and the tracker goes on as if it had never seen it."""
    frames = demo.frames[:3]
    h, w = frames[0].shape[:2]
    t, ref = Tracker(FAST), Tracker(FAST)
    for tr in (t, ref):
        tr.init(frames[0], demo.groundtruth[0])
    r1 = t.update(frames[1])
    assert ref.update(frames[1]).box == r1.box
    for other in (frames[2][: h - 40], frames[2][:, : w - 1], cv2.resize(frames[2], (2 * w, 2 * h))):
        oh, ow = other.shape[:2]
        with pytest.raises(ValueError, match=rf"{ow}x{oh} pixels but init's frame was {w}x{h}"):
            t.update_detailed(other) if detailed else t.update(other)
    assert t.box == r1.box
    np.testing.assert_array_equal(t.update(frames[2]).box, ref.update(frames[2]).box)


def test_gray_and_16bit_frames_track_like_8bit(demo):
    gray8 = demo.frames[:6].mean(axis=3).astype(np.uint8)
    gray16 = gray8.astype(np.uint16) * 257
    a = _track(list(gray8), demo.groundtruth[0], FAST)
    b = _track(list(gray16), demo.groundtruth[0], FAST)
    np.testing.assert_allclose(a, b, atol=1e-6)
    # measured 0.910 (seeds 1-3: 0.881, 0.937, 0.894); a box that never moves scores 0.467
    assert overlap_ratio(a, demo.groundtruth[:6]).mean() > 0.8


def test_blank_and_partly_outside_never_nan(demo):
    t = Tracker(FAST)
    t.init(demo.frames[0], (300.0, 200.0, 40.0, 40.0))  # partly outside a 320x240 frame
    for f in [np.zeros_like(demo.frames[0])] * 3 + list(demo.frames[1:3]):
        r = t.update(f)
        assert np.all(np.isfinite(r.box)) and np.isfinite(r.score)


def test_reinit_restarts_on_new_target(demo):
    t = Tracker(FAST)
    t.init(demo.frames[0], demo.groundtruth[0])
    t.update(demo.frames[1])
    t.init(demo.frames[0], (20.0, 20.0, 30.0, 30.0))
    assert t.box == (20.0, 20.0, 30.0, 30.0)
    r = t.update(demo.frames[0])
    assert overlap_ratio(np.array([r.box]), np.array([[20.0, 20, 30, 30]]))[0] > 0.7


@pytest.mark.slow
def test_tracks_real_crossing(otb_dir):
    """OTB Crossing (120 frames); the paper reports 0.78 average overlap.

    Measured 0.811 with the defaults (seed 0; 0.807 without the coarse view,
    0.785 earlier, 0.751 before the foreground term, 0.800 before the anchor
    term); threshold set 0.04 below the lowest, kept.
    """
    from smtmvt.data import open_sequence

    seq = open_sequence(otb_dir / "Crossing")
    boxes = _track([seq[i] for i in range(len(seq))], seq.first_box, TrackerConfig(seed=0))
    overlap = overlap_ratio(boxes, seq.groundtruth)
    assert overlap.mean() > 0.71, overlap.mean()


def test_prepare_frame_keeps_the_channel_count_it_is_given():
    from smtmvt.preprocess import prepare_frame

    rgb = np.zeros((20, 30, 3), np.uint8)
    rgb[..., 0] = 200
    gray_as_rgb = np.repeat(np.arange(600, dtype=np.uint8).reshape(20, 30)[..., None], 3, axis=2)
    assert prepare_frame(rgb).color.shape == (20, 30, 3)
    assert prepare_frame(gray_as_rgb).color.shape == (20, 30, 1)
    assert prepare_frame(gray_as_rgb, channels=3).color.shape == (20, 30, 3)
    one = prepare_frame(rgb, channels=1)
    assert one.color.shape == (20, 30, 1)
    np.testing.assert_allclose(one.color[..., 0], 200 / 255 * 0.299, atol=2e-3)


@pytest.mark.parametrize(
    "name,views", [("l1t", ("intensity",)), ("mtt", ("intensity",)), ("mtmvt-ls", ("intensity", "color", "hog", "lbp"))]
)
def test_comparison_models_track_in_the_same_filter(demo, name, views):
    """The paper's comparison models as observation models of our particle filter."""
    from smtmvt.evaluation.trackers import make_tracker

    paper = TrackerConfig.paper(seed=0)
    cfg = paper.replace(model=name, views=views, n_particles=60)
    boxes = _track(demo.frames[:10], demo.groundtruth[0], cfg)
    assert overlap_ratio(boxes, demo.groundtruth[:10]).mean() > 0.5
    # A different observation model really ran: same particles (same seed), other codes.
    residuals = {}
    for model, v in ((name, views), ("smtmvt", views)):
        t = Tracker(paper.replace(model=model, views=v, n_particles=60))
        t.init(demo.frames[0], demo.groundtruth[0])
        residuals[model] = t.update(demo.frames[1]).residual
    assert residuals[name] != pytest.approx(residuals["smtmvt"], rel=1e-6)
    adapter = make_tracker(f"smtmvt-{name}", seed=0)
    assert adapter.config.model == name and adapter.config.views == views


@pytest.mark.parametrize("name,views", [("mtt", ("intensity",)), ("mtmvt-ls", ("intensity", "color", "hog", "lbp"))])
def test_comparison_models_code_every_valid_candidate(demo, name, views):
    """Bounded coding is exact only for SMTMVT's per-candidate model (solvers.BOUNDED_CODING):
    the comparison models code every valid candidate, and no view is deferred."""
    t = Tracker(TrackerConfig(model=name, views=views, n_particles=80, seed=0))
    t.init(demo.frames[0], demo.groundtruth[0])
    for frame in demo.frames[1:4]:
        _, detail = t.update_detailed(frame)
        obs = detail.observation
        valid = obs.likelihood > 0
        assert valid.sum() > 40 and obs.coded[valid].all() and obs.complete.all()
    smtmvt = Tracker(TrackerConfig(n_particles=80, seed=0))
    smtmvt.init(demo.frames[0], demo.groundtruth[0])
    for frame in demo.frames[1:4]:
        _, detail = smtmvt.update_detailed(frame)
    assert not detail.observation.coded.all()  # SMTMVT does skip candidates here


def test_unknown_model_is_rejected():
    with pytest.raises(ValueError, match="model"):
        TrackerConfig(model="nope")


def test_view_weights_of_one_change_nothing(demo):
    a = _track(demo.frames[:6], demo.groundtruth[0], FAST)
    b = _track(demo.frames[:6], demo.groundtruth[0], FAST.replace(view_weights=(1,) * len(FAST.views)))
    np.testing.assert_array_equal(a, b)


@pytest.mark.parametrize("weights", [(1, 1, 1), (1, 0, 1, 1), (1, -1, 1, 1), (1, float("nan"), 1, 1)])
def test_view_weights_are_checked(weights):
    with pytest.raises(ValueError, match="view_weights"):
        TrackerConfig(view_weights=weights)


def test_view_weights_weigh_each_views_residual(demo):
    """The chosen candidate's residual is sum_k w_k ||D_k c_k - x_k||^2 on the unit-norm
    views and templates (its codes come from the problem scaled by sqrt(w_k)), and the
    templates stay unit-norm (the update rule's angles assume it)."""
    w = (2.0, 0.25, 0.75, 0.5, 1.0)
    assert len(w) == len(FAST.views)
    t = Tracker(FAST.replace(view_weights=w))
    t.init(demo.frames[0], demo.groundtruth[0])
    D = [Dk.copy() for Dk in t._sparse.templates.dictionaries]
    result, detail = t.update_detailed(demo.frames[1])
    C = detail.observation.C[:, :, detail.best]
    parts = [wk * float(np.sum((Dk @ C[k] - x) ** 2)) for k, (wk, Dk, x) in enumerate(zip(w, D, detail.best_views))]
    assert result.residual == pytest.approx(sum(parts), rel=1e-5)
    assert parts[0] != pytest.approx(sum(parts) / len(w), rel=0.05)  # the views are not all alike
    for Dk in t._sparse.templates.dictionaries:
        np.testing.assert_allclose(np.linalg.norm(Dk, axis=0), 1.0, atol=1e-5)


def test_compiled_solver_tracks_like_the_numpy_engine(demo, monkeypatch):
    """The compiled ADMM engine (the default) and the numpy one run the same
    iteration: 30 frames of the demo give the same boxes to rounding."""
    import smtmvt.solvers.smtmvt as solver_module

    config = TrackerConfig(seed=3)
    compiled = _track(demo.frames[:30], demo.groundtruth[0], config)
    monkeypatch.setattr(solver_module, "run_candidates", solver_module._admm_batched)
    batched = _track(demo.frames[:30], demo.groundtruth[0], config)
    assert np.max(np.abs(compiled - batched)) <= 1e-6
    assert np.ptp(compiled[:, 0]) > 5  # the target moved: a real comparison


def test_full_shape_pull_keeps_the_first_boxes_aspect(demo):
    """With shape_pull 1 every frame starts from the first box's aspect ratio and skew: the
    chosen box's aspect differs from it by one frame's noise only (std 1.4% in log aspect):
    measured 0.037 at most over 25 demo frames, against 0.136 without the pull."""
    boxes = _track(demo.frames[:25], demo.groundtruth[0], FAST.replace(shape_pull=1.0, report_aspect=0.0))
    aspect = np.log(boxes[:, 3] / boxes[:, 2])
    assert np.abs(aspect - aspect[0]).max() < 0.06
    with pytest.raises(ValueError, match="shape_pull"):
        TrackerConfig(shape_pull=1.5)


def test_aspect_std_zero_tracks_with_the_first_boxes_aspect(demo):
    """aspect_std 0: the random walk changes the box's scale, never its aspect
    (the skew terms alone move it, by far less than 1%); the free walk's boxes
    change aspect by several percent over the same frames."""
    state = FAST.replace(report_aspect=0.0, report_scale=1.0)  # the states' boxes, not reshaped for reporting
    fixed = _track(demo.frames[:25], demo.groundtruth[0], state.replace(aspect_std=0.0))
    free = _track(demo.frames[:25], demo.groundtruth[0], state)
    drift = [np.abs(np.log(b[:, 3] / b[:, 2]) - np.log(b[0, 3] / b[0, 2])).max() for b in (fixed, free)]
    assert drift[0] < 0.005 < 0.03 < drift[1]
    assert np.ptp(fixed[:, 2]) > 0.5  # the scale still moved
    with pytest.raises(ValueError, match="aspect_std"):
        TrackerConfig(aspect_std=-0.01)


def test_report_aspect_reshapes_only_the_reported_box(demo):
    """report_aspect changes the box reported, not the tracking: the same centres
    and areas at 0 (the state's box), 0.5 and 1, and at 1 the first box's aspect
    ratio on every frame (the state's own drifts by several percent here)."""
    gt0 = demo.groundtruth[0]
    # the state's box reshaped (report_read_size reads another size: tests/test_correlation_scales.py)
    boxes = {
        f: _track(demo.frames[:20], gt0, FAST.replace(report_aspect=f, report_read_size=0)) for f in (0.0, 0.5, 1.0)
    }

    log_aspect = {f: np.log(b[:, 3] / b[:, 2]) for f, b in boxes.items()}
    first = np.log(gt0[3] / gt0[2])
    for f in (0.5, 1.0):
        np.testing.assert_allclose(_centre(boxes[f]), _centre(boxes[0.0]), atol=1e-9)
        np.testing.assert_allclose(boxes[f][:, 2] * boxes[f][:, 3], boxes[0.0][:, 2] * boxes[0.0][:, 3], rtol=1e-9)
        np.testing.assert_allclose(log_aspect[f], (1 - f) * log_aspect[0.0] + f * first, atol=1e-9)
    assert np.abs(log_aspect[0.0] - first).max() > 0.03
    assert TrackerConfig().report_aspect == 1.0 and TrackerConfig.paper().report_aspect == 0.0
    with pytest.raises(ValueError, match="report_aspect"):
        TrackerConfig(report_aspect=1.5)


def test_report_scale_scales_only_the_reported_box(demo):
    """report_scale changes the box reported, not the tracking: the same centres,
    aspect ratios and sides times the factor on every frame after the first
    (the first box is the one given)."""
    gt0 = demo.groundtruth[0]
    boxes = {f: _track(demo.frames[:12], gt0, FAST.replace(report_scale=f, report_read_size=0)) for f in (1.0, 1.1)}

    np.testing.assert_allclose(_centre(boxes[1.1]), _centre(boxes[1.0]), atol=1e-9)
    np.testing.assert_allclose(boxes[1.1][1:, 2:], 1.1 * boxes[1.0][1:, 2:], rtol=1e-9)
    np.testing.assert_array_equal(boxes[1.1][0], boxes[1.0][0])
    assert TrackerConfig.paper().report_scale == 1.0
    with pytest.raises(ValueError, match="report_scale"):
        TrackerConfig(report_scale=0.0)


def test_velocity_fraction_moves_that_share_of_the_particles(demo):
    """velocity_fraction 0.5: every other particle is moved by the velocity term, the
    others stay (no noise here, so the motion is the shift alone)."""
    # none placed at the correlation filter's peak (they would replace the last particle)
    cfg = FAST.replace(
        velocity=1.0, velocity_fraction=0.5, affine_std=(0.0,) * 6, n_particles=10, correlation_particles=0.0
    )
    t = Tracker(cfg)
    t.init(demo.frames[0], demo.groundtruth[0])
    state = t._state.copy()
    t._motion.velocity = np.array([6.0, -2.0])
    _, detail = t.update_detailed(demo.frames[1])
    moved = detail.particles[:, 4:] - state[4:]
    np.testing.assert_allclose(moved[1::2], np.tile([6.0, -2.0], (5, 1)))
    np.testing.assert_allclose(moved[0::2], 0.0)
    with pytest.raises(ValueError, match="velocity_fraction"):
        TrackerConfig(velocity_fraction=-0.1)


def test_color_size_samples_the_color_view_at_its_own_size(demo):
    """``color_size`` equal to the feature size is the default; a smaller one
    samples the color patches (and so the templates) at that size."""
    frames, box = demo.frames[:6], demo.groundtruth[0]
    plain = _track(frames, box, FAST)
    np.testing.assert_array_equal(plain, _track(frames, box, FAST.replace(color_size=(32, 32))))
    t = Tracker(FAST.replace(color_size=(16, 12)))
    t.init(frames[0], box)
    patches = t._sampler.patches(t._prepare(frames[1], "frame", t._channels), t._motion.particles[:5], 1.0, t._work_box)
    assert patches.color.shape == (5, 16, 12, 3) and patches.raw.shape == (5, 32, 32)
    ref = Tracker(FAST)
    ref.init(frames[0], box)
    d16, d32 = t._sparse.templates.dictionaries[1], ref._sparse.templates.dictionaries[1]  # the color view
    assert d16.shape == d32.shape and not np.allclose(d16, d32, atol=1e-3)
    with pytest.raises(ValueError, match="color_size"):
        TrackerConfig(color_size=(1, 16))


def test_search_expand_follows_the_residual_over_its_median(demo):
    t = Tracker(FAST.replace(search_expand=3.0))
    t.init(demo.frames[0], demo.groundtruth[0])
    factors = [t._motion.search_expand(r) for r in (1.0, 1.0, 1.0, 2.5, 5.0, 0.5)]
    # medians 1, 1, 1, 1, 1, 1: the factor is the residual's ratio to them, within [1, 3]
    assert factors == [1.0, 1.0, 1.0, 2.5, 3.0, 1.0]
    off = Tracker(FAST)
    off.init(demo.frames[0], demo.groundtruth[0])
    assert off._motion.search_expand(10.0) == 1.0
    with pytest.raises(ValueError, match="search_expand"):
        TrackerConfig(search_expand=0.5)


def test_search_expand_widens_the_translation_of_the_next_frames_particles(demo):
    """The same draws with the factor 1, 2 and 3: the particles' translations move
    by equal steps (base + k * noise), their shapes not at all."""
    particles = []
    for k in (1.0, 2.0, 3.0):
        t = Tracker(FAST.replace(search_expand=3.0))
        t.init(demo.frames[0], demo.groundtruth[0])
        t._motion.expand = k
        particles.append(t.update_detailed(demo.frames[1])[1].particles)
    p1, p2, p3 = particles
    np.testing.assert_allclose(p3[:, 4:] - p2[:, 4:], p2[:, 4:] - p1[:, 4:], atol=1e-9)
    assert np.abs(p2[:, 4:] - p1[:, 4:]).max() > 1.0
    np.testing.assert_array_equal(p1[:, :4], p3[:, :4])


@pytest.mark.parametrize("gray_frames", [False, True])
def test_color_and_gray_patches_sampled_together_equal_each_sampled_alone(gray_frames):
    """On cropped planes the tracker samples the color channels and the gray
    plane as one 4-channel plane (a gray frame's one plane once): bit for bit
    the patches of smoothing and sampling each plane alone."""
    from smtmvt.motion import propagate
    from smtmvt.preprocess import sample_window, smooth
    from smtmvt.sampling import plane_extent
    from smtmvt.warp import remap_patches, sampling_grid

    demo = make_demo_sequence(n_frames=2)
    frames = [f.mean(axis=2).astype(np.uint8) if gray_frames else f for f in demo.frames]
    t = Tracker(TrackerConfig(n_particles=80, seed=1, crop_planes=True))
    t.init(frames[0], demo.groundtruth[0])
    states = propagate(np.repeat(t._state[None], 80, axis=0), t.config.affine_std, np.random.default_rng(0))
    t._frame_index = 1  # not a frame of config.crop_refresh's whole planes
    prepared = t._prepare(frames[1], "f", t._channels, 1.0, states)
    assert prepared.color.shape[2] == (1 if gray_frames else 3) and prepared.full_shape is not None
    patches = t._sampler.patches(prepared, states, 1.0, t._work_box)
    _, sigma, _ = t._sampler.smoothing(1.0, t._work_box)
    assert sigma > 1  # the anti-aliasing blur is on
    x0, y0, x1, y1 = plane_extent(states, 1.0)
    ox, oy = prepared.origin
    win = sample_window((x0 - ox, y0 - oy, x1 - ox, y1 - oy), prepared.shape)
    X, Y = sampling_grid(states, t.config.feature_size, 1.0, prepared.origin)
    np.testing.assert_array_equal(patches.color, remap_patches(smooth(prepared.color, sigma, win), X, Y))
    np.testing.assert_array_equal(patches.raw, remap_patches(smooth(prepared.gray, sigma, win), X, Y))


def test_intensity_factor_sets_the_intensity_template_size():
    demo = make_demo_sequence(n_frames=3)
    sizes = []
    for factor in (None, 0.5):
        t = Tracker(TrackerConfig(n_particles=30, seed=0, intensity_factor=factor))
        t.init(demo.frames[0], demo.groundtruth[0])
        t.update(demo.frames[1])
        sizes.append(t._sampler.intensity_size)
        assert t._sparse.templates.dictionaries[0].shape[0] == sizes[-1][0] * sizes[-1][1]
    w, h = demo.groundtruth[0][2:]
    assert sizes[1] == (int(np.floor(h / 2 + 0.5)), int(np.floor(w / 2 + 0.5))) and sizes[0] != sizes[1]
    with pytest.raises(ValueError, match="intensity_factor"):
        TrackerConfig(intensity_factor=-1.0)


def test_stage_timings_are_disjoint(demo):
    """Each stage's time is counted once: a block timed inside a block of the same
    stage (a deferred view's features inside the likelihood's bookkeeping) is not
    added again, so the stages' times sum to no more than the updates' wall time."""
    import time

    frames = demo.frames
    t = Tracker(TrackerConfig(n_particles=100, seed=1, deferred_views=("hog", "lbp")))
    t.init(frames[0], demo.groundtruth[0])
    t.timings.clear()
    t0 = time.perf_counter()
    with t._timed("features"):
        with t._timed("features"):
            time.sleep(0.05)
    assert t.timings["features"] <= time.perf_counter() - t0  # once, not twice
    t.timings.clear()
    t0 = time.perf_counter()
    for f in frames[1:6]:
        t.update(f)
    wall = time.perf_counter() - t0
    assert {"warp", "features", "solve", "likelihood"} <= set(t.timings)
    assert sum(t.timings.values()) <= wall


def _first_intensity_template(frame, box, plane):
    t = Tracker(TrackerConfig(n_particles=10, n_templates=1, seed=0, intensity_plane=plane))
    t.init(frame, box)
    return t._sparse.templates.dictionaries[t._sparse.intensity_index][:, 0]


def test_intensity_planes_keep_what_each_is_invariant_to():
    """``intensity_plane``: "gray" samples the gray frame (its zero-mean,
    unit-norm template ignores a brightness offset and a gain); "dog" is a
    difference of Gaussians of the frame's gamma ``gray ** 0.2`` (a gain
    multiplies it by ``gain ** 0.2``, so the template stays; an offset does
    not); the three planes give three different templates."""
    rng = np.random.default_rng(0)
    fine, coarse = (cv2.GaussianBlur(rng.random((120, 160)).astype(np.float32), (0, 0), s) for s in (1.0, 6.0))
    frame = fine / fine.std() + coarse / coarse.std()  # texture at the frame's and the template's scales
    frame = 0.02 + 0.48 * (frame - frame.min()) / np.ptp(frame)  # in [0.02, 0.5]
    box = (50.0, 40.0, 40.0, 30.0)
    t = {p: _first_intensity_template(frame, box, p) for p in ("tan_triggs", "gray", "dog")}
    for a, b in (("tan_triggs", "gray"), ("tan_triggs", "dog"), ("gray", "dog")):
        assert float(t[a] @ t[b]) < 0.95, (a, b)
    np.testing.assert_allclose(_first_intensity_template(0.5 * frame + 0.15, box, "gray"), t["gray"], atol=1e-4)
    np.testing.assert_allclose(_first_intensity_template(0.5 * frame, box, "dog"), t["dog"], atol=1e-4)
    assert float(_first_intensity_template(frame + 0.5, box, "dog") @ t["dog"]) < 0.999
    with pytest.raises(ValueError, match="intensity_plane"):
        TrackerConfig(intensity_plane="rgb")


def test_dog_intensity_plane_against_scipy():
    """The "dog" plane is ``G(s) - G(2 s)`` of ``gray ** 0.2`` (scipy's Gaussian
    filter as the reference, away from the borders, where the two differ)."""
    from scipy.ndimage import gaussian_filter

    from smtmvt.preprocess import prepare_frame
    from smtmvt.sampling import Sampler

    rng = np.random.default_rng(1)
    frame = cv2.GaussianBlur(rng.random((90, 110)).astype(np.float32), (0, 0), 1.0)
    frame = 0.05 + 0.9 * (frame - frame.min()) / np.ptp(frame)
    prepared = prepare_frame(frame, "test frame", 1)
    sampler = Sampler(TrackerConfig(intensity_plane="dog"), np.ones(2), (0.0, 0.0, 30.0, 30.0), crop=False)
    sigma = 2.5
    plane = sampler.intensity_plane(prepared, sigma, None)
    g = prepared.gray.astype(np.float64) ** 0.2
    ref = gaussian_filter(g, sigma, truncate=4.0) - gaussian_filter(g, 2 * sigma, truncate=4.0)
    inner = (slice(25, -25), slice(25, -25))
    np.testing.assert_allclose(plane[inner], ref[inner], atol=2e-4 * np.abs(ref[inner]).max())


@pytest.mark.parametrize(
    "box,shown",
    [
        (np.array([-40.0, -40.0, 50.0, 50.0]), "box (-40.0, -40.0, 50.0, 50.0) is mostly outside"),
        (np.array([10.0, 10.0, 0.0, 20.0]), "box (10.0, 10.0, 0.0, 20.0) has zero or negative size"),
        ((np.float64(1), np.nan, 3, 4), "got (1.0, nan, 3.0, 4.0)"),
    ],
)
def test_box_errors_show_plain_numbers(demo, box, shown):
    with pytest.raises(ValueError) as info:
        Tracker(FAST).init(demo.frames[0], box)
    assert shown in str(info.value) and "np." not in str(info.value)
