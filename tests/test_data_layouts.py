"""Benchmark layouts (GOT-10k, LaSOT, UAV123, VOT) read from the same real frames as OTB."""

from __future__ import annotations

import numpy as np
import pytest

from layout_folders import write_all, write_got10k, write_uav123, write_vot
from smtmvt.data import SequenceError, detect_layout, list_dataset, open_dataset
from smtmvt.data.layouts import uav123

LAYOUTS = ("otb", "got10k", "lasot", "uav123", "vot")
ABSENT = (10, 11, 25)


@pytest.fixture(scope="module")
def crossing(otb_dir):
    return otb_dir / "Crossing"


@pytest.fixture(scope="module")
def folders(crossing, tmp_path_factory):
    return write_all(tmp_path_factory.mktemp("clean"), crossing)


@pytest.fixture(scope="module")
def absent_folders(crossing, tmp_path_factory):
    return write_all(tmp_path_factory.mktemp("absent"), crossing, absent=ABSENT)


@pytest.mark.parametrize("layout", LAYOUTS)
def test_detection_picks_the_layout(folders, layout):
    assert detect_layout(folders[layout]) == layout


@pytest.mark.parametrize("layout", LAYOUTS[1:])
def test_every_layout_reads_the_otb_frames_and_boxes(folders, layout):
    (ref,) = open_dataset(folders["otb"])
    (seq,) = open_dataset(folders[layout])
    assert len(seq) == len(ref) == 40
    np.testing.assert_array_equal(seq.groundtruth, ref.groundtruth)
    assert seq.first_box == ref.first_box
    for i in (0, 17, 39):
        np.testing.assert_array_equal(seq[i], ref[i])


@pytest.mark.parametrize("layout", LAYOUTS[1:])
def test_absent_frames_have_no_box(absent_folders, layout):
    (ref,) = open_dataset(absent_folders["otb"])
    (seq,) = open_dataset(absent_folders[layout])
    assert list(np.flatnonzero(~seq.annotated)) == list(ABSENT)
    keep = seq.annotated
    np.testing.assert_array_equal(seq.groundtruth[keep], ref.groundtruth[keep])


def test_sequence_names_follow_each_layout(folders):
    names = {k: [e[0] for e in list_dataset(p)] for k, p in folders.items()}
    assert names == {
        "otb": ["Crossing"],
        "got10k": ["Crossing"],
        "lasot": ["crossing-1"],
        "uav123": ["crossing"],
        "vot": ["crossing"],
    }


def test_got10k_without_cover_label_reads_absence_label(crossing, tmp_path):
    from layout_folders import cut

    files, boxes = cut(crossing, 12)
    root = write_got10k(tmp_path, "Crossing", files, boxes, absent={3})
    (root / "Crossing" / "cover.label").unlink()
    (seq,) = open_dataset(root)
    assert list(np.flatnonzero(~seq.annotated)) == [3]


def test_a_bad_label_names_file_and_line(crossing, tmp_path):
    from layout_folders import cut

    files, boxes = cut(crossing, 12)
    root = write_got10k(tmp_path, "Crossing", files, boxes)
    label = root / "Crossing" / "cover.label"
    label.write_text("8\n8\nhalf\n" + "8\n" * 9)
    with pytest.raises(SequenceError, match=r"cover\.label, line 3: not a number: 'half'") as info:
        open_dataset(root)
    assert info.value.line == 3 and info.value.path == str(label)
    label.write_text("8\n" * 11)
    with pytest.raises(SequenceError, match=r"cover\.label: 11 labels for 12 frames"):
        open_dataset(root)


def test_vot_rectangles_without_color_folder(crossing, tmp_path):
    from layout_folders import cut

    files, boxes = cut(crossing, 12)
    root = write_vot(tmp_path, "crossing", files, boxes, color=False)
    assert detect_layout(root) == "vot"
    (seq,) = open_dataset(root)
    np.testing.assert_array_equal(seq.groundtruth, boxes - [1, 1, 0, 0])


def test_vot_polygon_becomes_its_bounding_rectangle(crossing, tmp_path):
    from layout_folders import cut

    files, boxes = cut(crossing, 2)
    root = write_vot(tmp_path, "crossing", files, boxes)
    # a diamond: x in [10, 30], y in [5, 45]
    (root / "crossing" / "groundtruth.txt").write_text("20,5,30,25,20,45,10,25\n" + "1,2,3,2,3,4,1,4\n")
    (seq,) = open_dataset(root)
    np.testing.assert_array_equal(seq.groundtruth + [1, 1, 0, 0], [[10, 5, 20, 40], [1, 2, 2, 2]])


@pytest.mark.parametrize(
    ("line", "problem"),
    [("1,2,3,4,5", "found 5 fields"), ("m1,2,3,4,0,1", "mask region"), ("1,2,x,4", "not a number: 'x'")],
)
def test_a_bad_vot_line_names_file_and_line(crossing, tmp_path, line, problem):
    from layout_folders import cut

    files, boxes = cut(crossing, 3)
    root = write_vot(tmp_path, "crossing", files, boxes)
    gt = root / "crossing" / "groundtruth.txt"
    gt.write_text("1,1,9,1,9,9,1,9\n" + line + "\n1,1,9,1,9,9,1,9\n")
    with pytest.raises(SequenceError, match=rf"groundtruth\.txt, line 2: .*{problem}") as info:
        open_dataset(root)
    assert info.value.line == 2 and info.value.path == str(gt)


def test_uav123_subsequence_reads_its_frame_range(crossing, tmp_path, monkeypatch):
    """As got10k's UAV123 class: a listed sequence is a range of its folder's frames."""
    from layout_folders import cut

    files, boxes = cut(crossing, 20)
    root = write_uav123(tmp_path, "crossing", files, boxes, first=101)
    anno = root / "anno" / "UAV123"
    (anno / "crossing.txt").rename(anno / "crossing_2.txt")
    (anno / "crossing_2.txt").write_text("".join(",".join(map(str, b)) + "\n" for b in boxes[5:15]))
    monkeypatch.setitem(uav123.UAV123_RANGES, "crossing_2", ("crossing", 106, 115))
    (seq,) = open_dataset(root)
    assert seq.name == "crossing_2" and len(seq) == 10
    assert [f.name for f in seq.files] == [f"{k:06d}.jpg" for k in range(106, 116)]
    np.testing.assert_array_equal(seq.groundtruth + [1, 1, 0, 0], boxes[5:15])
    monkeypatch.setitem(uav123.UAV123_RANGES, "crossing_2", ("crossing", 106, 116))
    with pytest.raises(SequenceError, match=r"crossing_2\.txt: 10 lines, but crossing_2 is frames 106-116"):
        open_dataset(root)
    monkeypatch.setitem(uav123.UAV123_RANGES, "crossing_2", ("crossing", 115, 124))
    with pytest.raises(SequenceError, match=r"frame file .*000121\.jpg not found"):
        open_dataset(root)


def test_the_shipped_uav123_ranges_are_well_formed():
    for name, (folder, first, last) in uav123.UAV123_RANGES.items():
        assert name.startswith(folder) and 1 <= first <= last, name
