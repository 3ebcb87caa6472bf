"""Fuzz: entries of the doublet-lattice AIC cache (``PROPWHIRL_DLM_CACHE``; issue 33, item 4).

A cache of two AICs of a small wing, then an entry's ``.npy`` or its ``.sha256`` checksum
changed: bytes flipped, cut, appended, replaced, the file deleted or turned into a directory,
the matrix replaced by another one (any shape, non-finite values) without touching its
checksum.  Every read gives the uncached AIC bit for bit, with at most a one-line warning per
entry naming it, or (an entry turned into a directory: not a regular file, which the cache
never writes) a one-line InputError naming it — never a changed number, a traceback or an
unworded recomputation of a damaged entry.  A forger who also rewrites the checksum of the first entry read is met by the
spot check: the uncached AIC (a perturbation within round-off) or a one-line InputError naming
the cache directory."""
from __future__ import annotations

import hashlib
import shutil
import warnings

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from fuzz.conftest import FUZZ, record

pytest.importorskip("panelaero")

from propwhirl.model.aerodynamics import dlm, dlm_cache  # noqa: E402
from propwhirl.model.structure.wing import Wing  # noqa: E402
from propwhirl.validate import InputError  # noqa: E402

MACH, KS = 0.3, (0.3, 0.6)
LOAD = dlm_cache.load


def aero():
    w = Wing(semi_span=2.0, mass_per_length=1.0, EI=1e4, GJ=1e4, radius_of_gyration=0.25,
             n_elements=3)
    return dlm.DlmAerodynamics(w, n_chord=2, n_span=3)


@pytest.fixture(scope="module")
def pristine(tmp_path_factory):
    """(a directory holding the two entries with their checksums, the uncached AICs)."""
    mp = pytest.MonkeyPatch()
    mp.delenv(dlm_cache.CACHE_ENV, raising=False)
    want = [aero().aic(MACH, k) for k in KS]
    directory = tmp_path_factory.mktemp("aic-pristine")
    mp.setenv(dlm_cache.CACHE_ENV, str(directory))
    a = aero()
    for k in KS:
        a.aic(MACH, k)
    mp.undo()
    assert len(list(directory.glob("aic-*.npy"))) == len(KS)
    return directory, want


def checksum_path(path):
    return path.with_suffix(".sha256")


def fresh(pristine, tmp_path, monkeypatch):
    directory = tmp_path / "aic"
    shutil.rmtree(directory, ignore_errors=True)
    shutil.copytree(pristine[0], directory)
    monkeypatch.setenv(dlm_cache.CACHE_ENV, str(directory))
    a = aero()
    paths = [dlm_cache._path(directory, a._geometry, MACH, k / a.b_ref) for k in KS]
    return directory, a, paths


FINITE = st.floats(-1e6, 1e6, allow_nan=False)
MATRIX = st.tuples(st.integers(0, 8), st.integers(0, 8), st.sampled_from(["c16", "f8", "i8"]),
                   st.lists(st.one_of(FINITE, st.sampled_from([np.nan, np.inf])), min_size=1,
                            max_size=4))
CHANGE = st.one_of(
    st.tuples(st.just("flip"), st.lists(st.tuples(st.integers(0, 10**6), st.integers(1, 255)),
                                        min_size=1, max_size=4)),
    st.tuples(st.just("cut"), st.integers(0, 10**6)),
    st.tuples(st.just("append"), st.binary(min_size=1, max_size=64)),
    st.tuples(st.just("replace"), st.binary(max_size=300)),
    st.tuples(st.just("delete"), st.none()),
    st.tuples(st.just("directory"), st.none()),
    st.tuples(st.just("matrix"), MATRIX),
    st.tuples(st.just("scaled"), FINITE),
)


def apply(path, how, arg):
    if how in ("delete", "directory"):
        path.unlink()
        if how == "directory":
            path.mkdir()
        return
    data = path.read_bytes()
    if how in ("matrix", "scaled") and path.suffix == ".sha256":
        how, arg = "replace", hashlib.sha256(repr(arg).encode()).hexdigest().encode()
    if how == "flip" and data:
        b = bytearray(data)
        for pos, x in arg:
            b[pos % len(b)] ^= x
        data = bytes(b)
    elif how == "cut":
        data = data[:arg % (len(data) + 1)]
    elif how == "append":
        data += arg
    elif how == "replace":
        data = arg
    elif how in ("matrix", "scaled"):
        if how == "matrix":
            rows, cols, kind, values = arg
            Q = np.resize(np.array(values), rows * cols).reshape(rows, cols)
            Q = np.nan_to_num(Q, posinf=1.0, neginf=-1.0) if kind == "i8" else Q
            Q = Q.astype(kind)
        else:
            try:
                Q = arg * np.load(path, allow_pickle=False)
            except (OSError, ValueError, EOFError):
                return                                  # damaged before: left so
        np.save(path, Q, allow_pickle=False)
        return
    path.write_bytes(data)


@FUZZ
@given(changes=st.lists(st.tuples(st.integers(0, 1), st.sampled_from(["npy", "sha256"]),
                                  CHANGE), min_size=1, max_size=3))
def test_fuzz_cache_entries(pristine, tmp_path, monkeypatch, changes):
    directory, a, paths = fresh(pristine, tmp_path, monkeypatch)
    for j, which, (how, arg) in changes:
        target = paths[j] if which == "npy" else checksum_path(paths[j])
        if target.is_file():
            apply(target, how, arg)
    # silence is allowed only where no entry can be checked: no checksum, or no file at all
    silent_ok = [not checksum_path(p).exists() or not p.exists() for p in paths]
    loaded = []
    with pytest.MonkeyPatch.context() as mp, warnings.catch_warnings(record=True) as caught:
        mp.setattr(dlm_cache, "load", lambda *args: loaded.append(LOAD(*args)) or loaded[-1])
        warnings.simplefilter("always")
        try:
            got = [a.aic(MACH, k) for k in KS]
        except InputError as exc:    # an entry that is not a regular file: refused, named
            msg = str(exc)
            assert "\n" not in msg and "not a regular file" in msg, msg
            assert any(p.is_dir() and p.name[-20:] in msg for p in paths), msg  # name shortened
            record("dlm cache entry", "InputError")
            return
    for g, w in zip(got, pristine[1]):
        assert np.array_equal(g, w), "a changed cache entry changed an AIC"
    named = [str(p) for p in paths] + [str(checksum_path(p)) for p in paths]
    for w in caught:
        msg = str(w.message)
        assert w.category is UserWarning and "\n" not in msg, msg
        assert msg.startswith(f"{dlm_cache.CACHE_ENV}: ") and any(p in msg for p in named), msg
    assert len(caught) <= 2 * len(KS)
    for j, p in enumerate(paths):               # an entry not used was said, or uncheckable
        said = any(str(p) in str(w.message) for w in caught)
        assert loaded[j] is not None or said or silent_ok[j], f"entry {j} recomputed unsaid"
    record("dlm cache entry", "warning" if caught else "result")


@FUZZ
@given(first=st.integers(0, 1), factor=st.one_of(
    FINITE, st.floats(1 - 1e-6, 1 + 1e-6), st.floats(1 - 1e-12, 1 + 1e-12)),
    noise=st.floats(0.0, 1e-3))
def test_fuzz_forged_entries(pristine, tmp_path, monkeypatch, first, factor, noise):
    """Both entries altered with valid checksums; the first read is spot-checked."""
    directory, a, paths = fresh(pristine, tmp_path, monkeypatch)
    rng = np.random.default_rng(abs(hash((first, factor, noise))) % 2**32)
    for p in paths:
        Q = np.load(p)
        Q = factor * Q + noise * np.abs(Q).max() * rng.standard_normal(Q.shape)
        np.save(p, Q, allow_pickle=False)
        checksum_path(p).write_text(dlm_cache.checksum(p, Q) + "\n")
    k = KS[first]
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            got = a.aic(MACH, k)
    except InputError as exc:
        msg = str(exc)
        assert "\n" not in msg and msg.startswith(
            f"{dlm_cache.CACHE_ENV} = {str(directory)!r} is invalid: {paths[first].name} "
            "differs from the AIC computed again"), msg
        assert a.evaluations == 1
        record("dlm cache forged", "InputError")
        return
    assert np.array_equal(got, pristine[1][first])     # within round-off: the computed one
    record("dlm cache forged", "result")
