"""Free vibration: natural frequencies and mode shapes of an undamped structure (V = 0).

For the wing alone (chapter 7 verification, Tables 7.2 and 9.2) and, with rotating propellers,
the Campbell diagram (frequencies against propeller RPM, Figures 8.6, 9.16, 10.3, 10.11).

The thesis's names of the modes (:func:`label_modes`) follow the Campbell diagrams: each
mode is followed by the tracker of :mod:`propwhirl.analysis.campbell` from Ω = 0 to a small
spin rate.  The Campbell diagram itself (:func:`~propwhirl.analysis.campbell.campbell`,
:class:`~propwhirl.analysis.campbell.CampbellResult`, the mode families, the propellers'
speed ratios) lives in :mod:`propwhirl.analysis.campbell` and is re-exported here.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.linalg as sl

from propwhirl import validate as v
from propwhirl.model.assembly import WING_DOF_NAMES, free_dofs, wing_dof_labels, wing_structure
from propwhirl.model.wing import Wing

# The Campbell diagram and its tracker (propwhirl.analysis.campbell), re-exported: the names
# users' scripts import from here; label_modes follows the modes with the tracker.
from propwhirl.analysis.campbell import (CAMPBELL_RPM, FAMILIES, RPM_FORM,  # noqa: F401
                                         CampbellResult, _flexible_propellers,
                                         _GyroscopicSystem, _track, campbell, mode_families,
                                         operating_rpm_ratio)


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


def torsion_fraction(modes: Modes, M: np.ndarray, twist: np.ndarray) -> np.ndarray:
    """Share of each mode's kinetic energy in the twist degrees of freedom (0 = pure bending).

    Energy share of DOF group g: Σ_{i∈g} x_i (M x)_i / xᵀMx, with M the (reduced) mass matrix
    the modes were computed with; ``twist`` the indices of the twist DOFs α in it.
    """
    X = modes.shapes
    e = X * (M @ X)
    return e[np.asarray(twist, dtype=int)].sum(axis=0) / e.sum(axis=0)


def classify_wing_modes(wing: Wing, count: int) -> list[tuple[str, float]]:
    """The lowest `count` wing modes as ('bending n' | 'torsion n', frequency [rad/s])."""
    M, _, K = wing_structure(wing)
    f = free_dofs(wing.n_nodes)
    modes = wing_modes(wing)
    twist = np.nonzero(f % 3 == WING_DOF_NAMES.index("alpha"))[0]   # (7.20): [h, φ, α] per node
    tors = torsion_fraction(modes, M[np.ix_(f, f)], twist)
    out, nb, nt = [], 0, 0
    for w, share in zip(modes.omega[:count], tors[:count]):
        if share > 0.5:
            nt += 1
            out.append((f"torsion {nt}", float(w)))
        else:
            nb += 1
            out.append((f"bending {nb}", float(w)))
    return out


def model_modes(model, basis: np.ndarray | None = None) -> tuple[Modes, np.ndarray]:
    """Undamped in-vacuo modes of any model (no aerodynamics; the gyroscopic and dissipative
    terms, which live in the damping matrix, play no part): K x = ω² M x with the structural
    M and K of ``model.without_aerodynamics()``.

    ``basis`` (n, r): Rayleigh–Ritz on its columns instead (a reduced model's basis,
    :mod:`propwhirl.model.reduction`): r modes, shapes lifted to the n DOFs.
    Returns the modes and the (reduced) structural mass matrix they are normalised with.
    """
    s = model.without_aerodynamics().second_order(np.array([1.0]))
    if basis is None:
        return undamped_modes(s.S1[0], s.S3[0], s.q_labels), s.S1[0]
    P = np.asarray(basis)
    m = undamped_modes(P.T @ s.S1[0] @ P, P.T @ s.S3[0] @ P, s.q_labels)
    return Modes(m.omega, P @ m.shapes, s.q_labels), s.S1[0]


def label_modes(model, basis: np.ndarray | None = None,
                modes: Modes | None = None) -> list[tuple[str, float]]:
    """All non-rotating modes of a PropellerWing as (label, frequency [Hz]), ascending.

    The thesis names one backward and one forward whirl mode per flexibly mounted propeller
    (at Ω = 0 the propeller pitch and yaw modes) and calls the others wing modes (§9.3.2,
    Tables 9.8, 10.3, 10.7); its names follow the Campbell diagrams (Figures 9.16, 10.3, 10.11):
    backward modes fall and forward modes rise as the rotor spins up.  Here the frequencies at
    Ω = 0 are compared with those at a small spin rate (one tenth of the lowest mount frequency,
    so the shifts stay far below the gaps between modes), each mode followed by the Campbell
    tracker (:mod:`propwhirl.analysis.campbell`); with N flexible propellers the N modes that
    fall most are 'backward k', the N that rise most 'forward k' (k by frequency), the rest
    'wing n'.
    ``basis``: the modes of the Rayleigh–Ritz problem on its columns (:func:`model_modes`);
    ``modes``: those modes if already computed (``model_modes(model, basis)[0]``).
    """
    if modes is None:
        modes, _ = model_modes(model, basis)
    f0 = modes.frequency_hz
    kinds = ["wing"] * f0.size
    flex = _flexible_propellers(model)
    if flex:
        f_mount = min(min(p.stiffness()[0] / p.pivot_inertia()["I_theta_P"],
                          p.stiffness()[1] / p.pivot_inertia()["I_psi_P"]) for p in flex) ** 0.5
        rpm = 0.1 * f_mount * 60.0 / (2.0 * np.pi)
        tracks = _track(_GyroscopicSystem.of(model, basis=basis),
                        np.array([0.0, rpm]) * 2.0 * np.pi / 60.0)
        delta = tracks.omega[-1] - tracks.omega[0]
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
