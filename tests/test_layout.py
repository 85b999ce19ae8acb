"""The package layout: no import cycles, arrows one way between the packages, a lean top level.

The import graph is read from the source with :mod:`ast` (every ``import`` statement, also those
inside functions), so a lazy import cannot hide a cycle.
"""

import ast
import importlib
import re
from pathlib import Path

import pytest

import microslip
from _paths import REPO

PACKAGE = Path(microslip.__file__).parent
ROOT = PACKAGE.parent

#: the allowed direction of the arrows: a module may import from its own top-level package or from
#: one of lower rank, never from one of higher rank
RANKS = {"common": 0, "_kernels": 0, "model": 1, "reference": 2, "fe": 2, "accuracy": 3,
         "frequency": 3, "tuning": 4, "measured": 5, "figures": 6, "study": 6, "cli": 7, "": 8}


def _module_name(path: Path) -> str:
    parts = list(path.relative_to(ROOT).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def _modules() -> dict:
    return {_module_name(p): p for p in PACKAGE.rglob("*.py")}


def _imports(name: str, path: Path, modules) -> set:
    """The package's modules that ``name`` imports (a ``from X import m`` of a submodule counts as m)."""
    is_package = path.name == "__init__.py"
    found = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            found.update(a.name for a in node.names if a.name.split(".")[0] == "microslip")
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = name.split(".") if is_package else name.split(".")[:-1]
                base = base[:len(base) - node.level + 1]
                source = ".".join(base + ([node.module] if node.module else []))
            else:
                source = node.module or ""
            if source.split(".")[0] != "microslip":
                continue
            subs = {f"{source}.{a.name}" for a in node.names} & set(modules)
            found.update(subs or {source})
            if len(subs) < len(node.names):
                found.add(source)
    return {m for m in found if m in modules and m != name}


@pytest.fixture(scope="module")
def graph():
    modules = _modules()
    return {name: _imports(name, path, modules) for name, path in modules.items()}


def _cycles(graph):
    """Strongly connected components with more than one module (Tarjan), each sorted."""
    index, low, stack, on_stack, out = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in graph[v]:
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                out.append(sorted(component))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return out


def test_the_cycle_finder_finds_a_cycle():
    assert _cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [["a", "b", "c"]]
    assert _cycles({"a": {"b"}, "b": set()}) == []


def test_no_import_cycles(graph):
    assert _cycles(graph) == []


def _top(name: str) -> str:
    parts = name.split(".")
    return parts[1] if len(parts) > 1 else ""


def test_arrows_run_one_way_between_packages(graph):
    assert {_top(m) for m in graph} <= set(RANKS), "a new top-level package needs its rank here"
    wrong = [(a, b) for a, targets in graph.items() for b in targets
             if _top(a) != _top(b) and RANKS[_top(b)] >= RANKS[_top(a)]]
    assert wrong == []


def test_the_top_level_holds_packages_and_a_handful_of_modules():
    modules = sorted(p.stem for p in PACKAGE.glob("*.py"))
    assert modules == ["__init__", "_kernels", "model"]
    packages = sorted(p.parent.name for p in PACKAGE.glob("*/__init__.py"))
    assert packages == ["accuracy", "cli", "common", "fe", "figures", "frequency", "measured", "reference",
                        "study", "tuning"]


def test_internal_modules_are_not_attributes_of_the_top_level():
    public = set(microslip.__all__) | {"__version__"}
    extra = {name for name in vars(microslip) if not name.startswith("__")} - public
    packages = {p.parent.name for p in PACKAGE.glob("*/__init__.py")}
    assert extra <= packages | {"model", "_kernels"}


def test_every_public_name_is_importable_where_users_import_it():
    for module in ("microslip", "microslip.fe", "microslip.frequency", "microslip.loops", "microslip.paths",
                   "microslip.reference", "microslip.tuning", "microslip.measured", "microslip.accuracy"):
        mod = importlib.import_module(module)
        for name in mod.__all__:
            assert getattr(mod, name) is not None, f"{module}.{name}"


def test_the_names_the_readme_uses_are_importable():
    readme = REPO / "README.md"
    text = readme.read_text(encoding="utf-8")
    statements = re.findall(r"^\s*from (microslip[\w.]*) import ([\w, ]+)$", text, flags=re.M)
    dotted = set(re.findall(r"`(microslip(?:\.\w+)+)", text))
    assert statements, "the README shows imports"
    for module, names in statements:
        mod = importlib.import_module(module)
        for name in names.split(","):
            assert hasattr(mod, name.strip()), f"from {module} import {name.strip()}"
    for path in dotted:
        parts = path.split(".")
        obj = importlib.import_module(parts[0])
        for i, part in enumerate(parts[1:], start=1):
            try:
                obj = getattr(obj, part)
            except AttributeError:
                obj = importlib.import_module(".".join(parts[:i + 1]))
        assert obj is not None, path


def test_old_import_paths_of_submodules_resolve_to_the_same_module():
    import microslip.loops.synthetic as old
    import microslip.measured.loops.synthetic as new

    assert old is new
