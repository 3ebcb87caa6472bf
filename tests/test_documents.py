"""The documentation installed with the package (propwhirl.documents): the pages output refers
to are in a pip install, and `propwhirl docs` finds them there (issue 11, friction 9)."""
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from propwhirl import documents
from propwhirl.validate import InputError

ROOT = Path(__file__).resolve().parent.parent


def test_every_page_of_docs_is_a_document():
    assert set(documents.names()) == {p.stem for p in (ROOT / "docs").glob("*.md")}
    assert {"validation", "errata", "model-file"} <= set(documents.names())
    assert documents.text("errata") == (ROOT / "docs" / "errata.md").read_text(encoding="utf-8")
    assert documents.path("errata.md") == documents.path("errata")


def test_an_unknown_page_names_the_pages():
    with pytest.raises(InputError, match=r"document 'x' is invalid: must be one of .*validation"):
        documents.path("x")


def test_the_package_data_is_declared():
    import tomllib

    cfg = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]
    assert cfg["package-dir"]["propwhirl.docs"] == "docs"
    assert "propwhirl.docs" in cfg["packages"]
    assert cfg["package-data"]["propwhirl.docs"] == ["*.md"]


def test_an_install_holds_the_pages_and_the_output_names_the_installed_file(tmp_path):
    """Build the installed tree as a wheel holds it (setuptools' build_py: the packages and
    their package data, from a copy of the sources) and ask that propwhirl where its
    validation page is."""
    src = tmp_path / "src-copy"
    src.mkdir()
    for name in ("pyproject.toml", "README.md"):
        shutil.copy(ROOT / name, src / name)
    for folder in ("src", "generated", "docs"):
        shutil.copytree(ROOT / folder, src / folder,
                        ignore=shutil.ignore_patterns("__pycache__", "*.egg-info"))
    lib = tmp_path / "lib"
    build = subprocess.run([sys.executable, "-c", "import setuptools; setuptools.setup()",
                            "--quiet", "build_py", "--build-lib", str(lib)], cwd=src,
                           capture_output=True, text=True, timeout=600)
    assert build.returncode == 0, build.stderr[-2000:]
    for page in ("validation", "errata", "model-file"):
        assert (lib / "propwhirl" / "docs" / f"{page}.md").is_file(), page
    assert not (lib / "propwhirl" / "docs" / "__init__.py").exists()
    code = "from propwhirl import documents; print(documents.cite('validation'))"
    run = subprocess.run([sys.executable, "-I", "-c", f"import sys; sys.path.insert(0, "
                          f"{str(lib)!r}); {code}"], capture_output=True, text=True,
                         timeout=120, cwd=tmp_path)
    assert run.returncode == 0, run.stderr
    installed = lib / "propwhirl" / "docs" / "validation.md"
    assert run.stdout == f"`propwhirl docs validation` ({installed})\n"
    assert installed.read_text(encoding="utf-8") == (ROOT / "docs" / "validation.md").read_text(
        encoding="utf-8")
