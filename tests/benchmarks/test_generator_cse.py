"""benchmarks/generator_cse.py rewrites only its own section of docs/performance.md."""
import importlib.util
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def load():
    spec = importlib.util.spec_from_file_location("generator_cse", ROOT / "benchmarks" / "generator_cse.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def test_markdown_section_is_replaced_between_its_markers_only(tmp_path):
    g = load()
    doc = tmp_path / "performance.md"
    doc.write_text(f"# Top\n\nother section\n\n{g.TITLE}\n\nprose\n\n{g.BEGIN}\nold table\n{g.END}\n\nafter\n")
    g.write_markdown(doc, "new table")
    assert doc.read_text() == (
        f"# Top\n\nother section\n\n{g.TITLE}\n\nprose\n\n{g.BEGIN}\nnew table\n{g.END}\n\nafter\n"
    )


def test_markdown_section_is_appended_when_absent(tmp_path):
    g = load()
    doc = tmp_path / "performance.md"
    doc.write_text("# Top\n\ntext\n")
    g.write_markdown(doc, "table")
    assert doc.read_text() == f"# Top\n\ntext\n\n{g.TITLE}\n\n{g.BEGIN}\ntable\n{g.END}\n"


def test_committed_docs_hold_the_section_once():
    g = load()
    text = (ROOT / "docs" / "performance.md").read_text()
    assert text.count(g.BEGIN) == text.count(g.END) == text.count(g.TITLE) == 1
    assert text.index(g.TITLE) < text.index(g.BEGIN) < text.index(g.END)
