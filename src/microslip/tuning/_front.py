"""The public front door of tuning: :func:`tune`.

It chooses between the paper's equations on points given or evenly spaced
(:mod:`.paper`) and points chosen to meet an accuracy target over a load range
(:mod:`.target`, which itself calls the paper's equations). Living here, it
imports both without a circle.
"""

from __future__ import annotations

from ..model import MicroslipModel
from .paper import model_from_points, tuning_points
from .target import tune_over_range


def tune(reference, normal_load, *, forces=None, displacements=None, elements=None, load_range=None,
         energy_target=None, force_target=None, progress: bool = False) -> MicroslipModel:
    """Tune the paper's microslip array on a reference contact.

    Parameters
    ----------
    reference : ContactReference
        The contact to imitate: e.g. :class:`microslip.Sphere`, or a reference
        built from measured loops. It provides ``mu``, a backbone at constant
        load, its inverse, the gross-slip displacement and a normal curve.
    normal_load : float
        The load ``N_tot`` to tune at (N): the highest the model will meet.
    forces : array_like, shape (J,), optional
        Tangential forces of the tuning points (N), strictly increasing, the
        last equal to ``mu * normal_load``.
    displacements : array_like, shape (J,), optional
        Tangential displacements of the tuning points (m), strictly
        increasing, the last at the gross-slip displacement.
    elements : int, optional
        Number of elements ``J``; the points are then evenly spaced in force,
        ``T_j = j mu N_tot / J`` (the paper's choice), unless ``load_range``
        is given.
    load_range : (float, float), optional
        ``(N_lo, N_hi)`` (N), ``N_hi = normal_load``: choose the points by
        measurement instead, to minimise the worst error against the exact
        contact over the variable-normal-load cycles within that range
        (:mod:`microslip.tuning.target`). With ``elements`` the ``J`` points
        are optimised; without, the smallest ``J`` (up to 32) meeting
        ``energy_target`` and ``force_target`` is found, with its optimised
        points. The paper's sphere over 7.5-37.5 N (amplitudes from half the
        gross-slip displacement, equal targets) reuses the points stored with
        the package: milliseconds for a given J, seconds for the smallest J;
        any other problem is searched afresh, which takes minutes.
    energy_target, force_target : float, optional
        With ``load_range``: worst allowed ``|energy error|`` and force
        difference, fractions in ``(0, 1]`` (0.02 means 2 %; values above 1
        are refused; 0.02 each when not given).
    progress : bool, default False
        With ``load_range``: show the search's progress on standard error.

    Returns
    -------
    MicroslipModel
        ``J`` elements; element 1 is the contact centre (slips last, gap 0).

    Raises
    ------
    ValueError
        Points not strictly increasing, or the last not at gross slip.
    TuningError
        Points not concave (names the point), or eq. (9) without solution
        for some element (names it and the condition that fails).
    TargetNotMet
        With ``load_range`` and no ``elements``: no J up to 32 meets the
        targets (its ``best`` holds the best found).

    Examples
    --------
    >>> from microslip import Sphere, tune
    >>> model = tune(Sphere.paper(), 37.5, elements=4)
    >>> model.elements, round(float(model.slip_force(Sphere.paper().approach(37.5))), 6)
    (4, 15.0)
    >>> tune(Sphere.paper(), 37.5, elements=6, load_range=(7.5, 37.5)).elements
    6
    """
    if load_range is not None or energy_target is not None or force_target is not None:
        if load_range is None:
            raise ValueError("energy_target= and force_target= need load_range=(N_lo, N_hi) in N (the loads the "
                             "targets are measured over)")
        from .target import tune_over_range  # lazy: tuning_target imports this module

        return tune_over_range(reference, normal_load, load_range, elements=elements, energy_target=energy_target,
                               force_target=force_target, forces=forces, displacements=displacements,
                               progress=progress)
    pts = tuning_points(reference, normal_load, forces=forces, displacements=displacements,
                        elements=elements)
    return model_from_points(reference, pts)
