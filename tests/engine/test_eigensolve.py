"""Eigen helpers, MAC (eq. 5.14), inverse iteration and its residual rules."""
from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st_

from propwhirl.engine import eigen, eigenvalues, mac, tracked_eigenvalue
from propwhirl.engine.eigensolve import _inverse_iteration

from helpers.engine_systems import badly_scaled, section


def test_mac_and_eigen_helpers():
    rng = np.random.default_rng(3)
    phi = rng.standard_normal(5) + 1j * rng.standard_normal(5)
    assert mac(phi, (2 - 3j) * phi) == pytest.approx(1.0)
    assert mac(phi, np.zeros(5)) == 0.0
    A = rng.standard_normal((4, 6, 6))
    lam, X = eigen(A)
    np.testing.assert_allclose(A @ X, X * lam[:, None, :], atol=1e-10)
    np.testing.assert_allclose(np.sort_complex(eigenvalues(A)), np.sort_complex(lam),
                               atol=1e-10)
    # tracked_eigenvalue: one mode by inverse iteration, same as the full solution
    fn, _, _ = section()
    full = np.linalg.eig(fn(np.array([15.0]))[0])
    j = int(np.argmax(full[0].imag))
    lam1, x1 = tracked_eigenvalue(fn, 15.0, full[0][j] * 1.01, full[1][:, j], n_dof=2)
    assert lam1 == pytest.approx(full[0][j], rel=1e-12)
    assert mac(x1, full[1][:, j]) == pytest.approx(1.0)


@given(re=st_.floats(-5, 5), im=st_.floats(-5, 5))
def test_mac_is_phase_and_scale_invariant(re, im):
    c = complex(re, im)
    phi = np.array([1.0 + 2j, -0.5j, 3.0])
    if abs(c) > 1e-6:
        assert mac(phi, c * phi) == pytest.approx(1.0)
    assert 0.0 <= mac(phi, np.array([c, 1.0, -1j])) <= 1.0 + 1e-12


def test_inverse_iteration_tolerance_scales_with_the_eigenvalue():
    """‖A‖₁ ≈ 1e10 here, so a tolerance on ‖A‖ ("converged" below 1e-13 ‖A‖, acceptable
    below 1e-8 ‖A‖ ≈ 100) accepts anything for an eigenvalue of size 50.  The residual must be
    small relative to |λ| or at the rounding floor of A x (eps ‖|A||x|‖): one step from a
    poor start is not accepted, a converged run is accurate."""
    A = badly_scaled()
    normA = np.linalg.norm(A, 1)
    exact = np.linalg.eigvals(A)
    pair = exact[np.abs(exact - 50) < 1]
    x0 = np.random.default_rng(0).standard_normal(4) + 0j
    lam, x, ok = _inverse_iteration(A, 50.3 + 0.2j, x0, maxit=1)
    res = np.linalg.norm(A @ x - lam * x)
    assert res <= 1e-8 * normA                 # the old rule would have accepted this
    floor = np.finfo(float).eps * np.linalg.norm(np.abs(A) @ np.abs(x))
    assert res > max(1e-8 * abs(lam), 1e3 * floor) and not ok
    err1 = np.min(np.abs(pair - lam))
    lam, x, ok = _inverse_iteration(A, 50.3 + 0.2j, x0)
    res = np.linalg.norm(A @ x - lam * x)
    floor = np.finfo(float).eps * np.linalg.norm(np.abs(A) @ np.abs(x))
    assert ok and res <= 64 * floor            # at the rounding floor of A x (~1e-5 here)
    err = np.min(np.abs(pair - lam))
    assert err <= 1e-5 * abs(lam) and err < 1e-2 * err1
    # through the public API, with the shape of the pair as the start
    fn = lambda V: np.broadcast_to(A, (np.size(V), 4, 4)).copy()  # noqa: E731
    w, X = np.linalg.eig(A)
    j = int(np.argmin(np.abs(w - (50 + 0.1j))))
    lam1, _ = tracked_eigenvalue(fn, 1.0, 50.3 + 0.2j, X[:, j])
    assert abs(lam1 - w[j]) <= 1e-5 * abs(w[j])
