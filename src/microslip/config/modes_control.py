"""The step control of a configuration's nonlinear mode: the mode's own, with what ``[continuation]`` sets."""

from __future__ import annotations

import dataclasses


def mode_control(cfg, given):
    """The :class:`~microslip.frequency.StepControl` of ``cfg``'s ``[modes]`` mode.

    ``nonlinear_modes`` sizes its steps by the chord rule on frequency and damping
    by default (:func:`~microslip.frequency.analyses.nonlinear_modes.default_control`
    of the amplitude range); a ``[continuation]`` table changes only the keys it names,
    so ``max_points = 250`` alone caps the mode the API computes rather than
    replacing its steps with the forced response's defaults (``cfg.control``
    holds those for every key the file leaves out); ``chord_error = false``
    gives the turn rule's steps (``default_control(..., chord_error=None)``).

    Parameters
    ----------
    cfg : FrfConfig
        A configuration read with ``nonlinear=True`` (its ``nonlinear_mode`` and ``control``).
    given : iterable of str
        The ``[continuation]`` keys the file (or a study's case) sets.

    Returns
    -------
    StepControl
        The mode's step control.

    Raises
    ------
    ValueError
        ``cfg`` has no ``[modes]`` table, or ``given`` names a key that is no setting of the step control.
    """
    from ..frequency.analyses.nonlinear_modes import default_control

    if getattr(cfg, "nonlinear_mode", None) is None:
        raise ValueError("cfg must be a configuration with a [modes] table (load_config(..., nonlinear=True))")
    keys = sorted(set(given))
    fields = {f.name for f in dataclasses.fields(cfg.control)}
    unknown = [k for k in keys if k not in fields]
    if unknown:
        raise ValueError(f"given names {', '.join(map(repr, unknown))}, not a [continuation] key (the keys: "
                         f"{', '.join(sorted(fields))})")
    # chord_error = false asks for the mode's former steps, the turn rule of default_control(..., chord_error=None)
    turn = "chord_error" in keys and cfg.control.chord_error is None
    amplitude = cfg.nonlinear_mode.amplitude
    own = default_control(*amplitude, chord_error=None) if turn else default_control(*amplitude)
    return dataclasses.replace(own, **{key: getattr(cfg.control, key) for key in keys})
