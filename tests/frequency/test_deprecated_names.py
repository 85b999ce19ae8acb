"""Names replaced so that one spelling has one meaning keep working, with a deprecation warning naming the new one.

``frequency.synthesise`` (the time samples of a Fourier series) is now ``frequency.time_samples``;
``NonlinearModes.synthesize`` (a forced response from a mode) is now ``NonlinearModes.forced_response``.
"""

import numpy as np
import pytest

import microslip
from microslip import MicroslipModel, Structure, nonlinear_modes
from microslip.frequency import time_samples


def test_synthesise_is_time_samples_with_a_warning():
    c = [0.3, 1.0, -0.5, 0.0, 0.25]  # c0 + cos - 0.5 sin + 0.25 sin 2tau
    with pytest.warns(microslip.MicroslipDeprecationWarning, match="synthesise is deprecated: use "
                                                                   "microslip.frequency.time_samples"):
        old = microslip.frequency.synthesise(c, 16)
    tau = 2 * np.pi * np.arange(16) / 16
    exact = 0.3 + np.cos(tau) - 0.5 * np.sin(tau) + 0.25 * np.sin(2 * tau)
    # the closed form summed in another order: equal to rounding (a few ulps of the largest term, 1)
    np.testing.assert_allclose(time_samples(c, 16), exact, rtol=0, atol=1e-14)
    np.testing.assert_array_equal(old, time_samples(c, 16))


def test_the_deprecation_warning_is_a_deprecation_warning_and_points_at_the_caller():
    with pytest.warns(DeprecationWarning) as record:
        microslip.frequency.synthesise([1.0], 1)
    assert record[0].filename == __file__


def test_nonlinear_modes_synthesize_is_forced_response_with_a_warning():
    s = Structure(np.diag([1.0, 0.5]), 0.5 * np.diag([1.0, 0.5]), np.array([[2e6, -1e6], [-1e6, 1e6]]))
    s.add_contact(MicroslipModel([2e5], [1e9], [0.0], 0.5), tangential=0, approach=2e-8)
    mode = nonlinear_modes(s, 1, (1e-6, 1e-2), harmonics=1)
    new = mode.forced_response([0.0, 1.0], points=20)
    with pytest.warns(microslip.MicroslipDeprecationWarning, match="NonlinearModes.synthesize is deprecated: use "
                                                                   "NonlinearModes.forced_response"):
        old = mode.synthesize([0.0, 1.0], points=20)
    np.testing.assert_array_equal(old.omega, new.omega)
    np.testing.assert_array_equal(old.modal_amplitude, new.modal_amplitude)
