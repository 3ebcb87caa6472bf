"""Every runtime package (and the generated modules) is listed for installation."""
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def test_every_package_directory_is_installed():
    cfg = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]
    listed = set(cfg["packages"])
    found = {
        "propwhirl" + "".join("." + part for part in p.parent.relative_to(ROOT / "src" / "propwhirl").parts)
        for p in (ROOT / "src" / "propwhirl").rglob("__init__.py")
    }
    assert found <= listed, f"not installed: {sorted(found - listed)}"
    assert "propwhirl.generated" in listed and cfg["package-dir"]["propwhirl.generated"] == "generated"
    assert cfg["package-data"]["propwhirl"] == ["data/*.toml", "app/templates/*.html"]


def test_markers_name_only_existing_make_targets():
    """The `long` marker's description and the Makefile agree (targets named exist, and the
    fast target deselects exactly that marker)."""
    import re

    cfg = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["pytest"]["ini_options"]
    makefile = (ROOT / "Makefile").read_text()
    targets = set(re.findall(r"^([a-z][a-z-]*):", makefile, flags=re.M))
    (long,) = [m for m in cfg["markers"] if m.startswith("long:")]
    named = set(re.findall(r"`make ([a-z-]+)`", long))
    assert named and named <= targets, (named, targets)
    assert re.search(r"^test-fast:.*\n\t.*-m \"not long\"", makefile, flags=re.M)


def test_the_nastran_extra_lives_in_an_environment_of_its_own():
    """pyNastran needs numpy < 2: the `nastran` extra is in no set of the main environment's
    stamps (pip would drop it to numpy 1.26), and `make test` runs tests/nastran in
    .venv-nastran, built by one pip request."""
    import re

    extras = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"][
        "optional-dependencies"]
    assert any(r.replace(" ", "") == "numpy<2" for r in extras["nastran"])
    makefile = (ROOT / "Makefile").read_text()
    main_sets = re.findall(r"\$\(VENV\)/\.stamp-([a-z+]+)", makefile)
    assert main_sets and all("nastran" not in s.split("+") for s in main_sets), main_sets
    recipe = re.search(r"^\$\(NASTRAN_STAMP\):.*\n((?:\t.*\n)+)", makefile, flags=re.M).group(1)
    assert recipe.count("pip install") == 1 and "nastran," in recipe
    test = re.search(r"^test:(.*)\n((?:\t.*\n)+)", makefile, flags=re.M)
    assert "$(NASTRAN_STAMP)" in test.group(1)
    assert "$(NASTRAN_VENV)/bin/python -m pytest -q tests/nastran $(NUMPY1_TESTS)" in test.group(2)


def test_the_numpy1_checks_are_test_files():
    """`make test` runs NUMPY1_TESTS in .venv-nastran too (numpy 1.26: issue 36, item 2): each
    one a test module of the suite."""
    import re

    makefile = (ROOT / "Makefile").read_text()
    listed = re.search(r"^NUMPY1_TESTS :=((?:.*\\\n)*.*)$", makefile, flags=re.M).group(1)
    files = listed.replace("\\", " ").split()
    assert len(files) >= 4 and all((ROOT / f).is_file() and Path(f).name.startswith("test_")
                                   for f in files), files
