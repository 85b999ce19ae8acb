"""Continuous reference contacts, the exact answers a tuned array is measured against."""

from .cylinder import Cylinder
from .sphere import Sphere

__all__ = ["Cylinder", "Sphere"]
