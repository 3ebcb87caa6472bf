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
    # what certification asks (the regulations' speed factors, the required speed, a campaign's
    # words): data below everything that uses it, so the campaign files and the studies share it
    "certification": {"validate"},
    "model": {"fileio", "generated", "limits", "validate"},
    "engine": {"fileio", "limits", "results", "validate"},   # model-agnostic: A(V) in, eigen-data out
    "analysis": {"certification", "engine", "fileio", "limits", "model", "results", "validate"},
    "cases": {"model", "validate"},               # model factories only
    "studies": {"analysis", "cases", "certification", "engine", "fileio", "limits", "model",
                "progress", "results", "validate"},
    "reproduce": {"analysis", "cases", "documents", "engine", "fileio", "generated", "model", "progress",
                  "results", "studies", "validate"},
    # files in and out (model, modal-model, campaign, NASTRAN, V-g-f CSV): just above model/,
    # beside the engine and the analyses, never importing them or the studies (a campaign
    # file is read to a plain CampaignSpec that studies.campaign.from_spec builds on);
    # docs/architecture.md draws it so
    "io": {"certification", "fileio", "limits", "model", "validate"},
    "app": {"analysis", "cases", "certification", "documents", "engine", "fileio", "io", "limits",
            "model", "progress", "reproduce", "results", "studies", "validate"},
    # entry point; the old import paths of the first release's flat layout, one alias table
    # (issue 38, item 5: its targets are imported by name, at first use, whatever their layer)
    "__main__": {"app"}, "__init__": {"compat"}, "compat": set(),
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


def test_the_architecture_document_draws_the_same_layers():
    """docs/architecture.md's table of the packages and what each may import is ALLOWED (issue
    38 item 2: the document and this test once disagreed on where io/ stands)."""
    doc = (SRC.parent.parent / "docs" / "architecture.md").read_text()
    head = "| package | may import (besides itself) |\n|---|---|\n"
    assert head in doc
    table = {}
    for line in doc.split(head, 1)[1].splitlines():
        if not line.startswith("| `"):
            break
        pkg, allowed = (cell.strip() for cell in line.strip("|").split("|"))
        table[pkg.strip("`")] = (set() if allowed == "(nothing)"
                                 else {a.strip().strip("`") for a in allowed.split(",")})
    assert table == ALLOWED


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


# ----------------------------------------------------------------------------- cycles
def _module_name(path: Path) -> str:
    parts = list(path.relative_to(SRC.parent).with_suffix("").parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


MODULES = {_module_name(p): p for p in FILES}


def _targets(node: ast.AST) -> list[str]:
    """The propwhirl modules an import statement loads (``from propwhirl.x import y`` loads
    ``propwhirl.x.y`` when that is a module, else ``propwhirl.x``)."""
    out = []
    if isinstance(node, ast.ImportFrom) and node.level == 0 and (node.module or "").startswith("propwhirl"):
        for a in node.names:
            sub = f"{node.module}.{a.name}"
            out.append(sub if sub in MODULES else node.module)
    elif isinstance(node, ast.Import):
        out += [a.name for a in node.names if a.name.startswith("propwhirl")]
    return [t for t in out if t in MODULES]


def _import_graph() -> tuple[dict[str, set[str]], list[tuple[str, int, str]]]:
    """Module-level imports {module: modules it loads when imported} (a submodule also loads
    its packages' __init__) and the function-level imports (module, line, target)."""
    graph, inner = {}, []
    for name, path in MODULES.items():
        tree = ast.parse(path.read_text())
        in_functions = set()
        for fn in ast.walk(tree):
            if isinstance(fn, (ast.FunctionDef, ast.AsyncFunctionDef)):
                for node in ast.walk(fn):
                    if isinstance(node, (ast.Import, ast.ImportFrom)):
                        in_functions.add(id(node))
                        inner += [(name, node.lineno, t) for t in _targets(node)]
        graph[name] = {t for node in ast.walk(tree) if isinstance(node, (ast.Import, ast.ImportFrom))
                       and id(node) not in in_functions for t in _targets(node)}
    for name in list(graph):
        parts = name.split(".")
        graph[name] |= {".".join(parts[:i]) for i in range(1, len(parts))} - {name}
    return graph, inner


def _reaches(graph: dict[str, set[str]], a: str, b: str) -> bool:
    seen, stack = set(), [a]
    while stack:
        x = stack.pop()
        if x == b:
            return True
        if x not in seen:
            seen.add(x)
            stack.extend(graph.get(x, ()))
    return False


def test_no_import_cycle_between_modules():
    """Issue 21.2: no two modules import each other, directly or round a loop (a package's
    ``__init__`` re-exporting its modules is not a loop: the edges from a module up to its
    own packages are left out here)."""
    graph, _ = _import_graph()
    explicit = {m: {t for t in ts if not m.startswith(t + ".")} for m, ts in graph.items()}
    loops = sorted(f"{a} -> {b}" for a, ts in explicit.items() for b in ts
                   if not b.startswith(a + ".") and _reaches(explicit, b, a))
    assert loops == []


def test_no_function_level_import_breaks_a_cycle():
    """Issue 21.2: an import inside a function is there for start-up time or an optional
    dependency, never to break a cycle: its target never loads the importing module back
    (at module level, packages' ``__init__`` included)."""
    graph, inner = _import_graph()
    breakers = sorted(f"{m}:{line} -> {t}" for m, line, t in inner if _reaches(graph, t, m))
    assert breakers == []


# ----------------------------------------------------------------------------- issue 38 item 4
def _private(name: str) -> bool:
    return name.startswith("_") and not name.startswith("__")


def test_no_private_name_is_imported_across_modules():
    """Issue 38.4: a helper another module uses is public in its module: no module imports
    ``_name`` from another propwhirl module, nor reads ``m._name`` of one it imported."""
    found = []
    for name, path in MODULES.items():
        tree = ast.parse(path.read_text())
        aliases = {}                 # local name -> the propwhirl module it is bound to
        for node in ast.walk(tree):
            if isinstance(node, ast.ImportFrom) and node.level == 0 and \
                    (node.module or "").startswith("propwhirl"):
                for a in node.names:
                    if _private(a.name) and node.module != name:
                        found.append(f"{path.relative_to(SRC)}:{node.lineno} imports {a.name} "
                                     f"from {node.module}")
                    if f"{node.module}.{a.name}" in MODULES:
                        aliases[a.asname or a.name] = f"{node.module}.{a.name}"
            elif isinstance(node, ast.Import):
                aliases |= {a.asname: a.name for a in node.names
                            if a.asname and a.name.startswith("propwhirl.")}
        for node in ast.walk(tree):
            if isinstance(node, ast.Attribute) and _private(node.attr) and \
                    isinstance(node.value, ast.Name) and aliases.get(node.value.id, name) != name:
                found.append(f"{path.relative_to(SRC)}:{node.lineno} reads {node.attr} of "
                             f"{aliases[node.value.id]}")
    assert found == []


def _strongly_connected(graph: dict[str, set[str]]) -> list[list[str]]:
    """The import loops of `graph`: its strongly connected components of more than one module
    (Tarjan's algorithm, iterative)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    loops = []
    for root in sorted(graph):
        if root in index:
            continue
        work = [(root, iter(sorted(graph[root])))]
        index[root] = low[root] = len(index)
        stack.append(root)
        on_stack.add(root)
        while work:
            v, edges = work[-1]
            w = next(edges, None)
            if w is not None:
                if w not in index:
                    index[w] = low[w] = len(index)
                    stack.append(w)
                    on_stack.add(w)
                    work.append((w, iter(sorted(graph.get(w, ())))))
                elif w in on_stack:
                    low[v] = min(low[v], index[w])
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[v])
            if low[v] == index[v]:
                component = []
                while True:
                    w = stack.pop()
                    on_stack.discard(w)
                    component.append(w)
                    if w == v:
                        break
                if len(component) > 1:
                    loops.append(sorted(component))
    return loops


def test_the_loop_finder_finds_loops():
    assert _strongly_connected({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [["a", "b", "c"]]
    assert _strongly_connected({"a": {"b"}, "b": set()}) == []


def test_no_import_cycle_even_through_imports_inside_functions():
    """Issue 38.4: no import cycle among propwhirl's modules, counting every import — at module
    level and inside functions (an import inside a function does not make a cycle go away,
    it only hides it until the function runs).  A package's ``__init__`` re-exporting its
    own modules is not a loop (the edges from a module up to its own packages are left out)."""
    graph, inner = _import_graph()
    for m, _, t in inner:
        graph[m].add(t)
    explicit = {m: {t for t in ts if not m.startswith(t + ".")} for m, ts in graph.items()}
    assert _strongly_connected(explicit) == []


#: The package whose import is what the command line defers: the models (SciPy's interpolate,
#: optimize and special with them; about 1 s on a quiet machine, 2-3 s on a loaded one).
DEFERRED = "propwhirl.model"
#: Where an import inside a function may load a propwhirl module: the command line, whose
#: `import propwhirl.app.cli` loads no model.
LAZY_PACKAGES = {"app"}


def _type_checking(node: ast.AST) -> bool:
    return isinstance(node, ast.If) and "TYPE_CHECKING" in ast.unparse(node.test)


def _runtime_graph() -> dict[str, set[str]]:
    """{module: the propwhirl modules its import executes directly}: its module-level imports
    (not those under ``if TYPE_CHECKING:``) and its packages' ``__init__``."""
    graph = {}
    for name, path in MODULES.items():
        tree = ast.parse(path.read_text())
        skip = {id(n) for fn in ast.walk(tree)
                if isinstance(fn, (ast.FunctionDef, ast.AsyncFunctionDef)) or _type_checking(fn)
                for n in ast.walk(fn)}
        parts = name.split(".")
        graph[name] = {t for node in ast.walk(tree) if isinstance(node, (ast.Import, ast.ImportFrom))
                       and id(node) not in skip for t in _targets(node)}
        graph[name] |= {".".join(parts[:i]) for i in range(1, len(parts))} - {name}
    return graph


def _loaded_by(graph: dict[str, set[str]], module: str) -> set[str]:
    """Every propwhirl module that importing `module` loads (itself included)."""
    seen, stack = set(), [module]
    while stack:
        m = stack.pop()
        if m not in seen:
            seen.add(m)
            stack.extend(graph.get(m, ()))
    return seen


def _imports_inside_functions() -> list[tuple[str, int, str, str]]:
    """(module, line, target, the text of the import statement and its comments) of every
    import of a propwhirl module inside a function."""
    out = []
    for name, path in MODULES.items():
        text = path.read_text()
        lines = text.splitlines()
        for fn in ast.walk(ast.parse(text)):
            if isinstance(fn, (ast.FunctionDef, ast.AsyncFunctionDef)):
                for node in ast.walk(fn):
                    if isinstance(node, (ast.Import, ast.ImportFrom)):
                        source = "\n".join(lines[node.lineno - 1:node.end_lineno])
                        out += [(name, node.lineno, t, source) for t in _targets(node)]
    return sorted(set(out))


LAZY = "# lazy: "


def test_imports_inside_functions_only_defer_the_models_on_the_command_line():
    """Issue 38.4, the rule of docs/architecture.md ("Imports"): propwhirl's modules import each
    other at module level.  Inside a function only (a) an optional extra (matplotlib, pandas,
    ...: not checked here) or (b) on the command line (app/), a propwhirl module that loads
    the models (DEFERRED) into a module that does not load them already, with the reason in a
    comment ``# lazy: <reason>`` on the import."""
    graph = _runtime_graph()
    wrong = []
    for module, line, target, source in _imports_inside_functions():
        where = f"{MODULES[module].relative_to(SRC)}:{line} imports {target}"
        reason = source.partition(LAZY)[2].strip()
        if module.split(".")[1] not in LAZY_PACKAGES:
            wrong.append(f"{where} inside a function: import it at module level")
        elif not reason:
            wrong.append(f"{where} inside a function without '{LAZY}<reason>'")
        elif DEFERRED not in _loaded_by(graph, target):
            wrong.append(f"{where} inside a function: it does not load {DEFERRED}, nothing to "
                         "defer (import it at module level)")
        elif DEFERRED in _loaded_by(graph, module):
            wrong.append(f"{where} inside a function: {module} loads {DEFERRED} already "
                         "(import it at module level)")
    assert wrong == []


def test_the_command_line_module_loads_no_model():
    """What the lazy imports of app/ are for: importing the command line's module loads none
    of the models (`propwhirl docs`, `--version` and the tests of the parser stay fast)."""
    assert DEFERRED not in _loaded_by(_runtime_graph(), "propwhirl.app.cli")
    assert DEFERRED in _loaded_by(_runtime_graph(), "propwhirl.app.run")
