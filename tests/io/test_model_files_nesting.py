"""Deeply nested model files: a one-line InputError naming the file, never a RecursionError."""
from __future__ import annotations

import pytest

from propwhirl import io
from propwhirl.limits import MAX_NESTING
from propwhirl.validate import InputError


@pytest.mark.parametrize("text", [
    "x = " + "[" * 10_000 + "]" * 10_000,                      # the 10,000 arrays
    "x = " + "{a = " * 5_000 + "1" + "}" * 5_000,              # and 5,000 inline tables
    'type = "propeller"\npropeller = ' + "[" * 900 + "]" * 900,
    "x = " + "[" * 40 + "]" * 40,                              # parsed, then refused
    "[" + ".".join(["t"] * 40) + "]\nv = 1",                   # dotted table headers
], ids=["arrays-10000", "inline-tables-5000", "value-900", "arrays-40", "headers-40"])
def test_deep_nesting_is_one_line_naming_the_file(text, tmp_path):
    path = tmp_path / "deep.toml"
    path.write_text(text)
    with pytest.raises(InputError) as exc:
        io.load_model(path)
    msg = str(exc.value)
    assert msg.startswith(str(path)) and "\n" not in msg
    assert f"nesting deeper than {MAX_NESTING} levels" in msg
    assert exc.value.__cause__ is None or not isinstance(exc.value.__cause__, RecursionError)


def test_shallow_nesting_reaches_the_model_checks():
    with pytest.raises(InputError, match="missing key 'type' at the top level") as exc:
        io.loads("x = " + "[" * 30 + "]" * 30, "f.toml")
    assert "nesting" not in str(exc.value)
