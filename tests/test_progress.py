"""Progress bars and spinners (issue 12, item 6; issue 37, item 3): on a terminal drawn in
place (tqdm when installed, a plain counter without it), on any other stream plain lines at
most every interval, each naming what, how far and an estimate; nothing before the delay,
never with quiet.  No test asserts an elapsed time: the lines are bounded by their counts."""
from __future__ import annotations

import io
import re
import sys
import time

import pytest

from propwhirl import progress
from propwhirl.validate import InputError


class FakeTTY(io.StringIO):
    """A stream that says it is a terminal."""

    def isatty(self) -> bool:
        return True


def run_bar(stream, n: int = 5, **kw) -> None:
    with progress.bar("points", n, stream=stream, **kw) as report:
        for k in range(n + 1):
            report(k, n)


def test_a_terminal_shows_the_bar_with_tqdm():
    pytest.importorskip("tqdm")
    tty = FakeTTY()
    assert isinstance(progress.bar("points", 5, stream=tty, delay=0.0), progress.TqdmBar)
    run_bar(tty, delay=0.0)
    text = tty.getvalue()
    assert "points" in text and "5/5" in text and "100%" in text


def test_without_tqdm_a_plain_counter(monkeypatch):
    monkeypatch.setitem(sys.modules, "tqdm", None)
    tty = FakeTTY()
    assert isinstance(progress.bar("points", 5, stream=tty), progress.PlainBar)
    run_bar(tty, delay=0.0)
    text = tty.getvalue()
    assert "\rpoints: 5/5 (100%) 00:00" in text and text.endswith("\n")


@pytest.mark.parametrize("tqdm_installed", [True, False])
def test_quiet_or_short_or_no_stream_shows_nothing(monkeypatch, tqdm_installed):
    if not tqdm_installed:
        monkeypatch.setitem(sys.modules, "tqdm", None)
    for stream in (FakeTTY(), io.StringIO()):        # a terminal, and not one
        run_bar(stream, delay=0.0, quiet=True)
        run_bar(stream, delay=60.0)                 # shorter than the delay
        assert stream.getvalue() == ""
    assert isinstance(progress.bar("p", 1, stream=None), progress.Silent)


class FakeClock:
    """progress's clock, set by hand (so the lines' times and estimates are exact)."""

    def __init__(self) -> None:
        self.t = 0.0

    def monotonic(self) -> float:
        return self.t


def count_of(line: str) -> int:
    return int(re.search(r"(\d+) of \d+", line).group(1))


def test_off_a_terminal_a_bar_writes_plain_lines_of_every_count():
    pipe = io.StringIO()
    assert isinstance(progress.bar("points", 5, stream=pipe), progress.Lines)
    run_bar(pipe, delay=0.0, interval=0.0)          # every report a line
    text = pipe.getvalue()
    lines = text.splitlines()
    assert "\r" not in text and all(line.startswith("points: ") for line in lines)
    assert {count_of(line) for line in lines} == {0, 1, 2, 3, 4, 5}
    assert re.fullmatch(r"points: 5 of 5 \(100 %\), done in \d+ s", lines[-1])


def test_off_a_terminal_at_most_one_line_per_interval():
    pipe = io.StringIO()
    run_bar(pipe, n=50, delay=0.0, interval=3600.0)
    lines = pipe.getvalue().splitlines()
    assert len(lines) == 2                          # the first, then the last on close
    assert lines[0].startswith("points: 0 of 50 (0 %), ")
    assert lines[1].startswith("points: 50 of 50 (100 %), done in ")


def test_a_line_says_what_how_far_and_estimates_the_time_left(monkeypatch):
    clock = FakeClock()
    monkeypatch.setattr(progress, "time", clock)
    pipe = io.StringIO()
    r = progress.bar("reproduce", 220, stream=pipe, delay=2.0, interval=10.0)
    r(0, 220)
    clock.t = 1.0
    r(2, 220)                                       # within the delay: nothing
    assert pipe.getvalue() == ""
    clock.t = 20.0
    r(40, 220)                                      # 40 in 20 s: the other 180 take 90 s
    clock.t = 25.0
    r(50, 220)                                      # within the interval: no line
    clock.t = 30.0
    r(60, 220)
    r.close()
    assert pipe.getvalue().splitlines() == [
        "reproduce: 40 of 220 (18 %), 20 s elapsed, est. 1 min 30 s left",
        "reproduce: 60 of 220 (27 %), 30 s elapsed, est. 1 min 20 s left",
        "reproduce: 60 of 220 (27 %), stopped after 30 s"]      # short of its total
    resumed = io.StringIO()                         # a resumed study: its rate from this run
    clock.t = 100.0
    r = progress.bar("campaign", 10, stream=resumed, delay=0.0, interval=0.0)
    r(6, 10)                                        # 6 points from the partial-results file
    clock.t = 110.0
    r(7, 10)
    r.close()
    assert resumed.getvalue().splitlines() == [
        "campaign: 6 of 10 (60 %), 0 s elapsed",
        "campaign: 7 of 10 (70 %), 10 s elapsed, est. 30 s left",
        "campaign: 7 of 10 (70 %), stopped after 10 s"]


def test_off_a_terminal_a_spinner_counts_its_stage_then_the_time(monkeypatch):
    clock = FakeClock()
    monkeypatch.setattr(progress, "time", clock)
    pipe = io.StringIO()
    spin = progress.spinner("analysing Goland", stream=pipe, delay=2.0, interval=10.0)
    assert isinstance(spin, progress.Lines)
    aics = spin.stage("doublet-lattice AICs")
    aics(0, 100)
    clock.t = 12.0
    aics(30, 100)
    clock.t = 40.0
    aics(100, 100)
    clock.t = 75.0
    spin(0, 0)                                      # no count: the time only
    spin.close()
    assert pipe.getvalue().splitlines() == [
        "analysing Goland: doublet-lattice AICs 30 of 100 (30 %), 12 s elapsed, "
        "est. 28 s left",
        "analysing Goland: doublet-lattice AICs 100 of 100 (100 %), 40 s elapsed",
        "analysing Goland: done in 1 min 15 s"]
    assert progress.Silent().stage("doublet-lattice AICs") is None


def test_the_environment_sets_the_delay_and_the_interval(monkeypatch):
    monkeypatch.setenv(progress.DELAY_ENV, "0")
    monkeypatch.setenv(progress.INTERVAL_ENV, "3600")
    r = progress.bar("p", 3, stream=io.StringIO())
    assert (r.delay, r.interval) == (0.0, 3600.0)
    monkeypatch.setenv(progress.INTERVAL_ENV, "soon")
    with pytest.raises(InputError, match="PROPWHIRL_PROGRESS_INTERVAL = 'soon' is invalid: must "
                                         "be a number of seconds >= 0"):
        progress.spinner("x", stream=io.StringIO())
    assert isinstance(progress.bar("p", 3, stream=io.StringIO(), quiet=True), progress.Silent)


def test_a_stream_that_breaks_ends_the_lines_not_the_work():
    class Broken(io.StringIO):
        def write(self, text):
            raise BrokenPipeError(32, "Broken pipe")

    with progress.bar("points", 3, stream=Broken(), delay=0.0, interval=0.0) as report:
        for k in range(4):
            report(k, 3)


def test_the_default_stream_is_stderr_when_called(monkeypatch):
    tty = FakeTTY()
    monkeypatch.setattr(sys, "stderr", tty)
    monkeypatch.setattr(progress, "DELAY", 0.0)
    run_bar(...)
    assert "5/5" in tty.getvalue()


def test_the_spinner_turns_on_a_terminal_and_clears_its_line():
    tty = FakeTTY()
    with progress.spinner("analysing big wing", stream=tty, delay=0.0):
        time.sleep(3 * progress.REFRESH)
    text = tty.getvalue()
    assert text.count("\ranalysing big wing ") >= 2
    assert text.endswith("\r")                  # the line is blanked at the end
    assert progress.spinner("x", stream=None).__class__ is progress.Silent
    quiet = FakeTTY()
    with progress.spinner("x", stream=quiet, delay=0.0, quiet=True):
        time.sleep(2 * progress.REFRESH)
    assert quiet.getvalue() == ""


def test_a_short_spinner_prints_nothing():
    tty = FakeTTY()
    with progress.spinner("quick", stream=tty, delay=30.0):
        pass
    assert tty.getvalue() == ""


def test_reporter_reads_the_progress_argument():
    assert isinstance(progress.reporter(None, "p", 3), progress.Silent)
    assert isinstance(progress.reporter(False, "p", 3), progress.Silent)
    seen = []
    with progress.reporter(lambda d, t: seen.append((d, t)), "p", 3) as r:
        r(1, 3)
    assert seen == [(1, 3)]
    with pytest.raises(InputError, match="progress"):
        progress.reporter("bar", "p", 3)
    with pytest.raises(InputError, match="total"):
        progress.bar("p", -1)
    with pytest.raises(InputError, match="delay"):
        progress.bar("p", 1, delay=-1.0)


def test_a_line_is_written_holding_the_fork_guard():
    """The lines' thread writes holding progress._WRITING, which a fork (a study's worker
    processes) holds while it copies the process: no child inherits a stream lock held."""
    held = []

    class Watched(io.StringIO):
        def write(self, text):
            held.append(progress._WRITING.locked())
            return super().write(text)

    with progress.spinner("x", stream=Watched(), delay=0.0, interval=0.0) as spin:
        spin.stage("AICs")(1, 2)
    assert held and all(held)
    assert not progress._WRITING.locked()


def test_on_a_terminal_the_spinner_shows_the_count_of_its_stage(monkeypatch):
    monkeypatch.setattr(progress, "REFRESH", 0.01)
    tty = FakeTTY()
    with progress.spinner("analysing big wing", stream=tty, delay=0.0) as spin:
        aics = spin.stage("doublet-lattice AICs")
        aics(0, 2)
        aics(1, 2)
        while "AICs 1 of 2 (50 %)" not in tty.getvalue():     # a redraw shows it
            time.sleep(0.01)
        aics(2, 2)
    assert "\ranalysing big wing " in tty.getvalue() and "\n" not in tty.getvalue()
