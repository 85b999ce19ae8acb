"""A unit given apart from the file (``units=``, ``--t-unit``, ``--T-unit``, ``--unit``) fills in a header
without one and never overrides the header's: a conflicting one is refused, naming both."""

from __future__ import annotations

import re

import numpy as np
import pytest

from microslip import MicroslipModel, loops
from microslip.cli import main
from microslip.loops.synthetic import dataset_files


def _table(tmp_path, header, name="run.csv"):
    k = np.arange(64)
    rows = [f"{0.5 * np.sin(k_ / 8):.6f}, {10 * np.cos(k_ / 8):.6f}" for k_ in k]
    path = tmp_path / name
    path.write_text(header + "\n" + "\n".join(rows) + "\n")
    return path


def test_read_refuses_a_unit_that_conflicts_with_the_header(tmp_path):
    path = _table(tmp_path, "t [um], T [N]")
    with pytest.raises(ValueError, match=re.escape(
            f"{path}: column 't' is in 'um' by its header, but units['t'] gives 'mm'; units['t'] only applies to "
            f"a column whose header has no unit")):
        loops.read(path, units={"t": "mm"})
    with pytest.raises(ValueError, match=re.escape("column 'T' is in 'N' by its header, but units['T'] gives 'kN'")):
        loops.read(path, units={"T": "kN"})


def test_read_accepts_the_same_unit_and_fills_in_a_missing_one(tmp_path):
    path = _table(tmp_path, "t [um], T [N]")
    ref = loops.read(path)
    # the same unit, or another symbol of it, is no conflict
    for given in ({"t": "um"}, {"t": "µm", "T": "N"}):
        np.testing.assert_array_equal(loops.read(path, units=given).t, ref.t)
    bare = _table(tmp_path, "t, T [N]", "bare.csv")
    np.testing.assert_allclose(loops.read(bare, units={"t": "mm"}).t, 1e3 * ref.t, rtol=1e-15)


def test_cli_tune_refuses_a_conflicting_t_unit(tmp_path, capsys):
    # the shipped files say 't [um]': --t-unit mm used to read them 1000 x too large
    rc = main(["tune", str(dataset_files()[-1]), "--t-unit", "mm", "-o", str(tmp_path / "m.json"), "--quiet"])
    err = capsys.readouterr().err
    # the command line's message names its own option, not the Python argument
    assert rc == 2 and "column 't' is in 'um' by its header, but --t-unit gives 'mm'" in err and "units[" not in err
    assert not (tmp_path / "m.json").exists()


def test_cli_simulate_unit_only_fills_in(tmp_path, capsys):
    model_file = tmp_path / "model.json"
    assert main(["tune", "-o", str(model_file)]) == 0
    history = tmp_path / "h.csv"
    history.write_text("t [um]\n0\n0.5\n1\n")
    rc = main(["simulate", str(model_file), str(history), "--n", "2um", "--unit", "mm",
               "-o", str(tmp_path / "f.csv")])
    err = capsys.readouterr().err
    assert rc == 2 and (f"{history}: column 't' is in 'um' by its header, but --unit gives 'mm'; --unit only "
                        f"applies to a column whose header has no unit") in err
    assert not (tmp_path / "f.csv").exists()
    # the header's own unit again, or a bare header: the same forces
    out_same, out_bare = tmp_path / "same.csv", tmp_path / "bare.csv"
    assert main(["simulate", str(model_file), str(history), "--n", "2um", "--unit", "um", "-o", str(out_same)]) == 0
    history.write_text("t\n0\n0.5\n1\n")
    assert main(["simulate", str(model_file), str(history), "--n", "2um", "--unit", "um", "-o", str(out_bare)]) == 0
    expected = MicroslipModel.load(model_file).simulate(np.array([0.0, 0.5e-6, 1e-6]), 2e-6).T
    for out in (out_same, out_bare):
        data = np.loadtxt(out, delimiter=",", skiprows=1)
        np.testing.assert_allclose(data[:, 2], expected, rtol=1e-12)
