"""Continuous reference contacts, the exact answers a tuned array is measured against."""

from .sphere import Sphere

__all__ = ["Sphere"]
