"""The bolted lap joint (microslip.fe.lap_joint) and its structure (microslip.frequency.jointed_structure)."""

from functools import cache

import numpy as np
import pytest
import scipy.linalg as sla

pytest.importorskip("skfem")

from microslip.fe import LapJoint, PressureLaw, lap_joint  # noqa: E402
from microslip.fe.joints import PRESETS  # noqa: E402
from microslip.frequency import jointed_structure, static_solution  # noqa: E402

MODES = 6


@cache
def small() -> LapJoint:
    """The coarsest preset (30 contacts) with few tied-interface modes: about 1 s to build."""
    return lap_joint(30, modes=MODES)


def test_the_coarsest_joint_has_its_pairs_contacts_and_dofs():
    j = small()
    preset = PRESETS[30]
    P = preset["along"] * preset["across"]
    assert len(j.patch) == P == 45
    assert j.contacts == 30 and j.tied_pairs.size == 15
    assert j.ndof == 3 * P + MODES
    assert np.array_equal(np.sort(np.concatenate([j.contact_pairs, j.tied_pairs])), np.arange(P))
    assert [b.size for b in j.bolt_pairs] == [5, 5, 5]
    for pairs, (x, y) in zip(j.bolt_pairs, j.bolt_positions):  # the line of nodes across, through the bolt
        xy = j.points[j.patch.nodes_a[pairs], :2]
        assert np.allclose(xy[:, 0], x, rtol=0, atol=1e-12) and np.min(np.abs(xy[:, 1] - y)) <= 1e-12
    assert "contacts=30" in repr(j)


@pytest.mark.parametrize("contacts", sorted(PRESETS))
def test_every_preset_has_its_contacts_and_a_node_on_every_bolt(contacts):
    preset = PRESETS[contacts]
    assert preset["along"] * preset["across"] - 3 * len(set(preset["tied"])) == contacts
    assert (preset["along"] - 1) % 4 == 0 and preset["across"] % 2 == 1  # bolts at 1/4, 1/2, 3/4, centre line


def test_the_bolt_dofs_are_the_relative_displacements_of_the_tied_pairs():
    j = small()
    dofs = j.bolt_dofs
    assert [d.size for d in dofs] == [15, 15, 15]
    assert np.array_equal(np.sort(np.concatenate(dofs)), np.sort(np.concatenate([3 * j.tied_pairs + k
                                                                                 for k in range(3)])))


def test_the_tributary_areas_sum_to_the_overlap():
    j = small()
    g = j.geometry
    # a flat rectangle split into quads: the areas are exact sums of products of the grid's spacings
    assert j.patch.total_area == pytest.approx(g["overlap"] * g["width"], rel=1e-12)
    assert np.allclose(j.patch.normal, [0.0, 0.0, 1.0])  # from the lower plate (a) to the upper one (b)
    assert np.max(j.patch.distance) <= 1e-9 * g["length"]
    sub = j.contact_patch()
    assert len(sub) == 30 and sub.total_area < j.patch.total_area


def test_the_reduced_coordinates_are_the_relative_displacements():
    """Rows of the recovery: u_b - u_a of every pair is its three relative coordinates, exactly."""
    j = small()
    P = len(j.patch)
    rows = {(int(node), c): k for k, (node, c) in enumerate(zip(j.dof_map.nodes, j.dof_map.components))}
    for p in range(P):
        for k, c in enumerate("xyz"):
            diff = j.recovery[rows[int(j.patch.nodes_b[p]), c]] - j.recovery[rows[int(j.patch.nodes_a[p]), c]]
            expected = np.zeros(j.ndof)
            expected[3 * p + k] = 1.0
            assert np.allclose(diff, expected, rtol=0, atol=1e-12)


def test_the_reduced_matrices_are_the_projection():
    j = small()
    T = j.recovery
    M = T.T @ (j.full_M @ T)
    assert np.allclose(j.M, 0.5 * (M + M.T), rtol=0, atol=1e-12 * np.abs(M).max())
    K = T.T @ (j.full_K @ T)
    assert np.allclose(j.K, 0.5 * (K + K.T), rtol=0, atol=1e-10 * np.abs(K).max())
    assert np.allclose(j.bolt_force, T.T @ j.full_bolt_force, rtol=0, atol=1e-9 * j.geometry["bolt_load"])


def test_the_bolts_press_each_plate_with_their_load():
    j = small()
    z = np.array([c == "z" for c in j.dof_map.components])
    lower = np.array([j.points[n, 2] < j.geometry["thickness"] / 2 for n in j.dof_map.nodes])
    F = 3 * j.geometry["bolt_load"]
    assert j.full_bolt_force[z & lower].sum() == pytest.approx(F, rel=1e-12)
    assert j.full_bolt_force[z & ~lower].sum() == pytest.approx(-F, rel=1e-12)
    assert not j.full_bolt_force[~z].any()


def test_the_tied_joint_is_the_monolithic_beam_of_euler_bernoulli():
    """The first tied-interface mode is the monolithic clamped-clamped beam's first bending mode.

    Tolerance 4 %: Euler-Bernoulli leaves out shear deformation and rotary inertia (for L / t = 30 they
    lower the first clamped-clamped frequency by about 1-2 %) and the 3D clamped faces that hold the Poisson
    contraction (which stiffens); measured -1.1 % at 30 contacts and -3.1 % at 120.
    """
    j = small()
    assert j.tied_frequencies[0] == pytest.approx(j.monolithic_frequency(), rel=0.04)
    # the mode bends across the thickness: its z displacements dominate
    lam, phi = sla.eigh(j.K[3 * len(j.patch):, 3 * len(j.patch):], j.M[3 * len(j.patch):, 3 * len(j.patch):],
                        subset_by_index=[0, 0])
    assert np.sqrt(lam[0]) == pytest.approx(j.tied_frequencies[0], rel=1e-8)


def test_the_stuck_joint_is_a_little_softer_than_the_monolithic_beam():
    j = small()
    s = jointed_structure(j, damping_ratio=1e-3)
    assert s.ndof == j.ndof and len(s.contacts) == 30 and all(c.planar for c in s.contacts)
    lam, phi = sla.eigh(s.stuck_stiffness(), s.M, subset_by_index=[0, 0])
    w = np.sqrt(lam[0])
    # the interface's compliance lowers the frequency a little: its stiffness per area is of the order of the
    # half plates' through-thickness stiffness per area, and the interface is short (measured -1.0 % here,
    # -1.5 % at 120 contacts)
    assert 0.95 * j.tied_frequencies[0] < w < j.tied_frequencies[0]
    u = j.recovery @ phi[:, 0]
    comp = np.array(j.dof_map.components)
    assert np.abs(u[comp == "z"]).max() > 5 * np.abs(u[comp != "z"]).max()  # bending across the thickness
    # C = beta K with the damping ratio asked for on that mode
    assert phi[:, 0] @ s.C @ phi[:, 0] / (2 * w) == pytest.approx(1e-3, rel=1e-8)


def test_the_prestressed_interface_carries_the_bolt_load():
    """Contacts and ties together carry the three bolts' clamping (the far clamps take almost nothing)."""
    j = small()
    law = PressureLaw(kn_per_area=2e13, kt_per_area=1e13, mu=0.6)
    s = jointed_structure(j, law)
    q0 = static_solution(s)
    P = len(j.patch)
    gap = q0[3 * np.arange(P) + 2]  # relative normal displacement u_b - u_a: negative when pressed
    contact = law.kn_per_area * j.patch.area[j.contact_pairs] * np.maximum(-gap[j.contact_pairs], 0.0)
    tie = -law.kn_per_area * j.patch.area[j.tied_pairs] * gap[j.tied_pairs]
    # 1e-3: the clamps at the far ends carry a small share through the plates' bending (measured 6e-5 here,
    # 3e-5 at 120 contacts)
    assert contact.sum() + tie.sum() == pytest.approx(3 * j.geometry["bolt_load"], rel=1e-3)
    assert np.count_nonzero(contact) >= 10  # the pairs around the bolts are pressed


@pytest.mark.parametrize("kwargs, match", [
    ({"contacts": 50}, "contacts must be one of"),
    ({"contacts": 30.0}, "contacts must be an integer"),
    ({"overlap": 0.3}, "overlap must be shorter than length"),
    ({"overlap": 0.001}, "overlap must be at least"),
    ({"washer": 0.5}, "washer must be at least 1"),
    ({"nu": 0.5}, "nu"),
    ({"modes": 0}, "modes"),
    ({"modes": 10**6}, "modes must be at most 500"),
    ({"width": 1.0}, "width must be at most length"),
    ({"bolt_load": -1.0}, "bolt_load"),
])
def test_bad_joints_are_refused_by_name(kwargs, match):
    with pytest.raises((ValueError, TypeError), match=match):
        lap_joint(**{"contacts": 30, "modes": MODES, **kwargs})


def test_jointed_structure_checks_its_arguments():
    with pytest.raises(TypeError, match="joint must be a microslip.fe.LapJoint"):
        jointed_structure("joint")
    with pytest.raises(TypeError, match="law must be"):
        jointed_structure(small(), law=1.0)
    with pytest.raises(ValueError, match="damping_ratio"):
        jointed_structure(small(), damping_ratio=1.0)
