"""The Campbell diagram of a cyclic sector: each nodal diameter's modes against speed, the aliasing of the engine
orders, checked against the whole disk assembled (its eigen-solve, and the plain structure's diagram)."""

import csv

import matplotlib

matplotlib.use("Agg")

import numpy as np
import pytest
import scipy.linalg as sla

from microslip import MicroslipModel
from microslip.frequency import CampbellDiagram, CyclicStructure, SpeedModel, campbell, excited_diameter

SECTORS = 6
# one sector: the disk's DOF 0 (left boundary) and 2 (right boundary, the next sector's 0), a blade (1, 3)
K0 = np.array([[3e6, -1e6, -1e6, 0.0], [-1e6, 2e6, 0.0, -1e6], [-1e6, 0.0, 1e6, 0.0], [0.0, -1e6, 0.0, 1e6]])
K1 = np.diag([0.0, 0.2, 0.0, 0.1])  # centrifugal stiffening of the blade (N s^2/m)
M = np.diag([0.1, 0.05, 0.1, 0.02])
FIT = [0.0, 1000.0]
CYCLIC = dict(sectors=SECTORS, left=[0], right=[2])
# a contact between this blade's tip and the next one's, pressed along DOF 1 (every element closed: gaps 0, preload)
LAW = MicroslipModel([1e5, 2e5], [1e6, 1e6], [0.0, 0.0], 0.5)
SPEEDS = np.linspace(0.0, 4000.0, 9)
EOS = (1, 2, 3, 5, 7, 8)  # 5 and 7 alias onto diameter 1, 8 onto 2 (N = 6)
REL = 1e-8  # brentq refines to 1e-13 of the speed; 1e-8 leaves room for the eigen-solves' rounding


def sector_model():
    template = CyclicStructure(M, None, K0, **CYCLIC)
    template.add_contact(LAW, tangential={3: 1.0, template.next(3): -1.0}, normal={1: 1.0}, preload=3.0)
    return SpeedModel(M, None, [K0, K0 + FIT[1] ** 2 * K1], FIT, contacts=template, cyclic=CYCLIC)


def whole(model, w, contacts=True):
    """The assembled disk at speed ``w`` (rad/s)."""
    return model.at(w, contacts=contacts).assembled()


def whole_stuck_frequencies(model, w, system):
    """Every natural frequency (rad/s) of the whole disk, its contacts stuck (every element is closed: gaps 0 and a
    preload) or removed, by a dense eigen-solve of the assembled matrices."""
    disk = whole(model, w, contacts=system == "stuck")
    K = np.array(disk.K, dtype=float)
    for c in disk.contacts:
        K += c.model.kt.sum() * np.outer(c.tangential, c.tangential) + c.model.kn.sum() * np.outer(c.normal, c.normal)
    return np.sqrt(sla.eigh(K, np.array(disk.M, dtype=float), eigvals_only=True))


@pytest.fixture(scope="module")
def diagram():
    model = sector_model()
    return model, campbell(model, SPEEDS, modes=3, engine_orders=EOS)


def test_engine_orders_excite_their_aliased_diameter():
    assert [excited_diameter(k, 6) for k in range(0, 14)] == [0, 1, 2, 3, 2, 1, 0, 1, 2, 3, 2, 1, 0, 1]
    assert [excited_diameter(k, 7) for k in (3, 4, 10, 11)] == [3, 3, 3, 3]
    with pytest.raises(ValueError, match="sectors must be"):
        excited_diameter(1, 2)
    with pytest.raises(ValueError, match="engine_order must be"):
        excited_diameter(-1, 6)


def test_the_diameters_together_are_the_whole_disks_spectrum(diagram):
    """Each diameter 0 < d < N/2 stands for a pair of modes (forward and backward waves): counted twice, the sector's
    frequencies of all diameters (3 DOFs each) are the 18 of the assembled disk, at every speed and in both systems.
    Tolerance: two dense eigen-solves of matrices of norm 1e7 with frequencies above 1e3 rad/s, 1e-9 relative."""
    model, d = diagram
    assert d.nodal_diameters.tolist() == [0, 1, 2, 3] and d.sectors == SECTORS
    for system in ("stuck", "free"):
        assert d.frequencies[system].shape == (SPEEDS.size, 4, 3)
        for k, w in enumerate(SPEEDS):
            f = d.frequencies[system][k]
            sector = np.sort(np.concatenate([f[0], f[1], f[1], f[2], f[2], f[3]]))
            np.testing.assert_allclose(sector, whole_stuck_frequencies(model, w, system), rtol=1e-9)
    assert np.all(d.frequencies["stuck"] >= d.frequencies["free"] * (1 - 1e-12))


def test_each_crossing_is_an_eigenfrequency_of_the_whole_disk_in_its_diameter(diagram):
    model, d = diagram
    assert {c["system"] for c in d.crossings} == {"stuck", "free"}
    assert {c["engine_order"] for c in d.crossings} >= {1, 2, 5, 7}  # aliased orders cross too
    for c in d.crossings:
        w = c["speed"]
        assert c["nodal_diameter"] == excited_diameter(c["engine_order"], SECTORS)
        assert c["frequency"] == c["engine_order"] * w
        f = whole_stuck_frequencies(model, w, c["system"])
        assert np.min(np.abs(f - c["frequency"])) <= REL * c["frequency"]
        # and it is mode ``mode`` of its own diameter there
        one = campbell(model, [w, w * (1 + 1e-9)], modes=3, engine_orders=[1], contacts=c["system"],
                       nodal_diameters=[c["nodal_diameter"]])
        assert one.frequencies[c["system"]][0, 0, c["mode"] - 1] == pytest.approx(c["frequency"], rel=REL)


def test_the_crossings_are_the_whole_disks_where_the_diameter_matches(diagram):
    """The plain Campbell diagram of the assembled disk (18 DOFs, every mode, no aliasing rule) crosses every
    engine-order line at every mode; those of its crossings whose frequency is a mode of the diameter the engine
    order excites are the sector's crossings, and the sector has no other."""
    model, d = diagram
    whole_model = SpeedModel(whole(model, 0.0, False).M, None, [whole(model, w, False).K for w in FIT], FIT,
                             contacts=whole(model, 0.0))
    orders = (1, 5, 8)  # a direct order, one aliased onto its diameter from below (N - 1), one from above (N + 2)
    plain = campbell(whole_model, SPEEDS, modes=18, engine_orders=orders)
    matched = 0
    for c in plain.crossings:
        nd = excited_diameter(c["engine_order"], SECTORS)
        mine = campbell(model, [c["speed"], c["speed"] * (1 + 1e-9)], modes=3, engine_orders=[1],
                        contacts=c["system"], nodal_diameters=[nd]).frequencies[c["system"]][0, 0]
        if np.min(np.abs(mine - c["frequency"])) > 1e-6 * c["frequency"]:
            continue  # a mode of another diameter: this engine order does not excite it
        matched += 1
        assert any(x["system"] == c["system"] and x["engine_order"] == c["engine_order"]
                   and x["speed"] == pytest.approx(c["speed"], rel=REL) for x in d.crossings), c
    # each sector crossing appears once in the disk's diagram, or twice for a pair of modes (0 < d < N/2)
    expected = sum(2 if 0 < x["nodal_diameter"] < SECTORS / 2 else 1 for x in d.crossings
                   if x["engine_order"] in orders)
    assert matched == expected and matched >= 10


def test_a_cyclic_diagram_writes_its_csv_and_plots(diagram, tmp_path):
    _, d = diagram
    rows = list(csv.DictReader(open(d.to_csv(tmp_path / "campbell.csv"))))
    assert len(rows) == max(SPEEDS.size, len(d.crossings))
    assert float(rows[2]["stuck ND 1 mode 2 [Hz]"]) == d.frequencies["stuck"][2, 1, 1] / (2 * np.pi)
    assert int(rows[0]["crossing nodal diameter [-]"]) == d.crossings[0]["nodal_diameter"]
    ax = d.plot()
    assert ax.get_xlabel() == "rotation speed (rpm)"
    assert any("EO7 (ND 1)" == t.get_text() for t in ax.texts)
    assert isinstance(d, CampbellDiagram) and d.hertz("free").shape == (SPEEDS.size, 4, 3)


def test_a_few_diameters_and_the_refusals_name_the_parameter():
    model = sector_model()
    d = campbell(model, [0.0, 1500.0, 3000.0], modes=2, engine_orders=[1, 5, 4], contacts="free",
                 nodal_diameters=[2, 1])
    assert d.nodal_diameters.tolist() == [1, 2] and d.frequencies["free"].shape == (3, 2, 2)
    assert all(c["nodal_diameter"] == excited_diameter(c["engine_order"], SECTORS) for c in d.crossings)
    with pytest.raises(ValueError, match=r"nodal_diameters\[0\] must be at most 3"):
        campbell(model, [0.0, 5.0], nodal_diameters=[4])
    with pytest.raises(ValueError, match="nodal_diameters must be distinct"):
        campbell(model, [0.0, 5.0], nodal_diameters=[1, 1])
    with pytest.raises(TypeError, match="nodal_diameters must be a sequence"):
        campbell(model, [0.0, 5.0], nodal_diameters=1)
    with pytest.raises(ValueError, match="modes must be at most 3"):
        campbell(model, [0.0, 5.0], modes=4)
    plain = SpeedModel(M, None, [K0, K0 + K1], FIT)
    with pytest.raises(ValueError, match="nodal_diameters is only for a cyclic sector"):
        campbell(plain, [0.0, 5.0], nodal_diameters=[0])
