"""The chapter modules of the reproduction: each registers the ids of its own chapter, and
builds its models with the case library's factories (the functions the named cases name)."""
from __future__ import annotations

import re

import pytest

from propwhirl.cases import registry
from propwhirl.reproduce import harness

#: chapter module -> the chapter (or appendix) its id prefixes must name
CHAPTER = {"ch04": "4", "ch06": "6", "ch07": "7", "ch09": "9", "ch10": "10", "ch11": "11", "appE": "E"}

#: The registered prefixes (34), as before reproduction functions moved out of propwhirl.cases.
PREFIXES = {
    "t4.1", "f6.2", "t7.2", "t7.3", "t7.4",
    "t9.2", "t9.4", "t9.5", "s9.2", "t9.6", "t9.7", "t9.8", "t9.9", "f9.19",
    "t10.1", "t10.2", "t10.3", "t10.4", "t10.5", "t10.6", "t10.7", "t10.8", "f10.6", "f10.14",
    "f11.3", "t11.2", "t11.3", "t11.4", "t11.5", "t11.6", "s11.6",
    "tE.1", "tE.2", "tE.3",
}


def test_the_registered_prefixes_are_unchanged():
    assert set(harness.registered_cases()) == PREFIXES


def test_every_function_is_registered_by_the_module_of_its_chapter():
    assert tuple(f"propwhirl.reproduce.{c}" for c in CHAPTER) == harness.CHAPTER_MODULES
    for prefix, func in harness.registered_cases().items():
        chapter = CHAPTER[func.__module__.rsplit(".", 1)[1]]
        assert re.fullmatch(rf"[tfs]{chapter}\.\d+", prefix), (prefix, func.__module__)


@pytest.mark.parametrize("name, chapter", [("patil", "ch07"), ("baseline-wing", "ch09"),
                                           ("isolated-propeller", "ch09"), ("inboard", "ch09"),
                                           ("wingtip", "ch10"), ("two-propeller", "ch10")])
def test_chapters_use_the_named_case_factories(name, chapter):
    import importlib

    module = importlib.import_module(f"propwhirl.reproduce.{chapter}")
    func = registry.CASES[name].function()
    assert getattr(module, func.__name__) is func
