"""One case of a study solved: the configuration built with the case's values, then a forced response or a mode.

:func:`solve_case` runs on a worker. It never raises: a failure comes back as
the case's error, so one case cannot stop the others. What it returns is small
(the summary row and the curves to store), not the solution objects.
"""

from __future__ import annotations

import time
import traceback
import warnings

import numpy as np

from .spec import Case, Study

#: curves stored per case, by solve: name -> (dims after "point", unit, description)
CURVES = {
    "frf": {"omega": ((), "rad/s", "excitation frequency"),
            "amplitude": (("dof",), "m", "response amplitude of each output DOF (of the largest blade for a "
                                         "mistuned disk)"),
            "dissipation": ((), "J", "energy dissipated per cycle by all contacts"),
            "stable": ((), "1", "1 where Hill's method finds the point stable, 0 where unstable, NaN if not computed")},
    "modes": {"modal_amplitude": ((), "kg^1/2 m", "modal amplitude"),
              "omega": ((), "rad/s", "natural frequency"),
              "damping_ratio": ((), "1", "modal damping ratio"),
              "amplitude": (("dof",), "m", "harmonic 1 amplitude of each output DOF")},
}


def solve_case(study: Study, case: Case) -> dict:
    """Solve one case; a dict with ``row`` (summary values), ``curves`` (arrays), ``error`` and ``time`` (s).

    BLAS runs on one thread (each worker is one process on one core).
    """
    import scipy.linalg  # noqa: F401  (loaded before the limit: a limit reaches only the BLAS already loaded)
    from threadpoolctl import threadpool_limits

    start = time.perf_counter()
    try:
        with threadpool_limits(1), warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            cfg = study.configuration(case)
            if study.solve == "modes":
                row, curves = _modes(study, cfg)
            elif case.mistuning_sample is not None:
                row, curves = _mistuned(study, cfg, case.mistuning_sample)
            else:
                row, curves = _frf(cfg)
        notes = sorted({f"{w.category.__name__}: {w.message}" for w in caught})
        return {"row": row, "curves": curves, "error": "", "warnings": "; ".join(notes),
                "time": time.perf_counter() - start}
    except Exception as exc:  # noqa: BLE001 - recorded as the case's error, the study goes on
        last = traceback.extract_tb(exc.__traceback__)[-1:]
        where = f" ({last[0].filename.rsplit('/', 1)[-1]}:{last[0].lineno})" if last else ""
        return {"row": {}, "curves": {}, "error": f"{type(exc).__name__}: {exc}{where}", "warnings": "",
                "time": time.perf_counter() - start}


def frf_arguments(cfg) -> dict:
    """The keyword arguments of :func:`~microslip.frequency.frequency_response` a configuration gives."""
    return dict(harmonics=cfg.harmonics, samples=cfg.samples, control=cfg.control, reduction=cfg.reduction,
                modes=cfg.modes, engine_order=cfg.engine_order)


def _frf(cfg):
    from ..config import apply_prestress
    from ..frequency import frequency_response

    state, _, force = apply_prestress(cfg, cfg.force)  # a [prestress]: the static step first
    result = frequency_response(cfg.structure, force, cfg.omega, **frf_arguments(cfg), prestress=state)
    amplitude = np.column_stack([result.amplitude(d, cfg.harmonic) for d in cfg.plot_dofs])
    return _frf_row(cfg, result, amplitude), _frf_curves(result, amplitude)


def _mistuned(study: Study, cfg, sample: int):
    """The assembled disk with the sample's blade stiffness scatter, excited by the travelling wave."""
    from ..frequency import frequency_response
    from ..frequency.analyses.blade_peaks import blade_amplitudes
    from ..frequency.structures.mistuning import blade_scatter, mistuned_disk
    from ..frequency.analyses.response import curve_peak

    m = study.mistuning
    if cfg.prestress is not None:
        raise ValueError("[prestress] is not available with [mistuning] (the mistuned disk is assembled whole)")
    sector = cfg.structure
    scatter = blade_scatter(sector.sectors, m.std, seed=m.seed, sample=sample)
    disk = mistuned_disk(sector, scatter, blade_dofs=range(cfg.bare.ndof))
    force = sector.travelling_wave(cfg.force, cfg.engine_order)
    result = frequency_response(disk, force, cfg.omega, harmonics=cfg.harmonics, samples=cfg.samples,
                                control=cfg.control, reduction=m.reduction, modes=m.modes, stability=False)
    blades = [blade_amplitudes(result, sector, d, harmonic=cfg.harmonic) for d in cfg.plot_dofs]  # (points, N)
    largest = np.column_stack([b.max(axis=1) for b in blades])  # the largest blade at each point
    row = _frf_row(cfg, result, largest)
    for d, b in zip(cfg.plot_dofs, blades):  # the largest blade's own peak, as blade_peaks gives it
        peaks = [curve_peak(result.omega, b[:, s]) for s in range(sector.sectors)]
        k = int(np.argmax([a for _, a in peaks]))
        row[f"peak {cfg.dof_names[d]} (m)"] = peaks[k][1]
        row[f"peak frequency {cfg.dof_names[d]} (Hz)"] = peaks[k][0] / (2 * np.pi)
        row[f"largest blade {cfg.dof_names[d]}"] = k
    row["blade stiffness scatter (std)"] = float(np.std(scatter))
    return row, _frf_curves(result, largest)


def _frf_row(cfg, result, amplitude) -> dict:
    from ..frequency.analyses.response import curve_peak

    row = {}
    for j, d in enumerate(cfg.plot_dofs):
        w, a = curve_peak(result.omega, amplitude[:, j])
        name = cfg.dof_names[d]
        row[f"peak {name} (m)"] = a
        row[f"peak frequency {name} (Hz)"] = w / (2 * np.pi)
    k = int(np.argmax(amplitude[:, 0]))
    row["dissipation at peak (J)"] = float(result.contact_dissipation[k].sum()) if result.structure.contacts else 0.0
    contacts = result.structure.contacts
    if len(contacts) <= 8:
        for c, contact in enumerate(contacts):
            row[f"static N0 {contact.name} (N)"] = float(result.static_normal_force[c])
            row[f"static T0 {contact.name} (N)"] = float(np.hypot(result.static_tangential_force[c],
                                                                  _second(result.static_tangential_force2, c)))
            row[f"static closed {contact.name}"] = int(result.static_closed_elements[c])
    elif contacts:
        row["static N0 min (N)"] = float(result.static_normal_force.min())
        row["static N0 max (N)"] = float(result.static_normal_force.max())
        row["static open contacts"] = int((result.static_closed_elements == 0).sum())
    row["points"] = int(result.points)
    row["complete"] = bool(result.complete)
    return row


def _second(values, c: int) -> float:
    return 0.0 if values is None else float(values[c])


def _frf_curves(result, amplitude) -> dict:
    dissipation = (result.contact_dissipation.sum(axis=1) if result.structure.contacts
                   else np.zeros(result.points))
    stable = (np.full(result.points, np.nan) if result.stable is None else result.stable.astype(float))
    return {"omega": np.asarray(result.omega, float), "amplitude": amplitude, "dissipation": dissipation,
            "stable": stable}


def _modes(study: Study, cfg):
    from ..config import apply_prestress
    from ..config.modes_control import mode_control
    from ..frequency import nonlinear_modes

    t = cfg.nonlinear_mode
    state = apply_prestress(cfg, cfg.force)[0]  # a [prestress]: the mode vibrates about its state
    mode = nonlinear_modes(cfg.structure, t.mode, t.amplitude, harmonics=cfg.harmonics, samples=cfg.samples,
                           reduction=cfg.reduction, modes=cfg.modes,
                           control=mode_control(cfg, cfg.continuation_keys),
                           nodal_diameter=t.nodal_diameter, prestress=state, folds=t.folds)
    amplitude = np.column_stack([mode.amplitude(d, 1) for d in cfg.plot_dofs])
    k = int(np.argmax(mode.damping_ratio))
    row = {"linear frequency (Hz)": float(mode.linear_frequency / (2 * np.pi)),
           "frequency at largest amplitude (Hz)": float(mode.omega[-1] / (2 * np.pi)),
           "largest damping ratio": float(mode.damping_ratio[k]),
           "modal amplitude at largest damping (kg^1/2 m)": float(mode.modal_amplitude[k]),
           "frequency at largest damping (Hz)": float(mode.omega[k] / (2 * np.pi)),
           "points": int(mode.modal_amplitude.size), "complete": bool(mode.complete)}
    curves = {"modal_amplitude": np.asarray(mode.modal_amplitude, float), "omega": np.asarray(mode.omega, float),
              "damping_ratio": np.asarray(mode.damping_ratio, float), "amplitude": amplitude}
    return row, curves
