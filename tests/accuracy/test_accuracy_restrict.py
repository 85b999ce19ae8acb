"""One restriction of the family (lowest load, amplitude) and one worst-error-per-amplitude, shared by all users."""

import numpy as np
import pytest

from microslip import Sphere, mdr, paths, tune
from microslip.accuracy import accuracy, restriction_mask

SPHERE = Sphere.paper()
OPTIONS = {"ratios": (0.0, 0.6), "phases_deg": (90.0,), "amplitudes": (0.2, 0.5, 1.0, 2.0), "levels": (0.3, 1.0),
           "steps_per_cycle": 40}


@pytest.fixture(scope="module")
def report():
    family = paths.default_family(SPHERE, 37.5, **OPTIONS)
    return accuracy(tune(SPHERE, 37.5, elements=4), mdr(SPHERE, max_load=37.5, elements=200), family)


def test_mask_follows_its_definition(report):
    lowest = np.array([p.params["N_m"] - p.params["N_a"] for p in report.paths])
    amp = np.array([p.params["amplitude"] for p in report.paths])
    mask = restriction_mask(report.paths, 7.5, 0.5)
    np.testing.assert_array_equal(mask, (lowest >= 7.5 * (1 - 1e-12)) & (amp >= 0.5))
    assert 0 < mask.sum() < len(report)
    # the bound itself is kept: the level 1 at ratio 0 has its lowest load at exactly 37.5 N
    assert restriction_mask(report.paths, 37.5).sum() == len(OPTIONS["amplitudes"])
    assert restriction_mask([paths.from_arrays([0.0, 1e-6], n=1e-6)], 0.0).tolist() == [False]  # no params


def test_restrict_is_where_of_the_mask(report):
    r = report.restrict(7.5, 0.5)
    kept = restriction_mask(report.paths, 7.5, 0.5)
    assert r.paths == tuple(p for p, k in zip(report.paths, kept) if k)
    np.testing.assert_array_equal(r.force_difference, report.force_difference[kept])
    with pytest.raises(ValueError, match="min_load 100 N and min_amplitude 0 leave no path of the report"):
        report.restrict(100.0)
    with pytest.raises(ValueError, match="min_load must be non-negative, got -1.0"):
        report.restrict(-1.0)


def test_worst_by_amplitude(report):
    amps, worst = report.worst_by_amplitude()
    np.testing.assert_array_equal(amps, OPTIONS["amplitudes"])
    err = np.abs(report.energy_error)
    for a, w in zip(amps, worst):
        sel = report.param("amplitude") == a
        assert w == np.nanmax(err[sel]) if np.any(~np.isnan(err[sel])) else np.isnan(w)
    ax = report.plot_amplitude(label="J = 4")
    np.testing.assert_allclose(ax.lines[0].get_ydata(), 100 * worst)
    with pytest.raises(ValueError, match="plot_amplitude\\(\\) needs paths with an 'amplitude' parameter"):
        accuracy(tune(SPHERE, 37.5, elements=4), mdr(SPHERE, max_load=37.5, elements=50),
                 paths.loop(SPHERE, 10.0, 1e-6)).plot_amplitude()
    import matplotlib.pyplot as plt

    plt.close("all")
