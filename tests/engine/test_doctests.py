"""The Examples sections of the engine's docstrings run, and are right (doctest)."""
from __future__ import annotations

import doctest
import importlib
import pkgutil

import pytest

import propwhirl.engine

MODULES = ["propwhirl.engine"] + [f"propwhirl.engine.{m.name}"
                                  for m in pkgutil.iter_modules(propwhirl.engine.__path__)]
#: modules whose public functions carry Examples (mac, eigenvalues, sweep, analyse,
#: critical_points, frequency_zero_points, time_response)
WITH_EXAMPLES = {"propwhirl.engine.eigensolve", "propwhirl.engine.tracker",
                 "propwhirl.engine.crossings", "propwhirl.engine.time_response"}


@pytest.mark.parametrize("name", MODULES)
def test_engine_doctests(name):
    # import_module returns the module even where the package re-exports a function of the
    # same name (propwhirl.engine.time_response)
    module = importlib.import_module(name)
    result = doctest.testmod(module, optionflags=doctest.ELLIPSIS, verbose=False)
    assert result.failed == 0
    if name in WITH_EXAMPLES:
        assert result.attempted > 0


def test_every_module_is_collected():
    assert WITH_EXAMPLES <= set(MODULES)
    assert len(MODULES) >= 12
