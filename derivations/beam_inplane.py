"""Beam element with the second (in-plane, chordwise) bending plane (beyond the thesis, issue 14).

Element degrees of freedom: the bending–torsion DOFs of the thesis's element (7.16) and, per
node, the in-plane displacement and slope:
  q_e = [h1, φ1, α1, v1, χ1, h2, φ2, α2, v2, χ2]
  h, φ, α  as in derivations/beam_element.py (h positive DOWN, φ = ∂h/∂y, α nose UP)
  v  in-plane (chordwise) displacement of the elastic axis, positive REARWARD        [m]
  χ  in-plane bending slope ∂v/∂y                                                  [rad]

A point of the section at chordwise position x (z ≈ 0: a thin section, as the thesis's
element) moves by
  δx = v,   δy = −(x − ab) χ,   δz = h + (x − ab) α,
(y spanwise: the rotation of the section about the vertical axis that turns the span line
by χ turns a chordwise fibre by −χ).  The kinetic energy per unit span adds to (7.3)
  ½ m v̇² + ½ ρI_z χ̇²,
ρI_z = Σ m (x − ab)² the in-plane rotary inertia about the vertical axis through the
elastic axis (for the thin section ρI_z = ρI_p; the runtime passes ρI_p), and the strain
energy adds ½ EI_c v''² to (7.4), EI_c the in-plane (chordwise) bending rigidity.  No
term couples the two planes: the cross terms of δx, δy with δz vanish (orthogonal
directions), and an unswept straight beam with its principal axes along chord and
thickness has no bending–bending coupling stiffness.  v uses the Hermite cubics of h (7.6),
so the in-plane matrices are the bending ones with (m, EI) → (m, EI_c), plus the rotary
inertia term (Rayleigh beam): ρI_z ∫ N'ᵀN' dy.

Lagrange's equations (5.1) on the 10-DOF element give its mass and stiffness; the derivation
checks that their bending–torsion part is exactly the thesis's element
(derivations/beam_element.py) and that nothing couples it to the in-plane DOFs, and
generates the in-plane block [v1, χ1, v2, χ2] alone (the bending–torsion block is the
existing generated element, unchanged).
"""
from __future__ import annotations

import sympy as sp

from derivations import beam_element as bt
from derivations.common import (
    Derivation,
    Output,
    Param,
    coordinates,
    lagrange_lhs,
    second_order_matrices,
    t,
)

DOFS = ("h1", "phi1", "alpha1", "v1", "chi1", "h2", "phi2", "alpha2", "v2", "chi2")
INPLANE = ("v1", "chi1", "v2", "chi2")
#: positions of the thesis element's DOFs [h1, φ1, α1, h2, φ2, α2] and of the in-plane ones
BT_INDEX = (0, 1, 2, 5, 6, 7)
IP_INDEX = (3, 4, 8, 9)

l_e, m, rho_Ip, x_alpha_b, EI, GJ = bt.l_e, bt.m, bt.rho_Ip, bt.x_alpha_b, bt.EI, bt.GJ
xi = bt.xi
rho_Iz, EI_c = sp.symbols("rho_Iz EI_chordwise", real=True)

PARAMS = (
    Param(l_e, "element length", "m"),
    Param(m, "mass per unit span", "kg/m"),
    Param(rho_Iz, "in-plane rotary inertia per unit span about the vertical axis through the "
          "elastic axis (thin section: the polar inertia rho I_p)", "kg m"),
    Param(EI_c, "in-plane (chordwise) bending rigidity", "N m^2"),
)


def energies():
    """(T, U, q) of the 10-DOF element, integrated over its length."""
    q = coordinates(DOFS)
    h1, p1, a1, v1, c1, h2, p2, a2, v2, c2 = q
    N, Tsh = bt.shape_functions()
    h = (N.T * sp.Matrix([h1, p1, h2, p2]))[0]       # (7.5)
    v = (N.T * sp.Matrix([v1, c1, v2, c2]))[0]       # the same Hermite cubics
    alpha = (Tsh.T * sp.Matrix([a1, a2]))[0]         # (7.7)
    dy_dxi = l_e / 2
    hd, ad, vd = (sp.diff(f, t) for f in (h, alpha, v))
    chid = sp.diff(v, xi, t) / dy_dxi                # χ̇ = ∂v̇/∂y
    T_density = sp.Rational(1, 2) * (m * hd**2 + 2 * m * x_alpha_b * hd * ad + rho_Ip * ad**2
                                     + m * vd**2 + rho_Iz * chid**2)
    h_yy = sp.diff(h, xi, 2) / dy_dxi**2
    v_yy = sp.diff(v, xi, 2) / dy_dxi**2
    a_y = sp.diff(alpha, xi) / dy_dxi
    U_density = sp.Rational(1, 2) * (EI * h_yy**2 + GJ * a_y**2 + EI_c * v_yy**2)
    T = sp.integrate(sp.expand(T_density * dy_dxi), (xi, -1, 1))
    U = sp.integrate(sp.expand(U_density * dy_dxi), (xi, -1, 1))
    return T, U, q


def derive() -> Derivation:
    T, U, q = energies()
    M, C, K = second_order_matrices(lagrange_lhs(T, U, 0, q), q)
    assert C == sp.zeros(10, 10)
    # The bending–torsion part is the thesis's element, and nothing couples the planes.
    ref = {o.name: o.matrix for o in bt.derive().outputs}
    bti, ipi = list(BT_INDEX), list(IP_INDEX)
    for mine, name in ((M, "mass"), (K, "stiffness")):
        if (mine.extract(bti, bti) - ref[name]).applyfunc(sp.expand) != sp.zeros(6, 6):
            raise AssertionError(f"bending-torsion {name} differs from derivations/beam_element")
        if mine.extract(bti, ipi) != sp.zeros(6, 4):
            raise AssertionError(f"in-plane DOFs couple to bending-torsion in the {name}")
    Mi, Ki = M.extract(ipi, ipi), K.extract(ipi, ipi)
    # in-plane = bending with (m, EI) → (m, EI_c), plus the rotary inertia of the section
    Mb = ref["mass"].extract([0, 1, 3, 4], [0, 1, 3, 4])
    Kb = ref["stiffness"].extract([0, 1, 3, 4], [0, 1, 3, 4]).subs(EI, EI_c)
    assert (Mi.subs(rho_Iz, 0) - Mb).applyfunc(sp.expand) == sp.zeros(4, 4)
    assert (Ki - Kb).applyfunc(sp.expand) == sp.zeros(4, 4)
    dofs = dict(rows=INPLANE, cols=INPLANE)
    return Derivation(
        module="beam_inplane",
        title="In-plane (chordwise) bending of the beam element",
        source="derivations/beam_inplane.py",
        equations="7.1–7.16 extended (issue 14)",
        doc=__doc__,
        params=PARAMS,
        outputs=[
            Output("inplane_mass", Mi, (l_e, m, rho_Iz),
                   "In-plane element mass matrix [v1, χ1, v2, χ2]: translation m and rotary "
                   "inertia rho_Iz (Rayleigh beam).", "7.11 with the rotary-inertia term",
                   **dofs),
            Output("inplane_stiffness", Ki, (l_e, EI_c),
                   "In-plane element stiffness matrix [v1, χ1, v2, χ2] (EI_c in place of EI "
                   "in 7.14).", "7.14", **dofs),
        ],
        blocks={"inplane_blocks": ("inplane_mass", "inplane_stiffness")},
    )
