"""smtmvt.data: reading frames and box files (synthetic files in tmp_path)."""

import os
import pickle

import cv2
import numpy as np
import pytest

from smtmvt.data import SequenceError, parse_boxes, read_boxes, read_frame, write_boxes

# ----------------------------------------------------------------------------- frames


def _bgr(rgb):
    return tuple(reversed(rgb))


@pytest.mark.parametrize("ext", [".png", ".bmp", ".tif", ".jpg"])
def test_read_frame_returns_rgb_order(tmp_path, ext):
    path = tmp_path / f"red{ext}"
    img = np.zeros((8, 10, 3), np.uint8)
    img[:] = _bgr((255, 0, 0))  # OpenCV writes BGR: this is pure red
    assert cv2.imwrite(str(path), img)
    frame = read_frame(path)
    assert frame.shape == (8, 10, 3) and frame.dtype == np.uint8
    tol = 3 if ext == ".jpg" else 0
    assert np.all(frame[..., 0] >= 255 - tol)
    assert np.all(frame[..., 1:] <= tol)


def test_read_frame_grayscale_and_16bit(tmp_path):
    gray = np.arange(48, dtype=np.uint8).reshape(6, 8)
    cv2.imwrite(str(tmp_path / "g.png"), gray)
    out = read_frame(tmp_path / "g.png")
    assert out.shape == (6, 8) and out.dtype == np.uint8
    np.testing.assert_array_equal(out, gray)

    deep = np.arange(48, dtype=np.uint16).reshape(6, 8) * 1000 + 7
    cv2.imwrite(str(tmp_path / "d.png"), deep)
    out = read_frame(tmp_path / "d.png")
    assert out.dtype == np.uint16
    np.testing.assert_array_equal(out, deep)

    deep_rgb = np.zeros((4, 5, 3), np.uint16)
    deep_rgb[..., 2] = 60000  # BGR on disk: red = 60000
    cv2.imwrite(str(tmp_path / "d3.png"), deep_rgb)
    out = read_frame(tmp_path / "d3.png")
    assert out.dtype == np.uint16 and out.shape == (4, 5, 3)
    assert np.all(out[..., 0] == 60000) and np.all(out[..., 1:] == 0)


def test_read_frame_drops_alpha(tmp_path):
    bgra = np.zeros((5, 7, 4), np.uint8)
    bgra[..., 1] = 200  # green
    bgra[..., 3] = 17  # alpha
    cv2.imwrite(str(tmp_path / "a.png"), bgra)
    out = read_frame(tmp_path / "a.png")
    assert out.shape == (5, 7, 3)
    assert np.all(out[..., 1] == 200) and np.all(out[..., 0] == 0) and np.all(out[..., 2] == 0)


def test_read_frame_errors_name_the_file(tmp_path):
    missing = tmp_path / "nope" / "0001.jpg"
    with pytest.raises(SequenceError, match="0001.jpg") as info:
        read_frame(missing)
    assert info.value.path == str(missing)
    broken = tmp_path / "broken.png"
    broken.write_bytes(b"this is not a png")
    with pytest.raises(SequenceError, match="broken.png"):
        read_frame(broken)
    empty = tmp_path / "empty.jpg"
    empty.write_bytes(b"")
    with pytest.raises(SequenceError, match="empty.jpg"):
        read_frame(empty)


def test_sequence_error_is_value_error_and_pickles():
    err = SequenceError("f.txt, line 3: bad", path="f.txt", line=3, sequence="S")
    assert isinstance(err, ValueError)
    back = pickle.loads(pickle.dumps(err))
    assert (str(back), back.path, back.line, back.sequence) == ("f.txt, line 3: bad", "f.txt", 3, "S")


# ------------------------------------------------------------------------------ boxes


def test_parse_boxes_mixed_separators_crlf_nan_trailing_blank_lines():
    text = "1,2,3,4\r\n5\t6\t7\t8\r\n9 10  11 12\n13, 14,\t15 16\nNaN,nan,NAN,1.5e1\n\n  \n"
    boxes = parse_boxes(text, source="gt.txt")
    assert boxes.dtype == np.float64 and boxes.shape == (5, 4)
    np.testing.assert_array_equal(boxes[:4], np.arange(1, 17, dtype=float).reshape(4, 4))
    assert np.isnan(boxes[4, :3]).all() and boxes[4, 3] == 15.0
    assert parse_boxes("", "x").shape == (0, 4)


@pytest.mark.parametrize(
    "bad_line, why",
    [
        ("5,6,7", "4 numbers"),
        ("5,6,7,8,9", "4 numbers"),
        ("5,6,x,8", "not a number"),
        ("5,,6,7", "empty field"),
        ("5,6,7,8,", "empty field"),
        ("5,6,7,inf", "not a number"),
        ("", "blank line"),
    ],
)
def test_parse_boxes_malformed_line_names_source_line_and_text(bad_line, why):
    text = f"1,2,3,4\n1,2,3,4\n{bad_line}\n1,2,3,4\n"
    with pytest.raises(SequenceError) as info:
        parse_boxes(text, source="seq/groundtruth_rect.txt")
    msg = str(info.value)
    assert "seq/groundtruth_rect.txt" in msg and "line 3" in msg and why in msg
    assert repr(bad_line) in msg
    assert info.value.line == 3


def test_read_boxes_zero_based_by_default(tmp_path):
    path = tmp_path / "gt.txt"
    path.write_text("198,214,34,81\n197\t214\t34\t81\n")
    np.testing.assert_array_equal(read_boxes(path), [[197, 213, 34, 81], [196, 213, 34, 81]])
    np.testing.assert_array_equal(read_boxes(path, one_based=True), [[198, 214, 34, 81], [197, 214, 34, 81]])


def test_read_boxes_empty_or_missing_file(tmp_path):
    empty = tmp_path / "groundtruth_rect.txt"
    empty.write_text("\n\n")
    with pytest.raises(SequenceError, match="empty.*groundtruth_rect.txt"):
        read_boxes(empty)
    assert read_boxes(empty, allow_empty=True).shape == (0, 4)
    with pytest.raises(SequenceError, match="missing.txt"):
        read_boxes(tmp_path / "missing.txt")


def test_read_boxes_malformed_line_names_file(tmp_path):
    path = tmp_path / "res.txt"
    path.write_text("1,2,3,4\n1;2;3;4\n")
    with pytest.raises(SequenceError, match=r"res\.txt, line 2: .*'1;2;3;4'"):
        read_boxes(path)


def test_write_boxes_one_based_on_disk_and_round_trip(tmp_path):
    boxes = np.array([[0, 0, 10, 20], [12.5, 7.25, 3, 4], [np.nan] * 4, [-3, 1e5, 0.1, 2]])
    path = tmp_path / "a" / "b" / "res.txt"  # parents created
    write_boxes(path, boxes)
    lines = path.read_text().splitlines()
    assert lines[:3] == ["1,1,10,20", "13.5,8.25,3,4", "NaN,NaN,NaN,NaN"]
    back = read_boxes(path)
    np.testing.assert_allclose(back, boxes, rtol=0, atol=1e-9)
    np.testing.assert_array_equal(back[:2], boxes[:2])  # whole and quarter pixels: exact
    with pytest.raises(ValueError, match="shape"):
        write_boxes(tmp_path / "x.txt", np.zeros((3, 5)))


def test_write_boxes_is_atomic(tmp_path, monkeypatch):
    path = tmp_path / "res.txt"
    write_boxes(path, [[0, 0, 5, 5]])
    old = path.read_text()
    assert sorted(os.listdir(tmp_path)) == ["res.txt"]  # no temporary file left

    real_fsync = os.fsync

    def failing_fsync(fd):
        real_fsync(fd)
        raise OSError("disk full (simulated)")

    monkeypatch.setattr(os, "fsync", failing_fsync)
    with pytest.raises(OSError, match="simulated"):
        write_boxes(path, np.zeros((1000, 4)))
    monkeypatch.undo()
    assert path.read_text() == old  # the old file is untouched, not truncated
    assert sorted(os.listdir(tmp_path)) == ["res.txt"]  # and the temp file is gone

    write_boxes(path, [[1, 1, 2, 2], [3, 3, 4, 4]])
    assert path.read_text() == "2,2,2,2\n4,4,4,4\n"
    assert sorted(os.listdir(tmp_path)) == ["res.txt"]
