"""Running independent analyses: in this process, on local processes, or on a Dask cluster;
finished points kept in a partial-results file as they complete; failing points recorded.

:func:`map_analyses` is ``[func(t) for t in tasks]`` with three interchangeable back ends that
give identical results (every worker runs its analyses with BLAS at one thread):

* serial, in the calling process (``processes=1``, no client);
* local processes (``processes > 1``): a :class:`concurrent.futures.ProcessPoolExecutor` of
  single-BLAS-thread workers, at most one per CPU;
* a Dask cluster (``client=``: a ``dask.distributed.Client``, or a scheduler address such as
  ``"tcp://host:8786"``; ``pip install propwhirl[distributed]``).  Each worker of the cluster
  pins BLAS to one thread when it starts (a worker plugin, so workers that join later too);
  `processes` is then ignored: the cluster's workers decide the parallelism.

`func` and the tasks must be picklable (a module-level function; Dask also accepts closures).

Failing points (``errors="record"``): an exception raised by ``func(t)`` — e.g. an
:class:`~propwhirl.validate.InputError` of a model that is invalid at some parameter value — is
returned in that point's place as a :class:`TaskError` (its type and one-line message) and the
other points go on; never silently dropped.  ``errors="raise"`` (the default) re-raises it.
``KeyboardInterrupt`` is never recorded.

Incremental results (``checkpoint=Checkpoint(path, ...)``): the finished points are written to
a JSON file (atomically, :func:`propwhirl.fileio.write_text`: the file is always a complete
earlier state) at most every ``interval`` seconds, after the last point, and when the run is
interrupted or fails.  An interrupted run raises :class:`Interrupted` (a KeyboardInterrupt
naming the file and the count kept); ``Checkpoint(path, resume=True)`` loads the finished points
of that file, runs only the others, and returns the same list as an uninterrupted run.  The file
names the study (``fingerprint``) and each point (``keys``): a file written by another study is
refused, not mixed in.  Results are stored as JSON when they are plain data (dict with string
keys, list, str, float, int, bool, None; floats round-trip exactly) and pickled otherwise.
"""
from __future__ import annotations

import base64
import json
import os
import pickle
import time
from concurrent.futures import ProcessPoolExecutor, as_completed
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Callable, Iterable, Iterator, Literal, Sequence

from propwhirl import fileio
from propwhirl import validate as v
from propwhirl.progress import ProgressCallback, reporter

#: The format tag of a partial-results file.
PARTIAL_FORMAT = "propwhirl partial results"
#: Version of the partial-results file layout.
PARTIAL_VERSION = 1


# ----------------------------------------------------------------------------- records
@dataclass(frozen=True)
class TaskError:
    """A point whose analysis failed: the exception's type name and its one-line message."""

    kind: str
    message: str

    def __str__(self) -> str:
        return f"{self.kind}: {self.message}"


class Interrupted(KeyboardInterrupt):
    """A run interrupted (Ctrl-C) after `done` of `total` points, kept in `path` (or None)."""

    def __init__(self, done: int, total: int, path: Path | None) -> None:
        self.done, self.total, self.path = done, total, path
        where = f" kept in {str(path)!r}: run it again with resume (--resume) to continue" if path else ""
        super().__init__(f"{done} of {total} points finished{where}")


@dataclass(frozen=True)
class Checkpoint:
    """Where a run keeps its finished points, and whether it resumes from them.

    path:        the partial-results file (JSON), e.g. beside the final result;
    resume:      load the finished points of `path` (if it exists) and run only the others;
    fingerprint: names the study (its parameters): a file with another fingerprint is refused;
    interval:    shortest time between two rewrites of the file while running [s].
    """

    path: str | Path
    resume: bool = False
    fingerprint: str = ""
    interval: float = 2.0

    def __post_init__(self) -> None:
        v.boolean("resume", self.resume)
        v.non_negative("interval", self.interval, "s")
        if not isinstance(self.fingerprint, str):
            raise v.InputError(f"fingerprint = {self.fingerprint!r} is invalid: must be a string")

    def load(self, keys: Sequence[str]) -> dict[int, Any]:
        """The finished points {index: result} of the file ({} when it does not exist)."""
        path = Path(self.path)
        if not path.exists():
            return {}
        text = fileio.read_text(path, "partial results file")
        name = f"partial results file {str(path)!r}"
        try:
            data = json.loads(text)
        except json.JSONDecodeError as exc:
            raise v.InputError(f"{name} is not valid JSON ({exc.msg}, line {exc.lineno}): "
                               "remove it or run without resume") from None
        if not isinstance(data, dict) or data.get("format") != PARTIAL_FORMAT:
            raise v.InputError(f"{name} is not a propwhirl partial results file (format "
                               f"{PARTIAL_FORMAT!r}): remove it or run without resume")
        if data.get("version") != PARTIAL_VERSION:
            raise v.InputError(f"{name} has version {data.get('version')!r}, expected "
                               f"{PARTIAL_VERSION}: remove it or run without resume")
        if data.get("fingerprint") != self.fingerprint or data.get("total") != len(keys):
            raise v.InputError(f"{name} belongs to another study ({data.get('total')!r} points "
                               f"of {data.get('fingerprint')!r}, this one: {len(keys)} of "
                               f"{self.fingerprint!r}): remove it or run without resume")
        out: dict[int, Any] = {}
        for point in data.get("points", []):
            i, key = point.get("index"), point.get("key")
            if not isinstance(i, int) or not 0 <= i < len(keys) or key != keys[i]:
                raise v.InputError(f"{name}: point {key!r} at index {i!r} is not point "
                                   f"{i!r} of this study: remove it or run without resume")
            out[i] = _decode(point, name)
        return out

    def write(self, keys: Sequence[str], results: dict[int, Any]) -> Path:
        """Write the finished points (atomically: the file is complete at every moment)."""
        points = [{"index": i, "key": keys[i], **_encode(results[i])} for i in sorted(results)]
        data = {"format": PARTIAL_FORMAT, "version": PARTIAL_VERSION,
                "fingerprint": self.fingerprint, "total": len(keys), "done": len(results),
                "points": points}
        return fileio.write_text(self.path, json.dumps(data, indent=1), what="partial results file")

    def discard(self) -> None:
        """Remove the file (after the final result is written); nothing if it is absent."""
        try:
            os.remove(self.path)
        except FileNotFoundError:
            pass
        except OSError as exc:
            raise v.InputError(f"cannot remove partial results file {str(self.path)!r}: "
                               f"{fileio.reason(exc)}") from None


def _plain(x: Any) -> bool:
    """JSON round-trips `x` exactly (floats by repr; NaN and infinities as JSON extensions)."""
    if x is None or type(x) in (bool, int, str) or isinstance(x, float):
        return True
    if isinstance(x, list):
        return all(_plain(y) for y in x)
    if isinstance(x, dict):
        return all(isinstance(k, str) and _plain(y) for k, y in x.items())
    return False


def _encode(result: Any) -> dict[str, Any]:
    if isinstance(result, TaskError):
        return {"error": result.message, "error_type": result.kind}
    if _plain(result):
        return {"value": result}
    return {"pickle": base64.b64encode(pickle.dumps(result)).decode("ascii")}


def _decode(point: dict[str, Any], name: str) -> Any:
    if "error" in point:
        return TaskError(str(point.get("error_type", "Error")), str(point["error"]))
    if "value" in point:
        return point["value"]
    if "pickle" in point:
        return pickle.loads(base64.b64decode(point["pickle"]))
    raise v.InputError(f"{name}: point {point.get('key')!r} has no result: remove the file or "
                       "run without resume")


class _Guarded:
    """``func(task)``, an exception returned as a :class:`TaskError` (picklable when `func` is)."""

    def __init__(self, func: Callable[[Any], Any]) -> None:
        self.func = func

    def __call__(self, task: Any) -> Any:
        try:
            return self.func(task)
        except Exception as exc:  # recorded in the point's place, the others go on
            message = " ".join(str(exc).split()) or type(exc).__name__
            return TaskError(type(exc).__name__, message)


# ----------------------------------------------------------------------------- back ends
def _init_worker() -> None:
    """Pin BLAS to one thread in a worker (2 cores: processes × 1 thread)."""
    for var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
        os.environ[var] = "1"
    from threadpoolctl import threadpool_limits

    threadpool_limits(limits=1)


def _serial(func: Callable, items: list[tuple[int, Any]]) -> Iterator[tuple[int, Any]]:
    for i, t in items:
        yield i, func(t)


def _processes(func: Callable, items: list[tuple[int, Any]], workers: int) -> Iterator[tuple[int, Any]]:
    pool = ProcessPoolExecutor(max_workers=workers, initializer=_init_worker)
    try:
        futures = {pool.submit(func, t): i for i, t in items}
        for f in as_completed(futures):
            yield futures[f], f.result()
    finally:  # also when the consumer stops early (interrupted): drop the points not started
        pool.shutdown(wait=True, cancel_futures=True)


def _one_blas_thread_plugin():
    """A Dask worker plugin running :func:`_init_worker` on every worker, present and future."""
    from distributed.diagnostics.plugin import WorkerPlugin

    class OneBlasThread(WorkerPlugin):
        name = "propwhirl-one-blas-thread"

        def setup(self, worker) -> None:  # noqa: D102 (Dask's hook)
            _init_worker()

    return OneBlasThread()


def _dask(func: Callable, items: list[tuple[int, Any]], client) -> Iterator[tuple[int, Any]]:
    from distributed import as_completed as dask_completed

    client.register_plugin(_one_blas_thread_plugin())
    futures = client.map(func, [t for _, t in items], pure=False)
    index = {f.key: i for f, (i, _) in zip(futures, items)}
    try:
        for f in dask_completed(futures):
            yield index[f.key], f.result()
    finally:
        client.cancel([f for f in futures if not f.done()])


def connect(scheduler: str, timeout: float = 10.0):
    """A ``dask.distributed.Client`` of the scheduler at address `scheduler`
    (e.g. ``"tcp://host:8786"``); one-line errors when dask is missing or it cannot connect."""
    if not isinstance(scheduler, str) or not scheduler.strip():
        raise v.InputError(f"scheduler = {scheduler!r} is invalid: must be an address such as "
                           "'tcp://host:8786'")
    Client = _client_class("scheduler")
    try:
        return Client(scheduler, timeout=timeout)
    except (OSError, TimeoutError, ValueError) as exc:
        reason = " ".join(str(exc).split()) or type(exc).__name__
        raise v.InputError(f"scheduler = {scheduler!r}: cannot connect ({reason})") from None


def _client_class(what: str):
    try:
        from distributed import Client
    except ImportError:
        raise v.InputError(f"{what} needs dask.distributed, which is not installed: "
                           "pip install propwhirl[distributed]") from None
    return Client


def _backend(func: Callable, items: list[tuple[int, Any]], processes: int,
             client) -> Iterator[tuple[int, Any]]:
    if not items:
        return _serial(func, items)
    if client is not None:
        return _dask(func, items, client)
    workers = min(processes, len(items), os.cpu_count() or 1)
    if workers <= 1:
        return _serial(func, items)
    return _processes(func, items, workers)


# ----------------------------------------------------------------------------- the map
def _keys(keys: Iterable[str] | None, n: int) -> list[str]:
    if keys is None:
        return [str(i) for i in range(n)]
    out = [str(k) for k in keys]
    if len(out) != n:
        raise v.InputError(f"keys has {len(out)} entries, expected one per task ({n})")
    if len(set(out)) != n:
        raise v.InputError("keys is invalid: two tasks have the same key")
    return out


def map_analyses(func: Callable[[Any], Any], tasks: Sequence[Any], processes: int = 1,
                 client=None, progress: bool | ProgressCallback | None = None, *,
                 errors: Literal["raise", "record"] = "raise", checkpoint: Checkpoint | None = None,
                 keys: Sequence[str] | None = None, desc: str = "points") -> list[Any]:
    """``[func(t) for t in tasks]``, order preserved, on the back end chosen (module docstring).

    processes: local worker processes (1: in this process; at most one per CPU);
    client:    a ``dask.distributed.Client`` or a scheduler address: run on that cluster;
    progress:  None/False (nothing), True (a bar on stderr when it is a terminal,
               :func:`propwhirl.progress.bar`) or a callable ``report(done, total)`` called
               after every finished point (and once before the first, with the points resumed);
    errors:    "raise" (a failing point stops the run) or "record" (a :class:`TaskError` in
               its place, the others go on);
    checkpoint: keep the finished points in a partial-results file, and resume from it;
    keys:      one string per task naming it in the partial-results file (default: its index);
    desc:      the progress bar's label.
    """
    v.integer_at_least("processes", processes, 1)
    if errors not in ("raise", "record"):
        raise v.InputError(f"errors = {errors!r} is invalid: must be 'raise' or 'record'")
    if checkpoint is not None and not isinstance(checkpoint, Checkpoint):
        raise v.InputError(f"checkpoint = {checkpoint!r} is invalid: must be a "
                           "propwhirl.studies.execution.Checkpoint")
    tasks = list(tasks)
    n = len(tasks)
    names = _keys(keys, n)
    results: dict[int, Any] = checkpoint.load(names) if checkpoint and checkpoint.resume else {}
    own_client = None
    if isinstance(client, str):
        client = own_client = connect(client)
    elif client is not None and not hasattr(client, "map"):
        raise v.InputError(f"client = {client!r} is invalid: must be a dask.distributed.Client "
                           "or a scheduler address such as 'tcp://host:8786'")
    call = _Guarded(func) if errors == "record" else func
    todo = [(i, t) for i, t in enumerate(tasks) if i not in results]
    last_write = time.monotonic()
    try:
        with reporter(progress, desc, n) as report:
            report(len(results), n)
            finished = _backend(call, todo, processes, client)
            try:
                for i, r in finished:
                    results[i] = r
                    if checkpoint is not None and (time.monotonic() - last_write >= checkpoint.interval
                                                   or len(results) == n):
                        checkpoint.write(names, results)
                        last_write = time.monotonic()
                    report(len(results), n)
            except BaseException as exc:
                if checkpoint is not None and results:
                    checkpoint.write(names, results)
                if isinstance(exc, KeyboardInterrupt) and not isinstance(exc, Interrupted):
                    path = Path(checkpoint.path) if checkpoint is not None and results else None
                    raise Interrupted(len(results), n, path) from exc
                raise
            finally:  # stops the workers' remaining points now, not when collected
                finished.close()
    finally:
        if own_client is not None:
            own_client.close()
    if checkpoint is not None and len(results) == n and not todo:
        checkpoint.write(names, results)  # everything resumed: the file stays complete
    return [results[i] for i in range(n)]


def failures(results: Sequence[Any]) -> list[tuple[int, TaskError]]:
    """The failed points of a result list: (index, :class:`TaskError`)."""
    return [(i, r) for i, r in enumerate(results) if isinstance(r, TaskError)]
