"""The nodes of a sweep: the full eigen-solution at one speed, evaluated in batches.

A node holds the eigenvalues, unit right eigenvectors and dλ/dV of all roots at one speed, in
LAPACK order (pairs adjacent, Im > 0 first).  dλ/dV = y A' x from the left eigenvectors (rows
of X⁻¹, only the diagonal formed, in real arithmetic) and a forward finite difference of
``state_matrix``: the forward difference for dA/dV also evaluates ``state_matrix`` at
V + 1e-6·max(V, 1 m/s) (batched with V in one call), so the model must accept speeds just
above the last one.
"""
from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from propwhirl.engine.eigensolve import (StateMatrixFn, call_state_matrix, conj_index,
                                         eig_derivative)
from propwhirl.engine.options import TrackingOptions


@dataclass
class Node:
    """Raw eigen-solution at one speed (LAPACK order)."""

    V: float
    lam: np.ndarray    # (n,) complex
    X: np.ndarray      # (n, n) complex, unit columns
    dlam: np.ndarray   # (n,) complex, dλ/dV [1/m]
    conj: np.ndarray   # (n,) int, index of the conjugate (itself if real)
    floor: float       # scale floor for relative distances [1/s]

    @property
    def s(self) -> float:
        """The tracked parameter (the airspeed V [m/s]) for the tracking core."""
        return self.V


def evaluate_nodes(fn: StateMatrixFn, V: np.ndarray, n: int | None,
                   labels: Sequence[str] | None, opts: TrackingOptions,
                   stats: dict[str, int]) -> list[Node]:
    """Full eigen-solutions at the speeds V (one vectorised model call, one stacked eig)."""
    V = np.asarray(V, dtype=float)
    h = opts.fd_rel * np.maximum(V, 1.0)
    A_all = call_state_matrix(fn, np.concatenate([V, V + h]), n, labels)
    A, Ah = A_all[: V.size], A_all[V.size:]
    w, X = np.linalg.eig(A)
    w, X = w.astype(complex, copy=False), X.astype(complex, copy=False)
    conj = conj_index(w)
    dlam = eig_derivative(w, X, conj, (Ah - A) / h[:, None, None])
    mag = np.abs(w)
    floor = np.maximum(1e-3 * np.median(mag, axis=1), 1e-12)
    stats["eig"] = stats.get("eig", 0) + V.size
    stats["state_matrix_calls"] = stats.get("state_matrix_calls", 0) + 1
    return [Node(float(V[t]), w[t], X[t], dlam[t], conj[t], float(floor[t]))
            for t in range(V.size)]
