"""File-system helpers shared by the tests of atomic writes and output checks."""
from pathlib import Path

import pytest


def unwritable_folder(tmp_path: Path) -> Path:
    """A folder no file can be created in: read-only permissions, or /sys for root (which
    permissions do not stop)."""
    folder = tmp_path / "ro"
    folder.mkdir()
    folder.chmod(0o555)
    try:
        (folder / "probe").write_text("x")
    except OSError:
        return folder
    (folder / "probe").unlink()
    if Path("/sys").is_dir():
        try:
            (Path("/sys") / "propwhirl-probe").write_text("x")
        except OSError:
            return Path("/sys")
    pytest.skip("no unwritable folder on this machine")
