"""bench/occlusion.py's L1-APG occlusion measure against scikit-image, and the demo's
occluded share against its own geometry."""

import importlib.util
import sys
from pathlib import Path

import numpy as np
import pytest
from skimage import measure, morphology

from smtmvt.demo import make_demo_sequence

_BENCH = Path(__file__).resolve().parents[1] / "bench"
sys.path.insert(0, str(_BENCH))  # occlusion.py imports boxes_md5.py beside it
_spec = importlib.util.spec_from_file_location("occlusion", _BENCH / "occlusion.py")
assert _spec is not None and _spec.loader is not None
occlusion = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(occlusion)


def _reference(e: np.ndarray, shape) -> float:
    """The same measure with scikit-image's closing and labelling (padded: no border erosion)."""
    mask = np.pad((np.abs(e) > 0).reshape(shape), 1)
    closed = morphology.closing(mask, morphology.disk(1))[1:-1, 1:-1]  # disk(1) is the 3x3 cross
    labels = measure.label(closed, connectivity=2)
    return 0.0 if labels.max() == 0 else np.bincount(labels.ravel())[1:].max() / closed.size


@pytest.mark.parametrize("seed", range(6))
def test_largest_closed_blob_matches_scikit_image(seed):
    rng = np.random.default_rng(seed)
    shape = (16, 15)
    e = rng.normal(size=shape[0] * shape[1]) * (rng.random(shape[0] * shape[1]) < 0.15 + 0.1 * seed)
    assert occlusion.largest_closed_blob(e, shape) == pytest.approx(_reference(e, shape))


def test_closing_joins_a_dotted_block_into_one_blob():
    shape = (12, 12)
    m = np.zeros(shape)
    m[2:8:2, 2:10] = 1.0  # three rows of 8, every other row
    # the cross closes the two rows between them except their end pixels (a cross there
    # reaches no set pixel sideways): 3 rows of 8 and 2 of 6, one blob
    assert occlusion.largest_closed_blob(m.ravel(), shape) == pytest.approx((3 * 8 + 2 * 6) / 144)
    assert occlusion.largest_closed_blob(np.zeros(144), shape) == 0.0


def test_the_demo_says_how_much_of_its_target_the_occluder_covers():
    demo = make_demo_sequence()
    share = demo.occluded_share
    first, last = demo.events["occlusion"]
    assert share.shape == (len(demo),) and np.all((share >= 0) & (share <= 1))
    assert not np.any(share[:first]) and not np.any(share[last + 1 :])
    # the block slides in and out over up to 45% of the target's width, over its whole height
    assert share.max() == pytest.approx(0.45, abs=0.02)
    assert int(np.argmax(share)) == pytest.approx((first + last) / 2, abs=2)
