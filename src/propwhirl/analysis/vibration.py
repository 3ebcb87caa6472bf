"""Free vibration: natural frequencies and mode shapes of an undamped structure (V = 0).

For the wing alone (chapter 7 verification, Tables 7.2 and 9.2): :func:`wing_modes`,
:func:`torsion_fraction`, :func:`classify_wing_modes`.

The in-vacuo modes of any model and their thesis names (:class:`Modes`,
:func:`undamped_modes`, :func:`model_modes`, :func:`label_modes`) live in
:mod:`propwhirl.analysis.modes`, the Campbell diagram (:func:`campbell`,
:class:`CampbellResult`, the mode families, the propellers' speed ratios) in
:mod:`propwhirl.analysis.campbell`; both are re-exported here, the names users' scripts import
from this module.
"""
from __future__ import annotations

import numpy as np

from propwhirl.analysis.campbell import (CAMPBELL_RPM, FAMILIES, RPM_FORM,  # noqa: F401
                                         CampbellResult, campbell, mode_families,
                                         operating_rpm_ratio)
from propwhirl.analysis.modes import Modes, label_modes, model_modes, undamped_modes  # noqa: F401
from propwhirl.model.structure.assembly import WING_DOF_NAMES, free_dofs, wing_dof_labels, wing_structure
from propwhirl.model.structure.wing import Wing


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
