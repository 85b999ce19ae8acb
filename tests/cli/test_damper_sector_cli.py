"""``microslip modes`` on a blade sector read from files (issue 26 item 5): the route of examples/damper_sector.py.

The example writes the sector's matrices (Matrix Market), its DOF map, the damper's contact laws and a
configuration; the command's mode must be the one ``nonlinear_modes`` computes from the same files, built
here through the API from the raw TOML values (not through the configuration reader).
"""

import sys
import tomllib

import numpy as np
import pytest
import scipy.io

from _paths import EXAMPLES
from microslip import MicroslipModel, nonlinear_modes
from microslip.cli import main
from microslip.common._table import read_table
from microslip.fe import DofMap
from microslip.frequency import CyclicStructure, UnderPlatformDamper

sys.path.insert(0, str(EXAMPLES))
import damper_sector  # noqa: E402

# harmonics 0-1 from stuck into the damper's slip (its damping ratio rises from the viscous part's 0.1 %):
# a few seconds; the example's own range and H = 3 take minutes
AMPLITUDE = (1e-7, 3e-6)  # kg^1/2 m


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
    folder = tmp_path_factory.mktemp("sector")
    damper_sector.write_files(folder, harmonics=1, amplitude=AMPLITUDE)
    return folder


def test_the_command_computes_the_api_mode_from_the_files(sector, capsys):
    out = sector / "mode"
    assert main(["modes", str(sector / "config.toml"), "--out", str(out), "--quiet"]) == 0
    for name in ("modes.csv", "modes.png", "report.html", "report.md"):
        assert (out / name).stat().st_size > 0
    printed = capsys.readouterr().out
    assert "Mode 1:" in printed and "contacts stuck" in printed
    structure, toml = api_sector(sector)
    mode = nonlinear_modes(structure, 1, AMPLITUDE, harmonics=1, nodal_diameter=3)
    columns, _ = read_table(out / "modes.csv")
    # the same equations from the same numbers solved by the same steps: equal to the rounding of the two
    # assemblies (measured below 1e-13), far below the continuation's 1e-9 tolerance
    assert columns["modal amplitude"].size == mode.points
    np.testing.assert_allclose(columns["modal amplitude"], mode.modal_amplitude, rtol=1e-9, atol=0)
    np.testing.assert_allclose(columns["omega"], mode.omega, rtol=1e-9, atol=0)
    np.testing.assert_allclose(columns["damping ratio"], mode.damping_ratio, rtol=1e-9, atol=0)
    # the damper slides within the range: its damping is well above the blade's own (C = 2e-7 K)
    assert mode.damping_ratio.max() > 2 * mode.damping_ratio[0]
    report = (out / "report.md").read_text()
    assert "| nodal diameter | 3 |" in report and "3 contacts" in report
    assert toml["modes"]["dof"] in report
