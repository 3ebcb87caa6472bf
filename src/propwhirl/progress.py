"""Progress on the terminal: a bar for a known number of steps, a spinner for an unknown one.

A run longer than about :data:`DELAY` seconds shows its progress on stderr — studies, maps,
``propwhirl reproduce`` (a bar: points or cases done of the total, elapsed time, rate) and long
analyses (a spinner with the elapsed time: the number of speeds an analysis evaluates is not
known in advance).  Nothing is written when the stream is not a terminal (a pipe, a file, a
notebook's captured stderr, the test suite) or when ``quiet`` is set, so output that is read by
programs never carries progress text.

The bar is drawn by tqdm when it is installed (``pip install propwhirl[progress]``), else by a
plain built-in counter (``reproduce: 12/41 (29%) 00:37``) redrawn in place; both appear only
after :data:`DELAY` seconds, so short runs stay silent.

Reporters are plain callables ``report(done, total)`` (:data:`ProgressCallback`): the
execution layer (:mod:`propwhirl.studies.execution`) calls one after every finished point, so a
caller may pass its own function instead of a bar.  A reporter is also a context manager: on
exit it clears or ends its line.

>>> with bar("points", total=3, stream=None) as report:   # no terminal: nothing is drawn
...     for k in range(1, 4):
...         report(k, 3)
"""
from __future__ import annotations

import sys
import threading
import time
from typing import Callable, Protocol, TextIO

from propwhirl import validate as v

#: Seconds before a bar or spinner appears: runs shorter than this print nothing [s].
DELAY = 2.0
#: Shortest interval between two redraws of the plain bar and the spinner [s].
REFRESH = 0.2

#: A progress reporter: called with (steps done, total steps) after every finished step.
ProgressCallback = Callable[[int, int], None]


class Reporter(Protocol):
    """A progress reporter: ``report(done, total)``, a context manager that ends its line."""

    def __call__(self, done: int, total: int) -> None: ...

    def __enter__(self) -> "Reporter": ...

    def __exit__(self, *exc: object) -> None: ...

    def close(self) -> None: ...


def is_terminal(stream: TextIO | None) -> bool:
    """Whether `stream` is an interactive terminal (``isatty()``); False for None, pipes, files."""
    if stream is None:
        return False
    try:
        return bool(stream.isatty())
    except (AttributeError, ValueError, OSError):  # closed or not a real stream
        return False


def _clock(seconds: float) -> str:
    m, s = divmod(int(seconds), 60)
    h, m = divmod(m, 60)
    return f"{h:d}:{m:02d}:{s:02d}" if h else f"{m:02d}:{s:02d}"


class Silent:
    """The reporter that reports nothing (not a terminal, ``--quiet``)."""

    def __call__(self, done: int, total: int) -> None:
        return None

    def close(self) -> None:
        return None

    def __enter__(self) -> "Silent":
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


class PlainBar:
    """A built-in bar without tqdm: ``desc: done/total (pct%) elapsed`` redrawn in place on
    `stream` (a terminal), first after `delay` [s], at most every :data:`REFRESH` s; the line
    is ended on close once something was drawn."""

    def __init__(self, desc: str, total: int, stream: TextIO, delay: float) -> None:
        self.desc, self.total, self.stream, self.delay = desc, total, stream, delay
        self.start = time.monotonic()
        self._last = -float("inf")
        self._drawn = False

    def __call__(self, done: int, total: int) -> None:
        self.total = total
        now = time.monotonic()
        if now - self.start < self.delay or (now - self._last < REFRESH and done < total):
            return
        self._last = now
        pct = 100.0 * done / total if total else 100.0
        self.stream.write(f"\r{self.desc}: {done}/{total} ({pct:.0f}%) {_clock(now - self.start)}")
        self.stream.flush()
        self._drawn = True

    def close(self) -> None:
        if self._drawn:
            self.stream.write("\n")
            self.stream.flush()
            self._drawn = False

    def __enter__(self) -> "PlainBar":
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


class TqdmBar:
    """A tqdm bar on `stream` (shown after `delay` [s], the line left in place on close)."""

    def __init__(self, desc: str, total: int, stream: TextIO, delay: float) -> None:
        from tqdm import tqdm

        self._bar = tqdm(total=total, desc=desc, file=stream, delay=delay, unit="pt",
                         dynamic_ncols=True, leave=True)
        self._done = 0

    def __call__(self, done: int, total: int) -> None:
        if total != self._bar.total:
            self._bar.total = total
        if done > self._done:
            self._bar.update(done - self._done)
            self._done = done

    def close(self) -> None:
        self._bar.close()

    def __enter__(self) -> "TqdmBar":
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


def bar(desc: str, total: int, *, stream: TextIO | None = ..., quiet: bool = False,  # type: ignore[assignment]
        delay: float | None = None) -> Reporter:
    """A progress bar of `total` steps labelled `desc` on `stream` (default: ``sys.stderr``).

    Silent (:class:`Silent`) when `quiet` or when `stream` is not a terminal; tqdm's bar when
    tqdm is installed, else :class:`PlainBar`.  delay [s]: nothing is drawn before (default
    :data:`DELAY`).
    """
    v.integer_at_least("total", total, 0)
    stream = sys.stderr if stream is ... else stream
    delay = DELAY if delay is None else float(v.non_negative("delay", delay, "s"))
    if quiet or not is_terminal(stream):
        return Silent()
    try:
        import tqdm  # noqa: F401
    except ImportError:
        return PlainBar(desc, total, stream, delay)
    return TqdmBar(desc, total, stream, delay)


class Spinner:
    """A spinner for work of unknown length: ``desc ⠋ 12 s`` redrawn in place on `stream`
    from a background thread every :data:`REFRESH` s, first after `delay` [s]; the line is
    cleared on close.  Use as a context manager around the work."""

    FRAMES = "|/-\\"

    def __init__(self, desc: str, stream: TextIO, delay: float) -> None:
        self.desc, self.stream, self.delay = desc, stream, delay
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._spin, name="propwhirl-spinner", daemon=True)
        self._width = 0

    def _spin(self) -> None:
        start = time.monotonic()
        if self._stop.wait(self.delay):
            return
        k = 0
        while not self._stop.is_set():
            text = f"\r{self.desc} {self.FRAMES[k % len(self.FRAMES)]} {_clock(time.monotonic() - start)}"
            self._width = max(self._width, len(text))
            self.stream.write(text)
            self.stream.flush()
            k += 1
            self._stop.wait(REFRESH)

    def __enter__(self) -> "Spinner":
        self._thread.start()
        return self

    def __call__(self, done: int, total: int) -> None:  # a Reporter too; the count is not shown
        return None

    def close(self) -> None:
        self._stop.set()
        if self._thread.is_alive():
            self._thread.join()
        if self._width:
            self.stream.write("\r" + " " * (self._width - 1) + "\r")
            self.stream.flush()
            self._width = 0

    def __exit__(self, *exc: object) -> None:
        self.close()


def spinner(desc: str, *, stream: TextIO | None = ..., quiet: bool = False,  # type: ignore[assignment]
            delay: float | None = None) -> Spinner | Silent:
    """A :class:`Spinner` labelled `desc` on `stream` (default ``sys.stderr``); silent when
    `quiet` or not a terminal.  delay [s]: default :data:`DELAY`."""
    stream = sys.stderr if stream is ... else stream
    delay = DELAY if delay is None else float(v.non_negative("delay", delay, "s"))
    if quiet or not is_terminal(stream):
        return Silent()
    return Spinner(desc, stream, delay)


def reporter(progress: bool | ProgressCallback | None, desc: str, total: int) -> Reporter:
    """The reporter a `progress` argument asks for: None or False → :class:`Silent`; True → a
    :func:`bar` on stderr (silent when stderr is not a terminal); a callable → itself, wrapped
    as a context manager."""
    if progress is None or progress is False:
        return Silent()
    if progress is True:
        return bar(desc, total)
    if callable(progress):
        return _Wrapped(progress)
    raise v.InputError(f"progress = {progress!r} is invalid: must be True, False, None or a "
                       "callable report(done, total)")


class _Wrapped:
    """A plain callable as a :class:`Reporter` (its own context manager, if any, is the caller's)."""

    def __init__(self, func: ProgressCallback) -> None:
        self.func = func

    def __call__(self, done: int, total: int) -> None:
        self.func(done, total)

    def close(self) -> None:
        return None

    def __enter__(self) -> "_Wrapped":
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()
