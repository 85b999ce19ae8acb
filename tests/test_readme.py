"""The README: one screen's worth, its two commands the ones CI runs, every Python block runs as shown."""

import re

import pytest

from _paths import REPO

README = REPO / "README.md"


def python_blocks() -> list[str]:
    """The README's fenced Python code blocks, in order."""
    return re.findall(r"^```python\n(.*?)^```", README.read_text(encoding="utf-8"), flags=re.M | re.S)


def test_the_readme_is_under_10_kb():
    assert README.stat().st_size < 10_000, f"README.md has {README.stat().st_size} bytes"


def test_the_readme_test_command_is_what_ci_runs():
    text = README.read_text(encoding="utf-8")
    commands = re.findall(r"^```bash\n(.*?)\n```", text, flags=re.M | re.S)
    assert commands[:2] == ['pip install . && microslip reproduce', 'pip install -e ".[test]" && python -m pytest']
    ci = (REPO / ".ci" / "run").read_text(encoding="utf-8").splitlines()
    assert commands[1] in ci, ".ci/run must run the README's test command verbatim"


def test_the_readme_shows_three_examples():
    assert len(python_blocks()) == 3


@pytest.mark.parametrize("index", range(3))
def test_every_python_block_of_the_readme_runs(index, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)  # a block that writes a file writes it here
    monkeypatch.setenv("MPLBACKEND", "Agg")
    block = python_blocks()[index]
    exec(compile(block, f"README.md, Python block {index + 1}", "exec"), {"__name__": "__readme__"})
