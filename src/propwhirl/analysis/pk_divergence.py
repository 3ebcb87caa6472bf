"""Divergence in the p-k method: where the quasi-steady stiffness becomes singular.

The p-k sweep (:func:`propwhirl.analysis.pk.pk_sweep`) follows one root per oscillatory
mode.  Divergence is a real root through p = 0: when a mode's complex pair meets the real
axis it splits into two real roots, one moving left and one towards p = 0, and the sweep
follows whichever lies nearer the pair's last root — on ``examples/x57_like.toml`` the one
moving left, so the p-k reported no divergence where the default finds it at 226.2 m/s.

At p = 0 the p-k equation [(M_s − M_a) p² − C_a p + (K_s − K_a(k))] q̂ = 0 is the static
one, (K_s − K_a(0; V)) q̂ = 0 (k = 0: Theodorsen's C(0) = 1, the doublet lattice's steady
Q), so

    det T(0; V) = det(M) · Π_i (−p_i(V))

changes sign exactly where an odd number of real roots crosses zero (complex pairs contribute
|p_i|² > 0).  :func:`divergence_crossings` finds the sign changes of det T(0; V) over the
swept speeds (one LU per speed), refines each by Brent's method on
sign(det) · |det|^(1/n) (continuous, of moderate size) to ``xtol``, and says from the real
root nearest zero on either side whether the wing diverges ("onset") or recovers
("recovery"), and that root's slope dp/dV, with which the p-k sweep converges a Mach-matched
doublet-lattice wing's crossing at its own Mach (:func:`propwhirl.analysis.pk_crossings.matched_crossing`).
No mode is followed, so no split can
be missed; the divergence speed is the finite-state models' too (their steady loads are the
same), which the tests use.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla
from scipy.optimize import brentq

from propwhirl.model.frequency_domain import K_MIN, pk_system, reference_semichord


@dataclass(frozen=True)
class StaticCrossing:
    """A divergence crossing of the p-k equation: speed V [m/s], the real root p [1/s]
    through zero there (≈ 0), the direction ("onset": a real root becomes positive with
    increasing V; "recovery") and that root's slope dp/dV [1/s per m/s]."""

    V: float
    p: complex
    direction: str
    slope: float


def static_stiffness(model, V: float, tables=None, dry=None) -> np.ndarray:
    """K_s − K_a(k → 0; V): the p-k equation's matrix at p = 0 at airspeed V [m/s]
    (:func:`propwhirl.model.frequency_domain.pk_system` at ω = K_MIN · V / b_ref; ``dry``:
    the analysis's :func:`~propwhirl.model.frequency_domain.dry_assembly`)."""
    return pk_system(model, V, tables, dry=dry)(K_MIN * V / reference_semichord(model))[2]


def _scaled_det(K: np.ndarray) -> float:
    """sign(det K) · |det K|^(1/n): zero where det K is, without over- or underflow."""
    sign, logdet = np.linalg.slogdet(K)
    return float(sign * np.exp(logdet / K.shape[0])) if sign != 0 else 0.0


def _root_near_zero(model, V: float, tables, dry=None) -> complex:
    """The real root [1/s] of the p-k equation at k → 0 nearest p = 0 at V [m/s]."""
    M, C, K = pk_system(model, V, tables, dry=dry)(K_MIN * V / reference_semichord(model))
    n = M.shape[0]
    eye, zero = np.eye(n), np.zeros((n, n))   # pencil [[0, I], [−K, −C]] − p [[I, 0], [0, M]]
    lam = sla.eigvals(np.block([[zero, eye], [-K, -C]]), np.block([[eye, zero], [zero, M]]))
    lam = lam[np.isfinite(lam)]
    return complex(lam[np.argmin(np.abs(lam))])


def divergence_crossings(model, speeds, *, xtol: float, tables=None,
                         dry=None) -> tuple[StaticCrossing, ...]:
    """The divergence crossings of the p-k equation of ``model`` over the increasing
    airspeeds ``speeds`` [m/s] (module docstring), each to ``xtol`` [m/s].  ``tables``: a
    doublet-lattice wing's (the analysis's; a Mach-matched wing's Q between the tables' Mach
    nodes, which the p-k sweep then converges at the crossing's own Mach); ``dry``: the
    analysis's :func:`~propwhirl.model.frequency_domain.dry_assembly`."""
    V = np.asarray(speeds, dtype=float)
    d = np.array([_scaled_det(static_stiffness(model, x, tables, dry)) for x in V])
    out = []
    for i in np.flatnonzero(d[:-1] * d[1:] < 0):
        a, b = float(V[i]), float(V[i + 1])
        Vd = brentq(lambda x: _scaled_det(static_stiffness(model, x, tables, dry)), a, b,
                    xtol=xtol)
        h = min(xtol, 0.25 * (b - a))
        lo = _root_near_zero(model, max(a, Vd - h), tables, dry)
        hi = _root_near_zero(model, min(b, Vd + h), tables, dry)
        p = _root_near_zero(model, Vd, tables, dry)
        out.append(StaticCrossing(float(Vd), complex(p.real, 0.0),
                                  "onset" if hi.real > lo.real else "recovery",
                                  float((hi.real - lo.real) / (2 * h))))
    return tuple(out)
