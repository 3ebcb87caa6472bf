"""Propeller flexibly mounted on a rigid wing: pitch–yaw whirl model (thesis chapter 6, §6.1).

Degrees of freedom (6.11):  q = [θ, ψ]
  θ  pitch of the propeller–nacelle about the pitch pivot                           [rad]
  ψ  yaw of the propeller–nacelle about the yaw pivot                               [rad]

Chapter-6 convention: e_θ, e_ψ > 0 are the DISTANCES from the pitch/yaw pivot forward to the
propeller plane (hub ahead of the pivot).  (Chapter 8 uses signed, rearward-positive distances,
so e_θ(ch.8) = −e_θ(ch.6); see derivations/prop_flexwing.py.)

Structure.  With the angular velocities (6.1)  ω_X = Ω + θ̇ sin ψ, ω_Y = θ̇ cos ψ, ω_Z = ψ̇,
the kinetic energy T = ½(I_X ω_X² + I_Y ω_Y² + I_Z ω_Z²) (6.2) — kept exact here and linearised
only after Lagrange's equations (5.1), so the gyroscopic coupling I_X Ω (ψ̇, −θ̇) of (6.8) comes
out of the derivation — the strain energy U = ½(K_θ θ² + K_ψ ψ²) (6.3) and a dissipation function
D in two readings:
  hysteretic (6.7)         D = ½ (K_θ g_θ/ω) θ̇² + ½ (K_ψ g_ψ/ω) ψ̇²,  ω the oscillation frequency;
  viscous equivalent (6.6) K_θ g_θ/ω → 2 ζ_θ ω_θ I_Y with ω_θ = √(K_θ/I_Y), ω_ψ = √(K_ψ/I_Z).
Lagrange's equations give M_s q̈ + C_s q̇ + K_s q (6.10, 6.12–6.14); G = I_X Ω [[0, 1], [−1, 0]]
is the gyroscopic part of C_s alone.

Aerodynamics.  The hub loads (4.25), with k1 = ½ρV²S', k2 = ρV²S'R, S' = πR²,
  F_Z   = k1 (C_Zθ θ̄ + C_Zψ ψ̄ + C_Zq θ̄̇ R/V + C_Zr ψ̄̇ R/V),   M_Y,P = k2 (C_mθ θ̄ + … ),
  F_Y   = k1 (C_Yθ θ̄ + … ),                                    M_Z,P = k2 (C_nθ θ̄ + … ),
use the effective angles (4.26)  θ̄ = θ − e_θ θ̇/V,  ψ̄ = ψ − e_ψ ψ̇/V; the rate terms use the
derivatives of the effective angles, which is where the aerodynamic mass terms (6.15) come
from.  All sixteen derivatives stay independent symbols: the symmetry relations (4.27) are
NOT imposed, so any measured subset may be supplied (unknown ones as zero).  The hub moves by
δz = −e_θ δθ, δy = +e_ψ δψ, so the virtual work
  δW = M_Y,P δθ − e_θ F_Z δθ + M_Z,P δψ + e_ψ F_Y δψ
gives the pivot moments Q_θ = M_Y = M_Y,P − e_θ F_Z and Q_ψ = M_Z = M_Z,P + e_ψ F_Y (6.9), and
Q = M_a q̈ + C_a q̇ + K_a q (6.15–6.17).
"""
from __future__ import annotations

import sympy as sp

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

DOFS = ("theta", "psi")

I_X, I_Y, I_Z = sp.symbols("I_X I_Y I_Z", positive=True)
K_theta, K_psi = sp.symbols("K_theta K_psi", positive=True)
Omega = sp.Symbol("Omega", real=True)
g_theta, g_psi, zeta_theta, zeta_psi = sp.symbols("g_theta g_psi zeta_theta zeta_psi", real=True)
omega = sp.Symbol("omega", positive=True)
rho, V, R = sp.symbols("rho V R", positive=True)
e_theta, e_psi = sp.symbols("e_theta e_psi", real=True)

#: The sixteen propeller aerodynamic derivatives of (4.25), in the order printed there.
DERIVATIVE_NAMES = tuple(
    f"{c}_{v}" for c in ("CZ", "Cm", "CY", "Cn") for v in ("theta", "psi", "q", "r")
)
DERIVATIVES = sp.symbols(" ".join(DERIVATIVE_NAMES), real=True)
D = dict(zip(DERIVATIVE_NAMES, DERIVATIVES))

_DERIVATIVE_DOCS = {
    "CZ": "vertical force F_Z",
    "Cm": "pitching moment M_Y,P",
    "CY": "side force F_Y",
    "Cn": "yawing moment M_Z,P",
}
_VAR_DOCS = {
    "theta": ("effective pitch angle θ̄", "1/rad"),
    "psi": ("effective yaw angle ψ̄", "1/rad"),
    "q": ("pitch rate θ̄̇R/V", "1/rad"),
    "r": ("yaw rate ψ̄̇R/V", "1/rad"),
}

PARAMS = (
    Param(I_X, "propeller mass moment of inertia about its rotation axis", "kg m^2"),
    Param(I_Y, "mass moment of inertia of the pivoting system about the pitch axis", "kg m^2"),
    Param(I_Z, "mass moment of inertia of the pivoting system about the yaw axis", "kg m^2"),
    Param(Omega, "propeller rotational speed", "rad/s"),
    Param(K_theta, "pitch stiffness of the propeller attachment", "N m/rad"),
    Param(K_psi, "yaw stiffness of the propeller attachment", "N m/rad"),
    Param(g_theta, "hysteretic (structural) damping coefficient in pitch", "-"),
    Param(g_psi, "hysteretic (structural) damping coefficient in yaw", "-"),
    Param(omega, "oscillation frequency at which hysteretic damping is evaluated", "rad/s"),
    Param(zeta_theta, "viscous damping ratio in pitch (fraction of critical)", "-"),
    Param(zeta_psi, "viscous damping ratio in yaw (fraction of critical)", "-"),
    Param(rho, "air density", "kg/m^3"),
    Param(V, "free-stream (inflow) velocity", "m/s"),
    Param(R, "propeller radius", "m"),
    Param(e_theta, "distance from the pitch pivot forward to the propeller plane (> 0)", "m"),
    Param(e_psi, "distance from the yaw pivot forward to the propeller plane (> 0)", "m"),
    *(
        Param(
            D[n],
            f"propeller derivative of {_DERIVATIVE_DOCS[n.split('_')[0]]} w.r.t. the "
            f"{_VAR_DOCS[n.split('_')[1]][0]}",
            _VAR_DOCS[n.split("_")[1]][1],
        )
        for n in DERIVATIVE_NAMES
    ),
)

AERO_ARGS = (rho, V, R, e_theta, e_psi, *DERIVATIVES)


def hub_loads(theta_bar: sp.Expr, psi_bar: sp.Expr) -> tuple[sp.Expr, sp.Expr, sp.Expr, sp.Expr]:
    """(F_Z, M_Y,P, F_Y, M_Z,P) of (4.25) for given effective angles (functions of t)."""
    S = sp.pi * R**2
    k1 = rho * V**2 * S / 2
    k2 = rho * V**2 * S * R
    tb_rate = sp.diff(theta_bar, t) * R / V
    pb_rate = sp.diff(psi_bar, t) * R / V

    def combo(c: str) -> sp.Expr:
        return (
            D[f"{c}_theta"] * theta_bar
            + D[f"{c}_psi"] * psi_bar
            + D[f"{c}_q"] * tb_rate
            + D[f"{c}_r"] * pb_rate
        )

    return k1 * combo("CZ"), k2 * combo("Cm"), k1 * combo("CY"), k2 * combo("Cn")


def structural(T: sp.Expr, U: sp.Expr, D_fn: sp.Expr, q) -> tuple[sp.Matrix, sp.Matrix, sp.Matrix]:
    return second_order_matrices(lagrange_lhs(T, U, D_fn, q), q)


def derive() -> Derivation:
    q = coordinates(DOFS)
    theta, psi = q
    thd, psd = sp.diff(theta, t), sp.diff(psi, t)

    # Kinetic energy (6.1)–(6.2) with the exact angular velocities; potential energy (6.3).
    wX = Omega + thd * sp.sin(psi)
    wY = thd * sp.cos(psi)
    wZ = psd
    T = (I_X * wX**2 + I_Y * wY**2 + I_Z * wZ**2) / 2
    U = (K_theta * theta**2 + K_psi * psi**2) / 2

    # Dissipation: hysteretic (6.7) and its viscous equivalent (6.6).
    D_hyst = (K_theta * g_theta / omega * thd**2 + K_psi * g_psi / omega * psd**2) / 2
    w_theta, w_psi = sp.sqrt(K_theta / I_Y), sp.sqrt(K_psi / I_Z)
    D_visc = (2 * zeta_theta * w_theta * I_Y * thd**2 + 2 * zeta_psi * w_psi * I_Z * psd**2) / 2

    Ms, C0, Ks = structural(T, U, 0, q)
    _, Cs_h, Ks_h = structural(T, U, D_hyst, q)
    _, Cs_v, Ks_v = structural(T, U, D_visc, q)
    assert Ks_h == Ks and Ks_v == Ks
    G = C0
    assert G == I_X * Omega * sp.Matrix([[0, 1], [-1, 0]]), G
    assert Ms == sp.diag(I_Y, I_Z) and Ks == sp.diag(K_theta, K_psi)

    # Aerodynamics: effective angles (4.26), hub loads (4.25), virtual work → (6.9).
    theta_bar = theta - e_theta * thd / V
    psi_bar = psi - e_psi * psd / V
    F_Z, M_YP, F_Y, M_ZP = hub_loads(theta_bar, psi_bar)
    d_theta, d_psi = sp.symbols("delta_theta delta_psi")
    dW = M_YP * d_theta + F_Z * (-e_theta * d_theta) + M_ZP * d_psi + F_Y * (e_psi * d_psi)
    Q = generalised_forces(dW, (d_theta, d_psi))
    assert sp.expand(Q[0] - (M_YP - e_theta * F_Z)) == 0  # (6.9)
    assert sp.expand(Q[1] - (M_ZP + e_psi * F_Y)) == 0
    Ma, Ca, Ka = second_order_matrices(Q, q)

    sdofs = dict(rows=DOFS, cols=DOFS)
    return Derivation(
        module="prop_rigid",
        title="Propeller on a rigid wing (pitch–yaw whirl)",
        source="derivations/prop_rigid.py",
        equations="6.1–6.17",
        doc=__doc__,
        params=PARAMS,
        outputs=[
            Output("Ms", Ms, (I_Y, I_Z), "Structural mass matrix M_s [θ, ψ].", "6.12", **sdofs),
            Output(
                "Cs_hysteretic",
                Cs_h,
                (I_X, Omega, K_theta, K_psi, g_theta, g_psi, omega),
                "Structural damping matrix C_s [θ, ψ] with hysteretic damping K g/ω "
                "(includes the gyroscopic part G).",
                "6.7, 6.8, 6.13",
                **sdofs,
            ),
            Output(
                "Cs_viscous",
                Cs_v,
                (I_X, Omega, I_Y, I_Z, K_theta, K_psi, zeta_theta, zeta_psi),
                "Structural damping matrix C_s [θ, ψ] with the viscous equivalent "
                "2ζ_θ ω_θ I_Y, ω_θ = √(K_θ/I_Y), 2ζ_ψ ω_ψ I_Z, ω_ψ = √(K_ψ/I_Z) "
                "(includes the gyroscopic part G).",
                "6.6, 6.8, 6.13",
                **sdofs,
            ),
            Output("Ks", Ks, (K_theta, K_psi), "Structural stiffness matrix K_s [θ, ψ].",
                   "6.14", **sdofs),
            Output(
                "G",
                G,
                (I_X, Omega),
                "Gyroscopic matrix alone, I_X Ω [[0, 1], [−1, 0]] (skew-symmetric part of C_s).",
                "6.8",
                **sdofs,
            ),
            Output("Ma", Ma, AERO_ARGS, "Propeller aerodynamic mass matrix M_a [θ, ψ].",
                   "4.25, 4.26, 6.9, 6.15", **sdofs),
            Output("Ca", Ca, AERO_ARGS, "Propeller aerodynamic damping matrix C_a [θ, ψ].",
                   "4.25, 4.26, 6.9, 6.16", **sdofs),
            Output("Ka", Ka, AERO_ARGS, "Propeller aerodynamic stiffness matrix K_a [θ, ψ].",
                   "4.25, 4.26, 6.9, 6.17", **sdofs),
        ],
        blocks={
            "structure_blocks": ("Ms", "Cs_viscous", "Ks"),
            "aero_blocks": ("Ma", "Ca", "Ka"),
        },
    )
