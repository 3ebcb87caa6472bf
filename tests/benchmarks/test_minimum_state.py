"""Karpel's minimum-state approximation of the doublet-lattice GAFs (issue 23, item 3b):
benchmarks/minimum_state.py (beside its benchmark since issue 38, item 6) against an exact minimum-state table, Roger's fit and the
DLM p-k flutter it approximates."""
import dataclasses
import importlib.util
import sys
from pathlib import Path

import numpy as np
import pytest

from propwhirl.validate import InputError

_SPEC = importlib.util.spec_from_file_location(
    "minimum_state", Path(__file__).resolve().parents[2] / "benchmarks" / "minimum_state.py")
ms = importlib.util.module_from_spec(_SPEC)
sys.modules.setdefault("minimum_state", ms)          # its dataclasses look their module up
_SPEC.loader.exec_module(ms)

KS = np.concatenate([[0.0], np.geomspace(0.02, 2.0, 16)])    # synthetic tables only


def test_an_exact_minimum_state_table_is_recovered():
    """Q built from known A, D, E with 3 lag states: the fit with the same lags reproduces it
    to rounding (the alternating least squares has the exact solution as its fixed point)."""
    rng = np.random.default_rng(3)
    n, lags = 5, np.array([0.15, 0.6, 1.8])
    A = rng.normal(size=(3, n, n))
    D, E = rng.normal(size=(n, 3)), rng.normal(size=(3, n))
    Q = ms._evaluate(A, D, E, lags, KS)
    f = ms.fit(Q, KS, lags, iterations=500, rtol=0.0)
    assert f.error < 1e-6
    assert np.allclose(f(0.7), ms._evaluate(A, D, E, lags, np.array([0.7]))[0], atol=1e-6)


def test_bad_arguments_are_one_line_errors():
    Q = np.zeros((KS.size, 3, 3), complex) + 1.0
    with pytest.raises(InputError, match="lags = .* is invalid: must be distinct"):
        ms.fit(Q, KS, (0.5, 0.5))
    with pytest.raises(InputError, match="lags"):
        ms.fit(Q, KS, (-0.5,))
    with pytest.raises(InputError, match="Q has shape"):
        ms.fit(Q[:, :2], KS, (0.5,))
    with pytest.raises(InputError, match="at least 4"):
        ms.fit(Q[:3], KS[:3], (0.5,))


@pytest.fixture(scope="module")
def patil():
    pytest.importorskip("panelaero")
    from propwhirl.cases.ch07_patil import patil_model

    m = patil_model(10)
    return m.with_(wing=dataclasses.replace(m.wing, aero="dlm", dlm_chordwise_panels=4,
                                            dlm_spanwise_panels=16, dlm_mach=0.1))


def test_few_shared_lag_states_give_the_pk_flutter(patil):
    """Patil's wing (10 elements, 4 × 16 panels, Mach 0.1): 12 lag states in all (Roger's
    has 4 per free wing DOF, 120) fit Q within 1.5 % (1.04 %), and the engine on their state
    space finds the DLM p-k flutter within 1.5 % (26.98 against 27.27 m/s; Roger's 26.95)
    and Roger's state space's within 1 %.  With 6 or 8 lag states: 27.35 and 27.59 m/s
    (docs/validation.md); with 2, the fit is worse."""
    from propwhirl.analysis.pk import pk_sweep
    from propwhirl.engine import analyse as engine_analyse
    from propwhirl.model.aerodynamics import dlm_rfa
    from propwhirl.model.aerodynamics.dlm import DlmTables

    tables = DlmTables()                  # one set of AICs for the p-k and the fits
    speeds = np.arange(20.0, 36.0, 4.0)
    pk = pk_sweep(patil, speeds, tables=tables).critical
    f = ms.fit_model(patil, np.geomspace(0.05, 3.0, 12), tables=tables)
    assert f.error < 0.015
    assert ms.fit_model(patil, (0.2, 1.0), tables=tables).error > f.error
    n = patil.dof_map().n_dof
    A = ms.state_matrix(patil, f, [25.0])[0]
    assert A.shape == (2 * n + 12,) * 2
    assert np.array_equal(A[2 * n:, n:n + f.D.shape[0]], f.E)
    assert np.allclose(np.diag(A[2 * n:, 2 * n:]), -(25.0 / f.b_ref) * f.lags)

    def flutter(matrix_fn, size):
        disp = np.zeros(size, bool)
        disp[:n] = True
        an = engine_analyse(matrix_fn, speeds, displacement=disp)
        out = [p for p in an.criticals.points if p.kind == "flutter" and p.direction == "onset"]
        assert len(out) == 1
        return out[0]

    mine = flutter(lambda V: ms.state_matrix(patil, f, V), 2 * n + 12)
    roger_fit = dlm_rfa.column_fit(tables.aero(patil.wing), 0.1)
    roger = flutter(lambda V: dlm_rfa.state_matrix(patil, roger_fit, V), 2 * n + 4 * 30)
    assert mine.V == pytest.approx(pk.V, rel=0.015)
    assert mine.frequency_hz == pytest.approx(pk.frequency_hz, rel=0.02)
    assert mine.V == pytest.approx(roger.V, rel=0.01)


def test_a_matched_wing_needs_a_mach(patil):
    matched = patil.with_(wing=dataclasses.replace(patil.wing, dlm_mach="speed"))
    with pytest.raises(InputError, match="one Mach"):
        ms.fit_model(matched, (0.5,))
