"""Free vibration: natural frequencies and mode shapes of an undamped structure (V = 0).

For the wing alone (chapter 7 verification, Tables 7.2 and 9.2) and, with rotating propellers,
the Campbell diagram (frequencies against propeller RPM, Figures 8.6, 9.16, 10.3) is built on
the same solve with the gyroscopic terms included (see propwhirl.model).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.linalg as sl

from propwhirl import validate as v
from propwhirl.assembly import free_dofs, wing_dof_labels, wing_structure
from propwhirl.wing import Wing


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
