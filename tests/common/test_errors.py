"""Every exception and warning class the package defines sits under one base, keeps its built-in parent and its
old import path.

The classes are found from the source (every class statement of every module, read with :mod:`ast`), so a
class added anywhere later is checked too.
"""

import ast
import importlib
import pickle
import warnings
from pathlib import Path

import pytest

import microslip
from microslip.common import errors

PACKAGE = Path(microslip.__file__).parent


def _defined_exceptions():
    """``(module name, class)`` of every exception or warning class a module of the package defines."""
    found = []
    for path in sorted(PACKAGE.rglob("*.py")):
        parts = list(path.relative_to(PACKAGE.parent).with_suffix("").parts)
        if parts[-1] == "__init__":
            parts.pop()
        name = ".".join(parts)
        tree = ast.parse(path.read_text(encoding="utf-8"))
        classes = [node.name for node in ast.walk(tree) if isinstance(node, ast.ClassDef)]
        if not classes:
            continue
        module = importlib.import_module(name)
        for cls in classes:
            obj = getattr(module, cls, None)
            assert obj is not None, f"{name}.{cls} is not a module-level name: the check cannot reach it"
            if isinstance(obj, type) and issubclass(obj, BaseException):
                found.append((name, obj))
    return found


def _misplaced(classes) -> list:
    """Classes outside the policy: warnings under MicroslipWarning, Ctrl-C a KeyboardInterrupt and no Exception
    (so ``except Exception`` lets it through), every other error under MicroslipError."""
    wrong = []
    for cls in classes:
        if issubclass(cls, Warning):
            ok = issubclass(cls, errors.MicroslipWarning)
        elif issubclass(cls, KeyboardInterrupt):
            ok = not issubclass(cls, Exception) and cls is errors.CurveInterrupted
        else:
            ok = issubclass(cls, errors.MicroslipError)
        if not ok:
            wrong.append(cls.__name__)
    return wrong


def test_the_source_defines_the_classes_expected():
    names = {cls.__name__ for _, cls in _defined_exceptions()}
    # the two private ones are internal signals of their modules; the rest are the public classes
    assert names == set(errors.__all__) | {"_TooFewModes", "_Unmeshable"}


def test_every_exception_and_warning_the_package_defines_is_under_its_base():
    assert _misplaced([cls for _, cls in _defined_exceptions()]) == []


def test_the_policy_check_finds_a_class_outside_the_bases():
    class Loose(ValueError):
        pass

    class LooseWarning(RuntimeWarning):
        pass

    class OtherInterrupt(KeyboardInterrupt):
        pass

    assert _misplaced([Loose, LooseWarning, OtherInterrupt, errors.ConfigError]) == ["Loose", "LooseWarning",
                                                                                     "OtherInterrupt"]


#: the built-in parent each class had before the common bases, kept so that ``except ValueError`` etc. still catch
PARENTS = {
    "ConfigError": ValueError, "TuningError": ValueError, "TargetNotMet": ValueError, "LoadLimitError": ValueError,
    "LoopError": ValueError, "SingularInteriorError": ValueError, "FileFormatError": ValueError,
    "MissingVariable": ValueError, "OneMatrixFile": ValueError, "ConvergenceError": RuntimeError,
    "NotPeriodicError": RuntimeError, "FolderInUseError": OSError, "BeyondTuningWarning": UserWarning,
    "UnderResolvedWarning": RuntimeWarning, "BranchPointWarning": RuntimeWarning, "PeakOnEdgeWarning": RuntimeWarning,
    "IncompleteCurveWarning": RuntimeWarning, "DesignPointWarning": RuntimeWarning,
    "OneSidedDamperWarning": UserWarning, "StudyFolderWarning": UserWarning, "CurveInterrupted": KeyboardInterrupt,
    "MicroslipDeprecationWarning": DeprecationWarning,
}


@pytest.mark.parametrize("name, parent", sorted(PARENTS.items(), key=lambda item: item[0]))
def test_each_class_keeps_its_builtin_parent_and_is_exported_at_the_top(name, parent):
    cls = getattr(microslip, name)
    assert issubclass(cls, parent)
    assert cls is getattr(errors, name)
    assert cls.__doc__ and cls.__doc__.strip()


def test_the_table_of_parents_covers_every_class():
    assert set(PARENTS) == set(errors.__all__) - {"MicroslipError", "MicroslipWarning"}


def test_ctrl_c_is_not_caught_by_except_exception():
    with pytest.raises(KeyboardInterrupt):
        try:
            raise microslip.CurveInterrupted("interrupted", partial=[1])
        except Exception:  # noqa: BLE001 - the point: a study's catch-all must let Ctrl-C through
            pytest.fail("except Exception caught Ctrl-C")


def test_a_warning_filter_on_the_base_reaches_every_warning():
    with warnings.catch_warnings():
        warnings.simplefilter("error", microslip.MicroslipWarning)
        with pytest.raises(microslip.UnderResolvedWarning):
            warnings.warn("x", microslip.UnderResolvedWarning)


#: where each class was defined before it moved to microslip.common.errors (old import paths keep working)
OLD_PATHS = [
    ("microslip.model", "BeyondTuningWarning"), ("microslip.config.frf", "ConfigError"),
    ("microslip.config", "ConfigError"), ("microslip.frequency.config", "ConfigError"),
    ("microslip.tuning.target.search", "TargetNotMet"), ("microslip.tuning", "TargetNotMet"),
    ("microslip.tuning.paper", "TuningError"), ("microslip.reference.mdr", "LoadLimitError"),
    ("microslip.reference", "LoadLimitError"), ("microslip.loops", "LoopError"),
    ("microslip.frequency.aft", "NotPeriodicError"), ("microslip.frequency.aft", "UnderResolvedWarning"),
    ("microslip.frequency.continuation", "ConvergenceError"),
    ("microslip.frequency.numerics.continuation", "BranchPointWarning"),
    ("microslip.frequency.design", "DesignPointWarning"), ("microslip.frequency.response", "PeakOnEdgeWarning"),
    ("microslip.frequency.analyses.response", "CurveInterrupted"),
    ("microslip.frequency.analyses.response", "IncompleteCurveWarning"),
    ("microslip.frequency.condensation", "SingularInteriorError"), ("microslip.study.folder", "StudyFolderWarning"),
    ("microslip.study.folder", "FolderInUseError"), ("microslip.fe", "FileFormatError"),
    ("microslip.fe.files", "FileFormatError"), ("microslip.fe._formats", "MissingVariable"),
    ("microslip.fe._formats", "OneMatrixFile"), ("microslip.frequency", "ConvergenceError"),
]


@pytest.mark.parametrize("module, name", OLD_PATHS)
def test_old_import_paths_give_the_same_class(module, name):
    assert getattr(importlib.import_module(module), name) is getattr(microslip, name)


def test_an_error_with_its_own_arguments_survives_pickling():
    # a study's worker sends its errors back pickled; the class is found by the path it names (microslip.X)
    error = pickle.loads(pickle.dumps(microslip.FileFormatError("blade.op4", "truncated", line=12)))
    assert type(error) is microslip.FileFormatError and str(error) == "blade.op4: line 12: truncated"
    assert error.line == 12
