"""Theodorsen's function C(k) (thesis eq. 4.31, 7.24): the lift deficiency of an oscillating
thin aerofoil in incompressible flow, used by the Houbolt–Reed propeller derivatives."""
from __future__ import annotations

import math

import numpy as np
from scipy.special import hankel2e

from propwhirl import validate as v

_EULER_GAMMA = 0.57721566490153286061
_SMALL_K = 1e-8  # below this C(k) uses its two-term expansion (error O(k² ln² k) < 1e-13)
_LARGE_K = 1e4   # above this C(k) uses its asymptotic expansion (error < 1e-17)


def theodorsen(k) -> np.ndarray:
    """Theodorsen's function C(k) = F(k) + iG(k) (eq. 4.31), vectorised over `k` (≥ 0).

    C(k) = H1⁽²⁾(k) / (H1⁽²⁾(k) + i H0⁽²⁾(k)).  Evaluated with the exponentially scaled
    Hankel functions (the common factor e^{ik} cancels).  Limits: for k < 1e-8 the
    expansion C ≈ 1 − πk/2 + i k (ln(k/2) + γ) (the Hankel functions overflow as k → 0),
    C(0) = 1 exactly; for k > 1e4 the asymptotic series
    C ≈ 1/2 + 1/(16k²) − i (1/(8k) − 7/(128k³)) (scipy loses digits and fails near 1e300),
    C(∞) = 1/2 exactly.  Returns a complex array of the shape of `k`.
    """
    try:
        k = np.asarray(k, dtype=float)
    except (TypeError, ValueError) as exc:
        raise v.InputError(f"reduced frequency k = {k!r} is invalid: must be real") from exc
    bad = np.isnan(k) | (k < 0)
    if bad.any():
        raise v.InputError(f"reduced frequency k = {k[bad].flat[0] if k.ndim else k.item()!r}"
                           " is invalid: must be >= 0 (inf allowed)")
    out = np.empty(k.shape, dtype=complex)
    small = k < _SMALL_K
    large = k > _LARGE_K
    reg = ~(small | large)
    if reg.any():
        kr = k[reg]
        h1 = hankel2e(1, kr)
        h0 = hankel2e(0, kr)
        out[reg] = h1 / (h1 + 1j * h0)
    if small.any():
        ks = k[small]
        with np.errstate(divide="ignore", invalid="ignore"):
            g = np.where(ks > 0, ks * (np.log(ks / 2.0) + _EULER_GAMMA), 0.0)
        out[small] = (1.0 - 0.5 * math.pi * ks) + 1j * g
    if large.any():
        with np.errstate(over="ignore", divide="ignore"):
            inv = 1.0 / k[large]                        # 0 at k = inf
            out[large] = (0.5 + inv * inv / 16.0) - 1j * (inv / 8.0 - 7.0 / 128.0 * inv ** 3)
    return out
