"""Roger's rational-function approximation of the doublet-lattice GAFs and its state space
(issue 23, item 3b).

On the wing's free bending–torsion DOFs and at one Mach number M, the tabulated Q(k, M)
(:mod:`propwhirl.model.dlm`) is fitted in the nondimensional Laplace variable p̄ = s b_ref / V
(p̄ = ik on the imaginary axis) by

    Q(p̄) ≈ A₀ + A₁ p̄ + A₂ p̄² + Σ_l A_{2+l} p̄ / (p̄ + β_l),        l = 1 … L

(Roger 1977), every A real, by linear least squares over the reduced frequencies ``ks``
(real and imaginary parts, all entries at once) for given lag roots β_l > 0.  Each lag term
is a set of aerodynamic states x_l (one per wing DOF) with ẋ_l = q̇_w − (V/b) β_l x_l, so the
aeroelastic system at airspeed V with q = ½ρV² is

    (M_s − q (b/V)² A₂) q̈ + (C_s − q (b/V) A₁) q̇ + (K_s − q A₀) q − q Σ_l A_{2+l} x_l = 0

on the model's DOFs (the wing block; the propellers' Houbolt–Reed loads as the model has
them), i.e. a constant-coefficient state matrix of size 2n + L n_w (:func:`state_matrix`),
which the eigenvalue engine analyses like the strip model's.  The fit is at one Mach number
(a matched point: give the Mach of the speed of interest); its error is reported
(:attr:`RogerFit.error`: the largest |Q_fit − Q| over the fitted k, relative to max |Q|).
"""
from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from propwhirl import validate as v
from propwhirl.model.dlm import check_mach, dlm_aerodynamics

#: default lag roots β_l (nondimensional, on the reference semichord)
DEFAULT_LAGS = (0.2, 0.5, 1.0, 2.0)


def _basis(k: np.ndarray, lags: np.ndarray) -> np.ndarray:
    """The complex basis [1, ik, (ik)², ik/(ik + β_l) …] at the reduced frequencies k."""
    p = 1j * np.asarray(k, float)[:, None]
    return np.concatenate([np.ones_like(p), p, p * p, p / (p + lags[None, :])], axis=1)


@dataclass(frozen=True)
class RogerFit:
    """A Roger approximation: ``A`` (3 + L, n_w, n_w) real, ``lags`` β_l (L,), the fitted
    reduced frequencies ``ks``, the Mach number, ``b_ref`` [m] and the relative fit ``error``."""

    A: np.ndarray
    lags: np.ndarray
    ks: np.ndarray
    mach: float
    b_ref: float
    error: float

    def __call__(self, k: float) -> np.ndarray:
        """Q_fit(ik) (n_w, n_w) complex."""
        return np.tensordot(_basis(np.array([k]), self.lags)[0], self.A, axes=1)


def roger_fit(model, mach: float, ks, lags=DEFAULT_LAGS) -> RogerFit:
    """The Roger fit of ``model``'s doublet-lattice Q(k, mach) on its free wing DOFs over the
    reduced frequencies ``ks`` (at least 3 + len(lags) of them, >= 0) with lag roots
    ``lags`` (> 0, distinct).  InputError for bad arguments, before any AIC is computed."""
    from propwhirl.model.assembly import free_dofs

    if getattr(getattr(model, "wing", None), "aero", None) != "dlm":
        raise v.InputError(f"model = {getattr(model, 'name', model)!r:.60} is invalid for the "
                           "Roger fit: needs a wing with aero = 'dlm'")
    check_mach(float(mach))
    lags = np.asarray(v.positive("lags", lags), float).ravel()
    if lags.size < 1 or np.unique(lags).size != lags.size:
        raise v.InputError(f"lags = {list(lags)} is invalid: must be distinct numbers > 0")
    ks = np.asarray(v.finite("ks", ks), float).ravel()
    if np.any(ks < 0) or np.unique(ks).size < 3 + lags.size:
        raise v.InputError(f"ks has {np.unique(ks).size} distinct reduced frequencies >= 0: "
                           f"the fit needs at least {3 + lags.size}")
    aero = dlm_aerodynamics(model.wing)
    keep = free_dofs(model.wing.n_nodes)
    Q = np.stack([aero.gaf(mach, k)[np.ix_(keep, keep)] for k in ks])      # (m, n_w, n_w)
    B = _basis(ks, lags)
    rows = np.concatenate([B.real, B.imag])                                  # (2m, 3 + L)
    rhs = np.concatenate([Q.real, Q.imag]).reshape(2 * ks.size, -1)
    coef, *_ = np.linalg.lstsq(rows, rhs, rcond=None)
    A = coef.reshape((3 + lags.size,) + Q.shape[1:])
    fit = np.tensordot(B, A, axes=1)
    error = float(np.abs(fit - Q).max() / np.abs(Q).max())
    return RogerFit(A, lags, ks, float(mach), aero.b_ref, error)


def state_matrix(model, fit: RogerFit, V) -> np.ndarray:
    """The first-order state matrices (nV, 2n + L n_w, 2n + L n_w) of ``model`` with the Roger
    fit of its doublet-lattice loads at the airspeeds V [m/s]; states [q, q̇, x_1, …, x_L]
    (q the model's DOFs without lag states, x_l the lag states of the wing DOFs)."""
    V = np.atleast_1d(v.positive("airspeed V", V, "m/s"))
    dry = replace(model, wing_aero=False).second_order(V)
    n = dry.S1.shape[-1]
    nw = fit.A.shape[-1]
    L = fit.lags.size
    b = fit.b_ref
    size = 2 * n + L * nw
    out = np.zeros((V.size, size, size))
    for i, Vi in enumerate(V):
        q = 0.5 * model.flight.density * Vi**2
        M, C, K = (np.array(X[i], float) for X in (dry.S1, dry.S2, dry.S3))
        M[:nw, :nw] -= q * (b / Vi) ** 2 * fit.A[2]
        C[:nw, :nw] -= q * (b / Vi) * fit.A[1]
        K[:nw, :nw] -= q * fit.A[0]
        F = np.zeros((n, L * nw))                    # the lag states' loads on the wing rows
        for l in range(L):
            F[:nw, l * nw:(l + 1) * nw] = q * fit.A[3 + l]
        Minv = np.linalg.inv(M)
        A = out[i]
        A[:n, n:2 * n] = np.eye(n)
        A[n:2 * n, :n] = -Minv @ K
        A[n:2 * n, n:2 * n] = -Minv @ C
        A[n:2 * n, 2 * n:] = Minv @ F
        for l in range(L):
            r = slice(2 * n + l * nw, 2 * n + (l + 1) * nw)
            A[r, n:n + nw] = np.eye(nw)
            A[r, r] = -(Vi / b) * fit.lags[l] * np.eye(nw)
    return out
