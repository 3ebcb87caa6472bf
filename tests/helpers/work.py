"""Counting work instead of timing it: a test bounds what a computation does (function calls,
factorisations, evaluations of generated code), never how many seconds it took — the seconds
depend on the machine's load, the work does not."""
from __future__ import annotations

import gc
import sys
from collections import Counter
from typing import Any, Callable


def count_calls(func: Callable[..., Any], *args: Any, **kwargs: Any) -> tuple[Any, Counter]:
    """``func(*args, **kwargs)`` and a Counter of the Python-level calls it made, keyed by
    ``(file, function name)`` (file relative to site-packages or ``src/``, e.g.
    ``"scipy/sparse/linalg/_dsolve/linsolve.py"``); calls of C functions are keyed
    ``("C", name)``.  The garbage collector is off while it counts (collected before): its
    finalizers of other tests' objects are not ``func``'s calls (a run of the 55 hypothesis
    modules with ``--hypothesis-seed=20261210`` counted 5 more calls for 400 speeds than for 4
    in ``test_400_speeds_cost_the_python_work_of_4``)."""
    calls: Counter = Counter()

    def profile(frame, event, arg):
        if event == "call":
            f = frame.f_code.co_filename.replace("\\", "/")
            f = f.split("site-packages/")[-1].split("/src/")[-1]
            calls[(f, frame.f_code.co_name)] += 1
        elif event == "c_call":
            calls[("C", getattr(arg, "__name__", "?"))] += 1

    previous = sys.getprofile()
    enabled = gc.isenabled()
    gc.collect()
    gc.disable()
    sys.setprofile(profile)
    try:
        out = func(*args, **kwargs)
    finally:
        sys.setprofile(previous)
        if enabled:
            gc.enable()
    return out, calls


def named(calls: Counter, *names: str) -> int:
    """How many calls of functions with one of these names (any module)."""
    return sum(n for (_, name), n in calls.items() if name in names)


def in_files(calls: Counter, part: str) -> int:
    """How many calls of functions defined in files whose path contains `part`."""
    return sum(n for (f, _), n in calls.items() if part in f)


def total(calls: Counter) -> int:
    """All Python-level and C calls."""
    return sum(calls.values())
