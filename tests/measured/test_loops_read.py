"""Reading measured loops: text tables with units, the damper JSON, and every error message."""

import codecs
import json
import re

import numpy as np
import pytest

from microslip import loops
from _paths import DAMPER


def _write(tmp_path, text, name="loops.csv"):
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


def _sine_table(sep=",", header="time [s],t [um],T [N]", samples=64, extra=""):
    k = np.arange(samples)
    rows = [header] + [sep.join(f"{v:.6g}" for v in (i * 1e-3, 0.5 * np.sin(k_ / 8), 10 * np.cos(k_ / 8)))
                       for i, k_ in zip(k, k)]
    return extra + "\n".join(rows) + "\n"


def test_csv_is_converted_to_si(tmp_path):
    r = loops.read(_write(tmp_path, _sine_table()))
    k = np.arange(64)
    np.testing.assert_allclose(r.t, 0.5e-6 * np.sin(k / 8), rtol=1e-5, atol=1e-12)  # µm -> m, 6 digits
    np.testing.assert_allclose(r.T, 10 * np.cos(k / 8), rtol=1e-5, atol=1e-5)
    np.testing.assert_allclose(r.time, k * 1e-3)
    assert r.N is None and r.normal_load is None and r.source == "loops.csv"


def test_whitespace_table_and_column_and_unit_overrides(tmp_path):
    text = _sine_table(sep=" ", header="clock  disp  force")
    r = loops.read(_write(tmp_path, text, "run.txt"), columns={"t": "disp", "T": "force", "time": "clock"},
                   units={"t": "mm", "T": "kN", "time": "ms"})
    assert r.t.max() == pytest.approx(0.5e-3, rel=1e-3)
    assert r.T.max() == pytest.approx(10e3, rel=1e-3)
    assert r.time[1] == pytest.approx(1e-6)


def test_whitespace_table_with_spaced_units(tmp_path):
    r = loops.read(_write(tmp_path, _sine_table(sep="  ", header="time [s]   t [um]   T [N]"), "ws.txt"))
    assert r.t.max() == pytest.approx(0.5e-6, rel=1e-3) and r.time[1] == pytest.approx(1e-3)


def test_normal_load_from_argument_comment_and_column(tmp_path):
    base = _sine_table()
    assert loops.read(_write(tmp_path, base), normal_load="36.6N").normal_load == pytest.approx(36.6)
    assert loops.read(_write(tmp_path, base), normal_load=12.0).normal_load == 12.0
    commented = _write(tmp_path, "# a comment\n# normal load = 2.5 kN\n" + base, "c.csv")
    assert loops.read(commented).normal_load == pytest.approx(2500.0)
    with_N = "t [um];T [N];N [N]\n" + "\n".join(f"{np.sin(i / 5):.5f};{np.cos(i / 5):.5f};{30 + (i % 2)}"
                                                for i in range(40))
    r = loops.read(_write(tmp_path, with_N, "n.csv"))
    assert r.normal_load == pytest.approx(30.5) and r.N.size == 40


def test_missing_column_names_those_present(tmp_path):
    path = _write(tmp_path, _sine_table(header="time [s],x2 [um],T [N]"))
    with pytest.raises(ValueError, match=r"no column for 't' \(length\).*'x2'"):
        loops.read(path)
    with pytest.raises(ValueError, match=re.escape("no column 'disp' (given by columns['t']); the columns are")):
        loops.read(path, columns={"t": "disp"})


def test_missing_force_column_advises_in_python_terms(tmp_path):
    path = _write(tmp_path, _sine_table(header="time [s],t [um],Fx [N]"))
    with pytest.raises(ValueError, match=re.escape(f"{path}: no column for 'T' (force): looked for ['T', 'F', "
                                                   f"'force', 'friction force', 'tangential force'], the columns "
                                                   f"are ['time', 't', 'Fx']; name it with columns={{'T': ...}}")):
        loops.read(path)


def test_unknown_unit_and_unit_of_wrong_kind(tmp_path):
    with pytest.raises(ValueError, match=r"column 't'.*unknown length unit 'furlong'"):
        loops.read(_write(tmp_path, _sine_table(header="time [s],t [furlong],T [N]")))
    with pytest.raises(ValueError, match=r"column 'T'.*unknown force unit 'mm'"):
        loops.read(_write(tmp_path, _sine_table(header="time [s],t [um],T [mm]")))


def test_column_without_unit_is_refused(tmp_path):
    with pytest.raises(ValueError, match=re.escape("column 't' (length) has no unit in the header; write it as "
                                                   "'t [unit]' or give units={'t': ...}")):
        loops.read(_write(tmp_path, _sine_table(header="time [s],t,T [N]")))


def test_non_numeric_cell_names_row_and_column(tmp_path):
    text = _sine_table().splitlines()
    text[5] = "0.004,oops,3.0"
    with pytest.raises(ValueError, match=r"line 6, column 't': 'oops' is not a number"):
        loops.read(_write(tmp_path, "\n".join(text)))


@pytest.mark.parametrize("cell, shown", [("nan", "nan"), ("NaN", "nan"), ("inf", "inf"), ("-1e999", "-inf")])
def test_non_finite_cell_names_the_file_line_and_column(tmp_path, cell, shown):
    # two comment lines and a blank line above the header: the line is counted in the file, as an
    # editor shows it (header on line 4, first data row on line 5, text[3] of the table on line 7)
    text = _sine_table().splitlines()
    text[3] = f"0.002,0.1,{cell}"
    path = _write(tmp_path, "# rig 2\n# normal load = 30 N\n\n" + "\n".join(text))
    with pytest.raises(ValueError, match=re.escape(f"{path}: line 7, column 'T': {shown} is not a finite number")):
        loops.read(path)
    # a line the fast reader refuses (a ragged-looking but valid row: spaces after the commas) counts alike
    text[1] = "0,  0,  10"
    path = _write(tmp_path, "\n".join(text), "slow.csv")
    with pytest.raises(ValueError, match=re.escape(f"{path}: line 4, column 'T': {shown} is not a finite number")):
        loops.read(path)


@pytest.mark.parametrize("newline", ["\n", "\r\n", "\r"])
def test_lines_are_counted_as_an_editor_counts_them(tmp_path, newline):
    text = _sine_table().splitlines()
    # a blank line, a line of spaces and a comment among the data: lines 4, 6 and 8 of the file
    text[3:3] = [""]
    text[5:5] = ["   "]
    text[7:7] = ["# the rig paused"]
    text[10] = "0.007,0.2,nan"  # line 11
    path = tmp_path / "edited.csv"
    path.write_bytes((newline.join(text) + newline + newline).encode())
    with pytest.raises(ValueError, match=re.escape(f"{path}: line 11, column 'T': nan is not a finite number")):
        loops.read(path)
    text[10] = "0.007,0.2,1.0"
    path.write_bytes((newline.join(text) + newline).encode())
    assert loops.read(path).samples == 64


def test_non_finite_value_in_an_unused_column_is_left_alone(tmp_path):
    k = np.arange(64)
    rows = [f"{np.sin(i / 8):.6g},{10 * np.cos(i / 8):.6g},{'nan' if i == 3 else 1.0}" for i in k]
    r = loops.read(_write(tmp_path, "t [um],T [N],v [m/s]\n" + "\n".join(rows)))
    assert r.samples == 64


def test_non_finite_value_in_the_damper_json_names_the_data_row(tmp_path):
    rows = [[i / 1024, np.sin(i / 10), 2 * np.cos(i / 10), 0.0, 100.0, 50.0] for i in range(40)]
    rows[6][2] = float("nan")
    doc = {"data": rows, "time units": "s", "displacement units": "in", "friction force units": "kip",
           "actuator force units": "lb"}
    path = _write(tmp_path, json.dumps(doc), "nan.json")
    with pytest.raises(ValueError, match=re.escape(f"{path}: data row 7, column 'friction force': nan is not a "
                                                   f"finite number")):
        loops.read(path)


def test_header_without_data_rows_names_the_file(tmp_path):
    path = _write(tmp_path, "# normal load = 30 N\ntime [s],t [um],T [N]\n\n# end\n", "empty.csv")
    with pytest.raises(ValueError, match=re.escape(f"{path}: no data rows: the header (line 2) names the columns "
                                                   f"['time', 't', 'T'], but no line of numbers follows it")):
        loops.read(path)


def test_a_column_name_given_twice_is_refused(tmp_path):
    # before: the second 't' silently replaced the first
    path = _write(tmp_path, _sine_table(header="time [s],t [um],T [N]").replace("time [s]", "t [mm]", 1))
    with pytest.raises(ValueError, match=re.escape(f"{path}: the header (line 1) names the column 't' twice, as "
                                                   f"columns 1 and 2; rename one of them")):
        loops.read(path)
    path = _write(tmp_path, "# c\n" + _sine_table(sep=" ", header="time [s]  t [um]  T [N]  T [kN]"), "ws.txt")
    with pytest.raises(ValueError, match=re.escape("the header (line 2) names the column 'T' twice, as columns 3 "
                                                   "and 4")):
        loops.read(path)


# -- encodings ----------------------------------------------------------------------------------

_ACCENTED = ("# Prüfstand 2, 20 °C, Kraftaufnehmer ± 0.1 N\n# normal load = 30 N\n"
             + _sine_table(header="time [s],t [µm],T [N]"))


@pytest.mark.parametrize("encoding, bom", [
    ("utf-8", b""), ("utf-8", codecs.BOM_UTF8), ("latin-1", b""), ("cp1252", b""),
    ("utf-16-le", codecs.BOM_UTF16_LE), ("utf-16-be", codecs.BOM_UTF16_BE), ("utf-16-le", b""),
    ("utf-16-be", b""), ("utf-32-le", codecs.BOM_UTF32_LE)])
def test_common_encodings_and_byte_order_marks_read_alike(tmp_path, encoding, bom):
    reference = loops.read(_write(tmp_path, _ACCENTED, "ref.csv"))
    path = tmp_path / "enc.csv"
    path.write_bytes(bom + _ACCENTED.encode(encoding))
    r = loops.read(path)
    # before: a UTF-8 mark made the first header cell '\ufeff#...' (a header, not a comment) or
    # '\ufefftime' (the time column dropped silently); other encodings failed to decode
    assert r.time is not None and r.normal_load == 30.0
    for name in ("t", "T", "time"):
        np.testing.assert_array_equal(getattr(r, name), getattr(reference, name))


def test_cp1252_characters_outside_latin1_are_read(tmp_path):
    path = tmp_path / "win.csv"
    path.write_bytes(("# Prüfung – „Reibung“ 5 €\n" + _sine_table()).encode("cp1252"))
    assert loops.read(path).samples == 64


def test_utf8_byte_order_mark_before_a_plain_header(tmp_path):
    path = tmp_path / "bom.csv"
    path.write_bytes(codecs.BOM_UTF8 + _sine_table().encode())
    r = loops.read(path)
    np.testing.assert_allclose(r.time, np.arange(64) * 1e-3)


def test_damper_json_with_a_byte_order_mark(tmp_path):
    rows = [[i / 1024, np.sin(i / 10), 2 * np.cos(i / 10), 0.0, 100.0, 50.0] for i in range(40)]
    doc = {"data": rows, "time units": "s", "displacement units": "in", "friction force units": "kip",
           "actuator force units": "lb"}
    path = tmp_path / "bom.json"
    path.write_bytes(codecs.BOM_UTF8 + json.dumps(doc).encode())
    assert loops.read(path).samples == 40


@pytest.mark.parametrize("raw, message", [
    (codecs.BOM_UTF8 + b"t [um],T [N]\n1,2\n\xb5\n", "the table reads as UTF-8 but is not valid UTF-8 near line 3 (byte 20"),
    (codecs.BOM_UTF16_LE + "t [um],T [N]\n".encode("utf-16-le") + b"\x00\xdc",
     "the table reads as UTF-16 but is not valid UTF-16 near line 2 (byte 28"),
    (b"PK\x03\x04\x14\x00\x06\x00", "not a text table: it holds binary data (a zero byte at byte 5)"),
])
def test_undecodable_file_is_named(tmp_path, raw, message):
    path = tmp_path / "bad.csv"
    path.write_bytes(raw)
    with pytest.raises(ValueError, match=re.escape(f"{path}: {message}")):
        loops.read(path)


def test_too_few_samples(tmp_path):
    with pytest.raises(ValueError, match=r"too few samples: 5"):
        loops.read(_write(tmp_path, _sine_table(samples=5)))


def test_no_complete_cycle(tmp_path):
    ramp = "t [um],T [N]\n" + "\n".join(f"{i / 10},{i}" for i in range(50))
    with pytest.raises(loops.LoopError, match=r"no complete cycle: 0 reversal\(s\)"):
        loops.analyse(loops.read(_write(tmp_path, ramp)))


def test_missing_file_and_bad_options(tmp_path):
    with pytest.raises(FileNotFoundError, match="does not exist"):
        loops.read(tmp_path / "absent.csv")
    path = _write(tmp_path, _sine_table())
    with pytest.raises(ValueError, match=r"unknown role\(s\) \['x'\]"):
        loops.read(path, columns={"x": "t"})
    with pytest.raises(TypeError, match="units must be a dict"):
        loops.read(path, units="um")


def test_damper_json_layout_errors(tmp_path):
    with pytest.raises(ValueError, match="not valid JSON"):
        loops.read(_write(tmp_path, "{", "a.json"))
    with pytest.raises(ValueError, match="expected a JSON object with a 'data' matrix"):
        loops.read(_write(tmp_path, json.dumps({"x": 1}), "b.json"))
    with pytest.raises(ValueError, match=r"'data' must have 6 columns"):
        loops.read(_write(tmp_path, json.dumps({"data": [[0, 1]] * 20}), "c.json"))
    doc = {"data": [[0, 1, 2, 3, 4, 5]] * 20, "time units": "s", "displacement units": "in",
           "friction force units": "kip"}
    with pytest.raises(ValueError, match="missing the key 'actuator force units'"):
        loops.read(_write(tmp_path, json.dumps(doc), "d.json"))


def test_damper_json_small_file_converts_inches_and_kips(tmp_path):
    rows = [[i / 1024, np.sin(i / 10), 2 * np.cos(i / 10), 0.0, 100.0, 50.0] for i in range(100)]
    doc = {"data": rows, "time units": "s", "displacement units": "in", "friction force units": "kip",
           "actuator force units": "lb"}
    r = loops.read(_write(tmp_path, json.dumps(doc), "small.json"))
    np.testing.assert_allclose(r.t, 0.0254 * np.sin(np.arange(100) / 10))
    np.testing.assert_allclose(r.T, 2 * 4448.2216152605 * np.cos(np.arange(100) / 10))
    assert r.normal_load == pytest.approx(150 * 4.4482216152605)  # both band actuators


def test_real_damper_record_reads_in_si():
    r = loops.read(DAMPER / "1Hz20lbtension.json")
    raw = np.asarray(json.loads((DAMPER / "1Hz20lbtension.json").read_text())["data"])
    assert r.samples == raw.shape[0] == 10241
    np.testing.assert_allclose(r.t, raw[:, 1] * 0.0254)
    np.testing.assert_allclose(r.T, raw[:, 2] * 4448.2216152605)
    # independent summary in tests/data/arts-friction-damper/README.md: displacement -1.016..+1.074 in,
    # force -2.005..+2.314 kip
    assert r.t.min() / 0.0254 == pytest.approx(-1.016, abs=1e-3)
    assert r.T.max() / 4448.2216152605 == pytest.approx(2.314, abs=1e-3)
