"""Folders the tests read: the repository, its examples, and the real measured damper data."""

from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
EXAMPLES = REPO / "examples"
#: two records of the ARTS-Lab band friction damper data set (CC BY-SA 4.0, see its README.md)
DAMPER = REPO / "tests" / "data" / "arts-friction-damper"
