"""The study commands' execution options (issue 12, items 5–6) on `propwhirl reproduce`:
progress on stderr — a bar on a terminal, plain lines on a pipe (issue 37, item 3), never
with --quiet —, an interrupted run resumed with --resume to the same records, --scheduler on a
Dask cluster; the spinner of `propwhirl analyse` and the count of its doublet-lattice AICs."""
from __future__ import annotations

import io
import json
import os
import re
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from propwhirl import progress
from propwhirl.app import cli
from propwhirl.model.aerodynamics.dlm_rfa import TRACKING_K_NODES
from propwhirl.reproduce import harness

ONLY = ["t4.1", "t7.2"]            # two quick cases


class FakeTTY(io.StringIO):
    def isatty(self) -> bool:
        return True


@pytest.fixture
def no_delay(monkeypatch):
    """Bars and spinners appear at once (the 2 s delay would hide them in a quick run)."""
    monkeypatch.setattr(progress, "DELAY", 0.0)


def run_with_stderr(monkeypatch, stream, argv) -> int:
    monkeypatch.setattr(sys, "stderr", stream)
    return cli.main(argv)


def test_a_terminal_shows_the_reproduction_bar_and_quiet_hides_it(monkeypatch, no_delay, capsys):
    tty = FakeTTY()
    assert run_with_stderr(monkeypatch, tty, ["reproduce", "--only", *ONLY]) == 0
    assert "reproduce" in tty.getvalue() and "2/2" in tty.getvalue()
    quiet = FakeTTY()
    assert run_with_stderr(monkeypatch, quiet, ["reproduce", "--only", *ONLY, "--quiet"]) == 0
    assert quiet.getvalue() == ""
    pipe = io.StringIO()                        # not a terminal: plain lines
    assert run_with_stderr(monkeypatch, pipe, ["reproduce", "--only", *ONLY]) == 0
    lines = pipe.getvalue().splitlines()
    assert "\r" not in pipe.getvalue()
    assert lines[0].startswith("reproduce: 0 of 2 (0 %), ")
    assert lines[-1].startswith("reproduce: 2 of 2 (100 %), done in ")
    assert "within tolerance" in capsys.readouterr().out


#: progress at once and at every report (the delay and interval off), so that a quick run
#: shows every count: the lines are bounded by counts, never by elapsed time
EVERY_REPORT = {"PROPWHIRL_PROGRESS_DELAY": "0", "PROPWHIRL_PROGRESS_INTERVAL": "0"}


def run_piped(argv: list[str]) -> subprocess.CompletedProcess:
    """`propwhirl ARGV` in a process of its own, stdout and stderr pipes (not terminals)."""
    env = dict(os.environ, **EVERY_REPORT)
    return subprocess.run([sys.executable, "-m", "propwhirl", *argv], capture_output=True,
                          text=True, timeout=600, env=env)


def progress_lines(stderr: str, desc: str) -> list[str]:
    return [line for line in stderr.splitlines() if line.startswith(f"{desc}: ")]


def test_a_pipe_gets_a_line_of_every_count_and_quiet_none():
    """A real process whose stderr is a pipe (issue 37, item 3): `reproduce` writes plain
    lines — what, how far, the time — of every count 0, 1, 2 of its cases, the last one
    `done in`; with --quiet none."""
    r = run_piped(["reproduce", "--only", *ONLY])
    assert r.returncode == 0, r.stderr
    lines = progress_lines(r.stderr, "reproduce")
    assert "\r" not in r.stderr and lines == r.stderr.splitlines()
    assert {int(re.match(r"reproduce: (\d+) of 2 ", line).group(1)) for line in lines} == {0, 1, 2}
    assert re.fullmatch(r"reproduce: 2 of 2 \(100 %\), done in \d+ s", lines[-1])
    assert "within tolerance" in r.stdout
    quiet = run_piped(["reproduce", "--only", *ONLY, "--quiet"])
    assert quiet.returncode == 0 and quiet.stderr == ""


def test_analyse_on_a_pipe_counts_its_doublet_lattice_aics(small_dlm_file):
    """`propwhirl analyse` of a doublet-lattice wing, stderr a pipe: the count of the AICs its
    Roger fit reads (8 reduced frequencies x 1 Mach column), every one from 0 to 8, with
    the estimate of the time left, then the elapsed time to `done in`; with --quiet none."""
    argv = ["analyse", str(small_dlm_file), "--speeds", "100", "290", "10"]
    r = run_piped(argv)
    assert r.returncode == 0, r.stderr
    assert "\r" not in r.stderr
    lines = progress_lines(r.stderr, "analysing small DLM tip model")
    counted = [re.search(r": doublet-lattice AICs (\d+) of (\d+) \(", line) for line in lines]
    counts = [(int(m.group(1)), int(m.group(2))) for m in counted if m]
    n = len(TRACKING_K_NODES)                # the modal state space's fit, one Mach column
    assert {total for _, total in counts} == {n}
    assert {done for done, _ in counts} == set(range(n + 1))
    assert any(", est. " in line and " left" in line for line in lines)
    assert re.fullmatch(r"analysing small DLM tip model: done in \d+ s", lines[-1])
    assert "critical:" in r.stdout
    quiet = run_piped(argv + ["--quiet"])
    assert quiet.returncode == 0, quiet.stderr
    assert progress_lines(quiet.stderr, "analysing small DLM tip model") == []
    assert quiet.stdout == r.stdout


def test_an_interrupted_reproduction_resumes_to_the_same_records(monkeypatch, tmp_path, capsys):
    plain = tmp_path / "plain.json"
    assert cli.main(["reproduce", "--only", *ONLY, "--json", str(plain)]) == 0
    assert not Path(str(plain) + ".partial").exists()   # removed once the records are written

    out = tmp_path / "records.json"
    partial = Path(str(out) + ".partial")
    real_call = harness._call

    def interrupted_at_t7(item):
        if item[0] == "t7.2":
            raise KeyboardInterrupt
        return real_call(item)

    monkeypatch.setattr(harness, "_call", interrupted_at_t7)
    capsys.readouterr()
    assert cli.main(["reproduce", "--only", *ONLY, "--json", str(out)]) == cli.EXIT_INTERRUPTED
    err = capsys.readouterr().err
    assert "interrupted: 1 of 2 points finished kept in" in err and "--resume" in err
    assert partial.exists() and not out.exists()
    assert [p["key"] for p in json.loads(partial.read_text())["points"]] == ["t4.1"]

    def not_t4(item):
        assert item[0] != "t4.1", "a finished case was computed again"
        return real_call(item)

    monkeypatch.setattr(harness, "_call", not_t4)
    assert cli.main(["reproduce", "--only", *ONLY, "--json", str(out), "--resume"]) == 0
    assert json.loads(out.read_text()) == json.loads(plain.read_text())
    assert not partial.exists()


def test_resume_needs_an_output_file(capsys):
    assert cli.main(["reproduce", "--only", "t4.1", "--resume"]) == 2
    assert "--resume needs the output file" in capsys.readouterr().err


def test_a_scheduler_runs_the_reproduction_on_dask(tmp_path, capsys):
    distributed = pytest.importorskip("distributed")
    plain, on_dask = tmp_path / "a.json", tmp_path / "b.json"
    assert cli.main(["reproduce", "--only", *ONLY, "--json", str(plain)]) == 0
    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=False,
                                  dashboard_address=None) as cluster:
        assert cli.main(["reproduce", "--only", *ONLY, "--json", str(on_dask),
                         "--scheduler", cluster.scheduler_address]) == 0
    assert json.loads(on_dask.read_text()) == json.loads(plain.read_text())


def test_a_scheduler_without_dask_names_the_extra(monkeypatch, capsys):
    monkeypatch.setitem(sys.modules, "distributed", None)
    assert cli.main(["reproduce", "--only", "t4.1", "--scheduler", "tcp://127.0.0.1:1"]) == 2
    assert "pip install propwhirl[distributed]" in capsys.readouterr().err


def test_analyse_spins_on_a_terminal_and_writes_lines_elsewhere(monkeypatch, no_delay, tmp_path,
                                                                 capsys):
    from propwhirl import io as pio
    from propwhirl.cases.ch09_baseline import baseline_flight, baseline_propeller, baseline_wing
    from propwhirl.model.systems import Installation, PropellerWing

    model = PropellerWing(baseline_wing(5), baseline_flight(),
                          (Installation(baseline_propeller(), 5.7),), name="small tip model")
    path = tmp_path / "m.toml"
    pio.save_model(model, path)
    monkeypatch.setattr(progress, "REFRESH", 0.01)
    tty = FakeTTY()
    assert run_with_stderr(monkeypatch, tty, ["analyse", str(path)]) == 0
    assert "\ranalysing small tip model " in tty.getvalue()
    quiet = FakeTTY()
    assert run_with_stderr(monkeypatch, quiet, ["analyse", str(path), "--quiet"]) == 0
    assert "analysing" not in quiet.getvalue()
    pipe = io.StringIO()                        # not a terminal: plain lines
    assert run_with_stderr(monkeypatch, pipe, ["analyse", str(path)]) == 0
    lines = progress_lines(pipe.getvalue(), "analysing small tip model")
    assert lines and "\r" not in pipe.getvalue()            # the first line at once (delay 0)
    assert lines[-1].startswith("analysing small tip model: done in ")
