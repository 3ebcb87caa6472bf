"""Fuzz: TOML model files mutated as a hostile user would (values of any type and size, keys
removed, unknown or duplicated, truncated or corrupted text, deep nesting)."""
from __future__ import annotations

import json
import math
import tomllib

import numpy as np
import tomli_w
from hypothesis import given
from hypothesis import strategies as st

from fuzz.conftest import FUZZ, held_to_the_rule
from propwhirl.analysis import analyse
from propwhirl.io import loads

SOURCE = "fuzz.toml"

VALUES = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True),
    st.sampled_from([0.0, -1.0, 1e-300, 1e300, -1e300, 1e-9, 1e9, 1e12, 1e15]),
    st.integers(min_value=-10**12, max_value=10**12),
    st.text(max_size=20), st.booleans(),
    st.lists(st.floats(allow_nan=True, allow_infinity=True), max_size=4),
    st.dictionaries(st.text(min_size=1, max_size=5), st.integers(), max_size=2),
)


def _leaves(doc, path=()):
    """Every (container, key) of a leaf value, inside tables and arrays of tables."""
    out = []
    items = doc.items() if isinstance(doc, dict) else enumerate(doc)
    for k, v in items:
        if isinstance(v, dict) or (isinstance(v, list) and v and isinstance(v[0], dict)):
            out += _leaves(v, path + (k,))
        else:
            out.append((doc, k))
    return out


def _check_model(model) -> None:
    """A loaded model's analysis: every number finite, the result file without NaN/inf."""
    a = analyse(model)
    assert np.isfinite(a.sweep.eigenvalues).all() and np.isfinite(a.sweep.V).all()
    assert all(math.isfinite(e.V) and math.isfinite(e.frequency_hz) for e in a.events)
    json.dumps(a.to_dict(), allow_nan=False)


def _scaled(value, data):
    """A plausible neighbour of a numeric value: scaled by 10^u, u in [-2, 2], maybe negated."""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return data.draw(VALUES, label="value")
    f = 10.0 ** data.draw(st.floats(-2.0, 2.0), label="log10 factor")
    out = value * f if value != 0 else f - 1.0
    if data.draw(st.integers(0, 9), label="negate") == 0:
        out = -out
    return int(round(out)) if isinstance(value, int) else out


def mutate(doc, data, kinds) -> None:
    """Mutate the TOML document `doc` in place 1–3 times: at a drawn leaf, a kind drawn from
    `kinds` — "scaled" (:func:`_scaled`), "value" (any of :data:`VALUES`), "delete" the key, or
    "unknown" (a key the schema does not know).  Shared by the fuzz cases of every TOML file."""
    leaves = _leaves(doc)
    for _ in range(data.draw(st.integers(1, 3), label="mutations")):
        container, key = data.draw(st.sampled_from(leaves), label="leaf")
        kind = data.draw(st.sampled_from(list(kinds)), label="kind")
        if kind == "scaled":
            container[key] = _scaled(container[key], data)
        elif kind == "value":
            container[key] = data.draw(VALUES, label="value")
        elif kind == "delete" and isinstance(container, dict):
            container.pop(key, None)
        elif isinstance(container, dict):
            container[data.draw(st.text("abcdefgh_", min_size=1, max_size=8))] = 1.0
        leaves = _leaves(doc)


@FUZZ
@given(data=st.data())
def test_mutated_values(base_text, data):
    doc = tomllib.loads(base_text)
    mutate(doc, data, ("scaled", "scaled", "scaled", "value", "delete", "unknown"))
    text = tomli_w.dumps(doc)
    with held_to_the_rule("toml: mutated values/keys", SOURCE):
        _check_model(loads(text, SOURCE))


@FUZZ
@given(cut=st.integers(min_value=0, max_value=5000), junk=st.binary(max_size=8))
def test_truncated_and_corrupted_text(base_text, cut, junk):
    raw = base_text.encode()
    cut = min(cut, len(raw))
    text = (raw[:cut] + junk + raw[cut:]).decode("utf-8", errors="replace")
    with held_to_the_rule("toml: truncated/corrupted text", SOURCE):
        loads(text, SOURCE)


@FUZZ
@given(depth=st.integers(min_value=1, max_value=20000), inline=st.booleans())
def test_deep_nesting(depth, inline):
    body = ("{a = " * depth + "1" + "}" * depth) if inline else ("[" * depth + "]" * depth)
    with held_to_the_rule("toml: deep nesting", SOURCE):
        loads(f"format = \"propwhirl-model\"\nformat_version = 1\nx = {body}\n", SOURCE)
