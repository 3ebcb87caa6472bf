"""The Examples sections of the package's docstrings run as doctests (numpydoc style).

Every module of propwhirl is imported and its docstring examples are run; the public entry
points named in ``PUBLIC_WITH_EXAMPLES`` must have examples (so this test cannot pass empty).
Every function and class of the curated API (the ``__all__`` of the packages in ``CURATED``)
has numpydoc: Parameters naming every parameter a caller gives (a class: Parameters or
Attributes), Returns (a function), and an Examples section whose doctests the first test runs.
"""
import doctest
import importlib
import inspect
import pkgutil
import re
import typing

import numpy as np
import pytest

import propwhirl

MODULES = sorted(m.name for m in pkgutil.walk_packages(propwhirl.__path__, "propwhirl.")
                 if not m.name.startswith("propwhirl.generated") and m.name != "propwhirl.__main__")

#: public functions and classes that must carry an Examples section
PUBLIC_WITH_EXAMPLES = [
    "propwhirl", "propwhirl.analysis.stability.critical",
    "propwhirl.analysis.naming.kinetic_energy_shares", "propwhirl.model.protocol",
    "propwhirl.model.statespace.state_matrix_from_mck",
    "propwhirl.engine.eigensolve.mac", "propwhirl.engine.eigensolve.eigenvalues",
    "propwhirl.engine.tracker.sweep", "propwhirl.engine.tracker.analyse",
    "propwhirl.engine.crossings.critical_points", "propwhirl.engine.crossings.frequency_zero_points",
    "propwhirl.engine.free_response.time_response", "propwhirl.io.model_files.loads",
    "propwhirl.io.model_files.dumps", "propwhirl.io.model_files.save_model",
    "propwhirl.analysis.stability.analyse", "propwhirl.analysis.stability.load",
    "propwhirl.cases.registry",
]


def test_every_module_is_collected():
    assert len(MODULES) >= 50 and "propwhirl.engine.crossings" in MODULES


@pytest.mark.parametrize("name", MODULES)
def test_module_examples(name):
    mod = importlib.import_module(name)
    finder = doctest.DocTestFinder(exclude_empty=True)
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    with np.printoptions(legacy=False):
        for test in finder.find(mod, name):
            if test.examples and test.name.startswith(name):  # defined here, not re-exported
                runner.run(test)
    assert runner.failures == 0, f"{runner.failures} doctest failure(s) in {name}"


@pytest.mark.parametrize("qualname", PUBLIC_WITH_EXAMPLES)
def test_public_entry_points_have_examples(qualname):
    modname, _, attr = qualname.rpartition(".")
    try:
        obj = importlib.import_module(qualname)
    except ImportError:
        obj = getattr(importlib.import_module(modname), attr)
    assert "Examples" in (obj.__doc__ or "") and ">>>" in obj.__doc__, qualname


# --- numpydoc of the curated API (issue 38 item 8) -------------------------------------------

#: the packages whose ``__all__`` is the curated API users call
CURATED = ["propwhirl", "propwhirl.analysis", "propwhirl.model", "propwhirl.engine", "propwhirl.io",
           "propwhirl.app.plots", "propwhirl.cases", "propwhirl.studies"]

_SECTION = re.compile(r"^[ \t]*([A-Z][A-Za-z ]+)\n[ \t]*-{3,}[ \t]*$", re.MULTILINE)
_ITEM = re.compile(r"^[ \t]*(\*{0,2}[A-Za-z_][\w]*(?:, \*{0,2}[A-Za-z_]\w*)*)[ \t]*(?::|$)",
                   re.MULTILINE)


def _sections(doc: str) -> dict[str, str]:
    """The numpydoc sections of ``doc``: title -> text up to the next section."""
    heads = list(_SECTION.finditer(doc))
    return {m.group(1).strip(): doc[m.end():heads[i + 1].start() if i + 1 < len(heads) else None]
            for i, m in enumerate(heads)}


def _documented(text: str) -> set[str]:
    """The names of the items of a Parameters/Attributes section (``a, b : type`` lines)."""
    indent = min((len(line) - len(line.lstrip()) for line in text.splitlines() if line.strip()),
                 default=0)
    names: set[str] = set()
    for line in text.splitlines():
        if line.strip() and len(line) - len(line.lstrip()) == indent:
            m = _ITEM.match(line)
            if m:
                names.update(n.strip() for n in m.group(1).split(","))
    return names


def _curated() -> list[tuple[str, object]]:
    """(public name, object) of every function and class of the curated ``__all__`` lists."""
    out = []
    for pkg in CURATED:
        mod = importlib.import_module(pkg)
        for name in getattr(mod, "__all__", ()):  # every package has one: test below
            obj = getattr(mod, name)
            if inspect.isclass(obj) or inspect.isfunction(obj):
                out.append((f"{pkg}.{name}", obj))
    return out


def _public_parameters(obj) -> list[str]:
    """The parameters a caller gives (``self`` and private ones left out; ``*a``, ``**k``)."""
    sig = inspect.signature(obj)
    stars = {inspect.Parameter.VAR_POSITIONAL: "*", inspect.Parameter.VAR_KEYWORD: "**"}
    return [stars.get(p.kind, "") + p.name for p in sig.parameters.values()
            if p.name != "self" and not p.name.startswith("_")]


def _numpydoc_problems(obj) -> list[str]:
    """What the numpydoc of a curated function or class lacks."""
    doc = inspect.cleandoc(obj.__doc__ or "")
    sec = _sections(doc)
    problems = []
    if inspect.isclass(obj):
        listed = "Parameters" if "Parameters" in sec else "Attributes"
        if listed not in sec:
            problems.append("no Parameters or Attributes section")
        elif obj.__init__ is not object.__init__ and not issubclass(obj, typing.Protocol):
            undocumented = set(_public_parameters(obj)) - set().union(
                *(_documented(sec[s]) for s in ("Parameters", "Attributes") if s in sec))
            if undocumented:
                problems.append(f"{listed} lack {sorted(undocumented)}")
    else:
        params = _public_parameters(obj)
        if params and "Parameters" not in sec:
            problems.append("no Parameters section")
        elif params:
            undocumented = set(params) - _documented(sec["Parameters"])
            if undocumented:
                problems.append(f"Parameters lack {sorted(undocumented)}")
        if "Returns" not in sec:
            problems.append("no Returns section")
    if "Examples" not in sec or ">>>" not in sec["Examples"]:
        problems.append("no Examples section with a doctest")
    return problems


@pytest.mark.parametrize("pkg", CURATED)
def test_curated_packages_have_all(pkg):
    assert getattr(importlib.import_module(pkg), "__all__", None), f"{pkg} has no __all__"


def test_studies_stub_names_what_the_package_exports():
    """propwhirl.studies imports its names on first use (PEP 562); its __init__.pyi gives them
    to static tools (the API page): the same names, from the same modules."""
    import ast
    from pathlib import Path

    import propwhirl.studies as studies

    tree = ast.parse((Path(studies.__file__).parent / "__init__.pyi").read_text())
    imported = {a.asname or a.name: node.module for node in tree.body
                if isinstance(node, ast.ImportFrom) for a in node.names}
    (stub_all,) = [ast.literal_eval(node.value) for node in tree.body if isinstance(node, ast.Assign)
                   and [t.id for t in node.targets] == ["__all__"]]
    assert imported == studies._EXPORTS and stub_all == studies.__all__
    assert all(getattr(studies, n).__module__ == m for n, m in studies._EXPORTS.items())


@pytest.mark.parametrize("name", [n for n, _ in _curated()])
def test_curated_api_has_numpydoc(name):
    """Every function and class of the curated API: Parameters (classes: or Attributes)
    naming every parameter a caller gives, Returns (functions), and Examples with doctests
    (run by test_module_examples in the module that defines them)."""
    obj = dict(_curated())[name]
    problems = _numpydoc_problems(obj)
    assert not problems, f"{name}: {'; '.join(problems)}"
