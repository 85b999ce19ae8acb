"""The contacts' section of the ``microslip frf`` report: static state, the damper's balance, the cycle at the peak."""

import csv
import sys

import numpy as np
import pytest

from _paths import REPO
from microslip.cli import main
from microslip.frequency import contact_cycle, frequency_response
from microslip.frequency.analyses.contact_cycle import SLIP_STATES

sys.path.insert(0, str(REPO / "tests" / "frequency"))
from test_damper import blade_pair, damper  # noqa: E402  (the blade pair and damper of the configuration)
from test_design_cli import config  # noqa: E402,F401  (the configuration file: a fixture)


LOAD = 500.0  # N: the curve is followed from 3000 to 5000 rad/s (at 50 N the continuation stalls near the peak)


@pytest.fixture
def run(config, tmp_path, capsys):  # noqa: F811
    text = config.read_text().replace('centrifugal_load = "50N"', f'centrifugal_load = "{LOAD:g}N"')
    config.write_text(text + "\n[output]\nplot = [2]\n")  # the peak of the tip
    out = tmp_path / "out"
    import matplotlib.pyplot as plt

    before = plt.get_fignums()
    assert main(["frf", str(config), "--out", str(out), "--quiet"]) == 0
    # its figures (frf, contacts, the cycle at the peak) saved and closed: a run within Python leaves none open
    assert plt.get_fignums() == before
    return out, (out / "report.md").read_text(), capsys.readouterr().out


@pytest.fixture(scope="module")
def api():
    """The same forced response through the API, and its contacts' cycles at the peak of the tip (DOF 2)."""
    d = damper(load=LOAD)
    s = d.attach(blade_pair())
    f = np.zeros(9)
    f[2] = 0.5
    r = frequency_response(s, f, (3000.0, 5000.0), harmonics=3)
    k = int(np.argmax(r.amplitude(2)))
    return d, r, k, [contact_cycle(r, c, k) for c in range(3)]


def test_the_report_gives_the_contacts_static_state_the_dampers_balance_and_the_cycle_at_the_peak(run, api):
    static_state_and_balance(run, api)
    cycle_at_the_peak(run, api)


def static_state_and_balance(run, api):
    out, report, printed = run
    d, r, _, _ = api
    header = ["contact", "normal load N0 (N)", "tangential force T0 (N)", "share of the slip force μN0",
              "elements closed"]
    assert "| " + " | ".join(header) + " |" in report
    for c, name in enumerate(["flat0", "flat1", "curved2"]):
        N0, T0 = r.static_normal_force[c], r.static_tangential_force[c]
        row = f"| {name} | {N0:.4g} | {T0:.4g} | {abs(T0) / (0.4 * N0):.3g} | {r.static_closed_elements[c]} of 4 |"
        assert row in report
    balance = f"balance to {d.static_balance(r):.1e} of the load"
    assert "Damper 0 (contacts flat0, flat1, curved2): centrifugal load 500 N" in report and balance in report
    assert balance in printed


def cycle_at_the_peak(run, api):
    out, report, printed = run
    _, r, k, at_peak = api
    assert f"at the peak of tip0 (ω = {r.omega[k]:.6g} rad/s" in report
    for cy in at_peak:
        shares = " | ".join(f"{100 * s:.0f}" for s in cy.fractions().values())
        assert f"| {cy.name} | {cy.N.min():.4g} to {cy.N.max():.4g} | {np.abs(cy.T).max():.4g} | {shares} |" in report
        assert f"Contact {cy.name} at the peak of tip0" in printed and cy.summary() in printed
    assert (out / "contact_cycle.png").stat().st_size > 20_000
    rows = list(csv.DictReader(open(out / "contact_cycle.csv")))
    assert len(rows) == r.samples
    for cy in at_peak:  # the samples as the API gives them (floats written with repr: exact)
        np.testing.assert_array_equal([float(row[f"{cy.name} N [N]"]) for row in rows], cy.N)
        np.testing.assert_array_equal([float(row[f"{cy.name} T [N]"]) for row in rows], cy.T)
        assert [row[f"{cy.name} state [-]"] for row in rows] == [SLIP_STATES[s] for s in cy.state]


def test_a_sector_configuration_takes_a_modal_reduction_and_refuses_none(config):  # noqa: F811
    from microslip.config import ConfigError, load_config

    text = config.read_text().replace('[excitation]', '[cyclic]\nsectors = 12\nleft = [0]\nright = [3]\n'
                                      'engine_order = 2\n\n[excitation]')
    text = text.replace("platform = {x = 3, y = 4}", 'platform = {x = "next:0", y = 4}')
    config.write_text(text.replace("harmonics = 3", 'harmonics = 3\nreduction = "modal"\nmodes = 4'))
    cfg = load_config(config)
    assert cfg.reduction == "modal" and cfg.modes == 4
    config.write_text(text.replace("harmonics = 3", 'harmonics = 3\nreduction = "none"'))
    with pytest.raises(ConfigError, match="\\[sweep\\] a CyclicStructure is solved with reduction='exact' or "
                                          "'modal'"):
        load_config(config)
