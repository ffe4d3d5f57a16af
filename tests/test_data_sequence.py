"""smtmvt.data: sequences from OTB folders, image folders, globs and videos (synthetic)."""

import pickle
import warnings

import cv2
import numpy as np
import pytest

from smtmvt.data import (
    ArraySequence,
    Sequence,
    SequenceError,
    SequenceWarning,
    open_sequence,
)


def _frame(i, shape=(6, 8)):
    """A BGR image (as cv2.imwrite wants) whose pixels encode ``i``: R = 10*i, G = 1, B = 2."""
    img = np.zeros(shape + (3,), np.uint8)
    img[..., 2] = 10 * i
    img[..., 1] = 1
    img[..., 0] = 2
    return img


def make_otb(root, name="Seq", n=5, gt_lines=None, fmt="{:04d}.png", start=1, gt_name="groundtruth_rect.txt", sep=","):
    """An OTB folder ``root/name`` with ``n`` frames and a ground truth of ``gt_lines`` lines."""
    folder = root / name
    (folder / "img").mkdir(parents=True)
    for k in range(n):
        cv2.imwrite(str(folder / "img" / fmt.format(start + k)), _frame(k))
    gt_lines = n if gt_lines is None else gt_lines
    if gt_name:
        rows = [sep.join(str(v) for v in (k + 1, 2 * k + 1, 3, 4)) for k in range(gt_lines)]
        (folder / gt_name).write_text("\n".join(rows) + ("\n" if rows else ""))
    return folder


def red_of(frame):
    return int(frame[0, 0, 0])


# --------------------------------------------------------------------------- OTB folders


def test_otb_folder_frames_lazy_rgb_and_zero_based_groundtruth(tmp_path):
    folder = make_otb(tmp_path, n=5)
    seq = open_sequence(folder)
    assert isinstance(seq, Sequence)
    assert seq.name == "Seq" and len(seq) == 5 and seq.source == folder
    assert seq.frame_names == ["0001.png", "0002.png", "0003.png", "0004.png", "0005.png"]
    assert [red_of(f) for f in seq] == [0, 10, 20, 30, 40]  # RGB order, file order
    assert red_of(seq[3]) == 30 and red_of(seq[-1]) == 40 and red_of(seq[np.int64(2)]) == 20
    with pytest.raises(IndexError):
        seq[5]
    with pytest.raises(IndexError):
        seq[-6]
    gt = seq.groundtruth
    assert gt.dtype == np.float64 and gt.shape == (5, 4)
    np.testing.assert_array_equal(gt[0], [0, 0, 3, 4])  # file line "1,1,3,4" minus (1,1,0,0)
    np.testing.assert_array_equal(gt[4], [4, 8, 3, 4])
    assert seq.first_box == (0.0, 0.0, 3.0, 4.0)
    assert seq.annotated.all()
    assert not seq.is_grayscale
    assert not gt.flags.writeable
    clone = pickle.loads(pickle.dumps(seq))  # sent to worker processes by the evaluation runner
    assert clone.name == "Seq" and red_of(clone[1]) == 10
    np.testing.assert_array_equal(clone.groundtruth, gt)


def test_frames_are_read_on_demand_and_a_missing_frame_names_file_and_index(tmp_path):
    folder = make_otb(tmp_path, n=4)
    seq = open_sequence(folder)
    (folder / "img" / "0003.png").unlink()  # removed after opening
    assert red_of(seq[3]) == 30
    with pytest.raises(SequenceError) as info:
        seq[2]
    msg = str(info.value)
    assert "0003.png" in msg and "frame 2" in msg and "'Seq'" in msg
    assert info.value.frame == 2
    with pytest.raises(SequenceError, match="0003.png"):
        list(seq)


def test_grayscale_detection(tmp_path):
    one = tmp_path / "one"
    one.mkdir()
    for k in range(2):
        cv2.imwrite(str(one / f"{k}.png"), np.full((4, 4), k, np.uint8))
    seq = open_sequence(one)
    assert seq[0].shape == (4, 4) and seq.is_grayscale

    three = tmp_path / "three"
    three.mkdir()
    cv2.imwrite(str(three / "0.png"), np.full((4, 4, 3), 9, np.uint8))  # 3 identical channels
    seq = open_sequence(three)
    assert seq[0].shape == (4, 4, 3) and seq.is_grayscale

    color = make_otb(tmp_path, "C", n=1)
    assert not open_sequence(color).is_grayscale


def test_mixed_separators_in_groundtruth(tmp_path):
    folder = make_otb(tmp_path, n=3, gt_name=None)
    (folder / "groundtruth_rect.txt").write_text("11,21,31,41\r\n12\t22\t32\t42\r\n13 22, 33\t43\r\n")
    np.testing.assert_array_equal(
        open_sequence(folder).groundtruth, [[10, 20, 31, 41], [11, 21, 32, 42], [12, 21, 33, 43]]
    )


def test_malformed_groundtruth_names_file_and_line(tmp_path):
    folder = make_otb(tmp_path, n=3, gt_name=None)
    (folder / "groundtruth_rect.txt").write_text("1,1,3,4\n2,2,3,4\n3,3,three,4\n")
    with pytest.raises(SequenceError) as info:
        open_sequence(folder)
    assert str(folder / "groundtruth_rect.txt") in str(info.value)
    assert "line 3" in str(info.value) and "3,3,three,4" in str(info.value)


def test_empty_groundtruth_is_an_error_naming_it(tmp_path):
    folder = make_otb(tmp_path, n=3, gt_lines=0)
    with pytest.raises(SequenceError, match="empty.*groundtruth_rect.txt"):
        open_sequence(folder)


def test_fewer_groundtruth_lines_warn_with_file_and_counts(tmp_path):
    folder = make_otb(tmp_path, n=5, gt_lines=3)
    with pytest.warns(SequenceWarning) as record:
        seq = open_sequence(folder)
    msg = str(record[0].message)
    assert "groundtruth_rect.txt" in msg and "3 boxes" in msg and "5 frames" in msg
    assert len(seq) == 5
    assert seq.annotated.tolist() == [True, True, True, False, False]
    assert np.isnan(seq.groundtruth[3:]).all()


def test_more_groundtruth_lines_than_frames_is_an_error(tmp_path):
    folder = make_otb(tmp_path, n=3, gt_lines=4)
    with pytest.raises(SequenceError) as info:
        open_sequence(folder)
    msg = str(info.value)
    assert "groundtruth_rect.txt" in msg and "4 boxes" in msg and "3 frames" in msg


def test_invalid_boxes_become_nan_rows(tmp_path):
    folder = make_otb(tmp_path, n=4, gt_name=None)
    (folder / "groundtruth_rect.txt").write_text("0,0,0,0\n5,5,3,4\nNaN,NaN,NaN,NaN\n5,5,-1,4\n")
    seq = open_sequence(folder)
    assert seq.annotated.tolist() == [False, True, False, False]
    assert np.isnan(seq.groundtruth[[0, 2, 3]]).all()
    with pytest.raises(ValueError, match="frame 0"):
        _ = seq.first_box


def test_two_targets_pick_first_with_warning_or_the_one_asked(tmp_path):
    folder = make_otb(tmp_path, "Jogging", n=3, gt_name="groundtruth_rect.1.txt")
    (folder / "groundtruth_rect.2.txt").write_text("50,60,7,8\n50,60,7,8\n50,60,7,8\n")
    with pytest.warns(SequenceWarning, match=r"groundtruth_rect\.1\.txt.*target"):
        seq = open_sequence(folder)
    assert seq.name == "Jogging-1" and seq.first_box == (0.0, 0.0, 3.0, 4.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        seq2 = open_sequence(folder, target=2)
    assert seq2.name == "Jogging-2" and seq2.first_box == (49.0, 59.0, 7.0, 8.0)
    assert seq2.groundtruth_file.name == "groundtruth_rect.2.txt"
    with pytest.raises(SequenceError, match=r"groundtruth_rect\.3\.txt"):
        open_sequence(folder, target=3)


def test_single_numbered_groundtruth_like_human4(tmp_path):
    folder = make_otb(tmp_path, "Human4", n=2, gt_name="groundtruth_rect.2.txt")
    (folder / "groundtruth_rect1.txt").write_text("")  # as in OTB: empty and ignored
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        seq = open_sequence(folder)
    assert seq.name == "Human4-2" and seq.annotated.all()


def test_five_digit_names_and_numbering_not_starting_at_one(tmp_path):
    board = make_otb(tmp_path, "Board", n=3, fmt="{:05d}.jpg")
    seq = open_sequence(board)
    assert seq.frame_names == ["00001.jpg", "00002.jpg", "00003.jpg"] and len(seq) == 3
    car = make_otb(tmp_path, "BlurCar1", n=4, start=247)
    seq = open_sequence(car)
    assert seq.frame_names[0] == "0247.png" and len(seq) == 4
    np.testing.assert_array_equal(seq.groundtruth[1], [1, 2, 3, 4])  # line 2 <-> 0248.png


def test_gap_in_frame_numbering_names_the_missing_file(tmp_path):
    folder = make_otb(tmp_path, n=5)
    (folder / "img" / "0003.png").unlink()
    with pytest.raises(SequenceError, match=r"0003\.png is missing"):
        open_sequence(folder)


def test_full_otb_david_folder_uses_frames_300_on(tmp_path):
    folder = tmp_path / "David"
    (folder / "img").mkdir(parents=True)
    tiny = np.zeros((2, 2), np.uint8)
    for k in range(1, 306):
        cv2.imwrite(str(folder / "img" / f"{k:04d}.png"), tiny + (k % 256))
    (folder / "groundtruth_rect.txt").write_text("10,10,5,5\n11,11,5,5\n12,12,5,5\n")
    with pytest.warns(SequenceWarning, match=r"3 boxes for 305 images.*0300\.png\.\.0302\.png"):
        seq = open_sequence(folder)
    assert len(seq) == 3 and seq.frame_names == ["0300.png", "0301.png", "0302.png"]
    assert int(seq[0][0, 0]) == 300 % 256


def test_football1_full_folder_is_cut_to_its_groundtruth(tmp_path):
    folder = make_otb(tmp_path, "Football1", n=6, gt_lines=4)
    with pytest.warns(SequenceWarning, match="Football1"):
        seq = open_sequence(folder)
    assert len(seq) == 4 and seq.annotated.all()


def test_groundtruth_argument_overrides(tmp_path):
    folder = make_otb(tmp_path, n=2)
    other = tmp_path / "mine.txt"
    other.write_text("100,100,10,10\n101,101,10,10\n")
    seq = open_sequence(folder, groundtruth=other, name="custom")
    assert seq.name == "custom" and seq.first_box == (99.0, 99.0, 10.0, 10.0)


# ----------------------------------------------------------------- folders, globs, errors


def _numbered_plain(folder, n, ext=".png"):
    folder.mkdir(parents=True, exist_ok=True)
    for k in range(1, n + 1):
        cv2.imwrite(str(folder / f"img{k}{ext}"), _frame(k))


def test_image_folder_sorted_naturally(tmp_path):
    _numbered_plain(tmp_path / "frames", 12)
    seq = open_sequence(tmp_path / "frames")
    assert seq.name == "frames" and seq.groundtruth is None
    assert seq.frame_names[:3] == ["img1.png", "img2.png", "img3.png"] and seq.frame_names[-1] == "img12.png"
    assert [red_of(f) for f in seq] == [10 * k for k in range(1, 13)]
    with pytest.raises(ValueError, match="no ground truth"):
        _ = seq.first_box


def test_image_folder_with_groundtruth_beside(tmp_path):
    _numbered_plain(tmp_path / "f", 2)
    (tmp_path / "f" / "groundtruth.txt").write_text("3,3,4,4\n4,4,4,4\n")
    assert open_sequence(tmp_path / "f").first_box == (2.0, 2.0, 4.0, 4.0)


def test_glob_pattern_natural_order_and_groundtruth(tmp_path):
    _numbered_plain(tmp_path / "clip" / "img", 11, ext=".jpg")
    (tmp_path / "clip" / "img" / "notes.txt").write_text("not an image")
    gt = tmp_path / "gt.txt"
    gt.write_text("\n".join("5,6,7,8" for _ in range(11)) + "\n")
    seq = open_sequence(str(tmp_path / "clip" / "img" / "img*"), groundtruth=gt)
    assert len(seq) == 11 and seq.name == "clip"
    assert seq.frame_names[1] == "img2.jpg" and seq.frame_names[-1] == "img11.jpg"
    assert seq.first_box == (4.0, 5.0, 7.0, 8.0)
    with pytest.raises(SequenceError, match="no image files match"):
        open_sequence(str(tmp_path / "clip" / "*.bmp"))


def test_open_sequence_errors_name_the_path(tmp_path):
    with pytest.raises(SequenceError, match="no such file or folder.*nothing-here"):
        open_sequence(tmp_path / "nothing-here")
    (tmp_path / "empty").mkdir()
    with pytest.raises(SequenceError, match="no image files in folder.*empty"):
        open_sequence(tmp_path / "empty")
    (tmp_path / "otb" / "img").mkdir(parents=True)
    with pytest.raises(SequenceError, match="no image files in .*img"):
        open_sequence(tmp_path / "otb")
    odd = tmp_path / "clip.xyz"
    odd.write_text("?")
    with pytest.raises(SequenceError, match=r"unknown file type '\.xyz'.*clip\.xyz"):
        open_sequence(odd)


def test_mixed_image_types_are_refused(tmp_path):
    folder = make_otb(tmp_path, n=2)
    cv2.imwrite(str(folder / "img" / "thumb.jpg"), _frame(0))
    with pytest.raises(SequenceError, match="mixed image types"):
        open_sequence(folder)


def test_array_sequence():
    frames = np.zeros((3, 4, 5), np.uint8)
    seq = ArraySequence(frames, "mem", [[0, 0, 2, 2]] * 3)
    assert len(seq) == 3 and seq.is_grayscale and seq.first_box == (0.0, 0.0, 2.0, 2.0)


# ------------------------------------------------------------------------------- videos


@pytest.fixture
def avi(tmp_path):
    """An MJPG .avi of 9 frames 32x24 whose red level encodes the frame index (20*i)."""
    path = tmp_path / "clip.avi"
    writer = cv2.VideoWriter(str(path), cv2.VideoWriter_fourcc(*"MJPG"), 10, (32, 24))
    if not writer.isOpened():
        pytest.skip("OpenCV here cannot write MJPG .avi (no codec)")
    for i in range(9):
        img = np.zeros((24, 32, 3), np.uint8)
        img[..., 2] = 20 * i  # BGR: red
        writer.write(img)
    writer.release()
    return path


def _red_index(frame):
    assert frame.shape == (24, 32, 3) and frame.dtype == np.uint8
    assert frame[..., 2].mean() < 8 and frame[..., 1].mean() < 8  # RGB order
    return int(round(frame[..., 0].mean() / 20))


def test_video_length_iteration_and_random_access(avi):
    seq = open_sequence(avi)
    assert seq.name == "clip" and len(seq) == 9 and seq.frame_names[4] == "frame 4"
    assert [_red_index(f) for f in seq] == list(range(9))
    assert [_red_index(seq[i]) for i in (3, 4, 7, 1, 8, -9, -1)] == [3, 4, 7, 1, 8, 0, 8]
    with pytest.raises(IndexError):
        seq[9]
    clone = pickle.loads(pickle.dumps(seq))  # the open capture is not carried
    assert _red_index(clone[5]) == 5


def test_video_with_groundtruth(avi, tmp_path):
    gt = tmp_path / "clip.txt"
    gt.write_text("\n".join(f"{i + 1},1,4,4" for i in range(9)))
    seq = open_sequence(avi, groundtruth=gt)
    assert seq.groundtruth.shape == (9, 4) and seq.first_box == (0.0, 0.0, 4.0, 4.0)
    gt.write_text("1,1,4,4\n" * 10)
    with pytest.raises(SequenceError, match="10 boxes.*9 frames"):
        open_sequence(avi, groundtruth=gt)


# ------------------------------------------------------------------------ one frame size


def test_a_frame_of_another_size_is_an_error_naming_it(tmp_path):
    """Boxes refer to one pixel grid: a frame of another size (a resized or foreign image)
    would silently shift every box; the first such frame is named (issue 8)."""
    folder = make_otb(tmp_path, n=5)
    cv2.imwrite(str(folder / "img" / "0004.png"), _frame(3, shape=(7, 8)))
    seq = open_sequence(folder)
    assert [red_of(seq[i]) for i in range(3)] == [0, 10, 20]
    with pytest.raises(
        SequenceError, match=r"frame 3 \(0004\.png\) is 8x7 pixels.*frame 0 \(0001\.png\) is 8x6"
    ) as info:
        seq[3]
    assert info.value.frame == 3 and info.value.path.endswith("0004.png")
    with pytest.raises(SequenceError, match="0004.png"):
        list(seq)
    fresh = open_sequence(folder)  # random access first: frame 0 is the reference all the same
    with pytest.raises(SequenceError, match="frame 3"):
        fresh[3]
    assert red_of(fresh[4]) == 40


def test_array_sequence_frames_of_another_size(tmp_path):
    frames = [np.zeros((6, 8), np.uint8), np.zeros((6, 8), np.uint8), np.zeros((6, 9), np.uint8)]
    seq = ArraySequence(frames, name="arr")
    with pytest.raises(SequenceError, match=r"'arr'.*frame 2 \(frame 2\) is 9x6"):
        list(seq)
