"""Cubic Hermite models of a quantity over one speed step (values and slopes at both ends).

The tracker models Re λ of a branch (hump check), the paths of complex branches (veering
check), the coefficients of a cluster's characteristic polynomial, a pair's discriminant and a
crossing's prediction this way, on s = (V − V_a)/(V_b − V_a) ∈ [0, 1]; the campaign report
draws its V-g-f curves between the analysed speeds with them
(:func:`propwhirl.app.plots.campaign_plot.hermite`).  (The beam element's Hermite shape
functions along the span are another thing: :func:`propwhirl.model.structure.mesh.beam_interpolation`.)
"""
from __future__ import annotations

import numpy as np


def hermite_coeffs(fa, fb, ga, gb, h):
    """The cubic p(s) = c0 + c1 s + c2 s² + c3 s³ on s = (V − V_a)/h ∈ [0, 1] with the values
    fa, fb and the slopes ga, gb [per unit of V] of a quantity at both ends of a step of
    h = V_b − V_a: (c0, c1, c2, c3), arrays broadcast (real or complex)."""
    c0, c1 = fa, ga * h
    c2 = 3 * (fb - fa) - (2 * ga + gb) * h
    c3 = 2 * (fa - fb) + (ga + gb) * h
    return c0, c1, c2, c3


def hermite_eval(c, s):
    """p(s) of the cubic of :func:`hermite_coeffs` (Horner), s broadcast with the coefficients."""
    c0, c1, c2, c3 = c
    return c0 + s * (c1 + s * (c2 + s * c3))


#: interior abscissae (fractions of a step) at which the Hermite models are checked, besides
#: their stationary points
CHECK_S = np.linspace(0.1, 0.9, 9)
