"""Karpel's minimum-state approximation of the doublet-lattice GAFs (issue 23, item 3b: "and
Karpel's minimum-state if it pays") — a measurement, kept beside its benchmark
(``benchmarks/dlm_minimum_state.py``), not a runtime option (issue 38, item 6: the runtime's
default, the modal Roger state space of :mod:`propwhirl.model.dlm_modal`, already has a few lag
states per kept mode, and this fit costs 0.5–1.7 s per Mach and cannot be interpolated in Mach).

On the free wing DOFs (n_w of them) and at one Mach number, the tabulated Q(k)
(:mod:`propwhirl.model.aerodynamics.dlm`) is fitted in p̄ = s b_ref / V (p̄ = ik on the imaginary axis) by

    Q(p̄) ≈ A₀ + A₁ p̄ + A₂ p̄² + D (p̄ I − R)⁻¹ E p̄,        R = −diag(β_1 … β_m)

(Karpel 1982; Tiffany & Adams 1988): m aerodynamic states in all, shared by every DOF, instead
of Roger's L per DOF (:mod:`propwhirl.model.aerodynamics.dlm_rfa`: L n_w).  D (n_w, m) and E (m, n_w) are
found by alternating least squares on the part of Q that the quasi-steady terms cannot fit
(variable projection: A₀, A₁, A₂ are projected out, then fitted last): with D fixed, E is one
linear least-squares problem (the same design matrix for every column of Q); with E fixed, D
is the same problem for Qᵀ; repeated from Roger's fit with the same lag roots (each lag
matrix's leading singular pair) until the residual stops falling.  Rows and columns of Q are
scaled by the square roots of their largest magnitudes first (heave in metres and twist in
radians alike) and unscaled after.  The lag states obey ẋ = (V/b) R x + E q̇_w and load the
wing with ½ρV² D x.

:func:`state_matrix` builds the first-order matrices of a model with such a fit (as
:func:`propwhirl.model.aerodynamics.dlm_rfa.state_matrix` does with Roger's), for the engine; the
benchmark ``benchmarks/dlm_minimum_state.py`` compares their critical speeds with Roger's and
the p-k's (docs/validation.md, "Karpel's minimum-state approximation").
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from propwhirl import validate as v
from propwhirl.model.structure.assembly import free_dofs
from propwhirl.model.aerodynamics.dlm import check_mach, dlm_aerodynamics, fixed_mach, snap_mach
from propwhirl.model.aerodynamics.dlm_rfa import lstsq_fit as roger_lstsq
from propwhirl.model.aerodynamics.dlm_rfa import fit_ks, quasi_steady

#: alternating least-squares sweeps at most (each one E-step and one D-step)
ITERATIONS = 200
#: stop when a sweep lowers the scaled residual by less than this fraction
RTOL = 1e-5


@dataclass(frozen=True)
class MinimumStateFit:
    """A minimum-state approximation: ``A`` (3, n_w, n_w) real (A₀, A₁, A₂), ``D`` (n_w, m),
    ``E`` (m, n_w), ``lags`` β_j (m,), the fitted ``ks``, the Mach number, ``b_ref`` [m], the
    relative ``error`` (max |Q_fit − Q| over the fitted k and entries / max |Q|, as
    :attr:`propwhirl.model.aerodynamics.dlm_rfa.RogerFit.error`) and the alternating sweeps done."""

    A: np.ndarray
    D: np.ndarray
    E: np.ndarray
    lags: np.ndarray
    ks: np.ndarray
    mach: float
    b_ref: float
    error: float
    sweeps: int

    def __call__(self, k: float) -> np.ndarray:
        """Q_fit(ik) (n_w, n_w) complex."""
        return _evaluate(self.A, self.D, self.E, self.lags, np.array([float(k)]))[0]


def _evaluate(A, D, E, lags, ks) -> np.ndarray:
    p = 1j * np.asarray(ks, float)
    g = p[:, None] / (p[:, None] + lags[None, :])                         # (K, m)
    return (A[0][None] + p[:, None, None] * A[1][None] + (p * p)[:, None, None] * A[2][None]
            + np.einsum("im,km,mj->kij", D, g, E))


def _real(f: np.ndarray) -> np.ndarray:
    """Complex values over k (first axis) as real ones: [Re f; Im f] (2K, …)."""
    return np.concatenate([f.real, f.imag])


def _projection(ks: np.ndarray, lags: np.ndarray):
    """(P, B⁺, Gr): the projector P (2K, 2K) onto the complement of the quasi-steady basis
    [1, ik, (ik)²] (real form B), its pseudo-inverse B⁺ (3, 2K) and the lag functions
    g_j(k) = ik / (ik + β_j) in real form Gr (2K, m)."""
    p = 1j * ks
    B = _real(np.stack([np.ones_like(p), p, p * p], axis=1))
    Bp = np.linalg.pinv(B)
    P = np.eye(2 * ks.size) - B @ Bp
    Gr = _real(p[:, None] / (p[:, None] + lags[None, :]))
    return P, Bp, Gr


def _step(PQ: np.ndarray, PG: np.ndarray, G: np.ndarray) -> np.ndarray:
    """X (m, n) minimising ‖PQ − Σ_j PG_j G_{·j} X_{j·}‖ (PQ (2K, n, n) the projected table,
    PG (2K, m), G (n, m) fixed): one least-squares problem, the same design for every column
    (variable projection: the quasi-steady A₀, A₁, A₂ are projected out)."""
    K2, n, _ = PQ.shape
    design = (PG[:, None, :] * G[None, :, :]).reshape(K2 * n, -1)
    X, *_ = np.linalg.lstsq(design, PQ.reshape(K2 * n, n), rcond=None)
    return X


def fit(Q: np.ndarray, ks, lags, mach: float = 0.0, b_ref: float = 1.0, *,
        iterations: int = ITERATIONS, rtol: float = RTOL) -> MinimumStateFit:
    """The minimum-state fit of Q (K, n_w, n_w) tabulated at the reduced frequencies ``ks``
    with the lag roots ``lags`` (m of them, > 0, distinct): alternating least squares from
    Roger's fit (module docstring)."""
    lags = np.asarray(v.positive("lags", lags), float).ravel()
    if lags.size < 1 or np.unique(lags).size != lags.size:
        raise v.InputError(f"lags = {list(lags)} is invalid: must be distinct numbers > 0")
    ks = np.asarray(v.finite("ks", ks), float).ravel()
    Q = np.asarray(Q, complex)
    if Q.ndim != 3 or Q.shape[0] != ks.size or Q.shape[1] != Q.shape[2]:
        raise v.InputError(f"Q has shape {Q.shape}: must be (len(ks), n, n) = ({ks.size}, n, n)")
    if np.unique(ks).size < 3 + 1 or np.any(ks < 0):
        raise v.InputError(f"ks has {np.unique(ks).size} distinct reduced frequencies >= 0: "
                           "the fit needs at least 4")
    n, m = Q.shape[1], lags.size
    with np.errstate(all="ignore"):
        row = np.sqrt(np.abs(Q).max(axis=(0, 2)))
        col = np.sqrt(np.abs(Q).max(axis=(0, 1)))
    row = np.where(row > 0, row, 1.0)
    col = np.where(col > 0, col, 1.0)
    S = Q / row[None, :, None] / col[None, None, :]                      # scaled
    roger = roger_lstsq(S, ks, lags, mach, b_ref)
    D = np.empty((n, m))
    E = np.empty((m, n))
    for j in range(m):                                                   # rank-1 start per lag
        U, s, Vt = np.linalg.svd(roger.A[3 + j])
        D[:, j], E[j] = U[:, 0] * s[0], Vt[0]
    P, Bp, Gr = _projection(ks, lags)
    Sr = _real(S)
    PS = np.tensordot(P, Sr, axes=1)                                     # (2K, n, n)
    PSt = np.transpose(PS, (0, 2, 1))
    PG = P @ Gr
    last, sweeps = np.inf, 0
    for sweeps in range(1, int(iterations) + 1):
        E = _step(PS, PG, D)
        D = _step(PSt, PG, E.T).T
        res = float(np.linalg.norm(PS - np.einsum("km,im,mj->kij", PG, D, E)))
        if res > last * (1 - rtol):
            break
        last = res
    lag_part = np.einsum("km,im,mj->kij", Gr, D, E)
    A = np.tensordot(Bp, Sr - lag_part, axes=1)                          # (3, n, n)
    A = A * (row[:, None] * col[None, :])[None]
    D = D * row[:, None]
    E = E * col[None, :]
    error = float(np.abs(_evaluate(A, D, E, lags, ks) - Q).max() / np.abs(Q).max())
    return MinimumStateFit(A, D, E, lags, ks, float(mach), float(b_ref), error, sweeps)


def fit_model(model, lags, mach: float | None = None, ks=None, tables=None,
              **kw) -> MinimumStateFit:
    """The minimum-state fit of ``model``'s doublet-lattice tables on its free wing DOFs at
    Mach ``mach`` (default its wing's fixed ``dlm_mach``) over ``ks`` (default the runtime's
    :func:`~propwhirl.model.aerodynamics.dlm_rfa.fit_ks`), read from ``tables`` (a
    :class:`~propwhirl.model.aerodynamics.dlm.DlmTables`; None: new ones)."""
    mach = fixed_mach(model.wing) if mach is None else float(mach)
    if mach is None:
        raise v.InputError("the minimum-state fit is at one Mach: give mach or a wing with a "
                           "fixed dlm_mach")
    check_mach(mach)
    ks = fit_ks() if ks is None else np.asarray(ks, float)
    aero = dlm_aerodynamics(model.wing, tables)
    keep = free_dofs(model.wing.n_nodes)
    mach = snap_mach(mach)
    Q = np.stack([aero.gaf(mach, k, exact_mach=True)[np.ix_(keep, keep)] for k in ks])
    return fit(Q, ks, lags, mach, aero.b_ref, **kw)


def state_matrix(model, f: MinimumStateFit, V) -> np.ndarray:
    """The first-order state matrices (nV, 2n + m, 2n + m) of ``model`` with the minimum-state
    fit ``f`` of its doublet-lattice loads at the airspeeds V [m/s]; states [q, q̇, x]."""
    V = np.atleast_1d(v.positive("airspeed V", V, "m/s"))
    b = f.b_ref
    Ms, Cs, Ks, qs = quasi_steady(model, V, f.A, b)
    n = Ms.shape[-1]
    nw, m = f.D.shape
    out = np.zeros((V.size, 2 * n + m, 2 * n + m))
    for i, Vi in enumerate(V):
        M, C, K, q = Ms[i], Cs[i], Ks[i], qs[i]
        F = np.zeros((n, m))
        F[:nw] = q * f.D
        Minv = np.linalg.inv(M)
        A = out[i]
        A[:n, n:2 * n] = np.eye(n)
        A[n:2 * n, :n] = -Minv @ K
        A[n:2 * n, n:2 * n] = -Minv @ C
        A[n:2 * n, 2 * n:] = Minv @ F
        A[2 * n:, n:n + nw] = f.E
        A[2 * n:, 2 * n:] = -(Vi / b) * np.diag(f.lags)
    return out
