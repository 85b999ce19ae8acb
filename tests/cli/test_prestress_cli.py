"""``[prestress]`` and ``--prestress`` of ``microslip frf`` and ``microslip modes``: a chain with a bolted contact.

The chain of ``tests/frequency/test_prestress.py``: two masses along x (DOFs x1, x2), the second pressed
on a Jenkins contact by a 300 N preload along its own normal DOF y2 (a 2e6 N/m spring shares it: the
contact carries N0 = 200 N), a 40 N static force on x2. Released: x2 = 40 N (1/k1 + 1/k2) = 8e-5 m;
stuck: the contact's kt = 1e6 N/m in parallel, x2 = 40 N * 2e6 / 3e12 = 2.667e-5 m.
"""

import csv

import numpy as np
import pytest

from microslip import MicroslipModel
from microslip.cli import main
from microslip.common._table import read_table
from microslip.config import ConfigError, load_config

CONFIG = """title = "bolted chain"

[structure]
M = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
K = [[2e6, -1e6, 0.0], [-1e6, 1e6, 0.0], [0.0, 0.0, 2e6]]
rayleigh = [0.0, 1e-4]
dofs = ["x1", "x2", "y2"]

[[contact]]
model = "jenkins.json"
tangential = 1
normal = 2
preload = "300N"
name = "joint"

[excitation]
static = {x2 = 40.0}
h1 = {x2 = 5.0}

[sweep]
omega = [900, 1100]
harmonics = 3

[modes]
amplitude = [1e-7, 1e-5]
dof = "x2"
compare = false

[prestress]
friction = "released"
modal_damping = [0.02, 0.02]
"""


@pytest.fixture
def chain_config(tmp_path):
    MicroslipModel([1e6], [4e6], [0.0], 0.5).save(tmp_path / "jenkins.json")
    (tmp_path / "chain.toml").write_text(CONFIG)
    return tmp_path / "chain.toml"


@pytest.mark.parametrize("flag, x2", [([], 8e-5), (["--prestress", "stuck"], 40.0 * 2e6 / 3e12)])
def test_frf_starts_from_the_prestressed_state(chain_config, capsys, flag, x2):
    out = chain_config.parent / "out"
    assert main(["frf", str(chain_config), "--out", str(out), "--quiet", *flag]) == 0
    columns, _ = read_table(out / "frf.csv")
    # the mean of x2 along the curve: the prestressed static state (the vibration, 5 N far below mu N0, sticks)
    assert np.allclose(columns["x2 static"], x2, rtol=1e-8)
    with open(out / "prestress.csv", newline="") as f:
        (row,) = list(csv.DictReader(f))
    assert row["contact"] == "joint" and float(row["N0 [N]"]) == pytest.approx(200.0, rel=1e-12)
    report = (out / "report.md").read_text()
    assert "Prestress: a static step with the friction" in report and "Linear modes of the prestressed" in report
    assert "modal damping ratios 0.02, 0.02" in report
    assert "normal force N0 = 200 N" in capsys.readouterr().out


def test_modes_vibrate_about_the_prestress(chain_config, capsys):
    out = chain_config.parent / "out"
    assert main(["modes", str(chain_config), "--out", str(out), "--quiet"]) == 0
    assert (out / "prestress.csv").is_file()
    printed = capsys.readouterr().out
    lowest = printed.split("prestressed modes (Hz): ")[1].split(",")[0]
    # the nonlinear mode starts at the prestressed structure's linear mode
    assert f"Mode 1: {lowest} Hz with the contacts stuck" in printed


@pytest.mark.parametrize("old, new, words", [
    ('friction = "released"', 'friction = "loose"', "[prestress] friction must be one of 'released', 'stuck'"),
    ('friction = "released"', 'fricton = "released"', "[prestress] has an unknown key 'fricton'"),
    ("modal_damping = [0.02, 0.02]", "modal_damping = [0.02, 0.02]\nrayleigh_damping = [0.01, 0.02]",
     "give either modal_damping or rayleigh_damping"),
    ("modal_damping = [0.02, 0.02]", "modal_damping = 0.02", "[prestress] modal_damping must be a list"),
    ("modal_damping = [0.02, 0.02]", "modal_damping = [-0.02]", "[prestress] modal_damping must be non-negative"),
    ("modal_damping = [0.02, 0.02]", "rayleigh_damping = [0.01, 0.02]\nrayleigh_modes = [2, 2]",
     "rayleigh_modes must be two different modes"),
    ("modal_damping = [0.02, 0.02]", "modes = 4", "asks for 4 prestressed modes; the structure has 3 DOFs"),
])
def test_prestress_table_errors_name_the_key(chain_config, old, new, words):
    text = chain_config.read_text()
    assert old in text
    chain_config.write_text(text.replace(old, new))
    with pytest.raises(ConfigError) as info:
        load_config(chain_config)
    assert words in str(info.value)


def test_a_design_study_case_solves_the_prestress(chain_config):
    from microslip.study.solve import _frf

    for friction, T0 in (("released", 0.0), ("stuck", 1e6 * 40.0 * 2e6 / 3e12)):
        chain_config.write_text(CONFIG.replace('friction = "released"', f'friction = "{friction}"'))
        row, _ = _frf(load_config(chain_config))
        assert row["static T0 joint (N)"] == pytest.approx(T0, abs=1e-9)
