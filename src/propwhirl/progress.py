"""Progress of long runs on stderr: a bar for a known number of steps, a spinner for an unknown one.

A run longer than about :data:`DELAY` seconds reports its progress on stderr — studies, maps,
``propwhirl reproduce``, campaigns (a bar: points or cases done of the total) and long analyses
(a spinner with the elapsed time, and the count of a stage whose length is known, e.g. the
doublet-lattice AICs of an analysis: ``doublet-lattice AICs 40 of 220, est. 1 min 20 s
left``).  How it is shown depends on the stream:

* **a terminal**: a bar redrawn in place (tqdm when installed, ``pip install
  propwhirl[progress]``, else a plain built-in counter ``reproduce: 12/41 (29%) 00:37``), or a
  spinner ``analysing big wing | 00:12``;
* **anything else** (a pipe, a log file, a batch job, a notebook's stderr): plain lines
  (:class:`Lines`), one at most every :data:`INTERVAL` seconds and at least that often while
  the work runs, each naming what runs, how far it is and an estimate of the time left —
  ``reproduce: 12 of 41 (29 %), 37 s elapsed, est. 1 min 30 s left`` — and a last line
  ``... done in 2 min 3 s`` when any was written;
* nothing with ``quiet`` (``--quiet``) or for a run shorter than :data:`DELAY` (every form
  waits that long), so short runs and output read by programs stay silent.

``PROPWHIRL_PROGRESS_DELAY`` and ``PROPWHIRL_PROGRESS_INTERVAL`` (seconds >= 0) override
:data:`DELAY` and :data:`INTERVAL` (0 and 0: every report shows, as the tests run it).

**Who asks for it.**  The Python API is silent unless asked: every ``progress`` argument is
None by default; ``progress=True`` of a study (:func:`reporter`) asks for a bar on stderr as
above, a callable ``report(done, total)`` (:data:`ProgressCallback`) receives the counts
instead.  The command line asks for it on every long command (the study commands, ``reproduce``,
``certify``, ``analyse``) unless ``--quiet``.

Reporters are plain callables ``report(done, total)``: the execution layer
(:mod:`propwhirl.studies.execution`) calls one after every finished point, an analysis after
every doublet-lattice AIC it computes, so a caller may pass its own function instead of a bar.
A reporter is also a context manager: on exit it clears or ends its line.  A spinner's
:meth:`Spinner.stage` is the reporter of a counted stage of its work.

>>> with bar("points", total=3, stream=None) as report:   # no stream: nothing is written
...     for k in range(1, 4):
...         report(k, 3)
"""
from __future__ import annotations

import math
import os
import sys
import threading
import time
from typing import Callable, Protocol, TextIO

from propwhirl import validate as v

#: Seconds before a bar, spinner or line appears: runs shorter than this print nothing [s].
DELAY = 2.0
#: Shortest interval between two redraws of the plain bar and the spinner [s].
REFRESH = 0.2
#: Seconds between two progress lines when the stream is not a terminal [s].
INTERVAL = 10.0
#: environment variables overriding :data:`DELAY` and :data:`INTERVAL` [s]
DELAY_ENV = "PROPWHIRL_PROGRESS_DELAY"
INTERVAL_ENV = "PROPWHIRL_PROGRESS_INTERVAL"

#: A progress reporter: called with (steps done, total steps) after every finished step.
ProgressCallback = Callable[[int, int], None]

class Cumulative:
    """One ``report(done, total)`` over a study's passes (issue 35 item 8: a warm-started map
    reported 4 of 4, then 0 of 21): each pass's callback (:meth:`stage`) adds its count to
    those of the passes before it, against the whole study's `total` announced from the
    start (raised only when a pass goes beyond it, e.g. a warm start's re-analyses).

    Examples
    --------
    >>> seen = []
    >>> c = Cumulative(lambda d, t: seen.append((d, t)), 25)
    >>> first, second = c.stage(), None
    >>> first(0, 4); first(4, 4)
    >>> second = c.stage()
    >>> second(0, 21); second(21, 21)
    >>> seen
    [(0, 25), (4, 25), (4, 25), (25, 25)]
    """

    def __init__(self, report: ProgressCallback, total: int) -> None:
        self.report, self.total, self.done = report, int(total), 0

    def stage(self) -> ProgressCallback:
        """The callback of the next pass (it starts where the last one ended)."""
        start = self.done

        def step(done: int, total: int) -> None:
            self.done = start + int(done)
            self.total = max(self.total, start + int(total))
            self.report(self.done, self.total)

        return step


#: Held by a :class:`Lines` reporter's thread while it writes, and by a fork (a study's worker
#: processes) while it copies the process: a child never inherits the stream's lock held by a
#: thread that does not exist in it (which would hang the child at its first write to stderr).
#: A lock of the process, not state of a run: nothing else reads or holds it.
_WRITING = threading.Lock()
if hasattr(os, "register_at_fork"):
    os.register_at_fork(before=_WRITING.acquire, after_in_parent=_WRITING.release,
                        after_in_child=_WRITING.release)


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


def duration(seconds: float) -> str:
    """A duration [s] as a line says it: '8 s', '1 min 20 s', '2 min', '2 h 5 min'."""
    s = max(0, int(round(seconds)))
    if s < 60:
        return f"{s} s"
    m, s = divmod(s, 60)
    if m < 60:
        return f"{m} min {s} s" if s else f"{m} min"
    h, m = divmod(m, 60)
    return f"{h} h {m} min" if m else f"{h} h"


def _seconds(name: str, env: str, default: float, given: float | None, read_env: bool) -> float:
    """A time setting [s]: `given` if not None (checked >= 0, an error naming `name`), else the
    environment variable `env` if `read_env` and set (a number of seconds >= 0; an InputError
    naming it otherwise), else `default`."""
    if given is not None:
        return float(v.non_negative(name, given, "s"))
    text = os.environ.get(env, "").strip() if read_env else ""
    if not text:
        return default
    try:
        x = float(text)
    except ValueError:
        x = math.nan
    if not (math.isfinite(x) and x >= 0):
        raise v.InputError(f"{env} = {text!r} is invalid: must be a number of seconds >= 0")
    return x


def timing(delay: float | None = None, interval: float | None = None, *,
           read_env: bool = True) -> tuple[float, float]:
    """(delay, interval) [s] of a reporter: the given ones, else ``PROPWHIRL_PROGRESS_DELAY``
    and ``PROPWHIRL_PROGRESS_INTERVAL`` (when `read_env`), else :data:`DELAY` and
    :data:`INTERVAL`."""
    return (_seconds("delay", DELAY_ENV, DELAY, delay, read_env),
            _seconds("interval", INTERVAL_ENV, INTERVAL, interval, read_env))


class _Count:
    """The count of a (stage of) work: ``what``, steps ``done`` of ``total``, counted since
    ``start`` [s, monotonic] from ``first`` done then (the estimate's rate counts this run's
    steps only: a resumed study's points are not)."""

    def __init__(self, what: str, done: int, total: int, now: float) -> None:
        self.what, self.done, self.total = what, done, total
        self.start, self.first = now, done


class Silent:
    """The reporter that reports nothing (``--quiet``, no stream, a progress not asked for)."""

    def __call__(self, done: int, total: int) -> None:
        return None

    def stage(self, what: str) -> None:
        """No reporter: a stage of silent work reports nothing (None)."""
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
        delay: float | None = None, interval: float | None = None) -> Reporter:
    """A progress bar of `total` steps labelled `desc` on `stream` (default: ``sys.stderr``).

    On a terminal tqdm's bar when tqdm is installed, else :class:`PlainBar`; on any other
    stream :class:`Lines`; silent (:class:`Silent`) when `quiet` or `stream` is None.
    delay [s]: nothing is written before (default :data:`DELAY`, ``PROPWHIRL_PROGRESS_DELAY``);
    interval [s]: between two lines off a terminal (default :data:`INTERVAL`,
    ``PROPWHIRL_PROGRESS_INTERVAL``).
    """
    v.integer_at_least("total", total, 0)
    stream = sys.stderr if stream is ... else stream
    silent = quiet or stream is None
    delay, interval = timing(delay, interval, read_env=not silent)
    if silent:
        return Silent()
    if not is_terminal(stream):
        return Lines(desc, total, stream, delay, interval)
    try:
        import tqdm  # noqa: F401
    except ImportError:
        return PlainBar(desc, total, stream, delay)
    return TqdmBar(desc, total, stream, delay)


class _Stages:
    """What a spinner or a line reporter shows: its label `desc`, the elapsed time and the
    count of the work (a bar: `total` steps) or of a spinner's current :meth:`stage`."""

    def __init__(self, desc: str, total: int | None) -> None:
        self.desc = desc
        self.start = time.monotonic()
        self._bar = total is not None
        self._total = 0 if total is None else total
        self._count: _Count | None = None
        self._lock = threading.Lock()

    def __call__(self, done: int, total: int) -> None:
        self._update("", done, total)

    def stage(self, what: str) -> ProgressCallback:
        """The reporter ``report(done, total)`` of a counted stage of the work, shown as
        ``what done of total`` with an estimate of the stage's time left until done = total."""

        def report(done: int, total: int) -> None:
            self._update(what, done, total)

        return report

    def _update(self, what: str, done: int, total: int) -> None:
        now = time.monotonic()
        with self._lock:
            c = self._count
            if c is None or c.what != what:
                c = self._count = _Count(what, done, total, now)
            c.done, c.total = done, total
            if total > 0 or self._bar:                      # an empty stage: nothing to show
                self._changed(now)
            if not self._bar and done >= total:             # the stage is over
                self._count = None

    def _changed(self, now: float) -> None:
        """Called with the lock held after every report."""

    def _counted(self, now: float) -> tuple[str, str]:
        """('AICs 40 of 220 (18 %)', 'est. 1 min 20 s left') of the count, ('', '') without."""
        c = self._count
        if c is None:
            return (f"0 of {self._total} (0 %)", "") if self._bar else ("", "")
        head = f"{c.what} " if c.what else ""
        pct = 100.0 * c.done / c.total if c.total else 100.0
        est = ""
        if c.first < c.done < c.total:
            est = f"est. {duration((now - c.start) * (c.total - c.done) / (c.done - c.first))} left"
        return f"{head}{c.done} of {c.total} ({pct:.0f} %)", est


class Lines(_Stages):
    """Progress as plain lines on a stream that is not a terminal (a pipe, a log file, a batch
    job, a notebook), for a bar of `total` steps or a spinner (`total` None):

        reproduce: 12 of 41 (29 %), 37 s elapsed, est. 1 min 30 s left
        analysing Goland: doublet-lattice AICs 40 of 220 (18 %), 25 s elapsed, est. 1 min 50 s left
        analysing Goland: 2 min 10 s elapsed

    (a spinner shows the count of its current :meth:`stage` while one runs).  The first line
    after `delay` [s], then one at most every `interval` [s]: on a report, and from a
    background thread while the reporter is entered as a context manager (so a slow step
    still shows that the run goes on); on close a last line ``... done in 2 min 3 s`` (or
    ``stopped after``: an error, or a bar short of its total) when any line was written.  A
    stream that cannot be written to ends the lines, never the work."""

    def __init__(self, desc: str, total: int | None, stream: TextIO, delay: float,
                 interval: float) -> None:
        super().__init__(desc, total)
        self.stream, self.delay, self.interval = stream, delay, interval
        self._last: float | None = None               # when the last line was written
        self._written = False
        self._broken = False
        self._stop = threading.Event()
        self._thread: threading.Thread | None = None

    def _line(self, now: float, end: str | None = None) -> str:
        count, est = self._counted(now)
        if end is not None:
            return f"{self.desc}: {count + ', ' if count else ''}{end} {duration(now - self.start)}"
        parts = [count] if count else []
        parts.append(f"{duration(now - self.start)} elapsed")
        if est:
            parts.append(est)
        return f"{self.desc}: {', '.join(parts)}"

    def _write(self, text: str) -> None:
        if self._broken:
            return
        try:
            with _WRITING:
                self.stream.write(text + "\n")
                self.stream.flush()
        except (OSError, ValueError):                # a closed pipe or stream: no more lines
            self._broken = True
            return
        self._written = True

    def _emit(self, now: float) -> None:
        """A line now if the delay has passed and the last line is `interval` old (lock held)."""
        if now - self.start < self.delay:
            return
        if self._last is not None and now - self._last < self.interval:
            return
        self._last = now
        self._write(self._line(now))

    def _changed(self, now: float) -> None:
        self._emit(now)

    def _beat(self) -> None:
        while True:
            now = time.monotonic()
            due = self.start + self.delay if self._last is None else self._last + self.interval
            if self._stop.wait(max(due - now, REFRESH)):
                return
            with self._lock:
                self._emit(time.monotonic())

    def __enter__(self) -> "Lines":
        with self._lock:                  # the first line at once when there is no delay
            self._emit(time.monotonic())
        if self._thread is None:
            self._thread = threading.Thread(target=self._beat, name="propwhirl-progress",
                                            daemon=True)
            self._thread.start()
        return self

    def close(self, failed: bool = False) -> None:
        """Stop the lines; a last one (done in / stopped after) if any was written."""
        self._stop.set()
        if self._thread is not None and self._thread is not threading.current_thread():
            self._thread.join()
        with self._lock:
            if self._written:
                c = self._count
                unfinished = self._bar and (c is None or c.done < c.total)
                end = "stopped after" if failed or unfinished else "done in"
                self._write(self._line(time.monotonic(), end))
                self._written = False

    def __exit__(self, exc_type: object, *exc: object) -> None:
        self.close(failed=exc_type is not None)


class Spinner(_Stages):
    """A spinner for work of unknown length: ``desc | 00:12`` redrawn in place on `stream`
    (a terminal) from a background thread every :data:`REFRESH` s, first after `delay` [s],
    followed by the count of the current :meth:`stage` while one runs (``doublet-lattice AICs
    40 of 220 (18 %), est. 1 min 20 s left``); the line is cleared on close.  Use as a context
    manager around the work."""

    FRAMES = "|/-\\"

    def __init__(self, desc: str, stream: TextIO, delay: float) -> None:
        super().__init__(desc, None)
        self.stream, self.delay = stream, delay
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._spin, name="propwhirl-spinner", daemon=True)
        self._width = 0

    def _spin(self) -> None:
        if self._stop.wait(self.delay):
            return
        k = 0
        while not self._stop.is_set():
            now = time.monotonic()
            with self._lock:
                count, est = self._counted(now)
            text = f"\r{self.desc} {self.FRAMES[k % len(self.FRAMES)]} {_clock(now - self.start)}"
            if count:
                text += f" {count}" + (f", {est}" if est else "")
            self._width = max(self._width, len(text))
            self.stream.write(text.ljust(self._width))
            self.stream.flush()
            k += 1
            self._stop.wait(REFRESH)

    def __enter__(self) -> "Spinner":
        self._thread.start()
        return self

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
            delay: float | None = None, interval: float | None = None) -> Spinner | Lines | Silent:
    """A spinner labelled `desc` on `stream` (default ``sys.stderr``): a :class:`Spinner` on a
    terminal, :class:`Lines` on any other stream, silent when `quiet` or `stream` is None.
    delay, interval [s]: as :func:`bar`."""
    stream = sys.stderr if stream is ... else stream
    silent = quiet or stream is None
    delay, interval = timing(delay, interval, read_env=not silent)
    if silent:
        return Silent()
    if not is_terminal(stream):
        return Lines(desc, None, stream, delay, interval)
    return Spinner(desc, stream, delay)


def reporter(progress: bool | ProgressCallback | None, desc: str, total: int) -> Reporter:
    """The reporter a `progress` argument asks for: None or False → :class:`Silent`; True → a
    :func:`bar` on stderr (plain lines when stderr is not a terminal); a callable → itself,
    wrapped as a context manager."""
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
