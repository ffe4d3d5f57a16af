"""Tracker configuration: one frozen dataclass holding every parameter.

The model's parameters are the paper's (Javanmardi & Qi, ICME 2018, section
"Experimental Results"): lambda 0.1, gamma 0.25, alpha 30, 400 particles, 10
templates. Where the paper is silent the default is named with its source.
:meth:`TrackerConfig.paper` is the paper's tracker; the defaults differ from
it in how the views are sampled (``scale_normalize``, ``antialias``,
``hog_plane``, ``lbp_plane``), in a 2x2 grid of color histograms
(``color_grid``), in comparing the histograms by their square roots
(``histogram_power``), in a fifth view, the coarse one (``views``), in a
constant-velocity term in the motion model (``velocity``), in a motion term
that weighs each candidate by the random walk's density (``motion_weight``),
in an anchor term toward the first template in the likelihood
(``anchor_weight``), in a foreground term from a color model of the first
frame (``foreground_weight``), in a correlation term from a filter learned
online (``correlation_weight``), in a confidence test on the template update
(``template_learn_gate``), in a wider search once the target seems lost
(``redetect_after``), in computing each frame's planes on the
candidates' window only (``crop_planes``, a speed setting) and the coarse
and HOG views only where the bounds need them (``deferred_views``, a speed
setting), in reporting each box at the first box's aspect ratio
(``report_aspect``) and with its sides 1.03 times the state's
(``report_scale``; the tracking itself is unchanged by either) and in not resizing
frames to 320x240, the best configuration measured.

How each default was chosen, the table of measured changes and the notes
[1] to [45] that the fields cite (mean average overlap over the 18
sequences of ``shared/data/otb`` and ``extra``, later 29 with the held-out
set, over the evaluation's seeds) are in ``docs/experiments.md``: a
field's "docs/experiments.md#nN" is the note [N] there.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any

from .solvers import SOLVERS

__all__ = ["TrackerConfig"]


def _is_gate(gate) -> bool:
    """Whether ``gate`` is a learn gate's ``(b1, b2)``: two factors, each >= 0."""
    return len(gate) == 2 and all(0 <= g for g in gate)


@dataclass(frozen=True)
class TrackerConfig:
    """All parameters of :class:`smtmvt.Tracker`.

    Attributes
    ----------
    lam : float
        Weight of the per-candidate nuclear norm across views (paper: 0.1).
    gamma : float
        Weight of the L1 penalties on C and E (paper: 0.25).
    alpha : float
        Likelihood sharpness, ``p = exp(-alpha * residual)`` (paper: 30).
    n_particles : int
        Number of particles / candidates per frame (paper: 400).
    n_templates : int
        Number of target templates N (paper: 10).
    views : tuple of str
        Names of the views (see :func:`smtmvt.features.available_views`).
        Default the paper's four (intensity, color, HOG, LBP) and a fifth,
        ``"coarse"`` (:mod:`smtmvt.features.coarse`: the gray patch's
        difference of Gaussians at the template's resolution, where the
        intensity view's Tan-Triggs plane keeps the frame's finest band only;
        docs/experiments.md#n29). The template update measures its angle on the intensity
        view whatever the others.
    affine_std : tuple of 6 floats
        Relative standard deviations of the affine random walk
        ``[a11, a12, a21, a22, tx, ty]``; the diagonal terms are perturbed in log
        space, the translation is in pixels and multiplied by the target scale
        ``sc`` (see :mod:`smtmvt.motion`). Default: MTT's OTB setting
        ``[0.005, 0.0005, 0.0005, 0.005, 4, 4]`` with twice its scale and
        translation terms. Measured on six sequences (demo, Crossing, Subway,
        Girl, Jumping, CarDark) with ``update_angle`` 60: translation 8 gave a
        mean overlap of 0.710, translation 6 gave 0.528 (Subway and Jumping,
        with fast motion, were lost). MTT's scale terms 0.005 instead of 0.01,
        with the current default, on the 18 sequences over 3 seeds: 0.540
        against 0.593 (less aspect drift on CarDark 0.56 -> 0.64, Walking2
        0.34 -> 0.49, Bolt 0.39 -> 0.50, but Car4, whose target grows, 0.77 ->
        0.45, Shaking 0.64 -> 0.23, Subway 0.64 -> 0.48).
    translation_power : float
        The translation std is ``affine_std[4:] * sc ** translation_power``
        pixels (``sc`` about the target size over 32): 1 as L1-APG and MTT;
        0.5 lets large targets search fewer pixels (Car4: 27 px per frame at
        1, where the car moves a few). Measured with the default views: 0.517
        against 0.526 (one seed): Car4 0.02 -> 0.37 and Bolt 0.05 -> 0.53,
        but the fast Deer 0.65 -> 0.26; kept at 1.
    aspect_std : float or None
        How the random walk perturbs the box's shape
        (:func:`smtmvt.motion.propagate`). None: ``a11`` and ``a22``
        independently by ``affine_std[0]`` and ``affine_std[3]`` in log space
        (L1-APG, MTT), which moves the log aspect ratio twice as much as the log
        scale. A float: the scale by ``affine_std[0]`` and the log aspect ratio
        ``log(h / w)`` by ``aspect_std``. In the ground truth of the 18
        sequences the log scale strays from the first frame's by 0.04-0.58
        (rms over frames), the log aspect by 0.00-0.18. None, the default
        (0.005 measured in the table of docs/experiments.md, docs/experiments.md#n14).
    narrow_fraction, narrow_scale : float
        A two-scale search: this fraction of the particles is drawn with
        ``narrow_scale`` times every standard deviation of ``affine_std`` (fine
        search around the last state), the others with ``affine_std`` (reach).
        0: one scale, as the paper. Measured on the 18 sequences with 0.5 and
        0.25: 0.550 against 0.568 (see the table of docs/experiments.md); kept at 0.
    estimate : str
        The state reported each frame: ``"best"``, the particle of highest
        likelihood (the paper), or ``"mean"``, the likelihood-weighted mean of
        the particles' affine parameters (less noisy in scale and aspect). At
        alpha 30 the weights are so peaked that the mean is the best particle
        to a thousandth of a pixel (measured on the demo): it matters only
        with a flatter likelihood.
    report_aspect : float in [0, 1]
        The box reported each frame (``TrackResult.box``, :attr:`Tracker.box`)
        is the state's box with its log aspect ratio ``log(h / w)`` moved
        this fraction of the way to the first box's, at the same centre and
        area (:func:`smtmvt.geometry.box_with_aspect`); the particles, the
        templates and the search keep the state's own shape, so the tracking
        is the same whatever the value. 1, the default: the first box's
        aspect ratio (as correlation-filter trackers such as CSRT report
        theirs). 0: the state's box (the paper). On the 18 sequences the
        state's box is taller and narrower than the truth on 15 (docs/experiments.md#n22),
        and the same tracks score 0.621 at 1 against 0.614 at 0 (docs/experiments.md#n23).
    report_scale : float > 0
        The reported box's width and height are then multiplied by this
        factor, about the same centre (:func:`smtmvt.geometry.box_scaled`);
        as with ``report_aspect`` the tracking is the same whatever the
        value. The state's box is smaller than the truth on most sequences
        (the coded residual is flat below the true size and steep above it,
        docs/experiments.md#n42): over the 29 sequences of ``bench/sweep.py``, seeds 0-2,
        the median over sequences of each one's median log size ratio on
        tracked frames is -0.026. Default 1.03, that bias undone
        (``exp(0.026)`` rounded; docs/experiments.md#n45). 1: the state's size (the paper).
    velocity : float
        Constant-velocity term of the motion model: every particle is first
        moved by ``velocity`` times the last frame's displacement of the
        chosen box (0: a pure random walk, as L1-APG and MTT). Default 0.5
        (measured in the table of docs/experiments.md; 0.25 gave 0.568 against 0.593, Shaking
        0.64 -> 0.35 and Subway 0.64 -> 0.49, Walking2 0.34 -> 0.46; 0.75 gave
        0.572, Shaking 0.64 -> 0.48, Subway 0.64 -> 0.47, David 0.68 -> 0.57,
        Walking2 0.34 -> 0.50).
    velocity_fraction : float in [0, 1]
        Fraction of the particles moved by the velocity term, spread evenly
        over the particle indices (resampled copies of one particle are
        adjacent, so each keeps both hypotheses); the others follow the pure
        random walk. 1: all (a constant-velocity model), the default; 0.5
        measured in the table of docs/experiments.md (0.534 against 0.593).
    search_expand : float >= 1
        After a frame whose chosen candidate is explained worse than usual
        (residual ``r`` above the median ``m`` of the residuals chosen so
        far: the target occluded or lost), the next frame's translation std
        is multiplied by ``clip(r / m, 1, search_expand)``, so that the
        particles can reach a target that moved while the box stayed on the
        background. 1: off (the paper), the default (3 measured in the table of
        docs/experiments.md, docs/experiments.md#n14).
    shape_pull : float in [0, 1]
        Mean reversion of the particles' shape (aspect ratio and skew) toward
        the first frame's box (:func:`smtmvt.motion.pull_shape`), applied
        before the noise each frame; 0: a free random walk (the paper), the
        default (0.05 and 0.02 measured in the table of docs/experiments.md, not kept).
    background_weight : float >= 0
        Weight ``beta`` of the background term (:mod:`smtmvt.background`):
        each frame ``background_samples`` boxes of the target's size on a
        ring around its predicted position are seen in the same views as the
        candidates, and a candidate's likelihood is lowered by ``exp(-alpha
        beta (b_max - b_i))``, ``b_i`` its residual over them (a candidate
        like the surroundings, such as a similar object near the target,
        loses). 0: the paper's likelihood, the default (0.15 and 0.5 measured
        in the table of docs/experiments.md, not kept).
    background_samples : int
        Boxes on the background ring (used when ``background_weight`` > 0).
    background_measure : str
        ``b_i`` of the background term: ``"nearest"``, the squared distance
        to the nearest ring box, or ``"nnls"``, the nonnegative least-squares
        residual over them (:func:`smtmvt.background.background_residuals`).
    anchor_weight : float >= 0
        Weight ``mu`` of the anchor term (:mod:`smtmvt.anchor`): each
        candidate's residual in the likelihood gains ``mu`` times its
        nonnegative least-squares residual over the first template alone (the
        exact first-frame target), so that templates that drifted onto the
        background cannot carry the box with them. Default 1 (measured in the
        table of docs/experiments.md: 0.605 against 0.585 without, 6 seeds; 0.594 over 9,
        where 0.5 gives 0.600, not told apart); 0: the paper's
        likelihood.
    foreground_weight : float >= 0
        Weight ``nu`` of the foreground term (:mod:`smtmvt.foreground`): a
        color model of the first frame (the box's colors against its
        surroundings') scores each candidate box by its contrast ``c_i``, the
        mean target probability inside it less that of the ring around it,
        and its residual in the likelihood gains ``nu (1 - c_i)``: nothing
        else in the likelihood says what the target is *not*. Default 1
        (measured in the table of docs/experiments.md, docs/experiments.md#n16); 0: the paper's likelihood.
    correlation_weight : float >= 0
        Weight ``rho`` of the correlation term (:mod:`smtmvt.correlation`): a
        correlation filter over a window about the predicted box, learned from
        the first box and updated from the chosen boxes (at
        ``correlation_rate``, on the frames ``correlation_learn_gate``
        passes), scores each candidate by its response ``r_i`` at the
        candidate's centre, and its residual in the likelihood gains
        ``rho (1 - r_i / r_max)`` (``r_max`` the response's peak over the
        window). Default 0.5
        (measured in the table of docs/experiments.md, docs/experiments.md#n32); 0: the paper's likelihood.
    correlation_particles : float in [0, 1]
        Fraction of the particles placed, each frame, about the peak of the
        correlation filter's response (:func:`smtmvt.motion.place`; the
        peak cell's centre plus normal noise of half a cell's standard
        deviation), after the random walk: a proposal from what the filter
        sees instead of from the last frame's particles alone. They keep the
        shape of the particles they replace (the last ones, where resampling
        puts copies of the best) and are scored like every other particle,
        motion term included. The filter is learned when this or
        ``correlation_weight`` is above 0. Default 0.1, with
        ``correlation_learn_gate`` (docs/experiments.md#n34); alone it gave the same mean
        as 0 over 18 seeds, gaining on sequences without a look-alike and
        losing where the filter's peak jumps to one (docs/experiments.md#n33). 0: the
        paper's random walk.
    correlation_learn_gate : (float, float), each >= 0
        ``(b1, b2)``: the correlation filter learns from a frame's chosen box
        only when that frame's response (over the window about the
        prediction) is confident, its peak at least ``b1`` times and its
        average peak-to-correlation energy at least ``b2`` times their means
        over the frames before (LMCF's criterion, Wang et al., CVPR 2017, with
        its values; :meth:`smtmvt.correlation.CorrelationFilter.confident`).
        Default ``(0.7, 0.45)``, with ``correlation_particles`` 0.1 (docs/experiments.md#n34); ``(0, 0)``: it learns from every frame. (0.6, 0.4) and
        (0.8, 0.5) measured worse on the mean (docs/experiments.md#n35).
    template_learn_gate : (float, float), each >= 0
        ``(b1, b2)``: the template update replaces no template on a frame
        whose correlation response does not pass this gate: LMCF's test of
        ``correlation_learn_gate``, with these factors, on the same response,
        but against the means of the last ``template_learn_memory``
        responses, and with the peak at least ``template_learn_floor`` times
        its mean over all of them; so that a box the filter doubts, an
        occluder or a look-alike, does not enter the dictionaries either. The
        template weights are still updated. No effect without the filter
        (``correlation_weight`` and ``correlation_particles`` 0). Default
        ``(0.7, 0.45)``, the filter's factors (docs/experiments.md#n38); ``(0, 0)``: the
        update's angle alone decides, as in the paper.
    template_learn_memory : int >= 0
        How many responses before a frame's the template gate compares it
        with (0: all of them, as the filter's gate). Default 20: against all
        of them (stop 34) the gate refuses every frame once the response
        weakens slowly (the demo's target growing and turning), and the
        templates stop following the target (docs/experiments.md#n38).
    template_learn_floor : float >= 0
        The template gate also wants the response's peak at least this
        times its mean over all the frames before. Default 0.4: without it a
        lost target's weak response becomes the recent norm and the
        templates learn the background (Car4, docs/experiments.md#n38).
    correlation_rate : float in (0, 1]
        Rate at which the correlation filter blends in the filter trained on
        a chosen box (:meth:`smtmvt.correlation.CorrelationFilter.update`):
        the model becomes ``(1 - rate) model + rate new``. Default 0.02
        (KCF's); 0.04 and 0.01 measured worse on the mean (docs/experiments.md#n35).
    correlation_first : float in [0, 1]
        Share of the first box's filter in the correlation filter's
        response: the response (its term, the peak where particles are
        placed, the learn gate's test) is ``1 - first`` times the learned
        model's plus ``first`` times that of the filter trained on the first
        box and never updated (:meth:`smtmvt.correlation.CorrelationFilter.response`),
        as the anchor term keeps the first template in the likelihood. 0:
        the learned model alone, the default (0.3 measured the same over 18
        seeds, 0.5 lower; docs/experiments.md#n36).
    redetect_after : int >= 0
        A search beyond the random walk's reach once the target seems lost:
        after this many frames in a row whose correlation response peaks
        below ``template_learn_floor`` times its mean over the frames before,
        the filter's response is also taken over the windows about the
        prediction's moved by half and by one box size in the eight
        directions, and about the last state the filter learned from; the
        response over the window centred on their highest peak, where it
        beats the prediction's and passes ``correlation_learn_gate`` against
        the frames before, replaces the prediction's for the frame (its term,
        and the particles placed at its peak, which then take no motion term;
        the velocity restarts at 0). The templates and the filter learn from
        that frame only if the chosen box is within half its size of that
        peak. It only proposes: the likelihood still chooses. It needs the
        responses judged (a learn gate above 0). Default 10 (docs/experiments.md#n40); 3
        also recovered the lost seeds but jumped to the car that hides
        Woman's legs; 0: off, the paper's search.
    motion_weight : float >= 0
        Weight ``w`` of the motion term: each particle's residual in the
        likelihood gains ``w d_i / (2 alpha)``, ``d_i`` the squared length of
        its own random-walk step in translation (from its parent moved by the
        velocity term, in the walk's standard deviations at the parent's
        scale: :func:`smtmvt.motion.translation_distance`), so that ``w = 1``
        multiplies each particle's likelihood by the random walk's Gaussian
        density of its step: the chosen particle is the most probable state
        under the motion model and the views together, not the best explained
        one wherever the search reached. A probe (``update_detailed``), which
        has no parent, is measured from the last state moved by the velocity
        term. Known before coding, like the anchor term. Default 1 (docs/experiments.md#n27: 0.628 against 0.618 without, 18 sequences x 18 seeds); 0: the
        paper's choice. The std is the frame's (widened by
        ``search_expand`` when it is); ``narrow_scale`` is not applied.
    scale_push : float >= 0
        Weight ``beta`` of the scale term: each candidate's residual gains
        ``-beta log(s_i / s)``, ``s_i`` its box's size ``sqrt(w h)`` and ``s``
        the last state's, so that of two candidates that the views explain
        about as well the larger wins (the box otherwise shrinks: a box
        inside the target costs the views little, one that takes in
        background much). Default 0 (off): 0.2 measured no better over 9
        seeds (docs/experiments.md#n42).
    scale_filter : float in [0, 1]
        Share of the way (in log) the chosen state's scale moves to the scale
        filter's estimate (:mod:`smtmvt.scale`, DSST's one-dimensional filter
        over scales at the chosen centre); the particle cloud moves with it.
        The filter learns on the frames the correlation filter learns from.
        Default 0 (off): 0.5 measured 0.682 against 0.693 on the 18 (docs/experiments.md#n43).
    term_views : tuple of str
        The views the anchor and background terms compare (those of ``views``
        among them; a term with none of them is 0). Default intensity, color
        and HOG, as measured. The background term needs them for every
        candidate: while it is on, they are computed for every candidate
        even when in ``deferred_views``; the anchor term is a sum over its
        views, so a deferred one adds its part where it is computed (the
        candidates without it keep a lower bound of the term, as of their
        residual).
    feature_size : (int, int)
        Height, width (pixels) to which each candidate is warped for the HOG,
        LBP and color views.
    intensity_factor : float or None
        Intensity template pixels per first-box pixel
        (:func:`smtmvt.features.intensity_template_size`). None: the paper's
        rule, a third of the box, a half when its shorter side is under 20
        pixels (the default). A larger template is sampled with a smaller
        step, so the anti-aliasing blur is smaller too; its cost grows with
        its area (0.5 on FaceOcc1's 114x162 box: 2.25 times the dimensions,
        a third fewer frames a second). Measured in docs/experiments.md#n21.
    color_size : (int, int) or None
        Height, width (pixels) of the color view's patches when they differ
        from ``feature_size`` (a histogram needs fewer samples than HOG
        and LBP need pixels; the anti-aliasing blur follows the coarser
        step). None: ``feature_size``, the default (16x16 measured in the
        table of docs/experiments.md, not kept).
    model : str
        Observation model, a key of :data:`smtmvt.solvers.SOLVERS`: ``"smtmvt"``
        (the paper's, default) or one of the comparison models of the paper's
        table, ``"l1t"``, ``"mtt"``, ``"mtmvt-ls"``, ``"mtmvt-lad"``, run in the
        same particle filter with their solvers' default weights (L1T and MTT
        are single-view: use them with ``views=("intensity",)``).
    solver : str
        Method of the SMTMVT solver: ``"admm"`` (exact ADMM, converges to the optimum; default)
        or ``"paper"`` (the paper's subgradient step).
    solver_tol : float
        Relative change of the iterates at which the solver stops.
    solver_max_iter : int
        Iteration cap of the solver inside the tracker.
    update_angle : float
        Template update trigger, degrees, on the intensity view (see
        :mod:`smtmvt.templates`). L1-APG's OTB wrapper uses 30 on raw
        intensities; on Tan-Triggs intensities a well-tracked target already
        sits at 35-60 degrees from its templates (measured on Subway,
        Crossing, Girl, CarDark), so 30 replaced a template nearly every
        frame and drifted. Mean overlap on the six sequences above: 30 -> 0.47,
        45 -> 0.50, 60 -> 0.61, never updating -> 0.60 (all with translation
        std 4). With the current views, on the 18 sequences over 3 seeds: 50
        -> 0.537 against 0.593 for 60 (Basketball 0.47 -> 0.18, Shaking 0.64
        -> 0.34; Walking2 0.34 -> 0.61); 70 -> 0.511 (Basketball 0.47 -> 0.05,
        Subway 0.64 -> 0.17, David 0.68 -> 0.36; Singer2 0.45 -> 0.65).
    update_margin : float or None
        None: the trigger is ``update_angle``. A number: ``update_angle`` on
        the first 10 frames, then the median of those frames' angles plus
        ``update_margin`` degrees where that is lower (first-10 medians: 7 on
        Freeman1, 11 on Dog1, 18 on CarDark, 50-57 on Basketball, Bolt and
        Shaking, which a higher trigger lost, 70: see ``update_angle``): the angle of a well-tracked target to its
        templates depends on its texture and size (median 51 degrees on
        Basketball's first 300 frames, 38 on CarDark's), so a fixed trigger
        replaced a template every 4-5 frames on Basketball, Singer2 and
        Soccer and none in 250 frames on CarDark, Dog1 and Freeman1. docs/experiments.md#n28: 20 gives 0.623 against 0.623 over 12 seeds (CarDark 0.59 ->
        0.67, Freeman1 0.45 -> 0.49; Football 0.65 -> 0.61, Dog1 0.74 ->
        0.72, Soccer 0.30 -> 0.26).
    fixed_templates : int
        The first ``fixed_templates`` templates (the first frame's target and
        its jittered copies) are never replaced; L1T keeps only the first.
        Not yet measured on the 18 sequences.
    anchor_cos : float
        Drift check of the template update: the best candidate replaces a
        template only when its mean cosine over the views with the first
        template (the exact initial target) is at least ``anchor_cos``; -1
        disables the check (the paper, L1T). 0.3 measured on the 18
        sequences over 3 seeds: 0.586 against 0.593 (1597 replacements
        instead of 1761; David 0.68 -> 0.61, Singer2 0.45 -> 0.35); kept at -1.
    view_weights : tuple of float or None
        One weight per view (in ``views`` order) on its squared residual, in
        the coding and in the likelihood: each view's candidates and templates
        are scaled by ``sqrt(weight)`` there (the template update still sees
        the unit-norm views). None weighs all views 1 (the paper). Measured on
        the 18 sequences in the table of docs/experiments.md (not kept).
    occlusion_fraction : float
        Fraction of the intensity template flagged by E above which the frame
        is treated as occluded and no template is replaced (L1-APG: 0.25).
    prune_eps : float
        Bounded coding (:func:`smtmvt.likelihood.observe`, SMTMVT's model only:
        the comparison models code every candidate): the candidates left
        uncoded have likelihood bounds summing to at most ``prune_eps`` times
        the best candidate's likelihood. The chosen box is the same as when
        coding all of them; the sum of the resampling weights changes by a
        relative ``prune_eps`` at most. 0 codes every candidate. The tracker
        uses ``min(prune_eps, 0.5 / n_particles)``, so that no skipped particle
        would have been copied by the resampling.
    frame_size : (int, int) or None
        Track on frames resized to ``(width, height)`` pixels (the paper resized
        every frame to 320x240); boxes are mapped back to the input frame.
        None: track at the input size.
    scale_normalize : bool
        Each frame, compute the planes (Tan-Triggs, gray, color) on the frame
        resized so that the target has its initial size in pixels (the
        factor is the initial over the current target scale, within [1/4, 4]).
        Tan-Triggs is a band-pass filter of fixed size in pixels, so without
        this a grown target's views drift away from its first templates,
        and a box smaller than the target matches them better (the demo's
        scale change). False: the planes of the working frame itself (the paper).
    crop_planes : bool
        Compute each frame's planes (gray, color, Tan-Triggs) only where the
        frame's candidates read them (the particles' extent grown by the
        smoothing's reach, :func:`smtmvt.preprocess.plane_window`). The cost
        of a frame then follows the search region, not the frame size.
        Tan-Triggs' contrast equalization takes its statistics as
        ``crop_refresh`` says. True, the default, with ``crop_refresh`` 10
        (stop 18, docs/experiments.md#n20: as accurate as whole planes over 9 seeds, 0.614
        against 0.615, and on Crossing 0.92-0.99 of CSRT's speed against
        0.70-0.79). False: whole frames (the paper). Forced off while
        ``background_weight`` > 0 (the ring reads farther).
    crop_context : float >= 1
        With ``crop_refresh`` 0, Tan-Triggs takes its statistics over the
        current box grown ``crop_context`` times about its centre (stop 15;
        docs/experiments.md#n15 and #n19: it lost the demo's target on half the seeds).
    crop_refresh : int >= 0
        With ``crop_planes``: k >= 1 computes the whole plane on the first
        frame and on every k-th frame after it (as without ``crop_planes``)
        and normalizes the crops of the frames between with that plane's two
        contrast divisors (:func:`smtmvt.features.tan_triggs.tan_triggs_scales`),
        so what the crop holds (an occluder entering the box's
        surroundings, docs/experiments.md#n19) does not move the statistics; 1 is the
        whole-plane tracker. 0: the statistics of ``crop_context``. Default 10.
    antialias : float
        Smooth each plane before sampling it on the patch grids, by a Gaussian
        of ``antialias`` times the sampling step (target size over patch size,
        :meth:`smtmvt.Tracker._views`); 0 samples the planes as they are (the
        paper). Measured on 18 sequences: the sampled Tan-Triggs intensity of
        the true box kept a cosine of 0.55 to the first template instead of
        0.33 (a band-pass image sampled at a third of its resolution aliases),
        and the mean average overlap rose from 0.455 to 0.504. Measured
        again with today's default (stop 17, seeds 3-5): 0 gives 0.581
        against 0.623, though CarDark alone gains 0.56 -> 0.82 (docs/experiments.md#n18);
        1.5 gives 0.623 against 0.621 over 9 seeds and 2 gives 0.588 on seeds
        0-2 (stop 20, docs/experiments.md#n24): 1 stays.
    intensity_plane : str
        Plane the intensity view is sampled from: ``"tan_triggs"`` (the
        paper, the default), ``"gray"`` (the gray frame; the view's
        zero-mean, unit-norm columns as L1-APG's raw intensities) or ``"dog"``
        (Tan-Triggs' gamma and difference of Gaussians at the template's
        resolution: ``G(s) - G(2 s)`` of ``gray ** 0.2``, ``s`` the
        anti-aliasing sigma, instead of the frame's ``G(1) - G(2)`` blurred by
        ``s``, which leaves a narrow band between ``sqrt(1 + s^2)`` and ``sqrt(4
        + s^2)``). docs/experiments.md#n28: "gray" 0.80 -> 0.06 on Car4, "dog" 0.632 against
        0.636 (Walking2 0.37 -> 0.59; David 0.72 -> 0.56).
    hog_plane, lbp_plane : str
        Plane the HOG and the LBP views are computed on: ``"tan_triggs"`` (the
        paper: every view after the illumination normalization) or ``"gray"``
        (the gray frame itself, default: both are normalized per cell or
        block, and LBP is invariant to monotonic changes of the gray levels).
    color_grid : int
        Cells per side of the color view (:func:`smtmvt.features.color.color_view`);
        1 is one histogram of the whole box. On 18 sequences a box shifted by
        half its size matched the first template as well as the true box
        with one histogram (cosines 0.87 and 0.87), better with 4x4 cells
        (0.63 against 0.71). Default 2 (measured in the table of docs/experiments.md, as 3; the
        paper: 1).
    lbp_radius : float
        Radius of the LBP view's neighbours, feature-patch pixels (1 as
        skimage's default; 2 separated a shifted box better in the same
        measurement; tracking with 2: 0.614 over 9 seeds, as the default,
        docs/experiments.md#n21 and #n22).
    histogram_power : float
        The color and LBP histograms are raised to this power before the
        views' normalization (0.5: the Hellinger embedding; 1: the
        histograms, the paper). Default 0.5 (measured in the table of docs/experiments.md).
    deferred_views : tuple of str
        Views computed only for the candidates whose likelihood bound cannot
        be settled without them (:func:`smtmvt.likelihood.observe`, "deferred
        views"): those of them that end ``views``, each computed in turn for
        the candidates that still need it. Default the coarse view, HOG, then
        LBP (docs/experiments.md#n29: the coarse view is computed for a median 226 of the
        400 candidates on Crossing, with the boxes of computing it for all;
        before it, docs/experiments.md#n26:
        on Crossing HOG is computed for about 60-140 of the 400 candidates,
        LBP for about 16; the frame 13-16% faster than with LBP alone, and
        160 of the 162 runs of seeds 0-8 byte-identical). A speed setting: the chosen
        box is the one computing every view would choose from the same
        particles, and the likelihoods the resampling sees differ by the
        bounded-coding rule's ``prune_eps`` at most. () computes every view of
        every candidate. Used with SMTMVT's model and ``prune_eps`` > 0 only.
    blas_threads : int or None
        Threads the BLAS library may use inside :meth:`Tracker.init` and
        :meth:`Tracker.update` (None: leave it alone). The per-frame matrices
        are small (N = 10 templates), where BLAS threading costs more than it
        gives: measured 8x slower with 2 threads on a loaded 2-core machine.
    seed : int or None
        Seed of the particle filter's random generator; the same seed gives the
        same boxes.
    """

    lam: float = 0.1
    gamma: float = 0.25
    alpha: float = 30.0
    n_particles: int = 400
    n_templates: int = 10
    views: tuple = ("intensity", "color", "coarse", "hog", "lbp")
    affine_std: tuple = (0.01, 0.0005, 0.0005, 0.01, 8.0, 8.0)
    translation_power: float = 1.0
    aspect_std: float | None = None
    narrow_fraction: float = 0.0
    narrow_scale: float = 0.25
    estimate: str = "best"
    report_aspect: float = 1.0
    report_scale: float = 1.03
    velocity: float = 0.5
    velocity_fraction: float = 1.0
    search_expand: float = 1.0
    shape_pull: float = 0.0
    background_weight: float = 0.0
    background_samples: int = 12
    background_measure: str = "nearest"
    anchor_weight: float = 1.0
    foreground_weight: float = 1.0
    correlation_weight: float = 0.5
    correlation_particles: float = 0.1
    correlation_learn_gate: tuple[float, float] = (0.7, 0.45)
    template_learn_gate: tuple[float, float] = (0.7, 0.45)
    template_learn_memory: int = 20
    template_learn_floor: float = 0.4
    correlation_rate: float = 0.02
    correlation_first: float = 0.0
    redetect_after: int = 10
    motion_weight: float = 1.0
    scale_push: float = 0.0
    scale_filter: float = 0.0
    term_views: tuple = ("intensity", "color", "hog")
    feature_size: tuple = (32, 32)
    intensity_factor: float | None = None
    color_size: tuple | None = None
    model: str = "smtmvt"
    solver: str = "admm"
    solver_tol: float = 1e-3
    solver_max_iter: int = 200
    update_angle: float = 60.0
    update_margin: float | None = None
    occlusion_fraction: float = 0.25
    fixed_templates: int = 1
    anchor_cos: float = -1.0
    view_weights: tuple | None = None
    prune_eps: float = 1e-3
    frame_size: tuple | None = None
    scale_normalize: bool = True
    crop_planes: bool = True
    crop_context: float = 3.0
    crop_refresh: int = 10
    antialias: float = 1.0
    intensity_plane: str = "tan_triggs"
    hog_plane: str = "gray"
    lbp_plane: str = "gray"
    color_grid: int = 2
    lbp_radius: float = 1.0
    histogram_power: float = 0.5
    deferred_views: tuple = ("coarse", "hog", "lbp")
    blas_threads: int | None = 1
    seed: int | None = 0

    def __post_init__(self):
        checks = {
            "lam": self.lam >= 0,
            "gamma": self.gamma >= 0,
            "alpha": self.alpha > 0,
            "n_particles": int(self.n_particles) >= 1,
            "n_templates": int(self.n_templates) >= 1,
            "views": len(self.views) >= 1,
            "model": self.model in SOLVERS,
            "affine_std": len(self.affine_std) == 6 and all(s >= 0 for s in self.affine_std),
            "feature_size": len(self.feature_size) == 2 and min(self.feature_size) >= 8,
            "color_size": self.color_size is None
            or (len(self.color_size) == 2 and min(self.color_size) >= max(2, int(self.color_grid))),
            "solver_tol": self.solver_tol > 0,
            "solver_max_iter": int(self.solver_max_iter) >= 1,
            "prune_eps": 0 <= self.prune_eps < 1,
            "frame_size": self.frame_size is None or (len(self.frame_size) == 2 and min(self.frame_size) >= 16),
            "antialias": self.antialias >= 0,
            "intensity_plane": self.intensity_plane in ("tan_triggs", "gray", "dog"),
            "hog_plane": self.hog_plane in ("tan_triggs", "gray"),
            "lbp_plane": self.lbp_plane in ("tan_triggs", "gray"),
            "color_grid": int(self.color_grid) >= 1,
            "lbp_radius": self.lbp_radius > 0,
            "histogram_power": self.histogram_power > 0,
            "velocity": 0 <= self.velocity <= 1,
            "report_aspect": 0 <= self.report_aspect <= 1,
            "report_scale": self.report_scale > 0,
            "shape_pull": 0 <= self.shape_pull <= 1,
            "velocity_fraction": 0 <= self.velocity_fraction <= 1,
            "search_expand": self.search_expand >= 1,
            "background_weight": self.background_weight >= 0,
            "background_samples": int(self.background_samples) >= 1,
            "background_measure": self.background_measure in ("nearest", "nnls"),
            "anchor_weight": self.anchor_weight >= 0,
            "foreground_weight": self.foreground_weight >= 0,
            "correlation_weight": self.correlation_weight >= 0,
            "correlation_particles": 0 <= self.correlation_particles <= 1,
            "correlation_learn_gate": _is_gate(self.correlation_learn_gate),
            "template_learn_gate": _is_gate(self.template_learn_gate),
            "template_learn_memory": int(self.template_learn_memory) == self.template_learn_memory
            and self.template_learn_memory >= 0,
            "template_learn_floor": self.template_learn_floor >= 0,
            "correlation_rate": 0 < self.correlation_rate <= 1,
            "correlation_first": 0 <= self.correlation_first <= 1,
            "redetect_after": int(self.redetect_after) == self.redetect_after and self.redetect_after >= 0,
            "motion_weight": self.motion_weight >= 0,
            "scale_push": self.scale_push >= 0,
            "scale_filter": 0 <= self.scale_filter <= 1,
            "estimate": self.estimate in ("best", "mean"),
            "fixed_templates": 1 <= int(self.fixed_templates) <= int(self.n_templates),
            "narrow_fraction": 0 <= self.narrow_fraction <= 1,
            "narrow_scale": self.narrow_scale > 0,
            "translation_power": 0 <= self.translation_power <= 1,
            "crop_context": self.crop_context >= 1,
            "intensity_factor": self.intensity_factor is None or self.intensity_factor > 0,
            "crop_refresh": int(self.crop_refresh) == self.crop_refresh and self.crop_refresh >= 0,
            "aspect_std": self.aspect_std is None or self.aspect_std >= 0,
            "update_margin": self.update_margin is None or self.update_margin >= 0,
        }
        for name, ok in checks.items():
            if not ok:
                raise ValueError(f"TrackerConfig: invalid {name}={getattr(self, name)!r}")
        object.__setattr__(self, "term_views", tuple(self.term_views))
        object.__setattr__(self, "views", tuple(self.views))
        object.__setattr__(self, "deferred_views", tuple(self.deferred_views))
        object.__setattr__(self, "affine_std", tuple(float(s) for s in self.affine_std))
        object.__setattr__(self, "correlation_learn_gate", tuple(float(g) for g in self.correlation_learn_gate))
        object.__setattr__(self, "template_learn_gate", tuple(float(g) for g in self.template_learn_gate))
        object.__setattr__(self, "feature_size", tuple(int(s) for s in self.feature_size))
        if self.color_size is not None:
            object.__setattr__(self, "color_size", tuple(int(s) for s in self.color_size))
        if self.frame_size is not None:
            object.__setattr__(self, "frame_size", tuple(int(s) for s in self.frame_size))
        if self.view_weights is not None:
            weights = tuple(float(w) for w in self.view_weights)
            if len(weights) != len(self.views) or not all(w > 0 and math.isfinite(w) for w in weights):
                raise ValueError(
                    f"TrackerConfig: invalid view_weights={self.view_weights!r}: "
                    f"one positive number per view ({len(self.views)})"
                )
            object.__setattr__(self, "view_weights", weights)

    @classmethod
    def paper(cls, **changes) -> TrackerConfig:
        """The tracker as the paper describes it, with our documented choices where it is silent.

        Paper values: lambda 0.1, gamma 0.25, alpha 30, 400 particles, 10
        templates, the four views, the exact solver of its model. Our choices
        where the paper is silent (measured in the first tracker issue): the
        random walk ``affine_std`` (MTT's with translation 8), the template
        update angle 60 degrees on the intensity view and occlusion fraction
        0.25 (L1T/L1-APG style rule). Frames are resized to 320x240 as in the
        paper's experiments. Every field is spelled out, so the
        defaults of :class:`TrackerConfig` may move on without changing it.
        ``changes`` override fields (e.g. ``seed``).
        """
        base: dict[str, Any] = dict(
            lam=0.1,
            gamma=0.25,
            alpha=30.0,
            n_particles=400,
            n_templates=10,
            views=("intensity", "color", "hog", "lbp"),
            affine_std=(0.01, 0.0005, 0.0005, 0.01, 8.0, 8.0),
            translation_power=1.0,
            aspect_std=None,
            narrow_fraction=0.0,
            narrow_scale=0.25,
            estimate="best",
            report_aspect=0.0,
            report_scale=1.0,
            velocity=0.0,
            velocity_fraction=1.0,
            search_expand=1.0,
            shape_pull=0.0,
            background_weight=0.0,
            background_samples=12,
            background_measure="nearest",
            anchor_weight=0.0,
            foreground_weight=0.0,
            correlation_weight=0.0,
            correlation_particles=0.0,
            correlation_learn_gate=(0.0, 0.0),
            template_learn_gate=(0.0, 0.0),
            template_learn_memory=20,
            template_learn_floor=0.4,
            redetect_after=0,
            motion_weight=0.0,
            scale_push=0.0,
            scale_filter=0.0,
            term_views=("intensity", "color", "hog"),
            feature_size=(32, 32),
            intensity_factor=None,
            color_size=None,
            model="smtmvt",
            solver="admm",
            solver_tol=1e-3,
            solver_max_iter=200,
            update_angle=60.0,
            update_margin=None,
            occlusion_fraction=0.25,
            fixed_templates=1,
            anchor_cos=-1.0,
            view_weights=None,
            frame_size=(320, 240),
            scale_normalize=False,
            crop_planes=False,
            crop_context=3.0,
            crop_refresh=0,
            antialias=0.0,
            intensity_plane="tan_triggs",
            hog_plane="tan_triggs",
            lbp_plane="tan_triggs",
            color_grid=1,
            lbp_radius=1.0,
            histogram_power=1.0,
            deferred_views=("lbp",),
        )
        base.update(changes)
        return cls(**base)

    def replace(self, **changes) -> TrackerConfig:
        """A copy with some fields changed."""
        return replace(self, **changes)
