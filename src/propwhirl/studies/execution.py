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
The partial-results file, its fingerprint and the point formats are
:mod:`propwhirl.studies.partial` (re-exported here: ``Checkpoint``, ``TaskError``, ...).
"""
from __future__ import annotations

import os
import re
import struct
import time
from concurrent.futures import ProcessPoolExecutor, as_completed
from pathlib import Path
from typing import Any, Callable, Iterable, Iterator, Literal, Sequence

from propwhirl import fileio
from propwhirl import validate as v
from propwhirl.progress import ProgressCallback, reporter
from propwhirl.studies.partial import (  # noqa: F401 (re-exported: their former home)
    MAX_DEPTH, MAX_PARTIAL_BYTES, MAX_STRING, OLD_PARTIAL_FORMAT, PARTIAL_FORMAT, PARTIAL_VERSION,
    PLAIN, Checkpoint, PointFormat, TaskError, check_plain, content_digest,
    fingerprint_differences)


# ----------------------------------------------------------------------------- records
class Interrupted(KeyboardInterrupt):
    """A run interrupted (Ctrl-C) after `done` of `total` points, kept in `path` (or None)."""

    def __init__(self, done: int, total: int, path: Path | None) -> None:
        self.done, self.total, self.path = done, total, path
        where = f" kept in {str(path)!r}: run it again with resume (--resume) to continue" if path else ""
        super().__init__(f"{done} of {total} points finished{where}")


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
#: Longest wait for the scheduler to accept a connection and send its handshake [s] (one
#: attempt; :func:`connect`).
CONNECT_TIMEOUT = 5.0
#: Most bytes the handshake a Dask scheduler sends first may announce (its own is about 60):
#: a server that announces more, e.g. the text "SSH-2.0-" read as a length, is not one.
MAX_HANDSHAKE_BYTES = 1 << 16


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
    if not colon or not host or re.fullmatch(r"[0-9]{1,5}", port) is None \
            or not 1 <= int(port) <= 65535 or any(c in host for c in "/?#@ "):
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


def _receive(sock, n: int, deadline: float) -> bytes:
    """Exactly `n` bytes from `sock` before `deadline` (:func:`time.monotonic`), or fewer when
    the peer closes the connection; :class:`TimeoutError` past the deadline."""
    data = b""
    while len(data) < n:
        left = deadline - time.monotonic()
        if left <= 0:
            raise TimeoutError
        sock.settimeout(left)
        chunk = sock.recv(n - len(data))
        if not chunk:
            break
        data += chunk
    return data


def _handshake(data: bytes) -> Any:
    """The handshake message of a Dask comm (frames packed as ``distributed.protocol``'s
    ``pack_frames``: a count, the lengths, msgpack), or None when `data` is not one."""
    try:
        (count,) = struct.unpack_from("Q", data)
        if not 1 <= count <= 16:
            return None
        lengths = struct.unpack_from(f"{count}Q", data, 8)
        if 8 * (1 + count) + sum(lengths) != len(data):
            return None
        from distributed.protocol.core import loads
        from distributed.protocol.utils import unpack_frames

        return loads(unpack_frames(data), deserialize=False)
    except Exception:  # any malformed message: not a scheduler's handshake
        return None


def _probe(scheme: str, host: str, port: int, scheduler: str, timeout: float) -> None:
    """One connection to the scheduler's port that must, within `timeout` [s] in all, be
    accepted and receive the handshake a Dask scheduler sends first (its Python version,
    compression, pickle protocol: at most :data:`MAX_HANDSHAKE_BYTES`); closed again.  An
    InputError naming the address otherwise — refused or unreachable (at once), silent (a
    server that waits to be spoken to, e.g. HTTP), or answering something else (an SSH
    banner): the Dask client would read such an answer as a frame length (exabytes) or wait
    for it without end."""
    import socket

    deadline = time.monotonic() + timeout
    where = f"scheduler = {scheduler!r}"
    try:
        sock = socket.create_connection((host, port), timeout=timeout)
    except (OSError, ValueError) as exc:
        why = "timed out" if isinstance(exc, TimeoutError) else fileio.reason(exc)
        raise v.InputError(f"{where}: cannot connect to {host}:{port} ({why})") from None
    try:
        if scheme == "tls":
            from distributed.security import Security

            ctx = Security().get_connection_args("client")["ssl_context"]
            sock.settimeout(max(deadline - time.monotonic(), 1e-3))
            sock = ctx.wrap_socket(sock, server_hostname=host)
        header = _receive(sock, 8, deadline)
        size = struct.unpack("Q", header)[0] if len(header) == 8 else 0
        body = _receive(sock, size, deadline) if 16 <= size <= MAX_HANDSHAKE_BYTES else b""
    except TimeoutError:
        raise v.InputError(f"{where}: {host}:{port} accepted the connection but sent no Dask "
                           f"handshake within {timeout:g} s (not a Dask scheduler, or not "
                           "answering)") from None
    except (OSError, ValueError) as exc:   # a TLS handshake refused, a reset ...
        raise v.InputError(f"{where}: {host}:{port} is not a Dask scheduler: "
                           f"{' '.join(fileio.reason(exc).split())[:120]}") from None
    finally:
        sock.close()
    message = _handshake(header + body) if len(body) == size else None
    if not (isinstance(message, dict) and "python" in message):
        seen = (header + body)[:24]
        raise v.InputError(f"{where}: {host}:{port} answered, but not as a Dask scheduler "
                           + (f"(its first bytes: {seen!r})" if seen else
                              "(it closed the connection without a handshake)"))


def connect(scheduler: str, timeout: float | None = None):
    """A ``dask.distributed.Client`` of the scheduler at address `scheduler`
    (``tcp://host:8786``; ``tls://`` with the Dask configuration's certificates).

    One attempt, bounded by `timeout` [s] (default :data:`CONNECT_TIMEOUT`): the scheduler's
    port must accept a connection and send a Dask scheduler's handshake within it
    (:func:`_probe`: else an InputError naming the address and the reason — at once for a
    refused connection, a server answering something else, e.g. an SSH banner or an HTTP
    error; after `timeout` for one that never answers); the client is then made once.
    One-line errors too when dask is missing or the address or its scheme is invalid
    (``ucx://``, ``inproc://`` ..., a port that is not ASCII digits)."""
    timeout = CONNECT_TIMEOUT if timeout is None else timeout
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
        _probe(scheme, host, port, scheduler, timeout)  # a Dask scheduler answers, in time
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
    progress:  None/False (nothing), True (a bar on stderr, plain lines when it is not a
               terminal: :func:`propwhirl.progress.bar`) or a callable ``report(done,
               total)`` called after every finished point (and once before the first, with
               the points resumed);
    errors:    "raise" (a failing point stops the run) or "record" (a :class:`TaskError` in
               its place, the others go on);
    checkpoint: keep the finished points in a partial-results file, and resume from it;
    keys:      one string per task naming it in the partial-results file (default: its index);
    desc:      the progress bar's label.

    Parameters
    ----------
    func : callable
        ``func(task)``; on processes or a cluster a module-level function (picklable).
    tasks : sequence
        The tasks.
    processes : int
        Local worker processes (1: in this process).
    client : dask.distributed.Client or str, optional
        Run on that cluster (or scheduler address).
    progress : bool or callable, optional
        A progress bar (True) or ``report(done, total)``.
    errors : {"raise", "record"}
        A failing point stops the run, or is recorded as a :class:`TaskError`.
    checkpoint : Checkpoint, optional
        The partial-results file.
    keys : sequence of str, optional
        One string per task naming it in the partial-results file.
    desc : str
        The progress bar's label.

    Returns
    -------
    list
        ``func(t)`` of every task, in order (with ``errors="record"``: a
        :class:`TaskError` in a failed task's place).

    Examples
    --------
    >>> from propwhirl.studies import map_analyses
    >>> map_analyses(abs, [-1.0, 2.0, -3.0])
    [1.0, 2.0, 3.0]
    >>> from propwhirl.analysis import analyse
    >>> from propwhirl.cases.ch09_baseline import isolated_baseline_propeller
    >>> models = [isolated_baseline_propeller(f_psi=f) for f in (6.0, 8.0)]
    >>> [round(a.critical.V, 1) for a in map_analyses(analyse, models)]
    [216.2, 257.6]
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
