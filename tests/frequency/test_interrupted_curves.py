"""Curves that stop early or meet NumPy's limits: no raw NumPy or SciPy message reaches the user, a synthesis
outside its range says so."""

import sys
import warnings

import numpy as np
import pytest

from microslip.frequency import nonlinear_modes
from microslip.frequency.analyses.nonlinear_modes import default_control
from test_damper import blade_pair, damper

from _paths import EXAMPLES

sys.path.insert(0, str(EXAMPLES))
from inclined_block import FORCE, inclined_block  # noqa: E402


@pytest.fixture(scope="module")
def damper_mode():
    """The blade pair's first mode with its damper at 50 N, past where it folds in amplitude (a harmonic of the
    mode meets another)."""
    control = default_control(1e-7, 1e-3)
    control.max_points = 1100
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        mode = nonlinear_modes(damper(load=50.0).attach(blade_pair()), 1, (1e-7, 1e-3), harmonics=3, control=control)
    return mode, caught


def test_the_synthesis_of_a_mode_that_turns_back_says_so(damper_mode):
    mode, _ = damper_mode
    a = mode.modal_amplitude
    assert np.any(np.diff(a) <= 0)  # the mode folds in amplitude
    force = np.zeros(mode.structure.ndof)
    force[2], force[5] = 5e4, -5e4  # N: a peak far above where the mode turns back (3.48e-4 kg^1/2 m)
    with pytest.raises(ValueError) as info:
        mode.synthesize(force)
    message = str(info.value)
    assert "strictly increasing" not in message  # not SciPy's words
    assert message.startswith("force: the synthesised peak lies above the mode's largest amplitude (")
    assert "where the mode turns back (a fold in amplitude, usually an internal resonance" in message
    # 50 N peaks below the fold (6.7e-6 kg^1/2 m): synthesised from the mode up to there
    force /= 1000
    response = mode.synthesize(force)
    assert response.peak_modal_amplitude < a[np.flatnonzero(np.diff(a) <= 0)[0]]


def test_a_synthesis_over_a_range_away_from_the_mode_says_so():
    mode = nonlinear_modes(inclined_block(), 1, (1e-9, 1e-5), harmonics=3)
    with pytest.raises(ValueError, match="^omega: the synthesised response has no point between 1e\\+06 and 2e\\+06 "
                                         "rad/s: it spans .* rad/s \\(its peak at .* rad/s\\)"):
        mode.synthesize(FORCE, (1e6, 2e6))
