"""The disk cache of doublet-lattice AICs (issue 23, item 6): propwhirl.model.aerodynamics.dlm_cache."""
import numpy as np
import pytest

pytest.importorskip("panelaero")

from propwhirl.model.aerodynamics import dlm, dlm_cache  # noqa: E402
from propwhirl.model.structure.wing import Wing  # noqa: E402
from propwhirl.validate import InputError  # noqa: E402


def aero(**kw):
    w = Wing(semi_span=2.0, mass_per_length=1.0, EI=1e4, GJ=1e4, radius_of_gyration=0.25,
             n_elements=4, **kw)
    return dlm.DlmAerodynamics(w, n_chord=3, n_span=4)


def test_no_cache_by_default(monkeypatch, tmp_path):
    monkeypatch.delenv(dlm_cache.CACHE_ENV, raising=False)
    a = aero()
    assert a.cache is None
    a.aic(0.2, 0.4)
    assert a.evaluations == 1 and a.cache_hits == 0


def test_a_second_analysis_reads_the_aics_back(monkeypatch, tmp_path):
    monkeypatch.setenv(dlm_cache.CACHE_ENV, str(tmp_path / "aic"))
    first = aero()
    Q = first.aic(0.2, 0.4)
    assert first.evaluations == 1 and len(list((tmp_path / "aic").glob("aic-*.npy"))) == 1
    assert len(list((tmp_path / "aic").glob("aic-*.sha256"))) == 1       # its checksum
    second = aero()                                   # a new analysis of the same panels
    assert np.array_equal(second.aic(0.2, 0.4), Q)
    # the first entry read of a geometry is computed again all the same (the spot check)
    assert second.evaluations == 1 and second.cache_hits == 1
    # another k, Mach or planform is another matrix
    second.aic(0.2, 0.41)
    second.aic(0.25, 0.4)
    assert second.evaluations == 3
    other = aero(root_chord=1.1)
    other.aic(0.2, 0.4)
    assert other.evaluations == 1 and len(list((tmp_path / "aic").glob("*.npy"))) == 4
    third = aero()                                    # after its spot check, read only
    for k in (0.4, 0.41):
        third.aic(0.2, k)
    third.aic(0.25, 0.4)
    assert third.evaluations == 1 and third.cache_hits == 3


def test_a_damaged_file_is_computed_again(monkeypatch, tmp_path):
    monkeypatch.setenv(dlm_cache.CACHE_ENV, str(tmp_path))
    Q = aero().aic(0.0, 0.3)
    (path,) = tmp_path.glob("aic-*.npy")
    path.write_bytes(b"not a matrix")
    again = aero()
    with pytest.warns(UserWarning, match=f"{path.name} is damaged .unreadable"):
        assert np.array_equal(again.aic(0.0, 0.3), Q) and again.evaluations == 1
    np.save(path, np.zeros((2, 2)), allow_pickle=False)     # wrong shape and type
    third = aero()
    with pytest.warns(UserWarning, match=f"{path.name} is damaged .not a finite 12 x 12"):
        assert np.array_equal(third.aic(0.0, 0.3), Q) and third.evaluations == 1
    assert dlm_cache.load(tmp_path, third._geometry, 0.0, 0.3 / third.b_ref, third.mesh.n) \
        is not None                                   # rewritten


def test_an_unusable_directory_is_an_input_error(monkeypatch, tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("x")
    monkeypatch.setenv(dlm_cache.CACHE_ENV, str(blocker / "sub"))
    with pytest.raises(InputError, match="PROPWHIRL_DLM_CACHE = .* is invalid: cannot create"):
        aero()


# ------------------------------------------------------------------ issue 33, item 3
def _entry(tmp_path, monkeypatch):
    """(the AIC model, the path of its entry at Mach 0, k = 0.3, its key's arguments)."""
    monkeypatch.setenv(dlm_cache.CACHE_ENV, str(tmp_path))
    a = aero()
    args = (a._geometry, 0.0, 0.3 / a.b_ref)
    return a, dlm_cache._path(tmp_path, *args), args


def test_a_fifo_as_a_cache_entry_is_refused_without_opening_it(tmp_path, monkeypatch):
    """A FIFO as an AIC cache entry waited for a writer for ever: one line naming it."""
    from helpers.files import FifoWriter

    a, path, _ = _entry(tmp_path, monkeypatch)
    with FifoWriter(path) as fifo:
        with pytest.raises(InputError) as e:
            a.aic(0.0, 0.3)
        assert not fifo.opened.is_set()
    from propwhirl.fileio import quoted

    assert str(e.value) == (f"cannot read PROPWHIRL_DLM_CACHE entry {quoted(path)}: it is a FIFO "
                            "(named pipe), not a regular file (propwhirl reads regular files "
                            "only)")
    assert a.evaluations == 0                                # refused before computing


def test_a_header_declaring_a_huge_matrix_is_read_first(tmp_path, monkeypatch):
    """A .npy header declaring (10^6, 10^6) was a MemoryError traceback: the header is checked
    before anything is allocated; the entry is computed anew and rewritten."""
    from numpy.lib import format as npf

    a, path, args = _entry(tmp_path, monkeypatch)
    with open(path, "wb") as fh:
        npf.write_array_header_1_0(fh, {"descr": "<c16", "fortran_order": False,
                                        "shape": (10 ** 6, 10 ** 6)})
        fh.write(b"\0" * 64)
    n = a.mesh.n
    assert dlm_cache.load(tmp_path, *args, n) is None
    Q = a.aic(0.0, 0.3)
    assert a.evaluations == 1 and np.array_equal(dlm_cache.load(tmp_path, *args, n), Q)


def test_an_entry_larger_than_its_matrix_is_refused_before_reading(tmp_path, monkeypatch):
    a, path, args = _entry(tmp_path, monkeypatch)
    with open(path, "wb") as fh:
        fh.truncate(2 ** 32)                                 # sparse: 4 GiB of nothing
    with pytest.raises(InputError, match="it has 4,294,967,296 bytes, more than"):
        dlm_cache.load(tmp_path, *args, a.mesh.n)
