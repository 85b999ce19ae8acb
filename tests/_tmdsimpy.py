"""tmdsimpy (MIT, not on PyPI) from the local copy ``TMDSIMPY_PATH`` names, for the side-by-side tests."""

from __future__ import annotations

import importlib
import os
import sys

import pytest

ROOT = os.environ.get("TMDSIMPY_PATH")


def import_tmdsimpy(modules, what: str) -> dict:
    """tmdsimpy's ``modules`` by their last name, or skip the test saying why (``what`` it compares)."""
    if not ROOT:
        pytest.skip(f"TMDSIMPY_PATH is not set: the comparison with {what} is skipped "
                    "(set it to a local copy of tmdsimpy, with jax installed, to run it)")
    sys.path.insert(0, ROOT)
    try:
        return {name.rsplit(".", 1)[1]: importlib.import_module(name) for name in modules}
    except ImportError as exc:
        pytest.skip(f"tmdsimpy from TMDSIMPY_PATH={ROOT!r} cannot be imported ({exc}): the comparison is skipped")
    finally:
        sys.path.remove(ROOT)
