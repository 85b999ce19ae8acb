"""The search of the tuning points and of the smallest number of elements meeting an accuracy target.

See :mod:`microslip.tuning.target` for the method.
"""

from __future__ import annotations

import numpy as np
from scipy import optimize

from ...common import _checks
from ...common._progress import Progress
from ...common.errors import TargetNotMet
from .points import stored_fractions
from .problem import SPACINGS, TargetProblem, TargetTuning, _load_range, ranged, target_fraction
from ..paper import TuningError, model_from_points, tuning_points


def _fractions(z):
    """Increasing fractions in (0, 1], last 1, from log-spacings ``z`` (length J-1; the last spacing is 1)."""
    w = np.exp(np.clip(np.append(z, 0.0), -30, 30))
    u = np.cumsum(w) / w.sum()
    u[-1] = 1.0
    return u


def _log_spacings(u):
    d = np.log(np.diff(np.concatenate([[0.0], u])))
    return d[:-1] - d[-1]


def _resample(u, J):
    """Fractions of another J resampled to J points (same shape of the spacing)."""
    x = np.arange(len(u) + 1) / len(u)
    return np.interp(np.arange(1, J + 1) / J, x, np.concatenate([[0.0], u]))


def _starts(J):
    """Candidate fractions: power and offset warps of even spacing (even displacement is p = 1, c = 0)."""
    j = np.arange(1, J + 1)
    for p in (0.7, 0.85, 1.0, 1.2):
        for c in (-0.5, 0.0, 0.3, 0.6):
            yield ((j - c) / (J - c)) ** p


METHODS = ("global", "local")

#: differential-evolution population per dimension of the global search
POPULATION = 8


def optimal_points(problem: TargetProblem, elements: int, *, start=None, method: str = "global",
                   budget: int | None = None, seed: int = 0, maxfev: int | None = None, restarts: int = 2,
                   progress: bool = False) -> TargetTuning:
    """Optimise the ``elements`` tuning points of ``problem`` (see the module docstring).

    The points are parametrised by the logarithms of their spacings (``J - 1``
    numbers; the points stay increasing and end at ``t_gs(N_hi)``). The
    objective is the minimax score :meth:`TargetProblem.score`. Three stages:
    the best of a few two-parameter spacing laws ``((j - c) / (J - c))**p``
    and of the given starts; with ``method='global'`` a differential
    evolution (fixed ``seed``, population seeded with that best start, about
    ``budget`` models); then ``restarts`` Nelder--Mead rounds on all the
    points. The whole search is deterministic.

    Parameters
    ----------
    problem : TargetProblem
    elements : int
        ``J >= 1``.
    start : array_like, shape (J,), or list of them, optional
        Fractions of ``t_gs(N_hi)`` to start from (increasing, last 1); the
        best of these and of a few warps of even spacing is the start.
    method : {'global', 'local'}, default 'global'
        ``'local'`` skips the differential evolution.
    budget : int, optional
        Models evaluated by the differential evolution (default ``600 J``;
        about 3 ms each on the default problem). Measured on the default
        problem at J = 10: 6000 give a score 1.16-1.3, 25000 give 1.16.
    seed : int, default 0
        Seed of the differential evolution.
    maxfev : int, optional
        Evaluations per Nelder--Mead round (default ``100 J``).
    restarts : int, default 2
        Nelder--Mead rounds (each restarts the simplex at the best point).
    progress : bool, default False
        Show progress (one line per stage) on standard error.

    Returns
    -------
    TargetTuning
        ``spacing='optimal'``; ``evaluations`` counts the models tried.
    """
    J = _checks.positive_int("elements", elements, minimum=1)
    if method not in METHODS:
        raise ValueError(f"method must be one of {', '.join(METHODS)}, got {method!r}")
    restarts = _checks.positive_int("restarts", restarts, minimum=0)
    maxfev = 100 * J if maxfev is None else _checks.positive_int("maxfev", maxfev)
    budget = 600 * J if budget is None else _checks.positive_int("budget", budget)
    seed = _checks.positive_int("seed", seed, minimum=0)
    count = 0

    def score(u):
        nonlocal count
        count += 1
        try:
            model, _ = problem.tune_fractions(u)
        except (TuningError, ValueError):
            return np.inf
        return problem.score(model)

    if J == 1:
        model, pts = problem.tune_fractions([1.0])
        return problem.result(model, pts, "optimal", 1)
    candidates = list(_starts(J))
    if start is None:
        given = []
    elif isinstance(start, (list, tuple)) and start and np.ndim(start[0]) == 1:
        given = list(start)  # several starts
    else:
        given = [start]
    for u0 in given:
        u0 = _checks.positive_array("start", u0, ndim=1)
        if u0.size != J:
            raise ValueError(f"start must have {J} fractions, got {u0.size}")
        candidates.append(u0 / u0[-1])
    bar = Progress(restarts + 1 + (method == "global"), enabled=progress)
    bar.step(f"J = {J}: {len(candidates)} starting spacings")
    scores = [score(u) for u in candidates]
    z, best = _log_spacings(candidates[int(np.argmin(scores))]), min(scores)
    if method == "global":
        z, best = _evolve(lambda zz: score(_fractions(zz)), z, best, budget, seed, bar, J)
    for k in range(restarts):
        bar.step(f"J = {J}: Nelder-Mead round {k + 1} of {restarts} (up to {maxfev} models), score {best:.4g}")
        res = optimize.minimize(lambda zz: score(_fractions(zz)), z, method="Nelder-Mead",
                                options={"maxfev": maxfev, "xatol": 1e-5, "fatol": 1e-6, "adaptive": True})
        if res.fun <= best:
            z, best = res.x, float(res.fun)
    model, pts = problem.tune_fractions(_fractions(z))
    bar.done(f"J = {J}: {count} models evaluated, score {best:.4g}")
    return problem.result(model, pts, "optimal", count)


def _evolve(objective, z0, f0, budget, seed, bar, J):
    """Differential evolution of the log-spacings around ``z0``; returns the better of it and ``(z0, f0)``."""
    dim = z0.size
    half = max(3.0, float(np.abs(z0).max()) + 0.5)  # spacings within a factor e**3 of the last, and z0 inside
    popsize = POPULATION
    generations = max(1, budget // (popsize * dim) - 1)
    bar.step(f"J = {J}: differential evolution, {generations} generations of {popsize * dim} models")
    best, generation = [f0], [0]

    def tracked(z):
        f = objective(z)
        best[0] = min(best[0], f)
        return f

    def report(xk, convergence=None):  # after each generation
        generation[0] += 1
        bar.note(f"generation {generation[0]} of {generations}, best score {best[0]:.4g}")

    res = optimize.differential_evolution(tracked, [(-half, half)] * dim, x0=z0, seed=seed, popsize=popsize,
                                          maxiter=generations, tol=0.0, polish=False, updating="immediate",
                                          callback=report)
    if res.fun < f0:
        return res.x, float(res.fun)
    return z0, f0


def tune_to_target(reference, load_range, *, elements: int, energy_target=0.02, force_target=0.02,
                   min_amplitude=0.5, problem: TargetProblem | None = None, **options) -> TargetTuning:
    """Tune the paper's array with ``elements`` points chosen to minimise the worst error over a load range.

    Parameters
    ----------
    reference : Sphere or similar
        The contact to imitate.
    load_range : (float, float)
        ``(N_lo, N_hi)`` (N); the model is tuned at ``N_hi``.
    elements : int
        Number of elements ``J``.
    energy_target, force_target : float, default 0.02
        Normalisation of the two errors in the objective, and the targets
        that ``meets`` reports: fractions in ``(0, 1]`` (0.02 means 2 %),
        or ``math.inf`` to leave one out.
    min_amplitude : float, default 0.5
        Smallest amplitude of the family (multiple of the gross-slip
        displacement at a path's lowest load).
    problem : TargetProblem, optional
        A prepared problem (reused to save the reference runs).
    **options
        Passed to :func:`optimal_points` (``start``, ``method``, ``budget``, ``seed``, ``maxfev``,
        ``restarts``).

    Returns
    -------
    TargetTuning
        The model, its points and its measured worst errors.

    Examples
    --------
    >>> from microslip import Sphere, tune_to_target
    >>> best = tune_to_target(Sphere.paper(), (7.5, 37.5), elements=6)   # doctest: +SKIP
    """
    J = _checks.positive_int("elements", elements, minimum=1)  # before the reference is built
    problem = problem or TargetProblem(reference, load_range, energy_target=energy_target,
                                       force_target=force_target, min_amplitude=min_amplitude)
    return optimal_points(problem, J, **options)


def smallest_elements(reference, load_range, *, energy_target=0.02, force_target=0.02, min_amplitude=0.5,
                      max_elements: int = 32, spacing: str = "optimal", start: int = 2,
                      problem: TargetProblem | None = None, fractions=None, progress: bool = False,
                      **options) -> TargetTuning:
    """The smallest number of elements whose tuned array meets the accuracy target.

    Tries ``J = start, start + 1, ... max_elements`` in turn.

    Parameters
    ----------
    reference, load_range, energy_target, force_target, min_amplitude
        As in :func:`tune_to_target`.
    max_elements : int, default 32
        Largest ``J`` tried.
    spacing : {'optimal', 'displacement', 'force'}
        How the points are chosen.
    start : int, default 2
        First ``J`` tried.
    problem : TargetProblem, optional
    fractions : dict of int -> array, optional
        Optimised points already known for this problem (e.g.
        :func:`stored_fractions`), as fractions of ``t_gs(N_hi)``: with
        ``spacing='optimal'`` a ``J`` found there is re-measured, not searched.
    progress : bool
        Show progress on standard error.

    Returns
    -------
    TargetTuning
        The first that meets the target.

    Raises
    ------
    TargetNotMet
        When no ``J`` up to ``max_elements`` does; its ``best`` attribute
        holds the best found (smallest score) and the message its errors.
    """
    if spacing not in SPACINGS:
        raise ValueError(f"spacing must be one of {', '.join(SPACINGS)}, got {spacing!r}")
    J0 = _checks.positive_int("start", start, minimum=1)
    Jmax = _checks.positive_int("max_elements", max_elements, minimum=J0)
    known = {int(k): np.asarray(v, dtype=float) for k, v in (fractions or {}).items()}
    problem = problem or TargetProblem(reference, load_range, energy_target=energy_target,
                                       force_target=force_target, min_amplitude=min_amplitude)
    bar = Progress(Jmax - J0 + 1, enabled=progress)
    best = None
    for J in range(J0, Jmax + 1):
        bar.step(f"J = {J} ({spacing} points{', stored' if spacing == 'optimal' and J in known else ''})")
        if spacing != "optimal":
            res = problem.tune_spacing(spacing, J)
        elif J in known:
            res = problem.result(*problem.tune_fractions(known[J]), "optimal")
        else:
            res = optimal_points(problem, J, **options)
        if res.meets:
            bar.done(f"J = {J} meets the target")
            return res
        key = problem.normalised(res.energy_error, res.force_difference)
        if best is None or key < best[0]:
            best = (key, res)
    res = best[1]
    raise TargetNotMet(
        f"no J up to max_elements = {Jmax} meets the target (|energy error| <= {100 * problem.energy_target:g} %, "
        f"force difference <= {100 * problem.force_target:g} %) with {spacing} points; the best found is "
        f"J = {res.elements}: energy {100 * res.energy_error:.3g} %, force {100 * res.force_difference:.3g} %",
        res)


def tune_over_range(reference, normal_load, load_range, *, elements=None, energy_target=None, force_target=None,
                    forces=None, displacements=None, progress: bool = False):
    """:func:`microslip.tune` with ``load_range=``: the points, or J and the points, chosen by measurement.

    See :func:`microslip.tune`. With ``elements`` the points are optimised
    (:func:`tune_to_target`); without, the smallest J meeting the targets is
    found (:func:`smallest_elements`). When the problem is the one the
    package's stored points solve (:func:`stored_fractions`) they are used
    instead of a search: milliseconds for a given J, seconds for the smallest
    J; a fresh search takes minutes.

    Returns
    -------
    MicroslipModel
    """
    if forces is not None or displacements is not None:
        raise ValueError("load_range= chooses the tuning points itself: give elements= or energy_target=/"
                         "force_target= with it, not forces= or displacements=")
    lo, hi = _load_range(load_range)
    N = _checks.positive_scalar("normal_load", normal_load)
    if not np.isclose(N, hi, rtol=1e-9, atol=0.0):
        raise ValueError(f"normal_load must be the top of load_range (the model is tuned there): got "
                         f"normal_load = {N:g} N with load_range ({lo:g}, {hi:g}) N")
    J = None if elements is None else _checks.positive_int("elements", elements, minimum=1)
    if J is None and energy_target is None and force_target is None:
        raise ValueError("load_range= needs elements= (optimise the points of J elements) or energy_target= / "
                         "force_target= (find the smallest J meeting them)")
    et = 0.02 if energy_target is None else target_fraction("energy_target", energy_target)
    ft = 0.02 if force_target is None else target_fraction("force_target", force_target)
    known = stored_fractions(reference, (lo, hi), energy_target=et, force_target=ft) or {}
    if J is not None and J in known:
        t = known[J] * float(reference.gross_slip_displacement(hi))
        model = model_from_points(reference, tuning_points(reference, hi, displacements=t))
        return ranged(model, (lo, hi), energy_target=et, force_target=ft, min_amplitude=0.5, dense_family=False)
    problem = TargetProblem(reference, (lo, hi), energy_target=et, force_target=ft)
    if J is not None:
        return optimal_points(problem, J, progress=progress).model
    return smallest_elements(reference, (lo, hi), problem=problem, fractions=known, progress=progress).model
