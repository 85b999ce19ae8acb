"""`microslip reproduce` end to end, and the numbers of its report against bounds with a reason."""

import re

import numpy as np
import pytest

from microslip.cli import main
from microslip.common._version import __version__
from microslip.common.report import energy_unit
from microslip.figures import SECTIONS, PaperCase, fig2a, fig2b, fig3a, fig3b, fig4a


@pytest.fixture(scope="module")
def case():
    return PaperCase()


@pytest.fixture(scope="module")
def reproduced(tmp_path_factory):
    out = tmp_path_factory.mktemp("reproduce") / "results"
    assert main(["reproduce", "--out", str(out), "--quiet"]) == 0
    return out


def test_reproduce_writes_every_figure_csv_and_a_self_contained_report(reproduced):
    out = reproduced
    for name in ("fig2a", "fig2b", "fig3a", "fig3b", "fig4a", "fig4b"):
        assert (out / f"{name}.png").stat().st_size > 10_000
        header = (out / f"{name}.csv").read_text().splitlines()[0]
        assert header.split(",")[0].endswith("[m]")  # a plain CSV: the header row first (SI units in the names)
    html = (out / "report.html").read_text()
    assert html.count("data:image/png;base64,") >= 6
    assert not re.search(r"<img[^>]+src='(?!data:)", html)  # nothing linked from outside
    md = (out / "report.md").read_text()
    assert "Differences between discrete and continuous" in md
    assert not list(out.glob(".*.tmp"))  # no temporary file left behind


def test_report_states_version_date_and_every_parameter(reproduced, case):
    md = (reproduced / "report.md").read_text(encoding="utf-8")
    run = md[:md.index("## ")]  # the table under the title, before the first section
    assert f"| microslip version | {__version__} |" in run
    assert re.search(r"\| date \| \d{4}-\d\d-\d\d \d\d:\d\d", run)
    for section in SECTIONS:
        for name, value in getattr(section, "parameters", lambda _: {})(case).items():
            assert f"| {name} | {value} |" in run
    assert f"| tuning load N_tot | {case.normal_load:g} N |" in run and f"| elements J | {case.elements} |" in run


def test_report_reads_as_an_engineering_document(reproduced):
    md = (reproduced / "report.md").read_text(encoding="utf-8")
    html = (reproduced / "report.html").read_text(encoding="utf-8")
    assert not re.search(r"\bissues?\b", md, re.IGNORECASE)
    assert not re.search(r"\b1 (element|path|point|record|load|cycle)s\b", md)
    assert "(1 element in contact)" in md  # Fig. 3b at 7.5 N: one element touches
    # one unit for every energy: the report's energies run from 0.1 to 18 µJ, so µJ
    units = set(re.findall(r"energy per cycle[^|]*?\((\w?J)\)", md))
    assert units == {energy_unit([1.8e-5, 1.1e-7])[0]} == {"µJ"}
    # numbers right-aligned and kept on one line, text left-aligned
    error_table = md[md.index("| quantity | discrete |"):].splitlines()
    assert error_table[1] == "|:---|---:|---:|---:|:---|"
    assert "<td class='num'>" in html and "white-space:nowrap" in html


def test_slip_load_error_is_positive_and_below_the_papers_8_percent(case):
    rows = fig3b.error_rows(fig3b.compute(case))
    errors = [e for q, _, _, e, _ in rows if "slip load" in q]
    assert len(errors) == len(case.lower_loads)
    # The array's normal curve is a chord of Hertz's convex curve, so at the Hertz
    # approach it carries at least the Hertz load (error >= 0); the paper claims < 8 %.
    assert min(errors) >= -1e-9
    assert max(errors) < 8.0


def test_tuned_curves_pass_through_the_points_and_stay_close_between(case):
    backbone = fig2a.error_rows(fig2a.compute(case))
    normal = fig2b.error_rows(fig2b.compute(case))
    # at the points: exact up to rounding of a few operations on numbers of order 10 N
    assert backbone[1][3] < 1e-9 and normal[1][3] < 1e-9
    # between the points the chords of J = 4 points deviate by a few % of the range: measured 3.7 %,
    # bounded here at 5 % so a regression in the tuning (e.g. the eq. (2) index slip) shows
    assert 0 < backbone[0][3] < 5 and 0 < normal[0][3] < 5


def test_loop_energy_against_mindlin(case):
    rows = fig3a.error_rows(fig3a.compute(case))
    full, half = rows[0][3], rows[1][3]
    # At gross slip the 4-element loop is made of straight chords under the concave branches:
    # it dissipates less than Mindlin (measured -11.9 %); a J = 4 array cannot be closer than ~5 %.
    assert -20 < full < -5
    assert abs(half) < 10


def test_join_point_of_the_raised_load_path(case):
    data = fig4a.compute(case)
    rows = fig4a.error_rows(data)
    # B is reached after the tangential increment mu*dN; the discrete array follows its own
    # virgin curve at N + dN there, whose error between tuning points is a few %.
    assert abs(rows[0][3]) < 3
    # the discrete path ends in gross slip at mu (N + dN) like the continuous one
    assert np.isclose(data["T_discrete"][-1], data["mu"] * data["N2"], rtol=1e-12)
