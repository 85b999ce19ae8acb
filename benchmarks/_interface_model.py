"""An interface-dominated test model: two plates of springs and masses lapped over their whole face.

A jointed structure reduced to relative interface coordinates looks like this: most of its DOFs are the
relative displacements of node pairs across the interface, each pair a contact on its plane. Two layers
of ``nx x ny`` nodes (3 DOFs each, a lumped mass per node, springs of unequal stiffness along each axis to the
in-layer neighbours), the lower clamped along its first column, the upper along its last (a lap joint). In the
coordinates ``r = u_upper - u_lower`` (the interface) and ``m = (u_upper + u_lower) / 2`` the mean motion
is reduced by Craig-Bampton to ``modes`` fixed-interface modes: ``3 nx ny + modes`` DOFs, dense and
symmetric positive definite, the first ``3 nx ny`` of them relative displacements. Every pair is a
plane contact (two tangential relative DOFs, the normal one) pressed by a preload; damping ``C = beta K``.

Used by benchmarks/bench_interface_solver.py; tests build smaller ones of their own.
"""

from __future__ import annotations

import numpy as np
import scipy.linalg as sla

#: layer springs (N/m), node mass (kg), contact stiffnesses per pair (N/m), preload per pair (N), friction
SPRING, MASS, KT, KN, PRELOAD, MU = 2e6, 0.01, 4e6, 2e7, 50.0, 0.5
#: the springs' stiffness along x, y, z relative to SPRING (unequal: no repeated natural frequencies)
AXES = (1.0, 1.7, 3.0)


def lattice(nx: int, ny: int) -> tuple[np.ndarray, np.ndarray]:
    """``(K, M)`` of one layer, free: springs between in-layer neighbours along each axis, ``(3 nx ny,)`` square."""
    n = nx * ny
    L = np.zeros((n, n))
    node = np.arange(n).reshape(nx, ny)
    for a, b in [(node[:-1].ravel(), node[1:].ravel()), (node[:, :-1].ravel(), node[:, 1:].ravel())]:
        np.add.at(L, (a, a), 1.0)
        np.add.at(L, (b, b), 1.0)
        np.add.at(L, (a, b), -1.0)
        np.add.at(L, (b, a), -1.0)
    return SPRING * np.kron(L, np.diag(AXES)), MASS * np.eye(3 * n)


def interface_model(nx: int = 21, ny: int = 7, modes: int = 40, *, elements: int = 4, beta: float = 2e-6):
    """``(structure, pairs)``: the lap joint of the module docstring with every pair a plane contact.

    Parameters
    ----------
    nx, ny : int
        Nodes of each layer along and across (``nx ny`` contact pairs, ``3 nx ny`` interface DOFs).
    modes : int
        Fixed-interface modes of the mean motion kept.
    elements : int
        Elements of each contact's microslip law (staggered gaps).
    beta : float
        Stiffness-proportional damping (s).

    Returns
    -------
    structure : microslip.frequency.Structure
        ``3 nx ny + modes`` DOFs, dense.
    pairs : int
        The number of contacts.
    """
    from microslip import MicroslipModel
    from microslip.frequency import Structure

    K1, M1 = lattice(nx, ny)
    n = K1.shape[0]
    clamp = 1e3 * SPRING
    lower, upper = K1.copy(), K1.copy()
    first = np.arange(ny)  # nodes of the first column, then of the last
    last = (nx - 1) * ny + np.arange(ny)
    for nodes, Kl in ((first, lower), (last, upper)):
        dofs = (3 * nodes[:, None] + np.arange(3)).ravel()
        Kl[dofs, dofs] += clamp
    Z = np.zeros((n, n))
    K = np.block([[upper, Z], [Z, lower]])
    M = np.block([[M1, Z], [Z, M1]])
    eye = np.eye(n)
    T = np.block([[0.5 * eye, eye], [-0.5 * eye, eye]])  # [u_upper; u_lower] = T [r; m]
    K, M = T.T @ K @ T, T.T @ M @ T
    r, m = slice(0, n), slice(n, 2 * n)
    psi = -np.linalg.solve(K[m, m], K[m, r])
    lam, phi = sla.eigh(K[m, m], M[m, m], subset_by_index=[0, modes - 1])
    V = np.zeros((2 * n, n + modes))
    V[r, :n] = eye
    V[m, :n] = psi
    V[m, n:] = phi
    Kr, Mr = V.T @ K @ V, V.T @ M @ V
    Kr, Mr = 0.5 * (Kr + Kr.T), 0.5 * (Mr + Mr.T)
    s = Structure(Mr, beta * Kr, Kr)
    gaps = np.linspace(0.0, 2e-7, elements)
    law = MicroslipModel(kt=np.full(elements, KT / elements), kn=np.full(elements, KN / elements), gaps=gaps, mu=MU)
    pairs = nx * ny
    for p in range(pairs):
        s.add_contact(law, tangential=[{3 * p: 1.0}, {3 * p + 1: 1.0}], normal={3 * p + 2: 1.0}, preload=PRELOAD)
    return s, pairs
