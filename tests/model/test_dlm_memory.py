"""The memory of a doublet-lattice AIC, estimated before any panel is built (issue 33, item 7):
2,000 panels (the most dlm_mesh allows) need ≈ 7.6 GiB per AIC; beyond the memory limit the
analysis is refused in one line naming the panel counts that fit, no AIC computed."""
import dataclasses
import tracemalloc

import numpy as np
import pytest

pytest.importorskip("panelaero")

from propwhirl import limits  # noqa: E402
from propwhirl.analysis import analyse  # noqa: E402
from propwhirl.cases.ch07_patil import patil_model  # noqa: E402
from propwhirl.model.aerodynamics import dlm, dlm_mesh  # noqa: E402
from propwhirl.validate import InputError  # noqa: E402

MESSAGE = ("dlm_chordwise_panels x dlm_spanwise_panels = 20 x 100 = 2,000 panels is invalid: "
           "each AIC needs ≈ 7.6 GiB (limit 4.0 GiB, set PROPWHIRL_MEMORY_LIMIT); at most 1,448 "
           "panels fit, e.g. 20 x 72 or 14 x 100")


def patil(nc, ns):
    m = patil_model(10)
    return m.with_(wing=dataclasses.replace(m.wing, aero="dlm", dlm_chordwise_panels=nc,
                                            dlm_spanwise_panels=ns))


@pytest.fixture
def no_aic(monkeypatch):
    """Every AIC path replaced by a counter that fails the test when called: propwhirl's kernel
    of a Mach column (``dlm.Kernel``) and PanelAero's own."""
    from panelaero import DLM

    calls = []

    def counted(*args, **kw):
        calls.append(args)
        raise AssertionError("an AIC was computed")

    monkeypatch.setattr(DLM, "calc_Qjj", counted)
    monkeypatch.setattr(DLM, "calc_Ajj", counted)
    monkeypatch.setattr(dlm.Kernel, "__init__", counted)
    return calls


@pytest.mark.parametrize("method", ["auto", "pk"])
def test_panels_at_the_maximum_refused_beyond_the_memory_limit(monkeypatch, no_aic, method):
    monkeypatch.setenv(limits.MEMORY_ENV, "4GiB")
    m = patil(20, 100)                                 # a valid model: the limit is the machine's
    with pytest.raises(InputError) as err:
        analyse(m, speeds=np.arange(20.0, 36.0, 4.0), method=method)
    assert str(err.value) == MESSAGE
    assert no_aic == []
    with pytest.raises(InputError, match="^dlm_chordwise_panels x dlm_spanwise_panels = 20 x 100"):
        dlm.DlmAerodynamics(m.wing)                    # the panels themselves: not built


def test_the_counts_named_fit_and_one_more_panel_does_not(monkeypatch):
    monkeypatch.setenv(limits.MEMORY_ENV, "4GiB")
    limit = limits.memory_limit()
    assert limits.aic_bytes(1448) <= limit < limits.aic_bytes(1449)
    for nc, ns in ((20, 72), (14, 100)):
        limits.check_panels(nc, ns)
    with pytest.raises(InputError, match=r"= 20 x 73 = 1,460 panels is invalid: .* at most "
                                         r"1,448 panels fit, e.g. 20 x 72 or 19 x 73$"):
        limits.check_panels(20, 73)


def test_a_small_limit_names_what_fits(monkeypatch):
    monkeypatch.setenv(limits.MEMORY_ENV, "64MiB")
    with pytest.raises(InputError, match=r"= 8 x 29 = 232 panels is invalid: each AIC needs "
                                         r"≈ 105 MiB \(limit 64.0 MiB, .*at most 181 panels fit, "
                                         r"e.g. 8 x 22 or 6 x 29$"):
        dlm_mesh.check_memory(patil(8, 29).wing)


def test_the_estimate_bounds_the_measured_memory(monkeypatch):
    """tracemalloc's peak (120 panels, 240 mirrored): PanelAero's whole kernel at k > 0 (the
    non-planar path, ``dlm.Kernel(planar=False)``) within the estimate and above 80 % of it
    (measured 481 of 512 bytes per entry); the planar path over four Mach columns (the kernels
    kept, a new one built, its AICs) within it too (measured 331)."""
    monkeypatch.delenv("PROPWHIRL_DLM_CACHE", raising=False)
    a = dlm.DlmAerodynamics(patil(4, 30).wing)
    a.aic(0.3, 0.0)                                    # PanelAero imported, k = 0 warmed
    need = limits.aic_bytes(a.mesh.n)
    whole = dlm.Kernel(a.grid, a.mesh.n, 0.3, planar=False)
    tracemalloc.start()
    try:
        whole.aic(0.4 / a.b_ref)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert 0.8 * need < peak <= need
    del whole
    tracemalloc.start()
    try:
        for mach in (0.2, 0.4, 0.5, 0.6):
            a.aic(mach, 0.4)
            a.aic(mach, 0.0)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert peak <= need
