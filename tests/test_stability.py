"""Stability engine (thesis chapter 5) on toy systems with independently known answers.

Toy systems are built from M, C, K families (eq. 5.2–5.4):
* a 2-DOF typical section with quasi-steady aero stiffness/damping — flutter checked against the
  Routh–Hurwitz boundary of its characteristic quartic, divergence against det K(V) = 0;
* a decoupled oscillator whose damping c(V) dips below zero — a hump with analytic crossings
  and analytic benignity;
* two oscillators whose frequencies cross (decoupled) or veer (coupled);
* the gyroscopic propeller of eq. (6.8) for the whirl sense;
* random 3-DOF aero-like families checked against a dense brute-force eigenvalue sweep.
"""
from __future__ import annotations

import json

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st_
from numpy.polynomial import polynomial as P
from scipy.optimize import brentq

from propwhirl.analysis.whirl import (content, dominant, orbit_signed_area,
                                      rotation_sign_from_gyroscopic, whirl_sense)
from propwhirl.engine import (Analysis, Sweep, TimeResponse, TrackingOptions, analyse,
                              critical_points, eigen, eigenvalues, mac, sweep, time_response,
                              tracked_eigenvalue)
from propwhirl.engine.eigensolve import _inverse_iteration
from propwhirl.model.statespace import second_order_labels, state_matrix_from_mck
from propwhirl.validate import InputError


# ----------------------------------------------------------------------------------------------
# toy systems
# ----------------------------------------------------------------------------------------------
def section(x_alpha=0.2, Pq=0.05, e=0.4, zeta=0.02, wh=4.0, wa=10.0, r2=0.25):
    """Typical section (h down, α nose up): lift L = Pq V² (α + ḣ/V) at e ahead of the EA."""
    m, S, Ia = 1.0, x_alpha, r2
    kh, ka = m * wh**2, Ia * wa**2

    def mck(V):
        V = np.atleast_1d(np.asarray(V, dtype=float))
        T = V.size
        M = np.broadcast_to(np.array([[m, S], [S, Ia]]), (T, 2, 2))
        q = Pq * V**2
        K = np.zeros((T, 2, 2))
        K[:, 0, 0], K[:, 0, 1], K[:, 1, 1] = kh, q, ka - e * q
        C = np.zeros((T, 2, 2))
        C[:, 0, 0] = 2 * zeta * m * wh + Pq * V
        C[:, 1, 1] = 2 * zeta * Ia * wa
        C[:, 1, 0] = -e * Pq * V
        return M, C, K

    def fn(V):
        M, C, K = mck(V)
        return state_matrix_from_mck(M, C, K, V)

    return fn, mck, np.sqrt(ka / (Pq * e))


def routh_hurwitz_flutter(mck, lo, hi):
    """First zero of the Hurwitz determinant Δ3 of det(λ²M + λC + K) on [lo, hi] and ω there."""
    def coeffs(V):
        M, C, K = (x[0] for x in mck(V))
        p = [[np.array([K[i, j], C[i, j], M[i, j]]) for j in range(2)] for i in range(2)]
        return P.polysub(P.polymul(p[0][0], p[1][1]), P.polymul(p[0][1], p[1][0]))

    def delta3(V):
        a0, a1, a2, a3, a4 = coeffs(V)
        return a3 * a2 * a1 - a4 * a1**2 - a3**2 * a0

    Vg = np.linspace(lo, hi, 400)
    d = np.array([delta3(v) for v in Vg])
    i = int(np.nonzero(np.sign(d[1:]) != np.sign(d[:-1]))[0][0])
    Vf = brentq(delta3, Vg[i], Vg[i + 1], xtol=1e-12)
    a0, a1, a2, a3, a4 = coeffs(Vf)
    return Vf, np.sqrt(a1 / a3)


def oscillators(kc, c1=0.1, c2=0.3):
    """Two unit masses, k1(V) = 25(1 + V/50) rising through k2 = 100 at V = 150, coupling kc."""
    def fn(V):
        V = np.atleast_1d(np.asarray(V, dtype=float))
        T = V.size
        K = np.zeros((T, 2, 2))
        K[:, 0, 0] = 25 * (1 + V / 50) + kc
        K[:, 1, 1] = 100 + kc
        K[:, 0, 1] = K[:, 1, 0] = -kc
        C = np.broadcast_to(np.diag([c1, c2]), (T, 2, 2))
        return state_matrix_from_mck(np.broadcast_to(np.eye(2), (T, 2, 2)), C, K, V)
    return fn


HUMP = dict(c0=0.2, beta=0.3, gamma=0.1 / 9, Vc=50.3)   # c < 0 for |V − Vc| < 3


def hump_system(c0, beta, gamma, Vc):
    def fn(V):
        V = np.atleast_1d(np.asarray(V, dtype=float))
        T = V.size
        C = np.zeros((T, 2, 2))
        C[:, 0, 0] = c0 + gamma * (V - Vc) ** 2 - beta
        C[:, 1, 1] = 0.5
        K = np.broadcast_to(np.diag([100.0, 400.0]), (T, 2, 2))
        return state_matrix_from_mck(np.broadcast_to(np.eye(2), (T, 2, 2)), C, K, V)
    return fn


def propeller(I_X=0.5, I_Y=2.0, I_Z=2.5, K_t=4000.0, K_p=1500.0, c=0.5):
    """Eq. (6.8) without aerodynamics; the sweep variable plays the role of Ω [rad/s]."""
    def fn(W):
        W = np.atleast_1d(np.asarray(W, dtype=float))
        T = W.size
        M = np.broadcast_to(np.diag([I_Y, I_Z]), (T, 2, 2))
        C = np.zeros((T, 2, 2))
        C[:, 0, 0] = C[:, 1, 1] = c
        C[:, 0, 1] = I_X * W
        C[:, 1, 0] = -I_X * W
        K = np.broadcast_to(np.diag([K_t, K_p]), (T, 2, 2))
        return state_matrix_from_mck(M, C, K, W)
    return fn


# ----------------------------------------------------------------------------------------------
# (a) flutter, (b) divergence, (f) refinement
# ----------------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def section_analysis():
    fn, mck, VD = section()
    an = analyse(fn, np.arange(1.0, 61.0, 5.0), n_dof=2,
                 state_labels=second_order_labels(["h", "alpha"]), xtol=1e-3)
    return fn, mck, VD, an


def test_flutter_matches_routh_hurwitz(section_analysis):
    fn, mck, _, an = section_analysis
    V_rh, w_rh = routh_hurwitz_flutter(mck, 1.0, 30.0)
    flutter = [p for p in an.criticals.points if p.kind == "flutter"]
    assert len(flutter) == 1
    p = flutter[0]
    assert p.direction == "onset"
    assert abs(p.V - V_rh) < 1e-3
    assert p.bracket[1] - p.bracket[0] <= 1e-3
    assert abs(2 * np.pi * p.frequency_hz - w_rh) < 1e-5 * w_rh
    assert an.criticals.critical is p
    assert "flutter" in an.criticals.summary() and f"{V_rh:.2f}" in an.criticals.summary()
    # benignity (5.13) against a brute-force central difference on full eigenvalue sets
    h = 0.01
    lam = np.linalg.eigvals(fn(np.array([p.V - h, p.V + h])))
    crit = lam[np.arange(2), np.argmax(np.where(lam.imag > 0, lam.real, -np.inf), axis=1)]
    dz = np.diff(-crit.real / np.abs(crit))[0] / (2 * h)
    assert p.dzeta_dV < 0 and abs(p.dzeta_dV - dz) < 1e-4 * abs(dz)
    assert p.benignity == pytest.approx(1 / p.dzeta_dV)


def test_divergence_matches_det_K(section_analysis):
    fn, mck, VD, an = section_analysis
    div = [p for p in an.criticals.points if p.kind == "divergence"]
    assert len(div) == 1
    p = div[0]
    assert p.direction == "onset" and abs(p.V - VD) < 1e-3
    assert p.frequency_hz == 0 and p.benignity is None and abs(p.eigenvalue) < 1e-6
    # det K(V) changes sign inside the reported bracket
    dets = [np.linalg.det(mck(v)[2][0]) for v in p.bracket]
    assert dets[0] * dets[1] < 0
    # the pair split into two real roots; the physical mode id kept the larger (crossing) root
    sw = an.sweep
    n_phys = int(sw.physical[0].sum())
    assert p.mode < n_phys and sw.eigenvalues[0, p.mode].imag > 0
    t = np.searchsorted(sw.V, p.V)
    partner = sw.partner[p.mode]
    assert sw.eigenvalues[t, p.mode].imag == 0 and sw.eigenvalues[t, partner].imag == 0
    assert sw.eigenvalues[t, p.mode].real > sw.eigenvalues[t, partner].real
    assert sw.physical[t, partner] and sw.mode_labels[partner] == f"mode {p.mode}'"


def test_divergence_alone_is_critical():
    fn, _, VD = section(x_alpha=-0.2, wa=6.0, zeta=0.05)
    an = analyse(fn, np.arange(1.0, 61.0, 5.0), n_dof=2, xtol=1e-3)
    c = an.criticals.critical
    assert c.kind == "divergence" and abs(c.V - VD) < 1e-3
    assert "divergence" in an.criticals.summary()


def test_refinement_to_one_hundredth(section_analysis):
    fn, mck, VD, _ = section_analysis
    V_rh, _ = routh_hurwitz_flutter(mck, 1.0, 30.0)
    an = analyse(fn, np.arange(1.0, 61.0, 10.0), n_dof=2, xtol=0.01)
    got = sorted(p.V for p in an.criticals.points)
    assert np.allclose(got, sorted([V_rh, VD]), atol=0.01, rtol=0)
    for p in an.criticals.points:
        assert p.bracket[1] - p.bracket[0] <= 0.01 + 1e-12
        assert p.bracket[0] <= p.V <= p.bracket[1]
    # eigenvalue-only: no full eigendecomposition needed in the refinement, and few solves
    stats = an.criticals.stats
    assert stats.get("fallback_eig", 0) == 0
    assert stats["state_matrix_calls"] <= 12 * len(an.criticals.points)


# ----------------------------------------------------------------------------------------------
# (c) hump mode
# ----------------------------------------------------------------------------------------------
def test_hump_mode_both_crossings_and_benignity():
    fn = hump_system(**HUMP)
    grid = np.arange(1.0, 102.0, 20.0)        # 41 and 61 bracket the hump at 47.3 … 53.3
    an = analyse(fn, grid, n_dof=2, xtol=1e-3)
    half = np.sqrt((HUMP["beta"] - HUMP["c0"]) / HUMP["gamma"])
    assert len(an.criticals.humps) == 1
    hump = an.criticals.humps[0]
    assert abs(hump.V_onset - (HUMP["Vc"] - half)) < 1e-3
    assert abs(hump.V_recovery - (HUMP["Vc"] + half)) < 1e-3
    assert hump.kind == "flutter"
    assert an.criticals.critical.V == pytest.approx(hump.V_onset)
    # ζ = c/(2√k) → dζ/dV = γ (V − Vc)/√k: benignity ∓ √k/(γ·half) = ∓300 m/s
    on, rec = (p for p in an.criticals.points if p.mode == hump.mode)
    expected = np.sqrt(100.0) / (HUMP["gamma"] * half)
    assert on.benignity == pytest.approx(-expected, rel=1e-5)
    assert rec.benignity == pytest.approx(expected, rel=1e-5)
    assert on.frequency_hz == pytest.approx(10 / (2 * np.pi), rel=1e-9)
    assert an.sweep.stats.get("hump_refined", 0) >= 1
    # without the Hermite check the coarse grid never sees the hump
    blind = analyse(fn, grid, n_dof=2, options=TrackingOptions(hump_check=False))
    assert blind.criticals.points == ()


# ----------------------------------------------------------------------------------------------
# (d) veering and crossing
# ----------------------------------------------------------------------------------------------
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


# ----------------------------------------------------------------------------------------------
# (e) whirl sense
# ----------------------------------------------------------------------------------------------
def _shoelace(theta_hat, psi_hat, n=2001):
    t = np.linspace(0, 2 * np.pi, n)
    th = np.real(theta_hat * np.exp(1j * t))
    ps = np.real(psi_hat * np.exp(1j * t))
    return 0.5 * np.sum(th[:-1] * ps[1:] - th[1:] * ps[:-1])


@pytest.mark.parametrize("theta_hat, psi_hat", [
    (1.0, -1j), (1.0, 1j),                                   # circles
    (1.0, 0.3 * np.exp(-1.2j)), (0.7j, 1.4 * np.exp(0.4j)),  # ellipses, phase lag ≠ 90°
])
@pytest.mark.parametrize("rotation", [1, -1])
def test_whirl_sense_from_orbit(theta_hat, psi_hat, rotation):
    area = _shoelace(theta_hat, psi_hat)
    assert orbit_signed_area(theta_hat, psi_hat) == pytest.approx(area, rel=1e-5)
    ccw = area > 0
    expected = "forward" if ccw == (rotation > 0) else "backward"
    assert whirl_sense(theta_hat, psi_hat, rotation) == expected
    # the conjugate eigenvalue (ω < 0) runs the orbit the other way round
    other = "backward" if expected == "forward" else "forward"
    assert whirl_sense(theta_hat, psi_hat, rotation, eigenvalue=-0.1 - 3j) == other


def test_whirl_sense_planar_and_bad_sign():
    assert whirl_sense(1.0, 0.5, 1) == "planar"
    assert whirl_sense(1.0, 0.5j, 1, eigenvalue=-2.0 + 0j) == "planar"
    with pytest.raises(InputError, match="rotation_sign"):
        whirl_sense(1.0, 1j, 0)
    with pytest.raises(InputError, match="g_theta_psi"):
        rotation_sign_from_gyroscopic(0.0)


@pytest.mark.parametrize("omega", [60.0, -60.0])
def test_gyroscopic_propeller_backward_is_lower(omega):
    """Eq. (6.8), unequal stiffness (elliptical orbits): the lower mode whirls backward.

    §9.2: for the thesis' counter-clockwise rotation (Ω > 0) the backward orbit is clockwise
    with ψ on the Y-axis and θ on the X-axis.
    """
    lam, X = eigen(propeller()(np.array([omega])))
    keep = lam[0].imag > 0
    lam, X = lam[0][keep], X[0][:, keep]
    order = np.argsort(lam.imag)
    rot = rotation_sign_from_gyroscopic(0.5 * omega)       # I_X Ω
    assert [whirl_sense(X[0, j], X[1, j], rot, eigenvalue=lam[j]) for j in order] == \
        ["backward", "forward"]
    low = order[0]
    assert not 0.95 < abs(X[0, low]) / abs(X[1, low]) < 1.05                # elliptical
    assert np.sign(orbit_signed_area(X[0, low], X[1, low])) == -np.sign(omega)


def test_sweep_mode_labels_from_whirl_sense():
    sw = sweep(propeller(), np.linspace(5.0, 80.0, 6), n_dof=2)
    sw = sw.relabel(lambda lam, x: whirl_sense(x[0], x[1], 1, lam) + " whirl")
    assert sw.mode_labels[:2] == ("backward whirl", "forward whirl")
    # along Ω the backward frequency falls and the forward one rises (§9.2, Figure 9.16)
    f = sw.frequency_hz
    assert np.all(np.diff(f[:, 0]) < 0) and np.all(np.diff(f[:, 1]) > 0)
    senses = {whirl_sense(sw.eigenvectors[t, 0, k], sw.eigenvectors[t, 1, k], 1,
                             sw.eigenvalues[t, k]) for t in range(sw.V.size) for k in (0, 1)}
    assert senses == {"backward", "forward"}


def test_content_and_dominant():
    x = np.array([3.0, 4.0j, 0.0, 1.0])
    c = content(x, {"bending": [0, 1], "torsion": [3]})
    assert c == pytest.approx({"bending": 25 / 26, "torsion": 1 / 26})
    assert dominant(x, {"bending": [0, 1], "torsion": np.array([0, 0, 0, 1], bool)}) == \
        "bending"
    many = content(np.stack([x, x[::-1]], axis=1), {"a": [0], "b": [3]})
    np.testing.assert_allclose(many["a"], [0.9, 0.1])
    with pytest.raises(InputError):
        content(x, {"a": [7]})


# ----------------------------------------------------------------------------------------------
# random aero-like families against a dense brute-force sweep
# ----------------------------------------------------------------------------------------------
def random_family(seed, N=3):
    rng = np.random.default_rng(seed)
    A0 = rng.standard_normal((N, N))
    M = np.eye(N) + 0.1 * (A0 @ A0.T)
    B = rng.standard_normal((N, N))
    K0 = np.diag(np.sort(rng.uniform(2, 20, N)) ** 2) + 0.5 * (B + B.T)
    K1 = rng.standard_normal((N, N)) * rng.uniform(0.02, 0.2)
    C0 = np.diag(rng.uniform(0.05, 0.5, N))
    C1 = rng.standard_normal((N, N)) * 0.01

    def fn(V):
        V = np.atleast_1d(V)
        K = K0[None] + (V**2)[:, None, None] * K1[None]
        C = C0[None] + V[:, None, None] * C1[None]
        return state_matrix_from_mck(np.broadcast_to(M, K.shape), C, K, V)
    return fn


@settings(max_examples=12, deadline=None)
@given(seed=st_.integers(0, 10_000))
def test_every_crossing_found_against_dense_sweep(seed):
    fn = random_family(seed)
    grid = np.arange(1.0, 60.0, 7.0)
    an = analyse(fn, grid, n_dof=3, xtol=1e-3)
    Vd = np.arange(grid[0], grid[-1], 0.004)
    nun = (np.linalg.eigvals(fn(Vd)).real > 0).sum(axis=1)     # number of unstable roots
    i = np.nonzero(nun[1:] != nun[:-1])[0]
    dense = 0.5 * (Vd[i] + Vd[i + 1])
    found = np.array([p.V for p in an.criticals.points if p.V < Vd[-1]])
    assert found.size == dense.size
    if dense.size:
        assert np.abs(np.sort(found) - dense).max() < 0.01
    net = sum((2 if p.kind == "flutter" else 1) * (1 if p.direction == "onset" else -1)
              for p in an.criticals.points if p.V < Vd[-1])
    assert net == nun[-1] - nun[0]
    # tracked eigenvalues are the eigenvalues; conjugate bookkeeping is exact
    lam = an.sweep.eigenvalues
    ref = np.sort_complex(np.linalg.eigvals(fn(an.sweep.V)))
    np.testing.assert_allclose(np.sort_complex(lam), ref, atol=1e-9)
    assert np.all(an.sweep.physical.sum(axis=1) == (lam.imag >= 0).sum(axis=1))


# ----------------------------------------------------------------------------------------------
# (g) save / load, time response, helpers
# ----------------------------------------------------------------------------------------------
def test_save_load_round_trip(section_analysis):
    an = section_analysis[3]
    text = json.dumps(an.to_dict())
    back = Analysis.from_dict(json.loads(text))
    for name in ("V", "eigenvalues", "eigenvectors", "dlam_dV", "physical", "displacement",
                 "partner", "grid", "floor"):
        np.testing.assert_array_equal(getattr(back.sweep, name), getattr(an.sweep, name))
    assert back.sweep.state_labels == an.sweep.state_labels
    assert back.sweep.mode_labels == an.sweep.mode_labels
    for p, q in zip(back.criticals.points, an.criticals.points):
        assert (p.V, p.kind, p.eigenvalue, p.benignity) == (q.V, q.kind, q.eigenvalue, q.benignity)
        np.testing.assert_array_equal(p.eigenvector, q.eigenvector)
    assert back.criticals.critical.V == an.criticals.critical.V
    tab = back.sweep.table()
    assert set(tab) == {"V", "mode", "label", "frequency_hz", "damping_ratio", "real", "imag"}
    assert np.all(np.diff(tab["V"]) >= 0) and tab["V"].size == an.sweep.physical.sum()


def test_saved_without_eigenvectors_and_unstable_at_start():
    fn = section()[0]
    an = analyse(fn, np.arange(25.0, 61.0, 5.0), n_dof=2)      # flutter began at 19.66
    unstable = an.criticals.unstable_at_start
    assert len(unstable) == 1 and an.sweep.eigenvalues[0, unstable[0]].imag > 0
    lean = Sweep.from_dict(json.loads(json.dumps(an.sweep.to_dict(include_eigenvectors=False))))
    assert lean.eigenvectors is None
    np.testing.assert_array_equal(lean.eigenvalues, an.sweep.eigenvalues)
    with pytest.raises(InputError, match="without eigenvectors"):
        lean.mode_shape(0, 0)
    with pytest.raises(InputError, match="without them"):
        critical_points(lean, fn)


def test_time_response_matches_closed_form():
    k, c = 40.0, 0.8
    A = state_matrix_from_mck(np.eye(1), c * np.eye(1), k * np.eye(1))[0]
    t = np.linspace(0.0, 5.0, 501)
    wn, z = np.sqrt(k), c / (2 * np.sqrt(k))
    wd = wn * np.sqrt(1 - z**2)
    exact = np.exp(-z * wn * t) * (np.cos(wd * t) + z * wn / wd * np.sin(wd * t))
    for method in ("expm", "ivp"):
        r = time_response(A, [1.0, 0.0], t, second_order_labels(["h"]), method=method)
        np.testing.assert_allclose(r["h"], exact, atol=1e-7)
    back = TimeResponse.from_dict(json.loads(json.dumps(r.to_dict())))
    np.testing.assert_array_equal(back.x, r.x)
    with pytest.raises(InputError, match="no state"):
        r["alpha"]


def test_time_response_nonuniform_and_whirl_orbit():
    """Propeller of eq. (6.8), 1° initial pitch: the backward mode survives; orbit clockwise."""
    fn = propeller(c=0.0, K_p=4000.0, I_Z=2.0)
    A = fn(np.array([60.0]))[0]
    t = np.concatenate([np.linspace(0, 1, 300), np.linspace(1.01, 3, 50)])
    r = time_response(A, [np.radians(1.0), 0, 0, 0], t)
    ivp = time_response(A, [np.radians(1.0), 0, 0, 0], t, method="ivp")
    np.testing.assert_allclose(r.x, ivp.x, atol=1e-7)
    energy = 0.5 * 2.0 * (r.x[:, 2] ** 2 + r.x[:, 3] ** 2) + 0.5 * 4000 * (r.x[:, 0] ** 2 +
                                                                          r.x[:, 1] ** 2)
    np.testing.assert_allclose(energy, energy[0], rtol=1e-9)      # gyroscopic: conservative


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


# ----------------------------------------------------------------------------------------------
# (h) bad input
# ----------------------------------------------------------------------------------------------
def test_bad_speeds():
    fn = section()[0]
    with pytest.raises(InputError, match=r"speeds\[0\] = 0.0 m/s.*> 0"):
        sweep(fn, [0.0, 10.0])
    with pytest.raises(InputError, match="> 0"):
        analyse(fn, [-5.0, 10.0])
    with pytest.raises(InputError, match="strictly increasing"):
        sweep(fn, [10.0, 10.0, 20.0])
    with pytest.raises(InputError, match="at least 2"):
        sweep(fn, [])
    with pytest.raises(InputError, match="finite"):
        sweep(fn, [1.0, np.nan])


def test_bad_state_matrices_name_the_speed():
    base = section()[0]

    def nan_at_30(V):
        A = base(V)
        A[np.isclose(V, 30.0), 3, 1] = np.nan
        return A

    with pytest.raises(InputError, match=r"V = 30.0 m/s, row 3 \(d\(alpha\)/dt\), column 1 "
                                         r"\(alpha\)"):
        sweep(nan_at_30, [10.0, 20.0, 30.0], state_labels=second_order_labels(["h", "alpha"]))
    with pytest.raises(InputError, match="shape"):
        sweep(lambda V: np.zeros((V.size, 3, 2)), [1.0, 2.0])
    with pytest.raises(InputError, match="complex"):
        sweep(lambda V: base(V) * (1 + 1j), [1.0, 2.0])
    with pytest.raises(InputError, match="n_dof"):
        sweep(base, [1.0, 2.0], n_dof=7)
    with pytest.raises(InputError, match="either n_dof or displacement"):
        sweep(base, [1.0, 2.0], n_dof=2, displacement=np.ones(4, bool))
    with pytest.raises(InputError, match="mass matrix M is singular.*V = 2.0 m/s"):
        state_matrix_from_mck(np.stack([np.eye(2), np.diag([1.0, 0.0])]), np.zeros((2, 2)),
                                 np.eye(2), V=[1.0, 2.0])
    with pytest.raises(InputError, match="min_step"):
        TrackingOptions(min_step=0.0)
    with pytest.raises(InputError, match="method"):
        time_response(np.eye(2), [1.0, 0.0], [0.0, 1.0], method="euler")
    with pytest.raises(InputError, match="x0"):
        time_response(np.eye(2), [1.0, 0.0, 0.0], [0.0, 1.0])


# ----------------------------------------------------------------------------------------------
# (i) the fast engine: coarse steps, real roots, clusters through branch points, tolerances
# ----------------------------------------------------------------------------------------------
def lag_family(n_lag=20, eps=0.02):
    """An oscillator whose damping 0.5 − 0.01 V changes sign at V = 50 m/s, coupled weakly to
    ``n_lag`` real 'aerodynamic lag' roots ≈ −b_i V in a cluster 2 % apart (like Leishman–Nguyen
    states: no displacement of their own), mixed by a nearest-neighbour coupling that grows
    with V (so their shapes rotate into each other along V, while they stay real)."""
    b = 0.5 * 1.02 ** np.arange(n_lag)
    T = np.eye(n_lag, k=1) + np.eye(n_lag, k=-1)

    def fn(V):
        V = np.atleast_1d(np.asarray(V, dtype=float))
        n = 2 + n_lag
        A = np.zeros((V.size, n, n))
        A[:, 0, 1] = 1.0
        A[:, 1, 0] = -100.0
        A[:, 1, 1] = -(0.5 - 0.01 * V)
        A[:, 1, 2:] = eps
        A[:, 2:, 1] = eps
        A[:, 2:, 2:] = -V[:, None, None] * (np.diag(b)[None] + (0.005 + 1e-4 * V)[:, None, None]
                                             * T[None])
        return A
    return fn, 2 + n_lag


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


def cubic_cluster(V):
    """Companion matrix of a real cubic whose coefficients are linear in V: a lightly damped
    pair that turns real (131.98 m/s) while its lower root merges with a third, real root
    into a new pair (132.12 m/s); the remaining real root crosses zero (144.33 m/s); the new
    pair turns real again (146.94 m/s) — the wing-1 events of the wingtip model."""
    r101 = np.array([-2.207 + 7.742j, -2.207 - 7.742j, -7.555])
    r141 = np.array([-0.558, -8.12 + 1.256j, -8.12 - 1.256j])
    c0, c1 = np.real(np.poly(r101)), np.real(np.poly(r141))
    V = np.atleast_1d(np.asarray(V, dtype=float))
    c = c0[None, :] + ((V - 101.0) / 40.0)[:, None] * (c1 - c0)[None, :]
    A = np.zeros((V.size, 3, 3))
    A[:, 0, :] = -c[:, 1:]
    A[:, 1, 0] = A[:, 2, 1] = 1.0
    return A


def test_cluster_followed_through_split_and_merge():
    """A pair turning real and its lower root merging with a real root 0.14 m/s later, inside
    one 49 m/s step: followed as a cluster (coefficients of its characteristic polynomial),
    with the module's conventions — the oscillatory mode keeps the larger root and owns the
    divergence, the merged pair's Im > 0 member goes to the smaller id (the real root's) —
    and no refinement down to the events."""
    an = analyse(cubic_cluster, np.array([91.0, 161.0]), initial_step=None, xtol=0.001)
    sw = an.sweep
    assert sw.unresolved == () and sw.stats["eig"] <= 6
    np.testing.assert_allclose(np.sort_complex(sw.eigenvalues),
                               np.sort_complex(np.linalg.eigvals(cubic_cluster(sw.V))),
                               atol=1e-9)
    assert sw.eigenvalues[0, 0].imag > 0 and sw.eigenvalues[0, 1].imag == 0
    after = np.nonzero((sw.V > 132.2) & (sw.V < 144.3))[0]
    assert after.size
    for t in after:
        assert sw.eigenvalues[t, 0].imag == 0                 # mode 0 owns the real root
        assert sw.eigenvalues[t, 1].imag > 0 and sw.physical[t, 1]   # smaller id: Im > 0
        assert not sw.physical[t, 2]
    (p,) = an.criticals.points
    Vd = np.arange(143.0, 146.0, 1e-4)
    det = np.linalg.det(cubic_cluster(Vd))
    V_exact = Vd[np.nonzero(np.diff(np.sign(det)))[0][0]]
    assert (p.kind, p.direction, p.mode) == ("divergence", "onset", 0)
    assert abs(p.V - V_exact) <= 1e-3 and p.frequency_hz == 0


def toy_fz(V):
    """A stable oscillator (−0.2 ± 5i) and an unstable pair 1 ± √(V − 30): it turns into two
    real roots at V = 30 m/s (frequency zero) and its smaller root recovers at 31 m/s."""
    V = np.atleast_1d(np.asarray(V, dtype=float))
    A = np.zeros((V.size, 4, 4))
    A[:, 0, 0] = A[:, 1, 1] = -0.2
    A[:, 0, 1], A[:, 1, 0] = 5.0, -5.0
    A[:, 2, 2] = A[:, 3, 3] = 1.0
    A[:, 2, 3], A[:, 3, 2] = 1.0, V - 30.0
    return A


def test_unstable_pair_turning_real_is_bracketed_by_two_nodes():
    """The branch point of an unstable pair turning real (the thesis's whirl divergence) is
    located from the discriminant of the pair's 2 × 2 Ritz matrix and bracketed by two sweep
    nodes 0.9·min_step apart: complex at the lower, real at the upper."""
    opts = TrackingOptions()
    sw = sweep(toy_fz, np.arange(1.0, 52.0, 10.0), options=opts)
    V = sw.V
    i = int(np.searchsorted(V, 30.0))
    assert V[i - 1] < 30.0 < V[i] and V[i] - V[i - 1] <= 0.9 * opts.min_step + 1e-12
    k = int(np.argmax(sw.eigenvalues[0].real))               # the unstable mode
    assert sw.eigenvalues[i - 1, k].imag != 0 and sw.eigenvalues[i, k].imag == 0
    assert sw.eigenvalues[i, k].real > 1.0                    # it keeps the larger root
    assert sw.stats["branch_point_nodes"] == 2


def rotating_shapes(V):
    """Fixed, well separated eigenvalues (−0.1 ± 10i, −0.2 ± 20i) whose mode shapes rotate by
    90° in the displacement plane every 50 m/s."""
    V = np.atleast_1d(np.asarray(V, dtype=float))
    out = np.zeros((V.size, 4, 4))
    M, C = np.eye(2), np.diag([0.2, 0.4])
    K = np.diag([100.0, 400.0])
    for t, v in enumerate(V):
        c, s = np.cos(np.pi * v / 100), np.sin(np.pi * v / 100)
        R = np.array([[c, -s], [s, c]])
        out[t] = state_matrix_from_mck(M, R @ C @ R.T, R @ K @ R.T)[0]
    return out


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


def badly_scaled(delta=1e-2, stiff=1e10, seed=4):
    """A 4 × 4 real matrix like a stiff structure's state matrix: a stiff oscillator
    (±1e5 i, entries 1e10) and a nearly defective pair 50 ± i√delta, mixed by a similarity."""
    B = np.zeros((4, 4))
    B[0, 1], B[1, 0], B[1, 1] = 1.0, -stiff, -1.0
    B[2, 2] = B[3, 3] = 50.0
    B[2, 3], B[3, 2] = 1.0, -delta
    S = np.eye(4) + 0.3 * np.random.default_rng(seed).standard_normal((4, 4))
    return S @ B @ np.linalg.inv(S)


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


def test_analyse_evaluates_a_subset_of_the_grid_and_all_on_request():
    fn, _, _ = section()
    grid = np.arange(1.0, 202.0, 5.0)
    coarse = analyse(fn, grid, n_dof=2, xtol=1e-3)
    full = analyse(fn, grid, n_dof=2, initial_step=None, xtol=1e-3)
    assert np.all(np.isin(grid, full.sweep.V))
    assert coarse.sweep.V.size < 0.5 * grid.size
    assert np.all(np.isin(coarse.sweep.grid, grid)) and coarse.sweep.V[0] == grid[0]
    assert coarse.sweep.V[-1] == grid[-1]
    for p, q in zip(coarse.criticals.points, full.criticals.points):
        assert (p.kind, p.direction) == (q.kind, q.direction) and abs(p.V - q.V) < 1e-3
    with pytest.raises(InputError, match="initial_step"):
        analyse(fn, grid, n_dof=2, initial_step=0.0)


def test_benignity_by_central_difference_on_request(section_analysis):
    """With ``benignity_step`` the benignity is a central difference of ζ (as the thesis),
    agreeing with the default, from dλ/dV at the crossing."""
    fn, _, _, an = section_analysis
    p = [q for q in an.criticals.points if q.kind == "flutter"][0]
    cd = critical_points(an.sweep, fn, benignity_step=0.01, xtol=1e-3)
    q = [r for r in cd.points if r.kind == "flutter"][0]
    assert q.dzeta_dV == pytest.approx(p.dzeta_dV, rel=1e-4)
