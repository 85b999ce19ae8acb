"""A contact's steady cycle at a point of a forced response: forces, and the slip state at every sample."""

import warnings

import numpy as np
import pytest

from microslip import Sphere, tune
from microslip.frequency import ContactCycle, Structure, contact_cycle, frequency_point
from microslip.frequency import UnderResolvedWarning
from microslip.kernels import aft as _aft
from microslip.frequency.analyses.contact_cycle import SLIP_STATES, slip_states

MODEL = tune(Sphere.paper(), 37.5, elements=4)


def pressed_block():
    """A 0.1 kg block on springs (x, y), pressed by 37.5 N along y against a sphere contact rubbing along x."""
    K = np.diag([1e7, 1e7])
    s = Structure(0.1 * np.eye(2), 1e-5 * K, K)
    s.add_contact(MODEL, tangential=0, normal=1, preload=37.5, name="sphere")
    return s


@pytest.fixture(scope="module")
def lifting():
    """Shaken along x (5 N) and, a quarter period later, along y (60 N): the contact opens part of the cycle."""
    with warnings.catch_warnings():  # a warning on the energy per cycle would not concern the forces compared here
        warnings.simplefilter("ignore", UnderResolvedWarning)
        return frequency_point(pressed_block(), [5.0, 60.0j], 2000.0, harmonics=5, samples=256)


def test_the_cycle_is_the_harmonic_balance_solution_in_time(lifting):
    cycle = contact_cycle(lifting, "sphere", 0)
    assert isinstance(cycle, ContactCycle) and cycle.name == "sphere" and cycle.time.size == 256
    E = _aft.tables(5, 256)[0]  # the AFT's synthesis table: samples of [1, cos, sin, ...]
    np.testing.assert_allclose(cycle.t, E @ lifting.contact_t[0, 0], rtol=0, atol=1e-18)
    # the forces marched here are those the harmonic balance was solved with: their Fourier coefficients
    # equal the solution's to rounding (measured 4e-15 N of 60 N)
    for force, coefficients in ((cycle.T, lifting.contact_T[0, 0]), (cycle.N, lifting.contact_N[0, 0])):
        fitted = np.linalg.lstsq(E, force, rcond=None)[0]
        np.testing.assert_allclose(fitted, coefficients, rtol=0, atol=1e-12 * np.abs(coefficients).max())
    assert cycle.time[1] == pytest.approx(2 * np.pi / 2000.0 / 256, rel=1e-14)


def test_every_slip_state_is_met_and_means_what_it_says(lifting):
    cycle = contact_cycle(lifting, 0, 0)
    shares = cycle.fractions()
    assert list(shares) == list(SLIP_STATES) and sum(shares.values()) == pytest.approx(1.0, abs=1e-15)
    assert all(share > 0 for share in shares.values())  # measured 52, 14, 6 and 29 % of the period
    state = cycle.state
    lift_off, gross = state == 3, state == 2
    assert np.all(cycle.N[lift_off] == 0) and np.all(cycle.T[lift_off] == 0)  # open: no force at all
    assert np.all(cycle.N[~lift_off] > 0)
    # gross slip: every closed element at its own slip force, the total at mu N (to rounding)
    np.testing.assert_allclose(np.abs(cycle.T[gross]), cycle.mu * cycle.N[gross], rtol=1e-12)
    assert np.all(np.abs(cycle.T[state < 2]) < cycle.mu * cycle.N[state < 2])  # below the slip force
    assert cycle.summary().startswith("stuck ") and "lift-off" in cycle.summary()


def test_slip_states_from_element_conditions():
    condition = np.array([[1, 1, 0], [2, 1, 0], [2, 2, 0], [0, 0, 0], [2, 2, 2]])
    assert [SLIP_STATES[k] for k in slip_states(condition)] == ["stuck", "microslip", "gross slip", "lift-off",
                                                                 "gross slip"]
    with pytest.raises(ValueError, match="condition must be a \\(samples, J\\) array"):
        slip_states([1, 2, 0])
    with pytest.raises(ValueError, match="condition must be"):
        slip_states([[3]])


def test_the_cycle_plots_both_forces_with_the_states_shaded(lifting):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    ax_n, ax_t = contact_cycle(lifting, 0, 0).plot()
    assert ax_n.get_ylabel() == "normal force N (N)" and ax_t.get_xlabel() == "time / period"
    labels = [t.get_text() for t in ax_t.get_legend().get_texts()]
    assert labels == ["T", "± μN"] + list(SLIP_STATES)
    plt.close("all")


@pytest.mark.parametrize("kwargs, error, message", [
    ({"contact": "damper"}, ValueError, "contact: no contact named 'damper'; the structure's contacts are"),
    ({"contact": 1}, ValueError, "contact must be below the number of contacts 1"),
    ({"point": 1}, ValueError, "point must be below the number of points 1"),
    ({"samples": 8}, ValueError, "samples"),
    ({"result": "frf.csv"}, TypeError, "result must be a FrequencyResponse"),
])
def test_contact_cycle_arguments_are_checked(lifting, kwargs, error, message):
    args = {"result": lifting, "contact": 0, "point": 0}
    args.update(kwargs)
    with pytest.raises(error, match=message):
        contact_cycle(args.pop("result"), args.pop("contact"), args.pop("point"), **args)


def test_the_cycles_of_several_contacts_in_one_figure(lifting):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from microslip.frequency import plot_contact_cycles

    cycle = contact_cycle(lifting, 0, 0)
    fig = plot_contact_cycles([cycle, cycle], "two")
    assert len(fig.axes) == 4 and fig.axes[3].get_xlabel() == "time / period" and fig.axes[1].get_xlabel() == ""
    assert [t.get_text() for t in fig.legends[0].get_texts()] == list(SLIP_STATES) + ["T", "± μN"]
    with pytest.raises(TypeError, match="cycles must be a non-empty sequence of ContactCycle"):
        plot_contact_cycles([])
    plt.close("all")
