"""Eigen-solutions of real state matrices: the linear algebra under the engine.

* :func:`eigen`, :func:`eigenvalues`: stacked eigendecompositions (LAPACK ``geev``);
* :func:`mac`: the Modal Assurance Criterion, eq. (5.14) in its Hermitian form;
* dλ/dV of all roots from the left eigenvectors (:func:`eig_derivative`, a stack, real
  arithmetic) and of one root (:func:`eigenvalue_derivative`);
* shifted inverse iteration (:func:`_inverse_iteration`) with residual rules scaled by the
  eigenvalue or the rounding floor of A x (:func:`_residual_ok`), the evaluation of one
  tracked mode (:func:`eval_mode`, :func:`tracked_eigenvalue`), of the real root nearest
  zero (:func:`zero_root`) and of the discriminant of a pair by real subspace iteration
  (:func:`pair_discriminant`, analytic through the branch point where the pair turns real);
* the checked evaluation of a model's ``state_matrix(V)`` (:func:`call_state_matrix`) and the
  displacement mask (:func:`displacement_mask`).

BLAS threads are limited to one inside every solve (a cached :class:`threadpoolctl.ThreadpoolController`).
Measured on the 2-core development machine: while other jobs loaded it, a 200×200 ``eig``
took 14.6 ms on one thread against 26.3 ms on two (300×300: 37 vs 90 ms); on the idle machine
the two were equal (14.0 vs 15.0 ms) but the inverse-iteration evaluation used by the
refinement took 1.0 ms on one thread against 3.9 ms on two (thread start-up on small BLAS-2
work).  The libraries' thread pools are found once (≈ 0.3 ms); entering the limiter then costs
≈ 0.01 ms.
"""
from __future__ import annotations

from collections.abc import Callable, Sequence

import functools

import numpy as np
import scipy.linalg as sla
from scipy.linalg import lapack
from threadpoolctl import ThreadpoolController

from propwhirl.validate import InputError, finite, integer_at_least, positive

#: A model's state matrices: ``state_matrix(V) -> A``, vectorised over a 1-D array of airspeeds
#: V [m/s], returning the real first-order state matrices, shape ``(len(V), n, n)``.
StateMatrixFn = Callable[[np.ndarray], np.ndarray]


@functools.lru_cache(maxsize=1)
def _blas_controller() -> ThreadpoolController:
    """The thread pools of the BLAS/OpenMP libraries loaded (NumPy's and SciPy's, both imported
    with this module), found once: finding them costs ≈ 0.3 ms, limiting them ≈ 0.01 ms."""
    return ThreadpoolController()


# LAPACK getrf/getrs called directly for double (real or complex) square matrices and vectors:
# scipy's lu_factor/lu_solve call the same routines with the same arguments (check_finite
# False, no overwrite) after a Python layer that costs ≈ 15 µs per call, more than the 50×50
# solve itself.  Anything else, and any call LAPACK reports as singular or illegal, goes
# through scipy (the same factors, with its warning or error).
_F8, _C16 = np.dtype(float), np.dtype(complex)
_GETRF = {_F8: lapack.dgetrf, _C16: lapack.zgetrf}


def _lu_factor(M: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``scipy.linalg.lu_factor(M, check_finite=False)``."""
    f = _GETRF.get(M.dtype)
    if f is None or M.ndim != 2 or M.size == 0:
        return sla.lu_factor(M, check_finite=False)
    lu, piv, info = f(M, overwrite_a=False)
    if info != 0:
        return sla.lu_factor(M, check_finite=False)
    return lu, piv


def _lu_solve(lu_piv: tuple[np.ndarray, np.ndarray], b: np.ndarray, trans: int = 0) -> np.ndarray:
    """``scipy.linalg.lu_solve(lu_piv, b, trans=trans, check_finite=False)``."""
    lu, piv = lu_piv
    kinds = (lu.dtype, b.dtype)
    if kinds == (_F8, _F8):
        f = lapack.dgetrs
    elif all(k in (_F8, _C16) for k in kinds):
        f = lapack.zgetrs
    else:
        f = None
    if f is None or lu.ndim != 2 or b.ndim not in (1, 2) or b.size == 0 or (
            b.shape[0] != lu.shape[0]):
        return sla.lu_solve(lu_piv, b, trans=trans, check_finite=False)
    x, info = f(lu, piv, b, trans=trans, overwrite_b=False)
    if info != 0:
        return sla.lu_solve(lu_piv, b, trans=trans, check_finite=False)
    return x


def _norm(x: np.ndarray) -> np.floating:
    """``numpy.linalg.norm(x)`` (2-norm of a vector, Frobenius of a matrix) of a float or
    complex array, without its argument handling: the same dot products in the same order."""
    x = x.ravel(order="K")
    if x.dtype.kind == "c":
        re, im = x.real, x.imag
        return np.sqrt(re.dot(re) + im.dot(im))
    return np.sqrt(x.dot(x))


def single_thread_blas():
    """Context manager limiting BLAS/OpenMP to one thread (small dense eigenproblems).

    Returns
    -------
    contextlib.AbstractContextManager
        Use in a ``with`` statement (threadpoolctl's limiter): the BLAS/OpenMP thread
        counts are restored on exit.

    Examples
    --------
    >>> import numpy as np
    >>> from propwhirl.engine import eigenvalues, single_thread_blas
    >>> with single_thread_blas():
    ...     lam = eigenvalues(np.array([[0.0, 1.0], [-4.0, 0.0]]))
    >>> np.allclose(lam, [2j, -2j])                     # λ = ±2i [1/s]
    True
    """
    return _blas_controller().limit(limits=1)


def one_blas_thread(func: Callable) -> Callable:
    """``func`` run with BLAS/OpenMP limited to one thread (:func:`single_thread_blas`) from
    its start to its end — for a whole analysis, whose naming, content and participation
    multiply small matrices outside the engine: a 77 × 77 matrix times a vector costs ≈ 8 µs
    on one thread and ≈ 8 ms under several OpenBLAS threads on a loaded machine (measured on
    2 shared cores, docs/performance.md)."""
    @functools.wraps(func)
    def limited(*args, **kwargs):
        with single_thread_blas():
            return func(*args, **kwargs)
    return limited


def as_square_stack(A, name: str = "A") -> np.ndarray:
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

    Parameters
    ----------
    A_stack : array_like, shape (..., n, n)
        Real square matrices (e.g. state matrices, eq. 5.4 [1/s]), vectorised over leading
        axes.

    Returns
    -------
    eigenvalues : ndarray, shape (..., n), complex
        λ [1/s for a state matrix].
    eigenvectors : ndarray, shape (..., n, n), complex
        Column j the unit-length right eigenvector of ``eigenvalues[..., j]``.

    Examples
    --------
    The oscillator ẍ + 0.4 ẋ + 4 x = 0: λ = −0.2 ± 1.990i, the vectors (1, λ) normalised.

    >>> import numpy as np
    >>> from propwhirl.engine import eigen
    >>> lam, X = eigen(np.array([[0.0, 1.0], [-4.0, -0.4]]))
    >>> np.round(lam, 3).tolist()
    [(-0.2+1.99j), (-0.2-1.99j)]
    >>> np.allclose(X[:, 1], X[:, 0].conj()), np.allclose(np.linalg.norm(X, axis=0), 1.0)
    (True, True)
    """
    A = as_square_stack(A_stack)
    with single_thread_blas():
        w, X = np.linalg.eig(A)
    return w.astype(complex), X.astype(complex)


def eigenvalues(A_stack) -> np.ndarray:
    """Eigenvalues only (cheaper than :func:`eigen`), complex, BLAS limited to one thread.

    Parameters
    ----------
    A_stack : array_like, shape (..., n, n)
        Real square matrices (e.g. state matrices, eq. 5.4), vectorised over leading axes.

    Returns
    -------
    numpy.ndarray, shape (..., n), complex
        The eigenvalues λ [1/s for a state matrix]; conjugate pairs adjacent, Im > 0 first.

    Examples
    --------
    The oscillator ẍ + 0.4 ẋ + 4 x = 0 in first-order form: λ = −0.2 ± i√3.96.

    >>> import numpy as np
    >>> from propwhirl.engine import eigenvalues
    >>> A = np.array([[0.0, 1.0], [-4.0, -0.4]])
    >>> lam = eigenvalues(A)
    >>> np.allclose(lam, [-0.2 + 1j * np.sqrt(3.96), -0.2 - 1j * np.sqrt(3.96)])
    True
    >>> eigenvalues(np.stack([A, 2 * A])).shape          # a stack of two matrices
    (2, 2)
    """
    A = as_square_stack(A_stack)
    with single_thread_blas():
        return np.linalg.eigvals(A).astype(complex)


def mac(phi1, phi2) -> np.ndarray:
    """Modal Assurance Criterion, eq. (5.14), in the Hermitian form valid for complex shapes.

    ``MAC = |φ1ᴴ φ2|² / ((φ1ᴴ φ1)(φ2ᴴ φ2))``, in [0, 1], 1 for any complex multiple.  The printed
    (5.14) uses the plain transpose, which is fine for real shapes but not for complex ones: it is
    complex in general, 0/0 for a circular whirl shape φ = (1, i) (φᵀφ = 0), and for φ2 = φ̄1 it
    equals |φ|⁴/|φᵀφ|² ≥ 1.

    Parameters
    ----------
    phi1, phi2 : array_like, shape (n,) or (n, k)
        Mode shapes (real or complex), one per column for matrices.

    Returns
    -------
    float or numpy.ndarray
        Vectors ``(n,)`` give a scalar, matrices ``(n, k1)``, ``(n, k2)`` (shapes in columns)
        give ``(k1, k2)``.  A zero vector gives MAC 0.

    Examples
    --------
    >>> import numpy as np
    >>> from propwhirl.engine import mac
    >>> whirl = np.array([1.0, 1j])                  # a circular whirl shape (φᵀφ = 0)
    >>> round(mac(whirl, (2 - 3j) * whirl), 12)      # any complex multiple: 1
    1.0
    >>> round(mac(whirl, whirl.conj()), 12)          # the opposite sense of whirl: 0
    0.0
    >>> np.round(mac(np.eye(2), np.array([[1.0], [1.0]])), 12)
    array([[0.5],
           [0.5]])
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


def call_state_matrix(fn: StateMatrixFn, V: np.ndarray, n: int | None,
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


def displacement_mask(n: int, n_dof, displacement) -> np.ndarray:
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


def conj_index(w: np.ndarray) -> np.ndarray:
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


def eig_derivative(w: np.ndarray, X: np.ndarray, conj: np.ndarray,
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


def eigenvalue_derivative(A: np.ndarray, dA: np.ndarray, lam: complex, x: np.ndarray,
                          stats: dict[str, int]) -> complex:
    """dλ/dV = wᵀ A' x / (wᵀ x) at a simple eigenpair (λ, x) of real A; w solves Aᵀ w = λ w
    (the conjugate of the left eigenvector), by two steps of inverse iteration at λ."""
    n = A.shape[0]
    with np.errstate(all="ignore"):
        lu = _lu_factor(A - (lam * (1 + 1e-13) + 1e-300) * np.eye(n))
        w = np.asarray(x, dtype=complex).conj()
        for _ in range(2):
            w = _lu_solve(lu, w, trans=1)
            w /= _norm(w)
        d = complex((w @ (dA @ x)) / (w @ x))
    stats["left_vectors"] = stats.get("left_vectors", 0) + 1
    return d if np.isfinite(d) else 0j


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
    x = x / _norm(x)
    shift = sigma.real if use_real else sigma
    lam = complex(shift)
    res, noise = np.inf, 0.0
    eye = np.eye(n)
    for _attempt in range(3):
        Ms = A - shift * eye
        with np.errstate(all="ignore"):
            lu = _lu_factor(Ms)
        if not np.isfinite(lu[0]).all() or (lu[0].diagonal() == 0).any():
            shift = shift + (1e-10 * max(abs(shift), 1.0))
            continue
        prev = np.inf
        for _ in range(maxit):
            y = _lu_solve(lu, x)
            ny = _norm(y)
            if not np.isfinite(ny) or ny == 0:
                break
            x = y / ny
            Ax = A @ x if use_real else (A @ x.real) + 1j * (A @ x.imag)
            lam = complex(np.vdot(x, Ax))
            res = float(_norm(Ax - lam * x))
            noise = _EPS * float(_norm(absA @ np.abs(x)))
            if _residual_ok(res, lam, noise, tol, 64.0):
                return lam, x, True
            if res > 0.5 * prev:      # stalled: refactor at the Rayleigh quotient
                break
            prev = res
        shift = lam.real if use_real else lam
    return lam, x, _residual_ok(res, lam, noise, 1e-8, 1e3)


def pair_discriminant(A: np.ndarray, Q0: np.ndarray, sigma: float, maxit: int = 12
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
        lu = _lu_factor(A - sigma * np.eye(n))
    Q, _ = np.linalg.qr(Q0)
    ok = False
    H = Q.T @ A @ Q
    for _ in range(maxit):
        Z = _lu_solve(lu, Q)
        if not np.isfinite(Z).all():
            break
        Q, _ = np.linalg.qr(Z)
        AQ = A @ Q
        H = Q.T @ AQ
        res = float(_norm(AQ - Q @ H))
        noise = _EPS * float(_norm(absA @ np.abs(Q)))
        scale = float(np.sqrt(abs(np.linalg.det(H))))
        if _residual_ok(res, scale, noise, 1e-10, 64.0):
            ok = True
            break
    tr2 = 0.5 * (H[0, 0] + H[1, 1])
    D = float(((H[0, 0] - H[1, 1]) / 2) ** 2 + H[0, 1] * H[1, 0])
    return D, float(tr2), Q, ok


def tracked_eigenvalue(state_matrix: StateMatrixFn, V: float, guess: complex,
                       shape: np.ndarray, *, n_dof: int | None = None, displacement=None,
                       mac_min: float = 0.5) -> tuple[complex, np.ndarray]:
    """Eigenvalue and eigenvector of the mode nearest ``guess`` at speed V [m/s] (no full eig).

    ``shape`` is a full-state vector of the mode (e.g. from a nearby speed): it starts the
    shifted inverse iteration and checks identity (MAC ≥ mac_min on the displacement part,
    else a full eigendecomposition picks the best match).

    Parameters
    ----------
    state_matrix : callable
        ``state_matrix(V) -> A``, vectorised over a 1-D array of airspeeds V [m/s], returning
        real state matrices (len(V), n, n) [1/s].
    V : float
        The speed [m/s], > 0.
    guess : complex
        Estimate of the eigenvalue [1/s] (the shift).
    shape : ndarray
        (n,) full-state vector of the mode.
    n_dof : int, optional
        The first `n_dof` states are displacements (or give `displacement`).
    displacement : array_like of bool, optional
        Mask of the displacement states; default: all states.
    mac_min : float
        Least MAC [-] of the displacement part with `shape` for the iteration's result.

    Returns
    -------
    eigenvalue : complex
        λ [1/s] at V.
    eigenvector : ndarray
        (n,) its right eigenvector.

    Examples
    --------
    The oscillator ẍ + (0.5 − 0.01 V) ẋ + 100 x = 0 followed from 50 to 60 m/s, where
    λ = 0.05 + i√(100 − 0.05²):

    >>> import numpy as np
    >>> from propwhirl.engine import sweep, tracked_eigenvalue
    >>> def state_matrix(V):
    ...     A = np.zeros((V.size, 2, 2))
    ...     A[:, 0, 1], A[:, 1, 0], A[:, 1, 1] = 1.0, -100.0, -(0.5 - 0.01 * V)
    ...     return A
    >>> sw = sweep(state_matrix, np.array([40.0, 50.0]), n_dof=1)
    >>> lam, x = tracked_eigenvalue(state_matrix, 60.0, sw.eigenvalues[-1, 0],
    ...                             sw.eigenvectors[-1, :, 0], n_dof=1)
    >>> round(lam.real, 6), round(lam.imag, 4)
    (0.05, 9.9999)
    """
    Vv = np.atleast_1d(positive("V", V, "m/s")).astype(float)
    if Vv.size != 1:
        raise InputError(f"V must be a single speed, got {Vv.size} values")
    with single_thread_blas():
        A = call_state_matrix(state_matrix, Vv, None, None)[0]
        disp = displacement_mask(A.shape[0], n_dof, displacement)
        lam, x, _ = eval_mode(A, complex(guess), np.asarray(shape, dtype=complex), disp,
                              mac_min, {})
    return lam, x


def eval_mode(A, sigma, x0, disp, mac_min, stats) -> tuple[complex, np.ndarray, bool]:
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


def zero_root(A: np.ndarray, x0: np.ndarray, stats: dict[str, int]
              ) -> tuple[complex, np.ndarray, bool, float]:
    """The real eigenvalue nearest zero (real inverse iteration at shift 0) and sign det A.

    Returns (λ, x, converged-and-real, sign det A).  sign det A = (−1)^(number of negative
    real eigenvalues): it flips exactly when a real root crosses zero, whatever its identity.
    """
    sign, _ = np.linalg.slogdet(A)
    lam, x, ok = _inverse_iteration(A, 0j, _real_vector(np.asarray(x0, dtype=complex)))
    stats["inverse_iterations"] = stats.get("inverse_iterations", 0) + 1
    return complex(lam), np.asarray(x, dtype=complex), bool(ok and lam.imag == 0), float(sign)
