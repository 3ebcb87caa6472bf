"""Propeller on a flexible cantilever wing: propeller and wing-node coupling (thesis §8.1–8.2).

Degrees of freedom:  q_P = [θ, ψ] (propeller pitch and yaw about their pivots)  and
q_WP = [h_P, α_P] (vertical displacement, positive DOWN, and twist, positive nose UP, of the wing
node carrying the propeller), ordered here as q = [θ, ψ, h_P, α_P].

Chapter-8 convention: every chordwise distance is SIGNED, positive REARWARD, measured from the
wing mid-chord: x along the shaft, l_θ, l_ψ the pitch/yaw pivots, a_P b_P the elastic axis,
e_θ = x_hub − l_θ and e_ψ = x_hub − l_ψ the pivot-to-propeller-plane distances (negative for a
tractor propeller ahead of its pivot), e_α = x_hub − a_P b_P = e_θ + l_θ − a_P b_P (8.35).

Structure.  The pivoting mass is point masses m_i on the shaft axis (8.2–8.3):
  z_i = h_P + (x_i − a_P b_P) α_P + (x_i − l_θ) θ,   y_i = −(x_i − l_ψ) ψ,
so T_P = ½ Σ m_i (ż_i² + ẏ_i²) is (8.4) with M_P = Σ m_i, S_θ,P = Σ m_i (x_i − l_θ),
I_θ,P = Σ m_i (x_i − l_θ)², I_ψ,P = Σ m_i (x_i − l_ψ)², S_α,P, I_α,P, I_θα,P as in (8.5–8.6);
the derivation checks (8.4)–(8.6) on generic point masses, then uses the inertia parameters as
symbols.  (Only the translational energy of masses on the axis is counted, as in the thesis:
the rotor's diametral inertia is not part of T_P.)  The rotor adds T_Ω = ½ I_Ω ω_X² with
ω_X = Ω + (θ̇ + α̇_P) sin ψ (8.7), kept exact and linearised after Lagrange's equations.
U = ½(K_θ θ² + K_ψ ψ²) (8.9); D (8.11) in the two readings of chapter 6: hysteretic K g/ω, or
the viscous equivalent 2 ζ_θ ω_θ I_θ,P with ω_θ = √(K_θ/I_θ,P), ω_ψ = √(K_ψ/I_ψ,P) (8.10).
Lagrange's equations (5.1) give (8.13), sorted into A_s, B_s, C_s, D_s, E_s (8.15–8.19, rows θ, ψ)
and F_s, G_s, H_s (8.21–8.23, rows h_P, α_P; the wing's own terms "…" come from the beam model).

Aerodynamics.  The hub loads (4.25) act at the hub, displaced by
  δz_hub = δh_P + e_α δα_P + e_θ δθ,   δy_hub = −e_ψ δψ,
with the propeller pitched by θ + α_P; the effective angles are the pitch/yaw plus the hub's
transverse velocity over V:  θ̄ = θ + α_P + ż_hub/V,  ψ̄ = ψ − ẏ_hub/V, which is (8.26).  The
virtual work
  δW = F_Z (δh_P + e_α δα_P + e_θ δθ) + M_Y,P (δθ + δα_P) − e_ψ F_Y δψ + M_Z,P δψ
gives Q_θ,P = M_Y,P + e_θ F_Z, Q_ψ,P = M_Z,P − e_ψ F_Y (8.25) and Q_h,P = F_Z,
Q_α,P = M_Y,P + e_α F_Z (8.34); their Jacobians are A_a … F_a (8.28–8.33) and P_1 … P_6
(8.37–8.42).  The sixteen derivatives are independent symbols (4.27 not imposed).  e_α is an
argument of its own; `e_alpha_geometry` evaluates (8.35) and the caller passes the result.
With h_P = α_P = 0 the propeller rows reduce to chapter 6 with e_θ(ch.6) = −e_θ(ch.8).
"""
from __future__ import annotations

import sympy as sp

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

DOFS = ("theta", "psi", "h_P", "alpha_P")
QP = DOFS[:2]
QWP = DOFS[2:]

I_Omega = sp.Symbol("I_Omega", positive=True)
M_P = sp.Symbol("M_P", positive=True)
I_theta_P, I_psi_P, I_alpha_P = sp.symbols("I_theta_P I_psi_P I_alpha_P", positive=True)
S_theta_P, S_alpha_P, I_theta_alpha_P = sp.symbols("S_theta_P S_alpha_P I_theta_alpha_P",
                                                   real=True)
l_theta, a_P_b_P, e_alpha = sp.symbols("l_theta a_P_b_P e_alpha", real=True)
Omega, K_theta, K_psi = ch6.Omega, ch6.K_theta, ch6.K_psi
g_theta, g_psi, omega, zeta_theta, zeta_psi = (ch6.g_theta, ch6.g_psi, ch6.omega,
                                               ch6.zeta_theta, ch6.zeta_psi)
rho, V, R = ch6.rho, ch6.V, ch6.R
e_theta, e_psi = ch6.e_theta, ch6.e_psi
DERIVATIVES = ch6.DERIVATIVES

_ch6_params = {p.symbol: p for p in ch6.PARAMS}

PARAMS = (
    Param(I_Omega, "rotor mass moment of inertia about its rotation axis", "kg m^2"),
    Param(M_P, "pivoting propeller–engine mass", "kg"),
    Param(S_theta_P, "static moment of the pivoting mass about the pitch pivot, Σ m (x − l_θ)",
          "kg m"),
    Param(I_theta_P, "moment of inertia of the pivoting mass about the pitch pivot", "kg m^2"),
    Param(I_psi_P, "moment of inertia of the pivoting mass about the yaw pivot", "kg m^2"),
    Param(S_alpha_P, "static moment of the pivoting mass about the wing elastic axis", "kg m"),
    Param(I_alpha_P, "moment of inertia of the pivoting mass about the wing elastic axis",
          "kg m^2"),
    Param(I_theta_alpha_P, "product of inertia Σ m (x − a_P b_P)(x − l_θ)", "kg m^2"),
    Param(l_theta, "pitch pivot position aft of the wing mid-chord (signed)", "m"),
    Param(a_P_b_P, "wing elastic-axis position aft of mid-chord at the propeller node (signed)",
          "m"),
    Param(e_theta, "propeller plane aft of the pitch pivot (signed; < 0 for a tractor)", "m"),
    Param(e_psi, "propeller plane aft of the yaw pivot (signed; < 0 for a tractor)", "m"),
    Param(e_alpha, "propeller plane aft of the wing elastic axis, e_θ + l_θ − a_P b_P (8.35)",
          "m"),
    *(_ch6_params[s] for s in (Omega, K_theta, K_psi, g_theta, g_psi, omega, zeta_theta,
                               zeta_psi, rho, V, R)),
    *(_ch6_params[s] for s in DERIVATIVES),
)

AERO_ARGS = (rho, V, R, e_theta, e_psi, e_alpha, *DERIVATIVES)


def check_point_mass_inertia(n: int = 3) -> None:
    """Verify (8.4)–(8.6) for n generic point masses on the shaft axis (raises if not)."""
    m = sp.symbols(f"m0:{n}", positive=True)
    x = sp.symbols(f"x0:{n}", real=True)
    l_psi = sp.Symbol("l_psi", real=True)
    th, ps, h, al = sp.symbols("thd psd hd ald", real=True)  # rates
    ab, l = a_P_b_P, l_theta
    # Kinetic energy of the point masses (8.2)–(8.3), rates as plain symbols.
    T_pts = sum(
        mi * ((h + (xi - ab) * al + (xi - l) * th) ** 2 + ((xi - l_psi) * ps) ** 2) / 2
        for mi, xi in zip(m, x)
    )
    Mp = sum(m)
    S_th = sum(mi * (xi - l) for mi, xi in zip(m, x))
    I_th = sum(mi * (xi - l) ** 2 for mi, xi in zip(m, x))
    I_ps = sum(mi * (xi - l_psi) ** 2 for mi, xi in zip(m, x))
    S_al = sum(mi * (xi - ab) for mi, xi in zip(m, x))  # (8.5) integrals
    I_al = sum(mi * (xi - ab) ** 2 for mi, xi in zip(m, x))
    I_ta = sum(mi * (xi - ab) * (xi - l) for mi, xi in zip(m, x))  # (8.6)
    T_84 = (Mp * h**2 / 2 + I_al * al**2 / 2 + I_th * th**2 / 2 + S_al * h * al
            + S_th * h * th + I_ta * al * th + I_ps * ps**2 / 2)
    if sp.expand(T_pts - T_84) != 0:
        raise AssertionError("point-mass kinetic energy differs from (8.4)")
    S_al_f, I_al_f, I_ta_f = inertia_formulas(Mp, S_th, I_th)
    for integral, formula, name in ((S_al, S_al_f, "S_alpha"), (I_al, I_al_f, "I_alpha"),
                                    (I_ta, I_ta_f, "I_theta_alpha")):
        if sp.expand(integral - formula) != 0:
            raise AssertionError(f"printed identity for {name} (8.5–8.6) fails")


def inertia_formulas(Mp: sp.Expr, S_th: sp.Expr, I_th: sp.Expr):
    """(S_α,P, I_α,P, I_θα,P) from (M_P, S_θ,P, I_θ,P) by the identities printed in (8.5)–(8.6)."""
    d = l_theta - a_P_b_P
    return (S_th + d * Mp, I_th + d**2 * Mp + 2 * d * S_th, I_th + d * S_th)


def derive() -> Derivation:
    check_point_mass_inertia()
    q = coordinates(DOFS)
    theta, psi, h, alpha = q
    thd, psd, hd, ald = (sp.diff(c, t) for c in q)

    # Kinetic energy (8.4) + (8.7), potential energy (8.9), dissipation (8.11) / viscous (8.10).
    T_P = (M_P * hd**2 / 2 + I_alpha_P * ald**2 / 2 + I_theta_P * thd**2 / 2
           + S_alpha_P * hd * ald + S_theta_P * hd * thd + I_theta_alpha_P * ald * thd
           + I_psi_P * psd**2 / 2)
    wX = Omega + (thd + ald) * sp.sin(psi)
    T = T_P + I_Omega * wX**2 / 2
    U = (K_theta * theta**2 + K_psi * psi**2) / 2
    D_hyst = (K_theta * g_theta / omega * thd**2 + K_psi * g_psi / omega * psd**2) / 2
    c_theta = 2 * zeta_theta * sp.sqrt(K_theta / I_theta_P) * I_theta_P
    c_psi = 2 * zeta_psi * sp.sqrt(K_psi / I_psi_P) * I_psi_P
    D_visc = (c_theta * thd**2 + c_psi * psd**2) / 2

    M, C0, K = second_order_matrices(lagrange_lhs(T, U, 0, q), q)
    _, C_h, _ = second_order_matrices(lagrange_lhs(T, U, D_hyst, q), q)
    _, C_v, _ = second_order_matrices(lagrange_lhs(T, U, D_visc, q), q)
    # The propeller adds no stiffness or damping to the wing node (8.13): those come from the
    # beam model; nor does the wing stiffness couple into the propeller rows.
    assert K[:, 2:] == sp.zeros(4, 2) and K[2:, :] == sp.zeros(2, 4)
    assert C_h[2:, 2:] == sp.zeros(2, 2) and C_h[2:, :2] == C0[2:, :2]
    assert C0 + C0.T == sp.zeros(4, 4)  # pure gyroscopic
    assert M == M.T

    # Aerodynamics: hub kinematics → effective angles (8.26), hub loads (4.25), virtual work.
    z_hub = h + e_alpha * alpha + e_theta * theta
    y_hub = -e_psi * psi
    theta_bar = theta + alpha + sp.diff(z_hub, t) / V
    psi_bar = psi - sp.diff(y_hub, t) / V
    assert sp.expand(theta_bar - (theta + alpha + e_theta / V * thd + e_alpha / V * ald
                                  + hd / V)) == 0
    assert sp.expand(psi_bar - (psi + e_psi / V * psd)) == 0
    F_Z, M_YP, F_Y, M_ZP = ch6.hub_loads(theta_bar, psi_bar)
    dq = sp.symbols("delta_theta delta_psi delta_h delta_alpha")
    d_th, d_ps, d_h, d_al = dq
    dW = (F_Z * (d_h + e_alpha * d_al + e_theta * d_th) + M_YP * (d_th + d_al)
          + F_Y * (-e_psi * d_ps) + M_ZP * d_ps)
    Q = generalised_forces(dW, dq)
    for Qi, printed in zip(Q, (M_YP + e_theta * F_Z, M_ZP - e_psi * F_Y, F_Z,
                               M_YP + e_alpha * F_Z)):  # (8.25), (8.34)
        assert sp.expand(Qi - printed) == 0
    Ma, Ca, Ka = second_order_matrices(Q, q)

    check_reduction_to_chapter6(M, C_h, C_v, K, Ma, Ca, Ka)

    P, W = slice(0, 2), slice(2, 4)
    e_alpha_geo = sp.Matrix([[e_theta + l_theta - a_P_b_P]])
    inertia = sp.Matrix(inertia_formulas(M_P, S_theta_P, I_theta_P))

    hyst = (I_Omega, Omega, K_theta, K_psi, g_theta, g_psi, omega)
    visc = (I_Omega, Omega, I_theta_P, I_psi_P, K_theta, K_psi, zeta_theta, zeta_psi)
    pp = dict(rows=QP, cols=QP)
    pw = dict(rows=QP, cols=QWP)
    wp = dict(rows=QWP, cols=QP)
    ww = dict(rows=QWP, cols=QWP)

    def aero(name: str, mat: sp.Matrix, what: str, eq: str, labels: dict) -> Output:
        return Output(name, mat, AERO_ARGS, what, f"4.25, 8.26, {eq}", **labels)

    outputs = [
        Output("As", M[P, P], (I_theta_P, I_psi_P),
               "Propeller structural mass A_s (rows θ, ψ; columns θ, ψ).", "8.13, 8.15", **pp),
        Output("Bs", M[P, W], (S_theta_P, I_theta_alpha_P),
               "Propeller structural mass coupling B_s (rows θ, ψ; columns h_P, α_P).",
               "8.13, 8.16", **pw),
        Output("Cs_hysteretic", C_h[P, P], hyst,
               "Propeller structural damping C_s (rows θ, ψ; columns θ, ψ), hysteretic K g/ω, "
               "including the gyroscopic terms ±I_Ω Ω.", "8.11, 8.13, 8.17", **pp),
        Output("Cs_viscous", C_v[P, P], visc,
               "Propeller structural damping C_s (rows θ, ψ; columns θ, ψ), viscous equivalent "
               "2ζ_θ ω_θ I_θ,P, ω_θ = √(K_θ/I_θ,P) (and likewise in yaw), including the "
               "gyroscopic terms ±I_Ω Ω.", "8.10, 8.13, 8.17", **pp),
        Output("Ds", C0[P, W], (I_Omega, Omega),
               "Propeller gyroscopic coupling D_s to the wing twist rate (rows θ, ψ; columns "
               "h_P, α_P).", "8.13, 8.18", **pw),
        Output("Es", K[P, P], (K_theta, K_psi),
               "Propeller structural stiffness E_s (rows θ, ψ; columns θ, ψ).", "8.13, 8.19",
               **pp),
        Output("Fs", M[W, P], (S_theta_P, I_theta_alpha_P),
               "Wing-node structural mass coupling F_s (rows h_P, α_P; columns θ, ψ).",
               "8.13, 8.21", **wp),
        Output("Gs", M[W, W], (M_P, S_alpha_P, I_alpha_P),
               "Wing-node added structural mass G_s (rows h_P, α_P; columns h_P, α_P).",
               "8.13, 8.22", **ww),
        Output("Hs", C0[W, P], (I_Omega, Omega),
               "Wing-node gyroscopic coupling H_s (rows h_P, α_P; columns θ, ψ).",
               "8.13, 8.23", **wp),
        aero("Aa", Ma[P, P], "Propeller aerodynamic mass A_a (rows θ, ψ; columns θ, ψ).",
             "8.25, 8.28", pp),
        aero("Ba", Ma[P, W], "Propeller aerodynamic mass B_a (rows θ, ψ; columns h_P, α_P).",
             "8.25, 8.29", pw),
        aero("Ca", Ca[P, P], "Propeller aerodynamic damping C_a (rows θ, ψ; columns θ, ψ).",
             "8.25, 8.30", pp),
        aero("Da", Ca[P, W],
             "Propeller aerodynamic damping D_a (rows θ, ψ; columns h_P, α_P).", "8.25, 8.31",
             pw),
        aero("Ea", Ka[P, P], "Propeller aerodynamic stiffness E_a (rows θ, ψ; columns θ, ψ).",
             "8.25, 8.32", pp),
        aero("Fa", Ka[P, W],
             "Propeller aerodynamic stiffness F_a (rows θ, ψ; columns h_P, α_P).", "8.25, 8.33",
             pw),
        aero("P1", Ma[W, P], "Propeller loads on the wing node P_1 (rows h_P, α_P; columns "
             "θ̈, ψ̈).", "8.34, 8.37", wp),
        aero("P2", Ma[W, W], "Propeller loads on the wing node P_2 (rows h_P, α_P; columns "
             "ḧ_P, α̈_P).", "8.34, 8.38", ww),
        aero("P3", Ca[W, P], "Propeller loads on the wing node P_3 (rows h_P, α_P; columns "
             "θ̇, ψ̇).", "8.34, 8.39", wp),
        aero("P4", Ca[W, W], "Propeller loads on the wing node P_4 (rows h_P, α_P; columns "
             "ḣ_P, α̇_P).", "8.34, 8.40", ww),
        aero("P5", Ka[W, P], "Propeller loads on the wing node P_5 (rows h_P, α_P; columns "
             "θ, ψ).", "8.34, 8.41", wp),
        aero("P6", Ka[W, W], "Propeller loads on the wing node P_6 (rows h_P, α_P; columns "
             "h_P, α_P).", "8.34, 8.42", ww),
        Output("e_alpha_geometry", e_alpha_geo, (e_theta, l_theta, a_P_b_P),
               "Propeller plane aft of the wing elastic axis, e_α = e_θ + l_θ − a_P b_P "
               "(signed, positive rearward) [m].", "8.35", rows=("e_alpha",), cols=("value",)),
        Output("inertia", inertia, (M_P, S_theta_P, I_theta_P, l_theta, a_P_b_P),
               "Inertia parameters about the wing elastic axis [S_α,P, I_α,P, I_θα,P] from "
               "those about the pitch pivot (identities verified on point masses).",
               "8.5, 8.6", rows=("S_alpha_P", "I_alpha_P", "I_theta_alpha_P"),
               cols=("value",)),
    ]
    return Derivation(
        module="prop_flexwing",
        title="Propeller on a flexible wing (propeller rows and wing-node coupling)",
        source="derivations/prop_flexwing.py",
        equations="8.1–8.42",
        doc=__doc__,
        params=PARAMS,
        outputs=outputs,
        blocks={
            "structure_blocks": ("As", "Bs", "Cs_viscous", "Ds", "Es", "Fs", "Gs", "Hs"),
            "aero_blocks": ("Aa", "Ba", "Ca", "Da", "Ea", "Fa", "P1", "P2", "P3", "P4", "P5", "P6"),
        },
    )


def check_reduction_to_chapter6(M, C_h, C_v, K, Ma, Ca, Ka) -> None:
    """With h_P = α_P = 0 the propeller rows must be chapter 6 with e(ch.6) = −e(ch.8)."""
    r = ch6.derive()
    mats = {o.name: o.matrix for o in r.outputs}
    same = {ch6.I_X: I_Omega, ch6.I_Y: I_theta_P, ch6.I_Z: I_psi_P,
            ch6.e_theta: -e_theta, ch6.e_psi: -e_psi}
    pairs = [("Ms", M), ("Cs_hysteretic", C_h), ("Cs_viscous", C_v), ("Ks", K),
             ("Ma", Ma), ("Ca", Ca), ("Ka", Ka)]
    for name, mine in pairs:
        diff = (mats[name].subs(same, simultaneous=True) - mine[:2, :2]).applyfunc(sp.expand)
        if diff != sp.zeros(2, 2):
            raise AssertionError(f"chapter 8 → chapter 6 reduction fails for {name}: {diff}")
