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
