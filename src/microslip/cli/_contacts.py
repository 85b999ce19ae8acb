"""The contacts' section of the ``microslip frf`` report: static state, dampers' balance, the cycle at the peak."""

from __future__ import annotations

import numpy as np

#: contacts drawn in the figure of the cycle at the peak (the table lists them all)
MAX_DRAWN = 8


def static_rows(result) -> list:
    """One row per contact: name, N0 (N), T0 (N), |T0| / (mu N0), elements closed of J."""
    rows = []
    for c, contact in enumerate(result.structure.contacts):
        N0, T0 = result.static_normal_force[c], static_tangential(result, c)
        limit = contact.model.mu * N0
        rows.append([contact.name, f"{N0:.4g}", f"{T0:.4g}", f"{abs(T0) / limit:.3g}" if limit > 0 else "open",
                     f"{result.static_closed_elements[c]} of {contact.model.elements}"])
    return rows


def static_tangential(result, c: int) -> float:
    """Contact ``c``'s static tangential force (N): signed along one direction, its size on a plane."""
    T0 = result.static_tangential_force[c]
    return float(np.hypot(T0, result.static_tangential_force2[c])) if result.structure.contacts[c].planar else T0


def damper_lines(result, dampers) -> list[str]:
    """For each damper: its load and how well its static forces and moment balance."""
    lines = []
    for k, d in enumerate(dampers):
        N0 = [result.static_normal_force[[c.name for c in result.structure.contacts].index(n)] for n in d.names]
        lines.append(f"Damper {k} (contacts {', '.join(d.names)}): centrifugal load {d.centrifugal_load:.6g} N, "
                     f"shared statically as {', '.join(f'{n:.4g}' for n in N0)} N of normal load; the forces and "
                     f"the moment on it balance to {d.static_balance(result):.1e} of the load.")
    return lines


def peak_point(result, dof, harmonic) -> int:
    """The point of the curve where ``dof``'s amplitude is highest."""
    return int(np.argmax(result.amplitude(dof, harmonic)))


def cycles(result, point: int) -> list:
    """Every contact's :class:`~microslip.frequency.ContactCycle` at ``point``."""
    from ..frequency import contact_cycle

    return [contact_cycle(result, c, point) for c in range(len(result.structure.contacts))]


def cycle_rows(cycles_at_peak) -> list:
    """One row per contact: N range (N), largest |T| (N), then the share of the period in each slip state (%)."""
    rows = []
    for cy in cycles_at_peak:
        shares = cy.fractions()
        rows.append([cy.name, f"{cy.N.min():.4g} to {cy.N.max():.4g}", f"{cy.magnitude.max():.4g}"]
                    + [f"{100 * s:.0f}" for s in shares.values()])
    return rows


def cycle_columns(cycles_at_peak) -> dict:
    """The cycles as CSV columns: time and phase, then each contact's N, T and slip state."""
    first = cycles_at_peak[0]
    cols = {"time [s]": first.time, "phase [-]": np.arange(first.time.size) / first.time.size}
    from ..frequency.analyses.contact_cycle import SLIP_STATES

    for cy in cycles_at_peak:
        cols[f"{cy.name} N [N]"] = cy.N
        cols[f"{cy.name} T [N]"] = cy.T
        if cy.T2 is not None:  # a contact on its plane: the second component
            cols[f"{cy.name} T2 [N]"] = cy.T2
        cols[f"{cy.name} state [-]"] = np.array([SLIP_STATES[k] for k in cy.state])
    return cols


def add_section(report, result, cfg, out) -> list[str]:
    """The contacts' section of the report (tables, figure, CSV); returns the lines to print."""
    from ..common._io import write_csv

    lines = []
    report.heading("Contacts")
    report.table(["contact", "normal load N0 (N)", "tangential force T0 (N)", "share of the slip force μN0",
                  "elements closed"],
                 static_rows(result), caption="Static state of each contact (before any vibration)")
    for line in damper_lines(result, cfg.dampers):
        report.text(line)
        lines.append(line)
    dof = cfg.plot_dofs[0]
    k = peak_point(result, dof, cfg.harmonic)
    at_peak = cycles(result, k)
    where = f"at the peak of {cfg.dof_names[dof]} (ω = {result.omega[k]:.6g} rad/s, f = " \
            f"{result.omega[k] / (2 * np.pi):.6g} Hz)"
    report.table(["contact", "normal load N over the cycle (N)", "largest tangential force (N)", "stuck (%)",
                  "microslip (%)", "gross slip (%)", "lift-off (%)"], cycle_rows(at_peak),
                 caption=f"Each contact over one period {where}: the share of the period in each slip state "
                         f"(stuck: every closed element sticks; microslip: some slip; gross slip: all slip, "
                         f"|T| = μN; lift-off: the contact is open)")
    from ..frequency import plot_contact_cycles

    fig = plot_contact_cycles(at_peak[:MAX_DRAWN], f"Contact forces over one period {where}")
    shown = "" if len(at_peak) <= MAX_DRAWN else f" (the first {MAX_DRAWN} of {len(at_peak)} contacts)"
    report.figure(fig, "contact_cycle", f"Normal force (left) and tangential force within ±μN (right) of each "
                  f"contact{shown} over one period {where}; the background shows the slip state. Samples: "
                  f"`contact_cycle.csv`.", out)
    write_csv(out / "contact_cycle.csv", cycle_columns(at_peak))
    for cy in at_peak:
        lines.append(f"Contact {cy.name} {where}: N from {cy.N.min():.4g} to {cy.N.max():.4g} N, |T| up to "
                     f"{cy.magnitude.max():.4g} N; {cy.summary()}.")
    return lines
