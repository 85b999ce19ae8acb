"""Continuous reference contacts, the exact answers a tuned array is measured against."""

from .cylinder import Cylinder
from .mdr import LoadLimitError, MDRContact, MDRModel, mdr
from .profiles import AxisymmetricProfile, RoundedPunch, SphereProfile
from .sphere import Sphere

__all__ = ["AxisymmetricProfile", "Cylinder", "LoadLimitError", "MDRContact", "MDRModel", "RoundedPunch", "Sphere",
           "SphereProfile", "mdr"]
