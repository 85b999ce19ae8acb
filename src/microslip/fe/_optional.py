"""Optional dependencies of :mod:`microslip.fe`, imported only where they are needed (private)."""

from __future__ import annotations

from ..common import _optional


def require(module: str, purpose: str):
    """Import ``module`` or raise an ImportError naming the package and ``pip install microslip[fe]``."""
    return _optional.require(module, purpose, "fe")
