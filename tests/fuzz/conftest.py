"""Shared set-up of the fuzz suite (issue 9): a small propeller-wing model file to mutate, the
outcome log, and the rule every case is held to.

Every generated input must give either a result whose every number is finite, or an
``InputError`` whose message is one line (naming the file where there is one) — never another
exception or a warning (warnings are errors inside a case).  No case is timed (issue 20.12:
the seconds depend on the machine's load): hypothesis runs without a deadline.
``PROPWHIRL_FUZZ_LOG=path`` appends one JSON line per case (category, outcome) for counting.
"""
from __future__ import annotations

import json
import os
import tomllib
import warnings
from contextlib import contextmanager
from pathlib import Path

import pytest
from hypothesis import HealthCheck, settings

from propwhirl.validate import InputError

ROOT = Path(__file__).resolve().parents[2]
FUZZ = settings(max_examples=150, deadline=None, derandomize=True,
                suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture])


def small_model_text() -> str:
    """examples/wingtip.toml with a 6-element wing (fast to analyse) and a short speed range."""
    doc = tomllib.loads((ROOT / "examples" / "wingtip.toml").read_text())
    doc["wing"]["n_elements"] = 6
    doc["installations"][0]["y_m"] = doc["wing"]["semi_span_m"]
    doc["flight"]["speed_range_m_per_s"] = [1.0, 350.0, 50.0]
    import tomli_w

    return tomli_w.dumps(doc)


def record(category: str, outcome: str) -> None:
    path = os.environ.get("PROPWHIRL_FUZZ_LOG")
    if path:
        with open(path, "a") as f:
            f.write(json.dumps({"category": category, "outcome": outcome}) + "\n")


@contextmanager
def held_to_the_rule(category: str, source: str | None = None):
    """Run one fuzz case: warnings are errors; an InputError must be one line (naming
    ``source`` when given) — or, a model file's every error at once, one such line per error
    (its ``errors``); anything else fails the test.  Records the outcome."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        try:
            yield
        except InputError as exc:
            lines = getattr(exc, "errors", None) or [str(exc)]
            assert "\n".join(lines) == str(exc), f"errors are not the message: {exc!s}"
            for msg in lines:
                assert "\n" not in msg, f"multi-line error: {msg!r}"
                assert msg.strip(), "empty error message"
                if source is not None:
                    assert source in msg, f"error does not name {source!r}: {msg}"
            record(category, "InputError")
            return
    record(category, "result")


@pytest.fixture(scope="session")
def base_text() -> str:
    return small_model_text()
