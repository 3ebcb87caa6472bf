"""Propeller on a flexible wing with in-plane wing bending: the node coupling (issue 14).

Degrees of freedom  q = [θ, ψ, h_P, α_P, v_P, χ_P]: those of derivations/prop_flexwing.py and the
wing node's in-plane displacement v_P (positive rearward, along the shaft) and in-plane slope
χ_P = ∂v/∂y (derivations/beam_inplane.py).  Distances signed, positive rearward, from the wing
mid-chord, as in chapter 8.

Kinematics.  The node's in-plane slope turns the nacelle about the vertical axis in the sense
of its yaw ψ, as its twist α_P turns it in the sense of its pitch θ; its in-plane displacement
moves the nacelle along the shaft.  A point mass m_i on the shaft axis at x_i moves by
  z_i = h_P + (x_i − a_P b_P) α_P + (x_i − l_θ) θ                       (8.2, unchanged)
  y_i = −(x_i − l_ψ) ψ − (x_i − a_P b_P) χ_P = −(x_i − l_ψ)(ψ + χ_P) − (l_ψ − a_P b_P) χ_P
  x_i = v_P,
so T_P = ½ Σ m_i (ż_i² + ẏ_i² + ẋ_i²) is (8.4) plus
  ½ M_P v̇_P² + I_ψχ,P ψ̇ χ̇_P + ½ I_χ,P χ̇_P²,
  I_χ,P = Σ m (x − a_P b_P)²,   I_ψχ,P = Σ m (x − l_ψ)(x − a_P b_P)
(from the pivot values: with d = l_ψ − a_P b_P, I_ψχ,P = I_ψ,P + d S_ψ,P and
I_χ,P = I_ψ,P + 2 d S_ψ,P + d² M_P, S_ψ,P = Σ m (x − l_ψ); checked on point masses).  The
rotor's spin energy T_Ω = ½ I_Ω ω_X² with ω_X = Ω + (θ̇ + α̇_P) sin(ψ + χ_P) (8.7 with the
total yaw): the gyroscopic moment of the rotor now loads the node's in-plane slope.
U and D as (8.9)–(8.11) (the wing's own in-plane stiffness and damping come from the beam).

Aerodynamics.  The hub moves by
  δz_hub = δh_P + e_α δα_P + e_θ δθ,   δy_hub = −e_ψ δψ − e_α δχ_P,
the effective angles are θ̄ = θ + α_P + ż_hub/V and ψ̄ = ψ + χ_P − ẏ_hub/V, the hub loads (4.25),
and the virtual work
  δW = F_Z (δh_P + e_α δα_P + e_θ δθ) + M_Y,P (δθ + δα_P)
       + F_Y (−e_ψ δψ − e_α δχ_P) + M_Z,P (δψ + δχ_P),
so Q_χ,P = M_Z,P − e_α F_Y: the side force through its offset e_α from the elastic axis and the
yaw moment bend the wing in its plane; Q_v,P = 0 (no thrust perturbation: the thesis's
windmilling propeller, §6.1).  The wing's strip aerodynamics have no in-plane (drag) loads.

With v_P = χ_P = 0 every matrix is chapter 8's (checked); the generated functions are the
blocks that change — B_s, D_s, F_s, G_s, H_s, B_a, D_a, F_a, P_1 … P_6 — over the node DOFs
[h_P, α_P, v_P, χ_P]; A_s, C_s, E_s, A_a, C_a, E_a are those of prop_flexwing (checked equal).
"""
from __future__ import annotations

import sympy as sp

from derivations import prop_flexwing as ch8
from derivations import prop_rigid as ch6
from derivations.common import (
    Derivation,
    Output,
    Param,
    coordinates,
    generalised_forces,
    lagrange_lhs,
    second_order_matrices,
    t,
)

DOFS = ("theta", "psi", "h_P", "alpha_P", "v_P", "chi_P")
QP = DOFS[:2]
QWP = DOFS[2:]

I_chi_P = sp.Symbol("I_chi_P", positive=True)
I_psi_chi_P, S_psi_P, l_psi = sp.symbols("I_psi_chi_P S_psi_P l_psi", real=True)
(I_Omega, M_P, I_theta_P, I_psi_P, I_alpha_P, S_theta_P, S_alpha_P, I_theta_alpha_P,
 a_P_b_P, e_alpha) = (ch8.I_Omega, ch8.M_P, ch8.I_theta_P, ch8.I_psi_P, ch8.I_alpha_P,
                      ch8.S_theta_P, ch8.S_alpha_P, ch8.I_theta_alpha_P, ch8.a_P_b_P,
                      ch8.e_alpha)
Omega, K_theta, K_psi = ch8.Omega, ch8.K_theta, ch8.K_psi
zeta_theta, zeta_psi = ch8.zeta_theta, ch8.zeta_psi
rho, V, R, e_theta, e_psi = ch8.rho, ch8.V, ch8.R, ch8.e_theta, ch8.e_psi
DERIVATIVES = ch8.DERIVATIVES

_ch8 = {p.symbol: p for p in ch8.PARAMS}
PARAMS = (
    *(_ch8[s] for s in (I_Omega, M_P, S_theta_P, I_theta_P, I_psi_P, S_alpha_P, I_alpha_P,
                        I_theta_alpha_P)),
    Param(S_psi_P, "static moment of the pivoting mass about the yaw pivot, Σ m (x − l_ψ)",
          "kg m"),
    Param(I_chi_P, "moment of inertia of the pivoting mass about the vertical axis through the "
          "wing elastic axis, Σ m (x − a_P b_P)^2", "kg m^2"),
    Param(I_psi_chi_P, "product of inertia Σ m (x − l_ψ)(x − a_P b_P)", "kg m^2"),
    Param(l_psi, "yaw pivot position aft of the wing mid-chord (signed)", "m"),
    *(_ch8[s] for s in (a_P_b_P, e_theta, e_psi, e_alpha, Omega, K_theta, K_psi, zeta_theta,
                        zeta_psi, rho, V, R)),
    *(_ch8[s] for s in DERIVATIVES),
)

AERO_ARGS = ch8.AERO_ARGS


def inplane_inertia_formulas(Mp: sp.Expr, S_ps: sp.Expr, I_ps: sp.Expr):
    """(I_χ,P, I_ψχ,P) from (M_P, S_ψ,P, I_ψ,P) about the yaw pivot (module docstring)."""
    d = l_psi - a_P_b_P
    return (I_ps + 2 * d * S_ps + d**2 * Mp, I_ps + d * S_ps)


def check_point_mass_inertia(n: int = 3) -> None:
    """The in-plane kinetic energy of n point masses on the shaft is the form used (raises if not)."""
    ms = sp.symbols(f"m0:{n}", positive=True)
    xs = sp.symbols(f"x0:{n}", real=True)
    psd, chd, vd = sp.symbols("psd chd vd", real=True)
    ab = a_P_b_P
    T_pts = sum(mi * (((xi - l_psi) * psd + (xi - ab) * chd) ** 2 + vd**2) / 2
                for mi, xi in zip(ms, xs))
    Mp = sum(ms)
    S_ps = sum(mi * (xi - l_psi) for mi, xi in zip(ms, xs))
    I_ps = sum(mi * (xi - l_psi) ** 2 for mi, xi in zip(ms, xs))
    I_ch, I_pc = inplane_inertia_formulas(Mp, S_ps, I_ps)
    T_form = Mp * vd**2 / 2 + I_ps * psd**2 / 2 + I_pc * psd * chd + I_ch * chd**2 / 2
    if sp.expand(T_pts - T_form) != 0:
        raise AssertionError("point-mass in-plane kinetic energy differs from the form used")


def derive() -> Derivation:
    check_point_mass_inertia()
    q = coordinates(DOFS)
    theta, psi, h, alpha, vP, chi = q
    thd, psd, hd, ald, vd, chd = (sp.diff(c, t) for c in q)

    T_P = (M_P * hd**2 / 2 + I_alpha_P * ald**2 / 2 + I_theta_P * thd**2 / 2
           + S_alpha_P * hd * ald + S_theta_P * hd * thd + I_theta_alpha_P * ald * thd
           + I_psi_P * psd**2 / 2                                   # (8.4)
           + M_P * vd**2 / 2 + I_psi_chi_P * psd * chd + I_chi_P * chd**2 / 2)
    wX = Omega + (thd + ald) * sp.sin(psi + chi)
    T = T_P + I_Omega * wX**2 / 2
    U = (K_theta * theta**2 + K_psi * psi**2) / 2
    c_theta = 2 * zeta_theta * sp.sqrt(K_theta / I_theta_P) * I_theta_P
    c_psi = 2 * zeta_psi * sp.sqrt(K_psi / I_psi_P) * I_psi_P
    D_visc = (c_theta * thd**2 + c_psi * psd**2) / 2
    M, C0, K = second_order_matrices(lagrange_lhs(T, U, 0, q), q)
    _, C_v, _ = second_order_matrices(lagrange_lhs(T, U, D_visc, q), q)
    assert K[:, 2:] == sp.zeros(6, 4) and K[2:, :] == sp.zeros(4, 6)
    assert C0 + C0.T == sp.zeros(6, 6) and M == M.T

    z_hub = h + e_alpha * alpha + e_theta * theta
    y_hub = -e_psi * psi - e_alpha * chi
    theta_bar = theta + alpha + sp.diff(z_hub, t) / V
    psi_bar = psi + chi - sp.diff(y_hub, t) / V
    F_Z, M_YP, F_Y, M_ZP = ch6.hub_loads(theta_bar, psi_bar)
    dq = sp.symbols("delta_theta delta_psi delta_h delta_alpha delta_v delta_chi")
    d_th, d_ps, d_h, d_al, d_v, d_ch = dq
    dW = (F_Z * (d_h + e_alpha * d_al + e_theta * d_th) + M_YP * (d_th + d_al)
          + F_Y * (-e_psi * d_ps - e_alpha * d_ch) + M_ZP * (d_ps + d_ch))
    Q = generalised_forces(dW, dq)
    assert Q[4] == 0 and sp.expand(Q[5] - (M_ZP - e_alpha * F_Y)) == 0
    Ma, Ca, Ka = second_order_matrices(Q, q)

    check_reduction_to_chapter8(M, C_v, K, Ma, Ca, Ka)

    P, W = slice(0, 2), slice(2, 6)
    inertia = sp.Matrix(inplane_inertia_formulas(M_P, S_psi_P, I_psi_P))
    pw = dict(rows=QP, cols=QWP)
    wp = dict(rows=QWP, cols=QP)
    ww = dict(rows=QWP, cols=QWP)
    eq = "8.13 with in-plane bending"

    def aero(name: str, mat: sp.Matrix, what: str, labels: dict) -> Output:
        return Output(name, mat, AERO_ARGS, what, "4.25, 8.26, 8.34 with in-plane bending",
                      **labels)

    outputs = [
        Output("Bs", M[P, W], (S_theta_P, I_theta_alpha_P, I_psi_chi_P),
               "Propeller structural mass coupling B_s (rows θ, ψ; columns h_P, α_P, v_P, χ_P).",
               eq, **pw),
        Output("Ds", C0[P, W], (I_Omega, Omega),
               "Propeller gyroscopic coupling D_s (rows θ, ψ; columns h_P, α_P, v_P, χ_P).",
               eq, **pw),
        Output("Fs", M[W, P], (S_theta_P, I_theta_alpha_P, I_psi_chi_P),
               "Wing-node structural mass coupling F_s (rows h_P, α_P, v_P, χ_P; columns θ, ψ).",
               eq, **wp),
        Output("Gs", M[W, W], (M_P, S_alpha_P, I_alpha_P, I_chi_P),
               "Wing-node added structural mass G_s (rows and columns h_P, α_P, v_P, χ_P).",
               eq, **ww),
        Output("Hs", C0[W, P], (I_Omega, Omega),
               "Wing-node gyroscopic coupling H_s (rows h_P, α_P, v_P, χ_P; columns θ, ψ).",
               eq, **wp),
        Output("Js", C0[W, W], (I_Omega, Omega),
               "Wing-node gyroscopic coupling of the node's own twist and in-plane slope J_s "
               "(rows and columns h_P, α_P, v_P, χ_P).", eq, **ww),
        aero("Ba", Ma[P, W], "Propeller aerodynamic mass B_a (rows θ, ψ; columns h_P, α_P, "
             "v_P, χ_P).", pw),
        aero("Da", Ca[P, W], "Propeller aerodynamic damping D_a (rows θ, ψ; columns h_P, α_P, "
             "v_P, χ_P).", pw),
        aero("Fa", Ka[P, W], "Propeller aerodynamic stiffness F_a (rows θ, ψ; columns h_P, "
             "α_P, v_P, χ_P).", pw),
        aero("P1", Ma[W, P], "Propeller loads on the wing node P_1 (rows h_P, α_P, v_P, χ_P; "
             "columns θ̈, ψ̈).", wp),
        aero("P2", Ma[W, W], "Propeller loads on the wing node P_2 (rows and columns h_P, α_P, "
             "v_P, χ_P; accelerations).", ww),
        aero("P3", Ca[W, P], "Propeller loads on the wing node P_3 (rows h_P, α_P, v_P, χ_P; "
             "columns θ̇, ψ̇).", wp),
        aero("P4", Ca[W, W], "Propeller loads on the wing node P_4 (rows and columns h_P, α_P, "
             "v_P, χ_P; rates).", ww),
        aero("P5", Ka[W, P], "Propeller loads on the wing node P_5 (rows h_P, α_P, v_P, χ_P; "
             "columns θ, ψ).", wp),
        aero("P6", Ka[W, W], "Propeller loads on the wing node P_6 (rows and columns h_P, α_P, "
             "v_P, χ_P; displacements).", ww),
        Output("inplane_inertia", inertia, (M_P, S_psi_P, I_psi_P, l_psi, a_P_b_P),
               "In-plane inertia parameters about the wing elastic axis [I_χ,P, I_ψχ,P] from "
               "those about the yaw pivot (verified on point masses).", "8.5, 8.6 in-plane",
               rows=("I_chi_P", "I_psi_chi_P"), cols=("value",)),
    ]
    return Derivation(
        module="prop_flexwing_inplane",
        title="Propeller on a flexible wing with in-plane bending (wing-node coupling)",
        source="derivations/prop_flexwing_inplane.py",
        equations="8.1–8.42 extended (issue 14)",
        doc=__doc__,
        params=PARAMS,
        outputs=outputs,
        blocks={
            "structure_blocks": ("Bs", "Ds", "Fs", "Gs", "Hs", "Js"),
            "aero_blocks": ("Ba", "Da", "Fa", "P1", "P2", "P3", "P4", "P5", "P6"),
        },
    )


def check_reduction_to_chapter8(M, C_v, K, Ma, Ca, Ka) -> None:
    """With v_P = χ_P = 0 every matrix must be chapter 8's (derivations/prop_flexwing.py)."""
    r = {o.name: o.matrix for o in ch8.derive().outputs}
    P, W = [0, 1], [2, 3]
    pairs = [
        ("As", M, P, P), ("Bs", M, P, W), ("Cs_viscous", C_v, P, P), ("Ds", C_v, P, W),
        ("Es", K, P, P), ("Fs", M, W, P), ("Gs", M, W, W), ("Hs", C_v, W, P),
        ("Aa", Ma, P, P), ("Ba", Ma, P, W), ("Ca", Ca, P, P), ("Da", Ca, P, W),
        ("Ea", Ka, P, P), ("Fa", Ka, P, W), ("P1", Ma, W, P), ("P2", Ma, W, W),
        ("P3", Ca, W, P), ("P4", Ca, W, W), ("P5", Ka, W, P), ("P6", Ka, W, W),
    ]
    for name, mine, rows, cols in pairs:
        diff = (mine.extract(rows, cols) - r[name]).applyfunc(sp.expand)
        if diff != sp.zeros(*diff.shape):
            raise AssertionError(f"in-plane → chapter 8 reduction fails for {name}: {diff}")
    if C_v.extract(W, W) != sp.zeros(2, 2):
        raise AssertionError("chapter 8 has no gyroscopic block on [h_P, α_P]")
