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
of that file, runs only the others, and returns the same list as an uninterrupted run.

The partial-results file (format ``propwhirl.partial/2``) is plain JSON — numbers, strings,
lists and objects, nothing that carries code: it may come from anyone, so it is read like any
other result file, every entry checked (:meth:`Checkpoint.load`).  It holds

* ``fingerprint``: an object naming everything that decides a point's result — for a study the
  sha256 of the model's canonical content (:func:`content_digest`), the parameter paths and
  values, the speeds, the method, the convention, the tolerance — plus the propwhirl version and
  the kind of the points.  A file whose fingerprint differs is refused, naming the entries that
  differ; it is never mixed in.  The study functions fill the fingerprint in from their own
  arguments (a Checkpoint given without one gets a full one);
* ``points``: one object per finished point, ``{"index", "key", "value"}`` or, for a failed
  point, ``{"index", "key", "error", "error_type"}``.  The value is written and read by the
  checkpoint's :class:`PointFormat`: :data:`PLAIN` (the default: numbers, strings, booleans,
  null, lists and objects with string keys; floats round-trip exactly) or a per-kind schema
  such as the study row of :mod:`propwhirl.studies.runner`.
"""
from __future__ import annotations

import dataclasses
import hashlib
import json
import marshal
import math
import os
import time
from concurrent.futures import ProcessPoolExecutor, as_completed
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable, Iterable, Iterator, Literal, Mapping, Sequence

import numpy as np

from propwhirl import fileio
from propwhirl import validate as v
from propwhirl.progress import ProgressCallback, reporter

#: Version of the partial-results file layout (2: plain JSON only, a structured fingerprint).
PARTIAL_VERSION = 2
#: The format tag of a partial-results file.
PARTIAL_FORMAT = f"propwhirl.partial/{PARTIAL_VERSION}"
#: The format tag of the files of version 1 (they could hold pickles: never read).
OLD_PARTIAL_FORMAT = "propwhirl partial results"
#: Largest partial-results file read [bytes] (a map of 250 000 points is ~100 MB).
MAX_PARTIAL_BYTES = 256 * 2**20
#: Deepest nesting of lists and objects in a partial-results file (the file's own levels
#: included: a point's value may nest about 12 deep).
MAX_DEPTH = 16
#: Longest string of a partial-results file (a key, a message, a label) [characters].
MAX_STRING = 100_000

_AGAIN = "remove it or run without --resume"


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


# ----------------------------------------------------------------------------- plain data
def _json_type(x: Any) -> str:
    return {dict: "an object", list: "a list", str: "a string", bool: "a boolean",
            int: "an integer", float: "a number", type(None): "null"}.get(type(x), type(x).__name__)


def check_plain(x: Any, where: str, *, max_depth: int = MAX_DEPTH, finite: bool = False) -> Any:
    """`x` when it is plain JSON data — None, bool, int, float, str, lists and dicts with
    string keys — nested at most `max_depth` deep with strings of at most :data:`MAX_STRING`
    characters (and, with `finite`, no NaN or infinity); else an InputError naming where
    (`where`, then the keys and indices) and what is wrong.  Iterative: any depth is refused
    without recursion."""
    stack: list[tuple[Any, str, int]] = [(x, where, 0)]
    while stack:
        y, at, depth = stack.pop()
        if y is None or type(y) in (bool, int):
            continue
        if isinstance(y, float):
            if finite and not math.isfinite(y):
                raise v.InputError(f"{at}: {y!r} is invalid: must be a finite number")
            continue
        if isinstance(y, str):
            if len(y) > MAX_STRING:
                raise v.InputError(f"{at}: a string of {len(y)} characters (at most {MAX_STRING})")
            continue
        if not isinstance(y, (list, dict)):
            raise v.InputError(f"{at}: {_json_type(y)} is not plain data (numbers, strings, "
                               "booleans, null, lists and objects with string keys)")
        if depth >= max_depth:
            raise v.InputError(f"{at}: nested too deeply (more than {max_depth} levels)")
        if isinstance(y, list):
            stack.extend((z, f"{at}[{i}]", depth + 1) for i, z in enumerate(y))
        else:
            for k, z in y.items():
                if not isinstance(k, str):
                    raise v.InputError(f"{at}: key {k!r} is not a string")
                stack.append((z, f"{at}.{k}", depth + 1))
    return x


# ----------------------------------------------------------------------------- fingerprints
def _canonical(obj: Any, depth: int, seen: dict[int, Any]) -> Any:
    """A JSON-able form of `obj` that two equal models share and two different ones do not:
    dataclasses by their type and init fields (derived, ``_``-prefixed fields left out),
    floats by their exact repr, arrays by dtype, shape and the sha256 of their bytes,
    functions by their qualified name and the sha256 of their code."""
    if depth > 64:
        raise v.InputError("the model is nested too deeply to be fingerprinted (more than 64 levels)")
    if obj is None or isinstance(obj, (bool, str)):
        return obj
    if isinstance(obj, (int, np.integer)):
        return int(obj)
    if isinstance(obj, (float, np.floating)):
        return ["float", repr(float(obj))]
    if isinstance(obj, np.generic):
        return ["scalar", str(obj.dtype), repr(obj.item())]
    if isinstance(obj, np.ndarray):
        key = id(obj)
        if key not in seen:
            arr = np.ascontiguousarray(obj)
            seen[key] = ["array", str(arr.dtype), list(arr.shape),
                         hashlib.sha256(arr.tobytes()).hexdigest()]
        return seen[key]
    if dataclasses.is_dataclass(obj) and not isinstance(obj, type):
        return ["dataclass", f"{type(obj).__module__}.{type(obj).__qualname__}",
                {f.name: _canonical(getattr(obj, f.name), depth + 1, seen)
                 for f in dataclasses.fields(obj) if f.init and not f.name.startswith("_")}]
    if isinstance(obj, (list, tuple)):
        return [type(obj).__name__, [_canonical(x, depth + 1, seen) for x in obj]]
    if isinstance(obj, Mapping):
        items = [[_canonical(k, depth + 1, seen), _canonical(x, depth + 1, seen)]
                 for k, x in obj.items()]
        return ["mapping", sorted(items, key=lambda kv: json.dumps(kv, sort_keys=True))]
    if callable(obj):
        code = getattr(obj, "__code__", None)
        return ["callable", f"{getattr(obj, '__module__', '')}.{getattr(obj, '__qualname__', repr(obj))}",
                None if code is None else hashlib.sha256(marshal.dumps(code)).hexdigest()]
    return ["object", f"{type(obj).__module__}.{type(obj).__qualname__}", repr(obj)]


def content_digest(obj: Any) -> str:
    """``"sha256:<hex>"`` of the canonical content of `obj` (a model, a propeller, a list of
    speed grids ...): equal for equal content, whatever file or defaults it came from; any
    field that differs (a number in its last bit, a distribution, a switch) changes it."""
    text = json.dumps(_canonical(obj, 0, {}), sort_keys=True, separators=(",", ":"))
    return "sha256:" + hashlib.sha256(text.encode("utf-8")).hexdigest()


def _fingerprint(fp: Any) -> dict[str, Any]:
    """A checkpoint's fingerprint as a dict (a non-empty string is ``{"label": text}``)."""
    if isinstance(fp, str):
        return {"label": fp} if fp else {}
    if not isinstance(fp, Mapping):
        raise v.InputError(f"fingerprint = {v.short_repr(fp)} is invalid: must be a mapping "
                           "{name: plain value} (or a string)")
    out = dict(fp)
    check_plain(out, "fingerprint")
    return out


def _short(x: Any) -> str:
    if isinstance(x, str) and x.startswith("sha256:"):
        return f"sha256 {x[7:19]}…"
    return v.short_repr(x, 40)


def fingerprint_differences(stored: Mapping[str, Any], current: Mapping[str, Any]) -> list[str]:
    """``name (the file's vs this run's)`` of each entry that differs (absent: "none")."""
    out = []
    for k in sorted(set(stored) | set(current)):
        a, b = stored.get(k, None), current.get(k, None)
        if k not in stored or k not in current or a != b or type(a) is not type(b):
            out.append(f"{k} ({_short(a) if k in stored else 'none'} vs "
                       f"{_short(b) if k in current else 'none'})")
    return out


# ----------------------------------------------------------------------------- point formats
@dataclass(frozen=True)
class PointFormat:
    """How a point's result is kept in a partial-results file: as plain JSON, each kind with
    its schema.

    name:   the kind, recorded in the fingerprint (a file of another kind is refused);
    encode: result -> plain JSON data (an InputError when the result does not fit the schema);
    decode: (plain data, where, key) -> the result of the point named `key`, every entry
            checked (an InputError naming ``where`` and the entry).
    """

    name: str
    encode: Callable[[Any], Any]
    decode: Callable[[Any, str, str], Any]


def _plain_encode(result: Any) -> Any:
    return check_plain(result, "result")


def _plain_decode(value: Any, where: str, key: str | None = None) -> Any:
    return check_plain(value, where)


#: The default point format: the result itself when it is plain JSON data (numbers, strings,
#: booleans, None, lists, dicts with string keys; NaN and infinities as JSON's extensions).
PLAIN = PointFormat("plain", _plain_encode, _plain_decode)


# ----------------------------------------------------------------------------- checkpoint
@dataclass(frozen=True)
class Checkpoint:
    """Where a run keeps its finished points, and whether it resumes from them.

    path:        the partial-results file (JSON), e.g. beside the final result;
    resume:      load the finished points of `path` (if it exists) and run only the others;
    fingerprint: what decides a point's result, ``{name: plain value}`` (a string is
                 ``{"label": text}``): a file with another fingerprint is refused.  The study
                 functions add their own entries (:meth:`with_entries`);
    interval:    shortest time between two rewrites of the file while running [s];
    points:      how a point's result is written and read (:class:`PointFormat`; default
                 :data:`PLAIN`).
    """

    path: str | Path
    resume: bool = False
    fingerprint: Mapping[str, Any] | str = field(default_factory=dict)
    interval: float = 2.0
    points: PointFormat = PLAIN

    def __post_init__(self) -> None:
        if not isinstance(self.path, (str, Path)) or not str(self.path):
            raise v.InputError(f"path = {self.path!r} is invalid: must be a file name")
        v.boolean("resume", self.resume)
        v.non_negative("interval", self.interval, "s")
        object.__setattr__(self, "fingerprint", _fingerprint(self.fingerprint))
        if not isinstance(self.points, PointFormat):
            raise v.InputError(f"points = {self.points!r} is invalid: must be a "
                               "propwhirl.studies.execution.PointFormat")

    def with_entries(self, points: PointFormat | None = None, **entries: Any) -> "Checkpoint":
        """This checkpoint with `entries` added to its fingerprint (replacing those of the
        same name) and, if given, the point format `points`."""
        new = {**self.fingerprint, **entries}
        return dataclasses.replace(self, fingerprint=new,
                                   points=self.points if points is None else points)

    def full_fingerprint(self, total: int) -> dict[str, Any]:
        """The fingerprint written to the file: this one, the point kind, the number of
        points and the propwhirl version."""
        from propwhirl import __version__

        return {**self.fingerprint, "points": self.points.name, "total": total,
                "propwhirl": __version__}

    def _name(self) -> str:
        return f"partial results file {str(self.path)!r}"

    def load(self, keys: Sequence[str]) -> dict[int, Any]:
        """The finished points {index: result} of the file ({} when it does not exist);
        every entry checked: a one-line InputError naming the file and the entry otherwise."""
        path = Path(self.path)
        if not path.exists():
            return {}
        name = self._name()
        try:
            size = path.stat().st_size
        except OSError as exc:
            raise v.InputError(f"cannot read {name}: {fileio.reason(exc)}") from None
        if size > MAX_PARTIAL_BYTES:
            raise v.InputError(f"{name} has {size} bytes, more than a partial results file "
                               f"holds ({MAX_PARTIAL_BYTES}): {_AGAIN}")
        data = _parse(fileio.read_text(path, "partial results file"), name)
        try:
            return self._points(data, keys, name)
        except v.InputError as exc:
            raise v.InputError(f"{name}: {exc}: {_AGAIN}") from None

    def _points(self, data: Any, keys: Sequence[str], name: str) -> dict[int, Any]:
        if not isinstance(data, dict):
            raise v.InputError(f"not a propwhirl partial results file (format {PARTIAL_FORMAT!r}): "
                               f"it is {_json_type(data)}")
        if data.get("format") == OLD_PARTIAL_FORMAT:
            raise v.InputError("written by an older propwhirl (partial results version 1, which "
                               "could hold pickled data: never read)")
        if data.get("format") != PARTIAL_FORMAT:
            raise v.InputError(f"not a propwhirl partial results file (format "
                               f"{PARTIAL_FORMAT!r}, got {v.short_repr(data.get('format'))})")
        wanted = {"format", "fingerprint", "done", "points"}
        missing = sorted(wanted - set(data))
        unknown = sorted(set(data) - wanted)
        if missing or unknown:
            raise v.InputError(f"missing keys {missing}" if missing else f"unknown keys {unknown}")
        stored = data["fingerprint"]
        if not isinstance(stored, dict):
            raise v.InputError(f"fingerprint: must be an object, got {_json_type(stored)}")
        diff = fingerprint_differences(stored, self.full_fingerprint(len(keys)))
        if diff:
            raise v.InputError(f"was written for another study: {', '.join(diff)} differ "
                               "(the file's vs this run's)")
        points = data["points"]
        if not isinstance(points, list):
            raise v.InputError(f"points: must be a list, got {_json_type(points)}")
        done = data["done"]
        if type(done) is not int or done != len(points):
            raise v.InputError(f"done = {v.short_repr(done)} is invalid: the file holds "
                               f"{len(points)} points")
        out: dict[int, Any] = {}
        for j, point in enumerate(points):
            where = f"points[{j}]"
            if isinstance(point, dict) and "pickle" in point:
                raise v.InputError(f"{where} holds a pickle (a file of an older propwhirl): "
                                   "never read")
            if not isinstance(point, dict):
                raise v.InputError(f"{where}: must be an object, got {_json_type(point)}")
            kind = "error" if "error" in point else "value"
            allowed = {"index", "key", kind} | ({"error_type"} if kind == "error" else set())
            if set(point) != allowed:
                unknown = sorted(set(point) - allowed)
                missing = sorted(allowed - set(point))
                raise v.InputError(f"{where}: unknown keys {unknown}" if unknown
                                   else f"{where}: missing keys {missing}")
            i, key = point["index"], point["key"]
            if type(i) is not int or not 0 <= i < len(keys):
                raise v.InputError(f"{where}.index = {v.short_repr(i)} is invalid: must be an "
                                   f"integer in [0, {len(keys) - 1}]")
            if key != keys[i]:
                raise v.InputError(f"point {v.short_repr(key)} at index {i} is not point {i} "
                                   f"of this study ({v.short_repr(keys[i])})")
            if i in out:
                raise v.InputError(f"{where}: point {i} is given twice")
            if kind == "error":
                message, error_type = point["error"], point["error_type"]
                if not isinstance(message, str) or not isinstance(error_type, str) \
                        or not error_type.isidentifier() or "\n" in message:
                    raise v.InputError(f"{where}: error and error_type must be a one-line "
                                       "message and an exception's name")
                check_plain(message, f"{where}.error")
                out[i] = TaskError(error_type, message)
            else:
                out[i] = self.points.decode(point["value"], f"{where}.value", key)
        return out

    def encode(self, keys: Sequence[str], i: int, result: Any) -> str:
        """The JSON text of point `i` in the file (its value by :attr:`points`)."""
        if isinstance(result, TaskError):
            entry = {"error": str(result.message), "error_type": str(result.kind)}
        else:
            try:
                entry = {"value": self.points.encode(result)}
            except v.InputError as exc:
                raise v.InputError(f"{self._name()}: the result of point {keys[i]!r} cannot be "
                                   f"kept ({exc})") from None
        return json.dumps({"index": i, "key": keys[i], **entry})

    def write(self, keys: Sequence[str], results: dict[int, Any],
              encoded: dict[int, str] | None = None) -> Path:
        """Write the finished points (atomically: the file is complete at every moment);
        `encoded`: the points' JSON texts already made by :meth:`encode` (kept by the run)."""
        lines = [encoded[i] if encoded is not None and i in encoded else self.encode(keys, i, results[i])
                 for i in sorted(results)]
        head = json.dumps({"format": PARTIAL_FORMAT, "fingerprint": self.full_fingerprint(len(keys)),
                           "done": len(results)})
        text = head[:-1] + ', "points": [\n' + ",\n".join(lines) + "\n]}\n"
        return fileio.write_text(self.path, text, what="partial results file")

    def discard(self) -> None:
        """Remove the file (after the final result is written); nothing if it is absent."""
        try:
            os.remove(self.path)
        except FileNotFoundError:
            pass
        except OSError as exc:
            raise v.InputError(f"cannot remove partial results file {str(self.path)!r}: "
                               f"{fileio.reason(exc)}") from None


def _parse(text: str, name: str) -> Any:
    """The JSON of a partial-results file, checked to be plain data of bounded depth."""
    try:
        data = json.loads(text)
    except json.JSONDecodeError as exc:
        raise v.InputError(f"{name} is not valid JSON ({exc.msg}, line {exc.lineno}): "
                           f"{_AGAIN}") from None
    except RecursionError:
        raise v.InputError(f"{name}: nested too deeply (more than {MAX_DEPTH} levels): "
                           f"{_AGAIN}") from None
    except ValueError as exc:  # an integer of too many digits
        raise v.InputError(f"{name} is not a partial results file ({' '.join(str(exc).split())}): "
                           f"{_AGAIN}") from None
    try:
        return check_plain(data, "file")
    except v.InputError as exc:
        raise v.InputError(f"{name}: {exc}: {_AGAIN}") from None


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


#: Schemes of a scheduler address that :func:`connect` opens (tls: with the certificates of
#: the Dask configuration, ``distributed.comm.tls``; inproc: a cluster of this process).
SCHEMES = ("tcp", "tls", "inproc")
#: Longest wait for the scheduler to accept a connection [s] (one attempt).
CONNECT_TIMEOUT = 5.0


def _address(scheduler: Any) -> tuple[str, str, int]:
    """(scheme, host, port) of a scheduler address ``[scheme://]host:port`` (scheme tcp when
    not given); a one-line InputError for anything else."""
    example = "must be an address such as 'tcp://host:8786'"
    if not isinstance(scheduler, str) or not scheduler.strip():
        raise v.InputError(f"scheduler = {v.short_repr(scheduler)} is invalid: {example}")
    text = scheduler.strip()
    scheme, sep, rest = text.partition("://")
    if not sep:
        scheme, rest = "tcp", text
    scheme = scheme.lower()
    if scheme == "inproc" and rest:
        return scheme, rest, 0
    if scheme not in SCHEMES:
        raise v.InputError(f"scheduler = {v.short_repr(scheduler)} is invalid: the scheme "
                           f"{v.short_repr(scheme)} is not supported (tcp:// or tls://; {example})")
    host, colon, port = rest.rpartition(":")
    if host.startswith("[") and host.endswith("]"):
        host = host[1:-1]                                   # [IPv6]:port
    if not colon or not host or not port.isdigit() or not 1 <= int(port) <= 65535 \
            or any(c in host for c in "/?#@ "):
        raise v.InputError(f"scheduler = {v.short_repr(scheduler)} is invalid: {example} "
                           "(a host and a port in [1, 65535])")
    if scheme == "tls":
        import dask

        tls = dask.config.get("distributed.comm.tls", default={}) or {}
        client = tls.get("client", {}) if isinstance(tls, dict) else {}
        if not (tls.get("ca-file") and client.get("cert")):
            raise v.InputError(f"scheduler = {v.short_repr(scheduler)}: tls:// needs the "
                               "certificates in the Dask configuration (distributed.comm.tls."
                               "ca-file and distributed.comm.tls.client.cert), none are set")
    return scheme, host, int(port)


def check_scheduler(scheduler: str) -> None:
    """Check a scheduler address before any work (dask installed, a supported scheme, a host
    and a port): the one-line errors of :func:`connect`, without connecting."""
    _client_class("scheduler")
    _address(scheduler)


def connect(scheduler: str, timeout: float = CONNECT_TIMEOUT):
    """A ``dask.distributed.Client`` of the scheduler at address `scheduler`
    (``tcp://host:8786``; ``tls://`` with the Dask configuration's certificates).

    One attempt: the scheduler's port must accept a connection within `timeout` [s] (else an
    InputError naming the address and the reason, at once for a refused connection); the
    client is then made once.  One-line errors too when dask is missing or the address or
    its scheme is invalid (``ucx://``, ``inproc://`` ...)."""
    import socket

    v.positive("timeout", timeout, "s")
    Client = _client_class("scheduler")
    scheme, host, port = _address(scheduler)
    if scheme == "inproc":
        from distributed.comm.inproc import global_manager

        address = f"inproc://{host}"
        try:
            listener = global_manager.get_listener_for(host)
        except ValueError:                # another host or process
            listener = None
        if listener is None:
            raise v.InputError(f"scheduler = {scheduler!r}: cannot connect (no scheduler of "
                               "this process listens there)")
    else:
        address = f"{scheme}://{host if ':' not in host else '[' + host + ']'}:{port}"
        try:                              # the probe: refused or unreachable fails here, once
            socket.create_connection((host, port), timeout=timeout).close()
        except (OSError, ValueError) as exc:
            why = "timed out" if isinstance(exc, TimeoutError) else fileio.reason(exc)
            raise v.InputError(f"scheduler = {scheduler!r}: cannot connect to {host}:{port} "
                               f"({why})") from None
    try:
        return Client(address, timeout=timeout)
    except (OSError, TimeoutError, ValueError, TypeError) as exc:
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
    # each point's JSON text, made once when it finishes (a result that cannot be kept in
    # the file stops the run at its first point, not at the first rewrite)
    encoded: dict[int, str] = ({i: checkpoint.encode(names, i, r) for i, r in results.items()}
                               if checkpoint is not None else {})
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
                    if checkpoint is not None:
                        encoded[i] = checkpoint.encode(names, i, r)
                    results[i] = r
                    if checkpoint is not None and (time.monotonic() - last_write >= checkpoint.interval
                                                   or len(results) == n):
                        checkpoint.write(names, results, encoded)
                        last_write = time.monotonic()
                    report(len(results), n)
            except BaseException as exc:
                if checkpoint is not None and results:
                    checkpoint.write(names, results, encoded)
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
        checkpoint.write(names, results, encoded)  # everything resumed: the file stays complete
    return [results[i] for i in range(n)]


def failures(results: Sequence[Any]) -> list[tuple[int, TaskError]]:
    """The failed points of a result list: (index, :class:`TaskError`)."""
    return [(i, r) for i, r in enumerate(results) if isinstance(r, TaskError)]
