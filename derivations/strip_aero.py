"""Strip aerodynamics of a wing section: Theodorsen loads in the time domain (thesis §7.2, §7.5).

Section loads per unit span of a thin aerofoil, semichord b, elastic axis at a semichords aft of
mid-chord, in the modified strip analysis of Yates (7.64–7.66):

    L = πρb²(ḧ + Vα̇ − baα̈) + C_lα ρ V b C(k) w
    M = πρb²[ab ḧ − Vb d α̇ − b²(1/8 + a²) α̈] + C_lα ρ V b² (a − a_c) C(k) w
    w = ḣ + Vα + b d α̇,        d = C_lα/(2π) + a_c − a

(L positive UP, M nose-up about the elastic axis, h positive DOWN, α nose-up; a_c is the
aerodynamic centre in semichords aft of mid-chord).  With C_lα = 2π, a_c = −1/2 these are
Theodorsen's (7.24–7.26).  The generalised loads Q_h = −L, Q_α = M (7.27) follow from the
virtual work δW = −L δh + M δα.

C(k) w is replaced by a time-domain operator built on Jones' approximation of Wagner's function
Φ(τ) = 1 − Ψ1 e^{−ε1 V τ/b} − Ψ2 e^{−ε2 V τ/b}, Ψ1 = 0.165, Ψ2 = 0.335, ε1 = 0.0455, ε2 = 0.3
(7.29), whose Laplace form is C(s) = 1 − Ψ1 s/(s + ε1V/b) − Ψ2 s/(s + ε2V/b).  Two realisations:

Wagner (4 states, 7.28–7.43, 7.67–7.73).  Duhamel (7.28): C w = Φ(0) w(t) + ∫₀ᵗ Φ̇(t−τ) w(τ) dτ.
With w = ẏ + Vα, y = h + b d α, integrating the ẏ part by parts gives (7.31)

    C w = Φ(0) w(t) + Φ̇(0) y(t) − Φ̇(t) y(0) + ∫₀ᵗ Φ̈(t−τ) y(τ) dτ + V ∫₀ᵗ Φ̇(t−τ) α(τ) dτ

and the exponential kernels make the integrals the states w1..w4 (7.30), with
ẇ = W1 [h, α] + W2 w (Leibniz, 7.34).  Φ̇(t) = Σ Ψi εi (V/b) e^{−εi V t/b} (decaying; the
thesis prints the exponent with a + sign).  The loads are

    Q = M q̈ + C q̇ + K q + W0 w + Φ̇(t) (h(0) + b d α(0)) g

`wagner_g` is the 2×1 vector g (7.41, 7.71 without the scalar in brackets); `wagner_g_ic` is the
2×2 matrix G with Φ̇(t) G [h(0), α(0)] the same initial-condition term.  The term vanishes for
motion starting from rest and plays no part in the eigenvalue analysis.

Leishman–Nguyen (2 states, 7.45–7.56, 7.74–7.80).  C(s) is realised in controllable canonical
form: C(s) = Φ(0) + (β0 + β1 s)/((s + ε1V/b)(s + ε2V/b)), β0 = (Ψ1+Ψ2) ε1ε2 (V/b)²,
β1 = (Ψ1ε1 + Ψ2ε2) V/b, driven by the three-quarter-chord angle α_3/4 = w/V (7.46):

    C w = V ([β0, β1] w + Φ(0) α_3/4),     ẇ = W1 w + [0, 1]ᵀ α_3/4
    Q = M q̈ + C q̇ + K q + W0 w,             ẇ = W1 w + W2 q̇ + W3 q

Φ(0) = 1 − Ψ1 − Ψ2 equals the printed 1/2 of (7.45) exactly because Ψ1 + Ψ2 = 1/2.

Exact Theodorsen, frequency domain (p-k method, issue 14).  For harmonic motion
q = q̂ e^{iωt} at the reduced frequency k = ωb/V, C(k) w = (F + iG)(ẏ + Vα) exactly, with
C(k) = F(k) + iG(k) (4.31) given as two real arguments.  Since i x = ẋ/ω and i ẏ = −ω y,

    C(k) w = F (ẏ + Vα) + G ((b/k) α̇ − (kV/b) y),        y = h + b d α

a real load Q = M_a q̈ + C_a(k) q̇ + K_a(k) q: the noncirculatory mass M_a unchanged, the
circulatory damping and stiffness functions of k, F and G (`theodorsen_*`; the derivation checks
the identity for harmonic motion).  Exact at the mode's own frequency, which the p-k iteration
enforces (runtime: src/propwhirl/analysis/pk.py).
"""
from __future__ import annotations

import sympy as sp

from derivations.common import (
    Derivation,
    Output,
    Param,
    coordinates,
    generalised_forces,
    second_order_matrices,
    t,
)

rho, V, b = sp.symbols("rho V b", positive=True)
a, Cla, ac = sp.symbols("a Cla ac", real=True)

#: Jones' constants (7.29) as exact rationals.
PSI1, PSI2 = sp.Rational(165, 1000), sp.Rational(335, 1000)
EPS1, EPS2 = sp.Rational(455, 10000), sp.Rational(3, 10)

PARAMS = (
    Param(rho, "air density", "kg/m^3"),
    Param(V, "airspeed", "m/s"),
    Param(b, "semichord", "m"),
    Param(a, "elastic axis aft of mid-chord, in semichords (-1/2 = quarter chord)", "-"),
    Param(Cla, "section lift-curve slope (2π for Theodorsen's flat plate)", "1/rad"),
    Param(ac, "aerodynamic centre aft of mid-chord, in semichords (-1/2 = quarter chord)", "-"),
    Param(t, "time since the start of the motion", "s"),
    Param(sp.Symbol("k", positive=True), "reduced frequency ω b / V of harmonic motion", "-"),
    Param(sp.Symbol("F", real=True), "real part of Theodorsen's function C(k) = F + iG", "-"),
    Param(sp.Symbol("G", real=True), "imaginary part of Theodorsen's function C(k) = F + iG",
          "-"),
)
kred, F_th, G_th = (p.symbol for p in PARAMS[-3:])

DOFS = ("h", "alpha")
WAGNER_STATES = ("w1", "w2", "w3", "w4")
LN_STATES = ("w1", "w2")

#: Downwash point aft of the elastic axis, in semichords: b d replaces b(1/2 − a) (7.66).
d = Cla / (2 * sp.pi) + ac - a
#: Elastic axis aft of the aerodynamic centre, in semichords: b e replaces b(a + 1/2) (7.65).
e = a - ac

tau = sp.Symbol("tau", real=True)
s = sp.Symbol("s")
RATES = (EPS1 * V / b, EPS2 * V / b)  # λ1, λ2 [1/s]


def wagner_function(x: sp.Expr) -> sp.Expr:
    """Jones' approximation of Wagner's function Φ(x), x in seconds (7.29)."""
    return 1 - PSI1 * sp.exp(-RATES[0] * x) - PSI2 * sp.exp(-RATES[1] * x)


def jones_C(s_: sp.Expr) -> sp.Expr:
    """Laplace transform of the Duhamel operator (7.28) with Φ of (7.29): C(s)."""
    return 1 - PSI1 * s_ / (s_ + RATES[0]) - PSI2 * s_ / (s_ + RATES[1])


def section_loads(hq: sp.Expr, alq: sp.Expr, circ: sp.Expr) -> tuple[sp.Expr, sp.Expr]:
    """(L, M) of (7.64–7.65) with the circulatory factor C(k) w replaced by `circ`."""
    hd, hdd = sp.diff(hq, t), sp.diff(hq, t, 2)
    ad, add = sp.diff(alq, t), sp.diff(alq, t, 2)
    L = sp.pi * rho * b**2 * (hdd + V * ad - b * a * add) + Cla * rho * V * b * circ
    M = (
        sp.pi * rho * b**2 * (a * b * hdd - V * b * d * ad - b**2 * (sp.Rational(1, 8) + a**2) * add)
        + Cla * rho * V * b**2 * e * circ
    )
    return L, M


def generalised_loads(hq: sp.Expr, alq: sp.Expr, circ: sp.Expr) -> sp.Matrix:
    """[Q_h, Q_α] from the virtual work δW = −L δh + M δα (7.27)."""
    L, M = section_loads(hq, alq, circ)
    dh, dal = sp.symbols("delta_h delta_alpha")
    return sp.Matrix(generalised_forces(-L * dh + M * dal, [dh, dal]))


def _exponential_coefficients(expr: sp.Expr, var: sp.Symbol) -> dict[int, sp.Expr]:
    """{i: c_i} with expr = Σ c_i exp(−λ_i var) over Jones' rates λ_i (no constant part)."""
    coeffs = {0: sp.S.Zero, 1: sp.S.Zero}
    for term in sp.Add.make_args(sp.expand(expr)):
        for i, lam in enumerate(RATES):
            c = sp.simplify(term / sp.exp(-lam * var))
            if not c.has(var):
                coeffs[i] += c
                break
        else:
            raise ValueError(f"term {term} is not a Jones exponential in {var}")
    return coeffs


def _check_integration_by_parts(dPhi, ddPhi) -> None:
    """d/dτ[Φ̇(t−τ) y(τ)] = −Φ̈(t−τ) y(τ) + Φ̇(t−τ) ẏ(τ): integrating over [0, t] gives (7.31)."""
    y = sp.Function("y")
    lhs = sp.diff(dPhi.subs(tau, t - tau) * y(tau), tau)
    rhs = -ddPhi.subs(tau, t - tau) * y(tau) + dPhi.subs(tau, t - tau) * sp.diff(y(tau), tau)
    assert sp.simplify(lhs - rhs) == 0


def _check_leibniz(lam: sp.Expr) -> None:
    """d/dt ∫₀ᵗ e^{−λ(t−τ)} x(τ) dτ = x(t) − λ ∫₀ᵗ ... (7.32–7.34)."""
    x = sp.Function("x")
    integral = sp.Integral(sp.exp(-lam * (t - tau)) * x(tau), (tau, 0, t))
    diff = sp.diff(integral, t).doit() - (x(t) - lam * integral)
    assert sp.simplify(sp.expand(diff)) == 0


def wagner(hq, alq):
    """Wagner / Jones realisation: (Q, states, Φ̇(t) symbol, h(0), α(0), W1, W2)."""
    Phi = wagner_function(tau)
    dPhi, ddPhi = sp.diff(Phi, tau), sp.diff(Phi, tau, 2)
    _check_integration_by_parts(dPhi, ddPhi)
    # States (7.30): w1, w2 = ∫ e^{−λ1,2 (t−τ)} h dτ;  w3, w4 = ∫ e^{−λ1,2 (t−τ)} α dτ.
    ws = sp.symbols("w1:5", real=True)
    conv_h, conv_al = ws[:2], ws[2:]
    c1 = _exponential_coefficients(dPhi, tau)  # Φ̇(τ) = Σ c1_i e^{−λ_i τ}
    c2 = _exponential_coefficients(ddPhi, tau)  # Φ̈(τ) = Σ c2_i e^{−λ_i τ}
    Phidot_t, h0, al0 = sp.symbols("Phidot_t h0 alpha0", real=True)
    y_t = hq + b * d * alq
    y_0 = h0 + b * d * al0
    w_t = sp.diff(hq, t) + V * alq + b * d * sp.diff(alq, t)  # (7.66)
    circ = (
        Phi.subs(tau, 0) * w_t
        + dPhi.subs(tau, 0) * y_t
        - Phidot_t * y_0
        + sum(c2[i] * (conv_h[i] + b * d * conv_al[i]) for i in range(2))  # ∫Φ̈(t−τ) y dτ
        + V * sum(c1[i] * conv_al[i] for i in range(2))  # V ∫Φ̇(t−τ) α dτ
    )
    # Leibniz (7.34): ẇ_k = x(t) − λ_k w_k with x = h or α.
    for lam in RATES:
        _check_leibniz(lam)
    x_of = [hq, hq, alq, alq]
    lam_of = [RATES[0], RATES[1], RATES[0], RATES[1]]
    wdot = sp.Matrix([x_of[k] - lam_of[k] * ws[k] for k in range(4)])
    xs = sp.symbols("_h _alpha")
    wdot = wdot.subs({hq: xs[0], alq: xs[1]})
    W1 = wdot.jacobian(xs)
    W2 = wdot.jacobian(ws)
    assert sp.expand(wdot - W1 * sp.Matrix(xs) - W2 * sp.Matrix(ws)) == sp.zeros(4, 1)
    return generalised_loads(hq, alq, circ), ws, Phidot_t, h0, al0, W1, W2


def jones_state_space():
    """Controllable canonical realisation of C(s): (feedthrough Φ(0), [β0, β1], A, B)."""
    num, den = sp.fraction(sp.together(jones_C(s)))
    n2, n1, n0 = sp.Poly(sp.expand(num), s).all_coeffs()
    d2, d1, d0 = sp.Poly(sp.expand(den), s).all_coeffs()
    # Monic denominator s² + d1 s + d0 = (s + λ1)(s + λ2), numerator n2 s² + n1 s + n0.
    n2, n1, n0, d1, d0 = (sp.cancel(c / d2) for c in (n2, n1, n0, d1, d0))
    feed = n2
    beta = [sp.expand(sp.cancel(n0 - feed * d0)), sp.expand(sp.cancel(n1 - feed * d1))]
    A = sp.Matrix([[0, 1], [-d0, -d1]]).applyfunc(sp.expand)
    B = sp.Matrix([0, 1])
    return sp.expand(feed), beta, A, B


def leishman_nguyen(hq, alq):
    """Leishman–Nguyen realisation: (Q, states, W1, W2, W3)."""
    feed, beta, A, B = jones_state_space()
    assert feed == 1 - PSI1 - PSI2 == sp.Rational(1, 2)
    ws = sp.symbols("w1:3", real=True)
    w_t = sp.diff(hq, t) + V * alq + b * d * sp.diff(alq, t)  # (7.66)
    alpha34 = w_t / V  # (7.46)
    circ = V * (beta[0] * ws[0] + beta[1] * ws[1] + feed * alpha34)  # V × (7.45)
    wdot = A * sp.Matrix(ws) + B * alpha34  # (7.47)
    xs, vs = sp.symbols("_h _alpha"), sp.symbols("_hd _alphad")
    subs = [(sp.diff(hq, t), vs[0]), (sp.diff(alq, t), vs[1]), (hq, xs[0]), (alq, xs[1])]
    wdot = wdot.subs(subs).applyfunc(sp.expand)
    W1, W2, W3 = wdot.jacobian(ws), wdot.jacobian(vs), wdot.jacobian(xs)
    rest = wdot - W1 * sp.Matrix(ws) - W2 * sp.Matrix(vs) - W3 * sp.Matrix(xs)
    assert rest.applyfunc(sp.expand) == sp.zeros(2, 1)
    return generalised_loads(hq, alq, circ), ws, W1, W2, W3


def theodorsen_harmonic(hq, alq):
    """Exact Theodorsen loads for harmonic motion at reduced frequency k, C(k) = F + iG given."""
    y = hq + b * d * alq
    circ = F_th * (sp.diff(y, t) + V * alq) + G_th * (b / kred * sp.diff(alq, t) - kred * V / b * y)
    # Check: for q = q̂ e^{iωt}, ω = kV/b, circ equals (F + iG)(iω ŷ + V α̂) e^{iωt}.
    hh, ah = sp.symbols("hhat alphahat")
    omega = kred * V / b
    ph = sp.exp(sp.I * omega * t)
    harmonic = {hq: hh * ph, alq: ah * ph}
    got = circ.subs(harmonic).doit()
    want = (F_th + sp.I * G_th) * (sp.I * omega * (hh + b * d * ah) + V * ah) * ph
    assert sp.simplify(sp.expand(got - want)) == 0
    return generalised_loads(hq, alq, circ)


def _split(Q: sp.Matrix, q, extra: dict) -> tuple:
    """(M, C, K) of Q with the non-coordinate symbols in `extra` set to zero."""
    return second_order_matrices([sp.expand(x.subs(extra)) for x in Q], q)


def derive() -> Derivation:
    q = coordinates(DOFS)
    hq, alq = q
    base = (rho, V, b, a, Cla, ac)

    Qw, ws, Phidot_t, h0, al0, W1w, W2w = wagner(hq, alq)
    zero = {x: 0 for x in (*ws, Phidot_t)}
    Mw, Cw, Kw = _split(Qw, q, zero)
    W0w = Qw.jacobian(ws).applyfunc(sp.expand)
    G = sp.expand(Qw.diff(Phidot_t)).jacobian([h0, al0]).applyfunc(sp.expand)
    g = G[:, 0]
    assert (G[:, 1] - b * d * g).applyfunc(sp.expand) == sp.zeros(2, 1)
    Phidot = sp.diff(wagner_function(tau), tau).subs(tau, t)

    Ql, ls, W1l, W2l, W3l = leishman_nguyen(hq, alq)
    Ml, Cl, Kl = _split(Ql, q, {x: 0 for x in ls})
    W0l = Ql.jacobian(ls).applyfunc(sp.expand)
    assert (Ml - Mw).applyfunc(sp.expand) == sp.zeros(2, 2)

    Qt = theodorsen_harmonic(hq, alq)
    Mt, Ct, Kt = _split(Qt, q, {})
    assert (Mt - Mw).applyfunc(sp.expand) == sp.zeros(2, 2)
    exact = (*base, kred, F_th, G_th)

    def out(name, mat, args, doc, eqs, rows=DOFS, cols=DOFS):
        return Output(name, sp.Matrix(mat), args, doc, eqs, rows, cols)

    outputs = [
        out("wagner_M", Mw, (rho, b, a), "Aerodynamic mass matrix M_aW (Q = M q̈ + ...) [kg/m, kg, kg m].", "7.37, 7.67"),
        out("wagner_C", Cw, base, "Wagner aerodynamic damping matrix C_aW [kg/(m s), kg/s, kg m/s].", "7.38, 7.68"),
        out("wagner_K", Kw, base, "Wagner aerodynamic stiffness matrix K_aW [N/m^2, N/m, N].", "7.39, 7.69"),
        out(
            "wagner_W0", W0w, base,
            "Wagner state influence matrix W0 = C_lα ρ b V W0' (loads per unit state).",
            "7.40, 7.70", DOFS, WAGNER_STATES,
        ),
        out(
            "wagner_g", g, base,
            "Initial-condition vector g: the loads gain Φ̇(t) (h(0) + b d α(0)) g, "
            "d = C_lα/(2π) + a_c − a [kg/(m s)].",
            "7.41, 7.71", DOFS, ("y0",),
        ),
        out(
            "wagner_g_ic", G, base,
            "Initial-condition matrix G = g [1, b d]: the loads gain Φ̇(t) G [h(0), α(0)].",
            "7.41, 7.71", DOFS, DOFS,
        ),
        out(
            "wagner_phidot", sp.Matrix([[Phidot]]), (V, b, t),
            "Time derivative Φ̇(t) of Jones' Wagner function, multiplying the g term [1/s].",
            "7.29, 7.31", ("phidot",), ("phidot",),
        ),
        out(
            "wagner_W1", W1w, (V,),
            "Wagner state input matrix: ẇ = W1 [h, α] + W2 w (constant; V only sets the "
            "broadcast shape) [-].", "7.34, 7.42, 7.72",
            WAGNER_STATES, DOFS,
        ),
        out(
            "wagner_W2", W2w, (V, b),
            "Wagner state matrix W2 = −diag(ε1, ε2, ε1, ε2) V/b [1/s].", "7.34, 7.43, 7.73",
            WAGNER_STATES, WAGNER_STATES,
        ),
        out("ln_M", Ml, (rho, b, a), "Aerodynamic mass matrix M_aW (same as Wagner's).", "7.50, 7.74"),
        out("ln_C", Cl, base, "Leishman–Nguyen aerodynamic damping matrix C_aW.", "7.51, 7.75"),
        out("ln_K", Kl, base, "Leishman–Nguyen aerodynamic stiffness matrix K_aW.", "7.52, 7.76"),
        out(
            "ln_W0", W0l, base,
            "Leishman–Nguyen state influence matrix W0 = C_lα ρ b V² W0'.", "7.53, 7.77",
            DOFS, LN_STATES,
        ),
        out(
            "ln_W1", W1l, (V, b),
            "Leishman–Nguyen state matrix: ẇ = W1 w + W2 q̇ + W3 q [1/s², 1/s].", "7.54, 7.78",
            LN_STATES, LN_STATES,
        ),
        out(
            "ln_W2", W2l, (V, b, a, Cla, ac),
            "Leishman–Nguyen state input on [ḣ, α̇] [s/m, s].", "7.55, 7.79", LN_STATES, DOFS,
        ),
        out(
            "ln_W3", W3l, (V,),
            "Leishman–Nguyen state input on [h, α] (only α enters α_3/4 statically; constant, "
            "V only sets the broadcast shape).",
            "7.56, 7.80", LN_STATES, DOFS,
        ),
        out("theodorsen_M", Mt, (rho, b, a),
            "Exact-Theodorsen aerodynamic mass matrix (noncirculatory, the same as Wagner's).",
            "7.24–7.27"),
        out("theodorsen_C", Ct, exact,
            "Exact-Theodorsen aerodynamic damping matrix C_a(k) for harmonic motion at the "
            "reduced frequency k, C(k) = F + iG [kg/(m s), kg/s, kg m/s].", "4.31, 7.24–7.27, 7.64–7.66"),
        out("theodorsen_K", Kt, exact,
            "Exact-Theodorsen aerodynamic stiffness matrix K_a(k) for harmonic motion at the "
            "reduced frequency k, C(k) = F + iG [N/m^2, N/m, N].", "4.31, 7.24–7.27, 7.64–7.66"),
    ]
    return Derivation(
        module="strip_aero",
        title="Strip aerodynamics: Theodorsen section loads with Wagner and Leishman–Nguyen states",
        source="derivations/strip_aero.py",
        equations="7.24–7.56, 7.64–7.80",
        doc=__doc__,
        params=PARAMS,
        outputs=outputs,
        blocks={
            "ln_blocks": ("ln_M", "ln_C", "ln_K", "ln_W0", "ln_W1", "ln_W2", "ln_W3"),
            "theodorsen_blocks": ("theodorsen_M", "theodorsen_C", "theodorsen_K"),
            "wagner_blocks": ("wagner_M", "wagner_C", "wagner_K", "wagner_W0", "wagner_W1", "wagner_W2"),
        },
    )
