"""smtmvt.data: benchmark folders (open_dataset) and attribute tables (synthetic)."""

import pytest

from smtmvt.data import (
    ATTRIBUTES,
    OTB_FLAG_ORDER,
    SequenceError,
    SequenceWarning,
    attributes_of,
    list_dataset,
    load_attributes,
    open_dataset,
)
from test_data_sequence import make_otb


@pytest.fixture
def bench(tmp_path):
    """Good: Alpha, beta, Jogging (2 targets). Broken: Bad (malformed gt), Empty (no images),
    NoGt (img/ without gt). Ignored: notes/ (no img, no gt), .hidden/."""
    root = tmp_path / "bench"
    make_otb(root, "beta", n=2)
    make_otb(root, "Alpha", n=3)
    jog = make_otb(root, "Jogging", n=2, gt_name="groundtruth_rect.1.txt")
    (jog / "groundtruth_rect.2.txt").write_text("9,9,2,2\n9,9,2,2\n")
    bad = make_otb(root, "Bad", n=2, gt_name=None)
    (bad / "groundtruth_rect.txt").write_text("1,1,3,4\n1 1 3\n")
    empty = root / "Empty"
    (empty / "img").mkdir(parents=True)
    (empty / "groundtruth_rect.txt").write_text("1,1,3,4\n")
    make_otb(root, "NoGt", n=2, gt_name=None)
    (root / "notes").mkdir()
    (root / "notes" / "readme.txt").write_text("x")
    make_otb(root / ".hidden", "x", n=1)
    return root


def test_list_dataset_names_sorted_and_targets_expanded(bench):
    assert [e[0] for e in list_dataset(bench)] == ["Alpha", "Bad", "beta", "Empty", "Jogging-1", "Jogging-2", "NoGt"]


def test_open_dataset_collect_keeps_going_and_names_files(bench):
    items = open_dataset(bench, on_error="collect")
    names = [getattr(i, "name", None) or i.sequence for i in items]
    assert names == ["Alpha", "Bad", "beta", "Empty", "Jogging-1", "Jogging-2", "NoGt"]
    errors = {i.sequence: i for i in items if isinstance(i, SequenceError)}
    assert sorted(errors) == ["Bad", "Empty", "NoGt"]
    assert "groundtruth_rect.txt" in str(errors["Bad"]) and "line 2" in str(errors["Bad"])
    assert errors["Bad"].line == 2
    assert "img" in str(errors["Empty"]) and "Empty" in str(errors["Empty"])
    assert "NoGt" in str(errors["NoGt"]) and "ground-truth" in str(errors["NoGt"])
    good = {i.name: i for i in items if not isinstance(i, SequenceError)}
    assert len(good["Alpha"]) == 3 and good["Jogging-2"].first_box == (8.0, 8.0, 2.0, 2.0)


def test_open_dataset_raise_stops_at_first_broken(bench):
    with pytest.raises(SequenceError, match="line 2") as info:
        open_dataset(bench)
    assert info.value.sequence == "Bad"


def test_open_dataset_filter_case_insensitive_and_unknown_names(bench):
    seqs = open_dataset(bench, ["ALPHA", "jogging-2"])
    assert [s.name for s in seqs] == ["Alpha", "Jogging-2"]
    assert [s.name for s in open_dataset(bench, ["jogging"])] == ["Jogging-1", "Jogging-2"]
    with pytest.raises(SequenceError, match=r"'Gamma'.*available: Alpha, Bad, beta"):
        open_dataset(bench, ["alpha", "Gamma"])
    with pytest.raises(ValueError, match="on_error"):
        open_dataset(bench, on_error="ignore")
    with pytest.raises(SequenceError, match="not found"):
        open_dataset(bench / "nope")


def test_open_dataset_targets_do_not_warn(bench):
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error", SequenceWarning)
        open_dataset(bench, ["jogging"])


# -------------------------------------------------------------------------- attributes


def test_flag_file_order_is_the_toolkits(tmp_path):
    att = tmp_path / "anno" / "att"
    att.mkdir(parents=True)
    # one flag at a time: position k of the file is OTB_FLAG_ORDER[k]
    for k in range(len(OTB_FLAG_ORDER)):
        flags = ["0"] * 11
        flags[k] = "1"
        (att / f"s{k}.txt").write_text(",".join(flags))
    (att / "Basketball.txt").write_text("1,1,0,1,1,0,0,0,0,1,0\n")
    table = load_attributes(att)
    assert table["s1"] == ("OPR",) and table["s2"] == ("SV",) and table["s7"] == ("IPR",)
    assert table["Basketball"] == ("IV", "OCC", "DEF", "OPR", "BC")  # display order
    assert load_attributes(tmp_path / "anno") == table  # anno/ with att/ inside is accepted
    assert attributes_of(table, "BASKETBALL") == ("IV", "OCC", "DEF", "OPR", "BC")
    with pytest.raises(KeyError, match="Basketball"):
        attributes_of(table, "football")


def test_results_folder_prefers_the_table_file(tmp_path):
    att = tmp_path / "anno" / "att"
    att.mkdir(parents=True)
    (att / "Crossing.txt").write_text("0,0,1,0,1,0,0,0,0,1,0\n")  # SV, DEF, BC
    assert load_attributes(tmp_path) == {"Crossing": ("SV", "DEF", "BC")}  # root with anno/att/
    (tmp_path / "attributes-tb100.txt").write_text("Crossing\tSV, DEF, FM, OPR, BC\n")
    assert load_attributes(tmp_path) == {"Crossing": ("SV", "DEF", "FM", "OPR", "BC")}


def test_flag_file_errors(tmp_path):
    (tmp_path / "Bad.txt").write_text("1,0,1\n")
    with pytest.raises(SequenceError, match=r"Bad\.txt.*11 flags"):
        load_attributes(tmp_path)
    with pytest.raises(SequenceError, match="not found"):
        load_attributes(tmp_path / "nope")


def test_table_file(tmp_path):
    path = tmp_path / "attributes.txt"
    path.write_text("Basketball\tIV, OCC, DEF, OPR, BC\nCarDark\tBC,IV\nEasy\t\n")
    table = load_attributes(path)
    assert table == {"Basketball": ("IV", "OCC", "DEF", "OPR", "BC"), "CarDark": ("IV", "BC"), "Easy": ()}
    assert set(ATTRIBUTES) == set(OTB_FLAG_ORDER) and len(ATTRIBUTES) == 11
    path.write_text("Basketball\tIV, OCC\nCarDark\tIV, XYZ\n")
    with pytest.raises(SequenceError, match=r"attributes\.txt, line 2: unknown attribute code 'XYZ'"):
        load_attributes(path)
    path.write_text("A\tIV\na\tBC\nA\tOV\n")
    with pytest.raises(SequenceError, match="line 3.*twice"):
        load_attributes(path)


def test_names_that_differ_only_in_case_or_separators_are_refused(tmp_path):
    """``Seq_1`` and ``seq-1`` are one name to the report and to imports (matched by
    canonical name): refuse both rather than let one row carry the other's score."""
    root = tmp_path / "bench"
    make_otb(root, "Seq_1", n=2)
    make_otb(root, "seq-1", n=2)
    make_otb(root, "Seq 2", n=2)
    make_otb(root, "Good", n=2)
    items = open_dataset(root, on_error="collect")
    by_name = {(i.sequence if isinstance(i, SequenceError) else i.name): i for i in items}
    assert set(by_name) == {"Good", "Seq 2", "Seq_1", "seq-1"}
    assert not isinstance(by_name["Good"], SequenceError) and not isinstance(by_name["Seq 2"], SequenceError)
    for name in ("Seq_1", "seq-1"):
        err = by_name[name]
        assert isinstance(err, SequenceError)
        assert "'Seq_1'" in str(err) and "'seq-1'" in str(err) and "differ only in case" in str(err)
    with pytest.raises(SequenceError, match="differ only in case"):
        open_dataset(root)
    # asking for one of them does not make the other go away
    (item,) = open_dataset(root, sequences=["Seq_1"], on_error="collect")
    assert isinstance(item, SequenceError)
