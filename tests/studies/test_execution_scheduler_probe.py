"""Issue 33, item 6: ``--scheduler`` / ``client=`` pointed at a server that is not a Dask
scheduler.  Throwaway TCP servers on threads — one sending an SSH banner, one answering HTTP
400 to whatever it reads, one that accepts and never answers, one that closes at once, one
sending a plausible length and garbage — each give one InputError line naming the address,
within the stated connect/handshake timeout the code enforces (here 0.5 s; no test times
anything: a thread joined with a generous bound only stops a hang from stalling the suite);
a port of non-ASCII digits (``²`` passes ``str.isdigit``) is refused as invalid.  A real
scheduler still connects (tests/studies/test_execution_dask.py)."""
from __future__ import annotations

import socket
import struct
import threading

import pytest

pytest.importorskip("distributed", reason="the [distributed] extra is not installed")

from propwhirl.app import cli  # noqa: E402
from propwhirl.studies import execution  # noqa: E402
from propwhirl.studies.execution import check_scheduler, connect, map_analyses  # noqa: E402
from propwhirl.validate import InputError  # noqa: E402

#: the connect/handshake timeout the tests give [s] (the default is CONNECT_TIMEOUT)
TIMEOUT = 0.5
#: a hang guard, far above TIMEOUT: a call still running then has hung (today's main did)
HANG = 120.0


def _ssh(conn: socket.socket) -> None:
    conn.sendall(b"SSH-2.0-OpenSSH_9.6p1 Ubuntu-3ubuntu13\r\n")


def _http(conn: socket.socket) -> None:
    conn.recv(4096)                              # whatever the client says: a 400
    conn.sendall(b"HTTP/1.1 400 Bad Request\r\nContent-Length: 0\r\nConnection: close\r\n\r\n")


def _silent(conn: socket.socket) -> None:
    pass                                          # accepts, never answers


def _closes(conn: socket.socket) -> None:
    conn.close()


def _garbage(conn: socket.socket) -> None:
    conn.sendall(struct.pack("Q", 40) + b"\x02" + b"\xff" * 39)   # a length, then no frames


SERVERS = {"ssh": _ssh, "http": _http, "silent": _silent, "closes": _closes,
           "garbage": _garbage}


@pytest.fixture(params=sorted(SERVERS))
def server(request):
    """(kind, tcp:// address) of a throwaway server on a thread; its connections are held
    open until the test ends (a silent server must not close them)."""
    listener = socket.create_server(("127.0.0.1", 0))
    held: list[socket.socket] = []
    stop = threading.Event()

    def serve() -> None:
        listener.settimeout(0.1)
        while not stop.is_set():
            try:
                conn, _ = listener.accept()
            except TimeoutError:
                continue
            except OSError:
                return
            held.append(conn)
            conn.settimeout(5.0)                  # a handler waiting to read gives up
            try:
                SERVERS[request.param](conn)
            except OSError:
                pass

    t = threading.Thread(target=serve, daemon=True)
    t.start()
    yield request.param, f"tcp://127.0.0.1:{listener.getsockname()[1]}"
    stop.set()
    t.join()
    listener.close()
    for c in held:
        c.close()


def _outcome(call) -> BaseException | None:
    """The exception `call()` raised (None: it returned), run on a thread joined within
    :data:`HANG` s; a call still running then fails the test (a hang)."""
    box: list = []

    def run() -> None:
        try:
            call()
            box.append(None)
        except BaseException as exc:  # noqa: BLE001 (whatever it is, the test reports it)
            box.append(exc)

    t = threading.Thread(target=run, daemon=True)
    t.start()
    t.join(HANG)
    assert not t.is_alive(), "connect did not return: it hangs"
    return box[0]


def test_a_server_that_is_not_a_dask_scheduler_is_one_line(server):
    kind, address = server
    exc = _outcome(lambda: connect(address, timeout=TIMEOUT))
    assert isinstance(exc, InputError), repr(exc)
    msg = str(exc)
    assert "\n" not in msg and msg.startswith(f"scheduler = {address!r}: "), msg
    if kind == "ssh":
        assert "not as a Dask scheduler" in msg and "SSH-2.0-" in msg
    elif kind in ("http", "silent"):                      # neither speaks first
        assert f"sent no Dask handshake within {TIMEOUT:g} s" in msg
    else:
        assert "not as a Dask scheduler" in msg


def test_a_study_given_such_an_address_stops_before_any_point(server):
    kind, address = server
    done: list = []
    exc = _outcome(lambda: map_analyses(done.append, [1, 2], client=address))
    assert isinstance(exc, InputError) and "\n" not in str(exc) and done == []


@pytest.mark.parametrize("port", ["²", "８７８６", "87a6", "1_000", "+8786", " 8786", "99999",
                                  "0"])
def test_a_port_of_other_than_ascii_digits_is_invalid(port):
    for call in (check_scheduler, connect):
        with pytest.raises(InputError, match=r"is invalid: must be an address such as "
                                             r"'tcp://host:8786' \(a host and a port in "
                                             r"\[1, 65535\]\)$"):
            call(f"tcp://127.0.0.1:{port}")


def test_the_command_line_says_it_in_one_line(server, monkeypatch, capsys):
    kind, address = server
    monkeypatch.setattr(execution, "CONNECT_TIMEOUT", TIMEOUT)
    codes: list[int] = []
    assert _outcome(lambda: codes.append(
        cli.main(["reproduce", "--only", "t4.1", "--scheduler", address]))) is None
    assert codes == [2]
    err = [ln for ln in capsys.readouterr().err.splitlines() if ln.strip()]
    assert len(err) == 1 and err[0].startswith("propwhirl: error: scheduler = "), err
    assert cli.main(["reproduce", "--only", "t4.1", "--scheduler", "tcp://127.0.0.1:²"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "a host and a port in [1, 65535]" in err[0], err
