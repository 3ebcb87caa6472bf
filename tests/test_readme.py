"""The README's Python and command-line examples are a contract with users: they run as written.

The Python block of "Using it" runs in a fresh interpreter; every command of its shell block
runs in one temporary folder (``propwhirl`` as ``python -m propwhirl``): the one that saves the
model the others read first, then the others two at a time (the machine's two cores; each
writes its own files).  The
reproduction commands of "Reproducing the thesis" run too (the full one is long).
"""
import re
import shlex
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import pytest

README = (Path(__file__).resolve().parent.parent / "README.md").read_text()


def _section(title: str) -> str:
    m = re.search(rf"^## {re.escape(title)}\n(.*?)(?=^## |\Z)", README, flags=re.M | re.S)
    assert m, f"README has no section {title!r}"
    return m.group(1)


def _blocks(text: str, lang: str) -> list[str]:
    return re.findall(rf"^```{lang}\n(.*?)^```", text, flags=re.M | re.S)


def _commands(block: str) -> list[list[str]]:
    """Shell commands of a block: continuation lines joined, comments dropped."""
    joined = re.sub(r"\\\n\s*", " ", block)
    out = []
    for line in joined.splitlines():
        line = line.split("#", 1)[0].strip()
        if line:
            out.append(shlex.split(line))
    return out


def _run(argv: list[str], cwd: Path, timeout: float = 600) -> subprocess.CompletedProcess:
    assert argv[0] == "propwhirl", argv
    res = subprocess.run([sys.executable, "-m", "propwhirl", *argv[1:]], cwd=cwd,
                         capture_output=True, text=True, timeout=timeout)
    assert res.returncode == 0, f"{' '.join(argv)} failed:\n{res.stdout}\n{res.stderr}"
    return res


def _run_all(cmds: list[list[str]], cwd: Path) -> list[subprocess.CompletedProcess]:
    """:func:`_run` of each command, two at a time (independent commands: each writes its own
    files), their results in the commands' order."""
    with ThreadPoolExecutor(max_workers=2) as pool:
        return list(pool.map(lambda argv: _run(argv, cwd), cmds))


def test_python_example_runs(tmp_path):
    (code,) = _blocks(_section("Using it"), "python")
    res = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, capture_output=True,
                         text=True, timeout=600)
    assert res.returncode == 0, res.stderr
    assert "critical:" in res.stdout
    assert (tmp_path / "a.json").stat().st_size > 0 and (tmp_path / "vgf.png").stat().st_size > 0


def test_command_line_examples_run(tmp_path):
    (block,) = _blocks(_section("Using it"), "sh")
    cmds = _commands(block)
    assert len(cmds) >= 7
    for argv in cmds:                  # the model the others read, first
        if "--save" in argv:
            _run(argv, tmp_path)
    _run_all([argv for argv in cmds if "--save" not in argv], tmp_path)
    for f in ("out/report.txt", "wingtip.toml", "vgf.png", "a.json", "vgf.csv", "campbell.png",
              "sweep.png", "map.png", "boundary.png"):
        assert (tmp_path / f).stat().st_size > 0, f


def test_many_propeller_examples_run(tmp_path):
    """"Many propellers": the commands as written, from a copy of the repository's examples
    (they name examples/...); the figures, the campaign's report and the margin line."""
    import shutil

    root = Path(__file__).resolve().parent.parent
    shutil.copytree(root / "examples", tmp_path / "examples",
                    ignore=shutil.ignore_patterns("certification", "*.ipynb", "figures"))
    (block,) = _blocks(_section("Many propellers"), "sh")
    outs = _run_all(_commands(block), tmp_path)
    assert "margin to 1.15 V_D" in outs[0].stdout
    assert "propellers 1–6" in outs[0].stdout
    assert "propeller 7 at 0.3111 x RPM" in outs[1].stdout     # the cruise propeller's own rpm
    assert "critical: divergence" in outs[2].stdout             # folded: no whirl flutter
    for f in ("x57_vgf.png", "x57_campbell.png", "report/report.html", "report/campaign.csv"):
        assert (tmp_path / f).stat().st_size > 0, f


@pytest.mark.long
def test_reproduction_examples_run(tmp_path, monkeypatch, capsys, reproduction_records):
    """The commands as written, through the CLI in this process; the reproduction itself is
    the session's one run (tests/conftest.py), selected by ``--only`` as the harness does."""
    from propwhirl.app import cli
    from propwhirl.reproduce import harness

    asked = []

    def session_run(only=None, processes=1, **options):
        asked.append((list(only) if only else None, processes))
        return [r for r in reproduction_records
                if not only or any(r.id.startswith(o) for o in only)]

    monkeypatch.setattr(harness, "run", session_run)
    monkeypatch.chdir(tmp_path)
    (block,) = _blocks(_section("Reproducing the thesis"), "sh")
    cmds = _commands(block)
    assert [c[:2] for c in cmds] == [["propwhirl", "reproduce"]] * 2
    (tmp_path / "out").mkdir()
    for argv in cmds:
        assert cli.main(argv[1:]) == 0, " ".join(argv)
        assert "t7.2/first_bending" in capsys.readouterr().out
    assert asked == [(None, 1), (["t7", "t9.5"], 2)]
    assert (tmp_path / "out" / "records.json").stat().st_size > 0


def test_make_run_installs_what_the_python_example_needs():
    """Issue 25.8: the Python example failed after `make run` (to_dataframe needs the `data`
    extra, which `make run` did not install): the extras of `make run`'s set-up cover every
    optional library the example uses."""
    makefile = (Path(__file__).resolve().parent.parent / "Makefile").read_text()
    (stamp,) = re.findall(r"^run: \$\(VENV\)/\.stamp-([\w+]+)", makefile, flags=re.M)
    extras = set(stamp.split("+"))
    (code,) = _blocks(_section("Using it"), "python")
    needs = {"data": "to_dataframe(", "plots": "plots.", "tables": "summary()"}
    assert {extra for extra, use in needs.items() if use in code} <= extras


def test_modal_route_examples_run(tmp_path):
    """"Modal structures through a campaign" (issue 34): the Python block writes the modal
    model file from a copy of the repository's examples, then the commands run as written;
    the analysis and the campaign's critical events name the propellers that whirl."""
    import shutil

    root = Path(__file__).resolve().parent.parent
    shutil.copytree(root / "examples", tmp_path / "examples",
                    ignore=shutil.ignore_patterns("certification", "*.ipynb", "figures",
                                                  "four_propeller_modal.*"))
    section = _section("Modal structures through a campaign")
    (code,) = _blocks(section, "python")
    res = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, capture_output=True,
                         text=True, timeout=600)
    assert res.returncode == 0, res.stderr
    assert (tmp_path / "examples" / "four_propeller_modal.modes.npz").stat().st_size > 0
    (block,) = _blocks(section, "sh")
    cmds = _commands(block)
    assert [c[:2] for c in cmds] == [["propwhirl", "analyse"], ["propwhirl", "certify"]]
    analysed, certified = _run_all(cmds, tmp_path)
    assert "(modal)" in analysed.stdout and "backward whirl, propellers 1–4" in analysed.stdout
    assert "CLEARED" in certified.stdout and "NOT CLEARED" not in certified.stdout
    for j in range(1, 5):       # each mount at 50 %: the critical event names its propeller
        row = next(ln for ln in certified.stdout.splitlines()
                   if ln.startswith(f"mount stiffness at 50 % (propeller {j})"))
        assert f"whirl, propeller {j}" in row, row
    assert (tmp_path / "modal_report" / "report.html").stat().st_size > 0
