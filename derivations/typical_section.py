"""Typical section: a rigid aerofoil on plunge and pitch springs (the classic 2-DOF flutter model).

Coordinates q = [h, α]: plunge of the elastic axis (positive DOWN) and pitch about it (nose UP),
as the wing sections of chapter 7.  Per unit span: mass m, static unbalance S = m x_α b (centre of
gravity aft of the elastic axis positive), inertia I_α about the elastic axis, springs K_h, K_α.

    T = ½ m ḣ² + S ḣ α̇ + ½ I_α α̇²        (7.3 for one rigid strip)
    U = ½ K_h h² + ½ K_α α²

Lagrange's equations (5.1) give the structural mass and stiffness; the aerodynamic loads are the
same strip aerodynamics as the wing (generated/strip_aero.py), so this model is a standard check
of the unsteady-aerodynamics implementation (compare with the exact Theodorsen flutter
determinant in tests/model/test_typical_section.py).
"""
from __future__ import annotations

import sympy as sp

from derivations.common import Derivation, Output, Param, coordinates, lagrange_lhs, second_order_matrices, t

DOFS = ("h", "alpha")

m, S, I_alpha, K_h, K_alpha = sp.symbols("m S I_alpha K_h K_alpha", real=True)

PARAMS = (
    Param(m, "mass per unit span", "kg/m"),
    Param(S, "static unbalance per unit span, m x_α b (centre of gravity aft positive)", "kg"),
    Param(I_alpha, "pitch inertia per unit span about the elastic axis", "kg m"),
    Param(K_h, "plunge spring per unit span", "N/m^2"),
    Param(K_alpha, "pitch spring per unit span", "N"),
)


def derive() -> Derivation:
    h, alpha = q = coordinates(DOFS)
    hd, ad = sp.diff(h, t), sp.diff(alpha, t)
    T = sp.Rational(1, 2) * m * hd**2 + S * hd * ad + sp.Rational(1, 2) * I_alpha * ad**2
    U = sp.Rational(1, 2) * K_h * h**2 + sp.Rational(1, 2) * K_alpha * alpha**2
    M, C, K = second_order_matrices(lagrange_lhs(T, U, 0, q), q)
    assert C == sp.zeros(2, 2)
    return Derivation(
        module="typical_section",
        title="Typical section (pitch–plunge aerofoil on springs)",
        source="derivations/typical_section.py",
        equations="5.1, 7.1–7.3",
        doc=__doc__,
        params=PARAMS,
        outputs=[
            Output("mass", M, (m, S, I_alpha), "Structural mass matrix [h, α].", "5.1, 7.3", DOFS, DOFS),
            Output("stiffness", K, (K_h, K_alpha), "Spring stiffness matrix [h, α].", "5.1", DOFS, DOFS),
        ],
        blocks={"blocks": ("mass", "stiffness")},
    )
