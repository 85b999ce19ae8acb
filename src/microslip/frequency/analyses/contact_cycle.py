"""One contact over one steady period of a forced response: forces and slip state at every sample.

At a point of a :class:`~microslip.frequency.FrequencyResponse` each contact's
tangential displacement ``t`` and normal approach ``n`` are periodic; the contact
is marched along them with the harmonic balance's convention (closed at ``t = 0``
with no force, loaded statically to the mean, then period after period until
its state repeats) and the last period is returned with each element's
condition. Each sample is then in one of four states:

* ``"stuck"`` -- every closed element sticks;
* ``"microslip"`` -- some closed elements slip, not all;
* ``"gross slip"`` -- every closed element slips: ``|T| = mu N`` (on the contact
  plane ``|T| <= mu N``: each element's force has its full length ``mu N_i``
  but points along its own slider's lag);
* ``"lift-off"`` -- no element is closed: ``N = T = 0``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...common import _checks
from ...kernels import aft as _aft, plane_march as _plane_march
from ..aft import MAX_PERIODS, NotPeriodicError, time_samples
from .response import FrequencyResponse

#: the slip states, in the order of :attr:`ContactCycle.state`'s codes
SLIP_STATES = ("stuck", "microslip", "gross slip", "lift-off")
#: background colour of each state in :meth:`ContactCycle.plot`
STATE_COLOURS = ("#4c72b0", "#dd8452", "#c44e52", "#8c8c8c")


@dataclass(frozen=True, eq=False)
class ContactCycle:
    """One contact over one steady period (from :func:`contact_cycle`); ``samples`` points.

    Attributes
    ----------
    name : str
        The contact's name.
    omega : float
        Excitation frequency (rad/s).
    time : ndarray, shape (samples,)
        Time from the start of the period (s).
    t, n : ndarray, shape (samples,)
        Tangential displacement and normal approach (m).
    T, N : ndarray, shape (samples,)
        Tangential and normal force (N).
    mu : float
        Friction coefficient of the contact.
    condition : ndarray of int8, shape (samples, J)
        Each element's condition: 0 open, 1 stick, 2 slip.
    state : ndarray of int, shape (samples,)
        The contact's state, an index into :data:`SLIP_STATES`.
    t2, T2 : ndarray, shape (samples,), or None
        For a contact moving on its plane, the second tangential displacement
        (m) and force (N) (``t``, ``T`` being the first); None otherwise.
    """

    name: str
    omega: float
    time: np.ndarray
    t: np.ndarray
    n: np.ndarray
    T: np.ndarray
    N: np.ndarray
    mu: float
    condition: np.ndarray
    state: np.ndarray
    t2: np.ndarray | None = None
    T2: np.ndarray | None = None

    @property
    def magnitude(self) -> np.ndarray:
        """``|T|`` (N), shape ``(samples,)``: the tangential force's size (both components on the plane)."""
        return np.abs(self.T) if self.T2 is None else np.hypot(self.T, self.T2)

    def fractions(self) -> dict:
        """``{state: fraction of the period}`` for each of :data:`SLIP_STATES` (fractions sum to 1)."""
        return {name: float(np.mean(self.state == k)) for k, name in enumerate(SLIP_STATES)}

    def summary(self) -> str:
        """The states met over the period with their shares, e.g. ``"stuck 60 %, microslip 40 %"``."""
        return ", ".join(f"{name} {100 * share:.0f} %" for name, share in self.fractions().items() if share > 0)

    def plot(self, axes=None, *, legend: bool = True):
        """Normal force, and tangential force within ``+-mu N``, over the period; the slip state shaded.

        For a contact on its plane the tangential axes show both components
        and the magnitude ``|T|`` within ``mu N``.

        Parameters
        ----------
        axes : (Axes, Axes), optional
            Where to draw the normal and the tangential force (a new figure if omitted).
        legend : bool
            Name the states and the curves.

        Returns
        -------
        (Axes, Axes)
        """
        import matplotlib.pyplot as plt
        from matplotlib.patches import Patch

        if axes is None:
            _, axes = plt.subplots(2, 1, figsize=(6, 4.5), sharex=True)
        ax_n, ax_t = axes
        phase = np.arange(self.time.size + 1) / self.time.size  # sample k stands for [k, k + 1) / samples
        for ax in (ax_n, ax_t):
            for k, colour in enumerate(STATE_COLOURS):
                for lo, hi in _runs(self.state == k):
                    ax.axvspan(phase[lo], phase[hi], color=colour, alpha=0.15, lw=0)
            ax.grid(True, alpha=0.3)
        closed = np.append(phase[:-1], 1.0)
        ax_n.plot(closed, np.append(self.N, self.N[0]), color="k")
        ax_n.set_ylabel("normal force N (N)")
        slip = np.append(self.mu * self.N, self.mu * self.N[0])
        if self.T2 is None:
            ax_t.plot(closed, np.append(self.T, self.T[0]), color="k", label="T")
            ax_t.plot(closed, slip, "--", color="0.4", lw=0.8, label="± μN")
            ax_t.plot(closed, -slip, "--", color="0.4", lw=0.8)
        else:
            size = np.hypot(self.T, self.T2)
            ax_t.plot(closed, np.append(size, size[0]), color="k", label="|T|")
            ax_t.plot(closed, slip, "--", color="0.4", lw=0.8, label="μN")
            for comp, style, name in ((self.T, ":", "T1"), (self.T2, "-.", "T2")):
                ax_t.plot(closed, np.append(comp, comp[0]), style, color="k", lw=0.8, label=name)
        ax_t.set_ylabel("tangential force T (N)")
        ax_t.set_xlabel("time / period")
        ax_t.set_xlim(0.0, 1.0)
        ax_n.set_title(f"{self.name}: {self.summary()}", fontsize=9)
        if legend:
            met = [k for k in range(len(SLIP_STATES)) if np.any(self.state == k)]
            handles = [Patch(color=STATE_COLOURS[k], alpha=0.3, label=SLIP_STATES[k]) for k in met]
            ax_t.legend(handles=ax_t.get_legend_handles_labels()[0] + handles, fontsize=7, loc="upper right",
                        ncol=2)
        return ax_n, ax_t


def plot_contact_cycles(cycles, title: str = ""):
    """One row per contact: its normal force (left) and tangential force within ``+-mu N`` (right), states shaded.

    Parameters
    ----------
    cycles : sequence of ContactCycle
        From :func:`contact_cycle` (e.g. every contact at one point).
    title : str
        Title of the figure.

    Returns
    -------
    matplotlib.figure.Figure
    """
    import matplotlib.pyplot as plt
    from matplotlib.patches import Patch

    cycles = list(cycles)
    if not cycles or not all(isinstance(c, ContactCycle) for c in cycles):
        raise TypeError(f"cycles must be a non-empty sequence of ContactCycle, got {cycles!r}")
    fig, axes = plt.subplots(len(cycles), 2, figsize=(10, 2.1 * len(cycles) + 0.8), sharex=True, squeeze=False)
    for i, cy in enumerate(cycles):
        row = axes[i]
        cy.plot(row, legend=False)
        row[0].set_title("")
        row[0].set_title(cy.name, fontsize=9, loc="left")
        row[1].set_title(cy.summary(), fontsize=8, loc="right")
        if i < len(cycles) - 1:
            row[1].set_xlabel("")
    axes[-1, 0].set_xlabel("time / period")
    handles = [Patch(color=c, alpha=0.3, label=s) for s, c in zip(SLIP_STATES, STATE_COLOURS)]
    handles += axes[0, 1].get_lines()[:2]
    fig.legend(handles=handles, labels=list(SLIP_STATES) + ["T", "± μN"], loc="upper center", ncol=6, fontsize=8,
               bbox_to_anchor=(0.5, 1.0))
    if title:
        fig.suptitle(title, y=1.03, fontsize=10)
    fig.tight_layout()
    return fig


def _runs(mask) -> list[tuple[int, int]]:
    """``(start, stop)`` of every run of True in ``mask``."""
    edges = np.diff(np.concatenate([[0], np.asarray(mask, dtype=np.int8), [0]]))
    return list(zip(np.flatnonzero(edges == 1), np.flatnonzero(edges == -1)))


def slip_states(condition) -> np.ndarray:
    """The contact's state at each sample, an index into :data:`SLIP_STATES`, from the elements' conditions.

    Parameters
    ----------
    condition : array_like of int, shape (samples, J)
        0 open, 1 stick, 2 slip (as :attr:`microslip.Response.condition`).

    Returns
    -------
    ndarray of int, shape (samples,)
    """
    c = np.asarray(condition)
    if c.ndim != 2 or not np.isin(c, (0, 1, 2)).all():
        raise ValueError(f"condition must be a (samples, J) array of 0 (open), 1 (stick), 2 (slip), got shape "
                         f"{c.shape}")
    closed = (c != 0).sum(axis=1)
    slipping = (c == 2).sum(axis=1)
    state = np.where(slipping == 0, 0, np.where(slipping < closed, 1, 2))
    return np.where(closed == 0, 3, state)


def contact_cycle(result, contact, point: int, *, samples: int | None = None,
                  max_periods: int = MAX_PERIODS) -> ContactCycle:
    """The steady cycle of one contact at one point of a forced response.

    Parameters
    ----------
    result : FrequencyResponse
        A forced response (or one point of it, :func:`~microslip.frequency.frequency_point`).
    contact : int or str
        The contact, by index or name.
    point : int
        The point of the curve (e.g. ``argmax`` of an amplitude: the peak).
    samples : int, optional
        Samples per period (default: the AFT's, those the solution was computed with).
    max_periods : int
        Periods marched at most for the contact's state to repeat.

    Returns
    -------
    ContactCycle

    Raises
    ------
    NotPeriodicError
        The contact's state does not repeat within ``max_periods`` periods.
    """
    if not isinstance(result, FrequencyResponse):
        raise TypeError(f"result must be a FrequencyResponse, got {type(result).__name__}")
    names = [c.name for c in result.structure.contacts]
    if isinstance(contact, str):
        if contact not in names:
            raise ValueError(f"contact: no contact named {contact!r}; the structure's contacts are {names}")
        c = names.index(contact)
    else:
        c = _checks.positive_int("contact", contact, minimum=0)
        if c >= len(names):
            raise ValueError(f"contact must be below the number of contacts {len(names)}, got {c}")
    k = _checks.positive_int("point", point, minimum=0)
    if k >= result.points:
        raise ValueError(f"point must be below the number of points {result.points}, got {k}")
    Ns = result.samples if samples is None else _checks.size("samples", samples, minimum=2 * result.harmonics + 1)
    periods = _checks.positive_int("max_periods", max_periods)
    model = result.structure.contacts[c].model
    xt, xn = result.contact_t[k, c], result.contact_n[k, c]
    t, n = time_samples(xt, Ns), time_samples(xn, Ns)
    omega = float(result.omega[k])
    time = 2 * np.pi / omega * np.arange(Ns) / Ns
    if result.structure.contacts[c].planar:
        return _plane_cycle(names[c], omega, time, model, xt, result.contact_t2[k, c], xn, Ns, periods)
    state = model.simulate([xt[0]], [xn[0]], per_element=False, work=False).state  # the static step
    for _ in range(periods):
        r = model.simulate(t, n, state, work=False)
        if np.array_equal(r.state.sliders, state.sliders):
            break
        state = r.state
    else:
        raise NotPeriodicError(f"contact {names[c]!r} did not reach a periodic state within {periods} periods")
    return ContactCycle(names[c], omega, time, t, n, r.T, r.N, float(model.mu), r.condition, slip_states(r.condition))


def _plane_cycle(name, omega, time, model, xt, xt2, xn, Ns, max_periods) -> ContactCycle:
    """:func:`contact_cycle` of a contact on its plane: from the AFT's periodic state, one period."""
    E = _aft.tables((xt.size - 1) // 2, Ns)[0]
    s = np.empty((2, model.elements))
    if _plane_march.periodic_state(model.kt, model.kn, model.gaps, model.mu, xt, xt2, xn, E, max_periods, s) < 0:
        raise NotPeriodicError(f"contact {name!r} did not reach a periodic state within {max_periods} periods")
    t, t2, n = E @ xt, E @ xt2, E @ xn
    T, N, cond = np.empty((Ns, 2)), np.empty(Ns), np.empty((Ns, model.elements), dtype=np.int8)
    _plane_march.march_plane(model.kt, model.kn, model.gaps, model.mu, t, t2, n, s, T, N, np.empty((0, 0, 2)), cond)
    return ContactCycle(name, omega, time, t, n, T[:, 0].copy(), N, float(model.mu), cond, slip_states(cond),
                        t2, T[:, 1].copy())
