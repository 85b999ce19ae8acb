"""Every exception and warning microslip defines, under two bases.

* :class:`MicroslipError` -- the base of every error the package raises of its own kind. Each error
  keeps the built-in parent it has always had (``ValueError`` for bad input or an unusable file,
  ``RuntimeError`` for a computation that did not converge, ``OSError`` for a folder in use), so
  ``except ValueError`` still catches what it caught, and ``except microslip.MicroslipError``
  catches all of them.
* :class:`MicroslipWarning` -- the base of every warning; each keeps its ``RuntimeWarning`` or
  ``UserWarning`` parent. ``warnings.simplefilter("error", microslip.MicroslipWarning)`` turns them
  all into errors.
* :class:`CurveInterrupted` is the one class outside both: it is Ctrl-C (a ``KeyboardInterrupt``)
  carrying the part of a curve computed, and it must stay out of ``except Exception`` (and so out of
  ``except MicroslipError``) for a loop or a study that records failures to stop on Ctrl-C.

The classes are defined here, once; the modules that raise them import them, so their former import
paths (``microslip.frequency.analyses.response.CurveInterrupted``, ``microslip.config.ConfigError``,
...) are the same class objects. Each is exported at the top level (``microslip.ConfigError``), and
its ``__module__`` says so, so a traceback names it by the path users import.
"""

from __future__ import annotations

from pathlib import Path


class MicroslipError(Exception):
    """Base of every error microslip defines; each also keeps its built-in parent (``ValueError``, ...)."""


class MicroslipWarning(Warning):
    """Base of every warning microslip defines; each also keeps its ``RuntimeWarning`` or ``UserWarning`` parent."""


# --- bad input and unusable files (ValueError) ---------------------------------------------------------------


class ConfigError(MicroslipError, ValueError):
    """A configuration file that cannot be used; the message names the file and the key."""


class TuningError(MicroslipError, ValueError):
    """The reference cannot be represented by the paper's array with the given points."""


class TargetNotMet(MicroslipError, ValueError):
    """No number of elements up to the limit meets the accuracy target; ``best`` holds the best found.

    Attributes
    ----------
    best : TargetTuning
        The most accurate tuning found (at the largest number of elements tried).
    """

    def __init__(self, message, best):
        super().__init__(message)
        self.best = best


class LoadLimitError(MicroslipError, ValueError):
    """An MDR model was asked for an approach (load) beyond what it was built for."""


class LoopError(MicroslipError, ValueError):
    """The record cannot be analysed (no complete cycle, no steady cycle, ...)."""


class SingularInteriorError(MicroslipError, ValueError):
    """The structure with its retained DOFs held fixed is singular at some frequency."""


class FileFormatError(MicroslipError, ValueError):
    """A file that cannot be what it claims to be: truncated, damaged or inconsistent.

    The message names the file and, for a text format, the line:
    ``"blade.op4: line 12: ..."``.

    Attributes
    ----------
    path : Path
        The file.
    line : int or None
        The line (from 1) of a text file, None when the format has no lines.
    """

    def __init__(self, path, what: str, line: int | None = None):
        self.path, self.line, self.what = Path(path), line, what
        super().__init__(f"{path}: line {line}: {what}" if line is not None else f"{path}: {what}")

    def __reduce__(self):  # pickled whole (a worker's error reaches the caller intact)
        return type(self), (self.path, self.what, self.line)


class MissingVariable(MicroslipError, ValueError):
    """A file lacks variables that were asked for; ``missing`` and ``held`` list the names.

    ``advice`` ends the message: how the caller chooses other variables.
    """

    def __init__(self, path: Path, missing: list[str], held,
                 advice: str = "choose others with names={'M': ..., 'K': ...}"):
        self.path, self.missing, self.held = path, list(missing), sorted(held)
        listed = ", ".join(self.held) if self.held else "no variables"
        super().__init__(f"{path}: no variable {', '.join(repr(m) for m in missing)}; the file holds {listed} "
                         f"({advice})")


class OneMatrixFile(MicroslipError, ValueError):
    """A file that holds a single matrix was asked for several (``M``, ``K``, ``C`` from one file).

    ``path`` is the file, ``kind`` its format.
    """

    def __init__(self, path: Path, kind: str, wanted: list[str]):
        self.path, self.kind = path, kind
        named = ", ".join(wanted[:-1]) + f" and {wanted[-1]}"
        super().__init__(f"{path}: a {kind} file holds a single matrix, which cannot be {named} at once; say which "
                         f"matrix each file is: one file per matrix (M=..., K=..., and C=... if any)")


# --- computations that did not succeed (RuntimeError) and a folder in use (OSError) ---------------------------


class ConvergenceError(MicroslipError, RuntimeError):
    """Newton's method or the continuation could not converge."""


class NotPeriodicError(MicroslipError, RuntimeError):
    """The contact state did not become periodic within the allowed number of periods."""


class FolderInUseError(MicroslipError, OSError):
    """Another run holds the results folder."""


# --- warnings ------------------------------------------------------------------------------------------------


class BeyondTuningWarning(MicroslipWarning, UserWarning):
    """A tuned model is driven beyond the normal load it was tuned for.

    Beyond its tuning approach every element of the paper's array is closed,
    so its normal and tangential stiffnesses only extrapolate linearly.
    """


class UnderResolvedWarning(MicroslipWarning, RuntimeWarning):
    """The AFT samples too few points per period to resolve a contact opening and closing during the cycle."""


class BranchPointWarning(MicroslipWarning, RuntimeWarning):
    """The curve passed a branch point: another branch of solutions crosses it there (it goes on along its own)."""


class PeakOnEdgeWarning(MicroslipWarning, RuntimeWarning):
    """The highest point of a curve is its first or last point: the resonance lies outside the range followed."""


class IncompleteCurveWarning(MicroslipWarning, RuntimeWarning):
    """The continuation stopped at ``StepControl.max_points`` before the end of the frequency range."""


class DesignPointWarning(MicroslipWarning, RuntimeWarning):
    """A load of a design curve is left out of its optimum: its forced response failed."""


class OneSidedDamperWarning(MicroslipWarning, UserWarning):
    """Every face of an under-platform damper touches the same sector's platforms: it joins a blade to itself."""


class MicroslipDeprecationWarning(MicroslipWarning, DeprecationWarning):
    """A name that is deprecated: it still works, and the message names the one that replaces it."""


class StudyFolderWarning(MicroslipWarning, UserWarning):
    """The results folder was not as a finished run leaves it: a case file not trusted, leftovers, a lock taken over."""


# --- Ctrl-C ------------------------------------------------------------------------------------------------


class CurveInterrupted(KeyboardInterrupt):
    """Ctrl-C (KeyboardInterrupt) during a computation along a curve.

    A ``KeyboardInterrupt`` still (a script stops as before, and ``except
    Exception`` does not catch it, which is why it is no :class:`MicroslipError`);
    ``partial`` holds what was computed up to there, with ``complete`` False:
    the curve up to its last accepted point (a
    :class:`~microslip.FrequencyResponse`, a :class:`~microslip.NonlinearModes`),
    or the loads finished of a :class:`~microslip.DesignCurve`.

    Attributes
    ----------
    partial : FrequencyResponse, NonlinearModes, DesignCurve or None
        What was computed before the interruption.
    """

    def __init__(self, message: str, partial=None):
        super().__init__(message)
        self.partial = partial


#: every class above; the top level exports each by its name
__all__ = [
    "BeyondTuningWarning", "BranchPointWarning", "ConfigError", "ConvergenceError", "CurveInterrupted",
    "DesignPointWarning", "FileFormatError", "FolderInUseError", "IncompleteCurveWarning", "LoadLimitError",
    "LoopError", "MicroslipDeprecationWarning", "MicroslipError", "MicroslipWarning", "MissingVariable",
    "NotPeriodicError", "OneMatrixFile", "OneSidedDamperWarning", "PeakOnEdgeWarning", "SingularInteriorError",
    "StudyFolderWarning", "TargetNotMet", "TuningError", "UnderResolvedWarning",
]

for _name in __all__:  # a traceback and the API reference name each by the path users import
    globals()[_name].__module__ = "microslip"
del _name


def deprecated(old: str, new: str, stacklevel: int = 3) -> None:
    """Warn that the name ``old`` is deprecated in favour of ``new`` (a :class:`MicroslipDeprecationWarning`).

    ``stacklevel`` 3 points the warning at the caller of the function that calls this one.
    """
    import warnings

    warnings.warn(f"{old} is deprecated: use {new} (the same arguments)", MicroslipDeprecationWarning,
                  stacklevel=stacklevel)
