"""Arguments of the frequency-domain entry points refused by name: sizes, flags, frequencies, names, files."""

import numpy as np
import pytest

from microslip import MicroslipModel
from microslip.frequency import (HarmonicBalance, Structure, aft, frequency_point, frequency_response,
                                 static_solution, steady_state, time_samples)

JENKINS = MicroslipModel(kt=[1e4], kn=[1e6], gaps=[0.0], mu=1.0)


def oscillator():
    s = Structure(M=[[1.0]], C=[[1.0]], K=[[1e4]])
    s.add_contact(JENKINS, tangential=0, approach=1e-6)
    return s


@pytest.mark.parametrize("call, error, message", [
    (lambda: aft(JENKINS, [0.0, 1e-6, 0.0], [1e-6, 0.0, 0.0], samples=10**12), ValueError,
     r"samples must be at most 10000000 \(a size: larger ones would need gigabytes\), got 1000000000000"),
    (lambda: time_samples([0.0, 1.0, 0.0], 10**12), ValueError, "samples must be at most 10000000"),
    (lambda: HarmonicBalance(oscillator(), [1.0], 1).evaluate([0.0, 1e-6, 0.0], 100.0, jacobian="no"), TypeError,
     "jacobian must be True or False, got 'no'"),
    (lambda: HarmonicBalance(oscillator(), [1.0], 1).local([0.0, 1e-6]), ValueError,
     r"x must be a vector of the n = \(2H\+1\) ndof = 3 unknowns"),
    (lambda: HarmonicBalance(oscillator(), [1.0], 1).local([0.0, np.nan, 0.0]), ValueError, "x must be finite"),
    (lambda: HarmonicBalance(oscillator(), [1.0], 1).dynamic_stiffness(np.nan), ValueError, "omega must be finite"),
    (lambda: HarmonicBalance(oscillator(), [1.0], 1).dynamic_stiffness(1e300), ValueError,
     "omega is too large: 1e[+]300 gives a result beyond the floating-point range"),
    (lambda: frequency_point(oscillator(), [1.0], 1e300, harmonics=1), ValueError, "omega is too large"),
    (lambda: frequency_response(oscillator(), [1.0], (90.0, 110.0), harmonics=1, progress="no"), TypeError,
     "progress must be True or False, got 'no'"),
    (lambda: static_solution(oscillator(), [1.0], tolerance=0.0), ValueError,
     r"tolerance must lie in \(0.0, 1.0\), got 0.0"),
    (lambda: steady_state(oscillator(), [1.0], 1e-300, steps_per_period=64, harmonics=1), ValueError,
     "omega = 1e-300 rad/s is too low: a stable step needs .* steps per period"),
    (lambda: steady_state(oscillator(), [1.0], 100.0, steps_per_period=64, harmonics=40), ValueError,
     "harmonics must be at most 31"),
    (lambda: steady_state(oscillator(), {"a": [1.0]}, 100.0, steps_per_period=64, harmonics=1), TypeError,
     "force: harmonic keys must be integers, got 'a'"),
    (lambda: oscillator().force_vector([1.0], name=1.0), TypeError, "name must be a string, got 1.0"),
    # sizes below the general limit of 10**7 that still needed gigabytes (MemoryError after a long wait):
    # the AFT's tables hold samples x (2H + 1) numbers, limited to 2**22
    (lambda: frequency_response(oscillator(), [1.0], (90.0, 110.0), harmonics=7, samples=10**7), ValueError,
     r"samples must be at most 279620 with harmonics = 7 \(the tables of a period hold samples x \(2 harmonics "
     r"\+ 1\) numbers, at most 4194304\), got 10000000"),
    (lambda: aft(JENKINS, [0.0, 1e-6, 0.0], [1e-6, 0.0, 0.0], samples=10**7), ValueError,
     "samples must be at most 1398101 with harmonics = 1"),
    (lambda: frequency_point(oscillator(), [1.0], 100.0, harmonics=10**4), ValueError,
     r"harmonics must be at most 256 \(a size: larger ones would need gigabytes\), got 10000"),
    (lambda: HarmonicBalance(oscillator(), [1.0], 300), ValueError, "harmonics must be at most 256"),
    (lambda: time_samples(np.zeros(2 * 300 + 1), 4096), ValueError,
     "coefficients: the number of harmonics H must be at most 256"),
    (lambda: steady_state(oscillator(), [1.0], 100.0, steps_per_period=10**7, harmonics=7), ValueError,
     "steps_per_period must be at most 279620 with harmonics = 7"),
])
def test_bad_arguments_are_named(call, error, message):
    with pytest.raises(error, match=message):
        call()


def test_results_check_their_arguments(tmp_path):
    point = frequency_point(oscillator(), [1.0], 100.0, harmonics=1)
    with pytest.raises(ValueError, match="samples must be at most 10000000"):
        point.time_history(0, samples=10**12)
    with pytest.raises(TypeError, match=r"path must be a file name \(str or os.PathLike\), got 1.0"):
        point.to_csv(1.0)
    state = steady_state(oscillator(), [1.0], 100.0, steps_per_period=64, harmonics=1, max_periods=20)
    with pytest.raises(ValueError, match=r"harmonic must be at most 1 \(the harmonics computed\), got 2"):
        state.amplitude(0, harmonic=2)
