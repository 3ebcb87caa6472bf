"""Stability engine (thesis chapter 5): eigen-analysis of ẋ = A(V) x along the airspeed.

The engine is model-agnostic.  A model supplies

* ``state_matrix(V) -> A`` — a callable, vectorised over a 1-D array of airspeeds V [m/s],
  returning the real first-order state matrices, shape ``(len(V), n, n)`` (eq. 5.3/5.4, 6.18,
  7.59, C.63, D.27);
* the state labels (``n`` strings) and which states are displacements: ``n_dof`` (the first
  ``n_dof`` states, eq. 5.7) or a boolean ``displacement`` mask.  Velocity states follow the
  displacements, aerodynamic lag states come last.

What is computed
----------------
:func:`sweep`
    Eigenvalues/eigenvectors along V with *mode tracking*: every eigenvalue branch is followed
    from speed to speed by an optimal (Hungarian, :func:`scipy.optimize.linear_sum_assignment`)
    assignment whose cost combines the complex MAC of the displacement part (eq. 5.14 in its
    Hermitian form, see :func:`mac`) with the distance of the candidate from the branch's
    trapezoidal prediction ``λ_b ≈ λ_a + ½(λ'_a + λ'_b) ΔV``, where ``λ' = dλ/dV = yᴴ A' x``
    comes from the left eigenvectors ``Y = X⁻¹`` and a forward finite difference of
    ``state_matrix``.  The speed step is bisected (down to ``min_step``) wherever the
    assignment is *ambiguous* — the best cost not clearly better than the runner-up, the MAC of
    the chosen match low, the chosen eigenvalue far from the prediction, or two eigenvalue
    paths predicted to approach each other inside the step (a veering or crossing).  A cubic
    Hermite check of Re λ(V) between samples (values and dλ/dV) inserts samples where a hump
    narrower than the step may hide an instability.  Intervals still ambiguous at
    ``min_step`` (or when the node budget runs out) are listed in ``Sweep.unresolved``.
:func:`critical_points`
    Every sign change of a tracked mode's real part, refined to ``xtol`` (default 1e-3 m/s)
    with eigenvalue-only evaluations: shifted inverse iteration at the Hermite-predicted
    eigenvalue (one LU factorisation + a few triangular solves instead of a full
    eigendecomposition) inside a safeguarded secant/bisection bracket.  Classified as flutter
    (complex pair) or divergence (real root through zero); onsets and recoveries; hump modes;
    benignity (eq. 5.13) by central difference; the critical (lowest onset) instability.
    Where a pair splits into (or merges from) real roots inside the bracket, a real root
    through zero is located as the sign change of det A(V) (only real roots change its sign).
:func:`analyse`
    Both, in one call.

Conventions
-----------
*Branches and mode ids.*  All ``n`` eigenvalues are tracked as ``n`` continuous branches, so
the count never changes.  A complex-conjugate pair occupies two branches; only the member with
``Im λ > 0`` is *physical* (reported); its conjugate partner branch is hidden while complex.
Real eigenvalues are always physical.  When a pair meets the real axis and splits into two
real roots (a divergence branch), **the branch that carried the physical (Im > 0) member keeps
the larger real root** (the less stable one) and the partner branch — until then hidden —
becomes physical with the smaller root.  When two real roots merge into a pair, **the branch
with the smaller id takes the member with Im > 0**.  So a mode id may own a real eigenvalue
(frequency 0, ζ = ±1) over some speed range.  Ids are given at the first speed: physical
oscillatory modes first by increasing frequency, then real roots by decreasing real part, then
the hidden conjugate partners in the order of their partners.  Default labels: ``"mode k"``
and ``"mode k'"`` for the partner of mode k.

*Frequency and damping* (eq. 5.5): f = |Im λ|/2π [Hz], ζ = −Re λ/|λ| (ζ = 0 where λ = 0).

*Identity through veering/crossing.*  A mode's identity is the analytic continuation of its
(eigenvalue, eigenvector) branch at the resolved step.  Pairs of complex eigenvalues whose
linearly predicted paths approach within the step are refined until the step resolves the
approach, so a veering is followed along its branch (the shape rotates) while a true crossing
(decoupled modes) keeps each shape.  A veering is resolved only down to ``min_step``; one
narrower than that is treated like a crossing.  Repeated eigenvalues (degenerate within
``degenerate_tol``) have no defined shape identity; they are tracked by eigenvalue.

The forward difference for dA/dV also evaluates ``state_matrix`` at V + 1e-6·max(V, 1 m/s)
(batched with V in one call), so the model must accept speeds just above the last one.

BLAS threads are limited to one inside every solve (:func:`threadpoolctl.threadpool_limits`).
Measured on the 2-core development machine: while other jobs loaded it, a 200×200 ``eig``
took 14.6 ms on one thread against 26.3 ms on two (300×300: 37 vs 90 ms); on the idle machine
the two were equal (14.0 vs 15.0 ms) but the inverse-iteration evaluation used by the
refinement took 1.0 ms on one thread against 3.9 ms on two (thread start-up on small BLAS-2
work).  Entering the limiter costs 2–5 ms, so a sweep enters it once.

Cost of one evaluation, random real 200×200 matrix, one thread: full ``eig`` 14 ms,
``eigvals`` 10 ms, the eigenvalue-only evaluation (complex LU 0.6 ms + triangular solves and
Rayleigh quotients) 1.0 ms.
"""
from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field, fields, replace
from typing import Any

import numpy as np
import scipy.linalg as sla
from scipy.integrate import solve_ivp
from scipy.optimize import linear_sum_assignment
from threadpoolctl import threadpool_limits

from propwhirl.validate import InputError, finite, in_range, increasing, integer_at_least, positive

StateMatrixFn = Callable[[np.ndarray], np.ndarray]

__all__ = [
    "TrackingOptions", "Sweep", "CriticalPoint", "Hump", "Criticals", "Analysis", "TimeResponse",
    "eigen", "eigenvalues", "single_thread_blas", "mac", "state_matrix_from_mck",
    "second_order_labels", "sweep", "critical_points", "analyse", "tracked_eigenvalue",
    "whirl_sense", "orbit_signed_area", "rotation_sign_from_gyroscopic", "content", "dominant",
    "time_response",
]


# ----------------------------------------------------------------------------------------------
# Eigen helpers, BLAS threads
# ----------------------------------------------------------------------------------------------
def single_thread_blas():
    """Context manager limiting BLAS/OpenMP to one thread (small dense eigenproblems)."""
    return threadpool_limits(limits=1)


def _as_square_stack(A, name: str = "A") -> np.ndarray:
    arr = np.asarray(A)
    if arr.ndim < 2 or arr.shape[-1] != arr.shape[-2]:
        raise InputError(f"{name} must be a square matrix or a stack of them, "
                         f"got shape {arr.shape}")
    if np.iscomplexobj(arr):
        raise InputError(f"{name} must be real (the state matrices of eq. 5.4 are real)")
    return finite(name, arr)


def eigen(A_stack) -> tuple[np.ndarray, np.ndarray]:
    """Eigenvalues ``(…, n)`` and unit right eigenvectors ``(…, n, n)`` (columns) of real matrices.

    Vectorised over leading axes; BLAS limited to one thread.  Complex-conjugate pairs are
    adjacent with the ``Im > 0`` member first and have exactly conjugate eigenvectors (LAPACK
    ``geev``).  Always returns complex arrays.
    """
    A = _as_square_stack(A_stack)
    with single_thread_blas():
        w, X = np.linalg.eig(A)
    return w.astype(complex), X.astype(complex)


def eigenvalues(A_stack) -> np.ndarray:
    """Eigenvalues only (cheaper than :func:`eigen`), complex, BLAS limited to one thread."""
    A = _as_square_stack(A_stack)
    with single_thread_blas():
        return np.linalg.eigvals(A).astype(complex)


def mac(phi1, phi2) -> np.ndarray:
    """Modal Assurance Criterion, eq. (5.14), in the Hermitian form valid for complex shapes.

    ``MAC = |φ1ᴴ φ2|² / ((φ1ᴴ φ1)(φ2ᴴ φ2))``, in [0, 1], 1 for any complex multiple.  The printed
    (5.14) uses the plain transpose, which is fine for real shapes but not for complex ones: it is
    complex in general, 0/0 for a circular whirl shape φ = (1, i) (φᵀφ = 0), and for φ2 = φ̄1 it
    equals |φ|⁴/|φᵀφ|² ≥ 1.  Vectors ``(n,)`` give a
    scalar, matrices ``(n, k1)``, ``(n, k2)`` (shapes in columns) give ``(k1, k2)``.  A zero
    vector gives MAC 0.
    """
    a = np.asarray(phi1, dtype=complex)
    b = np.asarray(phi2, dtype=complex)
    vec = a.ndim == 1 and b.ndim == 1
    a2 = a.reshape(a.shape[0], -1)
    b2 = b.reshape(b.shape[0], -1)
    if a2.shape[0] != b2.shape[0]:
        raise InputError(f"mac: vectors of different length {a2.shape[0]} and {b2.shape[0]}")
    num = np.abs(a2.conj().T @ b2) ** 2
    den = np.sum(np.abs(a2) ** 2, axis=0)[:, None] * np.sum(np.abs(b2) ** 2, axis=0)[None, :]
    out = np.divide(num, den, out=np.zeros_like(num), where=den > 0)
    return float(out[0, 0]) if vec else out


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


# ----------------------------------------------------------------------------------------------
# Options and state-matrix evaluation
# ----------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class TrackingOptions:
    """Tuning of the mode tracker (dimensionless unless stated).

    mac_min:          a match whose MAC is below this is ambiguous (step refined).
    cost_ratio:       a match whose cost exceeds this fraction of the runner-up's cost is
                      ambiguous.  Cost = (1 − MAC) + |λ_b − λ_pred| / s, s = max(|λ_a|, floor);
                      the correct continuation's cost → 0 as the step shrinks, a wrong one's
                      does not, so a relative test resolves even near-identical shapes.
    dist_max:         a match farther than this (relative to s) from its prediction is
                      ambiguous.
    approach_ratio:   two complex eigenvalues whose predicted paths come closer inside a step
                      than this fraction of their end separations mark the step ambiguous.
    min_step:         smallest speed step of the refinement [m/s].
    fd_rel:           relative finite-difference step for dA/dV (h = fd_rel·max(V, 1 m/s)).
    degenerate_tol:   eigenvalues closer than this (relative) are treated as repeated.
    zero_tol:         |Re λ| ≤ zero_tol·max(|λ|, floor) counts as neutral (no sign).
    max_nodes:        budget of speeds (grid + refinement); None → 20·len(grid) + 200.
    hump_check:       insert samples where the Hermite interpolant of Re λ changes sign
                      between samples of equal sign.
    """

    mac_min: float = 0.8
    cost_ratio: float = 0.5
    dist_max: float = 0.1
    approach_ratio: float = 0.5
    min_step: float = 0.01
    fd_rel: float = 1e-6
    degenerate_tol: float = 1e-7
    zero_tol: float = 1e-9
    max_nodes: int | None = None
    hump_check: bool = True

    def __post_init__(self) -> None:
        in_range("mac_min", self.mac_min, 0.0, 1.0)
        in_range("cost_ratio", self.cost_ratio, 0.0, 1.0, low_open=True)
        positive("dist_max", self.dist_max)
        in_range("approach_ratio", self.approach_ratio, 0.0, 1.0)
        positive("min_step", self.min_step, "m/s")
        in_range("fd_rel", self.fd_rel, 0.0, 1e-2, low_open=True)
        in_range("degenerate_tol", self.degenerate_tol, 0.0, 1e-2)
        in_range("zero_tol", self.zero_tol, 0.0, 1e-3)
        if self.max_nodes is not None:
            integer_at_least("max_nodes", self.max_nodes, 2)


def _check_speeds(speeds) -> np.ndarray:
    V = increasing("speeds", speeds, "m/s")
    if V[0] <= 0:
        raise InputError(
            f"speeds[0] = {float(V[0])!r} m/s is invalid: must be > 0 (the aerodynamic matrices "
            f"carry 1/V; start the sweep at a small positive speed, e.g. 0.1 m/s)")
    return V


def _call_state_matrix(fn: StateMatrixFn, V: np.ndarray, n: int | None,
                       labels: Sequence[str] | None) -> np.ndarray:
    """Evaluate ``fn(V)`` and check shape, realness and finiteness, naming the speed."""
    A = np.asarray(fn(np.asarray(V, dtype=float)))
    if A.ndim != 3 or A.shape[0] != V.size or A.shape[1] != A.shape[2] or (
            n is not None and A.shape[1] != n):
        want = f"({V.size}, n, n)" if n is None else f"({V.size}, {n}, {n})"
        raise InputError(f"state_matrix(V) must return shape {want} for {V.size} speeds, "
                         f"got {A.shape}")
    if np.iscomplexobj(A):
        if np.any(A.imag != 0):
            t = int(np.argwhere(A.imag != 0)[0][0])
            raise InputError(f"state matrix is complex at V = {float(V[t])!r} m/s: must be real")
        A = A.real
    A = A.astype(float, copy=False)
    bad = ~np.isfinite(A)
    if bad.any():
        t, r, c = (int(i) for i in np.argwhere(bad)[0])
        lr = f" ({labels[r]})" if labels is not None else ""
        lc = f" ({labels[c]})" if labels is not None else ""
        raise InputError(
            f"state matrix has a non-finite entry {float(A[t, r, c])!r} at "
            f"V = {float(V[t])!r} m/s, row {r}{lr}, "
            f"column {c}{lc}: check the model parameters that enter it at this speed")
    return A


@dataclass
class _Node:
    """Raw eigen-solution at one speed (LAPACK order)."""

    V: float
    lam: np.ndarray    # (n,) complex
    X: np.ndarray      # (n, n) complex, unit columns
    dlam: np.ndarray   # (n,) complex, dλ/dV [1/m]
    conj: np.ndarray   # (n,) int, index of the conjugate (itself if real)
    floor: float       # scale floor for relative distances [1/s]


def _conj_index(w: np.ndarray) -> np.ndarray:
    """Index of each eigenvalue's conjugate (LAPACK puts pairs adjacent, Im > 0 first)."""
    m, n = w.shape
    idx = np.broadcast_to(np.arange(n), (m, n)).copy()
    idx[w.imag > 0] += 1
    idx[w.imag < 0] -= 1
    np.clip(idx, 0, n - 1, out=idx)
    ok = np.take_along_axis(w, idx, axis=1) == w.conj()
    if not ok.all():  # not LAPACK order: nearest conjugate
        for t in np.nonzero(~ok.all(axis=1))[0]:
            d = np.abs(w[t][:, None] - w[t].conj()[None, :])
            np.fill_diagonal(d, np.where(w[t].imag == 0, -1.0, np.inf))
            idx[t] = np.argmin(d, axis=1)
    return idx


def _eig_derivative(X: np.ndarray, dA: np.ndarray) -> np.ndarray:
    """dλ_k/dV = (X⁻¹ A' X)_kk for a stack; non-finite (defective X) → 0."""
    try:
        Y = np.linalg.inv(X)
    except np.linalg.LinAlgError:
        Y = np.linalg.pinv(X)
    with np.errstate(all="ignore"):
        d = np.einsum("tkm,tmk->tk", Y @ dA, X)
    d[~np.isfinite(d)] = 0.0
    return d


def _evaluate_nodes(fn: StateMatrixFn, V: np.ndarray, n: int | None,
                    labels: Sequence[str] | None, opts: TrackingOptions,
                    stats: dict[str, int]) -> list[_Node]:
    """Full eigen-solutions at the speeds V (one vectorised model call, one stacked eig)."""
    V = np.asarray(V, dtype=float)
    h = opts.fd_rel * np.maximum(V, 1.0)
    A_all = _call_state_matrix(fn, np.concatenate([V, V + h]), n, labels)
    A, Ah = A_all[: V.size], A_all[V.size:]
    w, X = np.linalg.eig(A)
    w, X = w.astype(complex), X.astype(complex)
    dlam = _eig_derivative(X, (Ah - A) / h[:, None, None])
    conj = _conj_index(w)
    mag = np.abs(w)
    floor = np.maximum(1e-3 * np.median(mag, axis=1), 1e-12)
    stats["eig"] = stats.get("eig", 0) + V.size
    stats["state_matrix_calls"] = stats.get("state_matrix_calls", 0) + 1
    return [_Node(float(V[t]), w[t], X[t], dlam[t], conj[t], float(floor[t]))
            for t in range(V.size)]


# ----------------------------------------------------------------------------------------------
# Linking consecutive speeds
# ----------------------------------------------------------------------------------------------
def _mac_matrix(Xa: np.ndarray, Xb: np.ndarray, disp: np.ndarray) -> np.ndarray:
    """MAC between all columns, on the displacement rows; full vectors where those vanish."""
    Pa, Pb = Xa[disp], Xb[disp]
    na = np.sum(np.abs(Pa) ** 2, axis=0)
    nb = np.sum(np.abs(Pb) ** 2, axis=0)
    m = np.abs(Pa.conj().T @ Pb) ** 2
    den = na[:, None] * nb[None, :]
    m = np.divide(m, den, out=np.zeros_like(m), where=den > 0)
    small_a, small_b = na < 1e-10, nb < 1e-10
    if small_a.any() or small_b.any():
        full = np.abs(Xa.conj().T @ Xb) ** 2 / (
            np.sum(np.abs(Xa) ** 2, axis=0)[:, None] * np.sum(np.abs(Xb) ** 2, axis=0)[None, :])
        use = small_a[:, None] | small_b[None, :]
        m = np.where(use, full, m)
    return m


def _near(lam: np.ndarray, conj: np.ndarray, scale: np.ndarray, tol: float) -> np.ndarray:
    """True where another eigenvalue (not the conjugate) lies within tol·scale."""
    n = lam.size
    d = np.abs(lam[:, None] - lam[None, :])
    d[np.arange(n), np.arange(n)] = np.inf
    d[np.arange(n), conj] = np.inf
    return np.any(d <= tol * scale[:, None], axis=1)


def _link(a: _Node, b: _Node, disp: np.ndarray, opts: TrackingOptions) -> tuple[np.ndarray, bool]:
    """Optimal assignment raw(a) → raw(b) and whether it is ambiguous (see TrackingOptions)."""
    n = a.lam.size
    ar = np.arange(n)
    h = b.V - a.V
    scale = np.maximum(np.abs(a.lam), a.floor)
    macm = _mac_matrix(a.X, b.X, disp)
    dlam = b.lam[None, :] - a.lam[:, None]
    trap = np.abs(dlam - 0.5 * (a.dlam[:, None] + b.dlam[None, :]) * h)
    dist = np.minimum(trap, np.abs(dlam)) / scale[:, None]
    cost = (1.0 - macm) + dist
    _, perm = linear_sum_assignment(cost)
    if n == 1:
        return perm, bool(dist[0, 0] > opts.dist_max)
    inv = np.empty(n, dtype=int)
    inv[perm] = ar
    c0 = cost[ar, perm]
    # runner-up in the row (other candidates for branch i) and the column (other branches for
    # candidate j), excluding the harmless alternatives: the conjugate of the chosen
    # candidate and whatever the conjugate partner branch took (real-axis events).
    row = cost.copy()
    for cols in (perm, b.conj[perm], perm[a.conj]):
        row[ar, cols] = np.inf
    col = cost[:, perm].T.copy()          # col[i, r] = cost[r, perm[i]]
    for rows in (ar, a.conj, inv[b.conj[perm]]):
        col[ar, rows] = np.inf
    alt = np.minimum(row.min(axis=1), col.min(axis=1))
    shape_free = _near(a.lam, a.conj, scale, opts.degenerate_tol) & _near(
        b.lam, b.conj, np.maximum(np.abs(b.lam), b.floor), opts.degenerate_tol)[perm]
    amb = ((~shape_free & ((c0 > opts.cost_ratio * alt) | (macm[ar, perm] < opts.mac_min)))
           | (dist[ar, perm] > opts.dist_max))
    return perm, bool(amb.any() or _approach(a, b, perm, opts))


def _approach(a: _Node, b: _Node, perm: np.ndarray, opts: TrackingOptions) -> bool:
    """Do two complex eigenvalues' predicted paths approach each other inside the step?

    For physical complex branches i, k with paths λ_i + λ'_i s, s ∈ [0, h], the closest approach
    m at an interior s* flags the step when m < approach_ratio · min(separation at a, at b):
    the step does not resolve a veering or crossing there.
    """
    up = np.nonzero(a.lam.imag > 0)[0]
    if up.size < 2:
        return False
    h = b.V - a.V
    lam, d = a.lam[up], a.dlam[up]
    r0 = lam[:, None] - lam[None, :]
    rd = d[:, None] - d[None, :]
    rd2 = np.abs(rd) ** 2
    with np.errstate(all="ignore"):
        s = np.where(rd2 > 0, -np.real(r0.conj() * rd) / rd2, 0.0)
    interior = (s > 0) & (s < h)
    m = np.abs(r0 + rd * np.clip(s, 0, h))
    lb = b.lam[perm[up]]
    eb = np.abs(lb[:, None] - lb[None, :])
    flag = interior & (m < opts.approach_ratio * np.minimum(np.abs(r0), eb))
    np.fill_diagonal(flag, False)
    return bool(flag.any())


# ----------------------------------------------------------------------------------------------
# Ordering the chain of nodes into branches
# ----------------------------------------------------------------------------------------------
def _initial_order(node: _Node) -> tuple[np.ndarray, np.ndarray, int]:
    """Raw indices in branch order at the first speed, partner ids, number of physical modes."""
    lam = node.lam
    phys = np.nonzero(lam.imag >= 0)[0]
    osc = phys[lam[phys].imag > 0]
    real = phys[lam[phys].imag == 0]
    osc = osc[np.lexsort((lam[osc].real, lam[osc].imag))]
    real = real[np.argsort(-lam[real].real, kind="stable")]
    first = np.concatenate([osc, real])
    hidden = node.conj[osc]
    order = np.concatenate([first, hidden]).astype(int)
    n = lam.size
    partner = np.full(n, -1, dtype=int)
    k_osc = np.arange(osc.size)
    k_hid = first.size + np.arange(osc.size)
    partner[k_osc] = k_hid
    partner[k_hid] = k_osc
    return order, partner, first.size


def _order_chain(nodes: list[_Node], perms: list[np.ndarray]) -> np.ndarray:
    """R[t, k] = raw index of branch k at node t, with the real-axis conventions applied."""
    T = len(nodes)
    n = nodes[0].lam.size
    R = np.empty((T, n), dtype=int)
    R[0] = _initial_order(nodes[0])[0]
    for t in range(1, T):
        R[t] = perms[t - 1][R[t - 1]]
    for t in range(1, T):
        _canonical_events(nodes[t - 1], nodes[t], R, t)
    return R


def _canonical_events(prev: _Node, cur: _Node, R: np.ndarray, t: int) -> None:
    """Apply the split/merge conventions at node t (swap branch columns of R[t:])."""
    n = R.shape[1]
    inv_prev = np.empty(n, dtype=int)
    inv_prev[R[t - 1]] = np.arange(n)
    lp = prev.lam[R[t - 1]]
    # split: pair (k upper, k') at t-1 -> both real at t; k keeps the larger root
    for k in np.nonzero(lp.imag > 0)[0]:
        kp = inv_prev[prev.conj[R[t - 1, k]]]
        lk, lkp = cur.lam[R[t, k]], cur.lam[R[t, kp]]
        if lk.imag == 0 and lkp.imag == 0 and lk.real < lkp.real:
            R[t:, [k, kp]] = R[t:, [kp, k]]
    # merge: two reals at t-1 -> conjugate pair at t; the smaller id takes Im > 0
    inv_cur = np.empty(n, dtype=int)
    inv_cur[R[t]] = np.arange(n)
    lc = cur.lam[R[t]]
    for k in np.nonzero(lc.imag < 0)[0]:
        kp = inv_cur[cur.conj[R[t, k]]]
        if k < kp and lp[k].imag == 0 and lp[kp].imag == 0:
            R[t:, [k, kp]] = R[t:, [kp, k]]
            inv_cur[R[t]] = np.arange(n)


def _hermite_coeffs(fa, fb, ga, gb, h):
    """Cubic p(s) = c0 + c1 s + c2 s² + c3 s³ on s ∈ [0, 1] with p, p' matching (h = ΔV)."""
    c0, c1 = fa, ga * h
    c2 = 3 * (fb - fa) - (2 * ga + gb) * h
    c3 = 2 * (fa - fb) + (ga + gb) * h
    return c0, c1, c2, c3


def _hermite_eval(c, s):
    c0, c1, c2, c3 = c
    return c0 + s * (c1 + s * (c2 + s * c3))


def _hump_candidates(V: np.ndarray, lam: np.ndarray, dlam: np.ndarray, floor: np.ndarray,
                     opts: TrackingOptions) -> list[float]:
    """Speeds where the Hermite interpolant of Re λ changes sign between equal-sign samples."""
    h = np.diff(V)[:, None]
    f = lam.real
    g = dlam.real
    tol = opts.zero_tol * np.maximum(np.abs(lam), floor[:, None])
    sgn = np.where(np.abs(f) <= tol, 0, np.sign(f))
    phys = lam.imag >= 0
    ok = (phys[:-1] & phys[1:] & (sgn[:-1] == sgn[1:]) & (sgn[:-1] != 0)
          & (h >= 2 * opts.min_step))
    c = _hermite_coeffs(f[:-1], f[1:], g[:-1], g[1:], h)
    # stationary points: c1 + 2 c2 s + 3 c3 s² = 0
    A, B, C = 3 * c[3], 2 * c[2], c[1]
    disc = B * B - 4 * A * C
    sq = np.sqrt(np.maximum(disc, 0.0))
    with np.errstate(all="ignore"):
        s1 = np.where(np.abs(A) > 1e-300, (-B + sq) / (2 * A), -C / B)
        s2 = np.where(np.abs(A) > 1e-300, (-B - sq) / (2 * A), -C / B)
    best_s = np.full(f[:-1].shape, np.nan)
    best_v = np.zeros(f[:-1].shape)
    for s in (s1, s2):
        valid = ok & (disc >= 0) & np.isfinite(s) & (s > 0) & (s < 1)
        p = _hermite_eval(c, np.where(valid, s, 0.5))
        tol_mid = np.maximum(tol[:-1], tol[1:])
        viol = valid & (p * sgn[:-1] < -tol_mid)
        better = viol & (np.abs(p) > best_v)
        best_s = np.where(better, s, best_s)
        best_v = np.where(better, np.abs(p), best_v)
    out = {}
    for t, k in zip(*np.nonzero(np.isfinite(best_s))):
        s = float(np.clip(best_s[t, k], 0.05, 0.95))
        out.setdefault(int(t), V[t] + s * (V[t + 1] - V[t]))
    return sorted(out.values())


# ----------------------------------------------------------------------------------------------
# Results
# ----------------------------------------------------------------------------------------------
def _c2d(z: np.ndarray) -> dict[str, Any]:
    z = np.asarray(z)
    return {"re": z.real.tolist(), "im": z.imag.tolist()}


def _d2c(d: Mapping[str, Any]) -> np.ndarray:
    return np.asarray(d["re"], dtype=float) + 1j * np.asarray(d["im"], dtype=float)


@dataclass(frozen=True)
class Sweep:
    """Tracked eigen-solutions along the airspeed.

    Column ``k`` of every ``(T, n)`` array is mode (branch) ``k``; ``physical[t, k]`` says whether
    it is reported at speed ``V[t]`` (Im λ ≥ 0; see the module docstring).

    V:            (T,) speeds [m/s], the grid plus refinement points, increasing.
    eigenvalues:  (T, n) complex λ [1/s].
    eigenvectors: (T, n, n) complex, ``[t, :, k]`` the unit right eigenvector of mode k, phase
                  aligned along V (first speed: largest displacement entry real positive);
                  None when re-read from a dict saved without them.  Memory: T·n²·16 bytes
                  (100 speeds × 300 states ≈ 144 MB).
    dlam_dV:      (T, n) complex dλ/dV [1/m].
    physical:     (T, n) bool.
    state_labels: n state labels; displacement: (n,) bool mask of displacement states.
    mode_labels:  n mode labels; partner: (n,) id of the conjugate partner branch (−1 if none).
    grid:         the speeds asked for [m/s].
    floor:        (T,) scale floor of |λ| used for relative tolerances [1/s].
    unresolved:   speed intervals [m/s] left ambiguous at ``min_step`` or the node budget.
    stats:        counters (eig, state_matrix_calls, nodes, refined).
    """

    V: np.ndarray
    eigenvalues: np.ndarray
    eigenvectors: np.ndarray | None
    dlam_dV: np.ndarray
    physical: np.ndarray
    state_labels: tuple[str, ...]
    displacement: np.ndarray
    mode_labels: tuple[str, ...]
    partner: np.ndarray
    grid: np.ndarray
    floor: np.ndarray
    unresolved: tuple[tuple[float, float], ...] = ()
    stats: Mapping[str, int] = field(default_factory=dict)

    @property
    def n_modes(self) -> int:
        return self.eigenvalues.shape[1]

    @property
    def frequency_hz(self) -> np.ndarray:
        """f = |Im λ| / 2π [Hz]."""
        return np.abs(self.eigenvalues.imag) / (2 * np.pi)

    @property
    def damping_ratio(self) -> np.ndarray:
        """ζ = −Re λ / |λ| (eq. 5.5); 0 where λ = 0."""
        mag = np.abs(self.eigenvalues)
        return np.divide(-self.eigenvalues.real, mag, out=np.zeros_like(mag), where=mag > 0)

    def mode_shape(self, mode: int, t: int) -> np.ndarray:
        """Displacement part x̂ of mode ``mode`` at speed index ``t`` (eq. 5.7)."""
        if self.eigenvectors is None:
            raise InputError("this Sweep was saved without eigenvectors")
        return self.eigenvectors[t, self.displacement, mode]

    def relabel(self, labels: Sequence[str] | Callable[[complex, np.ndarray], str]) -> "Sweep":
        """New Sweep with mode labels: a sequence of n strings or f(λ, eigenvector) at V[0]."""
        if callable(labels):
            if self.eigenvectors is None:
                raise InputError("labelling by shape needs the eigenvectors")
            labels = [labels(self.eigenvalues[0, k], self.eigenvectors[0, :, k])
                      for k in range(self.n_modes)]
        labels = tuple(str(s) for s in labels)
        if len(labels) != self.n_modes:
            raise InputError(f"mode labels: got {len(labels)}, need {self.n_modes}")
        return replace(self, mode_labels=labels)

    def table(self) -> dict[str, np.ndarray]:
        """Tidy columns of the physical modes, sorted by V then mode id.

        V [m/s], mode, label, frequency_hz [Hz], damping_ratio (5.5), real, imag [1/s].
        """
        t, k = np.nonzero(self.physical)
        lam = self.eigenvalues[t, k]
        return {
            "V": self.V[t], "mode": k, "label": np.asarray(self.mode_labels, dtype=object)[k],
            "frequency_hz": self.frequency_hz[t, k], "damping_ratio": self.damping_ratio[t, k],
            "real": lam.real, "imag": lam.imag,
        }

    def to_dict(self, include_eigenvectors: bool = True) -> dict[str, Any]:
        """JSON-able dict (complex arrays as {"re", "im"})."""
        d: dict[str, Any] = {
            "V": self.V.tolist(), "eigenvalues": _c2d(self.eigenvalues),
            "dlam_dV": _c2d(self.dlam_dV), "physical": self.physical.tolist(),
            "state_labels": list(self.state_labels), "displacement": self.displacement.tolist(),
            "mode_labels": list(self.mode_labels), "partner": self.partner.tolist(),
            "grid": self.grid.tolist(), "floor": self.floor.tolist(),
            "unresolved": [list(u) for u in self.unresolved], "stats": dict(self.stats),
        }
        if include_eigenvectors and self.eigenvectors is not None:
            d["eigenvectors"] = _c2d(self.eigenvectors)
        return d

    @classmethod
    def from_dict(cls, d: Mapping[str, Any]) -> "Sweep":
        lam = _d2c(d["eigenvalues"])
        X = _d2c(d["eigenvectors"]) if "eigenvectors" in d else None
        return cls(
            V=np.asarray(d["V"], dtype=float), eigenvalues=lam, eigenvectors=X,
            dlam_dV=_d2c(d["dlam_dV"]), physical=np.asarray(d["physical"], dtype=bool),
            state_labels=tuple(d["state_labels"]),
            displacement=np.asarray(d["displacement"], dtype=bool),
            mode_labels=tuple(d["mode_labels"]), partner=np.asarray(d["partner"], dtype=int),
            grid=np.asarray(d["grid"], dtype=float), floor=np.asarray(d["floor"], dtype=float),
            unresolved=tuple(tuple(u) for u in d["unresolved"]), stats=dict(d["stats"]),
        )


@dataclass(frozen=True)
class CriticalPoint:
    """A sign change of a tracked mode's real part.

    mode, label:   tracked mode id and label.
    kind:          "flutter" (complex pair, Im λ ≠ 0) or "divergence" (real root through 0).
    direction:     "onset" (Re λ − → +) or "recovery" (+ → −).
    V:             crossing speed [m/s] (bracket width ≤ xtol); bracket: (lo, hi) [m/s].
    frequency_hz:  |Im λ|/2π at V [Hz]; eigenvalue: λ at V [1/s].
    dzeta_dV:      dζ/dV at V [s/m] (central difference), None for divergence.
    benignity:     (dζ/dV)⁻¹ [m/s] (eq. 5.13), signed (negative at an onset); None for divergence.
    eigenvector:   full-state eigenvector at V (mode shape for plotting).
    """

    mode: int
    label: str
    kind: str
    direction: str
    V: float
    bracket: tuple[float, float]
    frequency_hz: float
    eigenvalue: complex
    dzeta_dV: float | None
    benignity: float | None
    eigenvector: np.ndarray

    def to_dict(self) -> dict[str, Any]:
        d = {f.name: getattr(self, f.name) for f in fields(self)}
        d["eigenvalue"] = {"re": self.eigenvalue.real, "im": self.eigenvalue.imag}
        d["eigenvector"] = _c2d(self.eigenvector)
        d["bracket"] = list(self.bracket)
        return d

    @classmethod
    def from_dict(cls, d: Mapping[str, Any]) -> "CriticalPoint":
        kw = dict(d)
        kw["eigenvalue"] = complex(d["eigenvalue"]["re"], d["eigenvalue"]["im"])
        kw["eigenvector"] = _d2c(d["eigenvector"])
        kw["bracket"] = tuple(d["bracket"])
        return cls(**kw)


@dataclass(frozen=True)
class Hump:
    """A mode that goes unstable at ``V_onset`` and recovers at ``V_recovery`` [m/s]."""

    mode: int
    label: str
    kind: str
    V_onset: float
    V_recovery: float


@dataclass(frozen=True)
class Criticals:
    """All crossings of a sweep (sorted by V), hump modes, modes unstable at the first speed."""

    points: tuple[CriticalPoint, ...]
    humps: tuple[Hump, ...]
    unstable_at_start: tuple[int, ...]
    stats: Mapping[str, int] = field(default_factory=dict)

    @property
    def critical(self) -> CriticalPoint | None:
        """The lowest-speed onset (the critical instability), or None."""
        on = [p for p in self.points if p.direction == "onset"]
        return min(on, key=lambda p: p.V) if on else None

    def summary(self) -> str:
        c = self.critical
        if c is None:
            return "no instability onset in the speed range"
        f = f", {c.frequency_hz:.3f} Hz" if c.kind == "flutter" else ""
        return f"critical: {c.kind} of {c.label} at {c.V:.2f} m/s{f}"

    def to_dict(self) -> dict[str, Any]:
        return {"points": [p.to_dict() for p in self.points],
                "humps": [vars(h).copy() for h in self.humps],
                "unstable_at_start": list(self.unstable_at_start), "stats": dict(self.stats)}

    @classmethod
    def from_dict(cls, d: Mapping[str, Any]) -> "Criticals":
        return cls(points=tuple(CriticalPoint.from_dict(p) for p in d["points"]),
                   humps=tuple(Hump(**h) for h in d["humps"]),
                   unstable_at_start=tuple(d["unstable_at_start"]), stats=dict(d["stats"]))


@dataclass(frozen=True)
class Analysis:
    """A sweep and its critical points."""

    sweep: Sweep
    criticals: Criticals

    def to_dict(self, include_eigenvectors: bool = True) -> dict[str, Any]:
        return {"sweep": self.sweep.to_dict(include_eigenvectors),
                "criticals": self.criticals.to_dict()}

    @classmethod
    def from_dict(cls, d: Mapping[str, Any]) -> "Analysis":
        return cls(Sweep.from_dict(d["sweep"]), Criticals.from_dict(d["criticals"]))


# ----------------------------------------------------------------------------------------------
# The sweep
# ----------------------------------------------------------------------------------------------
def _displacement_mask(n: int, n_dof, displacement) -> np.ndarray:
    if n_dof is not None and displacement is not None:
        raise InputError("give either n_dof or displacement, not both")
    if displacement is not None:
        mask = np.asarray(displacement)
        if mask.dtype != bool or mask.shape != (n,) or not mask.any():
            raise InputError(f"displacement must be a boolean mask of {n} states with at least "
                             f"one True, got {mask!r}")
        return mask.copy()
    mask = np.zeros(n, dtype=bool)
    if n_dof is None:
        mask[:] = True
    else:
        nd = integer_at_least("n_dof", n_dof, 1)
        if nd > n:
            raise InputError(f"n_dof = {nd} is invalid: must be <= the number of states {n}")
        mask[:nd] = True
    return mask


def sweep(state_matrix: StateMatrixFn, speeds, *, n_dof: int | None = None,
          displacement=None, state_labels: Sequence[str] | None = None,
          mode_labels: Sequence[str] | Callable[[complex, np.ndarray], str] | None = None,
          options: TrackingOptions | None = None) -> Sweep:
    """Eigen-analysis along the speeds with mode tracking (see the module docstring).

    speeds: increasing grid [m/s], all > 0 (the aerodynamic matrices carry 1/V); it is refined
    automatically where tracking is ambiguous and where a hump may hide between samples.
    """
    opts = options or TrackingOptions()
    grid = _check_speeds(speeds)
    labels = None if state_labels is None else tuple(str(s) for s in state_labels)
    with single_thread_blas():
        return _sweep(state_matrix, grid, n_dof, displacement, labels, mode_labels, opts)


def _sweep(fn, grid, n_dof, displacement, labels, mode_labels, opts) -> Sweep:
    stats: dict[str, int] = {}
    n = None if labels is None else len(labels)
    nodes = _evaluate_nodes(fn, grid, n, labels, opts, stats)
    n = nodes[0].lam.size
    if labels is None:
        labels = tuple(f"x{i}" for i in range(n))
    disp = _displacement_mask(n, n_dof, displacement)
    budget = opts.max_nodes or (20 * grid.size + 200)
    links: dict[tuple[float, float], tuple[np.ndarray, bool]] = {}
    refined = 0
    while True:
        new_V = []
        for a, b in zip(nodes[:-1], nodes[1:]):
            key = (a.V, b.V)
            if key in links:
                continue
            perm, amb = _link(a, b, disp, opts)
            if (amb and 0.5 * (b.V - a.V) >= opts.min_step
                    and len(nodes) + len(new_V) < budget):
                new_V.append(0.5 * (a.V + b.V))
                continue
            links[key] = (perm, amb)
        if not new_V:
            perms = [links[(a.V, b.V)][0] for a, b in zip(nodes[:-1], nodes[1:])]
            R = _order_chain(nodes, perms)
            if not opts.hump_check:
                break
            V = np.array([nd.V for nd in nodes])
            lam = np.stack([nd.lam[R[t]] for t, nd in enumerate(nodes)])
            dl = np.stack([nd.dlam[R[t]] for t, nd in enumerate(nodes)])
            fl = np.array([nd.floor for nd in nodes])
            new_V = _hump_candidates(V, lam, dl, fl, opts)
            new_V = new_V[: max(0, budget - len(nodes))]
            if not new_V:
                break
            stats["hump_refined"] = stats.get("hump_refined", 0) + len(new_V)
        else:
            refined += len(new_V)
        nodes = sorted(nodes + _evaluate_nodes(fn, np.array(new_V), n, labels, opts, stats),
                       key=lambda nd: nd.V)
    stats["refined"] = refined
    stats["nodes"] = len(nodes)
    unresolved = tuple((a.V, b.V) for a, b in zip(nodes[:-1], nodes[1:])
                       if links[(a.V, b.V)][1])
    return _assemble(nodes, R, grid, labels, disp, mode_labels, unresolved, stats)


def _assemble(nodes, R, grid, labels, disp, mode_labels, unresolved, stats) -> Sweep:
    T, n = R.shape
    V = np.array([nd.V for nd in nodes])
    lam = np.stack([nd.lam[R[t]] for t, nd in enumerate(nodes)])
    dl = np.stack([nd.dlam[R[t]] for t, nd in enumerate(nodes)])
    X = np.stack([nd.X[:, R[t]] for t, nd in enumerate(nodes)])
    # phase: first speed — largest displacement entry real positive; then aligned step by step
    P = X[0][disp]
    big = P[np.argmax(np.abs(P), axis=0), np.arange(n)]
    ph0 = np.where(np.abs(big) > 0, np.conj(big) / np.where(big == 0, 1, np.abs(big)), 1.0)
    inner = np.einsum("tik,tik->tk", X[:-1].conj(), X[1:])
    step = np.where(np.abs(inner) > 0, np.conj(inner) / np.where(inner == 0, 1, np.abs(inner)),
                    1.0)
    phase = np.concatenate([ph0[None], ph0[None] * np.cumprod(step, axis=0)], axis=0)
    X = X * phase[:, None, :]
    _, partner, n_phys = _initial_order(nodes[0])
    if mode_labels is None:
        ml = tuple(f"mode {k}" if k < n_phys else f"mode {partner[k]}'" for k in range(n))
    elif callable(mode_labels):
        ml = tuple(str(mode_labels(lam[0, k], X[0, :, k])) for k in range(n))
    else:
        ml = tuple(str(s) for s in mode_labels)
        if len(ml) != n:
            raise InputError(f"mode_labels: got {len(ml)}, need {n}")
    return Sweep(V=V, eigenvalues=lam, eigenvectors=X, dlam_dV=dl, physical=lam.imag >= 0,
                 state_labels=labels, displacement=disp, mode_labels=ml, partner=partner,
                 grid=grid, floor=np.array([nd.floor for nd in nodes]),
                 unresolved=unresolved, stats=dict(stats))


# ----------------------------------------------------------------------------------------------
# Eigenvalue-only evaluation of one tracked mode, and the critical points
# ----------------------------------------------------------------------------------------------
def _inverse_iteration(A: np.ndarray, sigma: complex, x0: np.ndarray, tol: float = 1e-13,
                       maxit: int = 40) -> tuple[complex, np.ndarray, bool]:
    """Shifted inverse iteration for the eigenvalue of A nearest σ (Rayleigh quotient).

    Real arithmetic when σ is real (divergence roots); the shift is updated to the Rayleigh
    quotient (one new LU) if convergence stalls.  Returns (λ, unit x, converged).
    """
    n = A.shape[0]
    use_real = sigma.imag == 0 and not np.iscomplexobj(x0)
    dt = float if use_real else complex
    normA = np.linalg.norm(A, 1)
    x = np.asarray(x0, dtype=dt)
    x = x / np.linalg.norm(x)
    shift = sigma.real if use_real else sigma
    lam = complex(shift)
    res = np.inf
    for attempt in range(3):
        Ms = A.astype(dt) - shift * np.eye(n)
        with np.errstate(all="ignore"):
            lu = sla.lu_factor(Ms, check_finite=False)
        if not np.all(np.isfinite(lu[0])) or np.any(np.diag(lu[0]) == 0):
            shift = shift + (1e-10 * max(abs(shift), 1.0))
            continue
        prev = np.inf
        for _ in range(maxit):
            y = sla.lu_solve(lu, x, check_finite=False)
            ny = np.linalg.norm(y)
            if not np.isfinite(ny) or ny == 0:
                break
            x = y / ny
            Ax = A @ x
            lam = complex(np.vdot(x, Ax))
            res = np.linalg.norm(Ax - lam * x)
            if res <= tol * max(normA, 1e-300):
                return lam, x, True
            if res > 0.5 * prev:      # stalled: refactor at the Rayleigh quotient
                break
            prev = res
        shift = lam.real if use_real else lam
    return lam, x, res <= 1e-8 * normA


def tracked_eigenvalue(state_matrix: StateMatrixFn, V: float, guess: complex,
                       shape: np.ndarray, *, n_dof: int | None = None, displacement=None,
                       mac_min: float = 0.5) -> tuple[complex, np.ndarray]:
    """Eigenvalue and eigenvector of the mode nearest ``guess`` at speed V [m/s] (no full eig).

    ``shape`` is a full-state vector of the mode (e.g. from a nearby speed): it starts the
    shifted inverse iteration and checks identity (MAC ≥ mac_min on the displacement part,
    else a full eigendecomposition picks the best match).
    """
    Vv = np.atleast_1d(positive("V", V, "m/s")).astype(float)
    if Vv.size != 1:
        raise InputError(f"V must be a single speed, got {Vv.size} values")
    with single_thread_blas():
        A = _call_state_matrix(state_matrix, Vv, None, None)[0]
        disp = _displacement_mask(A.shape[0], n_dof, displacement)
        lam, x, _ = _eval_mode(A, complex(guess), np.asarray(shape, dtype=complex), disp,
                               mac_min, {})
    return lam, x


def _eval_mode(A, sigma, x0, disp, mac_min, stats) -> tuple[complex, np.ndarray, bool]:
    """Tracked-mode evaluation: inverse iteration, verified, full-eig fallback."""
    x0r = x0
    if sigma.imag == 0:        # real root: real arithmetic with the phase-free real vector
        big = x0[np.argmax(np.abs(x0))]
        x0r = (x0 * (np.conj(big) / abs(big))).real if big != 0 else np.ones(x0.size)
    lam, x, ok = _inverse_iteration(A, sigma, x0r)
    stats["inverse_iterations"] = stats.get("inverse_iterations", 0) + 1
    if ok and mac(x0[disp], x[disp]) >= mac_min:
        return lam, x, False
    stats["fallback_eig"] = stats.get("fallback_eig", 0) + 1
    w, X = np.linalg.eig(A)
    w, X = w.astype(complex), X.astype(complex)
    m = mac(x0[disp][:, None], X[disp]).ravel()
    s = max(abs(sigma), 1e-12)
    j = int(np.argmin((1 - m) + np.abs(w - sigma) / s))
    return complex(w[j]), X[:, j], True


@dataclass
class _Bracket:
    """Hermite model of one tracked mode between two sweep samples."""

    Va: float
    Vb: float
    coeffs: tuple            # complex Hermite coefficients in s = (V − Va)/(Vb − Va)
    xa: np.ndarray
    xb: np.ndarray

    def predict(self, V: float) -> complex:
        s = (V - self.Va) / (self.Vb - self.Va)
        return complex(_hermite_eval(self.coeffs, s))

    def slope(self, V: float) -> float:
        h = self.Vb - self.Va
        s = (V - self.Va) / h
        c0, c1, c2, c3 = self.coeffs
        return float(np.real(c1 + 2 * c2 * s + 3 * c3 * s * s) / h)

    def shape(self, V: float) -> np.ndarray:
        s = float(np.clip((V - self.Va) / (self.Vb - self.Va), 0.0, 1.0))
        x = (1 - s) * self.xa + s * self.xb
        return x / np.linalg.norm(x)


class _ModeEvaluator:
    """Eigenvalue-only evaluations of one tracked mode (and det A), cached per speed."""

    def __init__(self, fn, br: _Bracket, disp, labels, stats, real_root: bool):
        self.fn, self.br, self.disp, self.labels, self.stats = fn, br, disp, labels, stats
        self.real_root = real_root
        self.cache: dict[float, tuple[complex, np.ndarray]] = {}
        self.mats: dict[float, np.ndarray] = {}

    def matrix(self, V: float) -> np.ndarray:
        if V not in self.mats:
            self.mats[V] = _call_state_matrix(self.fn, np.array([V]), self.br.xa.size,
                                              self.labels)[0]
            self.stats["state_matrix_calls"] = self.stats.get("state_matrix_calls", 0) + 1
        return self.mats[V]

    def __call__(self, V: float) -> tuple[complex, np.ndarray]:
        """The tracked eigenvalue (nearest the Hermite prediction, identity-checked)."""
        if V not in self.cache:
            sigma = self.br.predict(V)
            if self.real_root:
                sigma = complex(sigma.real, 0.0)
            lam, x, _ = _eval_mode(self.matrix(V), sigma, self.br.shape(V), self.disp, 0.5,
                                   self.stats)
            self.cache[V] = (lam, x)
        return self.cache[V]

    def logdet(self, V: float) -> tuple[float, float]:
        """(sign, log|det A|): the sign flips exactly when a real root crosses zero."""
        sign, ld = np.linalg.slogdet(self.matrix(V))
        return float(sign), float(ld)

    def zero_root(self, V: float) -> tuple[complex, np.ndarray]:
        """The real eigenvalue nearest zero and its eigenvector (divergence mode shape)."""
        x0 = self.br.shape(V)
        x0 = x0.real if np.linalg.norm(x0.real) > 1e-8 else np.ones(x0.size)
        lam, x, ok = _inverse_iteration(self.matrix(V), 0j, x0)
        self.stats["inverse_iterations"] = self.stats.get("inverse_iterations", 0) + 1
        if not ok:
            self.stats["fallback_eig"] = self.stats.get("fallback_eig", 0) + 1
            w, X = np.linalg.eig(self.matrix(V))
            j = int(np.argmin(np.abs(w) + np.where(w.imag == 0, 0.0, np.inf)))
            lam, x = complex(w[j]), X[:, j].astype(complex)
        return complex(lam), np.asarray(x, dtype=complex)


def _refine_root(f: Callable[[float], float], lo: float, hi: float, flo: float, fhi: float,
                 guess: float, slope: float, xtol: float) -> tuple[float, float, float]:
    """Bracket a sign change of f to width ≤ xtol starting from an accurate guess.

    Newton/secant steps that deliberately land just past the predicted root (so one accurate
    prediction closes the bracket in two evaluations), safeguarded by bisection.  Returns
    (V, lo, hi) with V the linear interpolation inside the final bracket.
    """
    x = float(np.clip(guess, lo + 0.25 * xtol, hi - 0.25 * xtol)) if hi - lo > xtol else lo
    xp = fp = None
    width = hi - lo
    stall = 0
    for _ in range(100):
        if hi - lo <= xtol:
            break
        fx = f(x)
        if fx == 0.0:
            return x, x, x
        if np.sign(fx) == np.sign(flo):
            lo, flo = x, fx
        else:
            hi, fhi = x, fx
        if hi - lo <= xtol:
            break
        if xp is not None and x != xp and fx != fp:
            slope = (fx - fp) / (x - xp)
        xp, fp = x, fx
        stall = stall + 1 if (hi - lo) > 0.5 * width else 0
        width = hi - lo
        r = x - fx / slope if slope not in (0.0,) and np.isfinite(slope) else np.nan
        cand = r + np.sign(r - x) * 0.45 * xtol if np.isfinite(r) else np.nan
        if stall >= 2 or not (lo < cand < hi):
            cand = 0.5 * (lo + hi)
            stall = 0
        x = float(cand)
    V = lo - flo * (hi - lo) / (fhi - flo) if fhi != flo else 0.5 * (lo + hi)
    return float(V), lo, hi


def critical_points(result: Sweep, state_matrix: StateMatrixFn, *, xtol: float = 1e-3,
                    benignity_step: float | None = None, zero_tol: float = 1e-9) -> Criticals:
    """Every sign change of a tracked mode's Re λ, refined to ``xtol`` [m/s].

    Eigenvalue-only: each evaluation is one state-matrix call and a shifted inverse iteration at
    the Hermite prediction of the mode (see :func:`_inverse_iteration`).  Flutter if Im λ ≠ 0 at
    the crossing, divergence if the root is real there.  Benignity (eq. 5.13) = (dζ/dV)⁻¹ by a
    central difference of step ``benignity_step`` (default max(1e-4·V, 1e-3) m/s).
    """
    positive("xtol", xtol, "m/s")
    if benignity_step is not None:
        positive("benignity_step", benignity_step, "m/s")
    with single_thread_blas():
        return _critical_points(result, state_matrix, xtol, benignity_step, zero_tol)


def _critical_points(res: Sweep, fn, xtol, bstep, zero_tol) -> Criticals:
    if res.eigenvectors is None:
        raise InputError("critical_points needs a Sweep with eigenvectors (to start the "
                         "inverse iterations); this one was saved without them")
    stats: dict[str, int] = {}
    lam, V = res.eigenvalues, res.V
    tol = zero_tol * np.maximum(np.abs(lam), res.floor[:, None])
    sgn = np.where(np.abs(lam.real) <= tol, 0, np.sign(lam.real)).astype(int)
    pts: list[CriticalPoint] = []
    for k in range(res.n_modes):
        idx = np.nonzero(sgn[:, k] != 0)[0]
        for t0, t1 in zip(idx[:-1], idx[1:]):
            if sgn[t0, k] == sgn[t1, k] or not res.physical[t0:t1 + 1, k].any():
                continue
            p = _refine_crossing(res, fn, k, int(t0), int(t1), xtol, bstep, stats)
            if p is not None:
                pts.append(p)
    pts.sort(key=lambda p: p.V)
    humps = []
    for k in range(res.n_modes):
        mine = [p for p in pts if p.mode == k]
        for p, q in zip(mine[:-1], mine[1:]):
            if p.direction == "onset" and q.direction == "recovery":
                humps.append(Hump(k, p.label, p.kind, p.V, q.V))
    start = tuple(int(k) for k in np.nonzero((sgn[0] > 0) & res.physical[0])[0])
    return Criticals(tuple(pts), tuple(humps), start, stats)


def _refine_crossing(res: Sweep, fn, k, t0, t1, xtol, bstep, stats) -> CriticalPoint | None:
    """Refine one sign change of Re λ of branch k between samples t0 < t1.

    * complex at both ends — a pair crossing: flutter, root of Re λ of the tracked mode
      (reported by the physical member only; None for the hidden conjugate);
    * real at both ends — a real root through zero: divergence, root of the tracked root;
    * complex at one end only — a pair splits into / merges from real roots inside the
      bracket.  If sign(det A) differs at the ends a real root crosses zero there: divergence,
      located as the root of det A(V) (exact, whichever root the branch owns after the split);
      otherwise the pair crossed while complex: flutter for the physical member, None for the
      hidden one.
    """
    la, lb = res.eigenvalues[t0, k], res.eigenvalues[t1, k]
    Va, Vb = float(res.V[t0]), float(res.V[t1])
    coeffs = _hermite_coeffs(la, lb, res.dlam_dV[t0, k], res.dlam_dV[t1, k], Vb - Va)
    br = _Bracket(Va, Vb, coeffs, res.eigenvectors[t0, :, k], res.eigenvectors[t1, :, k])
    both_phys = bool(res.physical[t0, k] and res.physical[t1, k])
    ca, cb = la.imag != 0, lb.imag != 0
    ev = _ModeEvaluator(fn, br, res.displacement, res.state_labels, stats,
                        real_root=not (ca or cb))
    if ca != cb:
        (sa, da), (sb, _) = ev.logdet(Va), ev.logdet(Vb)
        kind = "divergence" if sa != sb else "flutter"
    else:
        kind = "flutter" if ca else "divergence"
    if kind == "flutter" and not both_phys:
        return None
    direction = "onset" if lb.real > la.real else "recovery"
    if ca != cb and kind == "divergence":
        def f(Vq: float) -> float:
            sgn, ld = ev.logdet(Vq)
            return sgn * math.exp(min(ld - da, 700.0))
        fa, fb = f(Va), f(Vb)
        Vc, lo, hi = _refine_root(f, Va, Vb, fa, fb, 0.5 * (Va + Vb), (fb - fa) / (Vb - Va),
                                  xtol)
        lam_c, x_c = ev.zero_root(Vc)
    else:
        c = tuple(np.real(ci) for ci in coeffs)
        roots = np.roots([c[3], c[2], c[1], c[0]]) if any(ci != 0 for ci in c[1:]) else []
        roots = [r.real for r in np.atleast_1d(roots) if abs(r.imag) < 1e-12 and 0 <= r.real <= 1]
        s0 = roots[0] if roots else la.real / (la.real - lb.real)
        guess = Va + s0 * (Vb - Va)
        Vc, lo, hi = _refine_root(lambda Vq: ev(Vq)[0].real, Va, Vb, la.real, lb.real, guess,
                                  br.slope(guess), xtol)
        lam_c, x_c = ev(Vc)
    if lam_c.imag < 0:
        lam_c, x_c = lam_c.conjugate(), x_c.conj()
    dz = ben = None
    if kind == "flutter":
        h = bstep if bstep is not None else max(1e-4 * Vc, 1e-3)
        dz = (_zeta(ev(Vc + h)[0]) - _zeta(ev(Vc - h)[0])) / (2 * h)
        ben = 1.0 / dz if dz != 0 else None
    return CriticalPoint(mode=k, label=res.mode_labels[k], kind=kind, direction=direction,
                         V=Vc, bracket=(lo, hi), frequency_hz=abs(lam_c.imag) / (2 * np.pi),
                         eigenvalue=lam_c, dzeta_dV=dz, benignity=ben, eigenvector=x_c)


def _zeta(lam: complex) -> float:
    return -lam.real / abs(lam) if lam != 0 else 0.0


def analyse(state_matrix: StateMatrixFn, speeds, *, n_dof: int | None = None,
            displacement=None, state_labels: Sequence[str] | None = None,
            mode_labels=None, options: TrackingOptions | None = None,
            xtol: float = 1e-3, benignity_step: float | None = None) -> Analysis:
    """:func:`sweep` followed by :func:`critical_points` (one BLAS-limited context)."""
    opts = options or TrackingOptions()
    grid = _check_speeds(speeds)
    positive("xtol", xtol, "m/s")
    labels = None if state_labels is None else tuple(str(s) for s in state_labels)
    with single_thread_blas():
        sw = _sweep(state_matrix, grid, n_dof, displacement, labels, mode_labels, opts)
        cr = _critical_points(sw, state_matrix, xtol, benignity_step, opts.zero_tol)
    return Analysis(sw, cr)


# ----------------------------------------------------------------------------------------------
# Mode labels
# ----------------------------------------------------------------------------------------------
def orbit_signed_area(theta_hat, psi_hat) -> np.ndarray:
    """Signed area [rad²] of the (θ on X, ψ on Y) orbit of x(t) = Re(x̂ e^{iωt}), ω > 0.

    A = ∮ θ dψ = −π Im(conj(θ̂) ψ̂): positive for a counter-clockwise orbit.  It equals the
    time-averaged angular momentum (θψ̇ − ψθ̇) times 2π/ω and is valid for elliptical orbits.
    """
    th = np.asarray(theta_hat, dtype=complex)
    ps = np.asarray(psi_hat, dtype=complex)
    return -np.pi * np.imag(np.conj(th) * ps)


def rotation_sign_from_gyroscopic(g_theta_psi: float) -> int:
    """Rotation sign for :func:`whirl_sense` from the gyroscopic coupling.

    ``g_theta_psi`` is the coefficient of ψ̇ in the θ equation (the (θ, ψ) entry of the
    gyroscopic part of the damping matrix, eq. 6.8/6.13: +I_X Ω).  Its sign is the sense of the
    spin in the (θ on X, ψ on Y) plane (+1 counter-clockwise), independently of how θ and ψ are
    oriented (flipping either flips both this coefficient and the orbit sense).
    """
    g = float(finite("g_theta_psi", g_theta_psi))
    if g == 0:
        raise InputError("g_theta_psi = 0.0 is invalid: a non-rotating propeller has no whirl "
                         "sense")
    return 1 if g > 0 else -1


def whirl_sense(theta_hat, psi_hat, rotation_sign: int = 1, eigenvalue: complex | None = None,
                tol: float = 1e-6) -> str:
    """'forward' or 'backward' whirl from the sense of the θ–ψ orbit; 'planar' if degenerate.

    The orbit of x(t) = Re(x̂ e^{λt}) runs counter-clockwise in the (θ on X, ψ on Y) plane when
    sign(Im λ)·Im(conj(θ̂) ψ̂) < 0 (:func:`orbit_signed_area` > 0 for Im λ > 0).
    ``rotation_sign`` = +1 when the propeller spin is counter-clockwise in that plane.  For the
    thesis equations (6.8) — gyroscopic term +I_X Ω ψ̇ in the θ equation — this is
    ``sign(Ω)`` (:func:`rotation_sign_from_gyroscopic`): solving (6.8) without aerodynamics and
    damping gives ψ̂ = i (K_θ − I_Y ω²)/(ω I_X Ω) θ̂, so the lower (backward) mode has
    Im(conj θ̂ ψ̂) > 0, a clockwise orbit against the counter-clockwise blade rotation of
    Figure 6.1 — exactly the statement of §9.2.  'forward' = orbit in the sense of rotation.
    ``eigenvalue`` (optional) gives the sign of ω; default ω > 0.  'planar' when |Im(conj θ̂ ψ̂)|
    ≤ tol·|θ̂||ψ̂| (a straight-line orbit, or a real eigenvalue).
    """
    if rotation_sign not in (1, -1):
        raise InputError(f"rotation_sign = {rotation_sign!r} is invalid: must be +1 or -1")
    th, ps = complex(theta_hat), complex(psi_hat)
    w_sign = 1.0
    if eigenvalue is not None:
        lam = complex(eigenvalue)
        if lam.imag == 0:
            return "planar"
        w_sign = math.copysign(1.0, lam.imag)
    cross = (th.conjugate() * ps).imag * w_sign
    if abs(cross) <= tol * abs(th) * abs(ps) or abs(th) * abs(ps) == 0:
        return "planar"
    ccw = cross < 0
    return "forward" if ccw == (rotation_sign > 0) else "backward"


def content(eigvec, groups: Mapping[str, Sequence[int] | np.ndarray]
            ) -> dict[str, float | np.ndarray]:
    """Fraction of Σ|x̂_i|² in each group of state indices (normalised over all groups).

    ``eigvec``: (n,) or (n, m) (modes in columns → arrays of m fractions).  Groups are index
    lists or boolean masks, e.g. {"bending": h_and_phi_idx, "torsion": alpha_idx}.  Note the
    entries carry their own units (m, rad): the fractions compare like with like only when the
    groups do.  An all-zero vector gives zero fractions.
    """
    x = np.asarray(eigvec, dtype=complex)
    if not groups:
        raise InputError("groups must name at least one group of state indices")
    e = np.abs(x) ** 2
    sums = {}
    for name, idx in groups.items():
        ix = np.asarray(idx)
        if ix.dtype == bool:
            if ix.shape[0] != x.shape[0]:
                raise InputError(f"group {name!r}: mask of length {ix.shape[0]}, need {x.shape[0]}")
        elif ix.size and (ix.min() < -x.shape[0] or ix.max() >= x.shape[0]):
            raise InputError(f"group {name!r}: index out of range for {x.shape[0]} states")
        sums[name] = e[ix].sum(axis=0)
    tot = sum(sums.values())
    out = {}
    for name, s in sums.items():
        fr = np.divide(s, tot, out=np.zeros_like(np.asarray(s, dtype=float)), where=tot > 0)
        out[name] = float(fr) if np.ndim(fr) == 0 else fr
    return out


def dominant(eigvec, groups: Mapping[str, Sequence[int] | np.ndarray]) -> str:
    """Name of the group with the largest :func:`content` of a single mode."""
    c = content(np.asarray(eigvec).reshape(-1), groups)
    return max(c, key=lambda g: c[g])


# ----------------------------------------------------------------------------------------------
# Time response
# ----------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class TimeResponse:
    """Time histories of the states: t (T,) [s], x (T, n), labels (n)."""

    t: np.ndarray
    x: np.ndarray
    labels: tuple[str, ...]

    def __getitem__(self, label: str) -> np.ndarray:
        try:
            return self.x[:, self.labels.index(label)]
        except ValueError:
            raise InputError(f"no state labelled {label!r}; states are {self.labels}") from None

    def to_dict(self) -> dict[str, Any]:
        return {"t": self.t.tolist(), "x": self.x.tolist(), "labels": list(self.labels)}

    @classmethod
    def from_dict(cls, d: Mapping[str, Any]) -> "TimeResponse":
        return cls(np.asarray(d["t"], dtype=float), np.asarray(d["x"], dtype=float),
                   tuple(d["labels"]))


def time_response(A, x0, t, state_labels: Sequence[str] | None = None, *,
                  method: str = "expm", rtol: float = 1e-9) -> TimeResponse:
    """Free response of ẋ = A x from x(t[0]) = x0 (§9.2, Figures 9.11–9.12).

    method "expm": exact transition matrices e^{AΔt} (scipy.linalg.expm), one per distinct
    step, applied step by step; "ivp": scipy's solve_ivp (RK45, like MATLAB's ode45) with
    ``rtol``.  ``t`` [s] strictly increasing.
    """
    A = _as_square_stack(A, "A")
    if A.ndim != 2:
        raise InputError(f"A must be one square matrix, got shape {A.shape}")
    n = A.shape[0]
    x0 = finite("x0", x0)
    if x0.shape != (n,):
        raise InputError(f"x0 must have {n} entries (one per state), got shape {x0.shape}")
    tt = increasing("t", t, "s")
    labels = tuple(f"x{i}" for i in range(n)) if state_labels is None else tuple(state_labels)
    if len(labels) != n:
        raise InputError(f"state_labels: got {len(labels)}, need {n}")
    if method == "expm":
        dts = np.diff(tt)
        key = np.round(dts / dts.max(), 12)
        uniq, inv = np.unique(key, return_inverse=True)
        with single_thread_blas():
            Phi = {i: sla.expm(A * dts[np.argmax(inv == i)]) for i in range(uniq.size)}
        x = np.empty((tt.size, n))
        x[0] = x0
        for j in range(tt.size - 1):          # sequential in time by nature
            x[j + 1] = Phi[int(inv[j])] @ x[j]
    elif method == "ivp":
        in_range("rtol", rtol, 0.0, 1e-2, low_open=True)
        atol = rtol * max(float(np.abs(x0).max()), 1e-300) * 1e-3
        sol = solve_ivp(lambda _t, y: A @ y, (tt[0], tt[-1]), x0, t_eval=tt, rtol=rtol,
                        atol=atol, method="RK45")
        if not sol.success:
            raise InputError(f"time integration failed: {sol.message}")
        x = sol.y.T
    else:
        raise InputError(f"method = {method!r} is invalid: must be 'expm' or 'ivp'")
    return TimeResponse(tt, x, labels)
