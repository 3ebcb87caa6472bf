"""Command line and files: Ctrl-C exits 130 with one line and no partial output; an output
folder that cannot be written is found before computing, naming the folder (issue 9, item 5)."""
from __future__ import annotations

import os
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import pytest

from helpers.files import unwritable_folder

from propwhirl import io
from propwhirl.app import cli

ROOT = Path(__file__).resolve().parents[2]


def small_tip_model():
    """Baseline wing with 5 elements and the baseline propeller at the tip (fast)."""
    from propwhirl.cases.ch09_baseline import baseline_flight, baseline_propeller, baseline_wing
    from propwhirl.model.systems import Installation, PropellerWing

    return PropellerWing(baseline_wing(5), baseline_flight(),
                         (Installation(baseline_propeller(), 5.7),), name="small tip model")


@pytest.fixture(scope="module")
def small_file(tmp_path_factory):
    path = tmp_path_factory.mktemp("models") / "small.toml"
    io.save_model(small_tip_model(), path)
    return path


# ----------------------------------------------------------------------------- Ctrl-C
SCRIPT = textwrap.dedent("""
    import os, sys, time
    from pathlib import Path

    where, marker, argv = sys.argv[1], Path(sys.argv[2]), sys.argv[3:]
    if where == "computing":           # Ctrl-C during the analysis
        import propwhirl.analysis.stability as stability

        def analyse(*args, **kwargs):
            marker.touch()
            time.sleep(120)
        stability.analyse = analyse
    else:                              # Ctrl-C while the JSON file is being written
        import io

        def stall():
            marker.touch()
            time.sleep(120)

        real_write, real_open = os.write, io.open

        def write(fd, data):           # the write path of propwhirl.fileio
            n = real_write(fd, data[:100])
            stall()
            return n

        class Stalling:                # a file object's write (any other write path)
            def __init__(self, fh):
                self.fh = fh

            def write(self, data):
                self.fh.write(data[:100])
                self.fh.flush()
                stall()

            def __enter__(self):
                return self

            def __exit__(self, *exc):
                return self.fh.__exit__(*exc)

            def __getattr__(self, name):
                return getattr(self.fh, name)

        def open_(file, mode="r", *args, **kwargs):
            fh = real_open(file, mode, *args, **kwargs)
            return Stalling(fh) if "w" in mode else fh

        import propwhirl.analysis.stability as stability
        real_save = stability.ModelAnalysis.save

        def save(self, path, *a, **k):
            os.write, io.open = write, open_
            try:
                return real_save(self, path, *a, **k)
            finally:
                os.write, io.open = real_write, real_open
        stability.ModelAnalysis.save = save
    from propwhirl.app.cli import main
    sys.exit(main(argv))
""")


@pytest.mark.parametrize("where", ["computing", "writing"])
def test_sigint_exits_130_with_one_line_and_no_partial_output(small_file, tmp_path, where):
    """Issue 9.5: Ctrl-C printed a KeyboardInterrupt traceback and left a 0-byte or partial
    file; now exit code 130, one line on stderr, no output file and no temporary file."""
    out = tmp_path / "out"
    out.mkdir()
    script, marker = tmp_path / "run.py", tmp_path / "marker"
    script.write_text(SCRIPT)
    argv = ["analyse", str(small_file), "--speeds", "1", "350", "50",
            "--json", str(out / "a.json"), "--csv", str(out / "a.csv")]
    env = dict(os.environ, PYTHONPATH=str(ROOT / "src"))
    proc = subprocess.Popen([sys.executable, str(script), where, str(marker), *argv], env=env,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    while not marker.exists():        # the child ends (and fails the test) if it never gets there
        assert proc.poll() is None, proc.communicate()
        time.sleep(0.05)
    if where == "writing":
        assert [p.name for p in out.iterdir()] != []      # mid-write: a file is there
    proc.send_signal(signal.SIGINT)
    stdout, stderr = proc.communicate(timeout=600)   # a hang guard, not a measure
    assert proc.returncode == 130
    # the interruption is one line (after the analysis's validity warnings, if any)
    lines = stderr.splitlines()
    assert lines[-1] == "propwhirl: interrupted" and "Traceback" not in stderr
    assert all(ln.startswith("propwhirl: warning: ") for ln in lines[:-1]), stderr
    assert list(out.iterdir()) == []            # no a.json, no a.csv, no temporary file


@pytest.mark.skipif(not Path("/proc/self/maps").exists(), reason="needs Linux /proc")
def test_sigint_to_the_real_command(tmp_path):
    """`python -m propwhirl analyse` (no patches) interrupted once scipy's compiled modules are
    loaded: while the command line loads (its imports at module level since issue 38 item 4;
    `python -m propwhirl` catches it there too) or while it computes, SIGINT gives the one
    line and 130."""
    model = tmp_path / "m.toml"
    assert cli.main(["case", "wingtip", "--save", str(model)]) == 0
    out = tmp_path / "out"
    out.mkdir()
    argv = [sys.executable, "-m", "propwhirl", "analyse", str(model), "--speeds", "1", "350",
            "0.5", "--json", str(out / "a.json"), "--csv", str(out / "a.csv")]
    env = dict(os.environ, PYTHONPATH=str(ROOT / "src"))
    proc = subprocess.Popen(argv, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True)
    maps = Path(f"/proc/{proc.pid}/maps")
    while "/scipy/linalg/" not in maps.read_text():     # as above: no clock, the child's end
        assert proc.poll() is None, proc.communicate()
        time.sleep(0.02)
    proc.send_signal(signal.SIGINT)
    stdout, stderr = proc.communicate(timeout=600)   # a hang guard, not a measure
    assert (proc.returncode, stderr) == (130, "propwhirl: interrupted\n")
    assert list(out.iterdir()) == []


def test_keyboard_interrupt_in_main(small_file, monkeypatch, capsys):
    import propwhirl.analysis.stability as stability

    def interrupted(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(stability, "analyse", interrupted)
    assert cli.main(["analyse", str(small_file)]) == cli.EXIT_INTERRUPTED == 130
    assert capsys.readouterr().err == "propwhirl: interrupted\n"


# ----------------------------------------------------------------------------- outputs
@pytest.fixture
def no_computing(monkeypatch):
    """Every computation fails the test: the output check must come first."""
    import propwhirl.analysis.stability as stability
    import propwhirl.analysis.vibration as vibration
    import propwhirl.app.run as run
    import propwhirl.reproduce.harness as harness

    def fail(*args, **kwargs):
        raise AssertionError("computed before checking the output path")

    for module, name in ((stability, "analyse"), (vibration, "campbell"), (run, "analyse"),
                         (run, "headline_model"), (harness, "run")):
        monkeypatch.setattr(module, name, fail)


@pytest.mark.parametrize("option", ["--json", "--csv", "--plot"])
def test_analyse_output_in_a_read_only_folder_fails_before_computing(
        small_file, tmp_path, capsys, no_computing, option):
    """Issue 9.5: a read-only folder was found only after the whole analysis."""
    ro = unwritable_folder(tmp_path)
    name = "a.png" if option == "--plot" else "a.out"
    assert cli.main(["analyse", str(small_file), option, str(ro / name)]) == 2   # no_computing
    err = capsys.readouterr().err
    assert err.count("\n") == 1
    assert err.startswith(f"propwhirl: error: {option} {ro / name}: cannot write to the folder "
                          f"'{ro}': ")


@pytest.mark.parametrize("argv", [
    ["case", "wingtip", "--save", "{ro}/m.toml"],
    ["campbell", "{model}", "--rpm", "0", "1000", "3", "--plot", "{ro}/c.png"],
    ["reproduce", "--only", "t9", "--json", "{ro}/r.json"],
    ["run", "--out", "{ro}"],
    ["run", "--out", "{ro}/sub"],
])
def test_other_outputs_fail_before_computing(small_file, tmp_path, capsys, no_computing, argv):
    ro = unwritable_folder(tmp_path)
    argv = [a.format(ro=ro, model=small_file) for a in argv]
    assert cli.main(argv) == 2          # no_computing: nothing was computed before the check
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("propwhirl: error: ")
    assert f"'{ro}" in err and ("cannot write to the folder" in err
                                or "cannot create the folder" in err)


def test_missing_folder_and_plot_format_fail_before_computing(small_file, tmp_path, capsys,
                                                              no_computing):
    assert cli.main(["analyse", str(small_file), "--json", str(tmp_path / "no" / "a.json")]) == 2
    assert f"the folder '{tmp_path / 'no'}' does not exist" in capsys.readouterr().err
    assert cli.main(["analyse", str(small_file), "--plot", str(tmp_path / "a.xyz")]) == 2
    assert "format 'xyz' is not supported" in capsys.readouterr().err
    assert cli.main(["analyse", str(small_file), "--csv", str(tmp_path)]) == 2
    assert "is a folder, not a file" in capsys.readouterr().err
