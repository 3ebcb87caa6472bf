"""benchmarks/generated_form.py: its line counts by kind of function, its comparison of two
reproduction outputs, and its own section of docs/performance.md (nothing timed here)."""
import importlib.util
import json
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def load():
    spec = importlib.util.spec_from_file_location("generated_form", ROOT / "benchmarks" / "generated_form.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


MODULE = '''"""doc"""
OUTPUTS = {"A": ((), (), (), ""), "B": ((), (), (), ""), "C": ((), (), (), "")}
BLOCKS = {"blocks": ((), ("A", "B"))}
VIEWS = {"A": "blocks"}
PARTIALS = {"blocks_d": ((), {})}


def _broadcast():
    pass


def blocks():
    x = 1
    return x


def A():
    return 1


def B():
    x = 1
    y = 2
    return x


def C():
    return 3


def blocks_d():
    return 4
'''


def test_lines_are_counted_by_kind_of_function():
    g = load()
    assert g.kind_lines(MODULE) == {
        "block functions": 3, "per-matrix code (matrices in a block)": 4, "views": 2,
        "matrices in no block": 2, "derivative functions": 2, "helpers": 2,
        "file": MODULE.count("\n"),
    }


def records(values: dict) -> str:
    return json.dumps({"records": [{"id": i, "computed": v, "within_tol": ok}
                                   for i, (v, ok) in values.items()]})


def test_reproduction_change_against_the_last_printed_digit(tmp_path):
    """%.5g of 286.87093 prints 286.87: one unit of the last digit is 0.01."""
    g = load()
    before, after = tmp_path / "before.json", tmp_path / "after.json"
    before.write_text(records({"a": (286.87093, True), "b": (1.0, True), "c": (None, False),
                               "d": (0.012345, True)}))
    after.write_text(records({"a": (286.87118, True), "b": (1.0, True), "c": (None, False),
                              "d": (0.012365, False)}))
    out = g.reproduce_change(before, after)
    assert (out["n"], out["computed"], out["moved"]) == (4, 3, 2)
    assert out["max_id"] == "d" and out["max_rel_change"] == pytest.approx(0.02 / 12.345)
    assert out["printed_changed"] == ["d"] and out["beyond_last_digit"] == ["d"]
    assert out["within_tol_changed"] == ["d"]
    assert g.last_digit(286.87093) == pytest.approx(0.01) and g.last_digit(0.012345) == pytest.approx(1e-6)


def test_reproduction_outputs_with_different_ids_are_refused(tmp_path):
    g = load()
    before, after = tmp_path / "before.json", tmp_path / "after.json"
    before.write_text(records({"a": (1.0, True)}))
    after.write_text(records({"b": (1.0, True)}))
    with pytest.raises(ValueError, match="different ids"):
        g.reproduce_change(before, after)


def test_committed_docs_hold_the_section_once():
    g = load()
    text = (ROOT / "docs" / "performance.md").read_text()
    assert text.count(g.BEGIN) == text.count(g.END) == text.count(g.TITLE) == 1
    assert text.index(g.TITLE) < text.index(g.BEGIN) < text.index(g.END)
