"""Target templates: the per-view dictionaries ``D^k`` and their update rule.

The rule follows L1T (Mei & Ling 2011), which the paper cites for its update
("similar to L1T"), with SMTMVT's outlier matrix E in the role of L1T's trivial
coefficients:

1. Importance. Each template ``j`` has a weight ``w_j`` (all 1 at start). After
   every frame ``w_j <- w_j * exp(c_j)``, ``c_j`` the best candidate's
   coefficient of template ``j`` averaged over the views; then weights are
   normalized to sum to 1 (L1T).
2. Occlusion. The best candidate's outlier vectors ``e^k`` flag the entries it
   could not explain. If the fraction of non-zero entries of ``e`` (over the
   intensity view when present, else over all views) exceeds
   ``occlusion_fraction`` (0.25, L1-APG's blob threshold), the frame is taken as
   occluded: no template is replaced for this and the next 4 frames (L1-APG
   flags occlusion for 5 frames).
3. Replacement. Let ``j*`` be the template with the largest coefficient. If the
   angle between the best candidate and ``j*`` exceeds ``update_angle`` (60
   degrees by default; L1-APG uses 30 on raw intensities, see
   :class:`smtmvt.config.TrackerConfig`), the appearance has changed: the template of least weight,
   never template 0 (the exact first-frame target), is replaced by the best
   candidate and given the median weight (L1T). The angle is measured, as in
   L1-APG, on the intensity view (``arccos`` of the cosine similarity of the
   normalized vectors); without an intensity view, on the mean cosine over the
   views. The histogram views (color, HOG, LBP) of neighbouring candidates
   differ much more than their intensities: measured on the mean over views, the
   angle exceeded 30 degrees on nearly every frame, and the templates were
   replaced every frame and drifted.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

__all__ = ["TemplateSet", "UpdateDecision"]


@dataclass
class UpdateDecision:
    """What :meth:`TemplateSet.update` decided for one frame."""

    replaced: int | None
    angle: float
    occlusion: float
    occluded: bool


@dataclass
class TemplateSet:
    """Per-view dictionaries and importance weights.

    Attributes
    ----------
    dictionaries : list of K arrays (d_k, N) float32, unit-norm columns.
    weights : (N,) float64 importance weights (sum 1).
    cooldown : frames left during which updates are suspended after occlusion.
    """

    dictionaries: list
    weights: np.ndarray = field(default=None)  # type: ignore[arg-type]  # set in __post_init__
    cooldown: int = 0

    def __post_init__(self):
        n = self.size
        if self.weights is None:
            self.weights = np.full(n, 1.0 / n)

    @property
    def size(self) -> int:
        return self.dictionaries[0].shape[1]

    def update(
        self,
        x,
        c,
        e,
        *,
        update_angle: float,
        occlusion_fraction: float,
        intensity_view: int | None = 0,
        anchor_cos: float = -1.0,
        fixed: int = 1,
    ) -> UpdateDecision:
        """Apply the rule of the module docstring for the frame's best candidate.

        Parameters
        ----------
        x : list of K arrays (d_k,), the best candidate's normalized views.
        c : (K, N) its coefficients.
        e : list of K arrays (d_k,), its outlier vectors.
        update_angle : degrees.
        occlusion_fraction : fraction in [0, 1].
        intensity_view : index of the intensity view in the lists, or None.
        fixed : the first ``fixed`` templates (the first frame's) are never
            replaced (L1T: 1, the exact initial target).
        anchor_cos : drift check against the first template: a template is
            replaced only when the mean over the views of the cosine between
            the candidate and template 0 is at least ``anchor_cos`` (-1: no check).
        """
        c = np.asarray(c, dtype=np.float64)
        mean_c = c.mean(axis=0)
        w = self.weights * np.exp(np.clip(mean_c, -50, 50))
        self.weights = w / w.sum()

        if intensity_view is not None:
            occ = float(np.mean(np.abs(e[intensity_view]) > 0))
        else:
            occ = float(np.mean(np.concatenate([np.abs(ek) > 0 for ek in e])))
        j_star = int(np.argmax(mean_c))
        if intensity_view is not None:
            cos = float(np.dot(x[intensity_view], self.dictionaries[intensity_view][:, j_star]))
        else:
            cos = float(np.mean([float(np.dot(xk, Dk[:, j_star])) for xk, Dk in zip(x, self.dictionaries)]))
        angle = float(np.degrees(np.arccos(np.clip(cos, -1.0, 1.0))))

        occluded = occ > occlusion_fraction
        if occluded:
            self.cooldown = 5
        replaced = None
        anchored = True
        if anchor_cos > -1.0:
            anchored = bool(
                np.mean([float(np.dot(xk, Dk[:, 0])) for xk, Dk in zip(x, self.dictionaries)]) >= anchor_cos
            )
        fixed = max(1, int(fixed))
        if self.cooldown == 0 and angle > update_angle and self.size > fixed and anchored:
            j = fixed + int(np.argmin(self.weights[fixed:]))
            for xk, Dk in zip(x, self.dictionaries):
                Dk[:, j] = xk
            self.weights[j] = np.median(self.weights)
            self.weights /= self.weights.sum()
            replaced = j
        if self.cooldown > 0:
            self.cooldown -= 1
        return UpdateDecision(replaced=replaced, angle=angle, occlusion=occ, occluded=occluded)
