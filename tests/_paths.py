"""Folders the tests read: the repository, its examples, and the real measured damper data."""

from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
EXAMPLES = REPO / "examples"
DAMPER = REPO.parent / "shared" / "data" / "arts-friction-damper"
