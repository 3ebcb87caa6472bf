"""Writing files safely: atomic replacement, one-line errors naming the file.

Every file propwhirl writes (model TOML, analysis JSON, V-g-f and study CSV, the report and the
plots) goes through :func:`write_text`, :func:`write_bytes` or :func:`write_with`:

1. the content is written to a temporary file in the target's folder (``.NAME.XXXX.tmp``,
   created exclusively, permissions as for a new file: ``0o666`` less the umask),
2. flushed and ``os.fsync``-ed,
3. moved onto the target with :func:`os.replace` (atomic on POSIX and Windows within one
   file system).

So a reader sees either the old file or the complete new one — never a half-written file, not
after a full disk, a Ctrl-C (``KeyboardInterrupt``) or a second process writing the same path.
On any failure the temporary file is removed and the target is left untouched; an ``OSError``
becomes one :class:`~propwhirl.validate.InputError` naming the file and the operating system's
reason, e.g. ``cannot write 'out/a.json': No space left on device``.

Reading is bounded (:func:`check_input`, the one rule of every file propwhirl reads): only a
regular file (symbolic links followed) is read — a device (``/dev/zero``), a FIFO or a socket
is refused before it is opened, so nothing grows without end and nothing waits forever — and
its size is checked against a stated limit before a byte is read: :data:`MAX_TOML_BYTES` for
model, modal-model and campaign files, :data:`MAX_READ_BYTES` for any other file read whole
(results, tables, the files the certification report hashes), the size its arrays take for an
``.npz`` or ``.npy`` file.  :func:`open_input` opens such a file (the ``.npz`` readers),
:func:`read_bytes`, :func:`read_text`, :func:`read_json` and :func:`sha256_file` read it.

Writing goes only to a regular file or a new path (:func:`check_output`): a device
(``/dev/null``), a FIFO or a socket as an output is refused before anything is computed or
written — the atomic rename would otherwise replace the device node itself.  No output may be
one of the command's inputs, nor two outputs one file (:func:`check_apart`: paths compared
resolved, symbolic links followed, hard links by their inode).

The readers and :func:`check_writable` turn every ``OSError`` into such a line too.  A path
longer than :data:`SHOWN_PATH` characters is named shortened (:func:`shown`: its first 60 and
last 20 characters and its length), so a file name of thousands of characters ("File name too
long") still gives one short line.

:func:`check_writable` lets a command fail *before* a long computation when an output folder
does not exist or cannot be written to.
"""
from __future__ import annotations

import os
import re
import secrets
import stat
from collections.abc import Callable, Iterable, Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import BinaryIO

from propwhirl.validate import InputError

#: Bytes handed to one ``os.write`` call.
CHUNK = 1 << 16
#: Paths longer than this [characters] are named shortened in messages (:func:`shown`).
SHOWN_PATH = 120
#: Characters of a temporary file's name taken from the target's name (a name of 255
#: characters, the usual limit, must not give a temporary name beyond it).
_TMP_STEM = 100
#: The largest model, modal-model or campaign file (TOML) read [bytes]: 16 MiB.  A model at
#: every size bound (200 elements, 64 propellers, per-node tables) takes well under 1 MiB.
MAX_TOML_BYTES = 16 * 2 ** 20
#: The largest file read whole otherwise [bytes]: 256 MiB (result files — JSON, CSV —, the
#: partial-results file of a study, the files the certification report hashes).
MAX_READ_BYTES = 256 * 2 ** 20

#: What a file that is not a regular one is, by its type (``stat.S_IFMT``).
_KINDS = {stat.S_IFDIR: "a folder", stat.S_IFCHR: "a character device",
          stat.S_IFBLK: "a block device", stat.S_IFIFO: "a FIFO (named pipe)",
          stat.S_IFSOCK: "a socket"}


def reason(exc: BaseException) -> str:
    """The operating system's reason for an error ("No space left on device"), else its text."""
    return (getattr(exc, "strerror", None) or str(exc) or type(exc).__name__).strip()


def shown(path: str | Path) -> str:
    """`path` as messages name it: in full up to :data:`SHOWN_PATH` characters, else its
    first 60 characters, "…", its last 20 and its length.

    >>> shown("out/a.json")
    'out/a.json'
    >>> shown("/tmp/" + "a" * 5000 + ".json")
    '/tmp/aaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaa…aaaaaaaaaaaaaaa.json (5,010 characters)'
    """
    s = str(path)
    if len(s) <= SHOWN_PATH:
        return s
    return f"{s[:60]}…{s[-20:]} ({len(s):,} characters)"


def quoted(path: str | Path) -> str:
    """``'path'`` for a message: quoted, shortened past :data:`SHOWN_PATH` characters as
    :func:`shown` does."""
    s = str(path)
    if len(s) <= SHOWN_PATH:
        return repr(s)
    return f"{s[:60] + '…' + s[-20:]!r} ({len(s):,} characters)"


def _name(path: str | Path, what: str) -> str:
    """``what 'path'`` (:func:`quoted`)."""
    return f"{what} {quoted(path)}" if what else quoted(path)


def read_json(path: str | Path, what: str):
    """The parsed JSON of the file `path` (a `what`, e.g. "boundary file"): :func:`read_text`'s
    errors, and one line naming the file when it is not JSON."""
    import json

    text = read_text(path, what)
    try:
        return json.loads(text)
    except json.JSONDecodeError as exc:
        raise InputError(f"{shown(path)}: not JSON ({exc})") from None


def exists(path: str | Path, what: str) -> bool:
    """Whether `path` (a `what`, e.g. "partial results file") exists; an error of the operating
    system other than "not found" (a name too long, a folder that cannot be searched) is one
    line naming it, where :meth:`pathlib.Path.exists` raises it.

    >>> exists("/nonexistent/a.json", "analysis file")
    False
    >>> exists("/tmp/" + "a" * 5000, "model file")
    Traceback (most recent call last):
    ...
    propwhirl.validate.InputError: cannot read model file '/tmp/aaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaa…aaaaaaaaaaaaaaaaaaaa' (5,005 characters): File name too long
    """
    try:
        os.stat(path)
    except (FileNotFoundError, NotADirectoryError):
        return False
    except OSError as exc:
        raise InputError(f"cannot read {_name(path, what)}: {reason(exc)}") from None
    except ValueError as exc:                     # a NUL character in the name
        raise InputError(f"{_name(path, what)} is not a valid file name: {exc}") from None
    return True


def kind(mode: int) -> str:
    """What a file of mode `mode` (``os.stat(...).st_mode``) is: "a regular file", "a folder",
    "a character device", "a FIFO (named pipe)", "a socket", ...."""
    if stat.S_ISREG(mode):
        return "a regular file"
    return _KINDS.get(stat.S_IFMT(mode), "not a regular file")


def _stat(path: str | Path, name: str) -> os.stat_result:
    """``os.stat(path)`` (symbolic links followed), errors as one line naming `name`."""
    try:
        return os.stat(path)
    except FileNotFoundError:
        raise InputError(f"{name} not found") from None
    except OSError as exc:
        raise InputError(f"cannot read {name}: {reason(exc)}") from None
    except ValueError as exc:                     # a NUL character in the name
        raise InputError(f"{name} is not a valid file name: {exc}") from None


def _check_input_stat(st: os.stat_result, name: str, limit: int, bound: str) -> None:
    if not stat.S_ISREG(st.st_mode):
        raise InputError(f"cannot read {name}: it is {kind(st.st_mode)}, not a regular file "
                         "(propwhirl reads regular files only)")
    if st.st_size > limit:
        raise InputError(f"cannot read {name}: it has {st.st_size:,} bytes, more than "
                         f"{limit:,} ({bound or 'the most propwhirl reads of such a file'})")


def check_input(path: str | Path, what: str, limit: int = MAX_READ_BYTES, *,
                bound: str = "") -> os.stat_result:
    """Check, before opening it, that `path` (a `what`, e.g. "model file") is a file propwhirl
    may read: it exists, is a regular file (symbolic links followed: not a device, a FIFO, a
    socket or a folder) and has at most `limit` bytes (`bound` says where the limit comes
    from, e.g. "the size its arrays take").  Returns its ``os.stat`` result; else one
    :class:`InputError` line naming the file.

    >>> check_input("/dev/zero", "model file")
    Traceback (most recent call last):
    ...
    propwhirl.validate.InputError: cannot read model file '/dev/zero': it is a character device, not a regular file (propwhirl reads regular files only)
    """
    name = _name(path, what)
    st = _stat(path, name)
    _check_input_stat(st, name, limit, bound)
    return st


@contextmanager
def open_input(path: str | Path, what: str, limit: int = MAX_READ_BYTES, *,
               bound: str = "") -> Iterator[BinaryIO]:
    """The file `path` (a `what`) opened for reading in binary, after :func:`check_input`.

    It is opened non-blocking, so a FIFO put in its place after the check does not wait for a
    writer, and checked again on the open descriptor (regular, at most `limit` bytes): what is
    read is what was checked.  Errors: one :class:`InputError` line naming the file; errors of
    the ``with`` body are the caller's.
    """
    name = _name(path, what)
    check_input(path, what, limit, bound=bound)
    flags = (os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_CLOEXEC", 0)
             | getattr(os, "O_BINARY", 0))
    try:
        fd = os.open(path, flags)
    except FileNotFoundError:
        raise InputError(f"{name} not found") from None
    except OSError as exc:
        raise InputError(f"cannot read {name}: {reason(exc)}") from None
    try:
        _check_input_stat(os.fstat(fd), name, limit, bound)
        fh = os.fdopen(fd, "rb")
    except BaseException:
        os.close(fd)
        raise
    with fh:
        yield fh


def _read_at_most(fh: BinaryIO, name: str, limit: int, bound: str) -> bytes:
    """The rest of `fh`, at most `limit` bytes (a file grown since its check is refused).
    Read as its size says, then in chunks of :data:`CHUNK`: nothing is allocated for the
    limit itself, only for what the file holds."""
    parts: list[bytes] = []
    total = 0
    try:
        n = min(os.fstat(fh.fileno()).st_size, limit) + 1
        while chunk := fh.read(n):
            parts.append(chunk)
            total += len(chunk)
            if total > limit:
                raise InputError(f"cannot read {name}: it has more than {limit:,} bytes "
                                 f"({bound or 'the most propwhirl reads of such a file'})")
            n = min(CHUNK, limit + 1 - total)
    except OSError as exc:
        raise InputError(f"cannot read {name}: {reason(exc)}") from None
    return b"".join(parts)


def read_bytes(path: str | Path, what: str, limit: int = MAX_READ_BYTES, *,
               bound: str = "") -> bytes:
    """The bytes of the file `path` (a `what`): a regular file of at most `limit` bytes
    (:func:`check_input`, before it is opened), one :class:`InputError` line otherwise."""
    with open_input(path, what, limit, bound=bound) as fh:
        return _read_at_most(fh, _name(path, what), limit, bound)


def sha256_file(path: str | Path, what: str, limit: int = MAX_READ_BYTES) -> str:
    """The SHA-256 (hex) of the file `path` (a `what`), read in chunks of :data:`CHUNK`
    bytes: a regular file of at most `limit` bytes (:func:`check_input`)."""
    import hashlib

    h = hashlib.sha256()
    name, seen = _name(path, what), 0
    with open_input(path, what, limit) as fh:
        while True:
            try:
                chunk = fh.read(CHUNK)
            except OSError as exc:
                raise InputError(f"cannot read {name}: {reason(exc)}") from None
            if not chunk:
                return h.hexdigest()
            seen += len(chunk)
            if seen > limit:
                raise InputError(f"cannot read {name}: it has more than {limit:,} bytes (the "
                                 "most propwhirl reads of such a file)")
            h.update(chunk)


def read_text(path: str | Path, what: str, *, empty_ok: bool = False,
              limit: int = MAX_READ_BYTES) -> str:
    """The UTF-8 text of the file `path` (a `what`, e.g. "analysis file"), with one-line
    errors naming it: not found, not a regular file or more than `limit` bytes
    (:func:`check_input`, before it is opened), unreadable (the OS's reason), not UTF-8 (the
    byte), empty (unless `empty_ok`: the caller's parser then says what is missing).

    >>> read_text("/nonexistent/a.json", "analysis file")
    Traceback (most recent call last):
    ...
    propwhirl.validate.InputError: analysis file '/nonexistent/a.json' not found
    """
    path = Path(path)
    article = "an" if what[:1].lower() in "aeiou" else "a"
    data = read_bytes(path, what, limit)
    if not empty_ok and not data.strip():
        raise InputError(f"{shown(path)}: the file is empty, not {article} {what}")
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise InputError(f"{shown(path)}: not {article} {what}: not UTF-8 text (byte "
                         f"{exc.start})") from None


def _create_temporary(path: Path) -> tuple[int, Path]:
    """A new temporary file beside `path`: (file descriptor, its path)."""
    flags = os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_BINARY", 0)
    for _ in range(100):
        tmp = path.with_name(f".{path.name[:_TMP_STEM]}.{secrets.token_hex(4)}.tmp")
        try:
            return os.open(tmp, flags, 0o666), tmp
        except FileExistsError:
            continue
    raise FileExistsError(f"no free temporary name beside {path}")


def _sync_folder(folder: Path) -> None:
    """Make the rename itself durable (POSIX; best effort)."""
    if os.name != "posix":
        return
    try:
        fd = os.open(folder, os.O_RDONLY)
    except OSError:
        return
    try:
        os.fsync(fd)
    except OSError:
        pass
    finally:
        os.close(fd)


def write_with(path: str | Path, fill: Callable[[BinaryIO], None], *, what: str = "") -> Path:
    """Write `path` atomically: ``fill(fh)`` writes the content to a binary file object.

    Parameters
    ----------
    path : str or Path
        The target file; its folder must exist.
    fill : callable
        Writes the whole content to the binary file object it is given (e.g.
        ``lambda fh: figure.savefig(fh, format="png")``).
    what : str, optional
        What the file is, for the error message ("model file", "plot").

    Returns
    -------
    Path
        The target path.

    Raises
    ------
    InputError
        The file cannot be written (the message names it and the reason); the target keeps its
        old content (or still does not exist) and no temporary file is left.
    """
    path = Path(path)
    tmp: Path | None = None
    try:
        check_output(path, what)    # a folder, a device, a FIFO, a socket: refused
        fd, tmp = _create_temporary(path)
        with os.fdopen(fd, "wb") as fh:
            fill(fh)
            fh.flush()
            os.fsync(fh.fileno())
        os.replace(tmp, path)
        tmp = None
    except OSError as exc:
        raise InputError(f"cannot write {_name(path, what)}: {reason(exc)}") from exc
    finally:  # also on KeyboardInterrupt and on errors of `fill`
        if tmp is not None:
            try:
                os.unlink(tmp)
            except OSError:
                pass
    _sync_folder(path.parent)
    return path


def check_output(path: str | Path, what: str = "") -> None:
    """Refuse to write `path` (a `what`) unless it is a regular file or a new path (symbolic
    links followed): a folder, a device (``/dev/null``, ``/dev/full``), a FIFO or a socket is
    one :class:`InputError` line, before anything is written.  The atomic write renames a new
    regular file onto the path: on a device node it would replace the node itself (run as
    root, ``/dev/null`` would stop being a device), so it is refused rather than written
    through (a FIFO written through would also wait for a reader without end).

    >>> check_output("/dev/null", "--json")
    Traceback (most recent call last):
    ...
    propwhirl.validate.InputError: cannot write --json '/dev/null': it is a character device, not a regular file (propwhirl writes regular files only)
    """
    try:
        problem = _output_kind(path)
    except OSError as exc:
        raise InputError(f"cannot write {_name(path, what)}: {reason(exc)}") from None
    if problem == _KINDS[stat.S_IFDIR]:
        raise InputError(f"cannot write {_name(path, what)}: it is a folder")
    if problem is not None:
        raise InputError(f"cannot write {_name(path, what)}: it is {problem}, not a regular "
                         "file (propwhirl writes regular files only)")


def _output_kind(path: str | Path) -> str | None:
    """What the existing `path` is when it is no regular file (:func:`kind`: "a folder", "a
    character device", ...; symbolic links followed), None for a regular file or a new path;
    an ``OSError`` other than "not found" is raised."""
    try:
        st = os.stat(path)
    except (FileNotFoundError, NotADirectoryError):
        return None                              # a new path (its folder is checked apart)
    return None if stat.S_ISREG(st.st_mode) else kind(st.st_mode)


def file_identity(path: str | Path) -> tuple:
    """One key per file: an existing file's (device, inode) — symbolic and hard links are the
    file —, else its absolute path with ``.``/``..`` and symbolic links resolved."""
    try:
        st = os.stat(path)
        return ("inode", st.st_dev, st.st_ino)
    except (OSError, ValueError):
        return ("path", os.path.normcase(os.path.realpath(os.path.abspath(path))))


def same_file(a: str | Path, b: str | Path) -> bool:
    """Whether the paths `a` and `b` name one file (:func:`file_identity`; also two new paths
    that resolve alike)."""
    return file_identity(a) == file_identity(b)


def check_apart(outputs: Iterable[tuple[str, str | Path]],
                inputs: Iterable[tuple[str, str | Path]] = ()) -> None:
    """Refuse, before any work, two outputs on one file and an output on one of the inputs.

    Parameters
    ----------
    outputs : iterable of (label, path)
        The files to be written, each with how the user gave it (``"--json"``,
        ``"--out DIR: campaign.json"``); outputs given as None are left out.
    inputs : iterable of (what, path)
        The files read (or kept) while the outputs are made, each with what it is (``"the
        model file MODEL m.toml"``); an input given as None is left out.

    Raises
    ------
    InputError
        ``LABEL1 PATH1 and LABEL2 PATH2 are the same file: give each output its own path``,
        or ``LABEL PATH is WHAT: give another path`` (paths compared by :func:`same_file`).
    """
    taken: dict[tuple, tuple[str, str]] = {}
    for label, path in sorted((lb, str(p)) for lb, p in outputs if p is not None):
        twin = taken.setdefault(file_identity(path), (label, path))
        if twin != (label, path):
            raise InputError(f"{twin[0]} {twin[1]} and {label} {path} are the same file: give "
                             "each output its own path")
    for what, other in inputs:
        if other is None:
            continue
        label, path = taken.get(file_identity(other), (None, None))
        if label is not None:
            raise InputError(f"{label} {path} is {what}: give another path")


def _write_all(fh: BinaryIO, data: bytes) -> None:
    """``os.write`` until every byte is written (a short write is continued, an error raised)."""
    fd = fh.fileno()
    view = memoryview(data)
    while view:
        n = os.write(fd, view[:CHUNK])
        view = view[n:]


def write_bytes(path: str | Path, data: bytes, *, what: str = "") -> Path:
    """Write `data` to `path` atomically (see :func:`write_with`); returns the path."""
    return write_with(path, lambda fh: _write_all(fh, data), what=what)


def write_text(path: str | Path, text: str, *, encoding: str = "utf-8", what: str = "") -> Path:
    """Write `text` to `path` atomically (see :func:`write_with`); returns the path.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from propwhirl.fileio import write_text
    >>> path = write_text(pathlib.Path(tempfile.mkdtemp()) / "a.txt", "complete\\n")
    >>> path.read_text()
    'complete\\n'
    """
    return write_bytes(path, text.encode(encoding), what=what)


def check_writable(path: str | Path, *, folder: bool = False, create: bool = False,
                   what: str = "") -> Path:
    """Check, before any computation, that a file can be written to `path`.

    Parameters
    ----------
    path : str or Path
        An output file (its folder is checked) or, with ``folder=True``, an output folder.
    folder : bool, optional
        `path` is the folder itself.
    create : bool, optional
        Create the folder (and its parents) when it does not exist, instead of an error.
    what : str, optional
        How the user gave the path (e.g. "--json"), for the error message.

    Returns
    -------
    Path
        The folder that was checked.

    Raises
    ------
    InputError
        The folder does not exist (and may not or cannot be created), is not a folder, or a
        file cannot be created in it; or `path` is an existing folder, device, FIFO or socket
        where a file is meant (:func:`check_output`).
        The message names the path and the reason.
    """
    path = Path(path)
    target = path if folder else path.parent
    label = f"{what} {shown(path)}" if what else shown(path)
    try:
        return _check_writable(path, target, label, folder, create)
    except OSError as exc:      # e.g. "File name too long" from is_dir() itself
        raise InputError(f"{label}: {reason(exc)}") from exc


def _check_writable(path: Path, target: Path, label: str, folder: bool, create: bool) -> Path:
    problem = None if folder else _output_kind(path)     # check_output's rule
    if problem == _KINDS[stat.S_IFDIR]:
        raise InputError(f"{label}: is a folder, not a file")
    if problem is not None:
        raise InputError(f"{label}: is {problem}, not a regular file (propwhirl writes "
                         "regular files only)")
    if not target.is_dir():
        if target.exists():
            raise InputError(f"{label}: {quoted(target)} is not a folder")
        if not create:
            raise InputError(f"{label}: the folder {quoted(target)} does not exist")
        try:
            target.mkdir(parents=True, exist_ok=True)
        except OSError as exc:
            raise InputError(f"{label}: cannot create the folder {quoted(target)}: "
                             f"{reason(exc)}") from exc
    try:
        fd, tmp = _create_temporary(target / "propwhirl-write-check")
    except OSError as exc:
        raise InputError(f"{label}: cannot write to the folder {quoted(target)}: "
                         f"{reason(exc)}") from exc
    os.close(fd)
    try:
        os.unlink(tmp)
    except OSError:
        pass
    return target


# ----------------------------------------------------------------------------- counted tables
#: The first line of a CSV table propwhirl reads back: how many rows follow its header, so a
#: table cut at a line boundary is found (``# propwhirl V-g-f table: 56 rows``).  Other
#: programs skip the line (``pandas.read_csv(path, skiprows=1)``,
#: ``numpy.genfromtxt(path, delimiter=",", skip_header=1, names=True)``).
COUNT_LINE = "# propwhirl {kind}: {rows} rows"


def count_line(kind: str, rows: int) -> str:
    """The first line of a counted table of `rows` rows (:data:`COUNT_LINE`)."""
    return COUNT_LINE.format(kind=kind, rows=rows)


def split_count(text: str, kind: str, where: str) -> tuple[int | None, str]:
    """(rows its first line announces, the text after that line) of a table written with
    :func:`count_line`; ``(None, text)`` for a table without the line (written by a propwhirl
    before it).  A first line starting with ``#`` that is not the count of a `kind` is an
    :class:`InputError` naming `where` and line 1."""
    import re

    if not text.startswith("#"):
        return None, text
    first, _, rest = text.partition("\n")
    m = re.fullmatch(r"# propwhirl " + re.escape(kind) + r": ([0-9]{1,12}) rows?",
                     first.rstrip("\r"))
    if m is None:
        raise InputError(f"{where}: line 1: {first.rstrip()[:60]!r} is not the row count of a "
                         f"{kind} ({count_line(kind, 'N')!r})")
    return int(m.group(1)), rest


def check_count(count: int | None, rows: int, kind: str, where: str) -> None:
    """A table read with :func:`split_count` has the `count` rows its first line announces,
    else an :class:`InputError` (cut at a line boundary, or rows added).  A table without
    the count (`count` None: written by an older propwhirl) passes: once it is read, say so
    with :func:`warn_uncounted`."""
    if count is not None and rows != count:
        raise InputError(f"{where}: has {rows} rows, its first line says {count}"
                         + (" (truncated?)" if rows < count else " (rows added?)"))


def warn_uncounted(kind: str, where: str) -> None:
    """A :class:`UserWarning` naming a table read without a row count (written by a propwhirl
    before :func:`count_line`): a cut at a line boundary cannot be found in it."""
    import warnings

    warnings.warn(f"{where}: a {kind} with no row count (written by an older propwhirl): a "
                  "table cut at a line boundary cannot be checked; write it again to add the "
                  "count", UserWarning, stacklevel=3)


# ----------------------------------------------------------------------------- CSV cells
#: The first characters that make a spreadsheet read a CSV cell as a formula (OWASP, "CSV
#: Injection"): ``= + - @``, tab and carriage return; and the single quote that marks a cell
#: neutralised (:func:`csv_cell`).
FORMULA_START = ("=", "+", "-", "@", "\t", "\r")
#: A plain decimal number (``-1.5``, ``+2``, ``-1e-05``): a spreadsheet reads it as a number,
#: never as a formula, so it is written as it is.
_CSV_NUMBER = re.compile(r"[+-]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?")


def csv_cell(x):
    """A CSV cell as propwhirl writes it: a text cell that a spreadsheet would evaluate — one
    starting with one of :data:`FORMULA_START` — gets a leading single quote (OWASP's
    neutralisation: ``=HYPERLINK(...)`` is written ``'=HYPERLINK(...)``), and so does a text
    starting with a single quote (so :func:`csv_text` reads every text back exactly).  A
    plain number, given as a number or as its text (``-1.5``, ``-1e-05``), and every other
    cell are written as they are.

    >>> [csv_cell(x) for x in ("=1+1", "-1+1", "@SUM(A1)", "-1.5", -1.5, "'q", "wing 1")]
    ["'=1+1", "'-1+1", "'@SUM(A1)", '-1.5', -1.5, "''q", 'wing 1']
    """
    if isinstance(x, str) and x[:1] in (*FORMULA_START, "'") \
            and _CSV_NUMBER.fullmatch(x) is None:
        return "'" + x
    return x


def csv_text(cell: str) -> str:
    """The text of a cell written by :func:`csv_cell` (its neutralising quote removed).

    >>> csv_text("'=1+1"), csv_text("-1.5"), csv_text("''q")
    ('=1+1', '-1.5', "'q")
    """
    return cell[1:] if cell.startswith("'") else cell


class _NeutralisingWriter:
    """A :func:`csv.writer` whose every cell goes through :func:`csv_cell`; a row with a
    carriage return inside a text is written with every cell quoted (the csv module quotes
    only the line terminator's characters: an unquoted CR would start a new row in a
    spreadsheet, whose first cell could be a formula)."""

    def __init__(self, fh, **options) -> None:
        import csv

        self._w = csv.writer(fh, **options)
        self._quoted = csv.writer(fh, **{**options, "quoting": csv.QUOTE_ALL})

    def writerow(self, row):
        cells = [csv_cell(x) for x in row]
        w = self._quoted if any(isinstance(x, str) and "\r" in x for x in cells) else self._w
        return w.writerow(cells)

    def writerows(self, rows) -> None:
        for row in rows:
            self.writerow(row)


def csv_writer(fh, **options) -> _NeutralisingWriter:
    """The one CSV writer of propwhirl: :func:`csv.writer` (`options` as its) with every cell
    neutralised against spreadsheet formulas (:func:`csv_cell`); the readers of the tables
    propwhirl reads back undo it with :func:`csv_text`."""
    return _NeutralisingWriter(fh, **options)


def csv_table(columns, units, path: str | Path | None = None, what: str = "table",
              count: bool = False) -> str:
    """A tidy table as CSV: header ``"column [unit]"`` (just ``column`` without a unit), one row
    per entry of the equal-length ``columns`` (a mapping name → sequence, in order); floats as
    the shortest text that reads back exactly, NaN and inf as an empty cell.  Also written to
    ``path`` if given (atomically, :func:`write_text`).  ``units``: name → unit ("" for none).
    With `count` (a table propwhirl reads back), a first line :func:`count_line` of `what`.
    Text cells are neutralised against spreadsheet formulas (:func:`csv_cell`)."""
    import io
    import math

    names = list(columns)
    buf = io.StringIO()
    w = csv_writer(buf, lineterminator="\n")
    if count:
        buf.write(count_line(what, len(columns[names[0]]) if names else 0) + "\n")
    w.writerow([f"{k} [{units[k]}]" if units.get(k) else k for k in names])
    n = len(columns[names[0]]) if names else 0
    for i in range(n):
        row = []
        for k in names:
            x = columns[k][i]
            if isinstance(x, float) or getattr(getattr(x, "dtype", None), "kind", "") == "f":
                row.append("" if not math.isfinite(float(x)) else repr(float(x)))
            else:
                row.append(str(x))
        w.writerow(row)
    text = buf.getvalue()
    if path is not None:
        write_text(path, text, what=what)
    return text
