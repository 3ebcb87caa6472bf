"""The one tracking core (propwhirl.engine.follow): its contract over any scalar
parameter, and that the sweep over V, the Campbell diagram over Ω and the naming of modes from
Ω = 0 all run through it (issue 21, item 3: one tracker)."""
from __future__ import annotations

import sys
from dataclasses import dataclass

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from propwhirl.analysis.campbell import campbell
from propwhirl.analysis.modes import label_modes
from propwhirl.cases.ch09_baseline import isolated_baseline_propeller
from propwhirl.engine import sweep
from propwhirl.engine import follow
from propwhirl.validate import InputError


@dataclass(frozen=True)
class _Point:
    s: float


@dataclass(frozen=True)
class _Verdict:
    ambiguous: bool


def _calls_of(fn, *args, **kwargs) -> int:
    """How many times the core's code runs while ``fn(*args, **kwargs)`` runs."""
    count = 0
    code = follow.__code__

    def profile(frame, event, arg):
        nonlocal count
        if event == "call" and frame.f_code is code:
            count += 1

    sys.setprofile(profile)
    try:
        fn(*args, **kwargs)
    finally:
        sys.setprofile(None)
    return count


def _oscillator(V):      # ẍ + (0.5 − 0.01 V) ẋ + 100 x = 0
    A = np.zeros((V.size, 2, 2))
    A[:, 0, 1] = 1.0
    A[:, 1, 0] = -100.0
    A[:, 1, 1] = -(0.5 - 0.01 * V)
    return A


def test_the_sweep_the_campbell_diagram_and_the_naming_use_the_one_core():
    model = isolated_baseline_propeller()
    assert _calls_of(sweep, _oscillator, np.arange(10.0, 101.0, 10.0), n_dof=1) == 1
    assert _calls_of(campbell, model, [0.0, 1000.0, 2000.0]) >= 1
    assert _calls_of(label_modes, model) == 1


@settings(max_examples=60, deadline=None)
@given(first=st.integers(2, 12), budget=st.integers(2, 80),
       min_step=st.floats(1e-3, 0.5), always_ambiguous=st.booleans())
def test_the_core_splits_ambiguous_steps_within_its_budget_and_smallest_step(
        first, budget, min_step, always_ambiguous):
    """Work is bounded: never more nodes than the budget (or the first values), no step split
    below 2·min_step, and every pair of consecutive nodes linked once."""
    evaluated: list[float] = []
    linked: list[tuple[float, float]] = []

    def evaluate(s):
        evaluated.extend(float(x) for x in s)
        return [_Point(float(x)) for x in s]

    def link(a, b):
        linked.append((a.s, b.s))
        return _Verdict(always_ambiguous)

    nodes, links, refined = follow(evaluate, link, np.linspace(0.0, 1.0, first),
                                    min_step=min_step, budget=budget,
                                    split=lambda a, b, lk: 0.5 * (a.s + b.s))
    s = np.array([nd.s for nd in nodes])
    assert len(evaluated) == len(set(evaluated)) == s.size     # each value evaluated once
    assert s.size <= max(first, budget)
    assert np.all(np.diff(s) > 0)
    assert refined == s.size - first
    assert set(links) == set(zip(s[:-1], s[1:]))
    if not always_ambiguous:
        assert refined == 0
    elif s.size < budget:       # not stopped by the budget: stopped at the smallest step
        assert np.all(np.diff(s) < 2 * min_step)


def test_the_core_restarts_a_degenerate_first_node_on_each_new_neighbour():
    """``at_start`` re-expresses the first node for its continuation to the node next to it,
    again whenever refinement puts a new node there; the settle step adds values last."""
    seen = []

    def at_start(a, b):
        seen.append(b.s)
        return _Point(a.s)

    calls = []

    def settle(nodes, links):
        calls.append(len(nodes))
        return [0.875] if len(calls) == 1 else []

    nodes, links, refined = follow(
        lambda s: [_Point(float(x)) for x in s],
        lambda a, b: _Verdict(b.s - a.s > 0.3), np.array([0.0, 1.0]), min_step=0.01,
        budget=50, split=lambda a, b, lk: 0.5 * (a.s + b.s), settle=settle, at_start=at_start)
    assert [nd.s for nd in nodes] == [0.0, 0.25, 0.5, 0.75, 0.875, 1.0]
    assert seen == [1.0, 0.5, 0.25]
    assert refined == 3 and calls == [5, 6]


def _points(s):
    return [_Point(float(x)) for x in s]


def _midpoint(a, b, lk):
    return 0.5 * (a.s + b.s)


@pytest.mark.parametrize("kwargs, message", [
    ({"first": [0.0, 1.0, 0.5]}, "first is invalid: must be strictly increasing"),
    ({"first": [0.0, float("nan")]}, "first"),
    ({"min_step": 0.0}, "min_step"),
    ({"budget": 1}, "budget"),
    ({"split": lambda a, b, lk: b.s}, "split returned s = 1.0 for the step (0.0, 1.0)"),
    ({"split": lambda a, b, lk: None}, "no bracket"),
    ({"evaluate": lambda s: _points(s)[:1]}, "evaluate returned 1 nodes for 2"),
])
def test_the_core_refuses_what_it_cannot_follow_in_one_line(kwargs, message):
    args = {"evaluate": _points, "link": lambda a, b: _Verdict(True), "first": [0.0, 1.0],
            "min_step": 0.01, "budget": 10, "split": _midpoint}
    args.update(kwargs)
    evaluate, link, first = args.pop("evaluate"), args.pop("link"), args.pop("first")
    with pytest.raises(InputError) as err:
        follow(evaluate, link, first, **args)
    assert message in str(err.value) and "\n" not in str(err.value)


def test_a_single_value_is_followed_as_it_is():
    nodes, links, refined = follow(_points, lambda a, b: _Verdict(True), [0.0], min_step=0.01,
                                   budget=10, split=_midpoint)
    assert [nd.s for nd in nodes] == [0.0] and links == {} and refined == 0
