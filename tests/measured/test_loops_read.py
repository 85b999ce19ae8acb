"""Reading measured loops: text tables with units, the damper JSON, and every error message."""

import json

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
    with pytest.raises(ValueError, match=r"no column 'disp' \(asked for 't'\)"):
        loops.read(path, columns={"t": "disp"})


def test_unknown_unit_and_unit_of_wrong_kind(tmp_path):
    with pytest.raises(ValueError, match=r"column 't'.*unknown length unit 'furlong'"):
        loops.read(_write(tmp_path, _sine_table(header="time [s],t [furlong],T [N]")))
    with pytest.raises(ValueError, match=r"column 'T'.*unknown force unit 'mm'"):
        loops.read(_write(tmp_path, _sine_table(header="time [s],t [um],T [mm]")))


def test_column_without_unit_is_refused(tmp_path):
    with pytest.raises(ValueError, match=r"column 't' \(length\) has no unit"):
        loops.read(_write(tmp_path, _sine_table(header="time [s],t,T [N]")))


def test_non_numeric_cell_names_row_and_column(tmp_path):
    text = _sine_table().splitlines()
    text[5] = "0.004,oops,3.0"
    with pytest.raises(ValueError, match=r"line 6, column 't': 'oops' is not a number"):
        loops.read(_write(tmp_path, "\n".join(text)))


def test_non_finite_cell_names_row_and_column(tmp_path):
    text = _sine_table().splitlines()
    text[3] = "0.002,0.1,nan"
    with pytest.raises(ValueError, match=r"data row 3 \(counting rows of numbers\), column 'T': nan is not"):
        loops.read(_write(tmp_path, "\n".join(text)))


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
