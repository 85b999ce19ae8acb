"""``microslip modes`` on a blade sector read from files (issue 26 item 5): the route of examples/damper_sector.py.

The example writes the sector's matrices (Matrix Market), its DOF map, the damper's contact laws and a
configuration; the command's mode must be the one ``nonlinear_modes`` computes from the same files, built
here through the API from the raw TOML values (not through the configuration reader).
"""

import dataclasses
import re
import sys
import tomllib
import warnings

import matplotlib.pyplot as plt
import numpy as np
import pytest
import scipy.io

from _paths import EXAMPLES
from microslip import MicroslipModel, nonlinear_modes
from microslip.cli import main
from microslip.common._table import read_table
from microslip.fe import DofMap
from microslip.frequency import CyclicStructure, UnderPlatformDamper, UnderResolvedWarning

sys.path.insert(0, str(EXAMPLES))
import damper_sector  # noqa: E402

# harmonics 0-1 where the damper's contacts start to slide (its damping ratio rises from 0.3 % to 1.6 %): about
# 20 points, seconds; the example's own range (1e-9 to 1e-4) and H = 3 take minutes
AMPLITUDE = (1e-6, 3e-6)  # kg^1/2 m


def api_sector(folder):
    """The sector and its damper through the API, from the files and the raw values of ``folder/config.toml``."""
    toml = tomllib.loads((folder / "config.toml").read_text())
    st, cyc, dmp = toml["structure"], toml["cyclic"], toml["damper"][0]
    M = scipy.io.mmread(folder / st["M"]).toarray()
    K = scipy.io.mmread(folder / st["K"]).toarray()
    alpha, beta = st["rayleigh"]
    dofs = DofMap.from_csv(folder / st["dof_map"])
    disk = CyclicStructure(M, alpha * M + beta * K, K, sectors=cyc["sectors"], left=[], right=[])

    def dof(name):
        return disk.next(dofs.index(name[5:])) if name.startswith("next:") else dofs.index(name)

    d = UnderPlatformDamper(dmp["mass"], dmp["inertia"], centrifugal_load=float(dmp["centrifugal_load"][:-1]),
                            damping=dmp["damping"])
    for face in dmp["interface"]:
        platform = face["platform"] if isinstance(face["platform"], list) else [face["platform"]]
        plats = [{axis: dof(p[axis]) for axis in ("x", "y")} for p in platform]
        d.add_interface(MicroslipModel.load(folder / face["model"]), points=face["points"],
                        angle_deg=face["angle"], platform=plats if len(plats) > 1 else plats[0], name=face["name"])
    return d.attach(disk), toml


@pytest.fixture(scope="module")
def sector(tmp_path_factory):
    """The example's files (H = 1, AMPLITUDE) and the mode the API computes from them."""
    folder = tmp_path_factory.mktemp("sector")
    damper_sector.write_files(folder, harmonics=1, amplitude=AMPLITUDE)
    structure, toml = api_sector(folder)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UnderResolvedWarning)  # the command warns the same (32 samples per period)
        mode = nonlinear_modes(structure, 1, AMPLITUDE, harmonics=1, nodal_diameter=3)
    return folder, toml, mode


def same_curve(csv, mode, points: int) -> None:
    """The command's ``modes.csv`` is the API's mode at its first ``points`` points: the same equations from the
    same numbers solved by the same steps, equal to the rounding of the two assemblies (measured: bit for bit),
    far below the continuation's 1e-9 tolerance."""
    columns, _ = read_table(csv)
    assert columns["modal amplitude"].size == points
    for column, api in (("modal amplitude", mode.modal_amplitude), ("omega", mode.omega),
                        ("damping ratio", mode.damping_ratio)):
        np.testing.assert_allclose(columns[column], api[:points], rtol=1e-9, atol=0, err_msg=column)


def test_the_command_computes_the_api_mode_from_the_files(sector, capsys):
    folder, toml, mode = sector
    out = folder / "mode"
    open_figures = plt.get_fignums()
    assert main(["modes", str(folder / "config.toml"), "--out", str(out), "--quiet"]) == 0
    assert plt.get_fignums() == open_figures  # its figure saved and closed (the gallery showed it twice)
    for name in ("modes.csv", "modes.png", "report.html", "report.md"):
        assert (out / name).stat().st_size > 0
    printed = capsys.readouterr()
    assert "Mode 1:" in printed.out and "with the contacts stuck" in printed.out and "Contact curved2:" in printed.out
    # 32 samples per period do not resolve the flat face's opening: the advice names the configuration's key
    assert "microslip modes: warning: contact 'flat0' opens and closes" in printed.err
    assert "[sweep] samples = " in printed.err and "samples=" not in printed.err
    # each contact's static state: the tangential force's share of the slip force as a percentage (was "0.104 of")
    assert re.search(r"Contact flat1: .*tangential force T0 = \S+ N \(\d+(\.\d+)? % of the slip force mu N0\)",
                     printed.out), printed.out
    assert mode.complete
    same_curve(out / "modes.csv", mode, mode.points)
    # the damper slides within the range: the contacts' damping well above the blade's own (C = 2e-7 K)
    assert mode.damping_ratio[-1] > 3 * mode.damping_ratio[0]
    report = (out / "report.md").read_text()
    assert "| nodal diameter | 3 |" in report and "| contacts | 3 |" in report and "| harmonics H | 1 |" in report
    assert f"{toml['modes']['dof']} harmonic 1" in report


def test_a_continuation_table_caps_the_mode_the_api_computes(sector, capsys):
    """``[continuation] max_points`` alone keeps the mode's own steps (the chord rule): the first points are the API's."""
    folder, _, mode = sector
    config = folder / "capped.toml"
    config.write_text((folder / "config.toml").read_text().replace("[output]", "[continuation]\nmax_points = 8\n\n"
                                                                               "[output]"))
    out = folder / "capped"
    assert main(["modes", str(config), "--out", str(out), "--quiet"]) == 1  # stopped before the end of the range
    err = capsys.readouterr().err
    assert "stopped at max_points = 8 points" in err and "raise [continuation] max_points" in err  # its words
    assert "StepControl" not in err
    assert mode.points > 8
    same_curve(out / "modes.csv", mode, 8)
    assert "**Incomplete mode**" in (out / "report.md").read_text()


@pytest.mark.parametrize("old, new, message", [
    ('dof_map = "dofs.csv"', 'dof_map = "dof.csv"', "dof.csv: no such file"),  # was "[Errno 2] No such file ..."
    ('M = "M.mtx"', 'M = "m.mtx"', "m.mtx: no such file"),
    ('"next:3:x"', '"next:3:z"', "'3:z'"),
])
def test_a_missing_file_or_dof_is_one_line_naming_it(sector, capsys, old, new, message):
    folder = sector[0]
    config = folder / "edited.toml"
    config.write_text((folder / "config.toml").read_text().replace(old, new))
    assert main(["modes", str(config), "--out", str(folder / "edited"), "--quiet"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("microslip modes: error: ") and message in err and "Errno" not in err, err


@pytest.mark.parametrize("api, config", [
    ("samples=1024 resolves it to 0.001", "[sweep] samples = 1024 resolves it to 0.001"),
    ("raise StepControl.max_points (or ds_max) to follow the whole mode",
     "raise [continuation] max_points to follow the whole mode"),
    # nonlinear_modes' message where a mode ends at a fold (its folds= argument, the [modes] folds key)
    ("The mode ends at the fold; folds='follow' follows the curve beyond it",
     'The mode ends at the fold; [modes] folds = "follow" follows the curve beyond it'),
    ("a tangential force T0 = 3 N, 8 samples per period", "a tangential force T0 = 3 N, 8 samples per period"),
])
def test_the_commands_advice_names_the_configuration_keys(api, config):
    from microslip.cli._words import in_config_words

    assert in_config_words(api) == config


def test_the_modes_step_control_is_its_own_with_the_keys_given(sector):
    from microslip.config import load_config
    from microslip.config.modes_control import mode_control
    from microslip.frequency import StepControl
    from microslip.frequency.analyses.nonlinear_modes import default_control

    folder = sector[0]
    config = folder / "steps.toml"
    config.write_text((folder / "config.toml").read_text().replace("[output]", "[continuation]\nmax_points = 250\n"
                                                                               "ds_min = 1e-6\n\n[output]"))
    cfg = load_config(config, nonlinear=True)
    own = default_control(*AMPLITUDE)  # the chord rule, steps of up to a decade of amplitude over the range
    assert own.ds_max != StepControl().ds_max  # not the forced response's steps, which cfg.control holds
    assert mode_control(cfg, []) == own
    assert mode_control(cfg, ["max_points", "ds_min"]) == StepControl(
        ds_initial=own.ds_initial, ds_max=own.ds_max, max_angle=own.max_angle, chord_error=own.chord_error,
        max_points=250, ds_min=1e-6)
    # chord_error = false: the mode's former steps (the turn rule), not the chord rule's longer bounds without it
    config.write_text((folder / "config.toml").read_text().replace("[output]", "[continuation]\nchord_error = false\n"
                                                                               "\n[output]"))
    off = load_config(config, nonlinear=True)
    assert off.control.chord_error is None
    assert mode_control(off, off.continuation_keys) == default_control(*AMPLITUDE, chord_error=None)
    with pytest.raises(ValueError, match=r"given names 'max_point', not a \[continuation\] key"):
        mode_control(cfg, ["max_point"])
    with pytest.raises(ValueError, match=r"cfg must be a configuration with a \[modes\] table"):
        mode_control(dataclasses.replace(cfg, nonlinear_mode=None), [])
