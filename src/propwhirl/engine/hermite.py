"""Cubic Hermite models of a quantity over one speed step (values and slopes at both ends).

The tracker models Re λ of a branch (hump check), the paths of complex branches (veering
check), the coefficients of a cluster's characteristic polynomial, a pair's discriminant and a
crossing's prediction this way, on s = (V − V_a)/(V_b − V_a) ∈ [0, 1].
"""
from __future__ import annotations

import numpy as np


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
