"""Whirl sense and modal content: what a propeller's θ–ψ orbit and a mode shape say.

* :func:`orbit_signed_area`, :func:`whirl_sense`, :func:`rotation_sign_from_gyroscopic`:
  forward or backward whirl of a propeller mode (§9.2) from the sense of its θ–ψ orbit;
* :func:`content`, :func:`dominant`: the share of a mode shape in groups of states.
"""
from __future__ import annotations

import math
from collections.abc import Mapping, Sequence

import numpy as np

from propwhirl.validate import InputError, finite


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
