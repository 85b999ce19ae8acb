"""Hypothesis strategies shared by the model, kernel and property tests.

Magnitudes follow the paper's benchmark (stiffnesses 1e5..1e8 N/m, gaps and
displacements of a few µm) so that elements open and close again along a
path: the normal approach ``n`` is drawn on both sides of every gap.
"""

from __future__ import annotations

import numpy as np
from hypothesis import strategies as st

from microslip import MicroslipModel

UM = 1e-6


def _log_uniform(lo, hi):
    return st.floats(np.log10(lo), np.log10(hi)).map(lambda e: float(10.0 ** e))


# Values on a coarse grid (multiples of 0.25 µm) make exact ties likely:
# an element exactly at its friction limit, n exactly at a gap.
def _length(lo, hi):
    grid = st.integers(int(lo / (0.25 * UM)), int(hi / (0.25 * UM))).map(lambda k: k * 0.25 * UM)
    return st.one_of(st.floats(lo, hi, allow_nan=False, allow_infinity=False), grid)


@st.composite
def models(draw, max_elements=6):
    """A random MicroslipModel with 1..max_elements elements."""
    J = draw(st.integers(1, max_elements))
    kt = [draw(_log_uniform(1e5, 1e8)) for _ in range(J)]
    kn = [draw(_log_uniform(1e5, 1e8)) for _ in range(J)]
    gaps = [draw(_length(0.0, 2 * UM)) for _ in range(J)]
    mu = draw(st.floats(0.05, 1.0))
    return MicroslipModel(kt=kt, kn=kn, gaps=gaps, mu=mu)


def lengths_array(draw, size, lo, hi):
    return np.array([draw(_length(lo, hi)) for _ in range(size)])


@st.composite
def paths(draw, min_size=1, max_size=40):
    """``(t, n)`` arrays (m) of equal length; ``n`` crosses the gaps of :func:`models`."""
    size = draw(st.integers(min_size, max_size))
    t = lengths_array(draw, size, -3 * UM, 3 * UM)
    n = lengths_array(draw, size, -0.5 * UM, 3 * UM)
    return t, n


@st.composite
def plane_paths(draw, min_size=1, max_size=40):
    """``(t, n)`` with ``t`` of shape (steps, 2) on the contact plane (m); ``n`` crosses the gaps of :func:`models`."""
    size = draw(st.integers(min_size, max_size))
    t = lengths_array(draw, 2 * size, -3 * UM, 3 * UM).reshape(size, 2)
    n = lengths_array(draw, size, -0.5 * UM, 3 * UM)
    return t, n


def random_contact(rng, J: int) -> MicroslipModel:
    """A contact of ``J`` elements (kt 1e6..3e6, kn 1e7..3e7 N/m, gaps in 0..2 µm from 0, mu 0.4) from ``rng``."""
    kt = rng.uniform(1, 3, J) * 1e6
    kn = rng.uniform(1, 3, J) * 1e7
    gaps = np.sort(rng.uniform(0, 2e-6, J))
    gaps[0] = 0.0
    return MicroslipModel(kt, kn, gaps, mu=0.4)
