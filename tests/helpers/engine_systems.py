"""Toy systems with independently known answers for the stability engine (thesis chapter 5).

Built from M, C, K families (eq. 5.2–5.4) or directly as state matrices:
* a 2-DOF typical section with quasi-steady aero stiffness/damping — flutter checked against the
  Routh–Hurwitz boundary of its characteristic quartic, divergence against det K(V) = 0;
* a decoupled oscillator whose damping c(V) dips below zero — a hump with analytic crossings
  and analytic benignity;
* two oscillators whose frequencies cross (decoupled) or veer (coupled);
* the gyroscopic propeller of eq. (6.8) for the whirl sense;
* random 3-DOF aero-like families checked against a dense brute-force eigenvalue sweep;
* lag-root clusters, a cubic whose roots split and merge, a pair turning real, rotating shapes,
  a badly scaled matrix.
"""
from __future__ import annotations

import numpy as np
from numpy.polynomial import polynomial as P
from scipy.optimize import brentq

from propwhirl.model.statespace import state_matrix_from_mck


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


def badly_scaled(delta=1e-2, stiff=1e10, seed=4):
    """A 4 × 4 real matrix like a stiff structure's state matrix: a stiff oscillator
    (±1e5 i, entries 1e10) and a nearly defective pair 50 ± i√delta, mixed by a similarity."""
    B = np.zeros((4, 4))
    B[0, 1], B[1, 0], B[1, 1] = 1.0, -stiff, -1.0
    B[2, 2] = B[3, 3] = 50.0
    B[2, 3], B[3, 2] = 1.0, -delta
    S = np.eye(4) + 0.3 * np.random.default_rng(seed).standard_normal((4, 4))
    return S @ B @ np.linalg.inv(S)
