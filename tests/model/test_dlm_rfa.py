"""Roger's rational-function state space of the doublet-lattice loads (issue 23, item 3b):
propwhirl.model.aerodynamics.dlm_rfa against the DLM p-k it approximates."""
import dataclasses

import numpy as np
import pytest

pytest.importorskip("panelaero")

from propwhirl.analysis.pk import pk_sweep  # noqa: E402
from propwhirl.cases.ch07_patil import patil_model  # noqa: E402
from propwhirl.engine import analyse as engine_analyse  # noqa: E402
from propwhirl.model.aerodynamics import dlm_rfa  # noqa: E402
from propwhirl.validate import InputError  # noqa: E402

SPEEDS = np.arange(20.0, 36.0, 4.0)
KS = np.concatenate([[0.0], np.geomspace(0.02, 2.0, 16)])


@pytest.fixture(scope="module")
def patil():
    m = patil_model(10)
    return m.with_(wing=dataclasses.replace(m.wing, aero="dlm", dlm_chordwise_panels=4,
                                            dlm_spanwise_panels=16))


def test_fit_reproduces_the_tables(patil):
    fit = dlm_rfa.roger_fit(patil, 0.1, KS)
    assert fit.error < 0.02
    from propwhirl.model.structure.assembly import free_dofs
    from propwhirl.model.aerodynamics.dlm import dlm_aerodynamics
    keep = free_dofs(patil.wing.n_nodes)
    Q = dlm_aerodynamics(patil.wing).gaf(0.1, 0.33)[np.ix_(keep, keep)]
    assert np.abs(fit(0.33) - Q).max() < 0.02 * np.abs(Q).max()     # between the fitted k


def test_state_space_flutter_is_the_dlm_pk_flutter(patil):
    """The engine on the Roger state matrix (matched Mach of the p-k flutter speed) finds the
    DLM p-k flutter within 1.5 % (27.05 vs 27.21 m/s)."""
    pk = pk_sweep(patil, SPEEDS).critical
    fit = dlm_rfa.roger_fit(patil, pk.V / patil.flight.speed_of_sound, KS)
    n = patil.dof_map().n_dof
    size = 2 * n + fit.lags.size * fit.A.shape[-1]
    disp = np.zeros(size, bool)
    disp[:n] = True
    an = engine_analyse(lambda V: dlm_rfa.state_matrix(patil, fit, V), SPEEDS, displacement=disp)
    flutter = [p for p in an.criticals.points if p.kind == "flutter" and p.direction == "onset"]
    assert len(flutter) == 1
    assert flutter[0].V == pytest.approx(pk.V, rel=0.015)
    assert flutter[0].frequency_hz == pytest.approx(pk.frequency_hz, rel=0.02)


def test_lag_states_follow_the_wing_rates(patil):
    fit = dlm_rfa.roger_fit(patil, 0.1, KS, lags=(0.3, 1.1))
    A = dlm_rfa.state_matrix(patil, fit, [25.0])[0]
    n, nw = patil.dof_map().n_dof, fit.A.shape[-1]
    assert A.shape == (2 * n + 2 * nw,) * 2
    x2 = slice(2 * n + nw, 2 * n + 2 * nw)
    assert np.array_equal(A[x2, n:n + nw], np.eye(nw))
    assert np.allclose(np.diag(A[x2, x2]), -(25.0 / fit.b_ref) * 1.1)


def test_bad_arguments_are_refused_before_any_work(patil):
    with pytest.raises(InputError, match="lags = .* is invalid: must be distinct"):
        dlm_rfa.roger_fit(patil, 0.1, KS, lags=(0.5, 0.5))
    with pytest.raises(InputError, match="lags"):
        dlm_rfa.roger_fit(patil, 0.1, KS, lags=(-0.5,))
    with pytest.raises(InputError, match="the fit needs at least 7"):
        dlm_rfa.roger_fit(patil, 0.1, [0.0, 0.1, 0.2])
    with pytest.raises(InputError, match="Mach = 0.95 is invalid"):
        dlm_rfa.roger_fit(patil, 0.95, KS)
    with pytest.raises(InputError, match="needs a wing with aero = 'dlm'"):
        dlm_rfa.roger_fit(patil_model(10), 0.1, KS)
