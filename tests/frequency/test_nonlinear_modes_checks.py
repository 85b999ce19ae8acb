"""Every parameter of nonlinear_modes, NonlinearModes and SynthesizedResponse refused by name; the warnings."""

import numpy as np
import pytest

from microslip import MicroslipModel, Structure
from microslip.frequency import CyclicStructure, IncompleteCurveWarning, StepControl, nonlinear_modes

M = np.diag([1.0, 0.5])
K = np.array([[2e6, -1e6], [-1e6, 1e6]])


def chain() -> Structure:
    s = Structure(M, 0.5 * M, K)
    s.add_contact(MicroslipModel([2e5], [1e9], [0.0], 0.5), tangential=0, approach=2e-8)
    return s


@pytest.fixture(scope="module")
def mode():
    return nonlinear_modes(chain(), 1, (1e-6, 1e-2), harmonics=3)


@pytest.mark.parametrize("kwargs, error, words", [
    ({"structure": "chain"}, TypeError, "structure must be a microslip Structure, got str"),
    ({"mode": 2.5}, TypeError, "mode must be an integer, got 2.5"),
    ({"mode": 0}, ValueError, "mode must be an integer >= 1, got 0"),
    ({"mode": 3}, ValueError, "mode must be at most 2 (the structure has 2 DOFs), got 3"),
    ({"amplitude": 1e-6}, TypeError, "amplitude must be a pair (start, end) of modal amplitudes"),
    ({"amplitude": (-1e-6, 1e-3)}, ValueError, "amplitude[0]"),
    ({"amplitude": (1e-3, 1e-6)}, ValueError, "amplitude must rise from start to end, got start = 0.001"),
    ({"amplitude": (1e-3, 1e-3)}, ValueError, "amplitude must rise from start to end"),
    # before: NaN modal mass, modal damping and damping ratios with a numpy RuntimeWarning (a^2 underflowed)
    ({"amplitude": (1e-300, 1e-299)}, ValueError, "amplitude must start at 1e-146 kg^1/2 m or above, got start = "
                                                  "1e-300: the mode is mass-normalised, so its energies are a^2 times "
                                                  "its modal mass"),
    ({"amplitude": (1e-160, 1e-3)}, ValueError, "amplitude must start at 1e-146 kg^1/2 m or above, got start = 1e-160"),
    ({"harmonics": 0}, ValueError, "harmonics must be an integer >= 1, got 0"),
    ({"harmonics": "3"}, TypeError, "harmonics must be an integer"),
    ({"samples": 4}, ValueError, "samples must be at least 2 * harmonics + 1 = 7"),
    ({"reduction": "fast"}, ValueError, "reduction must be one of 'auto', 'none', 'exact', 'modal', got 'fast'"),
    ({"reduction": "none", "modes": 1}, ValueError, "modes is used only with reduction='modal'"),
    ({"modes": 2}, ValueError, "modes must be below the number of DOFs (2), got 2"),
    ({"control": {"ds_max": 0.1}}, TypeError, "control must be a StepControl, got dict"),
    ({"progress": "yes"}, TypeError, "progress must be True or False, got 'yes'"),
    ({"max_periods": 0}, ValueError, "max_periods must be an integer >= 1, got 0"),
])
def test_nonlinear_modes_refuses_each_parameter_by_name(kwargs, error, words):
    arguments = {"structure": chain(), "mode": 1, "amplitude": (1e-6, 1e-3), "harmonics": 3, **kwargs}
    with pytest.raises(error) as info:
        nonlinear_modes(**arguments)
    assert words in str(info.value)


def disk():
    d = CyclicStructure(np.eye(3) * 0.1, None, [[2e6, -1e6, 0], [-1e6, 2e6, -1e6], [0, -1e6, 1e6]], sectors=8,
                        left=[0], right=[2])
    d.add_contact(MicroslipModel([1e4], [1e6], [0.0], 0.5), tangential=1, approach=1e-6)
    return d


@pytest.mark.parametrize("structure, kwargs, words", [
    (disk, {}, "nodal_diameter must be given for a CyclicStructure"),
    (disk, {"nodal_diameter": 8}, "nodal_diameter must be below the number of sectors 8, got 8"),
    (disk, {"nodal_diameter": -1}, "nodal_diameter must be an integer >= 0, got -1"),
    (disk, {"nodal_diameter": 1, "reduction": "modal"}, "a sector's nonlinear mode is condensed exactly"),
    (disk, {"nodal_diameter": 1, "mode": 3}, "mode must be at most 2 (the structure has 2 DOFs besides its right "
                                             "boundary), got 3"),
    (chain, {"nodal_diameter": 1}, "nodal_diameter is only for a CyclicStructure"),
])
def test_the_nodal_diameter_is_checked(structure, kwargs, words):
    with pytest.raises(ValueError) as info:
        nonlinear_modes(structure(), **kwargs)
    assert words in str(info.value)


def test_the_smallest_amplitude_gives_finite_results():
    from microslip.frequency.analyses.nonlinear_modes import MIN_AMPLITUDE

    m = nonlinear_modes(chain(), 1, (MIN_AMPLITUDE, 10 * MIN_AMPLITUDE), harmonics=1)
    for values in (m.modal_mass, m.modal_damping, m.damping_ratio, m.viscous_damping_ratio, m.contact_damping_ratio):
        assert np.all(np.isfinite(values))
    np.testing.assert_allclose(m.modal_mass, 1.0, rtol=1e-6)


def test_a_mode_without_stiffness_is_refused():
    s = Structure(np.eye(2), None, np.diag([1e6, 0.0]))  # DOF 1 is free: K singular, no contact on it
    s.add_contact(MicroslipModel([1e5], [1e9], [0.0], 0.5), tangential=0, approach=1e-8)
    with pytest.raises(ValueError, match="no stiffness from K or from the contacts' normal springs"):
        nonlinear_modes(s)  # the static check names the free DOF first


@pytest.mark.parametrize("call, error, words", [
    (lambda m: m.frequency("kHz"), ValueError, "unit must be one of"),
    (lambda m: m.amplitude(None, harmonic=1), ValueError, "harmonic is for a DOF's amplitude"),
    (lambda m: m.amplitude(5), ValueError, "dof: DOF 5 is out of range for a structure with 2 DOFs"),
    (lambda m: m.shape(-1), ValueError, "point must be an integer >= 0, got -1"),
    (lambda m: m.shape(10 ** 6), ValueError, "point must be below the number of points"),
    (lambda m: m.plot(frequency_unit="kHz"), ValueError, "frequency_unit must be one of"),
    (lambda m: m.forced_response([1.0]), ValueError, "force must have one entry per DOF (2), got 1"),
    (lambda m: m.forced_response([0.0, 0.0]), ValueError, "force must not be all zeros"),
    (lambda m: m.forced_response([0.0, "a"]), TypeError, "force"),
    (lambda m: m.forced_response([0.0, 1.0], omega=700.0), TypeError, "omega must be a pair (start, end)"),
    (lambda m: m.forced_response([0.0, 1.0], omega=(-1.0, 900.0)), ValueError, "omega[0]"),
    (lambda m: m.forced_response([0.0, 1.0], points=5), ValueError, "points must be an integer >= 10, got 5"),
    (lambda m: m.forced_response([0.0, 1e3]), ValueError,
     "the synthesised peak lies above the mode's largest amplitude"),
])
def test_results_refuse_each_parameter_by_name(mode, call, error, words):
    with pytest.raises(error) as info:
        call(mode)
    assert words in str(info.value)


def test_a_force_that_does_not_act_on_the_mode_is_refused():
    s = Structure(np.eye(2), None, np.diag([1e6, 4e6]))  # two uncoupled DOFs: mode 1 is DOF 0 alone
    s.add_contact(MicroslipModel([1e5], [1e9], [0.0], 0.5), tangential=0, approach=1e-8)
    mode = nonlinear_modes(s, 1, (1e-6, 1e-3), harmonics=1)
    with pytest.raises(ValueError, match="force does not act on the mode"):
        mode.forced_response([0.0, 1.0])


def test_the_continuation_stopped_early_is_a_warning(mode):
    with pytest.warns(IncompleteCurveWarning, match="stopped at max_points = 5 points"):
        short = nonlinear_modes(chain(), 1, (1e-6, 1e-2), harmonics=3, control=StepControl(max_points=5))
    assert not short.complete and short.points == 5


def test_a_mode_that_folds_back_in_amplitude_ends_at_the_fold_or_is_followed_with_a_warning():
    """A 10-mass chain whose first mode's third harmonic meets its fourth mode as the contacts slip (3 x 945 and
    2840 rad/s): the curve turns back in amplitude. By default the mode ends at the fold; followed, it leaves the
    range at its start."""
    n = 10
    Kc = np.diag(np.full(n, 2e6)) - np.diag(np.full(n - 1, 1e6), 1) - np.diag(np.full(n - 1, 1e6), -1)
    Mc = np.diag(np.linspace(0.1, 0.2, n))
    s = Structure(Mc, 2e-6 * Kc + 2.0 * Mc, Kc)
    for dof in (2, 7):
        s.add_contact(MicroslipModel([2e5, 1e5], [1e9, 1e9], [0.0, 0.0], 0.5), tangential=dof, approach=1e-8)
    control = StepControl(ds_initial=0.2, ds_max=0.2)
    with pytest.warns(IncompleteCurveWarning, match="the mode turns back in amplitude at modal amplitude .* folds='follow'"):
        stopped = nonlinear_modes(s, 1, (1e-5, 1e-2), harmonics=3, control=control)
    with pytest.warns(IncompleteCurveWarning, match="the mode turned back at modal amplitude"):
        folded = nonlinear_modes(s, 1, (1e-5, 1e-2), harmonics=3, control=control, folds="follow")
    assert folded.complete and folded.modal_amplitude.max() < 1e-4
    # stopped at the largest amplitude the followed curve reaches before it turns, on the same points up to there
    k = stopped.points
    assert not stopped.complete and np.all(np.diff(stopped.modal_amplitude) > 0)
    assert stopped.modal_amplitude[-1] == pytest.approx(folded.modal_amplitude[k - 1], rel=1e-12)
    assert folded.modal_amplitude[k] < folded.modal_amplitude[k - 1]
    np.testing.assert_allclose(stopped.omega, folded.omega[:k], rtol=1e-12)
    with pytest.raises(ValueError, match="folds must be one of 'stop', 'follow', got 'go on'"):
        nonlinear_modes(s, 1, (1e-5, 1e-2), harmonics=3, control=control, folds="go on")


def test_the_mode_and_its_synthesis_draw_and_write(mode, tmp_path):
    top, bottom = mode.plot(dof=1)
    assert top.get_xscale() == "log" and bottom.get_ylabel() == "damping ratio (%)"
    assert len(bottom.lines) == 2  # total and contacts' share (the viscous damping is not zero)
    path = mode.to_csv(tmp_path / "mode.csv")
    header = path.read_text().splitlines()[0].split(",")
    assert header[:4] == ["modal amplitude [kg^0.5 m]", "omega [rad/s]", "f [Hz]", "damping ratio [-]"]
    assert "excitation work [J]" not in header and len(path.read_text().splitlines()) == mode.points + 1
    assert repr(mode).startswith("NonlinearModes(mode=1, points=") and len(repr(mode)) < 300
    synthesis = mode.forced_response([0.0, 3.0])
    ax = synthesis.plot(dof=1)
    lo, hi = ax.get_xlim()
    assert lo < synthesis.peak_omega / (2 * np.pi) < hi and hi - lo < 0.3 * hi  # around the resonance
