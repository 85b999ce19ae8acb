import numpy as np

from microslip import Sphere, tune


def test_tuned_paper_model_reaches_gross_slip_at_mu_N():
    sphere = Sphere.paper()
    model = tune(sphere, 37.5, elements=4)
    n = float(sphere.approach(37.5))
    assert np.isclose(float(model.slip_force(n)), 0.4 * 37.5, rtol=1e-12)
