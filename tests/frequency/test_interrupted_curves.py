"""Curves that stop early or meet NumPy's limits: Ctrl-C keeps the points computed, progress says where a slow
mode has got to, no raw NumPy or SciPy message reaches the user, a synthesis outside its range says so."""

import sys
import warnings

import numpy as np
import pytest

from microslip.frequency import frequency_response, nonlinear_modes
from microslip.frequency.analyses import response as response_module
from microslip.frequency.analyses.nonlinear_modes import default_control
from microslip.frequency.analyses.response import CurveInterrupted
from test_damper import blade_pair, damper
from test_design import interrupt_after

from _paths import EXAMPLES

sys.path.insert(0, str(EXAMPLES))
from inclined_block import FORCE, RANGE, inclined_block  # noqa: E402


def test_an_interrupted_forced_response_keeps_the_points_it_reached(monkeypatch):
    whole = frequency_response(inclined_block(), FORCE, RANGE, harmonics=3)
    interrupt_after(monkeypatch, 9)
    with pytest.raises(CurveInterrupted, match="^interrupted at omega = .* after 9 points, before the end of the "
                                               "range \\(16500 rad/s\\)") as info:
        frequency_response(inclined_block(), FORCE, RANGE, harmonics=3)
    assert isinstance(info.value, KeyboardInterrupt)
    part = info.value.partial
    assert part.points == 9 and not part.complete
    # the points the continuation accepted, bit for bit
    np.testing.assert_array_equal(part.omega, whole.omega[:9])
    np.testing.assert_array_equal(part.coefficients, whole.coefficients[:9])
    assert part.stable is None  # not assessed: the user asked to stop


def test_an_interrupted_mode_keeps_the_amplitudes_it_reached(monkeypatch):
    whole = nonlinear_modes(inclined_block(), 1, (1e-9, 1e-5), harmonics=3)
    interrupt_after(monkeypatch, 15)
    with pytest.raises(CurveInterrupted, match="^interrupted at modal amplitude .* after 15 points") as info:
        nonlinear_modes(inclined_block(), 1, (1e-9, 1e-5), harmonics=3)
    part = info.value.partial
    assert part.points == 15 and not part.complete
    np.testing.assert_array_equal(part.modal_amplitude, whole.modal_amplitude[:15])
    np.testing.assert_array_equal(part.damping_ratio, whole.damping_ratio[:15])


def test_a_slow_mode_says_where_it_has_got_to_between_tenths(monkeypatch, capsys):
    # at most every PROGRESS_EVERY seconds (here: at every evaluation), the amplitude reached and the points so far
    monkeypatch.setattr(response_module, "PROGRESS_EVERY", 0.0)
    nonlinear_modes(inclined_block(), 1, (1e-9, 1e-5), harmonics=3, progress=True)
    lines = capsys.readouterr().err.splitlines()
    notes = [line for line in lines if line.startswith("      modal amplitude ")]
    assert len(notes) > 50 and "modal amplitude 1e-09 kg^1/2 m, 1 points so far" in notes[0]
    assert notes[-1].split(" (")[0].endswith("points so far") and int(notes[-1].split(", ")[1].split()[0]) > 50


@pytest.fixture(scope="module")
def damper_mode():
    """The blade pair's first mode with its damper at 50 N, followed through its fold in amplitude (a harmonic of
    the mode meets another): the corrector tries points where the equations are not finite, and refuses them."""
    control = default_control(1e-7, 1e-3)
    control.max_points = 1100
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        mode = nonlinear_modes(damper(load=50.0).attach(blade_pair()), 1, (1e-7, 1e-3), harmonics=3, control=control,
                               folds="follow")
    return mode, caught


def test_a_mode_whose_corrector_meets_non_finite_points_raises_no_numpy_warning(damper_mode):
    mode, caught = damper_mode
    assert mode.points == 1100
    raw = [str(w.message) for w in caught if "encountered in" in str(w.message)]
    assert not raw, raw  # divide by zero, overflow, invalid value: each trial point was refused by name
    assert {type(w.message).__module__.split(".")[0] for w in caught} == {"microslip"}


def test_the_synthesis_of_a_mode_that_turns_back_says_so(damper_mode):
    mode, _ = damper_mode
    a = mode.modal_amplitude
    assert np.any(np.diff(a) <= 0)  # the mode folds in amplitude
    force = np.zeros(mode.structure.ndof)
    force[2], force[5] = 5e4, -5e4  # N: a peak far above where the mode turns back (3.48e-4 kg^1/2 m)
    with pytest.raises(ValueError) as info:
        mode.forced_response(force)
    message = str(info.value)
    assert "strictly increasing" not in message  # not SciPy's words
    assert message.startswith("force: the synthesised peak lies above the mode's largest amplitude (")
    assert "where the mode turns back (a fold in amplitude, usually an internal resonance" in message
    # 50 N peaks below the fold (6.7e-6 kg^1/2 m): synthesised from the mode up to there
    force /= 1000
    response = mode.forced_response(force)
    assert response.peak_modal_amplitude < a[np.flatnonzero(np.diff(a) <= 0)[0]]


def test_a_synthesis_over_a_range_away_from_the_mode_says_so():
    mode = nonlinear_modes(inclined_block(), 1, (1e-9, 1e-5), harmonics=3)
    with pytest.raises(ValueError, match="^omega: the synthesised response has no point between 1e\\+06 and 2e\\+06 "
                                         "rad/s: it spans .* rad/s \\(its peak at .* rad/s\\)"):
        mode.forced_response(FORCE, (1e6, 2e6))
