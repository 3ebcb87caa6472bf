"""Full-order correction of a crossing found on a reduced model.

A reduced model (:mod:`propwhirl.model.reduction`) locates the crossings Re λ(V) = 0 cheaply;
:func:`correct_crossing` converges each one on the *full-order* sparse pencil F x = λ E x of the
model (:meth:`propwhirl.model.blocks.BlockSystem.pencil`), so the reported speed does not carry
the truncation error, and the shift it makes is that error's measure.

At each speed the root continuing the reduced one is found by shifted inverse iteration on a
sparse LU factorisation of F − σE (σ: the current estimate; Rayleigh quotient λ = xᴴFx / xᴴEx;
converged when the residual ‖Fx − λEx‖ is below ``RESIDUAL_TOL`` · (‖F‖ + |λ|‖E‖) ‖x‖, the
factorisation renewed at the new estimate when it is slow).  The crossing speed is then found by
the secant method on Re λ(V) — its first step Newton's with the reduced root's slope — until the
next step is below xtol/10 (the crossing is then that step's speed; λ and the vector are those of
the last evaluation, less than xtol/10 away).  A reduced crossing within xtol/10 of the full one
therefore costs one evaluation: the full-order root at the reduced crossing and Newton's step.  The root must stay the same branch (MAC with the previous vector ≥
``BRANCH_MAC``); a failure returns None, and the caller keeps the reduced result.  Cost: a few
sparse factorisations of the full pencil per crossing — linear in the number of elements for
the banded wing.

:func:`full_order_pair` decides the other kind of event a reduced model finds, the branch point
where an unstable pair turns into two real roots: the two roots of the pencil nearest a real
shift σ, by block inverse iteration on a real two-dimensional subspace (their invariant subspace
is smooth through the branch point, where each eigenvector alone is not) and the
Rayleigh–Ritz pencil of that subspace, whose 2 × 2 real eigenproblem says exactly whether the
pair is complex or real.
"""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from propwhirl.engine.eigensolve import mac

#: residual of a converged eigenpair, relative to (‖F‖ + |λ|‖E‖)‖x‖
RESIDUAL_TOL = 1e-10
#: MAC between successive vectors of one branch
BRANCH_MAC = 0.5
#: secant iterations allowed
MAX_SECANT = 25

Pencil = Callable[[float], tuple[sp.spmatrix, sp.spmatrix]]


@dataclass(frozen=True)
class Corrected:
    """A crossing on the full-order model: V [m/s], λ [1/s] and the unit eigenvector there,
    the secant iterations used and the number of pencil evaluations."""

    V: float
    eigenvalue: complex
    eigenvector: np.ndarray
    iterations: int
    evaluations: int


def real_direction(x: np.ndarray) -> np.ndarray:
    """The real vector of a real root's eigenvector given with any complex phase e^{iφ}
    (rotated so that its largest entry is real, then the real part: never the vanishing real
    part of a vector whose phase is near ±π/2)."""
    x = np.asarray(x)
    if not np.iscomplexobj(x):
        return x.astype(float)
    k = int(np.argmax(np.abs(x)))
    return np.real(x * (np.conj(x[k]) / abs(x[k]))) if abs(x[k]) > 0 else np.real(x)


def norm1(A) -> float:
    """‖A‖₁, the largest column sum of |a_ij| of a sparse matrix: ``scipy.sparse.linalg.norm(A,
    1)`` to the last bit without its temporary matrices.  That norm adds each column's |a_ij|
    one at a time by increasing row from 0 (a product with a vector of ones); so does this, for
    the stored entries of a canonical CSC matrix (rows increasing), all columns at once — one
    vector addition per entry of the longest column.  Any other matrix: that norm."""
    if not (sp.issparse(A) and A.format == "csc" and A.has_canonical_format and A.nnz):
        return spla.norm(A, 1)
    count = np.diff(A.indptr)
    column = np.repeat(np.arange(count.size), count)
    place = np.arange(A.nnz) - A.indptr[column]           # the entry's place in its column
    by_place = np.zeros((int(count.max()), count.size))
    by_place[place, column] = np.abs(A.data)
    total = np.zeros(count.size)
    for row in by_place:                    # adding a zero (past a column's end) is exact
        total += row
    return total.max()


def full_order_root(F, E, sigma: complex, x0: np.ndarray, max_iter: int = 40
                    ) -> tuple[complex, np.ndarray] | None:
    """The eigenpair of F x = λ E x nearest the shift ``sigma`` reached from ``x0``, by shifted
    inverse iteration on a sparse LU (module docstring); None if it does not converge."""
    real = np.isrealobj(x0) and np.imag(sigma) == 0
    dtype = float if real else complex
    shift = float(np.real(sigma)) if real else complex(sigma)
    x = np.asarray(x0, dtype=dtype)
    x = x / np.linalg.norm(x)
    nF, nE = norm1(F), norm1(E)
    per = max(4, max_iter // 4)
    for attempt in range(4):                 # renew the factorisation at the new estimate
        try:
            lu = spla.splu(sp.csc_matrix(F - shift * E, dtype=dtype))
        except RuntimeError:                 # exactly singular: the shift is an eigenvalue
            shift = shift * (1 + 1e-12) + 1e-14
            continue
        for it in range(per):
            y = lu.solve(E @ x)
            x = y / np.linalg.norm(y)
            Fx, Ex = F @ x, E @ x
            lam = np.vdot(x, Fx) / np.vdot(x, Ex)
            lam = float(lam.real) if real else complex(lam)
            if np.linalg.norm(Fx - lam * Ex) <= RESIDUAL_TOL * (nF + abs(lam) * nE):
                return lam, x
        shift = lam
    return None


def full_order_pair(F, E, sigma: float, X0: np.ndarray, max_iter: int = 30
                    ) -> np.ndarray | None:
    """The two eigenvalues of F x = λ E x nearest the real shift ``sigma`` [1/s], by block
    inverse iteration from the real subspace ``X0`` (n, 2) on a sparse LU of F − σE, and the
    eigenvalues of its Rayleigh–Ritz matrix S = (XᵀEX)⁻¹XᵀFX: a conjugate pair or two real
    numbers (a real 2 × 2 matrix's eigenvalues, so the imaginary part of a real pair is exactly
    0).  Converged when the subspace is invariant: ‖FX − EXS‖ ≤ ``RESIDUAL_TOL`` ·
    (‖F‖ + ‖S‖‖E‖) (X orthonormal); None if it is not within ``max_iter`` iterations.  The
    sparse-pencil counterpart of the tracker's dense
    :func:`propwhirl.engine.eigensolve.pair_discriminant` (a state matrix A of the reduced or
    small model), for the full order, whose dense A(V) is what a reduced analysis avoids.

    Examples
    --------
    Roots 1 ± 2i (a rotation block), 10 and 50 of an E = I pencil:

    >>> import numpy as np, scipy.sparse as sp
    >>> F = sp.csc_matrix(np.array([[1.0, 2, 0, 0], [-2, 1, 0, 0], [0, 0, 10, 0], [0, 0, 0, 50]]))
    >>> E = sp.identity(4, format="csc")
    >>> lam = full_order_pair(F, E, 1.0, np.ones((4, 2)) + np.eye(4)[:, :2])
    >>> np.sort_complex(lam).round(12)
    array([1.-2.j, 1.+2.j])
    """
    X0 = np.asarray(X0, dtype=float)
    try:
        lu = spla.splu(sp.csc_matrix(F - sigma * E, dtype=float))
    except RuntimeError:                     # exactly singular: σ is an eigenvalue
        lu = spla.splu(sp.csc_matrix(F - (sigma * (1 + 1e-12) + 1e-14) * E, dtype=float))
    nF, nE = norm1(F), norm1(E)
    X = np.linalg.qr(X0)[0]
    for _ in range(max_iter):
        X = np.linalg.qr(lu.solve(E @ X))[0]
        FX, EX = F @ X, E @ X
        S = np.linalg.solve(X.T @ EX, X.T @ FX)
        if np.linalg.norm(FX - EX @ S, 1) <= RESIDUAL_TOL * (nF + np.linalg.norm(S, 1) * nE):
            return np.linalg.eigvals(S)
    return None


def correct_crossing(pencil: Pencil, V0: float, lam0: complex, x0: np.ndarray, *,
                     xtol: float, slope: float | None = None, step: float | None = None,
                     bounds: tuple[float, float] | None = None) -> Corrected | None:
    """The crossing Re λ(V) = 0 of the full-order branch through (V0, λ0, x0) (module docstring).

    pencil(V) -> (F, E) sparse; lam0, x0: the reduced model's root at V0 and its vector lifted to
    the full state; xtol [m/s]: the crossing is accepted when the next secant step is below
    xtol/10; slope: d Re λ/dV [1/m] of the reduced root (the first step is then Newton's, and a
    reduced crossing within xtol/10 of the full one converges in one evaluation); step [m/s]: without a
    slope, the second speed's distance (default max(20 xtol, 1e-4 V0)); bounds: the speeds the
    crossing may not leave.  For a real root (divergence) the iteration is real.  Returns None
    when a root or the secant fails.
    """
    real = np.imag(lam0) == 0
    x = real_direction(x0) if real else np.asarray(x0, dtype=complex)
    lam = float(np.real(lam0)) if real else complex(lam0)
    h = max(20 * xtol, 1e-4 * abs(V0)) if step is None else step
    lo, hi = bounds if bounds is not None else (V0 - 50 * h, V0 + 50 * h)
    evals = 0

    def root(V, lam, x):
        nonlocal evals
        F, E = pencil(V)
        evals += 1
        got = full_order_root(F, E, lam, x)
        if got is None:
            return None
        lam_n, x_n = got
        if mac(x, x_n) < BRANCH_MAC:
            return None
        return lam_n, x_n

    a = root(V0, lam, x)
    if a is None:
        return None
    Va, (la, xa) = V0, a
    Vb = V0 + h
    if slope is not None and np.isfinite(slope) and slope != 0:
        Vb = V0 - np.real(la) / slope
        if abs(Vb - V0) <= 0.1 * xtol:       # Newton's step is below xtol/10: converged
            return Corrected(float(Vb), complex(la), np.asarray(xa, dtype=complex), 0, evals)
        if not (lo <= Vb <= hi) or Vb == V0:
            Vb = V0 + h
    b = root(Vb, la, xa)
    if b is None:
        return None
    lb, xb = b
    for it in range(MAX_SECANT):
        ga, gb = np.real(la), np.real(lb)
        if gb == ga:
            return None
        Vn = Vb - gb * (Vb - Va) / (gb - ga)
        if not (lo <= Vn <= hi):
            return None
        if abs(Vn - Vb) <= 0.1 * xtol:        # the next step is below xtol/10: converged
            return Corrected(float(Vn), complex(lb), np.asarray(xb, dtype=complex), it + 1,
                             evals)
        c = root(Vn, lb, xb)
        if c is None:
            return None
        Va, la, xa = Vb, lb, xb
        Vb, (lb, xb) = Vn, c
    return None
