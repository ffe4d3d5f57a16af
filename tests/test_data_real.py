"""smtmvt.data on the real OTB data in ../shared/data (skipped when it is absent)."""

import numpy as np

from smtmvt.data import attributes_of, load_attributes, open_dataset, open_sequence, read_boxes

# From ../shared/data/README.md: sequence -> (frames, (width, height), grayscale, attributes)
README = {
    "Basketball": (725, (576, 432), False, ("IV", "OCC", "DEF", "OPR", "BC")),
    "CarDark": (393, (320, 240), False, ("IV", "BC")),
    "Crossing": (120, (360, 240), False, ("SV", "DEF", "FM", "OPR", "BC")),
    "David": (471, (320, 240), False, ("IV", "SV", "OCC", "DEF", "MB", "IPR", "OPR")),
    "Dog1": (1350, (320, 240), True, ("SV", "IPR", "OPR")),
    "Girl": (500, (128, 96), False, ("SV", "OCC", "IPR", "OPR")),
    "Singer2": (366, (624, 352), False, ("IV", "DEF", "IPR", "OPR", "BC")),
    "Jumping": (313, (352, 288), True, ("MB", "FM")),
    "Subway": (175, (352, 288), False, ("OCC", "DEF", "BC")),
}


def _gt_lines(path):
    return sum(1 for line in path.read_text().splitlines() if line.strip())


def test_every_real_sequence_opens_with_matching_length_and_size(otb_dir):
    seqs = open_dataset(otb_dir)
    assert {s.name for s in seqs} >= set(README)
    for seq in seqs:
        assert len(seq) == _gt_lines(seq.groundtruth_file), seq.name
        assert seq.annotated.all(), seq.name
        if seq.name in README:
            n, (w, h), gray, _ = README[seq.name]
            assert len(seq) == n
            for frame in (seq[0], seq[-1]):
                assert frame.shape[:2] == (h, w) and frame.dtype == np.uint8, seq.name
                assert (frame.ndim == 2) == gray, seq.name
            assert seq.is_grayscale == gray, seq.name


def test_david_first_box_is_first_line_minus_one(otb_dir):
    seq = open_sequence(otb_dir / "David")
    first_line = (otb_dir / "David" / "groundtruth_rect.txt").read_text().splitlines()[0]
    x, y, w, h = (float(v) for v in first_line.split(","))
    assert seq.first_box == (x - 1, y - 1, w, h)
    assert seq.frame_names[0] == "0300.jpg" and seq.frame_names[-1] == "0770.jpg"


def test_tab_and_crlf_files_read_like_comma_files(otb_dir):
    # Girl and Subway use tabs and CRLF line ends.
    girl = read_boxes(otb_dir / "Girl" / "groundtruth_rect.txt", one_based=True)
    assert girl.shape == (500, 4)
    np.testing.assert_array_equal(girl[0], [57, 21, 31, 45])


def test_attribute_sources_agree(otb_results_dir):
    att = load_attributes(otb_results_dir / "anno" / "att")
    tb100 = load_attributes(otb_results_dir / "attributes-tb100.txt")
    assert len(att) == len(tb100) == 100
    assert attributes_of(att, "Basketball") == attributes_of(tb100, "basketball") == README["Basketball"][3]
    for name, (*_, codes) in README.items():
        assert attributes_of(tb100, name) == codes, name
    # The toolkit's anno/att files and the published table disagree on a few sequences
    # (the published per-attribute scores follow the table). Pin the list so a change shows.
    differ = set()
    for name, codes in att.items():
        try:
            other = attributes_of(tb100, name)
        except KeyError:
            differ.add(name.lower())
            continue
        if other != codes:
            differ.add(name.lower())
    assert differ == {"box", "car1", "car2", "coke", "crossing", "jump", "human4"}
