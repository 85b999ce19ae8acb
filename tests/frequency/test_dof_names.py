"""DOF names (``"node:component"``) where a DOF is shown: the axis of a forced response's plot (issue 24, item 18)."""

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from microslip import MicroslipModel  # noqa: E402
from microslip.fe import DofMap  # noqa: E402
from microslip.frequency import Structure, frequency_point  # noqa: E402
from microslip.frequency.structures.structure import dof_label  # noqa: E402


def test_the_plot_names_the_dof_from_the_dof_map():
    K = np.array([[2e6, -1e6], [-1e6, 1e6]])
    s = Structure(np.diag([1.0, 0.5]), 0.5 * np.eye(2), K, dof_map=DofMap([1113, 1113], ["x", "y"]))
    s.add_contact(MicroslipModel([2e5], [1e9], [0.0], 0.5), tangential="1113:x", approach=2e-8)
    r = frequency_point(s, {1: {"1113:y": 1.0}}, 900.0, harmonics=1)
    ax = r.plot(1)
    assert ax.get_ylabel() == "1113:y: max |q - q0| over a period (µm)"  # was "response: ..."
    plt.close("all")
    bare = Structure(np.eye(2), None, K)
    assert dof_label(bare, 1) == "DOF 1" and dof_label(s, 1) == "1113:y" and dof_label(s, "1113:2") == "1113:2"
    assert dof_label(s, {0: 1.0, 1: -1.0}) is None  # a combination keeps the generic label


def test_a_response_reads_a_dof_by_its_name():
    K = np.array([[2e6, -1e6], [-1e6, 1e6]])
    s = Structure(np.diag([1.0, 0.5]), 0.5 * np.eye(2), K, dof_map=DofMap([1113, 1113], ["x", "y"]))
    s.add_contact(MicroslipModel([2e5], [1e9], [0.0], 0.5), tangential="1113:x", approach=2e-8)
    r = frequency_point(s, {1: {"1113:y": 1.0}}, 900.0, harmonics=1)
    assert np.array_equal(r.amplitude("1113:y"), r.amplitude(1))  # the name refused before (issue 24, item 18)
    assert np.array_equal(r.dof_coefficients("1113:x"), r.dof_coefficients(0))
