"""The study commands' execution options (issue 12, items 5–6) on `propwhirl reproduce`:
progress on a terminal only (and never with --quiet), an interrupted run resumed with --resume
to the same records, --scheduler on a Dask cluster; the spinner of `propwhirl analyse`."""
from __future__ import annotations

import io
import json
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from propwhirl import progress
from propwhirl.app import cli
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
    pipe = io.StringIO()                        # not a terminal
    assert run_with_stderr(monkeypatch, pipe, ["reproduce", "--only", *ONLY]) == 0
    assert pipe.getvalue() == ""
    assert "within tolerance" in capsys.readouterr().out


def test_stderr_is_empty_when_it_is_a_pipe():
    """A real process whose stderr is a pipe: no progress text (delay 0, so not by brevity)."""
    code = textwrap.dedent("""
        import sys
        import propwhirl.progress as p
        p.DELAY = 0.0
        from propwhirl.app.cli import main
        sys.exit(main(["reproduce", "--only", "t4.1", "t7.2"]))
    """)
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    assert r.stderr == ""
    assert "within tolerance" in r.stdout


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


def test_analyse_spins_on_a_terminal_only(monkeypatch, no_delay, tmp_path, capsys):
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
    pipe = io.StringIO()
    assert run_with_stderr(monkeypatch, pipe, ["analyse", str(path)]) == 0
    assert "analysing" not in pipe.getvalue()
