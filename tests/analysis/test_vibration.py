"""The tracking over Ω (propwhirl.analysis.modes.track_gyroscopic: the engine's tracking core
with the gyroscopic nodes) on systems with known curves.

A rotor with equal pitch and yaw stiffness (θ, ψ; unit inertias, gyroscopic coupling g Ω)
whirls at ω± = √(ω₀² + (gΩ/2)²) ± gΩ/2: a repeated frequency at Ω = 0 that splits at first
order.  Beside it an oscillator at 4 Hz:

* uncoupled, the backward whirl (from 5 Hz, falling) crosses the oscillator exactly: the tracked
  curves cross and each keeps its exact formula, where a diagram sorted per speed swaps them
  (identity lost at the close approach);
* coupled through a small stiffness, the two veer: the tracked curves are the two analytic
  branches, do not cross, and keep a gap.
"""
from __future__ import annotations

import numpy as np
import pytest

from propwhirl.analysis.modes import GyroscopicSystem, track_gyroscopic

W0, WX, G = 2 * np.pi * 5.0, 2 * np.pi * 4.0, 1.0      # [rad/s], [rad/s], [-]


def rotor_and_oscillator(coupling: float) -> GyroscopicSystem:
    K = np.diag([W0**2, W0**2, WX**2])
    K[0, 2] = K[2, 0] = coupling
    dG = np.zeros((3, 3))
    dG[0, 1], dG[1, 0] = G, -G

    def matrices(omega):
        omega = np.asarray(omega, dtype=float)
        T = omega.size
        return (np.broadcast_to(np.eye(3), (T, 3, 3)), omega[:, None, None] * dG,
                np.broadcast_to(K, (T, 3, 3)))

    return GyroscopicSystem(matrices, dG)


def exact(Omega):
    root = np.sqrt(W0**2 + (G * Omega / 2) ** 2)
    return root - G * Omega / 2, root + G * Omega / 2


def test_uncoupled_modes_cross_and_keep_their_identity():
    Omega = np.linspace(0.0, 30.0, 7)          # backward whirl meets 4 Hz at Ω ≈ 14.1 rad/s
    tr = track_gyroscopic(rotor_and_oscillator(0.0), Omega)
    back, fwd = exact(Omega)
    assert not tr.unresolved and tr.resolved.all()
    np.testing.assert_allclose(tr.omega[:, 0], WX, rtol=1e-12)     # the oscillator, flat
    np.testing.assert_allclose(tr.omega[:, 1], back, rtol=1e-12)   # backward, through it
    np.testing.assert_allclose(tr.omega[:, 2], fwd, rtol=1e-12)
    np.testing.assert_allclose(tr.slope[:, 0], 0.0, atol=1e-12)
    assert tr.slope[0, 1] == pytest.approx(-G / 2) and tr.slope[0, 2] == pytest.approx(G / 2)
    assert tr.omega[-1, 1] < tr.omega[-1, 0]                       # they did cross
    sorted_diagram = np.sort(tr.omega, axis=1)
    assert not np.allclose(sorted_diagram[:, 0], WX)               # sorting swaps identity


def test_coupled_modes_veer_on_their_analytic_branches():
    Omega = np.linspace(0.0, 30.0, 7)
    tr = track_gyroscopic(rotor_and_oscillator(0.05 * WX**2), Omega)
    assert not tr.unresolved and tr.resolved.all()
    order = np.argsort(tr.omega, axis=1)
    assert np.all(order == order[0])                              # no crossing
    fine = track_gyroscopic(rotor_and_oscillator(0.05 * WX**2), np.linspace(0.0, 30.0, 301))
    assert np.min(fine.omega[:, 1] - fine.omega[:, 0]) > 0.5       # a gap [rad/s]
    # the frequencies are the eigenvalues of the system at every speed
    for t, Om in enumerate(Omega):
        M, Gm, K = (m[0] for m in rotor_and_oscillator(0.05 * WX**2).matrices(np.array([Om])))
        A = np.block([[np.zeros((3, 3)), np.eye(3)], [-K, -Gm]])
        lam = np.linalg.eigvals(A)
        np.testing.assert_allclose(tr.omega[t], np.sort(lam.imag[lam.imag > 0]), rtol=1e-10)
