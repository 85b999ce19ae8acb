"""Sectors in their own frames (issue 25, item 2): a sector given in the global Cartesian frame (its right boundary
the left one turned by 2 pi / N) and in cylindrical frames equals the whole disk built in the Cartesian frame.

The sector: five nodes of three translations each, joined by bars and grounded by isotropic springs, in a disk of
eight about an axis that is not a coordinate axis and does not pass through the origin. Nodes: 0 the ring (left
boundary), 1 and 2 the platform's edges, 3 the tip, 4 the ring of the next sector (right boundary). Contacts: the
platform's edge 2 on the next sector's edge 1 (a preload along the normal), the tip on the next tip and the edge 2
on the next sector's ring (each at a fixed normal load). A centrifugal static force on every node.
"""

import numpy as np
import pytest

from microslip import Sphere, tune
from microslip.frequency import CyclicStructure, Structure, frequency_point
from microslip.frequency.structures.frames import rotation

SPHERE = Sphere.paper()
MODEL = tune(SPHERE, 37.5, elements=4)
N = 8
ALPHA = 2 * np.pi / N
# the disk's frame: its axis turned away from z, its centre off the origin
G = rotation(np.array([1.0, 2.0, 3.0]) / np.sqrt(14.0), 0.7)
CENTRE = np.array([0.05, -0.02, 0.3])
AXIS = G[:, 2]
# node positions in the disk's frame (m): radius, angle (fraction of the sector), height
LOCAL = [(0.10, 0.0, 0.0), (0.20, 0.15, 0.01), (0.20, 0.85, -0.01), (0.30, 0.5, 0.02), (0.10, 1.0, 0.0)]
MASS = [0.05, 0.04, 0.04, 0.03, 0.05]  # kg; the ring's mass split between nodes 0 and 4 (shared by two sectors)
BARS = [(0, 4, 5e6), (0, 1, 4e6), (4, 2, 4e6), (1, 2, 3e6), (1, 3, 2e6), (2, 3, 2e6), (0, 2, 1e6), (4, 1, 1e6)]
GROUND = [1e6, 3e5, 3e5, 3e5, 1e6]  # N/m, isotropic (the ring's split too)
CENTRIFUGAL = [0.0, 10.0, 10.0, 40.0, 0.0]  # N, radial
F_TIP = np.array([2.0, 4.0, 6.0])  # N on the tip (radial, tangential, axial), first harmonic
SAMPLES = 16 * N  # a multiple of the sectors: the disk's AFT samples every sector at the same phases
OMEGA = 4500.0


def turn(sector):
    """The disk's frame turned to sector ``sector``: a local vector's global components."""
    return G @ rotation(np.array([0.0, 0.0, 1.0]), sector * ALPHA)


def position(sector, node):
    r, frac, z = LOCAL[node]
    return CENTRE + turn(sector) @ np.array([r * np.cos(frac * ALPHA), r * np.sin(frac * ALPHA), z])


def radial(sector, node):
    frac = LOCAL[node][1]
    return turn(sector) @ np.array([np.cos(frac * ALPHA), np.sin(frac * ALPHA), 0.0])


def tangential_unit(sector, node):
    frac = LOCAL[node][1]
    return turn(sector) @ np.array([-np.sin(frac * ALPHA), np.cos(frac * ALPHA), 0.0])


def bars(n_nodes, where, place):
    """Mass, damping and stiffness of the bars and springs of every sector placed by ``place(s, node) -> node``
    (``where(s, node)`` its position), on ``3 n_nodes`` DOFs."""
    M, K = np.zeros((3 * n_nodes,) * 2), np.zeros((3 * n_nodes,) * 2)
    for s, nodes in place:
        for i, j, k in BARS:
            e = where(s, j) - where(s, i)
            e /= np.linalg.norm(e)
            block = k * np.outer(e, e)
            a, b = 3 * nodes[i], 3 * nodes[j]
            K[a:a + 3, a:a + 3] += block
            K[b:b + 3, b:b + 3] += block
            K[a:a + 3, b:b + 3] -= block
            K[b:b + 3, a:a + 3] -= block
        for n in range(5):
            a = 3 * nodes[n]
            K[a:a + 3, a:a + 3] += GROUND[n] * np.eye(3)
            M[a:a + 3, a:a + 3] += MASS[n] * np.eye(3)
    return M, 1e-6 * K + 2.0 * M, K


def contacts(add, own, nxt, s):
    """The sector's three contacts in the global frame: ``own(node)``, ``nxt(node)`` give the DOF triples."""
    t_edge = (radial(s + 1, 0) + AXIS) / np.sqrt(2.0)  # on the boundary plane between the sectors
    n_edge = tangential_unit(s + 1, 0)  # 2 approaches the next sector's 1 along the circumference

    def vec(pairs):
        out = {}
        for dofs, v in pairs:
            for d, c in zip(dofs, v):
                out[d] = out.get(d, 0.0) + c
        return out

    add(MODEL, tangential=vec([(own(2), t_edge), (nxt(1), -t_edge)]), normal=vec([(own(2), n_edge), (nxt(1), -n_edge)]),
        preload=40.0)
    add(MODEL, tangential=vec([(own(3), AXIS), (nxt(3), -AXIS)]), approach=SPHERE.approach(15.0))
    add(MODEL, tangential=vec([(own(2), AXIS), (nxt(0), -AXIS)]), approach=SPHERE.approach(10.0))


def sector_static(s):
    f = np.zeros(15)
    for n in range(5):
        f[3 * n:3 * n + 3] = CENTRIFUGAL[n] * radial(s, n)
    return f


def tip_force(s):
    return np.concatenate([np.zeros(9), F_TIP @ np.array([radial(s, 3), tangential_unit(s, 3), AXIS]), np.zeros(3)])


def coordinates():
    return [[position(0, 0)], [position(0, 4)]]


def cartesian_sector(**kwargs):
    """The sector in the global Cartesian frame, as exported without cyclic coordinates."""
    M, C, K = bars(5, position, [(0, range(5))])
    d = CyclicStructure(M, C, K, sectors=N, left=[(0, 1, 2)], right=[(12, 13, 14)], frame="cartesian", axis=AXIS,
                        point=CENTRE, coordinates=coordinates(), nodes=[(3, 4, 5), (6, 7, 8), (9, 10, 11)],
                        **kwargs)
    triple = lambda n: (3 * n, 3 * n + 1, 3 * n + 2)  # noqa: E731
    contacts(d.add_contact, triple, lambda n: tuple(d.next(j) for j in triple(n)), 0)
    d.add_static_force(sector_static(0))
    return d


def cylindrical_basis(x):
    """Columns e_r, e_theta, e_axis at the point ``x`` (global components): ``u_global = B u_cylindrical``."""
    rel = x - CENTRE
    r = rel - (rel @ AXIS) * AXIS
    e_r = r / np.linalg.norm(r)
    return np.column_stack([e_r, np.cross(AXIS, e_r), AXIS])


def to_cylindrical():
    """``T`` (15, 15): the Cartesian sector's DOFs from the cylindrical one's, the boundary nodes in their nodal
    cylindrical frames (as ANSYS CYCLIC turns the edge nodes), the others left Cartesian."""
    T = np.eye(15)
    for n in (0, 4):
        T[3 * n:3 * n + 3, 3 * n:3 * n + 3] = cylindrical_basis(position(0, n))
    return T


def cylindrical_sector():
    """The same sector with its boundary nodes in cylindrical frames; the next sector's coefficients in its own
    frame at each node: ``(R B_n)^T d`` for a global direction ``d`` (``B_n`` the node's frame, ``R`` the turn)."""
    T = to_cylindrical()
    M, C, K = (T.T @ A @ T for A in bars(5, position, [(0, range(5))]))
    d = CyclicStructure(M, C, K, sectors=N, left=[(0, 1, 2)], right=[(12, 13, 14)], axis=AXIS, point=CENTRE,
                        coordinates=coordinates())
    R = rotation(AXIS, ALPHA)

    def add(model, *, tangential, normal=None, **kwargs):
        def local(direction):
            own, nxt = np.zeros(15), np.zeros(15)
            for key, c in direction.items():
                (nxt if hasattr(key, "dof") else own)[getattr(key, "dof", key)] += c
            own, nxt = T.T @ own, T.T @ np.kron(np.eye(5), R.T) @ nxt
            return {**{i: own[i] for i in np.flatnonzero(own)}, **{d.next(int(j)): nxt[j] for j in np.flatnonzero(nxt)}}

        return d.add_contact(model, tangential=local(tangential), normal=None if normal is None else local(normal),
                             **kwargs)

    triple = lambda n: (3 * n, 3 * n + 1, 3 * n + 2)  # noqa: E731
    contacts(add, triple, lambda n: tuple(d.next(j) for j in triple(n)), 0)
    d.add_static_force(T.T @ sector_static(0))
    return d, T


def hand_built_disk(engine_order):
    """The whole disk in the global frame, every sector's bars placed at its own nodes' positions: ring nodes
    0..N-1, then sector s's nodes 1, 2, 3 at N + 3 s + (0, 1, 2); with the travelling wave's force."""
    nodes = lambda s: (s % N, N + 3 * (s % N), N + 3 * (s % N) + 1, N + 3 * (s % N) + 2, (s + 1) % N)  # noqa: E731
    M, C, K = bars(4 * N, position, [(s, nodes(s)) for s in range(N)])
    whole = Structure(M, C, K)
    triple = lambda s: lambda n: tuple(3 * nodes(s)[n] + k for k in range(3))  # noqa: E731
    f = np.zeros(12 * N, dtype=complex)
    for s in range(N):
        contacts(whole.add_contact, triple(s), triple(s + 1), s)
        np.add.at(whole.static_force, [d for n in range(5) for d in triple(s)(n)], sector_static(s))
        np.add.at(f, [d for n in range(5) for d in triple(s)(n)], tip_force(s) * np.exp(-1j * s * ALPHA * engine_order))
    return whole, f, triple


def test_the_assembled_cartesian_disk_is_the_disk_built_in_the_global_frame():
    d = cartesian_sector()
    whole = d.assembled()
    built, f, triple = hand_built_disk(1)
    # assembled numbering: sector s's nodes 0..3 at 12 s + 3 n; the hand-built one: ring s, then N + 3 s + ...
    perm = np.array([dof for s in range(N) for n in range(4) for dof in triple(s)(n)])
    for A, B in ((whole.M, built.M), (whole.C, built.C), (whole.K, built.K)):
        np.testing.assert_allclose(A, B[np.ix_(perm, perm)], rtol=0, atol=1e-12 * np.abs(B).max())
    for A, B in zip(whole.contact_directions()[:2], built.contact_directions()[:2]):
        np.testing.assert_allclose(A, B[perm], rtol=0, atol=1e-14)
    np.testing.assert_allclose(whole.preload_force(), built.preload_force()[perm], rtol=0, atol=1e-12)
    np.testing.assert_allclose(d.travelling_wave(tip_force(0), 1)[1], f[perm], rtol=0, atol=1e-13)


def test_the_same_matrices_read_as_matching_frames_are_another_disk():
    """The defect of issue 25: a Cartesian sector taken as a chain of translated sectors, silently. The platform's
    static normal load is then far off (here 28.8 N for 9.92 N; the response 150 % off)."""
    M, C, K = bars(5, position, [(0, range(5))])
    naive = CyclicStructure(M, C, K, sectors=N, left=[0, 1, 2], right=[12, 13, 14])
    triple = lambda n: (3 * n, 3 * n + 1, 3 * n + 2)  # noqa: E731
    contacts(naive.add_contact, triple, lambda n: tuple(naive.next(j) for j in triple(n)), 0)
    naive.add_static_force(sector_static(0))
    right, wrong = (frequency_point(d, tip_force(0), OMEGA, harmonics=1, engine_order=1, samples=SAMPLES,
                                    stability=False) for d in (cartesian_sector(), naive))
    assert abs(wrong.static_normal_force[0] / right.static_normal_force[0] - 1) > 0.5


@pytest.mark.parametrize("engine_order", [0, 1, N // 2, N // 2 + 1])
def test_cartesian_and_cylindrical_sectors_equal_the_assembled_cartesian_disk(engine_order):
    cart = cartesian_sector()
    whole = cart.assembled()
    full = frequency_point(whole, cart.travelling_wave(tip_force(0), engine_order), OMEGA, harmonics=3,
                           reduction="exact", samples=SAMPLES, stability=False)
    scale = np.abs(full.coefficients).max()
    sector = frequency_point(cart, tip_force(0), OMEGA, harmonics=3, engine_order=engine_order, samples=SAMPLES,
                             stability=False)
    cyl, T = cylindrical_sector()
    in_cyl = frequency_point(cyl, T.T @ tip_force(0), OMEGA, harmonics=3, engine_order=engine_order,
                             samples=SAMPLES, stability=False)
    disk = np.array([full.dof_coefficients(j) for j in range(12 * N)])[:, 0]  # (dofs, 2H+1)
    u_cart = np.array([sector.dof_coefficients(j)[0] for j in range(15)])
    u_cyl = T @ np.array([in_cyl.dof_coefficients(j)[0] for j in range(15)])
    reference = np.concatenate([disk[:12], disk[12:15]])  # sector 0, its right boundary sector 1's ring
    errors = [np.abs(u - reference).max() / scale for u in (u_cart, u_cyl)]
    assert max(errors) < 1e-10, errors  # measured 1e-15 to 7e-15
    assert np.all(full.contact_dissipation[0, :3] > 0) or engine_order == 0  # the contacts slip (EO 0: tips at rest)
    # sector k in its own frame: the disk's sector k turned back
    k = 3
    back = np.kron(np.eye(4), turn(k) @ np.linalg.inv(turn(0))).T
    np.testing.assert_allclose(np.array([sector.sector_coefficients(j, k)[0] for j in range(12)]),
                               back @ disk[12 * k:12 * k + 12], rtol=0, atol=1e-10 * scale)
    for r in (sector, in_cyl):
        np.testing.assert_allclose(r.static_normal_force[0], full.static_normal_force[0], rtol=1e-10)
        np.testing.assert_allclose(r.contact_dissipation.sum(), full.contact_dissipation.sum() / N, rtol=1e-8)


def test_a_right_boundary_that_is_not_the_left_one_turned_is_refused_with_the_node_and_the_distance():
    M, C, K = bars(5, position, [(0, range(5))])
    kwargs = dict(sectors=N, left=[(0, 1, 2)], right=[(12, 13, 14)], frame="cartesian", axis=AXIS, point=CENTRE)
    off = [[position(0, 0)], [position(0, 4) + 1e-3 * AXIS]]
    with pytest.raises(ValueError, match="coordinates: the right boundary's node 0 \\(left DOFs \\[0, 1, 2\\], right "
                                         "DOFs \\[12, 13, 14\\]\\) at \\[0.0715167, 0.0776612, 0.299431\\] m is "
                                         "0.001 m from its left node at .* turned by 2 pi / sectors \\(45 deg, "
                                         "sectors = 8\\) about axis = .* through point = \\[0.05, -0.02, 0.3\\] "
                                         "\\(tolerance 1e-07 m"):
        CyclicStructure(M, C, K, coordinates=off, **kwargs)
    with pytest.raises(ValueError, match="0.141 m from .* it is the left one turned by -2 pi / sectors: give axis = "):
        CyclicStructure(M, C, K, coordinates=[[position(0, 4)], [position(0, 0)]], **kwargs)
    with pytest.raises(ValueError, match="coordinates: the right boundary's node 0 .* 0.141 m from"):  # either frame
        CyclicStructure(M, C, K, coordinates=[[position(0, 4)], [position(0, 0)]],
                        **{**kwargs, "frame": "cylindrical"})


@pytest.mark.parametrize("change, message", [
    ({"coordinates": None}, "coordinates must be given with frame='cartesian'"),
    ({"left": [0, 1, 2], "right": [12, 13, 14]}, "left\\[0\\]: DOF 0 is not in a node's tuple: in the Cartesian frame"),
    ({"left": [(0, 1, 2, 3)], "right": [(12, 13, 14, 5)]},
     "left\\[0\\] must be one node's \\(x, y\\) or \\(x, y, z\\)"),
    ({"left": [(0, 1)], "right": [(12, 13)]},
     "axis must lie along z for 2-D nodes \\(x, y\\), got axis = \\[0.39474, "),
    ({"right": [(12, 13)]}, "left and right must pair the boundary DOFs one to one, got 3 and 2 DOFs"),
    ({"frame": "polar"}, "frame must be one of 'cylindrical', 'cartesian', got 'polar'"),
    ({"axis": [0, 0, 0]}, "axis must not be zero"),
    ({"nodes": [(3, 4, 5, 6)]}, "nodes\\[0\\] must be a node's \\(x, y\\) or \\(x, y, z\\) DOFs"),
    ({"nodes": [(0, 4, 5)]}, "nodes\\[0\\]: DOF 0 is on a boundary"),
    ({"coordinates": [[position(0, 0)], [position(0, 4)], [position(0, 4)]]},
     "coordinates must have shape \\(2, 1, 2 or 3\\)"),
])
def test_bad_frames_are_refused_by_name(change, message):
    M, C, K = bars(5, position, [(0, range(5))])
    kwargs = dict(sectors=N, left=[(0, 1, 2)], right=[(12, 13, 14)], frame="cartesian", axis=AXIS, point=CENTRE,
                  coordinates=coordinates())
    with pytest.raises(ValueError, match=message):
        CyclicStructure(M, C, K, **{**kwargs, **change})


def test_a_next_sector_dof_must_be_in_a_node_that_turns():
    M, C, K = bars(5, position, [(0, range(5))])
    d = CyclicStructure(M, C, K, sectors=N, left=[(0, 1, 2)], right=[(12, 13, 14)], frame="cartesian", axis=AXIS,
                        point=CENTRE, coordinates=coordinates())
    with pytest.raises(ValueError, match="tangential: DOF 9 of the next sector is in no node's tuple: in the Cartesian "
                                         "frame"):
        d.add_contact(MODEL, tangential={9: 1.0, d.next(9): -1.0}, approach=1e-6)
    d.add_contact(MODEL, tangential={9: 1.0, d.next(0): -1.0}, approach=1e-6)  # the left boundary's node turns
    with pytest.raises(ValueError, match="nodes is for frame='cartesian'"):
        CyclicStructure(M, C, K, sectors=N, left=[0], right=[12], nodes=[(3, 4, 5)])


def test_planar_nodes_turn_about_z():
    """2-D nodes (x, y): the rotation about z on each pair."""
    c, s = np.cos(ALPHA), np.sin(ALPHA)
    K = np.kron(np.array([[2e6, -1e6, 0], [-1e6, 2e6, -1e6], [0, -1e6, 1e6]]), np.eye(2))
    kwargs = dict(sectors=N, left=[(0, 1)], right=[(4, 5)], frame="cartesian", point=[1.0, 2.0],
                  coordinates=[[[1.1, 2.0]], [[1.0 + 0.1 * c, 2.0 + 0.1 * s]]])
    d = CyclicStructure(np.eye(6) * 0.1, None, K, nodes=[(2, 3)], **kwargs)
    np.testing.assert_allclose(d.boundary_rotation.toarray(), [[c, -s], [s, c]], rtol=0, atol=1e-16)
    d.add_contact(MODEL, tangential={2: 1.0, d.next(2): -1.0}, approach=1e-6)
    np.testing.assert_allclose(d.contact_directions_next()[0][2:4, 0], [-c, s], rtol=0, atol=1e-16)  # R^T (-1, 0)
    with pytest.raises(ValueError, match="axis must lie along z for 2-D nodes"):
        CyclicStructure(np.eye(6) * 0.1, None, K, axis=[0, 1, 1], **kwargs)


def test_a_damper_and_a_craig_bampton_model_keep_the_frame(tmp_path):
    from microslip.frequency import CraigBampton, UnderPlatformDamper, craig_bampton

    d = cartesian_sector()
    upd = UnderPlatformDamper(0.02, 1e-6, centrifugal_load=40.0, retention=2e3)  # one contact per face: it rolls
    upd.add_interface(MODEL, points=[(-3e-3, 1e-3)], angle_deg=135.0, platform={"x": 6, "y": 7})
    upd.add_interface(MODEL, points=[(3e-3, 1e-3)], angle_deg=45.0, platform={"x": d.next(3), "y": d.next(4)})
    with_damper = upd.attach(d)
    assert with_damper.frame == "cartesian" and with_damper.ndof == 18
    np.testing.assert_array_equal(with_damper.boundary_rotation.toarray(), d.boundary_rotation.toarray())
    np.testing.assert_array_equal(with_damper.contact_directions_next()[0][:15, :3], d.contact_directions_next()[0])
    cb = craig_bampton(d, list(range(15)), modes=0)
    back = CraigBampton.load(cb.save(tmp_path / "sector.npz"))
    for model in (cb, back):
        s = model.structure
        assert s.frame == "cartesian" and s.coordinates is not None
        for A, B in zip(s.matrices(d.phase(1, 3)), d.matrices(d.phase(1, 3))):
            np.testing.assert_allclose(A.toarray(), B.toarray(), rtol=0, atol=1e-9 * abs(B).max())
        np.testing.assert_array_equal(s.contact_directions_next()[0], d.contact_directions_next()[0])


def test_a_dof_map_groups_the_nodes_and_places_them():
    """With a DOF map the boundaries are named one DOF at a time, the nodes come from it and ``coordinates`` is
    ``{node id: position}``: the same sector as with tuples."""
    from microslip.fe import DofMap

    ids = [100, 101, 102, 103, 200]  # node 200 the right boundary
    names = DofMap(np.repeat(ids, 3), ["x", "y", "z"] * 5)
    M, C, K = bars(5, position, [(0, range(5))])
    d = CyclicStructure(M, C, K, sectors=N, left=["100:x", "100:y", "100:z"], right=["200:1", "200:2", "200:3"],
                        dof_map=names, frame="cartesian", axis=AXIS, point=CENTRE,
                        coordinates={100: position(0, 0), 200: position(0, 4), 7: [0.0, 0.0, 0.0]})
    tuples = cartesian_sector()
    np.testing.assert_array_equal(d.boundary_rotation.toarray(), tuples.boundary_rotation.toarray())
    d.add_contact(MODEL, tangential={"102:x": 1.0, d.next("101:x"): -1.0}, approach=1e-6)  # node 101 from the map
    tuples.add_contact(MODEL, tangential={6: 1.0, tuples.next(3): -1.0}, approach=1e-6)
    np.testing.assert_array_equal(d.contact_directions_next()[0][:, -1], tuples.contact_directions_next()[0][:, -1])
    with pytest.raises(ValueError, match="coordinates has no position for node 200 of the right boundary"):
        CyclicStructure(M, C, K, sectors=N, left=["100:x", "100:y", "100:z"], right=["200:x", "200:y", "200:z"],
                        dof_map=names, frame="cartesian", axis=AXIS, point=CENTRE, coordinates={100: position(0, 0)})
    with pytest.raises(ValueError, match="right: the DOFs pair 100:x with 200:y, 100:y with 200:x"):
        CyclicStructure(M, C, K, sectors=N, left=["100:x", "100:y", "100:z"], right=["200:y", "200:x", "200:z"],
                        dof_map=names, frame="cartesian", axis=AXIS, point=CENTRE,
                        coordinates={100: position(0, 0), 200: position(0, 4)})
