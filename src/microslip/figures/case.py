"""The paper's sphere benchmark, computed once and shared by the figure modules."""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property

from ..model import MicroslipModel
from ..reference import Sphere
from ..tuning import TuningPoints, model_from_points, tuning_points


@dataclass(frozen=True)
class PaperCase:
    """Sphere d = 10 mm, steel (E = 200 GPa, nu = 0.3), mu = 0.4, tuned at 37.5 N with 4 elements.

    Attributes
    ----------
    sphere : Sphere
        The continuous reference.
    normal_load : float
        Tuning load N_tot (N).
    elements : int
        Number of elements J.
    lower_loads : tuple of float
        Loads of Fig. 3b (N).
    raised_from, raised_by : float
        Load before the step of Fig. 4 and the step dN (N).
    raised_at : float
        Fraction of ``mu * raised_from`` at which the load is raised (point A).
    """

    sphere: Sphere = field(default_factory=Sphere.paper)
    normal_load: float = 37.5
    elements: int = 4
    lower_loads: tuple = (37.5, 30.0, 22.5, 15.0, 7.5)
    raised_from: float = 25.0
    raised_by: float = 12.5
    raised_at: float = 0.5

    @cached_property
    def points(self) -> TuningPoints:
        """The tuning points (evenly spaced in force, as in the paper)."""
        return tuning_points(self.sphere, self.normal_load, elements=self.elements)

    @cached_property
    def model(self) -> MicroslipModel:
        """The tuned array."""
        return model_from_points(self.sphere, self.points)

    @property
    def gross_slip(self) -> float:
        """Gross-slip displacement at the tuning load (m)."""
        return float(self.sphere.gross_slip_displacement(self.normal_load))
