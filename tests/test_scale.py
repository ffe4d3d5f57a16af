"""The scale filter: it finds a known change of size, and the tracker moves its state toward it."""

import cv2
import numpy as np
import pytest
from skimage import data

from smtmvt import Tracker, TrackerConfig
from smtmvt.correlation import cell_features
from smtmvt.scale import ScaleFilter, factors, model_size, samples

BOX = np.array([200.0, 150.0, 60.0, 48.0])  # on the astronaut's face and helmet


def _centre(box):
    return np.array([box[0] + (box[2] - 1) / 2.0, box[1] + (box[3] - 1) / 2.0])


def _zoomed(img, centre, f):
    """``img`` grown ``f`` times about ``centre`` (pixel centres)."""
    M = np.array([[f, 0.0, centre[0] * (1 - f)], [0.0, f, centre[1] * (1 - f)]])
    return cv2.warpAffine(img, M, (img.shape[1], img.shape[0]), flags=cv2.INTER_LINEAR, borderMode=cv2.BORDER_REFLECT)


def test_factors_are_symmetric_powers_of_the_step():
    f = factors(5, 1.1)
    np.testing.assert_allclose(f, 1.1 ** np.array([-2, -1, 0, 1, 2]))
    with pytest.raises(ValueError, match="odd"):
        factors(4)


def test_model_size_keeps_the_aspect_and_caps_the_area():
    H, W = model_size((200.0, 100.0))
    assert H % 4 == 0 and W % 4 == 0
    assert H * W <= 1.2 * 512 and W / H == pytest.approx(2.0, rel=0.2)
    assert model_size((12.0, 10.0)) == (8, 12)  # (h, w): small boxes are not enlarged, sides rounded to cells
    with pytest.raises(ValueError, match="no area"):
        model_size((0.0, 10.0))


def test_a_sample_is_the_box_resampled_and_described_by_cells():
    """Factor 1's column is the cell features of the box resampled to the model
    size (a box the size of the model: its pixels), times the Hann weight of
    the middle factor; a factor 2 column describes the box twice as large."""
    img = data.astronaut()
    gray = img.astype(np.float32).mean(axis=2) / 255.0
    size = (16, 20)
    box = np.array([100.0, 120.0, 20.0, 16.0])
    X = samples(img, _centre(box), box[2:], [0.5, 1.0, 2.0], size)
    direct = cell_features(np.ascontiguousarray(gray[120:136, 100:120])).reshape(-1)
    np.testing.assert_allclose(X[:, 1], direct, rtol=1e-4, atol=1e-5)
    # Hann weights over three factors: 0.5, 1, 0.5
    big = cv2.resize(gray[112:144, 90:130], (20, 16), interpolation=cv2.INTER_AREA)
    assert np.corrcoef(X[:, 2], 0.5 * cell_features(big).reshape(-1))[0, 1] > 0.95


@pytest.mark.parametrize("f", [0.9, 0.95, 1.0, 1.06, 1.12])
def test_the_filter_finds_a_known_change_of_size(f):
    """Trained on a box, it gives the factor by which the frame was grown about
    the box's centre, between 1 and it: the ridge term pulls a one-frame
    filter's estimate toward 1 (measured: 0.908 for 0.9, 1.095 for 1.1), by
    at most an eighth of the change in log."""
    img = data.astronaut()
    sf = ScaleFilter(img, BOX)
    assert sf.estimate(img, BOX) == pytest.approx(1.0, abs=0.005)
    log_f = np.log(f)
    assert np.log(sf.estimate(_zoomed(img, _centre(BOX), f), BOX)) == pytest.approx(
        log_f, abs=0.125 * abs(log_f) + 0.002
    )


def test_the_tracker_moves_its_scale_the_configured_share_toward_the_filters():
    """With ``scale_filter`` w, the chosen box's log size moves w of the way to
    the filter's estimate at its centre (about the last box's size); the
    particles the likelihood saw and the one it chose are those without it."""
    img = data.astronaut()
    frame1 = _zoomed(img, _centre(BOX), 1.1)
    base = TrackerConfig(n_particles=60, seed=3, report_read_size=0)  # the state's size reported
    assert base.scale_filter == 0.0
    boxes = {}
    for w in (0.0, 0.5, 1.0):
        t = Tracker(base.replace(scale_filter=w))
        t.init(img, BOX)
        boxes[w] = np.asarray(t.update(frame1).box)
    b0 = boxes[0.0]
    at = np.concatenate([_centre(b0) - (BOX[2:] - 1) / 2.0, BOX[2:]])  # the chosen centre, the first size
    target = np.log(ScaleFilter(img, BOX).estimate(frame1, at) * np.sqrt(BOX[2] * BOX[3]))
    assert np.exp(target) / np.sqrt(BOX[2] * BOX[3]) > 1.03  # it saw the growth (the chosen centre is a little off)
    for w in (0.5, 1.0):
        np.testing.assert_allclose(_centre(boxes[w]), _centre(b0), atol=1e-6)
        log_size = 0.5 * np.log(boxes[w][2] * boxes[w][3])
        expected = 0.5 * np.log(b0[2] * b0[3]) + w * (target - 0.5 * np.log(b0[2] * b0[3]))
        assert log_size == pytest.approx(expected, abs=1e-6)
    with pytest.raises(ValueError, match="scale_filter"):
        TrackerConfig(scale_filter=1.5)
