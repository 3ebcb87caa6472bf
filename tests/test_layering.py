"""The data flow is one way: generated → model → engine → analysis → studies, reproduce → app.

Every import between propwhirl's packages (module level and inside functions) must follow the
allowed edges below; an import against the flow (say, the engine importing a model, or a model
importing an analysis) fails here.
"""
import ast
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parent.parent / "src" / "propwhirl"

#: package -> the propwhirl packages it may import (validate: the shared input checks;
#: limits: memory estimates, size limits, safe terminal text)
ALLOWED = {
    "validate": set(),
    "limits": {"validate"},                       # memory estimates and size limits
    "fileio": {"validate"},                       # atomic file writes, writability checks
    "results": {"fileio", "validate"},            # the result protocol, the checked reader
    "documents": {"validate"},                    # the installed docs/*.md pages
    "progress": {"validate"},                     # progress bars and spinners on a terminal
    "model": {"generated", "limits", "validate"},
    "engine": {"limits", "results", "validate"},             # model-agnostic: A(V) in, eigen-data out
    "analysis": {"engine", "fileio", "limits", "model", "results", "validate"},
    "cases": {"model", "validate"},               # model factories only
    "studies": {"analysis", "cases", "engine", "fileio", "limits", "model", "progress", "results",
                "validate"},
    "reproduce": {"analysis", "cases", "documents", "engine", "fileio", "generated", "model", "progress",
                  "results", "studies", "validate"},
    "io": {"fileio", "limits", "model", "validate"},
    "app": {"analysis", "cases", "documents", "engine", "fileio", "io", "limits", "model", "progress",
            "reproduce", "results", "studies", "validate"},
    # entry point and compatibility re-exports
    "__main__": {"app"}, "__init__": set(), "wing": {"model"}, "propeller": {"model"},
    "plots": {"app"},
    # the flat layout of the first release (issue 20, item 11: old import paths keep working)
    "aero": {"model"}, "assembly": {"model"}, "statespace": {"model"}, "vibration": {"analysis"},
    "response": {"analysis", "reproduce"}, "stability": {"analysis", "engine", "model"},
    "cli": {"app", "cases"}, "mainjob": {"app"},
}


def _imports(path: Path) -> set[str]:
    out = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            if node.module == "propwhirl":    # modules; the package's version is a constant
                out |= {a.name for a in node.names if a.name != "__version__"}
            elif node.module.startswith("propwhirl."):
                out.add(node.module.split(".")[1])
        elif isinstance(node, ast.Import):
            out |= {a.name.split(".")[1] for a in node.names if a.name.startswith("propwhirl.")}
    return out


FILES = sorted(SRC.rglob("*.py"))


@pytest.mark.parametrize("path", FILES, ids=[str(p.relative_to(SRC)) for p in FILES])
def test_imports_follow_the_data_flow(path):
    rel = path.relative_to(SRC)
    pkg = rel.parts[0] if len(rel.parts) > 1 else rel.stem
    assert pkg in ALLOWED, f"{rel}: package {pkg!r} has no place in the layering; add it"
    wrong = _imports(path) - ALLOWED[pkg] - {pkg}
    assert not wrong, f"{rel} imports {sorted(wrong)} against the data flow"


def test_the_check_sees_imports():
    assert _imports(SRC / "analysis" / "stability.py") >= {"engine", "model"}
    assert len(FILES) > 50


def test_the_architecture_document_names_every_module():
    """docs/architecture.md lists every module (so the map of the house cannot go stale)."""
    doc = (SRC.parent.parent / "docs" / "architecture.md").read_text()
    packages_listed_whole = {"cases", "reproduce"}     # described as a whole there
    missing = []
    for path in FILES:
        rel = path.relative_to(SRC)
        if rel.name in ("__init__.py", "__main__.py") and len(rel.parts) > 1:
            continue
        if len(rel.parts) > 1 and rel.parts[0] in packages_listed_whole:
            continue
        if f"`{rel.name}`" not in doc:
            missing.append(str(rel))
    assert not missing, f"docs/architecture.md does not describe {missing}"
