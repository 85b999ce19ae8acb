"""A reference contact built from measured hysteresis loops (the paper's Sect. 3).

The paper tunes its array on a branch of a steady measured loop at the
highest normal load: by Masing's rule the branch is the backbone scaled by
two about its reversal point. This module turns loops
(:meth:`MeasuredContact.from_loops`) or one measured branch
(:meth:`MeasuredContact.from_branch`) into a
:class:`~microslip.tuning.ContactReference`, so that
``tune(MeasuredContact.from_loops(...), N_tot, elements=J)`` works as for
the analytic sphere. The branch is fitted with a smooth, increasing,
concave curve (:mod:`microslip.measured.backbone_fit`); the checks that refuse data
the array cannot represent are in :mod:`microslip._loop_checks`.

The backbone at a lower load
----------------------------
Only the curve at the tuning load ``N_ref`` is measured. At a load
``N < N_ref`` the reference uses the rule that holds for any elastic contact
of the Cattaneo--Mindlin kind, uncoupled and on a half-space (Ciavarella;
Jäger): the tangential force is ``mu`` times the normal force lost by the
stick zone, ``T(t, N) = mu [N - N_stick]``. In terms of the measured curve
``f`` this reads

    ``T(t, N) = f(x0 + t) - f(x0)``,  with ``f(x0) = mu (N_ref - N)``:

the backbone at ``N`` is the part of the backbone at ``N_ref`` beyond the
point where it has reached ``mu (N_ref - N)``. For a sphere it gives
Cattaneo--Mindlin at every load exactly (checked in the tests); it needs no
normal law, and its gross-slip displacement is ``x_gs - x0(N)``. Loads above
``N_ref`` cannot be predicted and raise an error.

The fitted curve is scaled by ``mu N_ref / plateau`` so that it reaches
``mu N_ref`` exactly, as :func:`~microslip.tune` requires; when ``mu`` is
fitted from the slip forces at all loads the scale differs from 1 by the
scatter of the slip forces (reported).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..common import _checks
from . import _loop_checks
from ._loop_checks import backlash, fit_mu
from .backbone_fit import _KNOTS, FittedBackbone, fit_backbone
from .loops import analyse_branch
from ..tuning import TuningError

__all__ = ["FittedBackbone", "MeasuredContact", "backlash", "fit_backbone", "fit_mu"]

_MICROSLIP_MIN = 1.05  # k0 x_gs / T_gs below this: no microslip region (1 for a single Jenkins element)
_MASING_TOLERANCE = 0.1


@dataclass(frozen=True, eq=False)
class MeasuredContact:
    """A :class:`~microslip.tuning.ContactReference` from a measured branch and a normal law (SI units).

    Build it with :meth:`from_loops` (analysed records) or :meth:`from_branch`
    (one measured branch). The backbone at the tuning load is the
    fitted branch scaled to reach ``mu * normal_load``; at lower loads see
    the module docstring (the part of that backbone beyond ``mu (N_ref - N)``).

    Parameters
    ----------
    fit : FittedBackbone
        The curve fitted to the branch at the tuning load.
    normal : object
        The normal law: ``approach(N) -> n`` and ``normal_force(n) -> N``
        (m, N), e.g. :class:`microslip.Cylinder`.
    mu : float
        Friction coefficient.
    normal_load : float
        Tuning load ``N_ref`` (N), where the branch was measured.
    """

    fit: FittedBackbone
    normal: object
    mu: float
    normal_load: float
    notes: dict = field(default_factory=dict)

    def __post_init__(self):
        object.__setattr__(self, "mu", _checks.positive_scalar("mu", self.mu))
        object.__setattr__(self, "normal_load", _checks.positive_scalar("normal_load", self.normal_load))
        _loop_checks.normal_law(self.normal)

    @property
    def scale(self) -> float:
        """Factor applied to the fitted curve so that it reaches ``mu N_ref``: ``mu N_ref / plateau``."""
        return self.mu * self.normal_load / self.fit.plateau

    # -- ContactReference -------------------------------------------------------
    def _x0(self, N):
        N = _checks.positive_array("N", N)
        if np.any(N > self.normal_load * (1 + 1e-12)):
            raise ValueError(f"N must not exceed the tuning load {self.normal_load:g} N, where the branch was "
                             f"measured (no data above it), got {float(np.max(N)):g} N")
        N = np.minimum(N, self.normal_load)
        return self.fit.inverse(self.mu * (self.normal_load - N) / self.scale), N

    def _f(self, x):
        return self.scale * self.fit(np.minimum(x, self.fit.gross_slip_displacement))

    def backbone(self, t, N):
        """Virgin tangential force (N) at displacement ``t`` (m), load ``0 < N <= normal_load`` (N); odd in ``t``."""
        t = _checks.real_array("t", t)
        _checks.broadcast(t=t, N=_checks.real_array("N", N))
        x0, N = self._x0(N)
        return np.sign(t) * (self._f(x0 + np.abs(t)) - self._f(x0))

    def backbone_displacement(self, T, N):
        """Inverse of :meth:`backbone`: displacement (m) at force ``T`` (N), ``|T| <= mu N``."""
        T = _checks.real_array("T", T)
        _checks.broadcast(T=T, N=_checks.real_array("N", N))
        x0, N = self._x0(N)
        limit = self.mu * N
        if np.any(np.abs(T) > limit * (1 + 1e-9)):
            raise ValueError(f"T must satisfy |T| <= mu*N (gross slip); it exceeds it by up to "
                             f"{float(np.max(np.abs(T) - limit)):.6g} N")
        target = (np.minimum(np.abs(T), limit) + self.mu * (self.normal_load - N)) / self.scale
        x = self.fit.inverse(np.minimum(target, self.fit.plateau))
        return np.sign(T) * np.maximum(x - x0, 0.0)

    def gross_slip_displacement(self, N):
        """Displacement (m) at which the backbone at load ``N`` (N) reaches ``mu N``."""
        x0, _ = self._x0(N)
        return self.fit.gross_slip_displacement - x0

    def approach(self, N):
        """Normal approach (m) at load ``N`` (N), from the normal law."""
        return self.normal.approach(N)

    def normal_force(self, n):
        """Normal load (N) at approach ``n`` (m), from the normal law."""
        return self.normal.normal_force(n)

    def branch(self, t, N, t_reversal, T_reversal):
        """Masing branch (N) at load ``N`` from the reversal ``(t_reversal, T_reversal)`` (m, N)."""
        from ..reference import masing

        N = float(_checks.positive_scalar("N", N))
        return masing.branch(lambda x: self.backbone(x, N), t, t_reversal, T_reversal)

    # -- construction -----------------------------------------------------------
    @classmethod
    def from_loops(cls, loops, normal, *, mu=None, normal_load=None, knots: int = _KNOTS,
                   masing_tolerance: float = _MASING_TOLERANCE) -> "MeasuredContact":
        """Fit the reference on the steady loops at the highest normal load.

        Parameters
        ----------
        loops : Loops or sequence of Loops
            Analysed records (:func:`microslip.loops.analyse`), each with its
            ``normal_load``; the one at the highest load is tuned on, all of
            them give the friction coefficient when it is not given.
        normal : object
            Normal law, ``approach(N)`` and ``normal_force(n)``: e.g.
            :class:`microslip.Cylinder`. Its ``mu``, if set, is used.
        mu : float, optional
            Friction coefficient; default ``normal.mu``, else fitted from the
            slip forces (least squares through the origin of the slip force
            against the normal load, over the records in gross slip).
        normal_load : float, optional
            Tuning load (N); default the highest of the records (it must be
            one of them, to 0.1 %).
        knots : int, default 8
            Knots of the backbone fit.
        masing_tolerance : float, default 0.1
            Largest acceptable Masing error of the tuning record (fraction
            of the force amplitude), positive.

        Raises
        ------
        TuningError
            The data cannot be represented: loops not steady, not in gross
            slip, far from Masing, backlash (a convex start after reversals),
            no microslip region. The message gives the numbers.
        """
        masing_tolerance = _checks.positive_scalar("masing_tolerance", masing_tolerance)
        items = _loop_checks.loops_list(loops)
        ref = _loop_checks.tuning_record(items, normal_load)
        _loop_checks.check_loops(ref, masing_tolerance)
        x, y = ref.backbone_points()

        def mu_from_data(fit):
            value, residual = fit_mu(items)
            return value, {"mu_source": "fitted from the slip forces", "mu_fit_residual": residual}

        return cls._from_points(x, y, normal, float(ref.normal_load), mu, mu_from_data, knots=knots,
                                source=ref.record.source,
                                notes={"masing_error": ref.masing_error, "masing_basis": ref.masing_basis})

    @classmethod
    def from_branch(cls, t, T, normal, normal_load, mu=None, *, knots: int = _KNOTS,
                    source: str = "branch") -> "MeasuredContact":
        """Fit the reference on one measured branch of a steady loop.

        The branch, ascending or descending, from a reversal to the next, is
        twice the backbone by Masing's rule: its points ``((t - t_r)/2,
        (T - T_r)/2)`` from the reversal ``(t_r, T_r)`` are fitted as in
        :meth:`from_loops`, with the same checks (backlash, microslip region)
        and, as no cycle is given, without the checks of steadiness and of
        Masing's rule: the caller vouches that the loop was steady.

        Parameters
        ----------
        t : array_like, shape (S,)
            Tangential displacement along the branch (m), from the reversal
            on; a few samples before the reversal are dropped.
        T : array_like, shape (S,)
            Tangential force (N), acting along ``t`` (it rises with ``t``).
        normal : object
            Normal law, ``approach(N)`` and ``normal_force(n)`` (m, N), e.g.
            :class:`microslip.Cylinder`. Its ``mu``, if set, is used.
        normal_load : float
            Normal load at which the branch was measured (N): the tuning load.
        mu : float, optional
            Friction coefficient; default ``normal.mu``, else the branch's
            own: half its force change at gross slip over ``normal_load``.
        knots : int, default 8
            Knots of the backbone fit.
        source : str, default "branch"
            Name used in messages.

        Returns
        -------
        MeasuredContact

        Raises
        ------
        ValueError
            ``t``, ``T`` not finite 1-D arrays of one length (at least 16
            samples), ``normal_load`` not positive.
        microslip.loops.LoopError
            ``t`` does not vary or reverses (more than one branch), or the
            force sign is reversed.
        TuningError
            The branch does not reach gross slip, is not concave (backlash)
            or has no microslip region; the message gives the numbers.

        Examples
        --------
        >>> import numpy as np
        >>> from microslip import MeasuredContact, Sphere, tune
        >>> s = Sphere.paper()
        >>> t = np.linspace(-1.5e-6, 1.5e-6, 2000)             # ascending branch from -1.5 um
        >>> T = s.branch(t, 37.5, -1.5e-6, -15.0)              # Masing: twice the backbone
        >>> ref = MeasuredContact.from_branch(t, T, s, 37.5)
        >>> tune(ref, 37.5, elements=4).elements
        4
        """
        N_ref = _checks.positive_scalar("normal_load", normal_load)
        source = _checks.text("source", source)
        b = analyse_branch(t, T, source=source)
        if not b.gross_slip:
            raise TuningError(f"{source}: the branch does not reach gross slip: its slope over the last 10 % of "
                              f"the stroke, {b.end_slope:.4g} N/m, is not below 10 % of its stick stiffness "
                              f"{b.stick_stiffness:.4g} N/m, so it gives no slip force mu*N: measure a larger "
                              f"amplitude")

        def mu_from_data(fit):
            return fit.plateau / N_ref, {"mu_source": "fitted from the branch's slip force"}

        return cls._from_points(b.x, b.y, normal, N_ref, mu, mu_from_data, knots=knots, source=source,
                                notes={"branch": "ascending" if b.ascending else "descending"})

    @classmethod
    def _from_points(cls, x, y, normal, normal_load, mu, mu_from_data, *, knots, source, notes):
        """The fit and checks shared by :meth:`from_loops` and :meth:`from_branch`.

        ``mu_from_data(fit) -> (mu, notes)`` gives the friction coefficient
        when neither ``mu`` nor ``normal.mu`` does.
        """
        _loop_checks.normal_law(normal)
        _loop_checks.check_concave(x, y, source)
        fit = fit_backbone(x, y, knots=knots)
        if fit.microslip_ratio < _MICROSLIP_MIN:
            raise TuningError(
                f"{source}: the branch has no microslip region: initial stiffness "
                f"{fit.initial_stiffness:.4g} N/m x gross-slip displacement {fit.gross_slip_displacement:.4g} m "
                f"/ slip force {fit.plateau:.4g} N = {fit.microslip_ratio:.3f} (1 for a single macroslip "
                f"element, 1.5 for Cattaneo-Mindlin; needs >= {_MICROSLIP_MIN}): model it with one element")
        notes = {"fit_residual": fit.residual, "fit_relative_residual": fit.relative_residual, **notes}
        mu_given = mu if mu is not None else getattr(normal, "mu", None)
        if mu_given is None:
            mu_value, more = mu_from_data(fit)
            notes.update(more)
        else:
            mu_value = _checks.positive_scalar("mu", mu_given)
            notes["mu_source"] = "given"
        return cls(fit=fit, normal=normal, mu=mu_value, normal_load=normal_load, notes=notes)
