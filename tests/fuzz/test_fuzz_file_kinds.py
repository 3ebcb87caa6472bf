"""Fuzz: every file propwhirl reads or writes, given as every kind of file (issue 33, items
1-3).  Each reader — model file, modal model file, its ``[modes] file``, campaign file, the
campaign's model, a result file, the report's SHA-256, a DLM cache entry, ``upgrade-model
OLD`` — is handed a valid file, junk, an empty file, a device (a node of /dev/zero's numbers of
our own, or a link to one), a FIFO, a socket, a folder, a missing path or a sparse file past
every size limit; each writer — ``upgrade-model NEW``, ``save_model``, ``write_modes``,
``CampaignResult.to_csv``, ``analyse --json``, ``certify``'s outputs, ``write_report`` — a new
path, an existing file, a device node of our own (or a link to one), a FIFO, a socket, a
folder, a missing folder or one of its own inputs.  Every case gives a result or one line
(an ``InputError``; exit code 2 on the command line) — never a traceback, never a wait for a
FIFO's writer, never a device read (guarded: opening one fails the case), never a special
file replaced; special files, oversized files and outputs on an input are always refused.
Also: any ``.npy`` header in a DLM cache entry, and :func:`propwhirl.fileio.same_file`
against the file system's own answer."""
from __future__ import annotations

import io as _io
import os
import stat
from pathlib import Path

import numpy as np
import pytest
from hypothesis import example, given
from hypothesis import strategies as st

from fuzz.conftest import FUZZ, held_to_the_rule, record
from helpers.before_work import WorkStarted, count_work
from helpers.files import FifoWriter, NULL_DEVICE, ZERO_DEVICE, char_device, never_opened, \
    unix_socket

from propwhirl import fileio
from propwhirl.validate import InputError

ROOT = Path(__file__).resolve().parents[2]
RESULT = ROOT / "examples" / "certification" / "wingtip" / "campaign.json"
CAMPAIGN = """format = "propwhirl-campaign"
format_version = 1
model = "{model}"
[regulation]
name = "cs25"
[envelope]
airspeed = "TAS"
V_D_m_per_s = 50.0
altitudes_m = [0.0]
[[cases]]
name = "nominal"
"""
#: Bytes beyond every limit of a file read (a sparse file: no disk used).
HUGE = 2 ** 32 + 1
#: (major, minor) of a cache entry's matrix: 3 x 3 complex.
N_AIC = 3

INPUT_KINDS = ["valid", "junk", "empty", "device", "link to device", "fifo", "socket",
               "folder", "missing", "oversized"]
OUTPUT_KINDS = ["new", "existing", "device", "link to device", "fifo", "socket", "folder",
                "missing folder", "an input"]
#: kinds that must always be refused (and left as they are)
SPECIAL = {"device", "link to device", "fifo", "socket"}


class Modal(tuple):
    """(TOML text, the .npz's bytes) of a modal model; a short repr in hypothesis' reports."""

    def __repr__(self) -> str:
        return "<modal model w.toml, w.modes.npz>"


@pytest.fixture(scope="module")
def modal(tmp_path_factory) -> Modal:
    """A modal model: its TOML text ([modes] file = "w.modes.npz") and the .npz's bytes."""
    from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
    from propwhirl.io.modal_files import write_modes

    toml, npz = write_modes(wingtip_propeller_wing(), tmp_path_factory.mktemp("modal") / "w.toml")
    return Modal((toml.read_text(), npz.read_bytes()))


@pytest.fixture(scope="module")
def result():
    from propwhirl.studies.campaign_result import CampaignResult

    return CampaignResult.load(RESULT)


# --------------------------------------------------------------------------- making a kind
class Made:
    """A file of a kind at a path; `close` releases what is held; `intact` checks that a
    special file is still what it was."""

    def __init__(self, path: Path, kind: str):
        self.path, self.kind, self.fifo, self.sock, self.node = path, kind, None, None, None
        self.fifo_opened = False

    def intact(self) -> bool:
        if self.kind in ("device", "link to device"):
            return stat.S_ISCHR(os.lstat(self.node).st_mode) and (
                self.kind == "device" or os.path.islink(self.path))
        if self.kind == "fifo":
            return stat.S_ISFIFO(os.lstat(self.path).st_mode) and not self.fifo_opened
        if self.kind == "socket":
            return stat.S_ISSOCK(os.lstat(self.path).st_mode)
        return True

    def close(self) -> None:
        if self.fifo is not None:
            self.fifo_opened = self.fifo.opened.is_set()     # before close() releases it
            self.fifo.close()
        if self.sock is not None:
            self.sock.close()


def make(path: Path, kind: str, content: bytes, device: tuple[int, int],
         monkeypatch) -> Made:
    """`path` made a file of `kind` (`content` for a regular file)."""
    m = Made(path, kind)
    if kind in ("valid", "existing", "junk"):
        path.write_bytes(content)
    elif kind == "empty":
        path.write_bytes(b"")
    elif kind == "device":
        m.node = char_device(path, device)
        never_opened(monkeypatch, path)
    elif kind == "link to device":
        m.node = char_device(path.with_name("node"), device)
        path.symlink_to(m.node)
        never_opened(monkeypatch, m.node)
    elif kind == "fifo":
        m.fifo = FifoWriter(path)
    elif kind == "socket":
        m.sock = unix_socket(path)
    elif kind == "folder":
        path.mkdir()
    elif kind == "oversized":
        with open(path, "wb") as fh:
            fh.truncate(HUGE)
        never_opened(monkeypatch, path)             # refused on its size, before opening
    return m


def _aic_bytes() -> bytes:
    buf = _io.BytesIO()
    np.save(buf, np.eye(N_AIC, dtype=np.complex128), allow_pickle=False)
    return buf.getvalue()


# ------------------------------------------------------------------------------- readers
def _readers(base_text: str, modal, folder: Path):
    """name -> (file name, valid content, read(path) -> None; raises InputError or returns
    an exit code)."""
    from propwhirl import io
    from propwhirl.app import cli
    from propwhirl.app.report import sha256_file
    from propwhirl.io.campaign_files import load_campaign
    from propwhirl.model.aerodynamics import dlm_cache
    from propwhirl.studies.campaign_result import CampaignResult

    modal_text, npz = modal
    model = folder / "model.toml"
    model.write_text(base_text)
    aic = dlm_cache._path(folder, "geometry", 0.0, 0.1)

    def modes_file(path):
        toml = folder / "m.toml"
        text = modal_text.replace('file = "w.modes.npz"', f'file = "{path}"')
        toml.write_text(text)
        io.load_modal_model(toml)

    def campaign_model(path):
        (folder / "c.toml").write_text(CAMPAIGN.format(model=path.as_posix()))
        load_campaign(folder / "c.toml")

    return {
        "model file": ("x.toml", base_text.encode(), io.load_model),
        "modal model file": ("x.toml", modal_text.replace(
            'file = "w.modes.npz"', f'file = "{folder / "w.modes.npz"}"').encode(),
            io.load_modal_model),
        "[modes] file": ("x.npz", npz, modes_file),
        "campaign file": ("x.toml", CAMPAIGN.format(model=model.as_posix()).encode(),
                          load_campaign),
        "campaign model": ("x.toml", base_text.encode(), campaign_model),
        "result file": ("x.json", RESULT.read_bytes(), CampaignResult.load),
        "report hash": ("x.toml", b"anything\n", lambda p: sha256_file(p, "campaign file")),
        "DLM cache entry": (aic.name, _aic_bytes(),
                            lambda p: dlm_cache.load(folder, "geometry", 0.0, 0.1, N_AIC)),
        "upgrade-model OLD": ("x.toml", base_text.encode(),
                              lambda p: cli.main(["upgrade-model", str(p),
                                                  str(folder / "new.toml")])),
    }


READERS = ["model file", "modal model file", "[modes] file", "campaign file", "campaign model",
           "result file", "report hash", "DLM cache entry", "upgrade-model OLD"]


def _read_case(tmp_path_factory, base_text, modal, capsys, reader, kind, junk=b""):
    """One reader given one kind of file, held to the rule (module docstring)."""
    folder = tmp_path_factory.mktemp("in")
    (folder / "w.modes.npz").write_bytes(modal[1])     # the valid modal file's modes
    name, valid, read = _readers(base_text, modal, folder)[reader]
    path = folder / name
    with pytest.MonkeyPatch.context() as mp:
        made = make(path, kind, valid if kind == "valid" else junk, ZERO_DEVICE, mp)
        refused = False
        try:
            with held_to_the_rule(f"input {reader}: {kind}"):
                try:
                    code = read(path)
                except InputError:
                    refused = True
                    raise
                if isinstance(code, int):             # the command line: 0 or 2, one line
                    err = capsys.readouterr().err
                    assert code in (0, 2), err
                    record(f"input {reader}: {kind}", f"exit {code}")
                    if code == 2:
                        refused = True
                        assert err.startswith("propwhirl: error: ") and err.count("\n") == 1
        finally:
            made.close()
    if kind in SPECIAL or kind in ("folder", "oversized"):
        assert refused, f"{reader} read {kind}"
    assert made.intact(), f"{reader}: the {kind} was touched"


@pytest.mark.parametrize("kind", [k for k in INPUT_KINDS if k != "junk"])
@pytest.mark.parametrize("reader", READERS)
def test_every_kind_of_input_file(tmp_path_factory, base_text, modal, capsys, reader, kind):
    """Every reader and every kind of file: each pair once."""
    _read_case(tmp_path_factory, base_text, modal, capsys, reader, kind)


@FUZZ
@given(reader=st.sampled_from(READERS), junk=st.binary(max_size=300))
def test_any_junk_as_an_input_file(tmp_path_factory, base_text, modal, capsys, reader, junk):
    _read_case(tmp_path_factory, base_text, modal, capsys, reader, "junk", junk)


# ------------------------------------------------------------------------------- writers
def _writers(base_text: str, result, folder: Path):
    """name -> (file name, write(path); raises InputError or returns an exit code, the input
    it reads: None or a path)."""
    from propwhirl import io
    from propwhirl.app import cli
    from propwhirl.app.report import write_report
    from propwhirl.cases.registry import case_model
    from propwhirl.io.modal_files import write_modes

    model = folder / "model.toml"
    model.write_text(base_text)

    def certify(path):
        (folder / "c.toml").write_text(CAMPAIGN.format(model=model.as_posix()))
        return cli.main(["certify", str(folder / "c.toml"), "--out", str(path.parent),
                         "--no-pdf", "--quiet"])

    return {
        "upgrade-model NEW": ("x.toml", lambda p: cli.main(["upgrade-model", str(model),
                                                            str(p)]), model),
        "save_model": ("x.toml", lambda p: io.save_model(case_model("wingtip"), p), None),
        "write_modes": ("x.toml", lambda p: write_modes(io.load_model(model), p), model),
        "CampaignResult.to_csv": ("x.csv", lambda p: result.to_csv(p), None),
        "analyse --json": ("x.json", lambda p: cli.main(["analyse", str(model), "--json",
                                                         str(p)]), model),
        "certify campaign.csv": ("campaign.csv", certify, model),
        "write_report": ("report.html", lambda p: write_report(
            result, p.parent, model_file=model, pdf=False, figures=False), model),
    }


WRITERS = ["upgrade-model NEW", "save_model", "write_modes", "CampaignResult.to_csv",
           "analyse --json", "certify campaign.csv", "write_report"]


@pytest.mark.parametrize("kind", OUTPUT_KINDS)
@pytest.mark.parametrize("writer", WRITERS)
def test_every_kind_of_output_file(tmp_path_factory, base_text, result, capsys, writer, kind):
    """Every writer and every kind of output: each pair once (the work, where it would start,
    is replaced by a counter that raises)."""
    top = tmp_path_factory.mktemp("out")
    folder = top / "d"
    folder.mkdir()
    name, write, model = _writers(base_text, result, folder)[writer]
    path = folder / name
    if kind == "missing folder":
        path = folder / "missing" / name
    elif kind == "an input":
        if model is None:
            kind = "new"                               # this writer reads no file
        else:
            model.rename(path)                         # the input under the output's name
            model.symlink_to(path)
    with pytest.MonkeyPatch.context() as mp:
        work = count_work(mp)
        from propwhirl.studies import campaign

        mp.setattr(campaign, "run_campaign", lambda *a, **k: (_ for _ in ()).throw(
            WorkStarted("run_campaign called: the work started")))
        made = make(path, kind, b"old content\n", NULL_DEVICE, mp) \
            if kind not in ("missing folder", "an input") else Made(path, kind)
        before = path.read_bytes() if kind == "an input" else None
        refused = started = False
        try:
            with held_to_the_rule(f"output {writer}: {kind}"):
                try:
                    code = write(path)
                except InputError:
                    refused = True
                    raise
                except WorkStarted:                    # a valid output: the work began
                    started = True
                    code = None
                if isinstance(code, int):
                    err = capsys.readouterr().err
                    assert code in (0, 2), err
                    record(f"output {writer}: {kind}", f"exit {code}")
                    if code == 2:
                        refused = True
                        assert err.startswith("propwhirl: error: ") and err.count("\n") == 1
        finally:
            made.close()
    makes_folder = writer.startswith("certify")          # certify makes its --out folder
    if started:
        assert len(work) <= 1, work
        assert kind in ("new", "existing") or (kind == "missing folder" and makes_folder), \
            (writer, kind)
    if kind in SPECIAL or kind in ("folder", "an input") or (kind == "missing folder"
                                                              and not makes_folder):
        assert refused, f"{writer} wrote {kind}"
    if kind == "an input":
        assert path.read_bytes() == before, f"{writer} wrote over its input"
    assert made.intact(), f"{writer}: the {kind} was replaced"


# ---------------------------------------------------------------------- .npy headers, links
SHAPES = st.lists(st.one_of(st.integers(0, 8), st.integers(0, 10 ** 12)), min_size=0,
                  max_size=4).map(tuple)


@FUZZ
@example(shape=(N_AIC, N_AIC), descr="<c16", fortran=False, tail=bytes(16 * N_AIC ** 2))
@given(shape=SHAPES, descr=st.sampled_from(["<c16", ">c16", "<f8", "|O", "<i8", "<c8"]),
       fortran=st.booleans(), tail=st.binary(max_size=200))
def test_any_npy_header_in_a_cache_entry(tmp_path_factory, shape, descr, fortran, tail):
    """A cache entry declaring any shape and type: the matrix, or None (computed anew) — the
    header read before anything is allocated (no MemoryError, no pickle)."""
    from numpy.lib import format as npf

    from propwhirl.model.aerodynamics import dlm_cache

    folder = tmp_path_factory.mktemp("aic")
    path = dlm_cache._path(folder, "geometry", 0.0, 0.1)
    buf = _io.BytesIO()
    npf.write_array_header_1_0(buf, {"descr": descr, "fortran_order": fortran, "shape": shape})
    path.write_bytes(buf.getvalue() + tail)
    with held_to_the_rule("npy header"):
        Q = dlm_cache.load(folder, "geometry", 0.0, 0.1, N_AIC)
        assert Q is None or (Q.shape == (N_AIC, N_AIC) and Q.dtype == np.complex128)
    record("npy header", "matrix" if Q is not None else "None (computed anew)")


NAMES = st.lists(st.sampled_from(["a", "b", "sub", ".", "..", "soft", "hard", "new"]),
                 min_size=1, max_size=4).map(lambda parts: os.path.join(*parts))


@FUZZ
@given(a=NAMES, b=NAMES)
def test_same_file_is_the_file_systems_answer(tmp_path_factory, a, b):
    """Two paths name one file for :func:`propwhirl.fileio.check_apart` exactly when the file
    system says so (existing: ``os.path.samefile``; new: the same resolved path)."""
    top = tmp_path_factory.mktemp("names")
    (top / "sub").mkdir()
    for where in (top, top / "sub"):
        (where / "a").write_text("a")
        (where / "b").write_text("b")
        (where / "soft").symlink_to("a")
        os.link(where / "b", where / "hard")
    here = os.getcwd()
    os.chdir(top / "sub")
    try:
        exist = [os.path.exists(p) for p in (a, b)]
        if all(exist):
            truth = os.path.samefile(a, b)
        elif not any(exist):
            truth = os.path.realpath(a) == os.path.realpath(b)
        else:
            truth = False
        assert fileio.same_file(a, b) == truth, (a, b)
        outputs = [("--json", a), ("--csv", b)]
        if truth:
            with pytest.raises(InputError, match="are the same file|is the input"):
                fileio.check_apart(outputs)
        else:
            fileio.check_apart(outputs)
        record("same file", str(truth))
    finally:
        os.chdir(here)
