"""Speed-dependent structures: the fit through the given stiffness matrices, the Campbell diagram, a damper over speed."""

import csv
import warnings

import matplotlib

matplotlib.use("Agg")

import numpy as np
import pytest
import scipy.linalg as sla
import scipy.sparse as sp

from microslip import MicroslipModel
from microslip.frequency import (CampbellDiagram, CyclicStructure, SpeedCurve, SpeedModel, Structure, campbell,
                                 damper_design_curve, damper_speed_curve)
from microslip.frequency.analyses.response import PeakOnEdgeWarning
from test_damper import blade_pair, damper  # the blade pair with its damper
from test_design import antiphase

LAW = MicroslipModel([1e4, 2e4], [1e6, 1e6], [0.0, 0.5e-6], 0.5)


def chain(n=4, k=1e6, scale=1.0):
    """A chain of ``n`` masses (kg) on springs (N/m), grounded at the first."""
    K = np.zeros((n, n))
    for i in range(n):
        K[i, i] += 2 * k * scale if i < n - 1 else k * scale
        if i + 1 < n:
            K[i, i + 1] = K[i + 1, i] = -k * scale
    return K


def stiffness_at(speeds, K0, K1, K2):
    return [K0 + w**2 * K1 + w**4 * K2 for w in speeds]


K0 = chain()
K1 = np.diag([2.0, 1.0, 0.5, 0.25])          # centrifugal stiffening (N s^2/m)
K2 = -1e-7 * np.diag([1.0, 0.0, 1.0, 0.0])   # a little spin softening (N s^4/m)
M = np.diag([1.0, 0.8, 0.6, 0.4])
SPEEDS3 = [0.0, 400.0, 900.0]


def model3(**kwargs):
    return SpeedModel(M, None, stiffness_at(SPEEDS3, K0, K1, K2), SPEEDS3, **kwargs)


# -- the fit ---------------------------------------------------------------------------------------------------------

@pytest.mark.parametrize("k", [2, 3])
def test_the_fit_reproduces_the_given_matrices_exactly_dense_and_sparse(k):
    speeds = [0.0, 300.0, 1000.0][:k]
    mats = stiffness_at([150.0, 420.0, 777.0][:k], K0, K1, K2)  # any symmetric matrices
    for sparse in (False, True):
        given = [sp.csr_matrix(A) for A in mats] if sparse else mats
        m = SpeedModel(M, None, given, speeds)
        for w, A in zip(m.speeds, mats):
            K = m.stiffness(w)
            assert sp.issparse(K) == sparse
            assert np.array_equal(K.toarray() if sparse else K, A)  # bit for bit
            s = m.at(w)
            assert np.array_equal(s.K.toarray() if sparse else s.K, A)


def test_three_speeds_recover_the_polynomial_and_rpm_is_read():
    m = model3()
    c0, c1, c2 = m.coefficients()
    scale = np.abs(K0).max()
    assert np.abs(c0 - K0).max() <= 1e-12 * scale
    assert np.abs(c1 - K1).max() * 900.0**2 <= 1e-12 * scale * 10
    assert np.abs(c2 - K2).max() * 900.0**4 <= 1e-12 * scale * 10
    w = 613.0
    assert np.allclose(m.stiffness(w), K0 + w**2 * K1 + w**4 * K2, rtol=0, atol=1e-10 * scale)
    r = SpeedModel(M, None, stiffness_at([0.0, 400.0], K0, K1, 0 * K2), [0.0, "3819.7186342054883 rpm"])
    assert r.speeds[1] == pytest.approx(400.0, rel=1e-15)


def test_the_speed_model_refuses_by_name():
    A, B = K0, K0 + K1
    with pytest.raises(ValueError, match=r"speeds must be distinct: speeds\[0\] and speeds\[1\] are both 100.0"):
        SpeedModel(M, None, [A, B], [100.0, 100.0])
    with pytest.raises(ValueError, match=r"speeds\[1\] must be non-negative, got -5.0"):
        SpeedModel(M, None, [A, B], [0.0, -5.0])
    with pytest.raises(ValueError, match="speeds must hold 2 or 3 rotation speeds"):
        SpeedModel(M, None, [A], [0.0])
    with pytest.raises(ValueError, match=r"stiffness must hold one matrix per speed \(2\), got 3"):
        SpeedModel(M, None, [A, B, B], [0.0, 1.0])
    bad = B.copy()
    bad[0, 1] += 1e3
    with pytest.raises(ValueError, match=r"stiffness\[1\]: K must be symmetric"):
        SpeedModel(M, None, [A, bad], [0.0, 1.0])
    with pytest.raises(ValueError, match="speeds\\[1\\]: cannot read 'fast'"):
        SpeedModel(M, None, [A, B], [0.0, "fast"])
    with pytest.raises(ValueError, match="radius must be given"):
        SpeedModel(M, None, [A, B], [0.0, 1.0], damper=damper())
    with pytest.raises(TypeError, match="contacts must be a Structure"):
        SpeedModel(M, None, [A, B], [0.0, 1.0], contacts=3)
    with pytest.raises(ValueError, match="cyclic: .*sectors"):
        SpeedModel(M, None, [A, B], [0.0, 1.0], cyclic=dict(sectors=2, left=[0], right=[3]))
    with pytest.raises(ValueError, match="omega_rot must be at most 1e\\+75 rad/s"):
        model3().at(1e80)


def test_contacts_are_copied_from_a_template_or_added_by_a_callback():
    template = Structure(M, None, K0)
    template.add_contact(LAW, tangential=0, normal=1, preload=3.0, name="root")
    template.add_static_force([0.0, 0.0, 1.0, 0.0])
    a = model3(contacts=template).at(500.0)
    assert [c.name for c in a.contacts] == ["root"] and a.contacts[0].preload == 3.0
    assert np.array_equal(a.contacts[0].normal, template.contacts[0].normal)
    assert np.array_equal(a.static_force, template.static_force)

    def add(s, omega):
        s.add_contact(LAW, tangential=0, normal=1, preload=1e-3 * omega, name="root")

    b = model3(contacts=add).at(500.0)
    assert b.contacts[0].preload == 0.5
    assert model3(contacts=add).at(500.0, contacts=False).contacts == []


def test_a_cyclic_model_gives_sectors_and_the_damper_load_follows_the_square_of_the_speed():
    K = blade_pair(0.0, 0.0).K
    Ms = blade_pair(0.0, 0.0).M
    m = SpeedModel(Ms, None, [K, 1.2 * K], [0.0, 100.0], damper=damper(), radius=0.25)
    for w in (40.0, 80.0):
        s = m.at(w)
        assert s.ndof == 9 and s.static_force[7] == 0.02 * 0.25 * w * w  # m r Omega^2 on the damper's Y
    with pytest.raises(ValueError, match="omega_rot must be > 0 rad/s with a damper"):
        m.at(0.0)
    c = SpeedModel(Ms, None, [K, 1.2 * K], [0.0, 100.0], cyclic=dict(sectors=12, left=[0, 1], right=[3, 4]))
    assert isinstance(c.at(50.0), CyclicStructure) and c.at(50.0).sectors == 12


# -- the Campbell diagram -------------------------------------------------------------------------------------------

def stuck_direct(model, template, w):
    """``K(w)`` with the template's contact stuck (every element closed at rest: preload along its normal)."""
    K = model.stiffness(w).copy()
    c = template.contacts[0]
    K += c.model.kt.sum() * np.outer(c.tangential, c.tangential) + c.model.kn.sum() * np.outer(c.normal, c.normal)
    return K


@pytest.fixture(scope="module")
def diagram():
    template = Structure(M, None, K0)
    template.add_contact(MicroslipModel([1e4, 2e4], [1e6, 1e6], [0.0, 0.0], 0.5), tangential=0, normal=1,
                         preload=3.0)
    model = model3(contacts=template)
    return model, template, campbell(model, np.linspace(0.0, 1500.0, 16), modes=3, engine_orders=(1, 2, 3, 4))


def test_the_crossings_agree_with_an_eigen_solve_at_their_speed(diagram):
    model, template, d = diagram
    assert {c["system"] for c in d.crossings} == {"stuck", "free"} and len(d.crossings) >= 8
    for c in d.crossings:
        w = c["speed"]
        K = stuck_direct(model, template, w) if c["system"] == "stuck" else model.stiffness(w)
        f = np.sqrt(sla.eigh(K, M, eigvals_only=True)[c["mode"] - 1])
        assert f == pytest.approx(c["engine_order"] * w, rel=1e-8)
        assert c["frequency"] == c["engine_order"] * w
    # the curves are the eigen-solves at the speeds, the stuck system stiffer than the free one
    for k, w in enumerate(d.speeds):
        assert np.allclose(d.frequencies["free"][k], np.sqrt(sla.eigh(model.stiffness(w), M, eigvals_only=True)[:3]),
                           rtol=1e-12)
    assert np.all(d.frequencies["stuck"] >= d.frequencies["free"])


def test_the_diagram_writes_its_csv_and_plots(diagram, tmp_path):
    _, _, d = diagram
    path = d.to_csv(tmp_path / "campbell.csv")
    rows = list(csv.DictReader(open(path)))
    assert len(rows) == max(16, len(d.crossings))
    assert float(rows[3]["speed [rpm]"]) == pytest.approx(d.speeds[3] * 60 / (2 * np.pi))
    assert float(rows[0]["crossing speed [rad/s]"]) == d.crossings[0]["speed"]
    assert float(rows[2]["stuck mode 2 [Hz]"]) == d.frequencies["stuck"][2, 1] / (2 * np.pi)
    ax = d.plot()
    assert ax.get_xlabel() == "rotation speed (rpm)" and ax.get_ylabel() == "frequency (Hz)"
    assert isinstance(d, CampbellDiagram) and d.hertz("free").shape == (16, 3)


def test_campbell_refuses_by_name():
    m = model3()
    with pytest.raises(ValueError, match="speeds must be at least 2 increasing"):
        campbell(m, [10.0, 5.0])
    with pytest.raises(ValueError, match=r"engine_orders\[1\] must be"):
        campbell(m, [0.0, 5.0], engine_orders=(1, 0))
    with pytest.raises(ValueError, match="modes must be at most 4"):
        campbell(m, [0.0, 5.0], modes=5)
    with pytest.raises(ValueError, match="contacts must be one of"):
        campbell(m, [0.0, 5.0], contacts="slipping")
    with pytest.raises(TypeError, match="model must be a microslip SpeedModel"):
        campbell(Structure(M, None, K0), [0.0, 5.0])


# -- a damper over rotation speed ----------------------------------------------------------------------------------

def test_the_damper_speed_curve_is_the_design_curve_at_each_speeds_load(tmp_path):
    pair = blade_pair()
    m = SpeedModel(pair.M, pair.C, [pair.K, pair.K], [0.0, 100.0], damper=damper(), radius=0.25)
    speeds = [np.sqrt(5.0 / 0.005), np.sqrt(300.0 / 0.005)]  # loads 5 N (sliding) and 300 N (stuck)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        curve = damper_speed_curve(m, speeds, antiphase(), (3000.0, 5000.0), dof=2, harmonics=1)
        one = damper_design_curve(m.at(speeds[1], damper=False), damper(), [curve.loads[1]], antiphase(), (3000.0, 5000.0), dof=2,
                                  harmonics=1)
    assert isinstance(curve, SpeedCurve) and np.allclose(curve.loads, [5.0, 300.0], rtol=1e-14)
    assert curve.peak_amplitude[1] == one.peak_amplitude[0] and curve.status == ["peak", "peak"]
    assert curve.peak_amplitude[0] < curve.peak_amplitude[1]  # the sliding damper damps
    assert curve.worst[0] == speeds[1]
    rows = list(csv.DictReader(open(curve.to_csv(tmp_path / "speed.csv"))))
    assert float(rows[1]["speed [rad/s]"]) == speeds[1] and rows[0]["status"] == "peak"
    assert curve.plot().get_xlabel() == "rotation speed (rpm)"
    # a range per speed: the second one ends below the stuck resonance, its peak on the edge, flagged with its speed
    with pytest.warns(PeakOnEdgeWarning, match=f"speed {speeds[1]:.6g} rad/s .*rpm.*load 300 N: .*range"):
        edge = damper_speed_curve(m, speeds, antiphase(), [(3000.0, 5000.0), (3000.0, 4200.0)], dof=2,
                                  harmonics=1)
    assert edge.status == ["peak", "peak on the range's edge"] and edge.peak_amplitude[0] == curve.peak_amplitude[0]
    with pytest.raises(ValueError, match=r"omega must be a frequency range \(2,\) or one per speed"):
        damper_speed_curve(m, speeds, antiphase(), [1.0, 2.0, 3.0], dof=2)
    with pytest.raises(ValueError, match="model must carry a damper"):
        damper_speed_curve(model3(), speeds, antiphase(), (3000.0, 5000.0), dof=2)
