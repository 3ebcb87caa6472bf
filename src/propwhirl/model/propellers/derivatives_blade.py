"""Exact derivatives through the advance ratio: the Houbolt–Reed derivatives' ∂/∂μ and the
chain rule from a propeller's blade angle, zero-lift angle or rpm to the system.

At an operating point (V, Ω, M = V/a) the Houbolt–Reed derivatives (thesis eq. 4.39–4.42,
:mod:`propwhirl.model.propellers.propeller_aero`) depend on V and Ω only through the advance ratio
μ = V/(ΩR) (with M fixed): in η = r/R the blade integrals are

    I_n(μ) = N_b/(4 c0) · ∫_{η0}^{1} h_n dη,   h_n = μ^{p_n} η^{q_n} c g F(k) / s,
    s = sqrt(μ² + η²),   k = Ω c/(2U) = c/(2R s),   M_r² = min(M² (1 + η²/μ²), 1 − (a0/a_m)²),
    g = a/(2π) · 1/β · Aβ/(Aβ + 2),   β = sqrt(1 − M_r²)                          (4.18–4.24)

(J_n with G(k) for F(k)), and the derivatives C = ±{4, 2} f · {I_n, J_n} with f = Ωc0/V = c0/(μR).
The limits do not move with μ and the integrand is continuous where the cut-off starts (M_r²
is held there, not cut), so, exactly,

    ∂I_n/∂μ = N_b/(4 c0) ∫ h_n [p_n/μ − μ/s² + ∂ln g/∂μ] + μ^{p_n} η^{q_n} c g F'(k) ∂k/∂μ / s dη,
    ∂k/∂μ = −k μ/s²,   ∂ln g/∂μ = ∂β/∂μ (−1/β + 2/(β(Aβ + 2))),
    ∂β/∂μ = M² η²/(μ³ β) below the cut-off, 0 beyond it,
    ∂C/∂μ = C (∂X/∂μ / X − 1/μ)  (X the integral of C),

with F' + iG' = C'(k) = i (H0² + H1² − H0 H1/k)/(H1 + iH0)² (Hankel functions of the second
kind; H0' = −H1, H1' = H0 − H1/k) — evaluated by the same composite Gauss–Legendre rule in
t = asinh(η/μ) as the integrals themselves (so it is the exact derivative of the integral,
to the rule's accuracy, not of the rule's nodes).  Bennett–Bland (§4.2): ∂ tan δ/∂μ
= −(G'F − GF')/F² · ∂k_0.75/∂μ, ∂k_0.75/∂μ = −k_0.75 μ/(0.75² + μ²).

The chain to the model (:func:`chain`, for :mod:`propwhirl.model.derivatives`): fixed-pitch
windmilling has μ from the blade angle (eq. 9.1: μ = tan(β + α_0L), ∂μ/∂β = 1 + μ²; blade
element: μ = 0.75 tan(β − α_0L), ∂μ/∂β = 0.75 + μ²/0.75, ∂μ/∂α_0L = −∂μ/∂β) and Ω = V/(μR),
∂Ω/∂μ = −Ω/μ (the gyroscopic terms); constant speed has Ω = 2π rpm/60 and μ = V/(ΩR),
∂μ/∂rpm = −μ/rpm.  Angles in the fields are in degrees (∂/∂deg = π/180 ∂/∂rad).
"""
from __future__ import annotations

import math

import numpy as np
from scipy.special import hankel2e

from propwhirl.model.propellers.propeller import CROSS_DERIVATIVES, MeasuredDerivatives, Propeller
from propwhirl.model.propellers.propeller_aero import (
    TWO_PI,
    AeroSettings,
    HouboltReedSource,
    PropellerGeometry,
    houbolt_reed_source,
    panel_edges,
    quadrature_nodes,
)
from propwhirl.model.aerodynamics.theodorsen import theodorsen

_DEG = math.pi / 180.0


def theodorsen_derivative(k) -> np.ndarray:
    """C'(k) = dF/dk + i dG/dk of Theodorsen's function (k > 0), module docstring; the
    small- and large-k expansions of :func:`propwhirl.model.aerodynamics.theodorsen.theodorsen` are
    differentiated term by term where that function uses them."""
    k = np.asarray(k, dtype=float)
    out = np.empty(k.shape, dtype=complex)
    small, large = k < 1e-8, k > 1e4
    reg = ~(small | large)
    if reg.any():
        kr = k[reg]
        h0, h1 = hankel2e(0, kr), hankel2e(1, kr)
        out[reg] = 1j * (h0 * h0 + h1 * h1 - h0 * h1 / kr) / (h1 + 1j * h0) ** 2
    if small.any():
        ks = k[small]
        with np.errstate(divide="ignore"):
            out[small] = -0.5 * math.pi + 1j * (np.log(ks / 2.0) + 0.57721566490153286061 + 1.0)
    if large.any():
        inv = 1.0 / k[large]
        out[large] = -inv ** 3 / 8.0 + 1j * (inv ** 2 / 8.0 - 21.0 / 128.0 * inv ** 4)
    return out


def integrals_and_mu_derivatives(geometry: PropellerGeometry, settings: AeroSettings,
                                 mu: np.ndarray, mach: np.ndarray,
                                 wake: bool) -> tuple[dict, dict]:
    """({I1..J3}, {∂I1/∂μ..∂J3/∂μ}) at advance ratios μ and Mach numbers M (1-D arrays) —
    the integrals as ``propeller_aero._integrals`` computes them (same panels and rule) and
    their exact derivatives at fixed M (module docstring) [1/m]."""
    A = geometry.blade_aspect_ratio
    mr2_max = 1.0 - (TWO_PI / settings.cutoff_lift_slope) ** 2
    m2 = mach ** 2
    with np.errstate(divide="ignore"):
        cut_eta = np.where(m2 > 0, mu * np.sqrt(np.maximum(mr2_max / np.where(m2 > 0, m2, 1.0)
                                                           - 1.0, 0.0)), np.inf)
    mu_, m2_ = mu[:, None], m2[:, None]
    t, w = quadrature_nodes(np.arcsinh(panel_edges(geometry, cut_eta) / mu_),
                            settings.quadrature_order)
    eta = mu_ * np.sinh(t)
    chord = geometry.chord(eta)
    slope = 1.0 if geometry.lift_slope is None else geometry.lift_slope(eta) / TWO_PI
    raw = m2_ * (1.0 + eta ** 2 / mu_ ** 2)
    mr2 = np.minimum(raw, mr2_max)
    beta = np.sqrt(1.0 - mr2)
    dbeta = np.where(raw < mr2_max, m2_ * eta ** 2 / (mu_ ** 3 * beta), 0.0)   # ∂β/∂μ
    dlng = -1.0 / beta
    if settings.aspect_ratio_correction:
        arf = (A * beta) / (A * beta + 2.0)
        dlng = dlng + 2.0 / (beta * (A * beta + 2.0))
    else:
        arf = 1.0
    g = slope * (1.0 / beta) * arf
    s2 = mu_ ** 2 + eta ** 2
    base = w * chord * g                                  # weight · c g  (dt = dη/s)
    if wake:
        k = chord / (2.0 * geometry.radius * np.sqrt(s2))
        C, dC = theodorsen(k), theodorsen_derivative(k) * (-k * mu_ / s2)   # ∂C/∂μ via k
    else:
        C, dC = np.ones_like(eta, dtype=complex), np.zeros_like(eta, dtype=complex)
    common = dlng * dbeta - mu_ / s2                      # ∂ln(g / s)/∂μ
    scale = geometry.n_blades / 4.0 / geometry.c0
    values, derivs = {}, {}
    for n, (p, q) in enumerate(((2, 0), (1, 2), (0, 4)), start=1):
        eq = eta ** q
        for name, part in ((f"I{n}", np.real), (f"J{n}", np.imag)):
            if name.startswith("J") and not wake:
                values[name] = derivs[name] = np.zeros_like(mu)
                continue
            X = part(C)
            S = np.sum(base * eq * X, axis=1)
            dS = np.sum(base * eq * (X * common + part(dC)), axis=1)
            values[name] = scale * mu ** p * S
            derivs[name] = scale * (p * mu ** (p - 1) * S + mu ** p * dS) if p else scale * dS
    return values, derivs


#: each derivative as (coefficient, integral) of C = coefficient · f · integral, f = Ωc0/V
#: (eq. 4.39 and 4.27 with the thesis's C_nq sign); "rodden_rose" flips C_mr and C_nq.
_TERMS = dict(
    CZ_theta=(-4, "I1"), CZ_psi=(-4, "J1"), CZ_q=(4, "J2"), CZ_r=(-4, "I2"),
    Cm_theta=(-2, "J2"), Cm_psi=(2, "I2"), Cm_q=(-2, "I3"), Cm_r=(-2, "J3"),
    CY_theta=(-4, "J1"), CY_psi=(4, "I1"), CY_q=(-4, "I2"), CY_r=(-4, "J2"),
    Cn_theta=(-2, "I2"), Cn_psi=(-2, "J2"), Cn_q=(2, "J3"), Cn_r=(-2, "I3"),
)


def derivatives_and_mu_derivatives(geometry: PropellerGeometry, settings: AeroSettings,
                                   V, omega, mach) -> tuple[dict, dict]:
    """({name: C}, {name: ∂C/∂μ at fixed M}) of the sixteen Houbolt–Reed derivatives at
    (V [m/s], Ω [rad/s], M) (1-D arrays of one length): the values as
    :func:`propwhirl.model.propellers.propeller_aero.derivatives` gives them (so the two can be compared)
    and their exact advance-ratio derivatives (module docstring)."""
    V, omega, mach = (np.asarray(x, dtype=float).ravel() for x in (V, omega, mach))
    mu = V / (omega * geometry.radius)
    bb = settings.method == "bennett_bland"
    use_m = mach if (settings.compressibility and not bb) else np.zeros_like(mach)
    with np.errstate(over="ignore", under="ignore", invalid="ignore", divide="ignore"):
        X, dX = integrals_and_mu_derivatives(geometry, settings, mu, use_m,
                                             wake=settings.wake and not bb)
    if bb:
        s2 = 0.5625 + mu ** 2
        k75 = geometry.chord(0.75) / (2.0 * geometry.radius * np.sqrt(s2))
        C, dC = theodorsen(k75), theodorsen_derivative(k75) * (-k75 * mu / s2)
        tan, dtan = -C.imag / C.real, -(dC.imag * C.real - C.imag * dC.real) / C.real ** 2
        for n in (1, 2):
            X[f"J{n}"], dX[f"J{n}"] = -X[f"I{n}"] * tan, -(dX[f"I{n}"] * tan + X[f"I{n}"] * dtan)
        X["J3"] = dX["J3"] = np.zeros_like(mu)
    f = omega * geometry.c0 / V
    values, derivs = {}, {}
    for name, (coef, integral) in _TERMS.items():
        if name in ("Cm_r", "Cn_q") and settings.cnq_sign != "thesis":
            coef = -coef
        if bb and name in ("CY_r", "CZ_q"):
            coef = 0
        values[name] = coef * f * X[integral]
        derivs[name] = coef * f * (dX[integral] - X[integral] / mu)    # ∂f/∂μ = −f/μ
    return values, derivs


# ----------------------------------------------------------------------------- the model
def parameters(prop: Propeller, aero: bool) -> list[tuple[str, float, str, str]]:
    """(field, value, unit, meaning) of propeller `prop`'s rotation parameters with exact
    derivatives: β_0.75 and α_0L for fixed pitch, rpm for constant speed; none when its
    aerodynamic derivatives come (`aero`: they are used) from a source other than
    Houbolt–Reed or measured (constant) values."""
    if aero and not (prop.derivatives is None
                     or isinstance(prop.derivatives, (HouboltReedSource, MeasuredDerivatives))):
        return []
    if prop.operation == "constant-speed":
        return [("rpm", float(prop.rpm), "rev/min", "rotational speed (constant speed)")]
    return [("beta_075_deg", float(prop.beta_075_deg), "deg",
             f"blade angle at 0.75 R (advance ratio {prop.advance_ratio:.6g})"),
            ("zero_lift_angle_deg", float(prop.zero_lift_angle_deg), "deg",
             "blade-section zero-lift angle")]


def advance_ratio_rates(prop: Propeller, name: str, V: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(∂μ/∂p, ∂Ω/∂p) at airspeeds V of the rotation parameter `name` (unsigned Ω [rad/s];
    module docstring), arrays over V."""
    V = np.asarray(V, dtype=float)
    omega = prop.rotational_speed(V)
    if name == "rpm":
        mu = V / (omega * prop.radius)
        return -mu / prop.rpm, omega / prop.rpm
    mu = prop.advance_ratio
    if prop.advance_rule == "thesis_eq_9_1":
        dmu = (1.0 + mu ** 2) * _DEG                      # μ = tan(β + α_0L)
    else:
        dmu = (0.75 + mu ** 2 / 0.75) * _DEG              # μ = 0.75 tan(β − α_0L)
        if name == "zero_lift_angle_deg":
            dmu = -dmu
    dmu = np.full(V.shape, dmu)
    return dmu, -omega / mu * dmu                         # Ω = V/(μR)


def chain(ctx, par) -> list[tuple[str, np.ndarray]]:
    """[(generated argument, ∂argument/∂p over the speeds)] of a rotation parameter of
    installation ``par.index`` (``ctx``: the derivatives' context of the model at V):
    the signed Ω of the gyroscopic terms and the sixteen aerodynamic derivatives."""
    model, j = ctx.model, par.index
    inst = model.propellers[j]
    prop = inst.propeller
    V = ctx.V
    dmu, dOmega = advance_ratio_rates(prop, par.name, V)
    out = []
    if model.rotating and ctx.omega is None and inst.spinning:
        out.append(("Omega", inst.sense * dOmega))
    if (not (model.propeller_aero and inst.has_aero and inst.spinning)
            or isinstance(prop.derivatives, MeasuredDerivatives)):
        return out
    source = prop.derivatives if prop.derivatives is not None else houbolt_reed_source(
        prop, prop.aero_settings)
    a = model.flight.speed_of_sound
    mach = V / a if a is not None else np.zeros_like(V)
    _, d = derivatives_and_mu_derivatives(source.geometry, source.settings, V,
                                          prop.rotational_speed(V), mach)
    flip = prop.derivatives is None and inst.sense == -1
    for name, x in d.items():
        sign = -1.0 if flip and name in CROSS_DERIVATIVES else 1.0
        out.append((name, sign * x * dmu))
    return out
