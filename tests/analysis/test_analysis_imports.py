"""No import cycle among the modes' modules of analysis/ (campbell, modes, naming, vibration),
and none held apart by a function-level import (issue 21, item 2: the re-exports made
campbell → naming → vibration → campbell, broken by imports inside functions)."""
from __future__ import annotations

import ast
from pathlib import Path

import pytest

ANALYSIS = Path(__file__).resolve().parents[2] / "src" / "propwhirl" / "analysis"
MODULES = ("campbell", "modes", "naming", "vibration")


def _analysis_imports(path: Path) -> tuple[set[str], set[str]]:
    """The analysis modules ``path`` imports at module level and inside functions."""
    tree = ast.parse(path.read_text())
    top = {n for n in tree.body if isinstance(n, (ast.Import, ast.ImportFrom))}
    outer, inner = set(), set()
    for node in ast.walk(tree):
        names = []
        if isinstance(node, ast.ImportFrom) and node.module:
            names = [node.module] + [f"{node.module}.{a.name}" for a in node.names]
        elif isinstance(node, ast.Import):
            names = [a.name for a in node.names]
        found = {n.split(".")[2] for n in names
                 if n.startswith("propwhirl.analysis.") and n.count(".") >= 2}
        found &= {p.stem for p in ANALYSIS.glob("*.py")}
        (outer if node in top else inner).update(found)
    return outer, inner


def _graph() -> dict[str, set[str]]:
    g = {}
    for path in ANALYSIS.glob("*.py"):
        outer, inner = _analysis_imports(path)
        g[path.stem] = (outer | inner) - {path.stem}
    return g


def _cycle_through(g: dict[str, set[str]], start: str) -> list[str] | None:
    """A path start → … → start in g, if any (depth first)."""
    stack, seen = [(start, [start])], set()
    while stack:
        node, path = stack.pop()
        for nxt in sorted(g.get(node, ())):
            if nxt == start:
                return path + [start]
            if nxt not in seen:
                seen.add(nxt)
                stack.append((nxt, path + [nxt]))
    return None


@pytest.mark.parametrize("name", MODULES)
def test_no_import_cycle_through_the_modes_modules(name):
    """Counting imports inside functions too: a cycle hidden by one is still a cycle."""
    assert _cycle_through(_graph(), name) is None, _cycle_through(_graph(), name)


@pytest.mark.parametrize("name", MODULES)
def test_no_function_level_import_of_an_analysis_module(name):
    _, inner = _analysis_imports(ANALYSIS / f"{name}.py")
    assert not inner, f"{name}.py imports {sorted(inner)} inside a function"


def test_the_check_sees_a_cycle():
    assert _cycle_through({"a": {"b"}, "b": {"c"}, "c": {"a"}}, "a") == ["a", "b", "c", "a"]
    assert _analysis_imports(ANALYSIS / "stability.py")[0] >= {"naming"}
