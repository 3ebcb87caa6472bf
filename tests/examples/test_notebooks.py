"""The example notebooks (examples/*.ipynb) run from top to bottom on an IPython kernel
(nbclient; the ``notebooks`` extra), in the examples folder, and their figures display inline
as PNG images (a figure object at the end of a cell, no magics).  The NASTRAN walkthrough
reads a BDF, which needs pyNastran (numpy < 2): it runs in .venv-nastran
(tests/nastran/test_walkthrough_notebook.py) and is skipped here where pyNastran is not."""
from __future__ import annotations

import base64
import importlib.util
from pathlib import Path

import pytest

nbformat = pytest.importorskip("nbformat")
nbclient = pytest.importorskip("nbclient")
pytest.importorskip("ipykernel")

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
NOTEBOOKS = sorted(EXAMPLES.glob("*.ipynb"))
#: notebooks that end in a figure, and how many figures each shows
FIGURES = {"quick_start": 1, "design_study": 1, "nastran_walkthrough": 1}
#: notebooks that need pyNastran, run in .venv-nastran (make test-nastran)
NASTRAN = {"nastran_walkthrough"}
HAVE_PYNASTRAN = importlib.util.find_spec("pyNastran") is not None
PNG = b"\x89PNG\r\n\x1a\n"


def test_the_five_notebooks_are_there():
    assert [p.stem for p in NOTEBOOKS] == ["design_study", "generated_equations",
                                          "nastran_walkthrough", "own_model", "quick_start"]


def test_notebooks_are_committed_without_outputs():
    for path in NOTEBOOKS:
        book = nbformat.read(path, as_version=4)
        code = [c for c in book.cells if c.cell_type == "code"]
        assert all(not c.outputs and c.execution_count is None for c in code), path.name


def run(path: Path):
    """The notebook at `path` executed (a failing cell raises CellExecutionError)."""
    book = nbformat.read(path, as_version=4)
    client = nbclient.NotebookClient(book, timeout=300, kernel_name="python3",
                                     resources={"metadata": {"path": str(EXAMPLES)}})
    client.execute()
    return book


@pytest.fixture(scope="module")
def executed():
    return {}


@pytest.mark.parametrize("path", NOTEBOOKS, ids=[p.stem for p in NOTEBOOKS])
def test_notebook_runs_and_shows_its_figures(path, executed):
    if path.stem in NASTRAN and not HAVE_PYNASTRAN:
        pytest.skip(f"{path.name} reads a NASTRAN deck, which needs pyNastran (numpy < 2): "
                    "it runs in .venv-nastran (make test-nastran)")
    book = run(path)
    executed[path.stem] = check_outputs(book, path.stem)


def check_outputs(book, stem: str) -> str:
    """The executed notebook's text, once its outputs are checked: no error, its figures
    (FIGURES) PNG images, no figure shown as its repr."""
    outputs = [o for c in book.cells if c.cell_type == "code" for o in c.outputs]
    assert not [o for o in outputs if o.output_type == "error"]
    images = [base64.b64decode(o.data["image/png"]) for o in outputs
              if o.output_type in ("execute_result", "display_data") and "image/png" in o.data]
    assert len(images) == FIGURES.get(stem, 0)
    assert all(im.startswith(PNG) and len(im) > 10_000 for im in images)
    texts = [o.data.get("text/plain", "") for o in outputs if "data" in o]
    assert not any(t.startswith("<Figure size") for t in texts)   # an image, not its repr
    return "\n".join(o.get("text", "") for o in outputs) + "\n".join(texts)


def test_the_notebooks_say_what_they_show(executed):
    if len(executed) < len([p for p in NOTEBOOKS if p.stem not in NASTRAN]):
        pytest.skip("the notebooks did not all run")
    assert "critical: divergence of wing 1" in executed["quick_start"]
    assert "propeller 1 theta" in executed["own_model"]
    assert "largest difference:" in executed["generated_equations"]
    assert "nacelle stiffness" in executed["design_study"]
