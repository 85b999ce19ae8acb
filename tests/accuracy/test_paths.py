import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from microslip import Sphere, mdr, paths, tune
from microslip.paths import Path

SPHERE = Sphere.paper()


def test_loop_at_constant_load():
    p = paths.loop(SPHERE, 30.0, 1e-6, cycles=3, steps_per_cycle=100)
    assert len(p) == 301 and p.periodic
    assert p.t[0] == 0.0 and np.max(p.t) == pytest.approx(1e-6)
    assert np.all(p.n == SPHERE.approach(30.0)) and np.all(p.N == 30.0)
    assert p.steady == slice(200, 301)
    s = p.steady
    assert p.t[s][0] == pytest.approx(p.t[s][-1], abs=1e-20)


def test_variable_load_cycles_follow_the_formula():
    Nm, Na, phi = 20.0, 8.0, np.radians(90)
    p = paths.variable_load_cycles(SPHERE, Nm, Na, 5e-7, 90.0, cycles=2, steps_per_cycle=64)
    tau = 2 * np.pi * np.arange(129) / 64
    assert np.allclose(p.t, 5e-7 * np.sin(tau), rtol=0, atol=1e-22)
    assert np.allclose(p.N, Nm + Na * np.sin(tau + phi))
    assert np.allclose(p.n, SPHERE.approach(p.N))  # through the reference's normal law
    assert p.steady == slice(64, 129) and p.params["N_a"] == Na
    assert p.params["phase_deg"] == 90.0 and p.params["phase"] == phi and "90°" in p.label


@settings(max_examples=30, deadline=None)
@given(Nm=st.floats(0.5, 40.0), ratio=st.floats(0.0, 1.0), phase=st.floats(-180.0, 180.0),
       amp=st.floats(1e-8, 3e-6))
def test_variable_load_cycles_are_closed_and_never_pull(Nm, ratio, phase, amp):
    p = paths.variable_load_cycles(SPHERE, Nm, ratio * Nm, amp, phase, steps_per_cycle=40)
    s = p.steady
    assert p.N.min() >= 0.0
    # the steady cycle is closed in t and n, so ∮ N dn = 0 and ∮ T dt is the dissipated energy
    assert p.t[s][-1] == pytest.approx(p.t[s][0], abs=1e-15 * amp)
    assert p.n[s][-1] == pytest.approx(p.n[s][0], rel=1e-9, abs=1e-18)


@pytest.mark.parametrize("model_name", ["mdr", "J=4"])
def test_second_cycle_is_already_steady(model_name):
    """Justifies default_family(cycles=2): cycle 3 repeats cycle 2 for both the exact and the paper's array."""
    model = mdr(SPHERE, max_load=37.5, elements=400) if model_name == "mdr" else tune(SPHERE, 37.5, elements=4)
    for Nm, ratio, phi, amp in [(19.7, 0.9, 90, 1.0), (23.4, 0.6, 180, 0.35), (28.8, 0.3, 0, 3.0)]:
        spc = 90
        p = paths.variable_load_cycles(SPHERE, Nm, ratio * Nm, amp * SPHERE.gross_slip_displacement(Nm * (1 - ratio)),
                                       phi, cycles=3, steps_per_cycle=spc)
        T = p.simulate(model).T
        # measured: identical to round-off (<= 1e-13 of the peak)
        assert np.max(np.abs(T[spc:2 * spc + 1] - T[2 * spc:])) <= 1e-10 * np.max(np.abs(T))


def test_paper_fig4_path():
    p = paths.paper_fig4(SPHERE, 25.0, 12.5, 0.5, steps=50)
    assert len(p) == 50 + 49 + 49 and not p.periodic and p.steady == slice(0, len(p))
    tA = float(SPHERE.backbone_displacement(0.5 * SPHERE.mu * 25.0, 25.0))
    assert p.t[49] == pytest.approx(tA) and np.all(p.t[49:98] == p.t[49])  # N raised at constant t
    assert np.all(p.N[:50] == 25.0) and np.all(p.N[98:] == 37.5)
    assert p.t[-1] == pytest.approx(1.3 * float(SPHERE.gross_slip_displacement(37.5)))


def test_from_arrays():
    t = np.linspace(0, 1e-6, 5)
    p = paths.from_arrays(t, N=[10, 20, 30, 20, 10], reference=SPHERE, steady=slice(1, 5))
    assert np.allclose(p.n, SPHERE.approach([10, 20, 30, 20, 10])) and p.steady == slice(1, 5)
    q = paths.from_arrays(t, n=1e-6)
    assert np.all(q.n == 1e-6) and q.N is None and q.steady == slice(0, 5)


@pytest.mark.parametrize("call, exc, message", [
    (lambda: paths.from_arrays([0.0, np.nan], n=1e-6), ValueError, "t must be finite, got .*nan.* at flat index 1"),
    (lambda: paths.from_arrays([0.0, 1e-6], n=[0.0, np.inf]), ValueError, "n must be finite, got .*inf"),
    (lambda: paths.from_arrays([0.0, 1e-6], N=[1.0, -2.0], reference=SPHERE), ValueError,
     "N must be non-negative for the normal law .* got -2 N at sample 1"),
    (lambda: paths.from_arrays([0.0, 1e-6], N=[1.0, 2.0]), ValueError, "N= needs reference="),
    (lambda: paths.from_arrays([0.0, 1e-6]), ValueError, "give exactly one of n="),
    (lambda: paths.from_arrays([0.0, 1e-6], n=0.0, steady=slice(1, 2)), ValueError,
     "steady must select at least 2 consecutive samples"),
    (lambda: Path(t=[0.0, 1.0], n=[0.0, 1.0, 2.0], steady=slice(0, 2)), ValueError, "n must have the same shape"),
    (lambda: Path(t=[0.0, 1.0], n=[0.0, 1.0], steady=(0, 2)), TypeError, "steady must be a slice"),
    (lambda: paths.variable_load_cycles(SPHERE, 10.0, 12.0, 1e-6), ValueError,
     "load_amplitude must not exceed mean_load = 10 N .* got 12 N"),
    (lambda: paths.variable_load_cycles(SPHERE, -1.0, 0.0, 1e-6), ValueError, "mean_load must be positive"),
    (lambda: paths.variable_load_cycles(SPHERE, 10.0, 1.0, np.nan), ValueError, "amplitude must be finite"),
    (lambda: paths.loop(SPHERE, 10.0, 1e-6, steps_per_cycle=4), ValueError, "steps_per_cycle must be an integer >= 8"),
    (lambda: paths.paper_fig4(SPHERE, raised_at=1.5), ValueError, r"raised_at must lie in \[0.0, 1.0\]"),
    (lambda: paths.loop(object(), 10.0, 1e-6), TypeError, "reference must provide approach"),
    (lambda: paths.default_family(SPHERE, 37.5, ratios=[0.5, 1.0]), ValueError, "ratios must be below 1"),
    (lambda: paths.default_family(None, 37.5), TypeError,
     r"reference must provide approach\(\), gross_slip_displacement\(\) .* got NoneType"),
    (lambda: paths.paper_fig4(_OnlyNormal()), TypeError,
     r"reference must provide backbone_displacement\(\), gross_slip_displacement\(\) .* got _OnlyNormal"),
    (lambda: paths.paper_fig4(_NoMu()), TypeError, "reference must provide mu .* got _NoMu"),
    (lambda: paths.loop(_OnlyNormal(), 10.0, 1e-6).N[0], None, None),
    (lambda: paths.variable_load_cycles(None, 10.0, 1.0, 1e-6), TypeError, r"reference must provide approach\(\)"),
    (lambda: paths.variable_load_cycles(SPHERE, 10.0, 1.0, 1e-6, phase_deg="90"), TypeError,
     "phase_deg must be a real number, got '90'"),
    (lambda: paths.from_arrays([0.0, 1.0, 2.0], n=[1e-6, 1e-6]), ValueError,
     r"n must be a scalar or have the shape of t \(3,\), got shape \(2,\)"),
    (lambda: paths.from_arrays([0.0, 1.0, 2.0], N=[1.0, 2.0], reference=SPHERE), ValueError,
     r"N must be a scalar or have the shape of t \(3,\), got shape \(2,\)"),
    (lambda: paths.default_family(SPHERE, 37.5, levels=[0.5, 1.2]), ValueError, "levels must not exceed 1"),
    (lambda: paths.loop(SPHERE, 10.0, 1e-6).simulate("model"), TypeError,
     "model must be a MicroslipModel .* got str"),
    (lambda: paths.loop(SPHERE, 10.0, 1e-6).simulate(tune(SPHERE, 37.5, elements=2), per_element="no"), TypeError,
     "per_element must be True or False, got 'no'"),
    (lambda: paths.from_arrays([0.0, 1e-6], n=0.0, periodic="no"), TypeError, "periodic must be True or False"),
    (lambda: paths.from_arrays([0.0, 1e-6], n=0.0, label=1.0), TypeError, "label must be a string, got 1.0"),
    (lambda: Path(t=[0.0, 1.0], n=[0.0, 1.0], steady=slice(0, 2), params="abc"), TypeError,
     "params must be a mapping"),
    (lambda: paths.loop(SPHERE, 10.0, 1e-6, cycles=10**12), ValueError, "cycles must be at most 10000000"),
    (lambda: paths.loop(SPHERE, 10.0, 1e-6, cycles=10**5, steps_per_cycle=10**5), ValueError,
     "cycles [*] steps_per_cycle must be below 10000000 samples, got 100000 [*] 100000"),
    (lambda: paths.paper_fig4(SPHERE, steps=10**7), ValueError, "steps must be at most 3333333"),
])
def test_bad_input(call, exc, message):
    if exc is None:  # accepted: what it needs is there
        call()
        return
    with pytest.raises(exc, match=message):
        call()


class _OnlyNormal:
    """A reference with a normal law only (enough for loop, not for paper_fig4)."""

    def approach(self, N):
        return SPHERE.approach(N)


class _NoMu(_OnlyNormal):
    """Every method paper_fig4 calls, but no friction coefficient."""

    def backbone_displacement(self, T, N):
        return SPHERE.backbone_displacement(T, N)

    def gross_slip_displacement(self, N):
        return SPHERE.gross_slip_displacement(N)


def test_default_family():
    fam = paths.default_family(SPHERE, 37.5, steps_per_cycle=16)
    # 1 phase at ratio 0, 3 at each of the 3 other ratios; 5 levels; 9 amplitudes
    assert len(fam) == (1 + 3 * 3) * 5 * 9
    peaks = np.array([p.N.max() for p in fam])
    assert peaks.max() <= 37.5 * (1 + 1e-12)  # never beyond the tuning load
    ratios = {p.params["ratio"] for p in fam}
    assert ratios == {0.0, 0.3, 0.6, 0.9}
    for p in fam[::37]:
        Nmin = p.params["N_m"] - p.params["N_a"]
        assert p.params["t_a"] == pytest.approx(p.params["amplitude"] * float(SPHERE.gross_slip_displacement(Nmin)))
        assert p.params["N_m"] + p.params["N_a"] == pytest.approx(p.params["level"] * 37.5)
    means = sorted({p.params["N_m"] for p in fam if p.params["ratio"] == 0})
    assert means[0] == pytest.approx(3.75) and means[-1] == pytest.approx(37.5)


def test_plot():
    ax = paths.paper_fig4(SPHERE, steps=20).plot()
    assert "t (µm)" in ax.get_ylabel()
    ax = paths.from_arrays([0.0, 1e-6, 0.0], n=1e-6).plot()
    assert ax.get_title() == "user path"
    plt.close("all")


def test_a_periodic_path_must_close():
    with pytest.raises(ValueError, match=r"periodic: the steady part must close, but t goes from 0 m"):
        paths.from_arrays([0.0, 1e-6, 2e-6], n=[1e-6] * 3, periodic=True)
