"""Side by side with a peer: tmdsimpy's elastic dry friction element (MIT licence; not on PyPI).

tmdsimpy (Porter et al., https://github.com/tmd-lab/tmdsimpy) models a Jenkins slider with a normal
spring and lift-off, ``ElasticDryFriction2D``: one tangential and one normal local displacement,
normal force ``max(kn u_n, 0)`` (its documented ``meso_gap`` left at 0), tangential force clipped to
``+-mu N``. Its documented ``local_force_history`` marches a sampled period twice, the slider
starting at ``u0`` with zero force, and returns the forces of the second pass.

Run it when a local copy is given (its dependency jax installed)::

    TMDSIMPY_PATH=/path/to/tmdsimpy python -m pytest tests/model/test_tmdsimpy.py

Our array with ``J`` elements, all gaps 0, is ``J`` such elements side by side; driven on the
contact plane along a straight line at an angle, it must give tmdsimpy's forces along that line (the
element's two local DOFs being that line and the normal) to 1e-10 of ``mu N``: both march the same
return mapping (tmdsimpy adds each increment to the previous force, we keep the slider: the same
numbers up to rounding over the 256 samples).
"""

from __future__ import annotations

import numpy as np
import pytest

from microslip import MicroslipModel, State

from _tmdsimpy import import_tmdsimpy


@pytest.fixture(scope="module")
def dry_friction():
    module = import_tmdsimpy(["tmdsimpy.jax.nlforces.elastic_dry_fric_2d"], "tmdsimpy's ElasticDryFriction2D")
    return module["elastic_dry_fric_2d"].ElasticDryFriction2D


def tmdsimpy_forces(element_class, kt, kn, mu, u_t, u_n, u0):
    """Tangential and normal force of each element (lists of arrays, N) from tmdsimpy's documented
    ``local_force_history`` (the second pass over the sampled period)."""
    unlt = np.column_stack([u_t, u_n])
    zeros = np.zeros_like(unlt)
    tangential, normal = [], []
    for k_t, k_n in zip(kt, kn):
        # u0 as the documented array (entries 0::2: the sliders); a float reaches an indexing error in
        # local_force_history of the version tried (it indexes the scalar u0 * ones_like(unlth0[0]))
        element = element_class(np.eye(2), np.eye(2), k_t, k_n, mu, u0=np.array([u0, 0.0]))
        ft = np.asarray(element.local_force_history(unlt, zeros, np.array([0, 1]), np.ones((u_t.size, 3)),
                                                    np.zeros(2))[0])
        tangential.append(ft[:, 0])
        normal.append(ft[:, 1])
    return np.sum(tangential, axis=0), np.sum(normal, axis=0)


@pytest.mark.parametrize("angle", [0.0, 30.0, 115.0])
@pytest.mark.parametrize("u0", [0.0, 0.4e-6])
def test_the_array_on_a_line_of_the_plane_gives_tmdsimpys_forces(dry_friction, angle, u0):
    kt = np.array([2e6, 5e6, 1e7])
    kn = np.array([4e6, 1e7, 3e7])
    mu = 0.4
    samples = 256
    tau = 2 * np.pi * np.arange(samples) / samples
    u_t = 1.5e-6 * np.cos(tau) + 0.4e-6 * np.sin(2 * tau + 0.3)
    u_n = 0.3e-6 + 0.6e-6 * np.cos(tau + 1.1)  # the contact opens over part of the period
    T_peer, N_peer = tmdsimpy_forces(dry_friction, kt, kn, mu, u_t, u_n, u0)

    model = MicroslipModel(kt=kt, kn=kn, gaps=np.zeros(3), mu=mu)
    e = np.array([np.cos(np.radians(angle)), np.sin(np.radians(angle))])
    t = np.tile(u_t, 2)[:, None] * e  # two passes over the period, as tmdsimpy marches
    r = model.simulate(t, np.tile(u_n, 2), state=State(np.tile(u0 * e, (3, 1))))
    assert (r.condition[samples:] == 0).any() and (r.condition[samples:] == 2).any()  # opens and slips
    scale = mu * float(N_peer.max())
    np.testing.assert_allclose(r.T[samples:] @ e, T_peer, rtol=0, atol=1e-10 * scale)
    np.testing.assert_allclose(r.T[samples:] @ [-e[1], e[0]], 0.0, rtol=0, atol=1e-10 * scale)
    np.testing.assert_allclose(r.N[samples:], N_peer, rtol=0, atol=1e-10 * float(N_peer.max()))
