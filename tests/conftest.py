"""Test-suite settings: under CI the hypothesis examples are derandomised; figures are closed after each test.

Locally every run draws new examples (and keeps the failures it finds in
``.hypothesis/``); under CI (``CI`` set in the environment, as ``.ci/run``
runs) the same examples are drawn every time, so the gate is reproducible.
"""

import os

from hypothesis import settings

settings.register_profile("ci", derandomize=True, print_blob=True)
if os.environ.get("CI"):
    settings.load_profile("ci")


import pytest  # noqa: E402


@pytest.fixture(autouse=True)
def _close_figures():
    """Every figure a test draws is closed after it (pyplot keeps them open otherwise)."""
    yield
    import sys

    if "matplotlib.pyplot" in sys.modules:
        sys.modules["matplotlib.pyplot"].close("all")
