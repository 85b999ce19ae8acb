"""Units (units.py) and the tables with ``name [unit]`` headers (_table.py)."""

from __future__ import annotations

import re

import numpy as np
import pytest

from microslip.common._table import column_si, read_table
from microslip.common.units import parse_quantity, unit_factor


@pytest.mark.parametrize("unit, kind, factor", [
    ("m", "length", 1.0), ("mm", "length", 1e-3), ("um", "length", 1e-6), ("µm", "length", 1e-6),
    ("in", "length", 0.0254), ("N", "force", 1.0), ("kN", None, 1e3), ("lbf", "force", 4.4482216152605),
    ("GPa", "pressure", 1e9), ("psi", "pressure", 6894.757293168), ("N/um", "stiffness", 1e6),
    ("ms", "time", 1e-3), ("kHz", "frequency", 1e3), ("mJ", "energy", 1e-3), ("-", "dimensionless", 1.0),
])
def test_unit_factors(unit, kind, factor):
    assert unit_factor(unit, kind) == factor


def test_unit_factor_errors():
    with pytest.raises(ValueError, match=re.escape("unknown force unit 'um'; expected one of: N, kN, mN, lbf")):
        unit_factor("um", "force")
    with pytest.raises(ValueError, match=r"unknown unit 'parsec'; expected one of: m, mm, .*GPa"):
        unit_factor("parsec")
    with pytest.raises(ValueError, match=re.escape("kind must be one of ['angular frequency', 'dimensionless', "
                                                   "'energy', 'force', 'frequency', 'length', 'mass', "
                                                   "'moment of inertia', 'pressure', 'rate', 'stiffness', 'time'], "
                                                   "got 'colour'")):
        unit_factor("m", "colour")


def test_hertz_and_radians_per_second_are_different_kinds():
    # a unit factor cannot carry the 2 pi between Hz and rad/s: they must not be interchangeable
    assert unit_factor("Hz", "frequency") == 1.0 and unit_factor("rad/s", "angular frequency") == 1.0
    assert unit_factor("rad/s") == 1.0  # found without a kind, as before
    with pytest.raises(ValueError, match=re.escape("unknown frequency unit 'rad/s'; expected one of: Hz, kHz "
                                                   "('rad/s' is a unit of angular frequency)")):
        unit_factor("rad/s", "frequency")
    with pytest.raises(ValueError, match=re.escape("omega: unknown angular frequency unit 'Hz'; expected one of: "
                                                   "rad/s, rpm ('Hz' is a unit of frequency)")):
        parse_quantity("60Hz", "angular frequency", name="omega")


def test_a_rotation_speed_in_rpm_is_an_angular_frequency():
    # issue 24, item 18: "3000rpm" was an unknown unit
    assert parse_quantity("3000rpm", "angular frequency", name="speed") == pytest.approx(100 * np.pi, rel=1e-15)
    assert parse_quantity("60 rpm", "angular frequency") == pytest.approx(2 * np.pi, rel=1e-15)
    with pytest.raises(ValueError, match=re.escape("unknown frequency unit 'rpm'; expected one of: Hz, kHz ('rpm' is "
                                                   "a unit of angular frequency)")):
        parse_quantity("3000rpm", "frequency")


@pytest.mark.parametrize("text, kind, default, value", [
    ("10mm", "length", None, 1e-2),
    ("2.5 um", "length", None, 2.5e-6),
    ("-3e-2N", "force", None, -3e-2),
    (".5mm", "length", None, 5e-4),
    ("200GPa", "pressure", None, 200e9),
    ("7", "length", None, 7.0),
    ("7", "length", "um", 7e-6),
    (7, "length", "um", 7e-6),
    (2.5, "force", None, 2.5),
    ("  1E3 kN ", "force", None, 1e6),
])
def test_parse_quantity(text, kind, default, value):
    assert parse_quantity(text, kind, default_unit=default) == pytest.approx(value, rel=1e-15)


@pytest.mark.parametrize("text, kind, message", [
    ("abc", "length", "--gap: cannot read 'abc' as a number with a length unit (e.g. '10mm')"),
    ("", "length", "--gap: cannot read '' as a number with a length unit"),
    ("1 2 mm", "length", "--gap: cannot read '1 2 mm' as a number"),
    (True, "length", "--gap: cannot read True as a number"),
    ("10parsec", "length", "--gap: unknown length unit 'parsec'; expected one of: m, mm"),
    ("10N", "length", "--gap: unknown length unit 'N'"),
])
def test_parse_quantity_errors_name_the_quantity(text, kind, message):
    with pytest.raises(ValueError, match=re.escape(message)):
        parse_quantity(text, kind, name="--gap")


# -- tables ------------------------------------------------------------------------------
@pytest.mark.parametrize("text", [
    "# measured\nt [um], n [um], T\n0, 2, 0\n0.5, 2, 3.5\n1.0, 2.1, 7\n",
    "t [um]; n [um]; T\n0; 2; 0\n0.5; 2; 3.5\n1.0; 2.1; 7\n",
    "t [um]\tn [um]\tT\n0\t2\t0\n0.5\t2\t3.5\n1.0\t2.1\t7\n",
    "t [um]  n [um]  T\n\n0 2 0\n  0.5   2   3.5\n   # a comment line\n1.0 2.1 7\n",
])
def test_read_table_with_units(tmp_path, text):
    path = tmp_path / "table.txt"
    path.write_text(text)
    columns, units = read_table(path)
    assert list(columns) == ["t", "n", "T"]
    assert units == {"t": "um", "n": "um", "T": ""}
    np.testing.assert_array_equal(columns["t"], [0.0, 0.5, 1.0])
    np.testing.assert_allclose(column_si(columns, units, "t", "length"), [0.0, 0.5e-6, 1e-6], rtol=1e-15)
    np.testing.assert_array_equal(column_si(columns, units, "T", "force"), [0.0, 3.5, 7.0])  # no unit: SI
    np.testing.assert_allclose(column_si(columns, units, "T", "force", unit="kN"), [0.0, 3.5e3, 7e3])


def test_single_column_with_unit(tmp_path):
    path = tmp_path / "t.csv"
    path.write_text("t [mm]\n1\n2\n")
    columns, units = read_table(path)
    assert units == {"t": "mm"}
    np.testing.assert_allclose(column_si(columns, units, "t", "length"), [1e-3, 2e-3], rtol=1e-15)


def test_header_only_is_refused_naming_the_file(tmp_path):
    # before: empty columns, and the caller failed later with "t must have at least 1 value(s)"
    path = tmp_path / "t.csv"
    path.write_text("t [um], n [um]\n")
    with pytest.raises(ValueError, match=re.escape(f"{path}: no data rows: the header (line 1) names the columns "
                                                   f"['t', 'n'], but no line of numbers follows it")):
        read_table(path)


@pytest.mark.parametrize("text, message", [
    ("", "the file holds no header and no data"),
    ("# only\n# comments\n\n", "the file holds no header and no data"),
    ("t [um, n\n1, 2\n", "cannot read the header cell 't [um'; expected 'name [unit]'"),
    ("t, n\n1, 2\n3\n", "line 3 has 1 cells, the header names 2"),
    ("# c\nt, n\n1, 2\n\n3, x\n", "line 5, column 'n': 'x' is not a number"),
])
def test_read_table_errors(tmp_path, text, message):
    path = tmp_path / "bad.csv"
    path.write_text(text)
    with pytest.raises(ValueError, match=re.escape(f"{path}: {message}")):
        read_table(path)


def test_read_table_missing_file(tmp_path):
    missing = tmp_path / "none.csv"
    with pytest.raises(FileNotFoundError, match=re.escape(f"table file {str(missing)!r} does not exist")):
        read_table(missing)


def test_column_si_errors(tmp_path):
    path = tmp_path / "t.csv"
    path.write_text("# c\nt [parsec], n [N], u [mm]\n1, 2, 5\n3, 4, nan\n")
    columns, units = read_table(path)
    with pytest.raises(ValueError, match=re.escape(f"{path}: no column 'x'; the columns are ['t', 'n', 'u']")):
        column_si(columns, units, "x", "length", path=path)
    with pytest.raises(ValueError, match=re.escape(f"{path}: column 't': unknown length unit 'parsec'")):
        column_si(columns, units, "t", "length", path=path)
    with pytest.raises(ValueError, match=re.escape("column 'n': unknown length unit 'N'")):
        column_si(columns, units, "n", "length", path=path)
    # an explicit unit overrides the header's
    np.testing.assert_array_equal(column_si(columns, units, "t", "length", path=path, unit="mm"), [1e-3, 3e-3])
    # a value that is not finite: the file and its line (before: accepted, the caller failed without either)
    with pytest.raises(ValueError, match=re.escape(f"{path}: line 4, column 'u': nan is not a finite number")):
        column_si(columns, units, "u", "length", path=path)
    # a plain dict (no file lines): the data row
    with pytest.raises(ValueError, match=re.escape("x.json: data row 2, column 't': inf is not a finite number")):
        column_si({"t": np.array([1.0, np.inf])}, {"t": "mm"}, "t", "length", path="x.json")


@pytest.mark.parametrize("text, value", [("2%", 0.02), ("2 %", 0.02), ("0.02", 0.02), (".5", 0.5), ("1", 1.0),
                                         ("150%", 1.5), ("-3%", -0.03), (0.25, 0.25)])
def test_fractions_are_read_as_fractions_or_percentages(text, value):
    from microslip.common.units import parse_fraction

    assert parse_fraction(text) == pytest.approx(value, rel=1e-15)


@pytest.mark.parametrize("text, message", [
    ("2", "--energy-target: '2' is a fraction above 1 (fractions: 0.02 means 2 %); write 2% for 2 percent, or 0.02"),
    ("2N", "--energy-target: cannot read '2N' as a fraction such as 0.02 or a percentage such as 2%"),
    ("two", "cannot read 'two'"),
])
def test_a_bare_number_above_one_is_refused_with_both_spellings(text, message):
    from microslip.common.units import parse_fraction

    with pytest.raises(ValueError, match=re.escape(message)):
        parse_fraction(text, name="--energy-target")
