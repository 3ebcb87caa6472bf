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


#: Condition number of the mass matrix S1 above which a model is refused: the one singularity
#: rule of every state matrix.  The message tells a badly scaled S1 (a mass or inertia far
#: outside the others: the condition number of D^-1/2 S1 D^-1/2, D = |diag S1|, is below the
#: limit) from a singular one (a degree of freedom without independent inertia).
SINGULAR_CONDITION = 1e14

#: Largest magnitude of an entry of S1⁻¹S2, S1⁻¹S3, S1⁻¹S4 and of Ww, Wv, Wq (SI: 1/s, 1/s², …):
#: rates of about 1e25 rad/s, far beyond any structure, while the eigen-analysis (which forms
#: products of up to four roots) stays far from floating-point overflow.
RATE_LIMIT = 1e50

#: What each matrix of :class:`SecondOrder` is, for the messages.
ROLES = {"S1": "mass", "S2": "damping", "S3": "stiffness", "S4": "lag-state coupling",
         "Ww": "lag-state", "Wv": "lag-state rate coupling", "Wq": "lag-state coupling"}


class StateMatrixError(v.InputError):
    """A state matrix that cannot be built: names the matrix, the speed and the entry.

    matrix: "S1" … "Wq", or "S1^-1 S3" (etc.) for the solved blocks; index: speed index;
    row, col: labels of the offending entry's state (degree of freedom or lag state).
    Models catch it to name the model parameter behind the entry.
    """

    def __init__(self, message: str, matrix: str, index: int, row: str, col: str,
                 also: tuple[tuple[str, str], ...] = ()) -> None:
        super().__init__(message)
        self.matrix, self.index, self.row, self.col = matrix, index, row, col
        #: further suspect entries (row, col), e.g. both ends of a badly scaled diagonal
        self.entries = ((row, col),) + tuple(also)


def _where(V, t: int) -> str:
    """'V = … m/s' of stack index t (or 'index t' without speeds), for error messages."""
    if V is None:
        return f"index {t}"
    Va = np.atleast_1d(np.asarray(V, dtype=float))
    return f"V = {float(Va[min(t, Va.size - 1)])!r} m/s"


def _axes(sys: SecondOrder, name: str) -> tuple[tuple[str, ...], tuple[str, ...]]:
    """Row and column labels of matrix `name` of `sys`."""
    q, w = sys.q_labels, sys.w_labels
    return {"S1": (q, q), "S2": (q, q), "S3": (q, q), "S4": (q, w), "Ww": (w, w),
            "Wv": (w, q), "Wq": (w, q)}[name]


def check_finite(name: str, arr: np.ndarray, V: np.ndarray | None,
                 rows: tuple[str, ...] = (), cols: tuple[str, ...] = ()) -> None:
    """Raise :class:`StateMatrixError` naming the matrix, the first speed where it is not
    finite and the entry (by its row and column labels when given)."""
    finite = np.isfinite(arr)
    if finite.all():
        return
    t, r, c = (int(i) for i in np.argwhere(~finite)[0])
    lab = lambda labels, i: labels[i] if i < len(labels) else f"{i}"  # noqa: E731
    role = ROLES.get(name, "")
    raise StateMatrixError(
        f"the {role + ' matrix ' if role else ''}{name} is not finite at {_where(V, t)} "
        f"(row {lab(rows, r)}, column {lab(cols, c)})", name, t, lab(rows, r), lab(cols, c))


def check_system(sys: SecondOrder, V: np.ndarray | None = None) -> None:
    """Every matrix of `sys` finite (:func:`check_finite`, entries named by their states)."""
    for name in ROLES:
        check_finite(name, getattr(sys, name), V, *_axes(sys, name))


def _check_mass(sys: SecondOrder, V) -> None:
    """The singularity rule (:data:`SINGULAR_CONDITION`), badly scaled told from singular."""
    with np.errstate(all="ignore"):
        cond = np.linalg.cond(sys.S1)
    bad = ~(cond <= SINGULAR_CONDITION)
    if not bad.any():
        return
    t = int(np.argmax(bad))
    S1, labels = sys.S1[t], sys.q_labels
    d = np.abs(np.diag(S1))
    hi, lo = int(np.argmax(d)), int(np.argmin(d))
    head = "the mass matrix (structural plus aerodynamic, S1) is"
    where = f"at {_where(V, t)} (condition number {cond[t]:.3g} > {SINGULAR_CONDITION:.0e})"
    if d[lo] > 0 and d[hi] / d[lo] > SINGULAR_CONDITION:
        raise StateMatrixError(
            f"{head} numerically singular {where} because it is badly scaled: its diagonal "
            f"spans {d[lo]:.3g} at {labels[lo]} to {d[hi]:.3g} at {labels[hi]} (SI units), a "
            "mass or inertia far outside the others", "S1", t, labels[hi], labels[hi],
            ((labels[lo], labels[lo]),))
    if d[lo] > 0:
        s = 1.0 / np.sqrt(d)
        try:
            with np.errstate(all="ignore"):
                null = np.linalg.svd(s[:, None] * S1 * s[None, :])[2][-1] * s
        except np.linalg.LinAlgError:
            null = (np.arange(d.size) == lo).astype(float)
    else:
        null = (d == 0).astype(float)
    share = np.abs(null) / np.max(np.abs(null))
    dofs = [labels[i] for i in np.argsort(-share, kind="stable")[:3] if share[i] > 0.1]
    raise StateMatrixError(
        f"{head} singular {where}: {', '.join(dofs)} {'has' if len(dofs) == 1 else 'have'} "
        "no independent inertia (a zero mass or inertia?)", "S1", t, dofs[0], dofs[0])


def _check_solved(sys: SecondOrder, X: np.ndarray, V) -> None:
    """Every solved block and lag-state matrix finite and within :data:`RATE_LIMIT`; the
    error names the entry of S2/S3/S4 (or W) that feeds the offending one."""
    n = sys.n_dof
    q, w = sys.q_labels, sys.w_labels
    for name, block, src, rows, cols in (
            ("S1^-1 S3", X[..., :n], sys.S3, q, q), ("S1^-1 S2", X[..., n:2 * n], sys.S2, q, q),
            ("S1^-1 S4", X[..., 2 * n:], sys.S4, q, w), ("Ww", sys.Ww, None, w, w),
            ("Wv", sys.Wv, None, w, q), ("Wq", sys.Wq, None, w, q)):
        big = ~(np.abs(block) <= RATE_LIMIT)
        if not big.any():
            continue
        t, r, c = (int(i) for i in np.argwhere(big)[0])
        feed = ""
        if src is not None:   # the entry of S2/S3/S4 in column c largest against its mass
            with np.errstate(all="ignore"):
                ratio = np.abs(src[t, :, c]) / np.abs(np.diagonal(sys.S1[t]))
            k = int(np.argmax(np.where(np.isnan(ratio), np.inf, ratio)))
            feed = f", fed by {name.split()[-1]} at row {rows[k]}"
            r = k
        raise StateMatrixError(
            f"{name} reaches {float(block[t, int(np.argwhere(big)[0][1]), c]):.3g} (SI) at "
            f"{_where(V, t)} (column {cols[c]}{feed}), beyond {RATE_LIMIT:.0e}: a stiffness, "
            "damping or mass far outside the others", name, t, rows[r], cols[c])


def state_matrix(sys: SecondOrder, V: np.ndarray | None = None, *,
                 finite_checked: bool = False) -> np.ndarray:
    """The state matrix A(V) (nV, 2n+m, 2n+m) of x = [q, q̇, w] (eq. 5.4, 7.59, D.27).

    The one builder of every model's A: ``A = [[0, I, 0], [−S1⁻¹S3, −S1⁻¹S2, S1⁻¹S4],
    [Wq, Wv, Ww]]``, S1 solved once per speed.  Non-finite matrices, a mass matrix S1 with
    condition number above :data:`SINGULAR_CONDITION` (badly scaled or singular) and solved
    blocks beyond :data:`RATE_LIMIT` raise :class:`StateMatrixError` (an InputError) naming
    the speed ``V`` [m/s] (optional; only used in the messages) and the entry's states.
    ``finite_checked``: the caller has already passed `sys` through :func:`check_system`
    (a model's ``second_order`` does), so it is not checked twice.
    """
    n, m = sys.n_dof, sys.n_lag
    nV = sys.S1.shape[0]
    if not finite_checked:
        check_system(sys, V)
    rhs = np.concatenate([sys.S3, sys.S2, sys.S4], axis=-1)
    _check_mass(sys, V)
    with np.errstate(all="ignore"):
        X = np.linalg.solve(sys.S1, rhs)
    _check_solved(sys, X, V)
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
