"""The Examples sections of the package's docstrings run as doctests (numpydoc style).

Every module of propwhirl is imported and its docstring examples are run; the public entry
points named in ``PUBLIC_WITH_EXAMPLES`` must have examples (so this test cannot pass empty).
"""
import doctest
import importlib
import pkgutil

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
