"""``microslip campbell``: the frf configuration with a [speed] table to a Campbell diagram (CSV, PNG)."""

import csv

import numpy as np
import pytest
import scipy.io

from microslip import MicroslipModel
from microslip.cli import main
from microslip.config import ConfigError, load_config
from microslip.frequency import CyclicStructure, SpeedModel, Structure, campbell

K0 = np.array([[3e6, -1e6, -1e6, 0.0], [-1e6, 2e6, 0.0, -1e6], [-1e6, 0.0, 1e6, 0.0], [0.0, -1e6, 0.0, 1e6]])
K1 = np.diag([0.0, 0.2, 0.0, 0.1])  # N s^2/m
M = np.diag([0.1, 0.05, 0.1, 0.02])
LAW = MicroslipModel([1e5, 2e5], [1e6, 1e6], [0.0, 0.0], 0.5)


def read_csv(path) -> dict:
    """``{column header: values}``: floats, blank cells (the padding of the shorter columns) left out."""
    with open(path, newline="") as fh:
        table = list(csv.DictReader(fh))
    out = {}
    for name in table[0]:
        cells = [row[name] for row in table if row[name] != ""]
        try:
            out[name] = np.array([float(c) for c in cells])
        except ValueError:
            out[name] = cells
    return out


def rows(A) -> str:
    return "[" + ", ".join("[" + ", ".join(repr(float(v)) for v in row) + "]" for row in A) + "]"


def write(folder, extra: str, contact: str) -> str:
    LAW.save(folder / "contact.json")
    text = (f'title = "test disk"\n\n[structure]\nM = {rows(M)}\nK = {rows(K0)}\n\n' + extra
            + f'\n[[contact]]\nmodel = "contact.json"\n{contact}\nnormal = {{"1" = 1.0}}\npreload = "3N"\n')
    path = folder / "campbell.toml"
    path.write_text(text)
    return str(path)


PLAIN = f'[speed]\nat = [0.0, "9549.296585513721rpm"]\nK = [{rows(K0 + 1e6 * K1)}]\n\n' \
        '[campbell]\nspeeds = [0.0, 4000.0]\npoints = 9\nengine_orders = [1, 2, 3]\nmodes = 3\n'


def test_campbell_of_a_plain_structure_is_the_librarys(tmp_path, capsys):
    """The CSV is the library's diagram of the same model, bit for bit (the same computation), so the
    command's work is the reading: the second speed in rpm (1000 rad/s), the matrices, the contact."""
    cfg = write(tmp_path, PLAIN, 'tangential = {"3" = 1.0}')
    out = tmp_path / "out"
    assert main(["campbell", cfg, "--out", str(out)]) == 0
    printed = capsys.readouterr()
    assert "[1/20] stuck system at 0 rad/s" in printed.err and "Campbell diagram in" in printed.err
    assert "crossings with engine orders 1, 2, 3" in printed.out and "wrote" in printed.out
    assert (out / "campbell.png").stat().st_size > 0
    template = Structure(M, None, K0)
    template.add_contact(LAW, tangential={3: 1.0}, normal={1: 1.0}, preload=3.0)
    model = SpeedModel(M, None, [K0, K0 + 1e6 * K1], [0.0, 1000.0], contacts=template)
    want = campbell(model, np.linspace(0.0, 4000.0, 9), modes=3, engine_orders=[1, 2, 3])
    columns = read_csv(out / "campbell.csv")
    np.testing.assert_array_equal(columns["stuck mode 2 [Hz]"], want.frequencies["stuck"][:, 1] / (2 * np.pi))
    np.testing.assert_array_equal(columns["free mode 3 [Hz]"], want.frequencies["free"][:, 2] / (2 * np.pi))
    np.testing.assert_array_equal(columns["speed [rad/s]"], want.speeds)
    n = len(want.crossings)
    assert n >= 4
    np.testing.assert_array_equal(columns["crossing speed [rad/s]"], [c["speed"] for c in want.crossings])
    # the options override [campbell]
    assert main(["campbell", cfg, "--out", str(out), "--quiet", "--points", "5", "--modes", "2",
                 "--engine-orders", "1-2", "--contacts", "free"]) == 0
    assert capsys.readouterr().err == ""
    columns = read_csv(out / "campbell.csv")
    assert columns["speed [rad/s]"].size == 5 and "free mode 2 [Hz]" in columns and "free mode 3 [Hz]" not in columns
    assert "stuck mode 1 [Hz]" not in columns and set(columns["crossing engine order [-]"]) <= {1, 2}


def test_campbell_of_a_cyclic_sector_solves_each_diameter(tmp_path, capsys):
    """A sector, its stiffness at the second speed read from a Matrix Market file, a contact to the next sector,
    no engine order: the library's diagram of the same sector, every diameter, each crossing in its own."""
    scipy.io.mmwrite(str(tmp_path / "K1000.mtx"), K0 + 1e6 * K1)
    extra = ('[cyclic]\nsectors = 6\nleft = [0]\nright = [2]\n\n[speed]\nat = ["0rad/s", "1000rad/s"]\n'
             'K = ["K1000.mtx"]\n\n[campbell]\nspeeds = ["0rpm", "38197rpm"]\npoints = 9\nengine_orders = [1, 5, 7]\n'
             'modes = 2\nnodal_diameters = [0, 1, 3]\n')
    cfg = write(tmp_path, extra, 'tangential = {"3" = 1.0, "next:3" = -1.0}')
    out = tmp_path / "out"
    assert main(["campbell", cfg, "--out", str(out), "--quiet"]) == 0
    assert "nodal diameters 0, 1, 3 of 6 sectors" in capsys.readouterr().out
    template = CyclicStructure(M, None, K0, sectors=6, left=[0], right=[2])
    template.add_contact(LAW, tangential={3: 1.0, template.next(3): -1.0}, normal={1: 1.0}, preload=3.0)
    model = SpeedModel(M, None, [K0, K0 + 1e6 * K1], [0.0, 1000.0], contacts=template)
    want = campbell(model, np.linspace(0.0, 38197 / 60 * 2 * np.pi, 9), modes=2, engine_orders=[1, 5, 7],
                    nodal_diameters=[0, 1, 3])
    columns = read_csv(out / "campbell.csv")
    np.testing.assert_allclose(columns["stuck ND 1 mode 1 [Hz]"], want.frequencies["stuck"][:, 1, 0] / (2 * np.pi),
                               rtol=1e-12)  # the file's matrix is the inline one written with 16 digits
    assert len(want.crossings) >= 3 and set(columns["crossing nodal diameter [-]"]) == {1}  # 1, 5, 7 excite ND 1
    np.testing.assert_allclose(columns["crossing speed [rad/s]"], [c["speed"] for c in want.crossings], rtol=1e-10)


@pytest.mark.parametrize("edit, message", [
    (lambda t: t.replace("[speed]\nat", "[speed]\nspeds = 1\nat"), "[speed] has an unknown key 'speds'"),
    (lambda t: t.replace("points = 9", "point = 9"), "[campbell] has an unknown key 'point'"),
    (lambda t: t.replace("at = [0.0,", "at = [0.0, 500.0,"), "[speed] K must hold one matrix per speed after the first (2"),
    (lambda t: t.replace("engine_orders = [1, 2, 3]", "engine_orders = [0]"), "[campbell] engine_orders[0] must be"),
    (lambda t: t.replace("speeds = [0.0, 4000.0]", "speeds = [4000.0, 0.0]"), "[campbell] speeds must rise"),
    (lambda t: t.replace("[speed]\n", "[sped]\n"), "the file has an unknown key 'sped'"),
    (lambda t: t[:t.index("[speed]")] + t[t.index("[campbell]"):], "microslip campbell needs a [speed] table"),
    (lambda t: t.replace("modes = 3", 'modes = 3\ncontacts = "sliding"'), "[campbell] contacts must be one of"),
])
def test_a_bad_configuration_is_refused_by_name(tmp_path, edit, message, capsys):
    cfg = write(tmp_path, PLAIN, 'tangential = {"3" = 1.0}')
    (tmp_path / "campbell.toml").write_text(edit((tmp_path / "campbell.toml").read_text()))
    with pytest.raises((ConfigError, ValueError), match=message.replace("[", r"\[").replace("]", r"\]")
                       .replace("(", r"\(")):
        load_config(cfg, campbell=True)
    assert main(["campbell", cfg, "--out", str(tmp_path / "out"), "--quiet"]) == 2
    assert "microslip campbell: error:" in capsys.readouterr().err


def test_the_engine_orders_option_is_checked_when_read(tmp_path, capsys):
    cfg = write(tmp_path, PLAIN, 'tangential = {"3" = 1.0}')
    for bad in ("0", "3-1", "one", "1,,2"):
        with pytest.raises(SystemExit) as exc:
            main(["campbell", cfg, "--engine-orders", bad])
        assert exc.value.code == 2
        assert "argument --engine-orders" in capsys.readouterr().err
