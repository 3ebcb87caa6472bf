"""Cases are model factories only: no module of propwhirl.cases imports studies, reproduce or
app (so studies may import cases without a cycle), and the reproduction harness imports its
chapter modules only through its explicit list CHAPTER_MODULES."""
from __future__ import annotations

import ast
import json
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

import propwhirl

PACKAGE = Path(propwhirl.__file__).resolve().parent
CASE_FILES = sorted((PACKAGE / "cases").glob("*.py"))
CASE_MODULES = [f"propwhirl.cases.{p.stem}" if p.stem != "__init__" else "propwhirl.cases"
                for p in CASE_FILES]
#: What a case module may import from propwhirl (the models, their generated equations, checks).
ALLOWED = ("propwhirl.cases", "propwhirl.model", "propwhirl.generated", "propwhirl.validate")
FORBIDDEN = ("propwhirl.studies", "propwhirl.reproduce", "propwhirl.app")


def _imports(path: Path, package: str, top_level_only: bool = False) -> set[str]:
    """Absolute names of the modules imported by the file at `path` (relative imports resolved;
    every import statement, those inside functions included, unless `top_level_only`)."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    nodes = tree.body if top_level_only else ast.walk(tree)
    names = set()
    for node in nodes:
        if isinstance(node, ast.Import):
            names.update(a.name for a in node.names)
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                parts = package.split(".")[: len(package.split(".")) - node.level + 1]
                base = ".".join(parts + ([base] if base else []))
            names.add(base)
            names.update(f"{base}.{a.name}" for a in node.names)  # `from pkg import module`
    return names


def _is_under(name: str, prefixes: tuple[str, ...]) -> bool:
    return any(name == p or name.startswith(p + ".") for p in prefixes)


def test_the_ast_walk_sees_imports_inside_functions(tmp_path):
    probe = tmp_path / "probe.py"
    probe.write_text("def f():\n    from propwhirl.studies.parametric import build_model\n"
                     "from . import ch09_baseline\n")
    names = _imports(probe, "propwhirl.cases")
    assert "propwhirl.studies.parametric" in names and "propwhirl.cases.ch09_baseline" in names
    assert _imports(probe, "propwhirl.cases", top_level_only=True) == {
        "propwhirl.cases", "propwhirl.cases.ch09_baseline"}


@pytest.mark.parametrize("path", CASE_FILES, ids=[p.stem for p in CASE_FILES])
def test_case_modules_import_only_models(path):
    names = [n for n in _imports(path, "propwhirl.cases") if n.startswith("propwhirl")]
    assert not [n for n in names if _is_under(n, FORBIDDEN)], f"{path.name} imports {names}"
    assert all(_is_under(n, ALLOWED) for n in names), (
        f"{path.name} imports {sorted(n for n in names if not _is_under(n, ALLOWED))}: "
        f"a case module builds models from {ALLOWED} only")


def _fresh(code: str) -> str:
    res = subprocess.run([sys.executable, "-c", textwrap.dedent(code)], capture_output=True,
                         text=True, timeout=120)
    assert res.returncode == 0, res.stderr
    return res.stdout.strip()


def test_importing_every_case_module_loads_no_study_reproduction_or_app():
    out = _fresh(f"""
        import importlib, sys
        for name in {CASE_MODULES!r}:
            importlib.import_module(name)
        print(sorted(m for m in sys.modules if m.startswith({FORBIDDEN!r})))
        """)
    assert out == "[]"


def test_studies_and_reproduction_import_in_either_order():
    for first, second in (("propwhirl.studies.parametric", "propwhirl.reproduce.ch11"),
                          ("propwhirl.reproduce.ch11", "propwhirl.studies.parametric")):
        assert _fresh(f"import {first}, {second}; print('ok')") == "ok"


def test_harness_imports_chapters_only_through_its_list():
    harness = PACKAGE / "reproduce" / "harness.py"
    top = _imports(harness, "propwhirl.reproduce", top_level_only=True)
    assert not [n for n in top if _is_under(n, ("propwhirl.reproduce", "propwhirl.cases"))
                and n != "propwhirl.reproduce.harness"]
    out = _fresh("""
        import json, sys
        from propwhirl.reproduce import harness
        before = sorted(m for m in sys.modules if m.startswith(('propwhirl.cases', 'propwhirl.reproduce.')))
        harness.registered_cases()
        after = sorted(m for m in sys.modules if m.startswith('propwhirl.reproduce.'))
        print(json.dumps([before, after, list(harness.CHAPTER_MODULES)]))
        """)
    before, after, listed = json.loads(out)
    assert before == ["propwhirl.reproduce.harness"]
    assert set(after) == {"propwhirl.reproduce.harness", *listed}


def test_every_chapter_module_is_listed():
    from propwhirl.reproduce import harness

    on_disk = {f"propwhirl.reproduce.{p.stem}" for p in (PACKAGE / "reproduce").glob("*.py")
               if p.stem not in ("__init__", "harness")}
    assert set(harness.CHAPTER_MODULES) == on_disk
