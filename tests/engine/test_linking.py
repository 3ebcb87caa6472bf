"""Linking consecutive speeds: crossing, veering, MAC against eigenvalue evidence, real roots."""
from __future__ import annotations

import numpy as np
import pytest

from propwhirl.engine import TrackingOptions, analyse, mac, sweep

from helpers.engine_systems import lag_family, oscillators, random_family, rotating_shapes


def _consecutive_mac(sw, k):
    X = sw.eigenvectors[:, sw.displacement, k]
    return np.array([mac(a, b) for a, b in zip(X[:-1], X[1:])])


def test_true_crossing_keeps_shapes():
    sw = sweep(oscillators(kc=0.0), np.arange(10.0, 251.0, 40.0), n_dof=2)
    e = np.eye(2)
    for k, dof in ((0, 0), (1, 1)):
        macs = [mac(sw.eigenvectors[t, :2, k], e[dof]) for t in range(sw.V.size)]
        assert min(macs) > 0.999
    f = sw.frequency_hz
    assert f[0, 0] < f[0, 1] and f[-1, 0] > f[-1, 1]         # the frequencies did cross
    zeta = sw.damping_ratio
    assert np.all(zeta[:, 0] * 2 * np.abs(sw.eigenvalues[:, 0]) == pytest.approx(0.1))
    assert sw.unresolved == ()


def test_mac_decides_when_eigenvalue_evidence_is_tied():
    """Decoupled modes λ1 = −0.1 + i(5 + V), λ2 = −0.1 + i(15 − V), step 1 → 9 symmetric about
    the crossing at 5: the trapezoidal prediction fits both matches exactly and the wrong match
    is even the nearer eigenvalue, so only the MAC keeps the identities."""
    def fn(V):
        V = np.atleast_1d(V)
        A = np.zeros((V.size, 4, 4))
        for j, w in ((0, 5 + V), (2, 15 - V)):
            A[:, j, j] = A[:, j + 1, j + 1] = -0.1
            A[:, j, j + 1], A[:, j + 1, j] = w, -w
        return A
    for opts in (TrackingOptions(min_step=100.0), TrackingOptions()):
        sw = sweep(fn, [1.0, 9.0], options=opts)
        for k in (0, 1):
            assert mac(sw.eigenvectors[0, :, k], sw.eigenvectors[-1, :, k]) > 0.999
        np.testing.assert_allclose(sw.eigenvalues[-1, :2].imag, [14.0, 6.0])


def test_weak_coupling_passes_without_veering():
    """Coupling below half the damping difference: frequencies cross, shapes and damping stay.

    (κ ≈ kc/2ω = 0.025 < |Δσ|/2 = 0.05: no exchange; a frequency-sorted tracker would swap.)
    """
    sw = sweep(oscillators(kc=0.5, c1=0.1, c2=0.3), np.arange(10.0, 251.0, 40.0), n_dof=2)
    np.testing.assert_allclose(sw.eigenvalues[:, 0].real, -0.05, atol=0.01)
    np.testing.assert_allclose(sw.eigenvalues[:, 1].real, -0.15, atol=0.01)
    f = sw.frequency_hz
    assert f[0, 0] < f[0, 1] and f[-1, 0] > f[-1, 1]
    assert min(mac(sw.mode_shape(0, t), [1, 0]) for t in range(sw.V.size)) > 0.9


@pytest.mark.parametrize("kc, c", [(3.0, (0.1, 0.3)), (0.1, (0.2, 0.2)), (0.01, (0.2, 0.2))])
def test_veering_followed_along_its_branch(kc, c):
    """Wide (kc = 3) and narrow veerings (width ≈ 2kc/(dk1/dV) = 0.4 and 0.04 m/s ≪ 40 m/s)."""
    fn = oscillators(kc, *c)
    sw = sweep(fn, np.arange(10.0, 251.0, 40.0), n_dof=2)
    # along a veering the branches never cross: the analytic continuation is frequency order
    w = np.sort(np.abs(np.linalg.eigvals(fn(sw.V)).imag), axis=1)[:, ::2]
    np.testing.assert_allclose(np.abs(sw.eigenvalues[:, :2].imag), w, rtol=1e-12)
    for k in (0, 1):
        assert _consecutive_mac(sw, k).min() > TrackingOptions().mac_min
        # the shapes exchanged through the veering
        assert mac(sw.mode_shape(k, 0), sw.mode_shape(k, -1)) < 0.05
    assert sw.stats["refined"] > 0 and sw.unresolved == ()
    assert sw.stats["eig"] <= 30


def test_veering_on_coarse_grid_is_flagged_not_swapped():
    """A step across a narrow veering is ambiguous (paths approach); with refinement forbidden
    it is reported as unresolved instead of being accepted silently."""
    opts = TrackingOptions(min_step=100.0)
    sw = sweep(oscillators(0.1, 0.2, 0.2), np.array([130.0, 170.0]), n_dof=2, options=opts)
    assert sw.unresolved == ((130.0, 170.0),)


def test_decisive_eigenvalue_evidence_accepts_rotating_shapes():
    """Shapes may change completely between samples while the eigenvalue continuation stays
    unique: accepted without refinement by default, refined when the MAC is always required
    (``decisive_ratio`` 0); the same branches either way."""
    grid = np.arange(1.0, 102.0, 25.0)
    fast = sweep(rotating_shapes, grid, n_dof=2)
    strict = sweep(rotating_shapes, grid, n_dof=2,
                      options=TrackingOptions(decisive_ratio=0.0))
    macs = [mac(fast.mode_shape(0, t), fast.mode_shape(0, t + 1)) for t in range(4)]
    assert min(macs) < 0.8 and fast.stats["refined"] == 0
    assert strict.stats["refined"] > 0
    on_grid = np.isin(strict.V, grid)
    np.testing.assert_allclose(strict.eigenvalues[on_grid], fast.eigenvalues, atol=1e-12)


def test_veering_inside_a_long_step_is_not_taken_for_a_crossing():
    """Random family (seed 639): two modes veer inside the first 14 m/s step while one of them
    has a hump (unstable 7.27–9.35 m/s).  Straight-line predictions and MAC both accept the
    swap of a crossing; the Hermite paths through both samples meet — refined, hump found."""
    fn = random_family(639)
    an = analyse(fn, np.arange(1.0, 60.0, 7.0), n_dof=3, xtol=1e-3)
    on = sorted(p.V for p in an.criticals.points)
    assert np.allclose(on[:2], [7.274, 9.350], atol=0.01)


def test_lag_root_clusters_need_no_refinement():
    """Real roots that stay real with the same sign need no shape identity: a cluster of 20
    lag roots 2 % apart along a 1–101 m/s sweep costs no refinement, and the flutter crossing
    of the oscillator is exact."""
    fn, n = lag_family()
    disp = np.zeros(n, dtype=bool)
    disp[0] = True
    an = analyse(fn, np.arange(1.0, 102.0, 10.0), displacement=disp, xtol=0.01)
    assert an.sweep.stats["refined"] == 0 and an.sweep.unresolved == ()
    lam = np.linalg.eigvals(fn(an.sweep.V))
    np.testing.assert_allclose(np.sort_complex(an.sweep.eigenvalues), np.sort_complex(lam),
                               atol=1e-9)
    (p,) = an.criticals.points
    Vd = np.arange(45.0, 55.0, 1e-3)
    nun = (np.linalg.eigvals(fn(Vd)).real > 0).sum(axis=1)
    V_exact = Vd[np.argmax(nun > 0)]
    assert p.kind == "flutter" and p.direction == "onset" and p.mode == 0
    assert abs(p.V - V_exact) <= 0.01


def _repeated_copies_family(copies: int = 6):
    """A pair that goes unstable at V = 50 m/s (σ = 0.02 (V − 50), ω = 12 rad/s) and
    ``copies`` identical uncoupled oscillators (−0.3 ± (75 + 0.05 V) i: the mounts of equal
    stopped propellers), in a fixed random basis (eigenvectors of the repeated root are then
    arbitrary combinations at every speed, and its dλ/dV from finite differences of A(V)
    differs between the copies by rounding)."""
    n = 2 + 2 * copies
    T = np.eye(n) + 0.3 * np.random.default_rng(5).standard_normal((n, n))
    Ti = np.linalg.inv(T)

    def fn(V):
        V = np.atleast_1d(V)
        D = np.zeros((V.size, n, n))
        s = 0.02 * (V - 50.0)
        D[:, 0, 0] = D[:, 1, 1] = s
        D[:, 0, 1], D[:, 1, 0] = 12.0, -12.0
        for c in range(copies):
            i = 2 + 2 * c
            D[:, i, i] = D[:, i + 1, i + 1] = -0.3
            D[:, i, i + 1], D[:, i + 1, i] = 75.0 + 0.05 * V, -(75.0 + 0.05 * V)
        return T @ D @ Ti

    return fn, n


def test_exactly_repeated_roots_cost_no_refinement():
    """Copies of one uncoupled oscillator keep one eigenvalue at every speed: their "approach"
    inside a step is rounding, not a veering (linking._approach leaves pairs repeated within
    degenerate_tol at both ends out).  Before, every step was refined to the node budget
    (the six stopped propellers of examples/x57_like_folded.toml: 720 nodes)."""
    fn, n = _repeated_copies_family()
    disp = np.ones(n, dtype=bool)
    an = analyse(fn, np.arange(1.0, 102.0, 10.0), displacement=disp, xtol=0.01)
    assert an.sweep.unresolved == ()
    assert an.sweep.stats["nodes"] <= 20, an.sweep.stats      # before: 420, the budget
    (p,) = an.criticals.points
    assert p.kind == "flutter" and abs(p.V - 50.0) <= 0.01
