"""Propeller rigid on a hub point: its aerodynamic and gyroscopic loads on the hub's motion
(issue 22, a modal structure whose mount flexibility is inside the finite-element modes).

Degrees of freedom  u = [z_H, y_H, θ_H, ψ_H]: the hub's displacement down (z_H, the sense of
the wing's h), sideways (y_H, the sense of chapter 8's y_i, spanwise outboard for the thesis's
wing), its pitch (θ_H, nose up, the sense of θ and α_P) and its yaw (ψ_H, the sense of ψ and of
the in-plane slope χ_P).  The rotor's pivoting mass, its mount and everything else of the
structure are in the structure's modes; what the propeller adds on the hub are

* the rotor's spin energy T_Ω = ½ I_Ω ω_X², ω_X = Ω + θ̇_H sin ψ_H (8.7 with the hub's total
  pitch and yaw): the gyroscopic coupling of pitch and yaw rates;
* the Houbolt–Reed hub loads (4.25) at the effective angles θ̄ = θ_H + ż_H/V and
  ψ̄ = ψ_H − ẏ_H/V (8.26), by the virtual work δW = F_Z δz_H + F_Y δy_H + M_Y,P δθ_H + M_Z,P δψ_H.

Oracle (checked here): with the hub motion of chapter 8 with in-plane bending,
  z_H = h_P + e_α α_P + e_θ θ,  y_H = −e_ψ ψ − e_α χ_P,  θ_H = θ + α_P,  ψ_H = ψ + χ_P
(the matrix `hub_motion` G over [θ, ψ, h_P, α_P, v_P, χ_P]), Gᵀ (M_a, C_a, K_a) G are the
aerodynamic matrices and Gᵀ C_g G the gyroscopic matrix of derivations/prop_flexwing_inplane.py
(and so of chapter 8, to which that reduces) — every entry, symbolically.
"""
from __future__ import annotations

import sympy as sp

from derivations import prop_flexwing as ch8
from derivations import prop_flexwing_inplane as inplane
from derivations import prop_rigid as ch6
from derivations.common import (
    Derivation,
    Output,
    coordinates,
    generalised_forces,
    lagrange_lhs,
    second_order_matrices,
    t,
)

DOFS = ("z_H", "y_H", "theta_H", "psi_H")
INPLANE_DOFS = inplane.DOFS
I_Omega, Omega = ch8.I_Omega, ch8.Omega
rho, V, R = ch8.rho, ch8.V, ch8.R
e_theta, e_psi, e_alpha = ch8.e_theta, ch8.e_psi, ch8.e_alpha
DERIVATIVES = ch8.DERIVATIVES

_ch8 = {p.symbol: p for p in ch8.PARAMS}
PARAMS = tuple(_ch8[s] for s in (I_Omega, Omega, rho, V, R, e_theta, e_psi, e_alpha,
                                 *DERIVATIVES))
AERO_ARGS = (rho, V, R, *DERIVATIVES)


def hub_motion_matrix() -> sp.Matrix:
    """G (4 × 6): u = [z_H, y_H, θ_H, ψ_H] from [θ, ψ, h_P, α_P, v_P, χ_P] (module docstring)."""
    return sp.Matrix([
        [e_theta, 0, 1, e_alpha, 0, 0],
        [0, -e_psi, 0, 0, 0, -e_alpha],
        [1, 0, 0, 1, 0, 0],
        [0, 1, 0, 0, 0, 1],
    ])


def derive() -> Derivation:
    u = coordinates(DOFS)
    z, y, th, ps = u
    thd = sp.diff(th, t)
    wX = Omega + thd * sp.sin(ps)
    _, Cg, Kg = second_order_matrices(lagrange_lhs(I_Omega * wX**2 / 2, 0, 0, u), u)
    assert Kg == sp.zeros(4, 4) and Cg + Cg.T == sp.zeros(4, 4)
    theta_bar = th + sp.diff(z, t) / V
    psi_bar = ps - sp.diff(y, t) / V
    F_Z, M_YP, F_Y, M_ZP = ch6.hub_loads(theta_bar, psi_bar)
    du = sp.symbols("delta_z delta_y delta_theta delta_psi")
    dW = F_Z * du[0] + F_Y * du[1] + M_YP * du[2] + M_ZP * du[3]
    Ma, Ca, Ka = second_order_matrices(generalised_forces(dW, du), u)
    G = hub_motion_matrix()
    check_against_inplane(G, Cg, Ma, Ca, Ka)

    hub = dict(rows=DOFS, cols=DOFS)
    eq = "4.25, 8.7, 8.26 on the hub's motion"
    outputs = [
        Output("Cg", Cg, (I_Omega, Omega),
               "Gyroscopic matrix of the spinning rotor on the hub (rows and columns z_H, y_H, "
               "θ_H, ψ_H).", eq, **hub),
        Output("Ma_hub", Ma, AERO_ARGS, "Propeller aerodynamic mass on the hub (loads "
               "F_Z, F_Y, M_Y, M_Z per hub acceleration).", eq, **hub),
        Output("Ca_hub", Ca, AERO_ARGS, "Propeller aerodynamic damping on the hub.", eq, **hub),
        Output("Ka_hub", Ka, AERO_ARGS, "Propeller aerodynamic stiffness on the hub.", eq,
               **hub),
        Output("hub_motion", G, (e_theta, e_psi, e_alpha),
               "The hub's motion [z_H, y_H, θ_H, ψ_H] from chapter 8's coordinates with "
               "in-plane bending [θ, ψ, h_P, α_P, v_P, χ_P] (the oracle's map; a beam model's "
               "hub written as a grid).", "8.26, 8.34 with in-plane bending",
               rows=DOFS, cols=INPLANE_DOFS),
    ]
    return Derivation(
        module="prop_hub",
        title="Propeller rigid on a hub point (aerodynamic and gyroscopic loads on the hub)",
        source="derivations/prop_hub.py",
        equations="4.25, 8.7, 8.26 (issue 22)",
        doc=__doc__,
        params=PARAMS,
        outputs=outputs,
        blocks={"hub_blocks": ("Cg", "Ma_hub", "Ca_hub", "Ka_hub")},
    )


def _inplane_full(outs: dict, ch8outs: dict, names: tuple[str, str, str, str]) -> sp.Matrix:
    """A 6 × 6 matrix over [θ, ψ, h_P, α_P, v_P, χ_P] from its four blocks (names: P×P from
    chapter 8, P×W, W×P, W×W from the in-plane derivation)."""
    pp, pw, wp, ww = names
    A = ch8outs[pp] if isinstance(pp, str) else pp
    return sp.Matrix(sp.BlockMatrix([[A, outs[pw]], [outs[wp], outs[ww]]]))


def check_against_inplane(G, Cg, Ma, Ca, Ka) -> None:
    """Gᵀ X G is the in-plane chapter-8 model's X for the aerodynamic and gyroscopic matrices
    (module docstring); raises if any entry differs."""
    outs = {o.name: o.matrix for o in inplane.derive().outputs}
    c8 = {o.name: o.matrix for o in ch8.derive().outputs}
    gyro_pp = c8["Cs_viscous"].subs({ch8.zeta_theta: 0, ch8.zeta_psi: 0})
    pairs = [
        ("gyroscopic", Cg, _inplane_full(outs, c8, (gyro_pp, "Ds", "Hs", "Js"))),
        ("aerodynamic mass", Ma, _inplane_full(outs, c8, ("Aa", "Ba", "P1", "P2"))),
        ("aerodynamic damping", Ca, _inplane_full(outs, c8, ("Ca", "Da", "P3", "P4"))),
        ("aerodynamic stiffness", Ka, _inplane_full(outs, c8, ("Ea", "Fa", "P5", "P6"))),
    ]
    for name, hub, ref in pairs:
        diff = (G.T * hub * G - ref).applyfunc(sp.expand)
        if diff != sp.zeros(6, 6):
            raise AssertionError(f"the hub's {name} matrix is not chapter 8's through the hub "
                                 f"motion: {diff}")
