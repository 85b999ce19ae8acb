"""Contact patches from a mesh: tributary areas, normals, tangents, pairing, mesh files, contacts on a structure."""

import numpy as np
import pytest

from microslip import MicroslipModel
from microslip.fe import (ContactPatch, DofMap, PressureLaw, add_patch, contact_patch, patch_from_mesh,
                          patch_from_tables)
from microslip.frequency import Structure, static_solution

meshio = pytest.importorskip("meshio")

OFFSET = 1000  # node ids of side b: side a's + OFFSET


def flat_mesh(nx=5, ny=4, lx=0.03, ly=0.02, gap=0.0, seed=0):
    """An irregular flat patch of quads and triangles on [0, lx] x [0, ly] (z = 0), and its copy at z = gap.

    Returns points {id: xyz}, side a's faces (normals +z, towards b) and side b's (reversed).
    """
    rng = np.random.default_rng(seed)
    x, y = np.linspace(0, lx, nx + 1), np.linspace(0, ly, ny + 1)
    points = {}
    for i in range(nx + 1):
        for j in range(ny + 1):
            p = np.array([x[i], y[j], 0.0])
            if 0 < i < nx and 0 < j < ny:  # interior nodes moved: faces of unequal areas
                p[:2] += rng.uniform(-0.2, 0.2, 2) * [lx / nx, ly / ny]
            points[i * (ny + 1) + j] = p
    node = lambda i, j: i * (ny + 1) + j  # noqa: E731
    faces = []
    for i in range(nx):
        for j in range(ny):
            q = (node(i, j), node(i + 1, j), node(i + 1, j + 1), node(i, j + 1))
            if (i + j) % 3 == 0:  # some quads split into two triangles
                faces += [(q[0], q[1], q[2]), (q[0], q[2], q[3])]
            else:
                faces.append(q)
    points.update({k + OFFSET: p + [0.0, 0.0, gap] for k, p in list(points.items())})
    faces_b = [tuple(v + OFFSET for v in f[::-1]) for f in faces]
    return points, faces, faces_b


def test_tributary_areas_of_a_flat_mesh_sum_to_its_area():
    points, fa, fb = flat_mesh()
    patch = contact_patch(points, fa, fb, tolerance=1e-9)
    assert isinstance(patch, ContactPatch) and len(patch) == 30
    assert abs(patch.total_area - 0.03 * 0.02) <= 1e-12 * 0.03 * 0.02
    np.testing.assert_array_equal(patch.nodes_b, patch.nodes_a + OFFSET)
    np.testing.assert_allclose(patch.normal, np.tile([0.0, 0.0, 1.0], (30, 1)), atol=1e-15)
    # the frame is right-handed and orthonormal; tangent1 is the x axis (least aligned with the normal)
    np.testing.assert_allclose(patch.tangent1, np.tile([1.0, 0.0, 0.0], (30, 1)), atol=1e-15)
    np.testing.assert_allclose(np.cross(patch.tangent1, patch.tangent2), patch.normal, atol=1e-15)


def test_an_array_of_points_and_a_reversed_side_a_give_normals_pointing_the_other_way():
    points, fa, fb = flat_mesh(nx=2, ny=2)
    ids = sorted(points)
    array = np.array([points[k] for k in ids])
    row = {k: i for i, k in enumerate(ids)}
    renumber = lambda faces: [tuple(row[v] for v in f) for f in faces]  # noqa: E731
    patch = contact_patch(array, renumber([f[::-1] for f in fa]), renumber(fb), tolerance=1e-9)
    np.testing.assert_allclose(patch.normal[:, 2], -1.0, atol=1e-15)
    assert abs(patch.total_area - 6e-4) <= 1e-12 * 6e-4
    np.testing.assert_allclose(np.cross(patch.tangent1, patch.tangent2), patch.normal, atol=1e-15)


def cylinder(radius=0.05, height=0.01, n_theta=24, n_z=3):
    """A whole ring of quads on a cylinder (axis z): side a (normals outward) and side b on the same nodes' copy."""
    theta = 2 * np.pi * np.arange(n_theta) / n_theta
    z = np.linspace(0, height, n_z + 1)
    points = {}
    for i in range(n_theta):
        for j in range(n_z + 1):
            points[i * (n_z + 1) + j] = np.array([radius * np.cos(theta[i]), radius * np.sin(theta[i]), z[j]])
    node = lambda i, j: (i % n_theta) * (n_z + 1) + j  # noqa: E731
    fa = [(node(i, j), node(i + 1, j), node(i + 1, j + 1), node(i, j + 1)) for i in range(n_theta) for j in range(n_z)]
    points.update({k + OFFSET: p.copy() for k, p in list(points.items())})
    fb = [tuple(v + OFFSET for v in f[::-1]) for f in fa]
    return points, fa, fb


def test_the_normals_of_a_cylindrical_patch_are_radial():
    points, fa, fb = cylinder()
    patch = contact_patch(points, fa, fb, tolerance=0.0)
    xyz = np.array([points[int(k)] for k in patch.nodes_a])
    radial = np.column_stack([xyz[:, 0], xyz[:, 1], np.zeros(len(xyz))])
    radial /= np.linalg.norm(radial, axis=1)[:, None]
    assert np.max(np.abs(patch.normal - radial)) <= 1e-12
    assert np.max(np.abs(np.linalg.norm(patch.tangent1, axis=1) - 1)) <= 1e-15
    assert np.max(np.abs(np.sum(patch.tangent1 * patch.normal, axis=1))) <= 1e-15
    # the faces are flat quads (chords of the circle): their areas sum to the polygon's lateral area
    chord = 2 * 0.05 * np.sin(np.pi / 24)
    assert abs(patch.total_area - 24 * chord * 0.01) <= 1e-12 * patch.total_area


def test_a_node_beyond_the_tolerance_is_refused_by_name_with_its_distance():
    points, fa, fb = flat_mesh(nx=2, ny=2, gap=1e-7)
    points[OFFSET + 4] = points[OFFSET + 4] + [3e-6, 0.0, 0.0]
    with pytest.raises(ValueError, match=r"node 4 of surface_a .*node 1004.* 3\.00\d*e-06 m away"):
        contact_patch(points, fa, fb, tolerance=1e-6)
    # side b with a node more than side a: named
    extra = points | {OFFSET + 99: np.array([1.0, 1.0, 0.0])}
    fb2 = fb + [(OFFSET + 0, OFFSET + 99, OFFSET + 1)]
    with pytest.raises(ValueError, match=r"node 1099 of surface_b has no partner"):
        contact_patch(extra, fa, fb2, tolerance=1.0)


def test_two_nodes_matching_one_node_are_refused_by_name():
    points, fa, fb = flat_mesh(nx=2, ny=2)
    points[OFFSET + 4] = points[1].copy() + [0.0, 0.0, 1e-9]  # node 1004 moved onto node 1: 1 and 4 (or 1 and 1004's...) clash
    with pytest.raises(ValueError, match=r"both match node 100\d of surface_b"):
        contact_patch(points, fa, fb, tolerance=0.02)


def test_bad_faces_are_refused_by_name():
    points, fa, fb = flat_mesh(nx=1, ny=1)
    with pytest.raises(ValueError, match=r"surface_a\[0\] must be a triangle or a quad"):
        contact_patch(points, [(0, 1)], fb, tolerance=1e-9)
    with pytest.raises(ValueError, match=r"surface_b names nodes .*\[5000\]"):
        contact_patch(points, fa, [(5000, 1001, 1002)], tolerance=1e-9)
    collinear = {0: (0, 0, 0), 1: (1, 0, 0), 2: (2, 0, 0), 10: (0, 0, 0), 11: (1, 0, 0), 12: (2, 0, 0)}
    with pytest.raises(ValueError, match=r"surface_a\[0\] .*zero or non-finite area"):
        contact_patch(collinear, [(0, 1, 2)], [(10, 11, 12)], tolerance=1e-9)
    with pytest.raises(ValueError, match="tolerance must be non-negative"):
        contact_patch(points, fa, fb, tolerance=-1.0)


# -- mesh files ------------------------------------------------------------------------------------------

#: an Abaqus input as documented (*NODE, *ELEMENT with ELSET=, *NSET, *ELSET): two 2 x 1 shell patches
#: 1 µm apart; S4 elements read by meshio as quads
INP = """*HEADING
two shell patches
*NODE
1, 0.0, 0.0, 0.0
2, 0.01, 0.0, 0.0
3, 0.02, 0.0, 0.0
4, 0.0, 0.01, 0.0
5, 0.01, 0.01, 0.0
6, 0.02, 0.01, 0.0
11, 0.0, 0.0, 1e-6
12, 0.01, 0.0, 1e-6
13, 0.02, 0.0, 1e-6
14, 0.0, 0.01, 1e-6
15, 0.01, 0.01, 1e-6
16, 0.02, 0.01, 1e-6
*ELEMENT, TYPE=S4, ELSET=LOWER
1, 1, 2, 5, 4
2, 2, 3, 6, 5
*ELEMENT, TYPE=S4, ELSET=UPPER
3, 11, 14, 15, 12
4, 12, 15, 16, 13
*NSET, NSET=TOP
11, 12, 13, 14, 15, 16
"""


def test_an_abaqus_input_with_element_and_node_sets(tmp_path):
    path = tmp_path / "patch.inp"
    path.write_text(INP)
    for set_b in ("UPPER", "TOP"):  # a cell set or a node set
        patch = patch_from_mesh(path, "LOWER", set_b, tolerance=2e-6)
        assert len(patch) == 6 and abs(patch.total_area - 2e-4) <= 1e-12 * 2e-4
        np.testing.assert_array_equal(patch.nodes_b, patch.nodes_a + 6)  # meshio's 0-based point indices
        np.testing.assert_allclose(patch.normal[:, 2], 1.0)
        np.testing.assert_allclose(patch.distance, 1e-6)
    with pytest.raises(ValueError, match=r"set_b = 'UPPR' .*did you mean 'UPPER'.*'LOWER', 'TOP', 'UPPER'"):
        patch_from_mesh(path, "LOWER", "UPPR", tolerance=2e-6)
    with pytest.raises(ValueError, match=r"node 0 of surface_a"):
        patch_from_mesh(path, "LOWER", "UPPER", tolerance=1e-7)


def test_a_gmsh_file_written_by_meshio_with_physical_groups(tmp_path):
    points, fa, fb = flat_mesh(nx=3, ny=2, gap=0.0)
    ids = sorted(points)
    row = {k: i for i, k in enumerate(ids)}
    tri = [[row[v] for v in f] for f in fa + fb if len(f) == 3]
    quad = [[row[v] for v in f] for f in fa + fb if len(f) == 4]
    side = lambda fs, n: [1 if f[0] < OFFSET else 2 for f in fs if len(f) == n]  # noqa: E731
    mesh = meshio.Mesh(np.array([points[k] for k in ids]), [("triangle", np.array(tri)), ("quad", np.array(quad))],
                       cell_data={"gmsh:physical": [np.array(side(fa + fb, 3)), np.array(side(fa + fb, 4))],
                                  "gmsh:geometrical": [np.array(side(fa + fb, 3)), np.array(side(fa + fb, 4))]},
                       field_data={"bottom": np.array([1, 2]), "top": np.array([2, 2])})
    path = tmp_path / "patch.msh"
    meshio.write(path, mesh, file_format="gmsh22", binary=False)
    patch = patch_from_mesh(path, "bottom", "top", tolerance=1e-9)
    assert abs(patch.total_area - 6e-4) <= 1e-12 * 6e-4
    np.testing.assert_allclose(patch.normal[:, 2], 1.0)


def test_a_damaged_or_missing_file_is_refused_with_its_name(tmp_path):
    path = tmp_path / "broken.msh"
    path.write_text("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n3\n1 0 0\n")
    with pytest.raises(ValueError, match="broken.msh"):
        patch_from_mesh(path, "a", "b", tolerance=1e-6)
    with pytest.raises(ValueError, match="nothing.inp.*no such file"):
        patch_from_mesh(tmp_path / "nothing.inp", "a", "b", tolerance=1e-6)


# -- contacts on a structure -----------------------------------------------------------------------------


def test_a_uniform_overclosure_on_a_flat_patch_carries_the_pressure_times_the_area():
    """Each node on a spring proportional to its area (so the overclosure stays uniform): the static normal
    forces of the contacts sum to kn_per_area x overclosure x area, and balance the springs."""
    points, fa, fb = flat_mesh(gap=0.0)
    patch = contact_patch(points, fa, fb, tolerance=1e-9)
    area = dict(zip(patch.nodes_a.tolist(), patch.area)) | dict(zip(patch.nodes_b.tolist(), patch.area))
    nodes = sorted(area)
    dof_map = DofMap([n for n in nodes for _ in "xyz"], [c for _ in nodes for c in "xyz"])
    ks, kn, delta = 1e12, 2e12, 1e-6  # Pa/m, Pa/m, m
    K = np.diag([ks * area[n] for n in nodes for _ in "xyz"])
    s = Structure(np.eye(len(dof_map)), np.zeros_like(K), K, dof_map=dof_map)
    contacts = add_patch(s, patch, PressureLaw(kn_per_area=kn, kt_per_area=1e11, mu=0.5, gap=-delta))
    assert len(contacts) == len(patch) and contacts[0].name == "patch0"
    q0 = static_solution(s, tolerance=1e-13)
    n = np.array([c.normal @ q0 + c.approach for c in contacts])
    N = np.array([c.model.normal_force(x) for c, x in zip(contacts, n)])
    overclosure = delta * ks / (ks + 2 * kn)  # each side moves back by kn (delta - 2 u) / ks
    np.testing.assert_allclose(n + delta, overclosure, rtol=1e-10)
    assert abs(N.sum() - kn * overclosure * 0.03 * 0.02) <= 1e-10 * N.sum()
    # the springs carry it: side a pushed along -z, side b along +z
    z = [dof_map.index(f"{k}:z") for k in patch.nodes_a]
    assert abs(-(K @ q0)[z].sum() - N.sum()) <= 1e-9 * N.sum()


def test_a_microslip_model_per_unit_area_is_scaled_by_each_pair_s_area_and_the_directions_are_relative():
    points, fa, fb = flat_mesh(nx=2, ny=1)
    patch = contact_patch(points, fa, fb, tolerance=1e-9)
    nodes = sorted(set(patch.nodes_a.tolist()) | set(patch.nodes_b.tolist()))
    dofs = {n: (3 * i, 3 * i + 1, 3 * i + 2) for i, n in enumerate(nodes)}
    ndof = 3 * len(nodes)
    s = Structure(np.eye(ndof), np.zeros((ndof, ndof)), np.eye(ndof))
    law = MicroslipModel(kt=[1e10, 2e10], kn=[3e10, 3e10], gaps=[0.0, 1e-7], mu=0.3)
    contacts = add_patch(s, patch, law, dofs=dofs, name="p")
    for p, c in enumerate(contacts):
        np.testing.assert_allclose(c.model.kt, law.kt * patch.area[p], rtol=1e-15)
        np.testing.assert_array_equal(c.model.gaps, law.gaps)
        a, b = dofs[int(patch.nodes_a[p])], dofs[int(patch.nodes_b[p])]
        assert c.normal[a[2]] == 1.0 and c.normal[b[2]] == -1.0  # n grows as a moves towards b (+z)
        assert c.tangential[b[0]] == 1.0 and c.tangential[a[0]] == -1.0  # t1 = x . (u_b - u_a)
        assert c.tangential2[b[1]] == 1.0 and c.tangential2[a[1]] == -1.0
    with pytest.raises(ValueError, match="dofs has no entry for node 0"):
        add_patch(s, patch, law, dofs={}, name="q")
    with pytest.raises(ValueError, match="dofs must map each node id"):
        add_patch(s, patch, law)
    with pytest.raises(TypeError, match="law must be a MicroslipModel or a PressureLaw"):
        add_patch(s, patch, 1.0, dofs=dofs, name="r")


def test_pressure_law_is_checked_by_name():
    with pytest.raises(ValueError, match="kn_per_area must be positive"):
        PressureLaw(kn_per_area=0.0, kt_per_area=1.0, mu=0.1)
    with pytest.raises(ValueError, match="area = 1e.300 m²"):
        PressureLaw(kn_per_area=1e12, kt_per_area=1e12, mu=0.1).model(1e300)
    m = PressureLaw(kn_per_area=2e12, kt_per_area=1e12, mu=0.1, gap=1e-7).model(1e-4)
    assert m == MicroslipModel(kt=[1e8], kn=[2e8], gaps=[1e-7], mu=0.1)


# -- a reduced model's interface tables ------------------------------------------------------------------


def test_tables_of_relative_coordinates_give_the_same_contacts_as_the_nodes():
    """A pair's relative displacement r = u_b - u_a as the reduced model's DOFs: the contacts' directions are
    those on the nodes' DOFs mapped through r."""
    points, fa, fb = flat_mesh(nx=2, ny=1)
    patch = contact_patch(points, fa, fb, tolerance=1e-9)
    tables = patch_from_tables(patch.nodes_a, patch.area, patch.normal)
    np.testing.assert_array_equal(tables.tangent1, patch.tangent1)
    np.testing.assert_array_equal(tables.nodes_b, tables.nodes_a)
    P = len(patch)
    s = Structure(np.eye(3 * P), np.zeros((3 * P, 3 * P)), np.eye(3 * P))
    dofs = {int(n): (3 * p, 3 * p + 1, 3 * p + 2) for p, n in enumerate(patch.nodes_a)}
    law = PressureLaw(kn_per_area=1e12, kt_per_area=1e11, mu=0.3)
    contacts = add_patch(s, tables, law, dofs=dofs, relative=True)
    for p, c in enumerate(contacts):
        r = dofs[int(patch.nodes_a[p])]
        np.testing.assert_allclose(c.normal[list(r)], -patch.normal[p], atol=1e-15)  # n = -normal . r
        np.testing.assert_allclose(c.tangential[list(r)], patch.tangent1[p], atol=1e-15)
        np.testing.assert_allclose(c.tangential2[list(r)], patch.tangent2[p], atol=1e-15)
        assert c.model.kn[0] == pytest.approx(1e12 * patch.area[p], rel=1e-15)


def test_tables_are_checked_by_name():
    n = np.array([[0.0, 0.0, 1.0], [0.0, 0.0, 2.0]])
    with pytest.raises(ValueError, match=r"normal\[1\] must be a unit vector"):
        patch_from_tables([1, 2], [1e-4, 1e-4], n)
    with pytest.raises(ValueError, match=r"tangent1\[0\] must be perpendicular to normal\[0\]"):
        patch_from_tables([1], [1e-4], [[0.0, 0.0, 1.0]], tangent1=[[0.0, 0.6, 0.8]])
    with pytest.raises(ValueError, match="area must have one value per pair"):
        patch_from_tables([1, 2], [1e-4], [[0.0, 0.0, 1.0]] * 2)
    p = patch_from_tables([1], [1e-4], [[0.0, 0.0, 1.0]], tangent1=[[0.0, 1.0, 0.0]], nodes_b=[7])
    np.testing.assert_allclose(p.tangent2, [[-1.0, 0.0, 0.0]])
    assert p.nodes_b.tolist() == [7]
