"""Free vibration: natural frequencies and mode shapes of an undamped structure (V = 0).

For the wing alone (chapter 7 verification, Tables 7.2 and 9.2) and, with rotating propellers,
the Campbell diagram (frequencies against propeller RPM, Figures 8.6, 9.16, 10.3) is built on
the same solve with the gyroscopic terms included (see propwhirl.model.systems).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.linalg as sl

from propwhirl import validate as v
from propwhirl.model.assembly import free_dofs, wing_dof_labels, wing_structure
from propwhirl.model.wing import Wing


@dataclass(frozen=True)
class Modes:
    """Undamped modes: angular frequencies ω [rad/s], mass-normalised shapes (columns)."""

    omega: np.ndarray
    shapes: np.ndarray
    labels: tuple[str, ...]

    @property
    def frequency_hz(self) -> np.ndarray:
        return self.omega / (2.0 * np.pi)


def undamped_modes(M: np.ndarray, K: np.ndarray, labels: tuple[str, ...]) -> Modes:
    """Solve K x = ω² M x for symmetric M (positive definite) and K (symmetric)."""
    try:
        lam, X = sl.eigh(K, M)
    except np.linalg.LinAlgError as exc:
        raise v.InputError(f"structural mass matrix is not positive definite: {exc}") from exc
    return Modes(np.sqrt(np.clip(lam, 0.0, None)), X, labels)


def wing_modes(wing: Wing) -> Modes:
    """In-vacuo modes of the clamped wing (root degrees of freedom removed)."""
    M, _, K = wing_structure(wing)
    f = free_dofs(wing.n_nodes)
    labels = tuple(np.array(wing_dof_labels(wing.n_nodes))[f])
    return undamped_modes(M[np.ix_(f, f)], K[np.ix_(f, f)], labels)


def torsion_fraction(modes: Modes, M: np.ndarray) -> np.ndarray:
    """Share of each mode's kinetic energy in the twist degrees of freedom (0 = pure bending).

    Energy share of DOF group g: Σ_{i∈g} x_i (M x)_i / xᵀMx, with M the (reduced) mass matrix
    the modes were computed with.
    """
    X = modes.shapes
    e = X * (M @ X)
    alpha = np.array([lab.endswith("alpha") for lab in modes.labels])
    return e[alpha].sum(axis=0) / e.sum(axis=0)


def classify_wing_modes(wing: Wing, count: int) -> list[tuple[str, float]]:
    """The lowest `count` wing modes as ('bending n' | 'torsion n', frequency [rad/s])."""
    M, _, K = wing_structure(wing)
    f = free_dofs(wing.n_nodes)
    modes = wing_modes(wing)
    tors = torsion_fraction(modes, M[np.ix_(f, f)])
    out, nb, nt = [], 0, 0
    for w, share in zip(modes.omega[:count], tors[:count]):
        if share > 0.5:
            nt += 1
            out.append((f"torsion {nt}", float(w)))
        else:
            nb += 1
            out.append((f"bending {nb}", float(w)))
    return out


def model_modes(model) -> tuple[Modes, np.ndarray]:
    """Undamped in-vacuo modes of any model (no aerodynamics; the gyroscopic and dissipative
    terms, which live in the damping matrix, play no part): K x = ω² M x with the structural
    M and K of ``model.without_aerodynamics()``.

    Returns the modes and the (reduced) structural mass matrix they are normalised with.
    """
    s = model.without_aerodynamics().second_order(np.array([1.0]))
    return undamped_modes(s.S1[0], s.S3[0], s.q_labels), s.S1[0]


def label_modes(model) -> list[tuple[str, float]]:
    """All non-rotating modes of a PropellerWing as (label, frequency [Hz]), ascending.

    The thesis names one backward and one forward whirl mode per flexibly mounted propeller
    (at Ω = 0 the propeller pitch and yaw modes) and calls the others wing modes (§9.3.2,
    Tables 9.8, 10.3, 10.7); its names follow the Campbell diagrams (Figures 9.16, 10.3, 10.11):
    backward modes fall and forward modes rise as the rotor spins up.  Here the frequencies at
    Ω = 0 are compared with those at a small spin rate (one tenth of the lowest mount frequency,
    so the shifts stay far below the gaps between modes); with N flexible propellers the N
    modes that fall most are 'backward k', the N that rise most 'forward k' (k by frequency),
    the rest 'wing n'.
    """
    modes, _ = model_modes(model)
    f0 = modes.frequency_hz
    kinds = ["wing"] * f0.size
    flex = [model.propellers[j].propeller for j in model.flexible]
    if flex:
        f_mount = min(min(p.stiffness()[0] / p.pivot_inertia()["I_theta_P"],
                          p.stiffness()[1] / p.pivot_inertia()["I_psi_P"]) for p in flex) ** 0.5
        rpm = 0.1 * f_mount * 60.0 / (2.0 * np.pi)
        _, f1 = campbell(model, np.array([rpm]))
        delta = f1[0] - f0
        n = len(flex)
        order = np.argsort(delta)
        for i in order[:n]:
            kinds[i] = "backward"
        for i in order[::-1][:n]:
            kinds[i] = "forward"
    counters = {"backward": 0, "forward": 0, "wing": 0}
    out = []
    for kind, f in zip(kinds, f0):
        counters[kind] += 1
        out.append((f"{kind} {counters[kind]}", float(f)))
    return out


def campbell(model, rpm: np.ndarray, include_damping: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """Natural frequencies [Hz] against propeller rotational speed (Figures 8.6, 9.16, 10.3).

    Aerodynamics off; all propellers at the given speeds `rpm` [rev/min] (array).  Returns
    (rpm, frequencies) with frequencies of shape (len(rpm), n_modes), sorted per speed.
    Damping is left out unless asked for (the undamped gyroscopic system).
    """
    rpm = v.non_negative("rpm", np.atleast_1d(rpm), "rev/min")
    quiet = model.with_(wing_aero=False, propeller_aero=False, rotating=True)
    omega = rpm * 2.0 * np.pi / 60.0
    V = np.ones_like(omega)  # no aerodynamics: the airspeed plays no part
    s = quiet.second_order(V, omega)
    from propwhirl.model.statespace import SecondOrder, state_matrix

    S2 = s.S2 if include_damping else s.S2 - _symmetric_part(s.S2)
    A = state_matrix(SecondOrder(s.S1, S2, s.S3, s.S4, s.Ww, s.Wv, s.Wq, s.q_labels, s.w_labels), V)
    lam = np.linalg.eigvals(A)
    f = np.abs(lam.imag) / (2.0 * np.pi)
    f = np.sort(np.where(lam.imag >= 0, f, np.inf), axis=1)
    n = s.n_dof
    return rpm, f[:, :n]


def _symmetric_part(C: np.ndarray) -> np.ndarray:
    """Symmetric (dissipative) part of damping matrices (..., n, n); the skew part is gyroscopic."""
    return 0.5 * (C + np.swapaxes(C, -1, -2))
