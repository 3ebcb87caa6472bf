"""Euler–Bernoulli bending–torsion beam element of the cantilever wing (thesis §7.1).

Element degrees of freedom (7.16):  q_e = [h1, φ1, α1, h2, φ2, α2]
  h  vertical displacement of the elastic axis, positive DOWN            [m]
  φ  bending slope ∂h/∂y                                                [rad]
  α  twist about the elastic axis, positive nose UP                     [rad]

Displacement of a point at chordwise x (7.1):  z_W = h + (x − ab) α, so with the sectional
mass m, static unbalance S = m x_α b (centre of gravity aft of the elastic axis positive) and
polar inertia ρI_p about the elastic axis, the kinetic energy per unit span is
½(m ḣ² + 2 S ḣ α̇ + ρI_p α̇²)   (7.2–7.3);  the strain energy ½(EI h''² + GJ α'²)   (7.4).

Bending uses Hermite cubics, torsion linear shape functions, on ξ = 2y/l_e − 1 ∈ [−1, 1]
(7.5–7.8).  Integrating over the element and applying Lagrange's equations (5.1) gives the
element mass and stiffness matrices (7.9–7.15) with properties constant over the element.
"""
from __future__ import annotations

import sympy as sp

from derivations.common import (
    Derivation,
    Output,
    Param,
    coordinates,
    lagrange_lhs,
    second_order_matrices,
    t,
)

DOFS = ("h1", "phi1", "alpha1", "h2", "phi2", "alpha2")

l_e, m, rho_Ip, x_alpha_b, EI, GJ = sp.symbols("length m rho_Ip x_alpha_b EI GJ", real=True)
xi = sp.Symbol("xi", real=True)

PARAMS = (
    Param(l_e, "element length", "m"),
    Param(m, "mass per unit span", "kg/m"),
    Param(rho_Ip, "polar mass moment of inertia per unit span about the elastic axis", "kg m"),
    Param(x_alpha_b, "centre of gravity aft of the elastic axis (x_α b)", "m"),
    Param(EI, "bending rigidity", "N m^2"),
    Param(GJ, "torsional rigidity", "N m^2"),
)


def shape_functions():
    """Hermite bending shapes for (h1, φ1, h2, φ2) and linear torsion shapes (α1, α2).

    Thesis (7.6) prints the h2 shape as N2 and the φ2 shape without its minus sign; the
    functions here are ordered by the degree of freedom they multiply (see docs/errata.md).
    """
    N = sp.Matrix(
        [
            sp.Rational(1, 4) * (1 - xi) ** 2 * (2 + xi),  # h1
            l_e / 8 * (1 - xi) ** 2 * (1 + xi),  # φ1
            sp.Rational(1, 4) * (1 + xi) ** 2 * (2 - xi),  # h2
            -l_e / 8 * (1 + xi) ** 2 * (1 - xi),  # φ2
        ]
    )
    T = sp.Matrix([(1 - xi) / 2, (1 + xi) / 2])  # α1, α2   (7.8)
    return N, T


def derive() -> Derivation:
    q = coordinates(DOFS)
    h1, p1, a1, h2, p2, a2 = q
    N, Tsh = shape_functions()
    h = (N.T * sp.Matrix([h1, p1, h2, p2]))[0]  # (7.5)
    alpha = (Tsh.T * sp.Matrix([a1, a2]))[0]  # (7.7)
    dy_dxi = l_e / 2
    hd, ad = sp.diff(h, t), sp.diff(alpha, t)
    # Kinetic energy (7.3) and strain energy (7.4), integrated over the element.
    T_density = sp.Rational(1, 2) * (m * hd**2 + 2 * m * x_alpha_b * hd * ad + rho_Ip * ad**2)
    h_yy = sp.diff(h, xi, 2) / dy_dxi**2
    a_y = sp.diff(alpha, xi) / dy_dxi
    U_density = sp.Rational(1, 2) * (EI * h_yy**2 + GJ * a_y**2)
    T = sp.integrate(sp.expand(T_density * dy_dxi), (xi, -1, 1))
    U = sp.integrate(sp.expand(U_density * dy_dxi), (xi, -1, 1))
    M, C, K = second_order_matrices(lagrange_lhs(T, U, 0, q), q)
    assert C == sp.zeros(6, 6)
    return Derivation(
        module="beam_element",
        title="Euler–Bernoulli bending–torsion beam element",
        source="derivations/beam_element.py",
        equations="7.1–7.16",
        doc=__doc__,
        params=PARAMS,
        outputs=[
            Output(
                "mass",
                M,
                (l_e, m, rho_Ip, x_alpha_b),
                "Element mass matrix [h1, φ1, α1, h2, φ2, α2] (M_b, M_t, M_tb of 7.11–7.13).",
                "7.9–7.13",
                DOFS,
                DOFS,
            ),
            Output(
                "stiffness",
                K,
                (l_e, EI, GJ),
                "Element stiffness matrix [h1, φ1, α1, h2, φ2, α2] (K_b, K_t of 7.14–7.15).",
                "7.9, 7.14–7.15",
                DOFS,
                DOFS,
            ),
        ],
        blocks={"blocks": ("mass", "stiffness")},
    )
