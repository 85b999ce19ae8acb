"""DofMap: names, look-ups, CSV files and every message."""

import numpy as np
import pytest

from microslip.fe import DofMap, FileFormatError
from microslip.fe.dof_map import split_name


def test_lookups_by_letter_number_and_pair():
    d = DofMap([1204, 1204, 1300, 7], ["x", "y", 1, "6"])
    assert d.names == ["1204:x", "1204:y", "1300:x", "7:rz"]
    assert len(d) == 4
    assert d.index("1204:y") == 1
    assert d.index("1300:1") == d.index("1300:x") == d.index((1300, "x")) == 2
    assert d.index(" 7 : RZ ") == 3
    assert d.rows(1204) == {"x": 0, "y": 1} and d.rows(5) == {}
    np.testing.assert_array_equal(d.nodes, [1204, 1204, 1300, 7])
    assert d.components == ("x", "y", "x", "rz")
    assert repr(d) == "DofMap(4 rows, 3 nodes)"
    assert d == DofMap.from_names(d.names) and d != DofMap([1], ["x"])


def test_built_from_numpy_arrays():
    d = DofMap(np.array([3, 3, 4]), np.array(["x", "y", "x"]))
    assert d.index("4:x") == 2


def test_csv_round_trip_with_comments_bom_and_extra_columns(tmp_path):
    d = DofMap([10, 10, 11, 11], ["x", "y", "x", "y"])
    assert DofMap.from_csv(d.to_csv(tmp_path / "dofs.csv")) == d
    f = tmp_path / "nastran.csv"
    f.write_text("\ufeff# exported\nlabel,component,node\na,1,10\nb,2,10\n\nc,3,11\n", encoding="utf-8")
    assert DofMap.from_csv(f).names == ["10:x", "10:y", "11:z"]


@pytest.mark.parametrize("name, message", [
    ("1205:x", r"DOF '1205:x': node 1205 is not in the DOF map \(12 nodes, ids 1..1300\); "
               r"the nearest ids are 8, 9, 10, 1204, 1300$"),
    ("1204:z", r"DOF '1204:z': node 1204 has no component 'z'; it has 1204:x, 1204:y"),
    ("1204:w", r"DOF name '1204:w': component 'w' is not one of x, y, z, rx, ry, rz \(or their numbers 1..6\)"),
    ("1204:7", r"component '7' is not one of x, y, z"),
    ("1204", r"DOF name '1204' must be 'node:component', e.g. '1204:x' or '1204:1'"),
    ("tip:x", r"DOF name 'tip:x': node id must be a non-negative integer, got 'tip'"),
])
def test_unknown_names_are_refused_with_the_close_ones(name, message):
    d = DofMap(list(range(1, 11)) + [1204, 1204, 1300], ["x"] * 10 + ["x", "y", "x"])
    with pytest.raises(ValueError, match=message):
        d.index(name)


def test_a_name_must_be_a_string():
    with pytest.raises(TypeError, match="a DOF name must be a string such as '1204:x', got 12"):
        split_name(12)


@pytest.mark.parametrize("nodes, components, error, message", [
    ([1, 1], ["x", "x"], ValueError, "rows 0 and 1 both name DOF '1:x': each node and component must appear once"),
    ([1, 1], ["x", 1], ValueError, "rows 0 and 1 both name DOF '1:x'"),
    ([1, 2], ["x"], ValueError, "nodes and components must have the same length, got 2 and 1"),
    ([-1], ["x"], ValueError, "row 0: node id must be a non-negative integer, got -1"),
    ([1.5], ["x"], ValueError, "row 0: node id must be a non-negative integer, got 1.5"),
    ([True], ["x"], TypeError, "row 0: node id must be an integer, got True"),
    ([1], ["q"], ValueError, "row 0: component 'q' is not one of"),
    (5, ["x"], TypeError, "nodes must be a 1-D sequence, one entry per matrix row, got 5"),
    ([1], "x", TypeError, "components must be a 1-D sequence"),
])
def test_invalid_maps_are_refused(nodes, components, error, message):
    with pytest.raises(error, match=message):
        DofMap(nodes, components)


@pytest.mark.parametrize("text, message", [
    ("", "no header; the first line must name the columns 'node,component'"),
    ("1,x\n2,y\n", r"line 1: must be a header naming the columns 'node' and 'component' \(missing node, component\)"),
    ("node,dof\n1,x\n", r"\(missing component\)"),
    ("node,component\n", "no data row after the header"),
    ("node,component\n1,x\n2\n", "line 3: has 1 cell\\(s\\), the header has 2"),
    ("node,component\n1,x\n2,y,5\n", "line 3: has 3 cell\\(s\\), the header has 2"),
    ("node,component,node\n1,x,2\n", r"line 1: the header names the column\(s\) 'node' more than once"),
    ("component,node\nx,10\ny,1", r"line 3: the file does not end with a line break: it may be truncated"),  # 10 cut
    ("node,component\n1,x\nabc,y\n", "line 3: node id must be a non-negative integer, got 'abc'"),
    ("node,component\n1,x\n1,7\n", "line 3: component '7' is not one of"),
    ("node,component\n1,x\n1,1\n", r"rows 0 and 1 both name DOF '1:x'.*\(data rows counted from 0\)"),
])
def test_csv_errors_name_the_file_and_line(tmp_path, text, message):
    f = tmp_path / "dofs.csv"
    f.write_text(text, encoding="utf-8")
    with pytest.raises(FileFormatError, match=message) as err:
        DofMap.from_csv(f)
    assert str(f) in str(err.value)


def test_a_file_that_is_not_utf8_is_named(tmp_path):
    f = tmp_path / "dofs.csv"
    f.write_text("node,component\n1,x\n", encoding="utf-16")
    with pytest.raises(ValueError, match=r"dofs.csv: not a UTF-8 text file \(invalid start byte at byte 0\)"):
        DofMap.from_csv(f)
