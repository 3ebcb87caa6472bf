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
    assert cfg["package-data"]["propwhirl"] == ["data/*.toml"]


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
