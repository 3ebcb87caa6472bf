"""The README's doublet-lattice example (issue 23, done-when: "aero = 'dlm' works from the
README on a fresh clone with the optional extra") runs as written, in a fresh interpreter, and
`make run` / `make test` install the extra it needs."""
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
README = (ROOT / "README.md").read_text(encoding="utf-8")
TITLE = "Doublet-lattice wings (optional extra)"


def _section() -> str:
    m = re.search(rf"^## {re.escape(TITLE)}\n(.*?)(?=^## |\Z)", README, flags=re.M | re.S)
    assert m, f"README has no section {TITLE!r}"
    return m.group(1)


def test_readme_dlm_example_runs(tmp_path):
    pytest.importorskip("panelaero")
    (code,) = re.findall(r"^```python\n(.*?)^```", _section(), flags=re.M | re.S)
    assert 'aero="dlm"' in code and "pip install propwhirl[dlm]" in _section()
    res = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, capture_output=True,
                         text=True, timeout=600)
    assert res.returncode == 0, res.stderr
    assert "Roger state space of doublet-lattice wing aerodynamics" in res.stdout
    assert "critical:" in res.stdout and "flutter" in res.stdout


def test_make_run_and_make_test_install_the_dlm_extra():
    makefile = (ROOT / "Makefile").read_text(encoding="utf-8")
    (run,) = re.findall(r"^run: \$\(VENV\)/\.stamp-([\w+]+)", makefile, flags=re.M)
    (every,) = re.findall(r"^ALL := \$\(VENV\)/\.stamp-([\w+]+)", makefile, flags=re.M)
    assert "dlm" in run.split("+") and "dlm" in every.split("+")
    assert re.search(r"^test: \$\(ALL\)", makefile, flags=re.M)
