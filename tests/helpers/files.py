"""File-system helpers shared by the tests of atomic writes and output checks."""
from pathlib import Path

import pytest


def unwritable_folder(tmp_path: Path) -> Path:
    """A folder no file can be created in: read-only permissions, or /sys for root (which
    permissions do not stop)."""
    folder = tmp_path / "ro"
    folder.mkdir()
    folder.chmod(0o555)
    try:
        (folder / "probe").write_text("x")
    except OSError:
        return folder
    (folder / "probe").unlink()
    if Path("/sys").is_dir():
        try:
            (Path("/sys") / "propwhirl-probe").write_text("x")
        except OSError:
            return Path("/sys")
    pytest.skip("no unwritable folder on this machine")


# ------------------------------------------------ special files (issue 33, items 2 and 3)
import builtins  # noqa: E402
import io as _io  # noqa: E402
import os  # noqa: E402
import socket  # noqa: E402
import stat  # noqa: E402
import threading  # noqa: E402

#: (major, minor) of Linux's memory devices: /dev/null and /dev/zero.
NULL_DEVICE, ZERO_DEVICE = (1, 3), (1, 5)


def char_device(path: Path, device: tuple[int, int] = NULL_DEVICE) -> Path:
    """A private character-device node at `path` (by default the null device's numbers: a
    node of our own, so a test that replaced it would harm nothing — never /dev/null
    itself); skipped where nodes cannot be made (not root)."""
    try:
        os.mknod(path, stat.S_IFCHR | 0o666, os.makedev(*device))
    except (PermissionError, AttributeError, OSError) as exc:
        pytest.skip(f"cannot make a device node: {exc}")
    return path


def is_char_device(path: Path) -> bool:
    """Whether `path` itself (not a link's target) is still a character-device node."""
    return stat.S_ISCHR(os.lstat(path).st_mode)


def unix_socket(path: Path) -> socket.socket:
    """A listening Unix-domain socket bound at `path` (bound from its folder: a socket's
    name is limited to 108 bytes); close it when done."""
    s = socket.socket(socket.AF_UNIX)
    here = os.getcwd()
    os.chdir(path.parent)
    try:
        s.bind(path.name)
    finally:
        os.chdir(here)
    return s


class FifoWriter:
    """A FIFO at `path` with a writer thread waiting on it: a reader that opens the FIFO gets
    `data` and the end of the file (so code that wrongly opens it returns instead of waiting
    for ever) and :attr:`opened` is set.  :meth:`close` releases a writer still waiting (by
    opening the read end non-blocking) and removes nothing: the FIFO stays, to be checked."""

    def __init__(self, path: Path, data: bytes = b"not a propwhirl file\n"):
        self.path, self.data = Path(path), data
        os.mkfifo(self.path)
        self.opened = threading.Event()
        self._thread = threading.Thread(target=self._write, daemon=True)
        self._thread.start()

    def _write(self) -> None:
        try:
            fd = os.open(self.path, os.O_WRONLY)        # waits until a reader opens it
        except OSError:
            return
        self.opened.set()
        try:
            os.write(fd, self.data)
        except OSError:
            pass
        finally:
            os.close(fd)

    def close(self) -> None:
        if self._thread.is_alive():
            fd = os.open(self.path, os.O_RDONLY | os.O_NONBLOCK)
            self._thread.join(timeout=60)               # a safety net, not a timed assertion
            os.close(fd)

    def __enter__(self) -> "FifoWriter":
        return self

    def __exit__(self, *exc) -> None:
        self.close()


def never_opened(monkeypatch, *paths: Path | str) -> None:
    """Opening any of `paths` (resolved: a link to one counts) by ``open``, ``io.open`` or
    ``os.open`` raises AssertionError: a device that reads without end (/dev/zero) is
    checked to be refused before it is opened, and a regression fails here instead of
    growing past the machine's memory."""
    banned = {os.path.realpath(p) for p in paths}

    def check(file) -> None:
        if isinstance(file, (str, bytes, os.PathLike)):
            name = os.fsdecode(os.fspath(file))
            if os.path.realpath(name) in banned:
                raise AssertionError(f"opened {name}: it must be refused before opening")

    real_open, real_os_open = builtins.open, os.open

    def guarded_open(file, *args, **kwargs):
        check(file)
        return real_open(file, *args, **kwargs)

    def guarded_os_open(file, *args, **kwargs):
        check(file)
        return real_os_open(file, *args, **kwargs)

    monkeypatch.setattr(builtins, "open", guarded_open)
    monkeypatch.setattr(_io, "open", guarded_open)
    monkeypatch.setattr(os, "open", guarded_os_open)
