"""The one table of named cases: what `propwhirl case`, `propwhirl run` and the reproduction use."""
from __future__ import annotations

import inspect

import numpy as np
import pytest

from propwhirl.app import run
from propwhirl.cases import registry
from propwhirl.model.systems import IsolatedPropeller, PropellerWing
from propwhirl.validate import InputError

README_NAMES = ["patil", "baseline-wing", "isolated-propeller", "inboard", "wingtip", "two-propeller"]


def test_the_names_are_those_of_the_readme():
    assert list(registry.CASES) == README_NAMES
    assert all(name == case.name for name, case in registry.CASES.items())


@pytest.mark.parametrize("name", README_NAMES)
def test_each_factory_is_a_documented_case_function(name):
    case = registry.CASES[name]
    func = case.function()
    module = case.factory.split(":")[0]
    assert module.startswith("propwhirl.cases.") and func.__module__ == module
    assert inspect.getdoc(func), f"{case.factory} has no docstring"
    assert case.description and case.section and "\n" not in case.summary
    assert case.summary.isascii()  # printed by the command line


@pytest.mark.parametrize("name", README_NAMES)
def test_case_model_builds_the_factory_model(name):
    model = registry.case_model(name)
    assert isinstance(model, (PropellerWing, IsolatedPropeller))
    direct = registry.CASES[name].function()()
    V = np.array([50.0])
    np.testing.assert_array_equal(model.state_matrix(V), direct.state_matrix(V))


def test_options_reach_the_factory():
    model = registry.case_model("wingtip", mount="rigid", rotating=False)
    assert [i.mount for i in model.propellers] == ["rigid"] and not model.rotating


def test_unknown_name_is_one_line_with_the_valid_names():
    with pytest.raises(InputError) as exc:
        registry.get("concorde")
    msg = str(exc.value)
    assert "\n" not in msg and msg.startswith("case = 'concorde' is invalid")
    assert all(name in msg for name in README_NAMES)


def test_run_analyses_the_wingtip_case():
    assert run.MAIN_CASE == "wingtip"
    V = np.array([10.0, 200.0])
    np.testing.assert_array_equal(run.headline_model().state_matrix(V),
                                  registry.case_model("wingtip").state_matrix(V))
