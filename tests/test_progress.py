"""Progress bars and spinners (issue 12, item 6): drawn on a terminal only, after the delay,
never with quiet; tqdm when installed, a plain counter without it."""
from __future__ import annotations

import io
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
def test_not_a_terminal_or_quiet_or_short_shows_nothing(monkeypatch, tqdm_installed):
    if not tqdm_installed:
        monkeypatch.setitem(sys.modules, "tqdm", None)
    pipe = io.StringIO()
    run_bar(pipe, delay=0.0)
    assert pipe.getvalue() == ""
    tty = FakeTTY()
    run_bar(tty, delay=0.0, quiet=True)
    run_bar(tty, delay=60.0)                    # shorter than the delay
    assert tty.getvalue() == ""
    assert isinstance(progress.bar("p", 1, stream=None), progress.Silent)


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
    assert progress.spinner("x", stream=io.StringIO(), delay=0.0).__class__ is progress.Silent
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
