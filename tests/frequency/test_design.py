"""The damper design curve: peak response against the centrifugal load."""

import csv

import numpy as np
import pytest

from microslip.frequency import frequency_response
from microslip.frequency import damper_design_curve
from test_damper import blade_pair, damper  # the blade pair with its damper

LOADS = [300.0, 500.0, 1000.0]  # N


@pytest.fixture(scope="module")
def curve():
    f = np.zeros(6)
    f[2] = 0.5
    return damper_design_curve(blade_pair(), damper(), LOADS, f, (3000.0, 5000.0), dof=2, harmonics=3)


def test_each_point_is_the_peak_of_the_forced_response_at_that_load(curve):
    assert list(curve.loads) == LOADS and len(curve.responses) == 3
    f = np.zeros(9)
    f[2] = 0.5
    r = frequency_response(damper(load=500.0).attach(blade_pair()), f, (3000.0, 5000.0), harmonics=3)
    assert r.peak(2) == (curve.peak_frequency[1], curve.peak_amplitude[1])
    i = int(np.argmin(curve.peak_amplitude))
    assert curve.optimum == (LOADS[i], curve.peak_amplitude[i])


def test_the_curve_writes_csv_and_plots(curve, tmp_path):
    import matplotlib

    matplotlib.use("Agg")
    rows = list(csv.reader(line for line in open(curve.to_csv(tmp_path / "design.csv")) if not line.startswith("#")))
    assert rows[0][0] == "centrifugal load [N]" and len(rows) == 4
    np.testing.assert_allclose([float(r[1]) for r in rows[1:]], curve.peak_amplitude, rtol=1e-12)
    assert curve.plot().get_xlabel() == "damper centrifugal load (N)"


@pytest.mark.parametrize("kwargs, message", [
    ({"loads": [-1.0]}, "loads"),
    ({"dof": 99}, "dof: DOF 99 is out of range for a structure with 6 DOFs"),
    ({"force": np.zeros(9)}, "force must have one entry per DOF \\(6\\), got 9"),
])
def test_design_curve_arguments_are_checked(kwargs, message):
    f = np.zeros(6)
    f[2] = 0.5
    args = dict(loads=LOADS, force=f, dof=2)
    args.update(kwargs)
    with pytest.raises(ValueError, match=message):
        damper_design_curve(blade_pair(), damper(), args["loads"], args["force"], (3000.0, 5000.0), dof=args["dof"])
