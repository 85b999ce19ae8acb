"""Arguments of the measured-loop entry points refused by name: loops, sizes, flags, names, files."""

import numpy as np
import pytest

from microslip import MeasuredContact, Sphere, fit_backbone, loops, tune, tune_on_loops, validate

SPHERE = Sphere.paper()
N = 37.5


@pytest.fixture(scope="module")
def measured():
    """Steady loops of a 30-element array tuned on the sphere: Masing loops at 37.5 N."""
    t = 1.5e-6 * np.sin(2 * np.pi * np.linspace(0, 4, 801))
    T = tune(SPHERE, N, elements=30).simulate(t, float(SPHERE.approach(N)), per_element=False).T
    return loops.analyse(loops.Record(t=t, T=T, normal_load=N, source="sphere"))


@pytest.mark.parametrize("call, error, message", [
    (lambda L: MeasuredContact.from_loops(1.0, SPHERE), TypeError,
     "loops must be microslip.loops.Loops or a sequence of them, got float"),
    (lambda L: validate(tune(SPHERE, N, elements=2), SPHERE, 1.0), TypeError, "loops must be microslip.loops.Loops"),
    (lambda L: fit_backbone(*L.backbone_points(), knots=10**12), ValueError, "knots must be at most 160"),
    (lambda L: loops.analyse(L.record, noise_correction="no"), TypeError,
     "noise_correction must be True or False, got 'no'"),
    (lambda L: loops.read(1.0), TypeError, r"path must be a file name \(str or os.PathLike\), got 1.0"),
    (lambda L: MeasuredContact.from_loops(L, SPHERE).backbone([0.0, 1e-7, 2e-7], [10.0, 20.0]), ValueError,
     r"t \(shape \(3,\)\) and N \(shape \(2,\)\) must have shapes that broadcast"),
    (lambda L: MeasuredContact.from_branch(L.record.t[:200], L.record.T[:200], SPHERE, N, source=1.0), TypeError,
     "source must be a string, got 1.0"),
])
def test_bad_arguments_are_named(measured, call, error, message):
    with pytest.raises(error, match=message):
        call(measured)


def test_loop_tuning_checks_its_arguments(measured):
    result = tune_on_loops(measured, SPHERE, elements=3)
    with pytest.raises(ValueError, match="dN: N [+] dN = 47.5 N must not exceed the tuning load 37.5 N"):
        result.transition(N=20.0, dN=27.5)
    with pytest.raises(ValueError, match="points must be at most 10000000"):
        result.transition(N=20.0, dN=10.0, points=10**12)
    with pytest.raises(TypeError, match="stem must be a string, got 1.0"):
        result.report("out", stem=1.0)
    with pytest.raises(TypeError, match=r"out_dir must be a file name \(str or os.PathLike\), got None"):
        result.report(None)
