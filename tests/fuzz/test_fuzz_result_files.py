"""Fuzz: the result files propwhirl writes and reads back (issue 20, items 4 and 6).

* eigenvector ``.npz`` files whose arrays declare another shape or dtype than the analysis
  file says, or whose zip members declare (or inflate to) gigabytes: refused with one line
  naming the file, the array, the declared and the expected shape — before anything of that
  size is allocated (peak allocations measured with ``tracemalloc``: a work bound, not time);
* a file name of 5,000 characters given to every loader and writer: one short line naming the
  (shortened) path and the operating system's reason, never a raw ``OSError``;
* a V-g-f table cut at a line boundary: refused (the first line says how many rows follow).
"""
from __future__ import annotations

import io
import json
import struct
import tracemalloc
import zipfile
import zlib
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from fuzz.conftest import FUZZ, held_to_the_rule
from propwhirl import fileio
from propwhirl import io as pio
from propwhirl.analysis import analyse, load
from propwhirl.cases.ch09_baseline import isolated_baseline_propeller
from propwhirl.studies.sweeps import RESULT_UNITS, Axis, CriticalMap
from propwhirl.studies.table import StudyTable
from propwhirl.validate import InputError

#: peak bytes a refused file may make propwhirl allocate (the analysis file and its small
#: arrays are a few hundred kB; the files below declare 4.5-60 GiB)
PEAK = 50 * 2 ** 20


@pytest.fixture(scope="module")
def saved(tmp_path_factory):
    """An analysis file with its eigenvector file: (folder, JSON text, npz bytes, analysis)."""
    a = analyse(isolated_baseline_propeller(), speeds=[100.0, 200.0, 250.0], vgf=True)
    folder = tmp_path_factory.mktemp("saved")
    a.save(folder / "a.json", include_eigenvectors=True)
    return (folder, (folder / "a.json").read_text(),
            (folder / "a.eigenvectors.npz").read_bytes(), a)


def npy_header(shape, descr: str = "<c16", fortran: bool = False) -> bytes:
    """A version 1.0 ``.npy`` header declaring `shape` and `descr` (no data after it)."""
    h = repr({"descr": descr, "fortran_order": fortran, "shape": tuple(shape)})
    pad = 64 - (10 + len(h) + 1) % 64
    h = (h + " " * pad + "\n").encode("latin1")
    return b"\x93NUMPY\x01\x00" + struct.pack("<H", len(h)) + h


def members(npz: bytes) -> dict[str, bytes]:
    with zipfile.ZipFile(io.BytesIO(npz)) as z:
        return {n: z.read(n) for n in z.namelist()}


def stored_zip(files: dict[str, bytes]) -> bytes:
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w") as z:
        for name, data in files.items():
            z.writestr(name, data)
    return buf.getvalue()


def raw_zip(files: dict[str, tuple[bytes, int, int, int]]) -> bytes:
    """A zip built by hand: name → (deflated stream, declared uncompressed size, CRC-32,
    method) — the sizes need not be true (zip64 extra field for sizes ≥ 4 GiB)."""
    out, central = io.BytesIO(), io.BytesIO()
    for name, (data, size, crc, method) in files.items():
        n = name.encode()
        big = size >= 0xFFFFFFFF
        extra = struct.pack("<HHQ", 1, 8, size) if big else b""
        fsize = 0xFFFFFFFF if big else size
        offset = out.tell()
        out.write(struct.pack("<IHHHHHIIIHH", 0x04034B50, 45, 0, method, 0, 0x21, crc,
                              len(data), fsize, len(n), len(extra)) + n + extra + data)
        central.write(struct.pack("<IHHHHHHIIIHHHHHII", 0x02014B50, 45, 45, 0, method, 0,
                                  0x21, crc, len(data), fsize, len(n), len(extra), 0, 0, 0, 0,
                                  offset) + n + extra)
    cd = central.getvalue()
    start = out.tell()
    out.write(cd + struct.pack("<IHHHHIIH", 0x06054B50, 0, 0, len(files), len(files), len(cd),
                               start, 0))
    return out.getvalue()


def refused_within_bound(folder: Path, npz: bytes, *matches: str) -> str:
    """Write `npz` as the eigenvector file of the saved analysis, load it: an InputError of
    one line naming the npz and containing `matches`, with a bounded peak allocation."""
    (folder / "a.eigenvectors.npz").write_bytes(npz)
    tracemalloc.start()
    try:
        with pytest.raises(InputError) as err:
            load(folder / "a.json")
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    msg = str(err.value)
    assert "\n" not in msg and "a.eigenvectors.npz" in msg, msg
    for m in matches:
        assert m in msg, msg
    assert peak < PEAK, f"peak allocation {peak / 2 ** 20:.0f} MiB: {msg}"
    return msg


def copy_json(saved, tmp_path) -> Path:
    folder, text, _, _ = saved
    (tmp_path / "a.json").write_text(text)
    return tmp_path


# ----------------------------------------------------------------------------- npz
def test_the_saved_eigenvectors_are_read(saved, tmp_path):
    folder = copy_json(saved, tmp_path)
    (folder / "a.eigenvectors.npz").write_bytes(saved[2])
    a = saved[3]
    assert np.array_equal(load(folder / "a.json").sweep.eigenvectors, a.sweep.eigenvectors)


def test_a_300_byte_npz_declaring_60_GiB(saved, tmp_path):
    """Issue 20.4: eigenvectors.npy declaring (4, 10⁹) complex128 (59.6 GiB) in a 300-byte
    member: np.load allocated first (MemoryError); now its header is checked against the
    analysis file before anything is read."""
    folder = copy_json(saved, tmp_path)
    files = members(saved[2])
    files["eigenvectors.npy"] = npy_header((4, 10 ** 9))
    assert len(files["eigenvectors.npy"]) < 300
    T, n = saved[3].sweep.eigenvalues.shape
    ns = len(saved[3].sweep.state_labels)
    refused_within_bound(folder, stored_zip(files), "eigenvectors", "(4, 1000000000)",
                         f"({T}, {ns}, {n})")


def _zero_blocks(total: int, block: int = 1 << 20) -> bytes:
    """A raw deflate stream of `total` zero bytes, built from one compressed block repeated
    (a full flush makes each block independent): megabytes that inflate to gigabytes, built
    without compressing them."""
    c = zlib.compressobj(9, zlib.DEFLATED, -15)
    one = c.compress(bytes(block)) + c.flush(zlib.Z_FULL_FLUSH)
    assert c.compress(bytes(block)) + c.flush(zlib.Z_FULL_FLUSH) == one
    return one * (total // block) + c.flush()


def test_a_deflate_bomb(saved, tmp_path):
    """Issue 20.4: a member declaring 4.5 GiB (ZipInfo.file_size) whose npy header declares a
    matching shape, its deflate stream inflating to gigabytes: np.load allocated the 4.5 GiB
    and inflated into it; now the declared size is refused before inflating."""
    folder = copy_json(saved, tmp_path)
    T, n = saved[3].sweep.eigenvalues.shape
    ns = len(saved[3].sweep.state_labels)
    size = int(4.5 * 2 ** 30)
    head = npy_header((T, ns, (size - 128) // (16 * T * ns)))
    c = zlib.compressobj(9, zlib.DEFLATED, -15)
    stream = c.compress(head) + c.flush(zlib.Z_FULL_FLUSH) + _zero_blocks(64 << 20)
    assert len(stream) < 1 << 20
    files = {k: (zlib.compress(d)[2:-4], len(d), zlib.crc32(d), zipfile.ZIP_DEFLATED)
             for k, d in members(saved[2]).items() if k != "eigenvectors.npy"}
    files["eigenvectors.npy"] = (stream, size, 0, zipfile.ZIP_DEFLATED)
    msg = refused_within_bound(folder, raw_zip(files), "eigenvectors")
    assert "4.5 GiB" in msg or f"({T}, {ns}, {n})" in msg, msg


def test_a_stream_longer_than_its_declared_size_is_read_no_further(saved, tmp_path):
    """A member declaring the expected size whose stream goes on inflating (64 MiB of zeros
    and a wrong CRC): only the declared bytes are inflated, then refused (not the zip's CRC)."""
    folder = copy_json(saved, tmp_path)
    files = {k: (zlib.compress(d)[2:-4], len(d), zlib.crc32(d), zipfile.ZIP_DEFLATED)
             for k, d in members(saved[2]).items()}
    true = members(saved[2])["eigenvectors.npy"]
    c = zlib.compressobj(9, zlib.DEFLATED, -15)
    head = true[:len(true) - saved[3].sweep.eigenvectors.nbytes]
    stream = c.compress(head) + c.flush(zlib.Z_FULL_FLUSH) + _zero_blocks(64 << 20)
    files["eigenvectors.npy"] = (stream, len(true), zlib.crc32(true), zipfile.ZIP_DEFLATED)
    refused_within_bound(folder, raw_zip(files), "eigenvectors")


SHAPES = st.lists(st.one_of(st.integers(0, 8), st.sampled_from([10 ** 6, 10 ** 9, 2 ** 62])),
                  max_size=4).map(tuple)
DESCRS = st.sampled_from(["<c16", ">c16", "<f8", "<c8", "|O", "<i8", "|V16", "<U10", "|b1"])


@FUZZ
@given(name=st.sampled_from(["V.npy", "eigenvalues.npy", "eigenvectors.npy"]), shape=SHAPES,
       descr=DESCRS, fortran=st.booleans(), data_bytes=st.integers(0, 4096))
def test_any_declared_array(saved, tmp_path_factory, name, shape, descr, fortran, data_bytes):
    """Any shape and dtype declared by one member (with up to 4 kB of data after the
    header): a finite result or one line naming the npz, within the allocation bound."""
    folder = copy_json(saved, tmp_path_factory.mktemp("any"))
    files = members(saved[2])
    files[name] = npy_header(shape, descr, fortran) + bytes(data_bytes)
    (folder / "a.eigenvectors.npz").write_bytes(stored_zip(files))
    tracemalloc.start()
    try:
        with held_to_the_rule("result file: npz member", "a.eigenvectors.npz"):
            assert np.isfinite(load(folder / "a.json").sweep.eigenvectors).all()
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert peak < PEAK


@pytest.mark.parametrize("change", ["extra member", "missing member", "not a zip",
                                    "empty", "large file"])
def test_malformed_npz(saved, tmp_path, change):
    folder = copy_json(saved, tmp_path)
    files = members(saved[2])
    if change == "extra member":
        files["x.npy"] = npy_header((1,), "<f8") + bytes(8)
        npz = stored_zip(files)
    elif change == "missing member":
        del files["V.npy"]
        npz = stored_zip(files)
    elif change == "not a zip":
        npz = b"PK\x03\x04" + bytes(100)
    elif change == "empty":
        npz = b""
    else:       # 64 MiB of junk after a valid npz: the file is larger than its arrays
        npz = saved[2] + bytes(64 << 20)
    refused_within_bound(folder, npz)


def test_bzip2_members_are_refused(saved, tmp_path):
    """numpy writes stored or deflated members only; zipfile inflates bzip2 and LZMA without a
    bound per read, so they are refused (np.load read them)."""
    folder = copy_json(saved, tmp_path)
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w", zipfile.ZIP_BZIP2) as z:
        for name, data in members(saved[2]).items():
            z.writestr(name, data)
    refused_within_bound(folder, buf.getvalue(), "zip method 12")


def test_arrays_beyond_the_memory_limit(tmp_path, monkeypatch):
    """The arrays the analysis file describes are held to the memory limit before the npz
    is opened."""
    from propwhirl.engine.results import read_npz

    monkeypatch.setenv("PROPWHIRL_MEMORY_LIMIT", "64MiB")
    with pytest.raises(InputError, match=r"^x\.npz: its arrays eigenvectors \(100, 300, 300\) "
                                         r"complex128 needs ≈ 137 MiB to read \(limit 64\.0 "
                                         r"MiB, set PROPWHIRL_MEMORY_LIMIT\)$"):
        read_npz(tmp_path / "x.npz", {"eigenvectors": ((100, 300, 300), complex)}, "x.npz")


# ----------------------------------------------------------------------------- long names
LONG = "a" * 5000


def _loaders_and_writers(saved, d: Path):
    a = saved[3]
    table = StudyTable("t", "x", {"model": np.array(["m"]), "x": np.arange(1.0)})
    model = isolated_baseline_propeller()
    return {
        "fileio.read_text": lambda p: fileio.read_text(p, "analysis file"),
        "fileio.read_json": lambda p: fileio.read_json(p, "boundary file"),
        "fileio.write_text": lambda p: fileio.write_text(p, "x", what="report"),
        "fileio.write_bytes": lambda p: fileio.write_bytes(p, b"x", what="plot"),
        "fileio.check_writable": lambda p: fileio.check_writable(p, what="--json"),
        "fileio.check_writable folder": lambda p: fileio.check_writable(p, folder=True,
                                                                        create=True),
        "analysis save": lambda p: a.save(p),
        "analysis save with eigenvectors": lambda p: a.save(p, include_eigenvectors=True),
        "analysis load": load,
        "V-g-f table write": lambda p: pio.write_vgf_csv(a, p),
        "V-g-f table read": pio.read_vgf_csv,
        "study table CSV": table.to_csv,
        "model file read": pio.load_model,
        "model file write": lambda p: pio.save_model(model, p),
    }


@pytest.mark.parametrize("where", ["name", "folder"])
@pytest.mark.parametrize("call", ["fileio.read_text", "fileio.read_json", "fileio.write_text",
                                  "fileio.write_bytes", "fileio.check_writable",
                                  "fileio.check_writable folder", "analysis save",
                                  "analysis save with eigenvectors", "analysis load",
                                  "V-g-f table write", "V-g-f table read", "study table CSV",
                                  "model file read", "model file write"])
def test_a_5000_character_file_name(saved, tmp_path, call, where):
    """Issue 20.4: a 5,000-character file name gave a raw OSError (writers) or a 5,000-
    character message (readers); now one line naming the shortened path and the reason."""
    path = tmp_path / (LONG + ".json") if where == "name" else tmp_path / LONG / "a.json"
    f = _loaders_and_writers(saved, tmp_path)[call]
    with pytest.raises(InputError) as err:
        f(path)
    msg = str(err.value)
    assert "\n" not in msg and str(tmp_path)[:40] in msg, msg
    assert len(msg) < 400, msg
    assert "File name too long" in msg, msg
    assert "…" in msg, msg


def test_a_255_character_file_name_is_written(tmp_path):
    """The temporary file beside it took the whole name plus 14 characters: a name of 250
    characters (the usual limit is 255) could not be written."""
    path = tmp_path / ("a" * 251 + ".txt")
    fileio.write_text(path, "complete\n")
    assert path.read_text() == "complete\n" and len(list(tmp_path.iterdir())) == 1


def test_short_paths_are_named_in_full(tmp_path):
    path = tmp_path / "missing" / "a.json"
    with pytest.raises(InputError, match=f"'{path}'"):
        fileio.read_text(path, "analysis file")


# ----------------------------------------------------------------------------- CSV
@pytest.fixture(scope="module")
def vgf_text(saved, tmp_path_factory) -> str:
    path = pio.write_vgf_csv(saved[3], tmp_path_factory.mktemp("vgf") / "vgf.csv")
    return path.read_text()


def test_the_vgf_table_says_how_many_rows_it_has(saved, vgf_text, tmp_path):
    rows = len(saved[3].sweep.table()["V"])
    first = vgf_text.splitlines()[0]
    assert first.startswith("#") and f"{rows} rows" in first, first
    path = tmp_path / "vgf.csv"
    path.write_text(vgf_text, newline="")
    assert len(pio.read_vgf_csv(path)["V"]) == rows


@FUZZ
@given(keep=st.integers(2, 100))
def test_a_vgf_table_cut_at_a_line_boundary(vgf_text, tmp_path_factory, keep):
    """Issue 20.6: a table cut at a line boundary (all rows of a speed gone, or some) loaded
    as a shorter table; now the row count of its first line refuses it."""
    lines = vgf_text.splitlines(keepends=True)
    keep = min(keep, len(lines) - 1)
    path = tmp_path_factory.mktemp("cut") / "vgf.csv"
    path.write_text("".join(lines[:keep]), newline="")
    with pytest.raises(InputError, match=r"vgf\.csv: .*rows.*truncated") as err:
        pio.read_vgf_csv(path)
    assert "\n" not in str(err.value)


def test_a_vgf_table_with_rows_added(vgf_text, tmp_path):
    lines = vgf_text.splitlines(keepends=True)
    path = tmp_path / "vgf.csv"
    path.write_text("".join(lines + lines[-1:]), newline="")
    with pytest.raises(InputError, match=r"vgf\.csv: .*rows"):
        pio.read_vgf_csv(path)


@pytest.mark.parametrize("first", ["# propwhirl V-g-f table: many rows",
                                   "# propwhirl V-g-f table: -3 rows",
                                   "# propwhirl V-g-f table: 99999999999999999999999 rows",
                                   "# something else"])
def test_a_vgf_table_with_a_bad_count_line(vgf_text, tmp_path, first):
    lines = vgf_text.splitlines(keepends=True)
    path = tmp_path / "vgf.csv"
    path.write_text(first + "\r\n" + "".join(lines[1:]), newline="")
    with pytest.raises(InputError, match=r"vgf\.csv: line 1") as err:
        pio.read_vgf_csv(path)
    assert "\n" not in str(err.value)


def test_a_table_of_an_older_propwhirl_loads_with_a_warning(saved, vgf_text, tmp_path):
    """A table written before the row count (no first comment line) still loads, but a cut at
    a line boundary cannot be found in it: a warning says so, naming the file."""
    lines = vgf_text.splitlines(keepends=True)
    path = tmp_path / "old.csv"
    path.write_text("".join(lines[1:]), newline="")
    with pytest.warns(UserWarning, match=r"old\.csv: .*no row count.*cannot be checked"):
        t = pio.read_vgf_csv(path)
    assert np.array_equal(t["V"], saved[3].sweep.table()["V"])


@pytest.fixture(scope="module")
def map_text() -> str:
    """The CSV of a critical map over 2 × 3 parameter values (made up, not analysed)."""
    axes = (Axis("propeller.f_theta", np.array([4.0, 7.0]), "Hz"),
            Axis("propeller.f_psi", np.array([4.0, 7.0, 10.0]), "Hz"))
    V = np.arange(6.0).reshape(2, 3) * 10 + 100
    cols = {k: np.full((2, 3), "", dtype=object) for k in RESULT_UNITS}
    cols.update(critical_speed=V, critical_frequency=V / 20, propeller=np.zeros((2, 3), int),
                propeller_share=np.full((2, 3), 0.5),
                static_divergence_speed=np.full((2, 3), np.nan),
                critical_mode=np.full((2, 3), "forward 1", dtype=object),
                kind=np.full((2, 3), "flutter", dtype=object))
    m = CriticalMap("made up", axes, cols, "every instability counts")
    text = m.to_csv()
    assert np.array_equal(CriticalMap.from_csv(text).critical_speed, V)
    return text


@pytest.mark.parametrize("keep", [3, 4, 5])
def test_a_critical_map_cut_at_a_line_boundary(map_text, keep):
    """Issue 20.6: a critical map's CSV cut after a whole block of its first parameter (a
    smaller grid, nothing else wrong) or inside one loaded or failed deep inside; now the
    row count of its first line refuses it."""
    cut = "".join(map_text.splitlines(keepends=True)[:keep])
    with pytest.raises(InputError, match=r"^m\.csv: has \d rows, its first line says 6 "
                                         r"\(truncated\?\)$"):
        CriticalMap.from_csv(cut, "m.csv")


def test_a_critical_map_cut_inside_a_row(map_text):
    """A row cut short gave a raw IndexError."""
    cut = map_text[:map_text.rindex(",", 0, len(map_text) - 20)]
    with pytest.raises(InputError, match=r"^m\.csv: line 8 has \d+ columns, need \d+ "
                                         r"\(truncated\?\)$"):
        CriticalMap.from_csv(cut, "m.csv")


def test_a_critical_map_of_an_older_propwhirl_loads_with_a_warning(map_text):
    with pytest.warns(UserWarning, match=r"m\.csv: a critical map with no row count"):
        m = CriticalMap.from_csv(map_text.partition("\n")[2], "m.csv")
    assert m.critical_speed.shape == (2, 3)


def mutated(text: str, data) -> str:
    """`text` with one line cut, dropped, doubled, replaced by any text or by a field over
    csv's size limit.  The count line itself is kept (without it the file is an older
    propwhirl's: a warning, tested above)."""
    lines = text.splitlines(keepends=True)
    how = data.draw(st.sampled_from(["cut", "drop", "double", "replace", "huge field"]))
    i = data.draw(st.integers(0 if how in ("cut", "double") else 1, len(lines) - 1),
                  label="line")
    if how == "cut":
        lines = lines[:i] + [lines[i][:data.draw(st.integers(0, len(lines[i])))]]
    elif how == "drop":
        del lines[i]
    elif how == "double":
        lines.insert(i, lines[i])
    elif how == "replace":
        lines[i] = data.draw(st.text(max_size=40), label="text") + "\n"
    else:
        lines[i] = '"' + "x" * 200_000 + '"\n'
    return "".join(lines)


@FUZZ
@given(data=st.data())
def test_any_critical_map_csv(map_text, data):
    """A critical map's CSV mutated (:func:`mutated`): a map or one line naming the file (a
    field over csv's limit gave a raw csv.Error, a short row an IndexError)."""
    text = mutated(map_text, data)
    with held_to_the_rule("result file: critical-map CSV", "m.csv"):
        m = CriticalMap.from_csv(text, "m.csv")
        assert np.isfinite(m.critical_speed[~np.isnan(m.critical_speed)]).all()


@FUZZ
@given(data=st.data())
def test_any_vgf_csv(vgf_text, tmp_path_factory, data):
    """A V-g-f table mutated (:func:`mutated`): a table or one line naming the file."""
    path = tmp_path_factory.mktemp("any") / "vgf.csv"
    path.write_text(mutated(vgf_text, data), newline="")
    with held_to_the_rule("result file: V-g-f CSV", "vgf.csv"):
        t = pio.read_vgf_csv(path)
        assert all(np.isfinite(t[k]).all() for k in ("V", "frequency_hz", "real", "imag"))
