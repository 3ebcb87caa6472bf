"""First-order state-space form of the aeroelastic equations (eq. 5.3, 6.18, 7.59, C.63, D.27).

All models reduce to

    S1 q̈ + S2 q̇ + S3 q = S4 w,        ẇ = Ww w + Wv q̇ + Wq q

(second-order structural/aerodynamic equations with aerodynamic lag states w; Leishman–Nguyen
uses Wv and Wq, Wagner's form Wq only), stacked over airspeeds: every matrix has a leading
speed axis.  :func:`state_matrix` returns

    A = [[0, I, 0], [−S1⁻¹S3, −S1⁻¹S2, S1⁻¹S4], [Wq, Wv, Ww]]

for the state x = [q, q̇, w], solving S1 once per speed (stacked `numpy.linalg.solve`).
"""
from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from propwhirl import validate as v
from propwhirl.model.protocol import rate_label
from propwhirl.validate import InputError


@dataclass(frozen=True)
class SecondOrder:
    """Matrices of S1 q̈ + S2 q̇ + S3 q = S4 w, ẇ = Ww w + Wv q̇ + Wq q (leading speed axis)."""

    S1: np.ndarray  # (nV, n, n)
    S2: np.ndarray
    S3: np.ndarray
    S4: np.ndarray  # (nV, n, m)
    Ww: np.ndarray  # (nV, m, m)
    Wv: np.ndarray  # (nV, m, n)
    Wq: np.ndarray  # (nV, m, n)
    q_labels: tuple[str, ...]
    w_labels: tuple[str, ...]

    @property
    def n_dof(self) -> int:
        return self.S1.shape[-1]

    @property
    def n_lag(self) -> int:
        return self.Ww.shape[-1]

    @property
    def labels(self) -> tuple[str, ...]:
        """Labels of the first-order state [q, q̇, w]."""
        return self.q_labels + tuple(rate_label(s) for s in self.q_labels) + self.w_labels

    def reduced(self, keep_q: np.ndarray, keep_w: np.ndarray) -> "SecondOrder":
        """Keep only the listed degrees of freedom and lag states (e.g. remove a clamped root)."""
        ix = np.ix_
        return SecondOrder(
            self.S1[(...,) + ix(keep_q, keep_q)],
            self.S2[(...,) + ix(keep_q, keep_q)],
            self.S3[(...,) + ix(keep_q, keep_q)],
            self.S4[(...,) + ix(keep_q, keep_w)],
            self.Ww[(...,) + ix(keep_w, keep_w)],
            self.Wv[(...,) + ix(keep_w, keep_q)],
            self.Wq[(...,) + ix(keep_w, keep_q)],
            tuple(np.asarray(self.q_labels, dtype=object)[keep_q]),
            tuple(np.asarray(self.w_labels, dtype=object)[keep_w]) if self.w_labels else (),
        )


def check_finite(name: str, arr: np.ndarray, V: np.ndarray) -> None:
    """Raise InputError naming the matrix and the first speed where it is not finite."""
    bad = ~np.isfinite(arr).reshape(arr.shape[0], -1).all(axis=1)
    if bad.any():
        raise v.InputError(
            f"{name} has non-finite entries at V = {float(V[np.argmax(bad)])!r} m/s: "
            "check the model parameters feeding it (e.g. a zero semichord, radius or speed)"
        )


def state_matrix(sys: SecondOrder, V: np.ndarray) -> np.ndarray:
    """The state matrix A(V) (nV, 2n+m, 2n+m) of x = [q, q̇, w] (eq. 7.59, D.27)."""
    n, m = sys.n_dof, sys.n_lag
    nV = sys.S1.shape[0]
    for name in ("S1", "S2", "S3", "S4", "Ww", "Wv", "Wq"):
        check_finite(name, getattr(sys, name), V)
    rhs = np.concatenate([sys.S3, sys.S2, sys.S4], axis=-1)
    cond = np.linalg.cond(sys.S1)
    bad = ~np.isfinite(cond) | (cond > 1e14)
    if bad.any():
        raise v.InputError(
            f"the structural-plus-aerodynamic mass matrix is singular at V = "
            f"{float(V[np.argmax(bad)])!r} m/s (condition number {cond[np.argmax(bad)]:.3g}): "
            "a degree of freedom has no inertia (zero mass or inertia?)"
        )
    X = np.linalg.solve(sys.S1, rhs)
    A = np.zeros((nV, 2 * n + m, 2 * n + m))
    A[:, :n, n : 2 * n] = np.eye(n)
    A[:, n : 2 * n, :n] = -X[..., :n]
    A[:, n : 2 * n, n : 2 * n] = -X[..., n : 2 * n]
    A[:, n : 2 * n, 2 * n :] = X[..., 2 * n :]
    A[:, 2 * n :, :n] = sys.Wq
    A[:, 2 * n :, n : 2 * n] = sys.Wv
    A[:, 2 * n :, 2 * n :] = sys.Ww
    return A


def state_matrix_from_mck(M, C, K, V=None) -> np.ndarray:
    """First-order state matrix J = [[0, I], [−M⁻¹K, −M⁻¹C]] of eq. (5.4), vectorised.

    ``M, C, K``: ``(N, N)`` or stacks ``(T, N, N)`` (broadcast against each other).  ``V``
    [m/s] (optional, length T) is used only to name the speed in errors.  A singular or
    ill-conditioned (cond > 1e12) mass matrix raises :class:`InputError` naming the speed.
    """
    M, C, K = (np.asarray(x, dtype=float) for x in (M, C, K))
    M, C, K = np.broadcast_arrays(*(x if x.ndim == 3 else x[None] for x in (M, C, K)))
    for name, arr in (("M", M), ("C", C), ("K", K)):
        bad = ~np.isfinite(arr)
        if bad.any():
            t = int(np.argwhere(bad)[0][0])
            raise InputError(f"{name} has a non-finite entry at {_where(V, t)}")
    with np.errstate(all="ignore"):
        cond = np.linalg.cond(M)
    bad = ~(cond < 1e12)
    if bad.any():
        t = int(np.argmax(bad))
        raise InputError(f"mass matrix M is singular (condition number {cond[t]:.3g}) at "
                         f"{_where(V, t)}: check the inertia parameters")
    N = M.shape[-1]
    T = M.shape[0]
    rhs = np.concatenate([K, C], axis=-1)
    sol = np.linalg.solve(M, rhs)
    J = np.zeros((T, 2 * N, 2 * N))
    J[:, :N, N:] = np.eye(N)
    J[:, N:, :N] = -sol[..., :N]
    J[:, N:, N:] = -sol[..., N:]
    return J


def _where(V, t: int) -> str:
    if V is None:
        return f"index {t}"
    Va = np.atleast_1d(np.asarray(V, dtype=float))
    return f"V = {float(Va[min(t, Va.size - 1)])!r} m/s"


def second_order_labels(dof_labels: Sequence[str]) -> tuple[str, ...]:
    """State labels for [q, q̇] (eq. 5.3): the dof labels followed by ``"d(<label>)/dt"``."""
    dof = tuple(str(s) for s in dof_labels)
    return dof + tuple(f"d({s})/dt" for s in dof)
