"""benchmarks/design_size.py: its table builder on tiny models, and its section of docs/performance.md."""
import importlib.util
import re
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]


def load():
    spec = importlib.util.spec_from_file_location("design_size", ROOT / "benchmarks" / "design_size.py")
    mod = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = mod          # its dataclasses look their module up
    spec.loader.exec_module(mod)
    return mod


def _table(text, header_start):
    """The rows (lists of cells) of the markdown table whose header starts with `header_start`."""
    lines = text.splitlines()
    i = next(k for k, line in enumerate(lines) if line.startswith(header_start))
    rows = []
    for line in lines[i:]:
        if not line.startswith("|"):
            break
        rows.append([c.strip() for c in re.split(r"(?<!\\)\|", line.strip("|"))])  # not \|
    return rows[0], rows[2:]


def test_design_models_place_the_last_propeller_at_the_tip():
    d = load()
    m = d.design(8, 4)
    ys = [p.y for p in m.propellers]
    assert len(ys) == 4 and ys == sorted(ys)
    assert ys[-1] == max(m.wing.node_y)


def test_table_builder_on_tiny_models():
    d = load()
    res = d.run(configs=((4, 1), (6, 2)), case_a=(6, 2), big=(6, 2), small=(4, 1), repeats=1,
                wingtip_factory=lambda: d.design(4, 1), grid_speeds=np.arange(1.0, 351.0, 5.0))
    text = d.report(res)
    assert re.search(r"\*\*\d+ cores\*\*", text)
    head, rows = _table(text, "| elements / propellers")
    assert head == ["elements / propellers", "propellers placed", "states", "method",
                    "reduced states", "runs", "wall [s]", "CPU [s]"]
    assert [r[0] for r in rows] == ["4/1", "6/2"]
    for r in rows:
        assert int(r[2]) > 0 and r[3] in ("dense", "reduced") and float(r[7]) > 0
    assert "Ratio 6/2 / 4/1:" in text
    head, rows = _table(text, "| event | kind | mode (")
    # the default reduces every wing (issue 26), the tiny ones too
    assert head[3:6] == ["V reduced [m/s]", "V dense [m/s]", "ΔV [m/s]"] and len(head) == 9
    assert rows and all(len(r) == 9 for r in rows)
    assert "Same crossings: **True**" in text
    head, rows = _table(text, "| method | states")
    assert [r[0] for r in rows] == ["fixed grid", "reduced", "default (reduced)"]
    assert len(head) == 9 and all(r[8] in ("True", "False", "") for r in rows)
    head, rows = _table(text, "| event | kind | mode | V converged")
    assert rows and all(len(r) == 6 for r in rows)
    assert "tracemalloc peak" in text and res.memory["tracemalloc_peak_mb"] > 0


def test_markdown_section_is_replaced_between_its_markers_only(tmp_path):
    d = load()
    doc = tmp_path / "performance.md"
    doc.write_text(f"# Top\n\n{d.TITLE}\n\nprose\n\n{d.BEGIN}\nold table\n{d.END}\n\nafter\n")
    d.write_markdown(doc, "new table")
    assert doc.read_text() == f"# Top\n\n{d.TITLE}\n\nprose\n\n{d.BEGIN}\nnew table\n{d.END}\n\nafter\n"


def test_markdown_section_is_appended_when_absent(tmp_path):
    d = load()
    doc = tmp_path / "performance.md"
    doc.write_text("# Top\n\ntext\n")
    d.write_markdown(doc, "table")
    assert doc.read_text() == f"# Top\n\ntext\n\n{d.TITLE}\n\n{d.BEGIN}\ntable\n{d.END}\n"


def test_committed_docs_hold_the_section_once():
    d = load()
    text = (ROOT / "docs" / "performance.md").read_text()
    assert text.count(d.BEGIN) == text.count(d.END) == text.count(d.TITLE) == 1
    assert text.index(d.TITLE) < text.index(d.BEGIN) < text.index(d.END)
