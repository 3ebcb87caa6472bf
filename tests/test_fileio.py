"""Atomic file writes (propwhirl.fileio): a full disk, Ctrl-C mid-write and two concurrent
writers never leave a partial file or a temporary file; errors name the file (issue 9, item 5)."""
from __future__ import annotations

import errno
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

from helpers.files import unwritable_folder

from propwhirl import fileio, io
from propwhirl.analysis.stability import analyse, load
from propwhirl.cases.ch09_baseline import isolated_baseline_propeller
from propwhirl.validate import InputError

ROOT = Path(__file__).resolve().parents[1]


def leftovers(folder: Path, keep: set[str]) -> list[str]:
    """Files in `folder` other than `keep` (temporary files would be here)."""
    return sorted(p.name for p in folder.iterdir() if p.name not in keep)


@pytest.fixture(scope="module")
def small_analysis():
    return analyse(isolated_baseline_propeller(), np.arange(1.0, 351.0, 50.0))


def test_write_text_replaces_the_file_and_leaves_nothing_else(tmp_path):
    target = tmp_path / "a.txt"
    target.write_text("old")
    assert fileio.write_text(target, "new content\n") == target
    assert target.read_text() == "new content\n"
    assert leftovers(tmp_path, {"a.txt"}) == []
    fileio.write_bytes(target, b"\x00\x01")
    assert target.read_bytes() == b"\x00\x01"


def test_a_new_file_gets_the_usual_permissions(tmp_path):
    """Not mkstemp's 0o600: 0o666 less the umask, as open() would give."""
    mask = os.umask(0o022)
    os.umask(mask)
    path = fileio.write_text(tmp_path / "p.txt", "x")
    assert path.stat().st_mode & 0o777 == 0o666 & ~mask


class FullDisk:
    """os.write that writes `room` bytes in total, then raises ENOSPC (a full disk)."""

    def __init__(self, room: int):
        self.room = room
        self.real = os.write

    def __call__(self, fd, data):
        if self.room <= 0:
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
        n = self.real(fd, bytes(data[: self.room]))
        self.room -= n
        return n


@pytest.mark.parametrize("existing", [True, False])
def test_full_disk_keeps_the_old_file_and_names_the_file(tmp_path, monkeypatch, existing):
    target = tmp_path / "a.json"
    if existing:
        target.write_text('{"old": true}')
    monkeypatch.setattr(os, "write", FullDisk(65_536))
    with pytest.raises(InputError) as err:
        fileio.write_text(target, "x" * 300_000)
    monkeypatch.undo()
    assert str(err.value) == f"cannot write {str(target)!r}: No space left on device"
    if existing:
        assert target.read_text() == '{"old": true}'
    else:
        assert not target.exists()
    assert leftovers(tmp_path, {"a.json"}) == []


def test_full_disk_during_analysis_save(tmp_path, monkeypatch, small_analysis):
    """Issue 9.5: a full disk left a 65,536-byte invalid JSON and the error named no file."""
    target = tmp_path / "a.json"
    small_analysis.save(target)
    before = target.read_bytes()
    monkeypatch.setattr(os, "write", FullDisk(1000))
    with pytest.raises(InputError, match=r"cannot write analysis file '.*a\.json': No space left"):
        small_analysis.save(target, include_eigenvectors=True)
    monkeypatch.undo()
    assert target.read_bytes() == before
    assert load(target).events == small_analysis.events
    assert leftovers(tmp_path, {"a.json"}) == []


def test_full_disk_in_the_file_objects_write(tmp_path, small_analysis):
    """The plots' path: a writer that fills a file object (fh.write raising ENOSPC)."""
    target = tmp_path / "fig.png"
    target.write_bytes(b"old")

    def fill(fh):
        fh.write(b"partial")
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))

    with pytest.raises(InputError, match=r"cannot write plot '.*fig\.png': No space left"):
        fileio.write_with(target, fill, what="plot")
    assert target.read_bytes() == b"old"
    assert leftovers(tmp_path, {"fig.png"}) == []


SYNTHETIC = """
import numpy as np
from propwhirl.engine import Sweep

def synthetic_sweep(me=1, T=400, n=8):
    V = np.arange(1.0, T + 1.0)
    lam = (-0.01 * me - 0.1 * np.arange(n)) + 1j * (1.0 + me + np.arange(n)) * np.ones((T, 1))
    return Sweep(V=V, eigenvalues=lam, eigenvectors=None, dlam_dV=0 * lam,
                 physical=np.ones((T, n), bool), state_labels=tuple("s%d" % k for k in range(n)),
                 displacement=np.ones(n, bool), mode_labels=tuple("m%d" % k for k in range(n)),
                 partner=-np.ones(n, int), grid=V, floor=np.ones(T))
"""

FULL_DISK = SYNTHETIC + textwrap.dedent("""
    import resource, signal, sys
    from propwhirl.analysis.stability import ModelAnalysis
    from propwhirl.validate import InputError

    writer, path = sys.argv[1], sys.argv[2]
    sweep = synthetic_sweep()
    # the kernel refuses every byte past 1000 in any file this process writes (EFBIG)
    signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
    resource.setrlimit(resource.RLIMIT_FSIZE, (1000, resource.RLIM_INFINITY))
    try:
        if writer == "analysis":
            ModelAnalysis("synthetic", sweep, ()).save(path)
        elif writer == "csv":
            from propwhirl.io import write_vgf_csv
            write_vgf_csv(sweep, path)
        elif writer == "model":
            from propwhirl.cases.registry import case_model
            from propwhirl.io import save_model
            save_model(case_model("wingtip"), path)
        elif writer == "table":
            from propwhirl.studies.table import StudyTable
            StudyTable("t", "x", {"model": np.array(["a"] * 400),
                                  "x": np.arange(400.0)}).to_csv(path)
        elif writer == "plot":
            from propwhirl.app import plots
            plots.save(plots.vgf(ModelAnalysis("synthetic", sweep, ())), path)
    except InputError as exc:
        print(exc, file=sys.stderr)
        sys.exit(2)
""")


@pytest.mark.parametrize("writer", ["analysis", "csv", "model", "table", "plot"])
def test_a_file_size_limit_of_the_kernel_leaves_the_old_file(tmp_path, writer):
    """Issue 9.5: a full disk left a 65,536-byte invalid JSON and the error named no file.
    A real write failure of the kernel (RLIMIT_FSIZE: EFBIG past 1000 bytes, as a full disk
    gives ENOSPC) in every writer: an InputError naming the file, the old file untouched,
    no temporary file."""
    if writer == "plot":
        pytest.importorskip("matplotlib")
    target = tmp_path / ("out.png" if writer == "plot" else "out.file")
    target.write_text("old")
    script = tmp_path / "full.py"
    script.write_text(FULL_DISK)
    env = dict(os.environ, PYTHONPATH=str(ROOT / "src"), PYTHONDONTWRITEBYTECODE="1")
    r = subprocess.run([sys.executable, str(script), writer, str(target)], env=env,
                       capture_output=True, text=True, timeout=300)
    assert r.returncode == 2, r.stderr
    assert r.stderr.count("\n") == 1
    assert f"{str(target)!r}: File too large" in r.stderr
    assert target.read_text() == "old"
    assert leftovers(tmp_path, {target.name, "full.py"}) == []


def test_keyboard_interrupt_mid_write_removes_the_temporary_file(tmp_path):
    target = tmp_path / "a.csv"
    target.write_text("old,complete\n")
    seen = []

    def fill(fh):
        fh.write(b"half,")
        fh.flush()
        seen.extend(leftovers(tmp_path, {"a.csv"}))   # the temporary file, beside the target
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        fileio.write_with(target, fill)
    assert len(seen) == 1 and seen[0].startswith(".a.csv.") and seen[0].endswith(".tmp")
    assert target.read_text() == "old,complete\n"
    assert leftovers(tmp_path, {"a.csv"}) == []


def test_a_folder_or_a_missing_folder_is_an_error_naming_the_path(tmp_path):
    with pytest.raises(InputError, match="cannot write .*: it is a folder"):
        fileio.write_text(tmp_path, "x")
    with pytest.raises(InputError, match=r"cannot write '.*missing/a\.txt': No such file"):
        fileio.write_text(tmp_path / "missing" / "a.txt", "x")


def test_check_writable(tmp_path):
    assert fileio.check_writable(tmp_path / "a.json") == tmp_path
    assert leftovers(tmp_path, set()) == []           # the probe file is removed
    with pytest.raises(InputError, match=r"--json .*: the folder '.*nope' does not exist"):
        fileio.check_writable(tmp_path / "nope" / "a.json", what="--json")
    made = fileio.check_writable(tmp_path / "new" / "sub", folder=True, create=True)
    assert made.is_dir()
    (tmp_path / "file").write_text("x")
    with pytest.raises(InputError, match="is not a folder"):
        fileio.check_writable(tmp_path / "file" / "a.json")
    with pytest.raises(InputError, match="is a folder, not a file"):
        fileio.check_writable(tmp_path)
    ro = unwritable_folder(tmp_path)
    with pytest.raises(InputError, match=f"--csv .*cannot write to the folder '{ro}'"):
        fileio.check_writable(ro / "a.csv", what="--csv")


WRITER = SYNTHETIC + textwrap.dedent("""
    import sys
    from propwhirl.io import write_vgf_csv

    me, path = int(sys.argv[1]), sys.argv[2]
    sweep = synthetic_sweep(me)
    for _ in range(20):
        write_vgf_csv(sweep, path)
""")


def test_two_processes_writing_the_same_csv(tmp_path):
    """Issue 9.5: two processes writing the same CSV corrupted 8 of 20; now each final file
    is one writer's complete table."""
    path = tmp_path / "vgf.csv"
    script = tmp_path / "writer.py"
    script.write_text(WRITER)
    env = dict(os.environ, PYTHONPATH=str(ROOT / "src"))
    procs = [subprocess.Popen([sys.executable, str(script), str(me), str(path)], env=env)
             for me in (1, 2)]
    assert [p.wait(timeout=120) for p in procs] == [0, 0]
    t = io.read_vgf_csv(path)                       # complete and valid
    assert len(t["V"]) == 400 * 8
    assert set(t["imag"][:8] - np.arange(8)) in ({2.0}, {3.0})   # one writer's, not a mix
    assert leftovers(tmp_path, {"vgf.csv", "writer.py"}) == []


def test_two_writers_never_show_a_partial_file(tmp_path):
    """While two processes rewrite the file, every read sees a complete table."""
    path = tmp_path / "vgf.csv"
    script = tmp_path / "writer.py"
    script.write_text(WRITER)
    env = dict(os.environ, PYTHONPATH=str(ROOT / "src"))
    procs = [subprocess.Popen([sys.executable, str(script), str(me), str(path)], env=env)
             for me in (1, 2)]
    reads = 0
    while any(p.poll() is None for p in procs):
        if path.exists():
            t = io.read_vgf_csv(path)               # raises on a partial file
            assert len(t["V"]) == 400 * 8
            reads += 1
    assert [p.wait(timeout=120) for p in procs] == [0, 0]
    assert leftovers(tmp_path, {"vgf.csv", "writer.py"}) == []


# ------------------------------------------------------------------- issue 33, items 1-3
# Reading: regular files only, the size checked before reading; writing: regular files or
# new paths only; no output on an input.  Special files are refused before they are opened.
from helpers.files import (FifoWriter, ZERO_DEVICE, char_device, is_char_device,  # noqa: E402
                           never_opened, unix_socket)


@pytest.mark.parametrize("device", ["/dev/zero", "/dev/urandom"])
def test_a_device_is_refused_before_it_is_opened(monkeypatch, device):
    never_opened(monkeypatch, device)
    for read in (lambda: fileio.read_text(device, "model file"),
                 lambda: fileio.read_bytes(device, "model file"),
                 lambda: fileio.sha256_file(device, "model file")):
        with pytest.raises(InputError) as err:
            read()
        assert str(err.value) == (f"cannot read model file {device!r}: it is a character "
                                  "device, not a regular file (propwhirl reads regular files "
                                  "only)")


def test_a_link_to_a_device_is_the_device(tmp_path, monkeypatch):
    link = tmp_path / "wing.toml"
    link.symlink_to("/dev/zero")
    never_opened(monkeypatch, "/dev/zero")
    with pytest.raises(InputError, match=r"wing\.toml': it is a character device"):
        fileio.read_text(link, "model file")


def test_a_fifo_is_refused_without_opening_it(tmp_path):
    with FifoWriter(tmp_path / "pipe.toml") as fifo:
        with pytest.raises(InputError, match=r"pipe\.toml': it is a FIFO \(named pipe\), not a "
                                             r"regular file"):
            fileio.read_text(fifo.path, "model file")
        assert not fifo.opened.is_set()


def test_a_fifo_put_in_place_after_the_check_does_not_wait(tmp_path, monkeypatch):
    """The check on the open descriptor: opened non-blocking, then refused (no writer needed)."""
    monkeypatch.setattr(fileio, "check_input", lambda *a, **k: None)
    with FifoWriter(tmp_path / "late.toml") as fifo:
        with pytest.raises(InputError, match="it is a FIFO"):
            with fileio.open_input(fifo.path, "model file"):
                pass


def test_a_socket_and_a_folder_are_refused(tmp_path):
    s = unix_socket(tmp_path / "s.toml")
    try:
        with pytest.raises(InputError, match="it is a socket, not a regular file"):
            fileio.read_text(tmp_path / "s.toml", "model file")
    finally:
        s.close()
    with pytest.raises(InputError, match="it is a folder, not a regular file"):
        fileio.read_text(tmp_path, "model file")


def test_the_size_is_checked_before_reading(tmp_path, monkeypatch):
    big = tmp_path / "big.json"
    with open(big, "wb") as fh:                       # sparse: no disk used
        fh.truncate(fileio.MAX_READ_BYTES + 1)
    reads = []
    monkeypatch.setattr(fileio, "_read_at_most", lambda *a: reads.append(a))
    with pytest.raises(InputError) as err:
        fileio.read_text(big, "analysis file")
    assert str(err.value) == (f"cannot read analysis file {str(big)!r}: it has "
                              f"{fileio.MAX_READ_BYTES + 1:,} bytes, more than "
                              f"{fileio.MAX_READ_BYTES:,} (the most propwhirl reads of such a "
                              "file)")
    assert reads == []
    with pytest.raises(InputError, match="has 11 bytes, more than 10 .its arrays."):
        (tmp_path / "a.npz").write_bytes(b"x" * 11)
        fileio.check_input(tmp_path / "a.npz", "modes file", 10, bound="its arrays")


def test_a_file_grown_after_its_check_is_cut_at_the_limit(tmp_path, monkeypatch):
    path = tmp_path / "a.txt"
    path.write_bytes(b"x" * 100)
    monkeypatch.setattr(fileio, "_check_input_stat", lambda *a: None)   # grown after it
    with pytest.raises(InputError, match="it has more than 10 bytes"):
        fileio.read_bytes(path, "table", 10)
    with pytest.raises(InputError, match="it has more than 10 bytes"):
        fileio.sha256_file(path, "table", 10)


def test_the_hash_is_of_the_bytes(tmp_path):
    import hashlib

    path = tmp_path / "m.toml"
    data = os.urandom(3 * fileio.CHUNK + 17)
    path.write_bytes(data)
    assert fileio.sha256_file(path, "model file") == hashlib.sha256(data).hexdigest()


def _special(kind: str, path: Path):
    """A device node of our own, a FIFO or a socket at `path` (the thing to keep)."""
    if kind == "device":
        return char_device(path)
    if kind == "fifo":
        os.mkfifo(path)
        return path
    return unix_socket(path)


def _intact(kind: str, path: Path) -> bool:
    import stat

    mode = os.lstat(path).st_mode
    return {"device": stat.S_ISCHR, "fifo": stat.S_ISFIFO, "socket": stat.S_ISSOCK}[kind](mode)


@pytest.mark.parametrize("kind", ["device", "fifo", "socket"])
@pytest.mark.parametrize("link", [False, True])
def test_a_special_file_as_an_output_is_refused_before_any_write(tmp_path, monkeypatch, kind,
                                                                 link):
    """Item 2: the atomic rename would replace the node (run as root, /dev/null stopped being
    a device): refused in one line, no temporary file made — tested on nodes of our own."""
    node = tmp_path / "node"
    held = _special(kind, node)
    target = node
    if link:
        target = tmp_path / "out.csv"
        target.symlink_to(node)
    made = []
    monkeypatch.setattr(fileio, "_create_temporary", lambda p: made.append(p))
    try:
        with pytest.raises(InputError) as err:
            fileio.write_text(target, "x\n", what="table")
        assert "not a regular file (propwhirl writes regular files only)" in str(err.value)
        assert str(err.value).startswith(f"cannot write table {str(target)!r}: it is a")
        with pytest.raises(InputError, match="not a regular file"):
            fileio.check_writable(target, what="--csv")
        assert made == [] and _intact(kind, node)
    finally:
        if kind == "socket":
            held.close()


def test_outputs_apart_and_not_on_an_input(tmp_path, monkeypatch):
    """Item 1: resolved paths, symbolic links followed, hard links by their inode."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "m.toml").write_text("x")
    (tmp_path / "sub").mkdir()
    os.link(tmp_path / "m.toml", tmp_path / "hard.toml")
    (tmp_path / "soft.toml").symlink_to(tmp_path / "m.toml")
    model = [("the model file MODEL m.toml", "m.toml")]
    for out in ("m.toml", "./m.toml", "sub/../m.toml", str(tmp_path / "m.toml"), "hard.toml",
                "soft.toml"):
        with pytest.raises(InputError) as err:
            fileio.check_apart([("--json", out)], model)
        assert str(err.value) == f"--json {out} is the model file MODEL m.toml: give another path"
    with pytest.raises(InputError, match="--csv ./a and --json a are the same file"):
        fileio.check_apart([("--json", "a"), ("--csv", "./a")])
    fileio.check_apart([("--json", "a"), ("--csv", "sub/a"), ("--plot", None)],
                       model + [("nothing", None)])
    assert fileio.same_file("m.toml", "hard.toml") and not fileio.same_file("m.toml", "a")


def test_a_private_device_reads_as_a_device(tmp_path, monkeypatch):
    """The refusal does not depend on the name: a node of /dev/zero's numbers elsewhere."""
    node = char_device(tmp_path / "zero.toml", ZERO_DEVICE)
    never_opened(monkeypatch, node)
    with pytest.raises(InputError, match="it is a character device"):
        fileio.read_text(node, "model file")
    assert is_char_device(node)
