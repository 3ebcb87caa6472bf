"""model.reduction: the reduced model's roots below the cut-off against the full order."""
import numpy as np
import pytest

from propwhirl.cases.ch09_baseline import baseline_flight, baseline_propeller, baseline_wing
from propwhirl.model.reduction import CUTOFF_FACTOR, modal_basis, reduce
from propwhirl.model.systems import Installation, PropellerWing
from propwhirl.validate import InputError

V = np.array([60.0, 160.0, 260.0, 340.0])


def design(n_el: int, n_prop: int) -> PropellerWing:
    wing = baseline_wing(n_el)
    idx = np.unique(np.round(np.linspace(0, n_el, n_prop + 1)[1:]).astype(int))
    prop = baseline_propeller()
    return PropellerWing(wing, baseline_flight(), tuple(
        Installation(prop, float(wing.node_y[i]), "flexible") for i in idx))


@pytest.fixture(scope="module")
def four():
    m = design(30, 4)
    return m, reduce(m, np.arange(1.0, 351.0, 10.0))


def test_reduced_roots_match_the_full_order_below_30_hz(four):
    """Every full-order oscillatory root of 0.3–30 Hz and every root |λ| < 3 1/s has a reduced
    root within 1e-3 relative (measured: ≤ 7e-5)."""
    m, R = four
    lf = np.linalg.eigvals(m.state_matrix(V))
    lr = np.linalg.eigvals(R.state_matrix(V))
    for t in range(V.size):
        sel = ((lf[t].imag > 2 * np.pi * 0.3) & (lf[t].imag < 2 * np.pi * 30)) | (
            np.abs(lf[t]) < 3)
        assert sel.sum() >= 6
        err = [np.min(np.abs(lr[t] - lam)) / max(abs(lam), 1.0) for lam in lf[t][sel]]
        assert max(err) < 1e-3, (V[t], max(err))
    assert R.n_states < m.state_matrix(V[:1]).shape[-1]


def test_cutoff_is_the_factor_times_the_reference_frequency(four):
    m, R = four
    b = R.basis
    assert b.cutoff_hz == pytest.approx(CUTOFF_FACTOR * b.reference_hz)
    assert b.n_modes == int(np.sum(b.in_vacuo_hz <= b.cutoff_hz))
    # the propeller mounts (7 Hz) are below the reference; every kept Ritz vector M-orthonormal
    assert b.reference_hz >= 7.0
    quiet = m.with_(rotating=False).without_aerodynamics().second_order_blocks(V[:1]).dense()
    P = R.dof_basis
    np.testing.assert_allclose(P.T @ quiet.S1[0] @ P, np.eye(b.r), atol=1e-8)
    np.testing.assert_allclose(b.Q.T @ b.Q, np.eye(b.L), atol=1e-10)


def test_a_lower_cutoff_keeps_fewer_modes_and_an_explicit_one_is_checked():
    m = design(20, 2)
    grid = np.arange(1.0, 351.0, 10.0)
    lo, hi = modal_basis(m, grid, factor=1.5), modal_basis(m, grid, factor=4.0)
    assert lo.n_modes < hi.n_modes
    assert modal_basis(m, grid, cutoff_hz=30.0).cutoff_hz == 30.0
    with pytest.raises(InputError, match="cutoff_hz"):
        modal_basis(m, grid, cutoff_hz=-1.0)


def test_lift_maps_the_reduced_state_to_the_full_state(four):
    m, R = four
    L = R.lift
    n_full = m.state_matrix(V[:1]).shape[-1]
    assert L.shape == (n_full, R.n_states)
    r = R.basis.r
    z = np.zeros(R.n_states)
    z[0] = 1.0
    x = L @ z
    nq = len(m.dof_map().q_labels)
    np.testing.assert_allclose(x[:nq], R.dof_basis[:, 0])
    assert not x[nq:].any()
    assert R.displacement.sum() == r
