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
    from speed to speed.  The prediction of a branch over a step is trapezoidal,
    ``λ_b ≈ λ_a + ½(λ'_a + λ'_b) ΔV``, with ``λ' = dλ/dV = y A' x`` from the left eigenvectors
    (rows of X⁻¹, only the diagonal formed, in real arithmetic) and a forward finite difference
    of ``state_matrix``.  Linking two speeds (:func:`_link`):

    1. branches whose best candidate by prediction is mutual, close, with a MAC of the
       displacement part (eq. 5.14 in its Hermitian form, :func:`mac`) ≥ ``mac_min`` and
       clearly better than any other candidate are matched directly; so are those whose
       eigenvalue evidence alone is *decisive* (``decisive_ratio``: the shape may change a lot
       along V while the continuation is unique);
    2. the rest by an optimal (Hungarian, :func:`scipy.optimize.linear_sum_assignment`)
       assignment on the cost (1 − MAC) + prediction distance, with the runner-up tests;
       real roots that stay real with the same sign need no shape identity (their crossings
       are found from signs, a real root through zero being checked by sign det A) and are
       matched by distance alone, never flagged;
    3. where roots meet on the real axis — a pair turning real at its square-root branch point,
       two real roots merging, a split and a merge in one step — single-root predictions fail;
       small *clusters* (2–4 roots) are then followed as a set: the coefficients of their
       characteristic polynomial are analytic through the branch points, are predicted like
       single roots, and the roots of their Hermite interpolant, followed on sub-steps, fix
       who is who and show that no real part changes sign inside (:func:`_cluster_continuations`);
    4. two complex branches whose paths (straight from the first sample, or the Hermite curves
       through both) approach each other inside the step mark it as an unresolved veering or
       crossing.

    An ambiguous step is bisected (down to ``min_step``; at a grid speed near its middle if
    there is one, between a crossing and a branch point when a cluster shows both, at an
    unstable pair's branch point when a cluster shows one).  Then the Hermite model of Re λ of
    each branch between samples — values and slopes, with the trapezoidal mismatch as its
    uncertainty (``margin``) — inserts samples where a crossing may hide inside a step, and an
    unstable pair turning real (the thesis's "whirl divergence") is bracketed by two nodes
    0.9·``min_step`` apart around its branch point (root of the pair's discriminant, from the
    2×2 Ritz matrix of a real subspace iteration).  Intervals still ambiguous at ``min_step``
    (or when the node budget runs out) are listed in ``Sweep.unresolved``.  :func:`sweep`
    evaluates every grid speed (the V-g-f table).
:func:`critical_points`
    Every sign change of a tracked mode's real part, refined to ``xtol`` (default 1e-3 m/s)
    with eigenvalue-only evaluations, all crossings batched into one ``state_matrix`` call per
    round: shifted inverse iteration at the predicted eigenvalue (one LU factorisation and a
    few triangular solves instead of a full eigendecomposition); two evaluations at the
    predicted root ± 0.45 xtol, then a Newton step on their local slope evaluated with its two
    neighbours, which usually closes the bracket in two rounds.  Classified as flutter (complex
    pair) or divergence (real root through zero: the real eigenvalue nearest zero, its sign
    checked against sign det A, so whichever root crosses is found even where a pair split
    inside the step); onsets and recoveries; hump modes; benignity (eq. 5.13) from
    dλ/dV = yᴴA'x/(yᴴx) at the crossing; the critical (lowest onset) instability.
:func:`analyse`
    Both, in one call.  Locating critical speeds does not need an eigendecomposition at every
    grid speed: analyse starts from a subset of the grid ``initial_step`` (default 50 m/s)
    apart and lets the tracker add speeds where they are needed.

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
predicted paths approach within the step are refined until the step resolves the approach,
so a veering is followed along its branch (the shape rotates) while a true crossing
(decoupled modes) keeps each shape.  A veering is resolved only down to ``min_step``; one
narrower than that is treated like a crossing.  Repeated eigenvalues (degenerate within
``degenerate_tol``) have no defined shape identity; they are tracked by eigenvalue.  Inside a
cluster followed as a set, the conventions above are applied along the followed roots of its
interpolated characteristic polynomial (a pair formed inside a step by roots that were not
partners gives its Im > 0 member to the smaller id, like two real roots merging).

The forward difference for dA/dV also evaluates ``state_matrix`` at V + 1e-6·max(V, 1 m/s)
(batched with V in one call), so the model must accept speeds just above the last one.

BLAS threads are limited to one inside every solve (:func:`threadpoolctl.threadpool_limits`).
Measured on the 2-core development machine: while other jobs loaded it, a 200×200 ``eig``
took 14.6 ms on one thread against 26.3 ms on two (300×300: 37 vs 90 ms); on the idle machine
the two were equal (14.0 vs 15.0 ms) but the inverse-iteration evaluation used by the
refinement took 1.0 ms on one thread against 3.9 ms on two (thread start-up on small BLAS-2
work).  Entering the limiter costs 2–5 ms, so a sweep enters it once.

Cost on the wingtip propeller-wing (204 states, one thread; docs/performance.md): full
``eig`` ≈ 7 ms, ``eigvals`` ≈ 5 ms, dλ/dV of all roots ≈ 1 ms, ``state_matrix`` ≈ 0.7–0.9 ms
per speed in a batch (≈ 2.7 ms for a single speed), one inverse-iteration evaluation ≈ 1 ms.
"""
from __future__ import annotations

import itertools
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
    "time_response", "ANALYSE_INITIAL_STEP",
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
                      Between two real roots the cost is the distance term alone.
    dist_max:         a match farther than this (relative to s) from its prediction is
                      ambiguous.
    approach_ratio:   two complex eigenvalues whose predicted paths come closer inside a step
                      than this fraction of their end separations mark the step ambiguous.
    min_step:         smallest speed step of the refinement [m/s].
    fd_rel:           relative finite-difference step for dA/dV (h = fd_rel·max(V, 1 m/s)).
    degenerate_tol:   eigenvalues closer than this (relative) are treated as repeated.
    zero_tol:         |Re λ| ≤ zero_tol·max(|λ|, floor) counts as neutral (no sign).
    max_nodes:        budget of speeds (grid + refinement); None → 20·len(grid) + 200.
    hump_check:       insert samples where the cubic Hermite model of Re λ between two samples
                      of equal sign crosses zero, or comes closer to zero than ``margin`` times
                      its uncertainty (below).
    decisive_ratio:   a match whose prediction mismatch is below this fraction of every other
                      candidate's (below 0.1·dist_max, every other candidate farther than
                      dist_max) is unambiguous whatever its MAC: the
                      eigenvalue continuation is unique while the shape may change a lot along V
                      (e.g. whirl modes at low speed).  0: the MAC is always required.
    margin:           uncertainty of the Hermite model of a step = the mismatch of the
                      trapezoidal prediction at the step's end, |λ_b − λ_a − ½(λ'_a + λ'_b) ΔV|
                      (a third-order error estimate; the cubic's own error is of fourth order),
                      spread over the step as 16 s²(1 − s)² (zero at the samples, where λ and
                      λ' are exact).  A branch whose |Re λ| model falls below margin × that
                      envelope inside the step is sampled there.  0 keeps only the sign test.
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
    decisive_ratio: float = 0.05
    margin: float = 1.0

    def __post_init__(self) -> None:
        in_range("mac_min", self.mac_min, 0.0, 1.0)
        in_range("cost_ratio", self.cost_ratio, 0.0, 1.0, low_open=True)
        positive("dist_max", self.dist_max)
        in_range("approach_ratio", self.approach_ratio, 0.0, 1.0)
        positive("min_step", self.min_step, "m/s")
        in_range("fd_rel", self.fd_rel, 0.0, 1e-2, low_open=True)
        in_range("degenerate_tol", self.degenerate_tol, 0.0, 1e-2)
        in_range("zero_tol", self.zero_tol, 0.0, 1e-3)
        in_range("decisive_ratio", self.decisive_ratio, 0.0, 1.0)
        in_range("margin", self.margin, 0.0, 100.0)
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


def _eig_derivative(w: np.ndarray, X: np.ndarray, conj: np.ndarray,
                    dA: np.ndarray) -> np.ndarray:
    """dλ_k/dV = y_k A' x_k for a stack (y_k the rows of X⁻¹), only the diagonal formed.

    Real arithmetic: with R the real eigenvector basis of LAPACK (columns Re x, Im x for a
    pair, x for a real root) and P = R⁻¹ (rows p, q for a pair), the left eigenvector of
    x = u + i v is y = (p − i q)/2, so y A' x = ½[(pA'u + qA'v) + i(pA'v − qA'u)].  Only the
    rows where A' ≠ 0 enter (the kinematic rows [0 I 0] of eq. 5.4 do not depend on V).
    Non-finite results (a defective, branch-point X) → 0.
    """
    T, n = w.shape
    R = X.real.copy()
    t_up, j_up = np.nonzero(w.imag > 0)
    c_up = conj[t_up, j_up]
    R[t_up, :, c_up] = X[t_up, :, j_up].imag
    rows = np.nonzero(np.any(dA != 0, axis=(0, 2)))[0]
    d = np.zeros((T, n), dtype=complex)
    if rows.size == 0:
        return d
    with np.errstate(all="ignore"):
        E = np.zeros((T, n, rows.size))
        E[:, rows, np.arange(rows.size)] = 1.0
        try:
            Pr = np.linalg.solve(R, E)               # (T, n, r): the columns of R⁻¹ needed
        except np.linalg.LinAlgError:
            Pr = np.linalg.pinv(R)[:, :, rows]
        W = dA[:, rows, :] @ R                       # (T, r, n)
        dd = np.einsum("tjr,trj->tj", Pr, W)
        d = dd.astype(complex)
        if t_up.size:
            pu, qv = dd[t_up, j_up], dd[t_up, c_up]
            pv = np.einsum("mr,mr->m", Pr[t_up, j_up], W[t_up, :, c_up])
            qu = np.einsum("mr,mr->m", Pr[t_up, c_up], W[t_up, :, j_up])
            du = 0.5 * ((pu + qv) + 1j * (pv - qu))
            d[t_up, j_up] = du
            d[t_up, c_up] = du.conj()
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
    conj = _conj_index(w)
    dlam = _eig_derivative(w, X, conj, (Ah - A) / h[:, None, None])
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
        ia, ib = np.nonzero(small_a)[0], np.nonzero(small_b)[0]
        for rows, cols in ((ia, slice(None)), (slice(None), ib)):
            xa, xb = Xa[:, rows], Xb[:, cols]
            m[rows, cols] = np.abs(xa.conj().T @ xb) ** 2 / (
                np.sum(np.abs(xa) ** 2, axis=0)[:, None]
                * np.sum(np.abs(xb) ** 2, axis=0)[None, :])
    return m


def _mac_columns(Xa: np.ndarray, Xb: np.ndarray, disp: np.ndarray) -> np.ndarray:
    """MAC of corresponding columns (Xa[:, i] with Xb[:, i]), as :func:`_mac_matrix`."""
    Pa, Pb = Xa[disp], Xb[disp]
    na = np.sum(np.abs(Pa) ** 2, axis=0)
    nb = np.sum(np.abs(Pb) ** 2, axis=0)
    num = np.abs(np.sum(Pa.conj() * Pb, axis=0)) ** 2
    den = na * nb
    m = np.divide(num, den, out=np.zeros_like(num), where=den > 0)
    small = (na < 1e-10) | (nb < 1e-10)
    if small.any():
        xa, xb = Xa[:, small], Xb[:, small]
        m[small] = np.abs(np.sum(xa.conj() * xb, axis=0)) ** 2 / (
            np.sum(np.abs(xa) ** 2, axis=0) * np.sum(np.abs(xb) ** 2, axis=0))
    return m


def _near(lam: np.ndarray, conj: np.ndarray, scale: np.ndarray, tol: float,
          rows: np.ndarray) -> np.ndarray:
    """For each of ``rows``: another eigenvalue (not the conjugate) within tol·scale?"""
    d = np.abs(lam[rows, None] - lam[None, :])
    r = np.arange(rows.size)
    d[r, rows] = np.inf
    d[r, conj[rows]] = np.inf
    return np.any(d <= tol * scale[rows, None], axis=1)


@dataclass
class _Link:
    """Assignment raw(a) → raw(b) of one step and what the sweep needs to know about it.

    err:   absolute uncertainty of each a-row's continuation [1/s]: the mismatch of its
           trapezoidal prediction.
    clusters: roots followed as a set over the step (through branch points, see
           :func:`_cluster_continuations`), raw indices at a; checked as a cluster, so left
           out of the per-root Hermite check.
    split_at: where to refine an ambiguous step other than its middle [m/s] (see
           :func:`_cluster_continuations`).
    branch_points: unstable pairs turning real inside the step, estimated from accepted
           clusters: (V [m/s], raw rows at a, double root [1/s]).
    """

    perm: np.ndarray
    ambiguous: bool
    err: np.ndarray
    clusters: tuple[tuple[int, ...], ...] = ()
    split_at: float | None = None
    branch_points: tuple[tuple[float, int, int, float], ...] = ()


def _link(a: _Node, b: _Node, disp: np.ndarray, opts: TrackingOptions) -> _Link:
    """Optimal assignment raw(a) → raw(b) and whether it is ambiguous (see TrackingOptions).

    1. Branches whose best candidate by eigenvalue prediction is mutual, close, with a MAC
       above ``mac_min`` (complex) and clearly better than any other candidate (its cost below
       ``cost_ratio`` × the runner-up's distance, a lower bound of the runner-up's cost) are
       matched directly — they are unambiguous under the full test too — and so are those
       whose eigenvalue evidence alone is decisive (``decisive_ratio``).
    2. The rest go through an optimal (Hungarian) assignment on the full cost, MAC included,
       and the runner-up tests.  Real roots at both ends with the same sign of Re λ need no
       shape identity (the crossing detection only needs the sign; a real root through zero
       is checked by sign det A): they are matched by the distance alone and never flagged.
    3. A complex pair whose members fail the tests only because of the square-root branch
       point of a pair turning real (or two real roots merging) is accepted as a set when the
       pair's sum and product — analytic through the branch point — follow their prediction.
    """
    n = a.lam.size
    ar = np.arange(n)
    h = b.V - a.V
    scale = np.maximum(np.abs(a.lam), a.floor)
    dl = b.lam[None, :] - a.lam[:, None]
    trap = np.abs(dl - 0.5 * (a.dlam[:, None] + b.dlam[None, :]) * h)
    dist = np.minimum(trap, np.abs(dl)) / scale[:, None]
    ra, rb = a.lam.imag == 0, b.lam.imag == 0
    if n == 1:
        perm = np.zeros(1, dtype=int)
        return _Link(perm, bool(dist[0, 0] > opts.dist_max), trap[0, :1].copy())
    # 1. direct matches
    j1 = np.argmin(dist, axis=1)
    i1 = np.argmin(dist, axis=0)
    d1 = dist[ar, j1]
    row = dist.copy()
    row[ar, j1] = np.inf
    row[ar, b.conj[j1]] = np.inf
    col = dist[:, j1].T.copy()           # col[i, r] = dist[r, j1[i]]
    col[ar, ar] = np.inf
    col[ar, a.conj] = np.inf
    alt = np.minimum(row.min(axis=1), col.min(axis=1))
    rr = ra & rb[j1]
    m1 = np.ones(n)
    cplx = ~rr
    if cplx.any():
        m1[cplx] = _mac_columns(a.X[:, cplx], b.X[:, j1[cplx]], disp)
    c1 = np.where(rr, 0.0, 1.0 - m1) + d1
    decisive = ((d1 < opts.decisive_ratio * alt) & (d1 <= 0.1 * opts.dist_max)
                & (alt >= opts.dist_max))
    easy = ((i1[j1] == ar) & (d1 <= opts.dist_max)
            & (((c1 <= opts.cost_ratio * alt) & (rr | (m1 >= opts.mac_min))) | decisive))
    easy &= easy[a.conj] & (b.conj[j1] == j1[a.conj])
    perm = np.where(easy, j1, -1)
    amb = np.zeros(n, dtype=bool)
    hard = np.nonzero(~easy)[0]
    if hard.size:
        free = np.setdiff1d(ar, j1[easy], assume_unique=False)
        w = np.where(ra[hard][:, None] & rb[None, :], 0.0, 1.0)
        macH = _mac_matrix(a.X[:, hard], b.X, disp)
        costH = w * (1.0 - macH) + dist[hard]
        r_, c_ = linear_sum_assignment(costH[:, free])
        perm[hard[r_]] = free[c_]
        inv = np.empty(n, dtype=int)
        inv[perm] = ar
        hh = np.arange(hard.size)
        ph = perm[hard]
        c0 = costH[hh, ph]
        rowH = costH.copy()
        for cols in (ph, b.conj[ph], perm[a.conj[hard]]):
            rowH[hh, cols] = np.inf
        wC = np.where(ra[:, None] & rb[ph][None, :], 0.0, 1.0)
        costC = (wC * (1.0 - _mac_matrix(a.X, b.X[:, ph], disp)) + dist[:, ph]).T
        for rows in (hard, a.conj[hard], inv[b.conj[ph]]):
            costC[hh, rows] = np.inf
        altH = np.minimum(rowH.min(axis=1), costC.min(axis=1))
        rowD = dist[hard].copy()
        for cols in (ph, b.conj[ph], perm[a.conj[hard]]):
            rowD[hh, cols] = np.inf
        colD = dist[:, ph].T.copy()
        for rows in (hard, a.conj[hard], inv[b.conj[ph]]):
            colD[hh, rows] = np.inf
        d0 = dist[hard, ph]
        altD = np.minimum(rowD.min(axis=1), colD.min(axis=1))
        decisiveH = ((d0 < opts.decisive_ratio * altD) & (d0 <= 0.1 * opts.dist_max)
                     & (altD >= opts.dist_max))
        shape_free = _near(a.lam, a.conj, scale, opts.degenerate_tol, hard) & _near(
            b.lam, b.conj, np.maximum(np.abs(b.lam), b.floor), opts.degenerate_tol, ph)
        same_real = ra[hard] & rb[ph] & (np.sign(a.lam[hard].real) == np.sign(b.lam[ph].real))
        amb[hard] = ~same_real & ~decisiveH & (
            (~shape_free & ((c0 > opts.cost_ratio * altH) | (macH[hh, ph] < opts.mac_min)))
            | (d0 > opts.dist_max))
    err = trap[ar, perm]
    clusters, split_at, events = _cluster_continuations(a, b, perm, amb, trap[ar, perm] / scale,
                                                        disp, opts)
    err = trap[ar, perm]
    in_clusters = [i for rows in clusters for i in rows]
    return _Link(perm, bool(amb.any() or _approach(a, b, perm, opts, in_clusters)), err,
                 clusters, split_at, events)


def _poly_and_derivative(lam: np.ndarray, dlam: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Coefficients c of Π(z − λ_i) (leading 1 dropped) and their derivatives along V.

    The coefficients of a cluster's characteristic polynomial are analytic in V through the
    branch points where its roots split or merge (single roots have square-root
    singularities there); their derivatives follow from the λ'_i by the product rule.
    """
    k = lam.size
    c = np.zeros(k + 1, dtype=complex)
    dc = np.zeros(k + 1, dtype=complex)
    c[0] = 1.0
    for r, d in zip(lam, dlam):
        dc[1:] = dc[1:] - r * dc[:-1] - d * c[:-1]
        c[1:] = c[1:] - r * c[:-1]
    return c[1:], dc[1:]


def _cluster_mismatch(ca, dca, cb, dcb, h, scale):
    """Relative mismatch of the trapezoidal prediction of polynomial coefficients (last axis:
    the coefficients; each relative to scale^order and not larger than the change itself)."""
    k = ca.shape[-1]
    sc = scale ** np.arange(1, k + 1)
    mis = np.abs(cb - ca - 0.5 * (dca + dcb) * h)
    return np.max(np.minimum(mis, np.abs(cb - ca)) / sc, axis=-1), mis


def _alternative_mismatch(lam_o, dl_o, cand, dcand, c_fix, dc_fix, other_at_a, h, scale):
    """Mismatch with one member replaced by each candidate (vectorised over candidates)."""
    p, dp = _poly_and_derivative(lam_o, dl_o)
    p1 = np.concatenate([[1.0], p])
    dp1 = np.concatenate([[0.0], dp])
    # (z − x) Π_others: coefficients [1, p1 − x·…]
    c = (np.concatenate([p1, [0.0]])[None, :]
         - cand[:, None] * np.concatenate([[0.0], p1])[None, :])[:, 1:]
    dc = (np.concatenate([dp1, [0.0]])[None, :]
          - cand[:, None] * np.concatenate([[0.0], dp1])[None, :]
          - dcand[:, None] * np.concatenate([[0.0], p1])[None, :])[:, 1:]
    if other_at_a:
        return _cluster_mismatch(c, dc, c_fix[None, :], dc_fix[None, :], h, scale)[0]
    return _cluster_mismatch(c_fix[None, :], dc_fix[None, :], c, dc, h, scale)[0]


def _subspace_mac(Xa: np.ndarray, Xb: np.ndarray, disp: np.ndarray) -> float:
    """Smallest squared cosine of the principal angles between two shape subspaces."""
    Pa, Pb = Xa[disp], Xb[disp]
    if Pa.shape[0] < Pa.shape[1] or np.linalg.norm(Pa) < 1e-5 or np.linalg.norm(Pb) < 1e-5:
        Pa, Pb = Xa, Xb
    Qa, _ = np.linalg.qr(Pa)
    Qb, _ = np.linalg.qr(Pb)
    s = np.linalg.svd(Qa.conj().T @ Qb, compute_uv=False)
    return float(np.min(s) ** 2)


#: sub-steps on which the interpolated characteristic polynomial of a cluster is followed
_CLUSTER_SUBSTEPS = 32


def _interpolated_roots(coeffs, s: float) -> np.ndarray:
    """Roots of the cluster polynomial with Hermite-interpolated (real) coefficients at s."""
    c = np.real(_hermite_eval(coeffs, s))
    k = c.size
    comp = np.zeros((k, k))
    comp[0, :] = -c
    if k > 1:
        comp[np.arange(1, k), np.arange(k - 1)] = 1.0
    return np.linalg.eigvals(comp).astype(complex)


def _partners(r: np.ndarray) -> np.ndarray:
    """Index of each root's conjugate partner (−1 for a real root)."""
    out = np.full(r.size, -1)
    for i in np.nonzero(r.imag != 0)[0]:
        d = np.abs(r - r[i].conjugate())
        d[i] = np.inf
        out[i] = int(np.argmin(d))
    return out


def _follow_substep(cur, r, s0, s1, coeffs, perms, depth):
    """Continue the roots ``cur`` (at s0) to the roots ``r`` (at s1) by nearest distance, the
    Im > 0 member of a pair turning real taking the larger root; a sub-step in which the
    pairing changes by more than one split or one merge is halved (up to 2⁵ times)."""
    k = cur.size
    nxt = r[perms[int(np.argmin(np.abs(cur[None, :] - r[perms]).sum(axis=1)))]]
    for i in range(k):              # a pair turning real: Im > 0 takes the larger root
        if cur[i].imag > 0 and nxt[i].imag == 0:
            j = int(np.argmin(np.abs(cur - cur[i].conjugate()) + np.where(
                np.arange(k) == i, np.inf, 0.0)))
            if nxt[j].imag == 0 and nxt[j].real > nxt[i].real:
                nxt[i], nxt[j] = nxt[j], nxt[i]
    real_c, real_n = cur.imag == 0, nxt.imag == 0
    if np.array_equal(real_c, real_n) and (real_c.all() or np.array_equal(
            np.sign(cur.imag), np.sign(nxt.imag))) and real_c.sum() >= k - 2:
        return nxt                  # no root changed type: at most one pair, kept
    pc, pn = _partners(cur), _partners(nxt)
    changed = np.nonzero(pc != pn)[0]
    clean = changed.size == 0 or (changed.size == 2 and (
        (pc[changed[0]] == changed[1] and np.all(pn[changed] == -1))        # one split
        or (pn[changed[0]] == changed[1] and np.all(pc[changed] == -1))))   # one merge
    if clean or depth >= 5:
        return nxt
    sm = 0.5 * (s0 + s1)
    mid = _follow_substep(cur, _interpolated_roots(coeffs, sm), s0, sm, coeffs, perms,
                          depth + 1)
    return _follow_substep(mid, r, sm, s1, coeffs, perms, depth + 1)


def _follow_cluster(ca, dca, cb, dcb, la, lb, h, margin):
    """Follow the roots of a cluster's characteristic polynomial, interpolated in V.

    Each coefficient is the cubic Hermite interpolant of its exact values and derivatives at
    the step's ends; its roots are followed on ``_CLUSTER_SUBSTEPS`` sub-steps by nearest
    continuation (:func:`_follow_substep`: finer where a split and a merge fall into one
    sub-step), a pair turning real giving the larger root to its Im > 0 member (the module's
    convention; merging roots are fixed by branch id later).  Returns (q, events)
    with lb[q[i]] the continuation of la[i] and the unstable pairs of ``la`` that turn real
    inside (s, member, partner, the double root's real part); or (None, s) when the
    interpolated roots change the sign of their real part, come closer to zero than
    ``margin`` × their uncertainty (the coefficients' trapezoidal mismatch δp, spread as
    16 s²(1 − s)²: min(|δp|/|p'|, √(2|δp|/|p''|)) at the root), or end away from the exact
    roots — s ∈ (0, 1) is where to split the step: between a sign change and the nearest
    change of the number of real roots (a branch point), so that the two parts separate them;
    None for the middle.
    """
    k = la.size
    ca, dca, cb, dcb = (np.real(x) for x in (ca, dca, cb, dcb))   # conjugation-closed: real
    coeffs = _hermite_coeffs(ca, cb, dca, dcb, h)
    _, mis = _cluster_mismatch(ca, dca, cb, dcb, h, 1.0)
    S = np.linspace(0.0, 1.0, _CLUSTER_SUBSTEPS + 1)
    C = _hermite_eval(tuple(c[None, :] for c in coeffs), S[:, None])      # (m, k)
    comp = np.zeros((S.size, k, k))
    comp[:, 0, :] = -C
    if k > 1:
        comp[:, np.arange(1, k), np.arange(k - 1)] = 1.0
    roots = np.linalg.eigvals(comp).astype(complex)   # real roots exactly real (LAPACK)
    sign0 = np.sign(la.real)
    if np.any(sign0 == 0) or np.any(np.sign(lb.real) == 0):
        return None, None
    scale = max(float(np.max(np.abs(la))), float(np.max(np.abs(lb))), 1e-300)
    track = np.empty((S.size, k), dtype=complex)
    track[0] = la
    cur = la.astype(complex).copy()
    perms = np.array(list(itertools.permutations(range(k))))
    for m in range(1, S.size):
        cur = track[m] = _follow_substep(cur, roots[m], S[m - 1], S[m], coeffs, perms, 0)
    # real parts: sign kept, with margin over the uncertainty of the roots: first order
    # |δp(λ)|/|p'(λ)|, or √(2|δp(λ)|/|p''(λ)|) near a double root (where p' → 0)
    full = np.concatenate([np.ones((S.size, 1)), C], axis=1)             # (m, k+1)
    pw = np.arange(k, -1, -1)
    d1 = np.sum(full[:, :-1, None] * (pw[:-1, None] * track[:, None, :] ** np.maximum(
        pw[:-1, None] - 1, 0)), axis=1)
    d2 = np.sum(full[:, :-2, None] * ((pw[:-2] * (pw[:-2] - 1))[:, None] * track[:, None, :]
                                      ** np.maximum(pw[:-2, None] - 2, 0)), axis=1) \
        if k >= 2 else np.zeros_like(track)
    err = np.abs(sum(mis[q] * track ** (k - 1 - q) for q in range(k)))
    env = 16 * S ** 2 * (1 - S) ** 2
    with np.errstate(all="ignore"):
        lin = err / np.abs(d1)
        quad = np.sqrt(2 * err / np.abs(d2))
    unc = env[:, None] * np.nan_to_num(np.minimum(lin, quad), nan=np.inf, posinf=np.inf)
    flip = np.any(np.sign(track.real) != sign0, axis=1)
    thin = np.any(np.abs(track.real) < margin * unc, axis=1)
    if flip.any() or thin.any():
        if not flip.any():
            return None, None
        mc = int(np.argmax(flip))
        nreal = np.sum(track.imag == 0, axis=1)
        ev = np.nonzero(np.diff(nreal) != 0)[0] + 0.5          # branch points, in sub-steps
        if ev.size == 0:
            return None, None
        e = ev[np.argmin(np.abs(ev - mc))]
        return None, float(np.clip(0.5 * (e + mc) / _CLUSTER_SUBSTEPS, 0.05, 0.95))
    cost = np.abs(cur[:, None] - lb[None, :])
    rows, cols = linear_sum_assignment(cost)
    q = cols[np.argsort(rows)]
    if np.max(cost[np.arange(k), q]) > 1e-6 * scale:
        return None, None
    # unstable pairs of the first sample turning real: (s, member, partner, double root)
    events = []
    for i in np.nonzero((la.imag > 0) & (la.real > 0))[0]:
        real = np.nonzero(track[:, i].imag == 0)[0]
        if real.size:
            m = int(real[0])
            ic = int(np.argmin(np.abs(la - np.conj(la[i]))))
            n_real = int(np.count_nonzero(roots[m - 1].imag == 0))
            lo, hi = S[m - 1], S[m]
            for _ in range(12):        # the interpolated branch point, inside the sub-step
                mid = 0.5 * (lo + hi)
                cm = np.real(_hermite_eval(coeffs, mid))
                if np.count_nonzero(np.roots(np.concatenate([[1.0], cm])).imag == 0) == n_real:
                    lo = mid
                else:
                    hi = mid
            events.append((0.5 * (lo + hi), int(i), ic,
                           float(0.5 * (track[m - 1, i] + track[m - 1, ic]).real)))
    return q, events


def _closure(seed: set[int], perm: np.ndarray, inv: np.ndarray, a: _Node, b: _Node) -> set[int]:
    """Smallest row set containing ``seed`` closed under conjugation at both ends and perm."""
    S = set(seed)
    while True:
        S2 = S | {int(a.conj[i]) for i in S}
        T = {int(perm[i]) for i in S2}
        T |= {int(b.conj[j]) for j in T}
        S2 |= {int(inv[j]) for j in T}
        if S2 == S:
            return S
        S = S2


def _cluster_continuations(a: _Node, b: _Node, perm: np.ndarray, amb: np.ndarray,
                           rel_err: np.ndarray, disp: np.ndarray, opts: TrackingOptions):
    """Follow small clusters of roots as a set where single roots cannot be followed.

    Where roots meet — a pair turning real at its square-root branch point, two real roots
    merging into a pair, a split and a merge in the same step — single-root predictions fail
    although nothing is ambiguous about the set.  The coefficients of the cluster's
    characteristic polynomial Π(z − λ_i) stay analytic there.  Seeds: the ambiguous rows and
    the real roots whose own prediction misses by more than ``dist_max`` (not ambiguous, but
    their Hermite models are useless).  Each seed grows to the smallest row set closed under
    conjugation and under the assignment (then, if needed, by the nearest other roots) up to
    four roots.  Only clusters with a real root at either end, or a pair so close to the real
    axis that its own prediction misses by more than its imaginary part, qualify (complex
    pairs meeting away from the axis are a veering or crossing, resolved by refinement).  A
    cluster is accepted when

    * its coefficients follow their trapezoidal prediction within ``dist_max`` (relative to
      |λ|^order), clearly better (``cost_ratio``) than with any one member replaced by any
      other eigenvalue at either end (a real member not by the other real roots of its sign:
      like single real roots, those are interchangeable — e.g. the aerodynamic lag roots);
    * its shape subspaces at both ends agree (principal angles: MAC ≥ ``mac_min``);
    * the roots of the Hermite-interpolated polynomial, followed on sub-steps
      (:func:`_follow_cluster`), keep the sign of their real parts with ``margin`` to spare
      (a crossing inside is resolved with single roots, by refinement) and end on the exact
      roots — which also fixes who is who inside the cluster.

    Accepted clusters get that assignment and lose their ambiguity flags; their members are
    then checked as a cluster, not by the per-root Hermite check.  Returns the clusters (raw
    row indices at a); when a cluster was refused because a root crosses the imaginary axis
    inside the step, a speed where to split the step (between the crossing and the nearest
    branch point) [m/s]; and the unstable pairs that turn real inside accepted clusters
    (estimated speed [m/s], raw rows of the pair at a, estimated double root [1/s]).
    """
    n = a.lam.size
    h = b.V - a.V
    inv = np.empty(n, dtype=int)
    inv[perm] = np.arange(n)
    ra, rb = a.lam.imag == 0, b.lam.imag == 0
    # real roots badly predicted (not ambiguous) matter only where their Hermite model could
    # come near zero: |Re λ| not clearly above the mismatch at both ends
    mis = rel_err * np.maximum(np.abs(a.lam), a.floor)
    near_zero = np.minimum(np.abs(a.lam.real), np.abs(b.lam[perm].real)) <= 4 * max(
        opts.margin, 1.0) * mis
    bad = ra & rb[perm] & (rel_err > opts.dist_max) & near_zero & ~amb
    seeds = list(np.nonzero(amb)[0]) + list(np.nonzero(bad)[0])
    done: set[int] = set()
    out = []
    splits: list[float] = []
    events: list[tuple[float, int, int, float]] = []
    for seed in seeds:
        if int(seed) in done:
            continue
        base = _closure({int(seed)}, perm, inv, a, b)
        done.update(base)
        bl = np.array(sorted(base))
        if not (np.any(ra[bl]) or np.any(rb[perm[bl]])
                or np.any(np.abs(a.lam[bl].imag) <= mis[bl])):
            # complex pairs away from the real axis: a veering, unless their prediction
            # fails — then a real root may have joined them through branch points
            if not np.any(rel_err[bl] > opts.dist_max):
                continue
            d = np.abs(a.lam[:, None] - a.lam[bl][None, :]).min(axis=1)
            d[~ra] = np.inf
            d[bl] = np.inf
            near = [int(x) for x in np.argsort(d)[:3] if np.isfinite(d[x])]
            trials = [_closure(base | {x}, perm, inv, a, b) for x in near]
        elif len(base) > 1:
            trials = [base]
        else:                                   # a lone root: with one of its nearest others
            d = np.abs(a.lam - a.lam[seed])
            d[seed] = np.inf
            trials = [_closure(base | {int(x)}, perm, inv, a, b) for x in np.argsort(d)[:3]]
        tried: set[frozenset[int]] = set()
        while trials:
            S = trials.pop(0)
            if len(S) > 4 or frozenset(S) in tried:
                continue
            tried.add(frozenset(S))
            rows = np.array(sorted(S))
            q, info = _try_cluster(a, b, rows, perm[rows], rel_err[rows], disp, opts, h)
            if q is not None:
                perm[rows] = perm[rows][q]
                inv[perm] = np.arange(n)
                amb[rows] = False
                done.update(S)
                out.append(tuple(int(i) for i in rows))
                for s_ev, i, ic, sig in info:
                    events.append((a.V + s_ev * h, int(rows[i]), int(rows[ic]), sig))
                break
            if info is not None:
                splits.append(a.V + info * h)
            if len(tried) < 4:       # grow by one of the nearest other roots (at a)
                d = np.abs(a.lam[:, None] - a.lam[rows][None, :]).min(axis=1)
                d[rows] = np.inf
                for x in np.argsort(d)[:3]:
                    trials.append(_closure(S | {int(x)}, perm, inv, a, b))
    return tuple(out), (min(splits) if splits else None), tuple(events)


def _try_cluster(a: _Node, b: _Node, rows: np.ndarray, cols: np.ndarray, rel_err: np.ndarray,
                 disp: np.ndarray, opts: TrackingOptions, h: float):
    """The assignment inside an acceptable cluster (see :func:`_cluster_continuations`):
    (q, events of :func:`_follow_cluster`) with b[cols[q[i]]] the continuation of a[rows[i]];
    (None, where to split the step or None) if not acceptable."""
    la, da, lb, db = a.lam[rows], a.dlam[rows], b.lam[cols], b.dlam[cols]
    near_axis = np.abs(la.imag) <= rel_err * np.abs(la)
    if not (np.any(la.imag == 0) or np.any(lb.imag == 0) or np.any(near_axis)):
        return None, None     # complex pairs only: a veering, resolved by refinement
    scale = max(float(np.max(np.abs(la))), a.floor)
    ca, dca = _poly_and_derivative(la, da)
    cb, dcb = _poly_and_derivative(lb, db)
    e = float(_cluster_mismatch(ca, dca, cb, dcb, h, scale)[0])
    if not e <= opts.dist_max:
        return None, None
    q, events = _follow_cluster(ca, dca, cb, dcb, la, lb, h, opts.margin)
    if q is None:
        return None, events
    if _subspace_mac(a.X[:, rows], b.X[:, cols], disp) < opts.mac_min:
        return None, None
    n = a.lam.size
    oa = np.setdiff1d(np.arange(n), rows)
    ob = np.setdiff1d(np.arange(n), cols)
    alt = np.inf
    for m in range(rows.size if oa.size else 0):
        keep = np.delete(np.arange(rows.size), m)
        # a real member is interchangeable with the other real roots of its sign (no shape
        # identity is kept between them): they are no competitors
        for lam_o, dl_o, other, fix, dfix, at_a, x in (
                (la, da, oa, cb, dcb, True, la[m]), (lb, db, ob, ca, dca, False, lb[m])):
            node = a if at_a else b
            cand = other
            if x.imag == 0:
                cand = other[~((node.lam[other].imag == 0)
                               & (np.sign(node.lam[other].real) == np.sign(x.real)))]
            if cand.size:
                alt = min(alt, float(np.min(_alternative_mismatch(
                    lam_o[keep], dl_o[keep], node.lam[cand], node.dlam[cand], fix, dfix, at_a,
                    h, scale))))
    if e > opts.cost_ratio * alt:
        return None, None
    return q, events


def _approach(a: _Node, b: _Node, perm: np.ndarray, opts: TrackingOptions,
              skip: Sequence[int] = ()) -> bool:
    """Do two complex eigenvalues' paths approach each other inside the step?

    Two models of the paths of the physical complex branches i, k: the straight lines
    λ_i + λ'_i s from the first sample (s ∈ [0, h]), and the cubic Hermite curves through both
    samples (values and slopes).  A closest approach m inside the step below
    approach_ratio · min(separation at a, at b) flags the step: it does not resolve a veering
    or crossing there (a long step can otherwise take a veering for a crossing, the straight
    lines from either end both missing it).  Rows in ``skip`` (clusters followed as a set,
    whose single-root slopes are singular) are left out.
    """
    keep = (a.lam.imag > 0) & (b.lam[perm].imag > 0)
    keep[list(skip)] = False
    up = np.nonzero(keep)[0]
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
    ref = opts.approach_ratio * np.minimum(np.abs(r0), eb)
    flag = interior & (m < ref)
    # Hermite curves through both samples; only pairs that travel far enough to approach
    c = _hermite_coeffs(lam[:, None], lb[:, None], d[:, None], b.dlam[perm[up]][:, None], h)
    path = _hermite_eval(c, _CHECK_S[None, :])                      # (p, 9)
    travel = np.max(np.abs(path - lam[:, None]), axis=1)
    cand = (travel[:, None] + travel[None, :]) > np.abs(r0) - ref
    np.fill_diagonal(cand, False)
    i, k = np.nonzero(np.triu(cand))
    if i.size:
        dmin = np.min(np.abs(path[i] - path[k]), axis=1)
        flag[i, k] |= dmin < ref[i, k]
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
    # merge: a conjugate pair at t whose branches were not partners at t-1 (two reals
    # merging, or roots of a cluster that split and merged within the step): the smaller id
    # takes Im > 0
    inv_cur = np.empty(n, dtype=int)
    inv_cur[R[t]] = np.arange(n)
    lc = cur.lam[R[t]]
    for k in np.nonzero(lc.imag < 0)[0]:
        kp = inv_cur[cur.conj[R[t, k]]]
        if k < kp and prev.conj[R[t - 1, k]] != R[t - 1, kp]:
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


#: interior abscissae (fractions of a step) at which the Hermite models are checked, besides
#: their stationary points
_CHECK_S = np.linspace(0.1, 0.9, 9)


def _hump_candidates(V: np.ndarray, models, floor: np.ndarray,
                     opts: TrackingOptions) -> list[float]:
    """Speeds where a branch may hide a sign change of Re λ between samples of equal sign.

    ``models``: the per-step models of :func:`_step_models` (T−1, n) — values and slopes of
    Re λ at both samples, their uncertainty, which branches to check.  Per step and branch
    with Re λ of equal, non-zero sign at both samples: the cubic Hermite model p(s) of Re λ
    is evaluated at its stationary points and at ``_CHECK_S``; a sample is inserted at the
    worst s where sign·p(s) < margin · err · 16 s²(1 − s)² (the model crosses zero, or comes
    closer to it than its uncertainty).  One sample per step.
    """
    fa, fb, ga, gb, e, phys = models
    h = np.diff(V)[:, None]
    tola = opts.zero_tol * np.maximum(np.abs(fa), floor[:-1, None])
    tolb = opts.zero_tol * np.maximum(np.abs(fb), floor[1:, None])
    sa = np.where(np.abs(fa) <= tola, 0, np.sign(fa))
    sb = np.where(np.abs(fb) <= tolb, 0, np.sign(fb))
    ok = phys & (sa == sb) & (sa != 0) & (h >= 2 * opts.min_step)
    if not ok.any():
        return []
    t_i, k_i = np.nonzero(ok)
    hh = h[t_i, 0]
    c = _hermite_coeffs(fa[t_i, k_i], fb[t_i, k_i], ga[t_i, k_i], gb[t_i, k_i], hh)
    A, B, C = 3 * c[3], 2 * c[2], c[1]
    disc = B * B - 4 * A * C
    sq = np.sqrt(np.maximum(disc, 0.0))
    with np.errstate(all="ignore"):
        s1 = np.where(np.abs(A) > 1e-300, (-B + sq) / (2 * A), -C / B)
        s2 = np.where(np.abs(A) > 1e-300, (-B - sq) / (2 * A), -C / B)
    S = np.concatenate([np.stack([s1, s2], axis=1),
                        np.broadcast_to(_CHECK_S, (t_i.size, _CHECK_S.size))], axis=1)
    valid = np.isfinite(S) & (S > 0) & (S < 1)
    S = np.where(valid, S, 0.5)
    p = _hermite_eval(tuple(ci[:, None] for ci in c), S)
    tol_mid = np.maximum(tola[t_i, k_i], tolb[t_i, k_i])[:, None]
    env = opts.margin * e[t_i, k_i][:, None] * 16 * S ** 2 * (1 - S) ** 2
    viol = (p * sa[t_i, k_i][:, None] < np.maximum(env, 0.0) - tol_mid) & valid
    bad = viol.any(axis=1)
    out: dict[int, tuple[float, float]] = {}
    for r in np.nonzero(bad)[0]:
        score = np.where(viol[r], env[r] - p[r] * sa[t_i[r], k_i[r]], -np.inf)
        j = int(np.argmax(score))
        t = int(t_i[r])
        if t not in out or score[j] > out[t][1]:
            s = float(np.clip(S[r, j], 0.05, 0.95))
            out[t] = (V[t] + s * (V[t + 1] - V[t]), float(score[j]))
    return sorted(v for v, _ in out.values())


def _step_models(nodes: list[_Node], R: np.ndarray, links: list[_Link]):
    """Per step and branch: (Re λ_a, Re λ_b, Re λ'_a, Re λ'_b, uncertainty, checked) (T−1, n).

    Members of clusters followed as a set over a step (:func:`_cluster_continuations`) were
    checked there and are not checked again.
    """
    lam = np.stack([nd.lam[R[t]] for t, nd in enumerate(nodes)])
    dl = np.stack([nd.dlam[R[t]] for t, nd in enumerate(nodes)])
    T, n = lam.shape
    e = np.empty((T - 1, n))
    phys = (lam[:-1].imag >= 0) & (lam[1:].imag >= 0)
    for t, lk in enumerate(links):
        inv = np.empty(n, dtype=int)
        inv[R[t]] = np.arange(n)
        e[t] = lk.err[R[t]]
        for rows in lk.clusters:
            phys[t, inv[list(rows)]] = False
    return lam[:-1].real, lam[1:].real, dl[:-1].real, dl[1:].real, e, phys


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

    V:            (T,) speeds [m/s], increasing: the grid plus refinement points (from
                  :func:`analyse`: a subset of the grid plus refinement points).
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
    dzeta_dV:      dζ/dV at V [s/m] (from dλ/dV, or a central difference), None for divergence.
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
#: default spacing [m/s] of the speeds :func:`analyse` evaluates first (see its docstring)
ANALYSE_INITIAL_STEP = 50.0


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


def _initial_subset(grid: np.ndarray, step: float | None) -> np.ndarray:
    """The grid speeds nearest to an even division of [first, last] at spacing ≤ ``step``.

    Always the first and the last grid speed; the whole grid when ``step`` is None or the grid
    is already at least that coarse.
    """
    if step is None or grid.size <= 2:
        return grid
    m = int(math.ceil((grid[-1] - grid[0]) / step - 1e-9)) + 1
    if m >= grid.size:
        return grid
    targets = np.linspace(grid[0], grid[-1], m)
    idx = np.clip(np.searchsorted(grid, targets), 1, grid.size - 1)
    idx = np.where(np.abs(grid[idx - 1] - targets) <= np.abs(grid[idx] - targets), idx - 1, idx)
    return grid[np.unique(np.concatenate([[0], idx, [grid.size - 1]]))]


def _split_speed(Va: float, Vb: float, grid: np.ndarray) -> float:
    """Where to bisect the step (Va, Vb): the grid speed nearest its middle if one lies in its
    middle half (so refined sweeps report at asked speeds), else the midpoint."""
    mid = 0.5 * (Va + Vb)
    q = 0.25 * (Vb - Va)
    inside = grid[(grid > mid - q) & (grid < mid + q)]
    return float(inside[np.argmin(np.abs(inside - mid))]) if inside.size else mid


def sweep(state_matrix: StateMatrixFn, speeds, *, n_dof: int | None = None,
          displacement=None, state_labels: Sequence[str] | None = None,
          mode_labels: Sequence[str] | Callable[[complex, np.ndarray], str] | None = None,
          options: TrackingOptions | None = None) -> Sweep:
    """Eigen-analysis along the speeds with mode tracking (see the module docstring).

    speeds: increasing grid [m/s], all > 0 (the aerodynamic matrices carry 1/V); every grid
    speed is evaluated (the V-g-f table), and the grid is refined automatically where
    tracking is ambiguous and where a hump may hide between samples.
    """
    opts = options or TrackingOptions()
    grid = _check_speeds(speeds)
    labels = None if state_labels is None else tuple(str(s) for s in state_labels)
    with single_thread_blas():
        return _sweep(state_matrix, grid, n_dof, displacement, labels, mode_labels, opts)


def _sweep(fn, grid, n_dof, displacement, labels, mode_labels, opts,
           initial_step: float | None = None) -> Sweep:
    stats: dict[str, int] = {}
    n = None if labels is None else len(labels)
    nodes = _evaluate_nodes(fn, _initial_subset(grid, initial_step), n, labels, opts, stats)
    n = nodes[0].lam.size
    if labels is None:
        labels = tuple(f"x{i}" for i in range(n))
    disp = _displacement_mask(n, n_dof, displacement)
    budget = opts.max_nodes or (20 * grid.size + 200)
    links: dict[tuple[float, float], _Link] = {}
    refined = 0
    while True:
        new_V = []
        located = []
        for a, b in zip(nodes[:-1], nodes[1:]):
            key = (a.V, b.V)
            if key in links:
                continue
            lk = _link(a, b, disp, opts)
            if (lk.ambiguous and 0.5 * (b.V - a.V) >= opts.min_step
                    and len(nodes) + len(new_V) < budget):
                if lk.branch_points:        # refine there: bracket the unstable branch point
                    located.append((a, b, lk))
                else:
                    new_V.append(_split_speed(a.V, b.V, grid) if lk.split_at is None
                                 else lk.split_at)
                continue
            links[key] = lk
        if located:
            found = _branch_point_speeds(fn, located, n, labels, opts, stats)
            stats["branch_point_nodes"] = stats.get("branch_point_nodes", 0) + len(found)
            for a, b, _ in located:
                here = [v for v in found if a.V < v < b.V]
                new_V += here if here else [_split_speed(a.V, b.V, grid)]
        if not new_V:
            chain = [links[(a.V, b.V)] for a, b in zip(nodes[:-1], nodes[1:])]
            R = _order_chain(nodes, [lk.perm for lk in chain])
            if not opts.hump_check:
                break
            V = np.array([nd.V for nd in nodes])
            fl = np.array([nd.floor for nd in nodes])
            new_V = _hump_candidates(V, _step_models(nodes, R, chain), fl, opts)
            stats["hump_refined"] = stats.get("hump_refined", 0) + len(new_V)
            if not new_V:
                new_V = _branch_point_speeds(fn, list(zip(nodes[:-1], nodes[1:], chain)), n,
                                             labels, opts, stats)
                stats["branch_point_nodes"] = stats.get("branch_point_nodes", 0) + len(new_V)
            new_V = new_V[: max(0, budget - len(nodes))]
            if not new_V:
                break
        else:
            refined += len(new_V)
        nodes = sorted(nodes + _evaluate_nodes(fn, np.array(new_V), n, labels, opts, stats),
                       key=lambda nd: nd.V)
    stats["refined"] = refined
    stats["nodes"] = len(nodes)
    unresolved = tuple((a.V, b.V) for a, b in zip(nodes[:-1], nodes[1:])
                       if links[(a.V, b.V)].ambiguous)
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
    X *= phase[:, None, :]
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
_EPS = float(np.finfo(float).eps)


def _residual_ok(res: float, lam: complex, noise: float, rel: float, floor_mult: float) -> bool:
    """‖A x − λ x‖ small relative to the eigenvalue (rel·|λ|) or at the rounding floor of A x.

    ``noise`` = eps·‖|A| |x|‖ is what rounding alone leaves in A x for this x (for the badly
    scaled state matrices of stiff structures ‖A‖ ≫ |λ|, so a tolerance on ‖A‖ would accept
    residuals of the size of the low eigenvalues themselves).
    """
    return res <= max(rel * abs(lam), floor_mult * noise)


def _inverse_iteration(A: np.ndarray, sigma: complex, x0: np.ndarray, tol: float = 1e-12,
                       maxit: int = 40) -> tuple[complex, np.ndarray, bool]:
    """Shifted inverse iteration for the eigenvalue of A nearest σ (Rayleigh quotient).

    Real arithmetic when σ is real (divergence roots); the shift is updated to the Rayleigh
    quotient (one new LU) if convergence stalls.  Converged when the residual
    ‖A x − λ x‖ ≤ max(tol·|λ|, 64 eps ‖|A||x|‖) (scaled by the eigenvalue, or at the rounding
    floor of the product A x); after stalling, accepted ("converged" False → the caller falls
    back to a full eigendecomposition) only if ≤ max(1e-8 |λ|, 1e3 eps ‖|A||x|‖).  Returns
    (λ, unit x, converged).
    """
    n = A.shape[0]
    use_real = sigma.imag == 0 and not np.iscomplexobj(x0)
    dt = float if use_real else complex
    absA = np.abs(A)
    x = np.asarray(x0, dtype=dt)
    x = x / np.linalg.norm(x)
    shift = sigma.real if use_real else sigma
    lam = complex(shift)
    res, noise = np.inf, 0.0
    eye = np.eye(n)
    for _attempt in range(3):
        Ms = A - shift * eye
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
            Ax = A @ x if use_real else (A @ x.real) + 1j * (A @ x.imag)
            lam = complex(np.vdot(x, Ax))
            res = float(np.linalg.norm(Ax - lam * x))
            noise = _EPS * float(np.linalg.norm(absA @ np.abs(x)))
            if _residual_ok(res, lam, noise, tol, 64.0):
                return lam, x, True
            if res > 0.5 * prev:      # stalled: refactor at the Rayleigh quotient
                break
            prev = res
        shift = lam.real if use_real else lam
    return lam, x, _residual_ok(res, lam, noise, 1e-8, 1e3)


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
        return lam, np.asarray(x, dtype=complex), False
    stats["fallback_eig"] = stats.get("fallback_eig", 0) + 1
    w, X = np.linalg.eig(A)
    w, X = w.astype(complex), X.astype(complex)
    m = mac(x0[disp][:, None], X[disp]).ravel()
    s = max(abs(sigma), 1e-12)
    j = int(np.argmin((1 - m) + np.abs(w - sigma) / s))
    return complex(w[j]), X[:, j], True


def _real_vector(x: np.ndarray) -> np.ndarray:
    """The real vector of a (numerically) real eigenvector given with an arbitrary phase."""
    big = x[np.argmax(np.abs(x))]
    return (x * (np.conj(big) / abs(big))).real if big != 0 else np.ones(x.size)


def _zero_root(A: np.ndarray, x0: np.ndarray, stats: dict[str, int]
               ) -> tuple[complex, np.ndarray, bool, float]:
    """The real eigenvalue nearest zero (real inverse iteration at shift 0) and sign det A.

    Returns (λ, x, converged-and-real, sign det A).  sign det A = (−1)^(number of negative
    real eigenvalues): it flips exactly when a real root crosses zero, whatever its identity.
    """
    sign, _ = np.linalg.slogdet(A)
    lam, x, ok = _inverse_iteration(A, 0j, _real_vector(np.asarray(x0, dtype=complex)))
    stats["inverse_iterations"] = stats.get("inverse_iterations", 0) + 1
    return complex(lam), np.asarray(x, dtype=complex), bool(ok and lam.imag == 0), float(sign)


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

    def shape(self, V: float) -> np.ndarray:
        s = float(np.clip((V - self.Va) / (self.Vb - self.Va), 0.0, 1.0))
        x = (1 - s) * self.xa + s * self.xb
        return x / np.linalg.norm(x)


class _RootBracket:
    """Safeguarded root bracketing by rounds of two evaluations (one batched model call).

    Each round evaluates f at the current prediction ± δ (δ = 0.45 × the target width): if
    the root lies between them the bracket closes at once (width 0.9 × target); otherwise
    their secant — a local slope — gives a Newton step for the next prediction, with a
    bisection when that leaves the bracket or the bracket stops halving.  ``f`` values that
    carry only a sign (``valid`` False) update the bracket but give no slope.
    """

    def __init__(self, lo: float, hi: float, flo: float, fhi: float, guess: float,
                 width: float, centre: bool = False):
        self.lo, self.hi, self.flo, self.fhi = lo, hi, flo, fhi
        self.guess, self.width, self.stall = guess, width, 0
        self.centre, self.rounds = centre, 0

    @property
    def closed(self) -> bool:
        return self.hi - self.lo <= self.width

    def proposals(self) -> list[float]:
        """g ± δ; with ``centre``, after the first round also g itself (a Newton prediction
        from a local slope is usually that accurate, and then g is the root's evaluation)."""
        d = 0.45 * self.width
        c = float(np.clip(self.guess, self.lo + d, self.hi - d))
        return [c - d, c, c + d] if self.centre and self.rounds else [c - d, c + d]

    def feed(self, values: dict[float, tuple[float, bool]]) -> None:
        width = self.hi - self.lo
        self.rounds += 1
        for V in sorted(values):
            f = values[V][0]
            if not self.lo < V < self.hi:
                continue
            if f == 0.0:
                self.lo = self.hi = V
                self.flo = self.fhi = 0.0
                return
            if np.sign(f) == np.sign(self.flo):
                self.lo, self.flo = V, f
            else:
                self.hi, self.fhi = V, f
        if self.closed:
            return
        pts = sorted(values.items())
        (u1, (f1, ok1)), (u2, (f2, ok2)) = pts[0], pts[-1]
        self.stall = self.stall + 1 if self.hi - self.lo > 0.5 * width else 0
        r = np.nan
        if ok1 and ok2 and f1 != f2:
            r = 0.5 * (u1 + u2) - 0.5 * (f1 + f2) * (u2 - u1) / (f2 - f1)
        if self.stall >= 2 or not (self.lo < r < self.hi):
            r = 0.5 * (self.lo + self.hi)
            self.stall = 0
        self.guess = float(r)

    def interpolate(self) -> float:
        """The root by linear interpolation inside the bracket."""
        if self.fhi == self.flo:
            return 0.5 * (self.lo + self.hi)
        return self.lo - self.flo * (self.hi - self.lo) / (self.fhi - self.flo)


def _pair_discriminant(A: np.ndarray, Q0: np.ndarray, sigma: float, maxit: int = 12
                       ) -> tuple[float, float, np.ndarray, bool]:
    """Discriminant D = ((λ1 − λ2)/2)² and mean (λ1 + λ2)/2 of a pair of eigenvalues of A.

    Real subspace (block inverse) iteration with the real shift σ from the real basis
    ``Q0`` (n, 2) of the pair's invariant subspace at a nearby speed; λ1,2 are the
    eigenvalues of the 2 × 2 matrix H = Qᵀ A Q.  D < 0: a complex pair, D > 0: two real
    roots; D and the mean are analytic through the branch point D = 0, where single roots are
    not.  Returns (D, mean, Q, converged: ‖A Q − Q H‖ at the rounding floor or ≤ 1e-10 |λ|).
    """
    n = A.shape[0]
    absA = np.abs(A)
    with np.errstate(all="ignore"):
        lu = sla.lu_factor(A - sigma * np.eye(n), check_finite=False)
    Q, _ = np.linalg.qr(Q0)
    ok = False
    H = Q.T @ A @ Q
    for _ in range(maxit):
        Z = sla.lu_solve(lu, Q, check_finite=False)
        if not np.all(np.isfinite(Z)):
            break
        Q, _ = np.linalg.qr(Z)
        AQ = A @ Q
        H = Q.T @ AQ
        res = float(np.linalg.norm(AQ - Q @ H))
        noise = _EPS * float(np.linalg.norm(absA @ np.abs(Q)))
        scale = float(np.sqrt(abs(np.linalg.det(H))))
        if _residual_ok(res, scale, noise, 1e-10, 64.0):
            ok = True
            break
    tr2 = 0.5 * (H[0, 0] + H[1, 1])
    D = float(((H[0, 0] - H[1, 1]) / 2) ** 2 + H[0, 1] * H[1, 0])
    return D, float(tr2), Q, ok


class _BranchPoint:
    """Location of the branch point inside a step where a pair turns into two real roots.

    Root of the pair's discriminant D(V) (:func:`_pair_discriminant`), analytic and with a
    simple zero there; started from its cubic Hermite model (D = ((λ1 − λ2)/2)²,
    D' = (λ1 − λ2)(λ1' − λ2')/2 at both samples), bracketed to ``width`` by
    :class:`_RootBracket`.
    """

    def __init__(self, a: _Node, b: _Node, i: int, ic: int, j: int, jc: int, width: float):
        h = b.V - a.V
        da = ((a.lam[i] - a.lam[ic]) / 2) ** 2
        db = ((b.lam[j] - b.lam[jc]) / 2) ** 2
        ga = (a.lam[i] - a.lam[ic]) * (a.dlam[i] - a.dlam[ic]) / 2
        gb = (b.lam[j] - b.lam[jc]) * (b.dlam[j] - b.dlam[jc]) / 2
        c = tuple(np.real(x) for x in _hermite_coeffs(da, db, ga, gb, h))
        roots = np.roots([c[3], c[2], c[1], c[0]]) if any(ci != 0 for ci in c[1:]) else []
        roots = [r.real for r in np.atleast_1d(roots) if abs(r.imag) < 1e-12 and 0 < r.real < 1]
        fa, fb = float(np.real(da)), float(np.real(db))
        s0 = roots[0] if roots else (fa / (fa - fb) if fa != fb else 0.5)
        self.mean = tuple(np.real(x) for x in _hermite_coeffs(
            0.5 * (a.lam[i] + a.lam[ic]), 0.5 * (b.lam[j] + b.lam[jc]),
            0.5 * (a.dlam[i] + a.dlam[ic]), 0.5 * (b.dlam[j] + b.dlam[jc]), h))
        self.Va, self.Vb = a.V, b.V
        self.Q = {a.V: np.stack([a.X[:, i].real, a.X[:, i].imag], axis=1),
                  b.V: np.stack([b.X[:, j].real, b.X[:, jc].real], axis=1)}
        self.m: dict[float, float] = {}
        self.rb = _RootBracket(a.V, b.V, fa, fb, a.V + float(s0) * h, width)

    @classmethod
    def from_estimate(cls, a: _Node, i: int, ic: int, V_est: float, sigma: float, Vb: float,
                      width: float) -> "_BranchPoint":
        """The pair (i, ic) of ``a`` turns real near V_est (double root ≈ sigma) before Vb,
        after which it need not exist any more (a member may merge with another root)."""
        self = cls.__new__(cls)
        self.mean = (sigma, 0.0, 0.0, 0.0)
        self.Va, self.Vb = a.V, Vb
        self.Q = {a.V: np.stack([a.X[:, i].real, a.X[:, i].imag], axis=1)}
        self.m = {a.V: sigma}
        fa = float(np.real(((a.lam[i] - a.lam[ic]) / 2) ** 2))
        self.rb = _RootBracket(a.V, Vb, fa, 1e-300, V_est, width)
        return self

    def evaluate(self, V: float, A: np.ndarray) -> tuple[float, bool]:
        Vn = min(self.Q, key=lambda u: abs(u - V))
        sigma = self.m.get(Vn, float(_hermite_eval(self.mean, (V - self.Va) / (self.Vb - self.Va))))
        D, mean, Q, ok = _pair_discriminant(A, self.Q[Vn], sigma)
        if ok:
            self.Q[V], self.m[V] = Q, mean
        return D, ok


def _branch_point_speeds(fn, steps: list[tuple[_Node, _Node, _Link]], n: int, labels,
                         opts: TrackingOptions, stats: dict[str, int]) -> list[float]:
    """Speeds bracketing each unstable pair that turns into two real roots inside a step.

    The frequency of such a mode falls to zero at the branch point (the thesis's "whirl
    divergence" of an already unstable whirl mode); two nodes 0.9·min_step apart around it
    make the V-g-f data show it where it is, and let a caller bisecting on the sweep's samples
    start from that bracket.  Pairs already bracketed that tightly are left alone.
    """
    jobs = []
    width = 0.9 * opts.min_step
    for a, b, lk in steps:
        if b.V - a.V <= opts.min_step:
            continue
        seen = set()
        for V_est, i, ic, sigma in lk.branch_points:
            jobs.append(_BranchPoint.from_estimate(a, i, ic, V_est, sigma, b.V, width))
            seen.update((i, ic))
        for i in np.nonzero((a.lam.imag > 0) & (a.lam.real > 0))[0]:
            ic = a.conj[i]
            j, jc = lk.perm[i], lk.perm[ic]
            if i not in seen and b.lam[j].imag == 0 and b.lam[jc].imag == 0 and max(
                    b.lam[j].real, b.lam[jc].real) > 0:
                jobs.append(_BranchPoint(a, b, int(i), int(ic), int(j), int(jc), width))
    pending = [job for job in jobs if not job.rb.closed]
    for _round in range(12):
        if not pending:
            break
        asks = [(job, v) for job in pending for v in job.rb.proposals()]
        speeds = np.array(sorted({v for _, v in asks}))
        A = _call_state_matrix(fn, speeds, n, labels)
        stats["branch_point_evaluations"] = stats.get("branch_point_evaluations", 0) + len(asks)
        for job in pending:
            job.rb.feed({v: job.evaluate(v, A[int(np.searchsorted(speeds, v))])
                         for j2, v in asks if j2 is job})
        pending = [job for job in pending if not job.rb.closed]
    out = []
    for job in jobs:
        if job.rb.closed:
            out += [v for v in (job.rb.lo, job.rb.hi) if job.Va < v < job.Vb]
    return sorted(set(out))


class _Crossing:
    """Refinement of one sign change of Re λ of a tracked branch, by batched rounds.

    Each round asks for speeds (:meth:`requests`), the caller evaluates the state matrices of
    all crossings in one model call and feeds them back (:meth:`feed`).

    * kind "flutter" — Re λ of the tracked mode (shifted inverse iteration at the
      prediction, identity checked by MAC, full-eig fallback);
    * kind "divergence" — the real root through zero: the real eigenvalue nearest zero
      (inverse iteration at shift 0), accepted only where its sign agrees with sign det A
      (relative to the bracket's ends); elsewhere only that sign is known and the step is a
      bisection.  Exact whichever real root the branch owns (e.g. after a pair split).

    Bracketing (:class:`_RootBracket`): two evaluations at the predicted root ± 0.45 xtol;
    their sign change closes the bracket (width 0.9 xtol) at once, otherwise their secant
    gives a Newton prediction (local slope), evaluated with its neighbours ± 0.45 xtol —
    usually the root's own evaluation then, reported as the crossing — safeguarded by
    bisection.  Otherwise the crossing (linear interpolation in the final bracket) is
    evaluated in one more round.  Benignity: dλ/dV at the crossing from a forward difference
    of A (one more state matrix in the same round), or a central difference of ζ when
    ``benignity_step`` is given.
    """

    def __init__(self, res: Sweep, k: int, t0: int, t1: int, kind: str, xtol: float,
                 bstep: float | None, det_signs: np.ndarray):
        self.res, self.k, self.kind, self.xtol, self.bstep = res, k, kind, xtol, bstep
        self.t0, self.t1 = t0, t1
        la, lb = res.eigenvalues[t0, k], res.eigenvalues[t1, k]
        self.Va, self.Vb = float(res.V[t0]), float(res.V[t1])
        self.direction = "onset" if lb.real > la.real else "recovery"
        coeffs = _hermite_coeffs(la, lb, res.dlam_dV[t0, k], res.dlam_dV[t1, k],
                                 self.Vb - self.Va)
        self.br = _Bracket(self.Va, self.Vb, coeffs, res.eigenvectors[t0, :, k],
                           res.eigenvectors[t1, :, k])
        self.real_root = la.imag == 0 and lb.imag == 0
        self.det_a = float(det_signs[t0])
        self.points: dict[float, tuple[float, complex, np.ndarray, bool]] = {}
        self.rb = _RootBracket(self.Va, self.Vb, float(la.real), float(lb.real),
                               self._initial_guess(res, k, t0, t1), xtol, centre=True)
        self.phase = "final" if self.rb.closed else "bracket"
        self.result: CriticalPoint | None = None

    # -- predictions ------------------------------------------------------------------------
    def _initial_guess(self, res, k, t0, t1) -> float:
        la, lb = res.eigenvalues[t0, k], res.eigenvalues[t1, k]
        f = None
        if self.kind == "divergence" and (la.imag != 0) != (lb.imag != 0):
            f = self._product_model(res, k, t0, t1)
        if f is None:
            f = tuple(np.real(c) for c in self.br.coeffs)
        c = f
        roots = np.roots([c[3], c[2], c[1], c[0]]) if any(ci != 0 for ci in c[1:]) else []
        roots = [r.real for r in np.atleast_1d(roots) if abs(r.imag) < 1e-12 and 0 <= r.real <= 1]
        s0 = roots[0] if roots else (la.real / (la.real - lb.real) if la.real != lb.real
                                     else 0.5)
        return self.Va + float(s0) * (self.Vb - self.Va)

    @staticmethod
    def _product_model(res, k, t0, t1):
        """Hermite model of the product of the pair's two roots over a split/merge step (it
        crosses zero with the real root), or None when the pair cannot be identified."""
        lam, dl = res.eigenvalues, res.dlam_dV
        tc = t0 if lam[t0, k].imag != 0 else t1
        others = np.abs(lam[tc] - np.conj(lam[tc, k]))
        others[k] = np.inf
        kp = int(np.argmin(others))
        if others[kp] > 1e-9 * max(abs(lam[tc, k]), 1e-300):
            return None
        tr = t1 if tc == t0 else t0
        if lam[tr, k].imag != 0 or lam[tr, kp].imag != 0:
            return None
        p = [lam[t, k] * lam[t, kp] for t in (t0, t1)]
        dp = [dl[t, k] * lam[t, kp] + lam[t, k] * dl[t, kp] for t in (t0, t1)]
        c = _hermite_coeffs(p[0], p[1], dp[0], dp[1], res.V[t1] - res.V[t0])
        return tuple(np.real(ci) for ci in c)

    def _nearest(self, V: float):
        if not self.points:
            return None
        Vn = min(self.points, key=lambda u: abs(u - V))
        return self.points[Vn]

    def _sigma(self, V: float) -> complex:
        """Shift: linear model through the two nearest evaluations, else the Hermite model."""
        good = [(u, p[1]) for u, p in self.points.items() if p[3]]
        if len(good) >= 2:
            (u1, l1), (u2, l2) = sorted(good, key=lambda q: abs(q[0] - V))[:2]
            if u1 != u2:
                sig = l1 + (l2 - l1) * (V - u1) / (u2 - u1)
                return complex(sig.real, 0.0) if self.real_root else complex(sig)
        sig = self.br.predict(V)
        return complex(sig.real, 0.0) if self.real_root else sig

    # -- rounds -----------------------------------------------------------------------------
    @property
    def done(self) -> bool:
        return self.phase == "done"

    def _fd(self, V: float) -> float:
        return 1e-6 * max(V, 1.0)

    def requests(self) -> list[tuple[float, bool]]:
        """Speeds of this round: (V, True) for an evaluation of the mode, (V, False) for a
        state matrix only (the forward difference of dλ/dV for the benignity)."""
        if self.phase == "bracket":
            pts = self.rb.proposals()
            out = [(v, True) for v in pts]
            if self.kind == "flutter" and self.bstep is None and len(pts) == 3:
                out.append((pts[1] + self._fd(pts[1]), False))
            return out
        self.Vc = self.rb.interpolate()
        out = [(self.Vc, True)]
        if self.kind == "flutter":
            if self.bstep is None:
                out.append((self.Vc + self._fd(self.Vc), False))
            else:
                out += [(self.Vc - self.bstep, True), (self.Vc + self.bstep, True)]
        return out

    def evaluate(self, V: float, A: np.ndarray, stats: dict[str, int], final: bool = False
                 ) -> tuple[float, complex, np.ndarray, bool]:
        """(f, λ, x, f is a value rather than a sign) at speed V; ``final``: the crossing
        itself, where a divergence root that the iteration could not isolate is taken from a
        full eigendecomposition (the real eigenvalue nearest zero)."""
        near = self._nearest(V)
        if self.kind == "flutter":
            x0 = near[2] if near is not None else self.br.shape(V)
            lam, x, _ = _eval_mode(A, self._sigma(V), x0, self.res.displacement, 0.5, stats)
            return float(lam.real), lam, x, True
        real_b = self.res.eigenvalues[self.t1, self.k].imag == 0
        x0 = near[2] if near is not None else (self.br.xb if real_b else self.br.xa)
        lam, x, ok, sign = _zero_root(A, x0, stats)
        want = np.sign(self.rb.flo) if sign == self.det_a else np.sign(self.rb.fhi)
        if ok and (final or (np.sign(lam.real) == want and lam.real != 0)):
            return float(lam.real), lam, x, True
        if final:
            stats["fallback_eig"] = stats.get("fallback_eig", 0) + 1
            w, X = np.linalg.eig(A)
            j = int(np.argmin(np.abs(w) + np.where(w.imag == 0, 0.0, np.inf)))
            return float(w[j].real), complex(w[j]), X[:, j].astype(complex), True
        stats["sign_only"] = stats.get("sign_only", 0) + 1
        return float(want) * 1e-300, lam, x, False

    def feed(self, values: dict[float, tuple[float, complex, np.ndarray, bool]],
             mats: dict[float, np.ndarray], stats: dict[str, int]) -> None:
        self.points.update(values)
        if self.phase == "bracket":
            self.rb.feed({V: (v[0], v[3]) for V, v in values.items()})
            if not self.rb.closed:
                return
            mid = sorted(values)[1] if len(values) == 3 and self.bstep is None else None
            if mid is not None and self.rb.lo <= mid <= self.rb.hi and values[mid][3]:
                self._finish(mid, values, mats, stats)        # the Newton point is the root's
                return
            self.phase = "final"
            return
        self._finish(self.Vc, values, mats, stats)

    def _finish(self, Vc: float, values, mats, stats) -> None:
        _, lam_c, x_c, _ = values[Vc]
        if self.kind == "divergence":
            lam_c = complex(lam_c.real, 0.0) if lam_c.imag == 0 else lam_c
        if lam_c.imag < 0:
            lam_c, x_c = lam_c.conjugate(), x_c.conj()
        dz = ben = None
        if self.kind == "flutter":
            if self.bstep is None:
                h = self._fd(Vc)
                dlam = _eigenvalue_derivative(mats[Vc], (mats[Vc + h] - mats[Vc]) / h, lam_c,
                                              x_c, stats)
                dz = _dzeta(lam_c, dlam)
            else:
                h = self.bstep
                dz = (_zeta(values[Vc + h][1]) - _zeta(values[Vc - h][1])) / (2 * h)
            ben = 1.0 / dz if dz != 0 else None
        res = self.res
        self.result = CriticalPoint(
            mode=self.k, label=res.mode_labels[self.k], kind=self.kind,
            direction=self.direction, V=float(Vc), bracket=(self.rb.lo, self.rb.hi),
            frequency_hz=abs(lam_c.imag) / (2 * np.pi), eigenvalue=lam_c, dzeta_dV=dz,
            benignity=ben, eigenvector=x_c)
        self.phase = "done"


def _eigenvalue_derivative(A: np.ndarray, dA: np.ndarray, lam: complex, x: np.ndarray,
                           stats: dict[str, int]) -> complex:
    """dλ/dV = wᵀ A' x / (wᵀ x) at a simple eigenpair (λ, x) of real A; w solves Aᵀ w = λ w
    (the conjugate of the left eigenvector), by two steps of inverse iteration at λ."""
    n = A.shape[0]
    with np.errstate(all="ignore"):
        lu = sla.lu_factor(A - (lam * (1 + 1e-13) + 1e-300) * np.eye(n), check_finite=False)
        w = np.asarray(x, dtype=complex).conj()
        for _ in range(2):
            w = sla.lu_solve(lu, w, trans=1, check_finite=False)
            w /= np.linalg.norm(w)
        d = complex((w @ (dA @ x)) / (w @ x))
    stats["left_vectors"] = stats.get("left_vectors", 0) + 1
    return d if np.isfinite(d) else 0j


def _dzeta(lam: complex, dlam: complex) -> float:
    """dζ/dV of ζ = −Re λ/|λ| (eq. 5.5) from dλ/dV."""
    m = abs(lam)
    if m == 0:
        return 0.0
    return float(-(dlam.real * m * m - lam.real * (lam.conjugate() * dlam).real) / m ** 3)


def critical_points(result: Sweep, state_matrix: StateMatrixFn, *, xtol: float = 1e-3,
                    benignity_step: float | None = None, zero_tol: float = 1e-9) -> Criticals:
    """Every sign change of a tracked mode's Re λ, refined to ``xtol`` [m/s].

    Eigenvalue-only: each evaluation is a state matrix (batched over all crossings per round)
    and a shifted inverse iteration (see :class:`_Crossing`).  Flutter if Im λ ≠ 0 at the
    crossing, divergence if the root is real there.  Benignity (eq. 5.13) = (dζ/dV)⁻¹ with
    dζ/dV from dλ/dV = wᵀA'x/(wᵀx) at the crossing (A' by a forward difference of step
    1e-6·max(V, 1 m/s)); with ``benignity_step`` [m/s] given, by a central difference of ζ of
    that step instead.
    """
    positive("xtol", xtol, "m/s")
    if benignity_step is not None:
        positive("benignity_step", benignity_step, "m/s")
    with single_thread_blas():
        return _critical_points(result, state_matrix, xtol, benignity_step, zero_tol)


def _det_signs(lam: np.ndarray) -> np.ndarray:
    """sign det A at each sample from its eigenvalues: (−1)^(number of negative real roots)."""
    neg = np.count_nonzero((lam.imag == 0) & (lam.real < 0), axis=1)
    return np.where(neg % 2 == 1, -1.0, 1.0)


def _critical_points(res: Sweep, fn, xtol, bstep, zero_tol) -> Criticals:
    if res.eigenvectors is None:
        raise InputError("critical_points needs a Sweep with eigenvectors (to start the "
                         "inverse iterations); this one was saved without them")
    stats: dict[str, int] = {}
    lam, V = res.eigenvalues, res.V
    tol = zero_tol * np.maximum(np.abs(lam), res.floor[:, None])
    sgn = np.where(np.abs(lam.real) <= tol, 0, np.sign(lam.real)).astype(int)
    dets = _det_signs(lam)
    jobs: list[_Crossing] = []
    for k in range(res.n_modes):
        idx = np.nonzero(sgn[:, k] != 0)[0]
        for t0, t1 in zip(idx[:-1], idx[1:]):
            if sgn[t0, k] == sgn[t1, k] or not res.physical[t0:t1 + 1, k].any():
                continue
            ca, cb = lam[t0, k].imag != 0, lam[t1, k].imag != 0
            if ca != cb:
                kind = "divergence" if dets[t0] != dets[t1] else "flutter"
            else:
                kind = "flutter" if ca else "divergence"
            if kind == "flutter" and not (res.physical[t0, k] and res.physical[t1, k]):
                continue                      # the hidden conjugate of a crossing pair
            jobs.append(_Crossing(res, k, int(t0), int(t1), kind, xtol, bstep, dets))
    n = res.eigenvalues.shape[1]
    pending = jobs
    while pending:
        asks = [(job, v, ev) for job in pending for v, ev in job.requests()]
        speeds = np.array(sorted({v for _, v, _ in asks}))
        A = _call_state_matrix(fn, speeds, n, res.state_labels)
        stats["state_matrix_calls"] = stats.get("state_matrix_calls", 0) + 1
        for job in pending:
            final = job.phase == "final"
            mats = {v: A[int(np.searchsorted(speeds, v))] for j2, v, _ in asks if j2 is job}
            vals = {v: job.evaluate(v, mats[v], stats, final)
                    for j2, v, ev in asks if j2 is job and ev}
            stats["evaluations"] = stats.get("evaluations", 0) + len(vals)
            job.feed(vals, mats, stats)
        pending = [job for job in pending if not job.done]
    pts = sorted((job.result for job in jobs if job.result is not None), key=lambda p: p.V)
    humps = []
    for k in range(res.n_modes):
        mine = [p for p in pts if p.mode == k]
        for p, q in zip(mine[:-1], mine[1:]):
            if p.direction == "onset" and q.direction == "recovery":
                humps.append(Hump(k, p.label, p.kind, p.V, q.V))
    start = tuple(int(k) for k in np.nonzero((sgn[0] > 0) & res.physical[0])[0])
    return Criticals(tuple(pts), tuple(humps), start, stats)


def _zeta(lam: complex) -> float:
    return -lam.real / abs(lam) if lam != 0 else 0.0


def analyse(state_matrix: StateMatrixFn, speeds, *, n_dof: int | None = None,
            displacement=None, state_labels: Sequence[str] | None = None,
            mode_labels=None, options: TrackingOptions | None = None,
            xtol: float = 1e-3, benignity_step: float | None = None,
            initial_step: float | None = ANALYSE_INITIAL_STEP) -> Analysis:
    """:func:`sweep` followed by :func:`critical_points` (one BLAS-limited context).

    Locating the critical speeds does not need an eigendecomposition at every grid speed: the
    sweep starts from the grid speeds nearest an even division of the range at spacing
    ``initial_step`` [m/s] (default :data:`ANALYSE_INITIAL_STEP`; first and last speed always)
    and the tracker adds speeds — grid speeds where they fall in the middle of a step — only
    where the assignment is ambiguous or a Hermite model of Re λ may hide a crossing (see
    :class:`TrackingOptions`).  So ``Analysis.sweep.V`` is not the whole grid: for a V-g-f
    table at every grid speed use :func:`sweep` (or ``initial_step=None``).
    """
    opts = options or TrackingOptions()
    grid = _check_speeds(speeds)
    positive("xtol", xtol, "m/s")
    if initial_step is not None:
        positive("initial_step", initial_step, "m/s")
    labels = None if state_labels is None else tuple(str(s) for s in state_labels)
    with single_thread_blas():
        sw = _sweep(state_matrix, grid, n_dof, displacement, labels, mode_labels, opts,
                    initial_step)
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
