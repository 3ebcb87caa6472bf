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


def rate_label(label: str) -> str:
    """Label of the rate of a displacement state: ``"d/dt " + label`` (the one rule).

    >>> rate_label("node 3 h")
    'd/dt node 3 h'
    """
    return f"d/dt {label}"


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


#: Condition number of the mass matrix S1 above which a model is refused as singular (a DOF
#: without inertia): the one singularity rule of every state matrix.
SINGULAR_CONDITION = 1e14


def _where(V, t: int) -> str:
    """'V = … m/s' of stack index t (or 'index t' without speeds), for error messages."""
    if V is None:
        return f"index {t}"
    Va = np.atleast_1d(np.asarray(V, dtype=float))
    return f"V = {float(Va[min(t, Va.size - 1)])!r} m/s"


def check_finite(name: str, arr: np.ndarray, V: np.ndarray | None) -> None:
    """Raise InputError naming the matrix and the first speed where it is not finite."""
    bad = ~np.isfinite(arr).reshape(arr.shape[0], -1).all(axis=1)
    if bad.any():
        raise v.InputError(
            f"{name} has non-finite entries at {_where(V, int(np.argmax(bad)))}: "
            "check the model parameters feeding it (e.g. a zero semichord, radius or speed)"
        )


def state_matrix(sys: SecondOrder, V: np.ndarray | None = None) -> np.ndarray:
    """The state matrix A(V) (nV, 2n+m, 2n+m) of x = [q, q̇, w] (eq. 5.4, 7.59, D.27).

    The one builder of every model's A: ``A = [[0, I, 0], [−S1⁻¹S3, −S1⁻¹S2, S1⁻¹S4],
    [Wq, Wv, Ww]]``, S1 solved once per speed.  Non-finite matrices and a mass matrix S1 with
    condition number above :data:`SINGULAR_CONDITION` raise :class:`InputError` naming the
    speed ``V`` [m/s] (optional; only used in the messages).
    """
    n, m = sys.n_dof, sys.n_lag
    nV = sys.S1.shape[0]
    for name in ("S1", "S2", "S3", "S4", "Ww", "Wv", "Wq"):
        check_finite(name, getattr(sys, name), V)
    rhs = np.concatenate([sys.S3, sys.S2, sys.S4], axis=-1)
    with np.errstate(all="ignore"):
        cond = np.linalg.cond(sys.S1)
    bad = ~(cond <= SINGULAR_CONDITION)
    if bad.any():
        t = int(np.argmax(bad))
        raise v.InputError(
            f"the mass matrix (structural plus aerodynamic, S1) is singular at {_where(V, t)} "
            f"(condition number {cond[t]:.3g} > {SINGULAR_CONDITION:.0e}): a degree of freedom "
            "has no inertia (zero mass or inertia?)"
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
    """State matrix J = [[0, I], [−M⁻¹K, −M⁻¹C]] of M q̈ + C q̇ + K q = 0 (eq. 5.4), vectorised.

    ``M, C, K``: ``(N, N)`` or stacks ``(T, N, N)`` (broadcast against each other).  ``V``
    [m/s] (optional, length T) is used only to name the speed in errors.  Built by
    :func:`state_matrix` (a system without lag states), so the same singularity rule applies.

    Examples
    --------
    >>> state_matrix_from_mck(2.0 * np.eye(1), np.zeros((1, 1)), 8.0 * np.eye(1))[0]
    array([[ 0.,  1.],
           [-4., -0.]])
    """
    M, C, K = (np.asarray(x, dtype=float) for x in (M, C, K))
    M, C, K = np.broadcast_arrays(*(x if x.ndim == 3 else x[None] for x in (M, C, K)))
    T, N = M.shape[0], M.shape[-1]
    sys = SecondOrder(M, C, K, np.zeros((T, N, 0)), np.zeros((T, 0, 0)), np.zeros((T, 0, N)),
                      np.zeros((T, 0, N)), tuple(f"q{i}" for i in range(N)), ())
    return state_matrix(sys, V)


def second_order_labels(dof_labels: Sequence[str]) -> tuple[str, ...]:
    """State labels of [q, q̇] (eq. 5.3): the DOF labels, then their rates (:func:`rate_label`).

    >>> second_order_labels(["h", "alpha"])
    ('h', 'alpha', 'd/dt h', 'd/dt alpha')
    """
    dof = tuple(str(s) for s in dof_labels)
    return dof + tuple(rate_label(s) for s in dof)
