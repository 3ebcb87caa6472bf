"""Assembly of global matrices from generated element functions (index arithmetic, no loops).

Global wing degrees of freedom (7.20): node i contributes [h_i, φ_i, α_i] at indices 3i..3i+2,
node 0 is the clamped root.  Element e couples nodes e and e+1, i.e. global indices 3e..3e+5,
the order of the generated element matrices ([h1, φ1, α1, h2, φ2, α2]).
"""
from __future__ import annotations

import numpy as np

from propwhirl.generated import beam_element
from propwhirl.wing import Wing

WING_DOF_NAMES = ("h", "phi", "alpha")


def element_dofs(n_elements: int) -> np.ndarray:
    """Global indices (n_elements, 6) of each element's degrees of freedom."""
    return 3 * np.arange(n_elements)[:, None] + np.arange(6)[None, :]


def scatter(blocks: np.ndarray, dofs: np.ndarray, size: int) -> np.ndarray:
    """Sum element blocks (..., n_el, k, k) into global matrices (..., size, size).

    One `np.add.at` over all leading indices, elements and entries (overlapping element
    degrees of freedom add up, as in standard finite-element assembly).
    """
    lead = blocks.shape[:-3]
    nlead = int(np.prod(lead)) if lead else 1
    b = blocks.reshape((nlead,) + blocks.shape[-3:])
    lin = dofs[:, :, None] * size + dofs[:, None, :]  # (n_el, k, k) flat global index
    out = np.zeros((nlead, size * size))
    np.add.at(out, (np.arange(nlead)[:, None, None, None], lin[None]), b)
    return out.reshape(lead + (size, size))


def wing_structure(wing: Wing) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Global structural mass, damping and stiffness of the free wing (root included).

    Mass and stiffness from the generated beam element (7.9–7.15, assembled as in (C.18));
    damping by the Rayleigh model C = μM + λK (7.22).  Shapes (3 n_nodes, 3 n_nodes).
    """
    p = wing.element_properties()
    Me = beam_element.mass(p["length"], p["m"], p["rho_Ip"], p["x_alpha_b"])
    Ke = beam_element.stiffness(p["length"], p["EI"], p["GJ"])
    size = 3 * wing.n_nodes
    dofs = element_dofs(wing.n_elements)
    M = scatter(Me, dofs, size)
    K = scatter(Ke, dofs, size)
    mu, lam = wing.rayleigh
    return M, mu * M + lam * K, K


def free_dofs(n_nodes: int) -> np.ndarray:
    """Indices of the unconstrained wing degrees of freedom (root node clamped)."""
    return np.arange(3, 3 * n_nodes)


def wing_dof_labels(n_nodes: int) -> tuple[str, ...]:
    """Labels 'node i h' / 'node i phi' / 'node i alpha' for all wing DOFs (root = node 0)."""
    return tuple(f"node {i} {d}" for i in range(n_nodes) for d in WING_DOF_NAMES)
