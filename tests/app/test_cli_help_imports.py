"""`propwhirl --help` builds every command's parser and prints: it must not import the model
package, the analyses, the studies' heavy modules or the file readers (it took ~2 s when a
help text's default, the speed of sound, imported propwhirl.model at parser build).  The
values named in help texts are read when a help is printed (cli_common.LazyHelpFormatter).
Counted in a fresh interpreter: modules, not time."""
from __future__ import annotations

import json
import subprocess
import sys

CODE = """
import json, runpy, sys
sys.argv = ["propwhirl"] + sys.argv[1:]
try:
    runpy.run_module("propwhirl", run_name="__main__")
except SystemExit:
    pass
sys.stdout = sys.__stdout__
print(json.dumps(sorted(m for m in sys.modules if m.startswith("propwhirl"))))
"""
HEAVY = ("propwhirl.model", "propwhirl.analysis", "propwhirl.engine", "propwhirl.generated",
         "propwhirl.io", "propwhirl.studies.sensitivity_check", "propwhirl.studies.paths")


def _imported(*argv: str) -> list[str]:
    res = subprocess.run([sys.executable, "-c", CODE, *argv], capture_output=True, text=True,
                         timeout=120)
    assert res.returncode == 0, res.stderr
    return json.loads(res.stdout.strip().splitlines()[-1])


def test_help_imports_no_model_package():
    mods = _imported("--help")
    heavy = [m for m in mods if m.startswith(HEAVY)]
    assert not heavy, heavy
    assert len(mods) <= 30, mods          # 26 (the CLI, validate, fileio, cases' registry ...)


def test_a_command_help_reads_its_lazy_values_when_printed():
    res = subprocess.run([sys.executable, "-m", "propwhirl", "derivatives", "--help"],
                         capture_output=True, text=True, timeout=120)
    assert res.returncode == 0 and "(default 330.80, ISA at 8000 ft" in res.stdout, res.stdout
    assert "«" not in res.stdout
    for argv, said in ((["sensitivity", "--help"], "p(1 +- 0.001)"),
                       (["export", "--help"], "mm-t-s (mm, t, s, N)")):
        out = subprocess.run([sys.executable, "-m", "propwhirl", *argv], capture_output=True,
                             text=True, timeout=120).stdout
        assert said in " ".join(out.split()) and "«" not in out, out
