"""Oracle tests for the strip aerodynamics (thesis §7.2, §7.5, appendices C.2.4 and D.1).

The oracles are the thesis's PRINTED matrices, transcribed by hand: (7.37–7.43) and (7.50–7.56)
for Theodorsen's flat plate (C_lα = 2π, a_c = −1/2), (7.67–7.80) for the modified strip analysis
(general C_lα, a_c), and the 3×3 element forms (C.39–C.51), (D.3–D.15).  Entries the derivation
proves wrong are corrected and marked `# erratum:`.  Further checks, independent of the printed
matrices: both time-domain realisations give Theodorsen's loads with Jones' C(s); the steady
limit is the quasi-steady lift and moment; the Duhamel integral (7.28) evaluated by quadrature
equals the state form including the initial-condition term g Φ̇(t).
"""
from __future__ import annotations

import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.integrate import quad

from propwhirl.generated import strip_aero as sa

PI = np.pi
PSI1, PSI2, EPS1, EPS2 = 0.165, 0.335, 0.0455, 0.3
RTOL = 1e-12

rho_s = st.floats(0.05, 1.5)
V_s = st.floats(1.0, 300.0)
b_s = st.floats(0.05, 3.0)
a_s = st.floats(-1.0, 1.0)
Cla_s = st.floats(1.0, 7.0)
ac_s = st.floats(-1.0, 1.0)
SETTINGS = settings(max_examples=40, deadline=None)


def close(actual, expected, rtol=RTOL, atol_rel=1e-12):
    expected = np.asarray(expected)
    atol = atol_rel * max(np.abs(expected).max(), 1e-300)
    np.testing.assert_allclose(actual, expected, rtol=rtol, atol=atol)


# --------------------------------------------------------------------------------------------
# Hand transcriptions of the printed matrices
# --------------------------------------------------------------------------------------------
def phi0() -> float:
    """Φ(0) = 1 − Ψ1 − Ψ2 (below 7.31)."""
    return 1 - PSI1 - PSI2


def phidot0(V, b) -> float:
    """Φ̇(0) = Ψ1 ε1 V/b + Ψ2 ε2 V/b (below 7.31)."""
    return PSI1 * EPS1 * V / b + PSI2 * EPS2 * V / b


def phidot(V, b, t):
    """Φ̇(t) of Jones' Φ (7.29), below (7.31)."""
    # erratum: printed Ψ1 ε1 (V/b) e^{+ε1 V t/b} + Ψ2 ε2 (V/b) e^{+ε2 V t/b}, derived with
    # e^{−εi V t/b}, because Φ̇ is the time derivative of Φ = 1 − Ψ1 e^{−ε1Vt/b} − Ψ2 e^{−ε2Vt/b}
    # (7.29); the printed form grows without bound (test_duhamel_... shows it violates 7.28).
    return PSI1 * EPS1 * V / b * np.exp(-EPS1 * V * t / b) + PSI2 * EPS2 * V / b * np.exp(
        -EPS2 * V * t / b
    )


def mass_7_37(rho, b, a):
    """M_aW (7.37) = (7.50) = (7.67) = (7.74)."""
    return np.array(
        [
            [-PI * rho * b**2, PI * rho * b**3 * a],
            [PI * rho * b**3 * a, -PI * rho * b**4 * (1 / 8 + a**2)],
        ]
    )


def wagner_7_38(rho, V, b, a):
    P0 = phi0()
    return np.array(
        [
            [-2 * PI * rho * b * V * P0, -PI * rho * b**2 * V - 2 * PI * rho * b**2 * V * (0.5 - a) * P0],
            [
                2 * PI * rho * b * V * P0 * b * (a + 0.5),
                -PI * rho * b**3 * V * (0.5 - a)
                + 2 * PI * rho * b**2 * V * (0.5 - a) * P0 * b * (a + 0.5),
            ],
        ]
    )


def wagner_7_39(rho, V, b, a):
    P0, Pd0 = phi0(), phidot0(V, b)
    return np.array(
        [
            [
                -2 * PI * rho * b * V * Pd0,
                -2 * PI * rho * b * V**2 * P0 - 2 * PI * rho * b**2 * V * (0.5 - a) * Pd0,
            ],
            [
                2 * PI * rho * b * V * Pd0 * b * (a + 0.5),
                2 * PI * rho * b * V**2 * P0 * b * (a + 0.5)
                + 2 * PI * rho * b**2 * V * (0.5 - a) * Pd0 * b * (a + 0.5),
            ],
        ]
    )


def wagner_7_40(rho, V, b, a):
    r1 = [
        PSI1 * (EPS1 * V / b) ** 2,
        PSI2 * (EPS2 * V / b) ** 2,
        -PSI1 * EPS1 * V**2 / b * (1 - EPS1 * (0.5 - a)),
        -PSI2 * EPS2 * V**2 / b * (1 - EPS2 * (0.5 - a)),
    ]
    r2 = [
        -PSI1 * (EPS1 * V / b) ** 2 * b * (a + 0.5),
        -PSI2 * (EPS2 * V / b) ** 2 * b * (a + 0.5),
        PSI1 * EPS1 * V**2 / b * (1 - EPS1 * (0.5 - a)) * b * (a + 0.5),
        PSI2 * EPS2 * V**2 / b * (1 - EPS2 * (0.5 - a)) * b * (a + 0.5),
    ]
    return 2 * PI * rho * b * V * np.array([r1, r2])


def wagner_7_41(rho, V, b, a, h0, alpha0):
    """g of (7.41), including the bracketed scalar h(0) + b(1/2 − a) α(0); multiplies Φ̇(t)."""
    return 2 * PI * rho * b * V * (h0 + b * (0.5 - a) * alpha0) * np.array([[1.0], [-b * (a + 0.5)]])


W1_7_42 = np.array([[1.0, 0.0], [1.0, 0.0], [0.0, 1.0], [0.0, 1.0]])  # = (7.72)


def wagner_7_43(V, b):
    return np.diag([-EPS1 * V / b, -EPS2 * V / b, -EPS1 * V / b, -EPS2 * V / b])


def ln_7_51(rho, V, b, a):
    return np.array(
        [
            [-PI * rho * b * V, -PI * rho * b**2 * V - PI * rho * b**2 * V * (0.5 - a)],
            [
                PI * rho * b * V * b * (a + 0.5),
                -PI * rho * b**3 * V * (0.5 - a) + PI * rho * b**2 * V * (0.5 - a) * b * (a + 0.5),
            ],
        ]
    )


def ln_7_52(rho, V, b, a):
    return np.array([[0.0, -PI * rho * b * V**2], [0.0, PI * rho * V**2 * b**2 * (a + 0.5)]])


def ln_7_53(rho, V, b, a):
    c1 = (PSI1 + PSI2) * EPS1 * EPS2 * (V / b) ** 2
    c2 = (PSI1 * EPS1 + PSI2 * EPS2) * (V / b)
    W0p = np.array([[-c1, -c2], [c1 * b * (a + 0.5), c2 * b * (a + 0.5)]])
    return 2 * PI * rho * b * V**2 * W0p


def ln_7_54(V, b):
    """= (7.78)."""
    return np.array([[0.0, 1.0], [-EPS1 * EPS2 * (V / b) ** 2, -(EPS1 + EPS2) * (V / b)]])


def ln_7_55(V, b, a):
    return np.array([[0.0, 0.0], [1 / V, b / V * (0.5 - a)]])


W3_7_56 = np.array([[0.0, 0.0], [0.0, 1.0]])  # = (7.80)


# Modified strip analysis (7.67–7.80): dd = C_lα/(2π) + a_c − a,  ee = a − a_c.
def wagner_7_68(rho, V, b, a, Cla, ac):
    P0, dd, ee = phi0(), Cla / (2 * PI) + ac - a, a - ac
    return np.array(
        [
            [-Cla * rho * b * V * P0, -PI * rho * b**2 * V - Cla * rho * b**2 * V * dd * P0],
            [
                Cla * rho * b * V * P0 * b * ee,
                -PI * rho * b**3 * V * dd + Cla * rho * b**2 * V * dd * P0 * b * ee,
            ],
        ]
    )


def wagner_7_69(rho, V, b, a, Cla, ac):
    P0, Pd0, dd, ee = phi0(), phidot0(V, b), Cla / (2 * PI) + ac - a, a - ac
    return np.array(
        [
            [-Cla * rho * b * V * Pd0, -Cla * rho * b * V**2 * P0 - Cla * rho * b**2 * V * dd * Pd0],
            [
                Cla * rho * b * V * Pd0 * b * ee,
                Cla * rho * b * V**2 * P0 * b * ee + Cla * rho * b**2 * V * dd * Pd0 * b * ee,
            ],
        ]
    )


def wagner_7_70(rho, V, b, a, Cla, ac):
    dd, ee = Cla / (2 * PI) + ac - a, a - ac
    r1 = [
        PSI1 * (EPS1 * V / b) ** 2,
        PSI2 * (EPS2 * V / b) ** 2,
        -PSI1 * EPS1 * V**2 / b * (1 - EPS1 * dd),
        -PSI2 * EPS2 * V**2 / b * (1 - EPS2 * dd),
    ]
    r2 = [
        -PSI1 * (EPS1 * V / b) ** 2 * b * ee,
        -PSI2 * (EPS2 * V / b) ** 2 * b * ee,
        PSI1 * EPS1 * V**2 / b * (1 - EPS1 * dd) * b * ee,
        PSI2 * EPS2 * V**2 / b * (1 - EPS2 * dd) * b * ee,
    ]
    return Cla * rho * b * V * np.array([r1, r2])


def wagner_7_71(rho, V, b, a, Cla, ac, h0, alpha0):
    dd, ee = Cla / (2 * PI) + ac - a, a - ac
    return Cla * rho * b * V * (h0 + b * dd * alpha0) * np.array([[1.0], [-b * ee]])


def wagner_7_73(V, b):
    # erratum: printed last diagonal entry −ε2 V/c, derived −ε2 V/b, because ẇ4 = α − ε2 (V/b) w4
    # (7.34) and (7.43); c (= 2b) is not a symbol of the model.
    return np.diag([-EPS1 * V / b, -EPS2 * V / b, -EPS1 * V / b, -EPS2 * V / b])


def ln_7_75(rho, V, b, a, Cla, ac):
    dd, ee = Cla / (2 * PI) + ac - a, a - ac
    return np.array(
        [
            [-Cla * rho / 2 * b * V, -PI * rho * b**2 * V - Cla * rho / 2 * b**2 * V * dd],
            [
                Cla * rho / 2 * b * V * b * ee,
                -PI * rho * b**3 * V * dd + Cla * rho / 2 * b**2 * V * dd * b * ee,
            ],
        ]
    )


def ln_7_76(rho, V, b, a, Cla, ac):
    ee = a - ac
    return np.array([[0.0, -Cla * rho / 2 * b * V**2], [0.0, Cla * rho / 2 * V**2 * b**2 * ee]])


def ln_7_77(rho, V, b, a, Cla, ac):
    ee = a - ac
    c1 = (PSI1 + PSI2) * EPS1 * EPS2 * (V / b) ** 2
    c2 = (PSI1 * EPS1 + PSI2 * EPS2) * (V / b)
    return Cla * rho * b * V**2 * np.array([[-c1, -c2], [c1 * b * ee, c2 * b * ee]])


def ln_7_79(V, b, a, Cla, ac):
    dd = Cla / (2 * PI) + ac - a
    return np.array([[0.0, 0.0], [1 / V, b / V * dd]])


# --------------------------------------------------------------------------------------------
# Oracle tests
# --------------------------------------------------------------------------------------------
@SETTINGS
@given(rho=rho_s, V=V_s, b=b_s, a=a_s, h0=st.floats(-1, 1), alpha0=st.floats(-0.3, 0.3))
def test_wagner_flat_plate_matches_7_37_to_7_43(rho, V, b, a, h0, alpha0):
    args = (rho, V, b, a, 2 * PI, -0.5)
    close(sa.wagner_M(rho, b, a), mass_7_37(rho, b, a))
    close(sa.wagner_C(*args), wagner_7_38(rho, V, b, a))
    close(sa.wagner_K(*args), wagner_7_39(rho, V, b, a))
    close(sa.wagner_W0(*args), wagner_7_40(rho, V, b, a))
    y0 = h0 + b * (0.5 - a) * alpha0
    close(sa.wagner_g(*args) * y0, wagner_7_41(rho, V, b, a, h0, alpha0))
    # g = G [h(0), α(0)]: G column by column (the product may cancel to rounding)
    close(sa.wagner_g_ic(*args), np.hstack([wagner_7_41(rho, V, b, a, 1.0, 0.0),
                                            wagner_7_41(rho, V, b, a, 0.0, 1.0)]))
    close(sa.wagner_W1(V), W1_7_42)
    close(sa.wagner_W2(V, b), wagner_7_43(V, b))


@SETTINGS
@given(rho=rho_s, V=V_s, b=b_s, a=a_s, Cla=Cla_s, ac=ac_s, h0=st.floats(-1, 1), alpha0=st.floats(-0.3, 0.3))
def test_wagner_modified_strip_matches_7_67_to_7_73(rho, V, b, a, Cla, ac, h0, alpha0):
    args = (rho, V, b, a, Cla, ac)
    close(sa.wagner_M(rho, b, a), mass_7_37(rho, b, a))  # (7.67) prints the same matrix
    close(sa.wagner_C(*args), wagner_7_68(*args))
    close(sa.wagner_K(*args), wagner_7_69(*args))
    close(sa.wagner_W0(*args), wagner_7_70(*args))
    y0 = h0 + b * (Cla / (2 * PI) + ac - a) * alpha0
    close(sa.wagner_g(*args) * y0, wagner_7_71(*args, h0, alpha0))
    close(sa.wagner_g_ic(*args), np.hstack([wagner_7_71(*args, 1.0, 0.0), wagner_7_71(*args, 0.0, 1.0)]))
    close(sa.wagner_W1(V), W1_7_42)
    close(sa.wagner_W2(V, b), wagner_7_73(V, b))


@SETTINGS
@given(rho=rho_s, V=V_s, b=b_s, a=a_s)
def test_leishman_nguyen_flat_plate_matches_7_50_to_7_56(rho, V, b, a):
    args = (rho, V, b, a, 2 * PI, -0.5)
    close(sa.ln_M(rho, b, a), mass_7_37(rho, b, a))
    close(sa.ln_C(*args), ln_7_51(rho, V, b, a))
    close(sa.ln_K(*args), ln_7_52(rho, V, b, a))
    close(sa.ln_W0(*args), ln_7_53(rho, V, b, a))
    close(sa.ln_W1(V, b), ln_7_54(V, b))
    close(sa.ln_W2(V, b, a, 2 * PI, -0.5), ln_7_55(V, b, a))
    close(sa.ln_W3(V), W3_7_56)


@SETTINGS
@given(rho=rho_s, V=V_s, b=b_s, a=a_s, Cla=Cla_s, ac=ac_s)
def test_leishman_nguyen_modified_strip_matches_7_74_to_7_80(rho, V, b, a, Cla, ac):
    args = (rho, V, b, a, Cla, ac)
    close(sa.ln_M(rho, b, a), mass_7_37(rho, b, a))  # (7.74)
    close(sa.ln_C(*args), ln_7_75(*args))
    close(sa.ln_K(*args), ln_7_76(*args))
    close(sa.ln_W0(*args), ln_7_77(*args))
    close(sa.ln_W1(V, b), ln_7_54(V, b))  # (7.78)
    close(sa.ln_W2(V, b, a, Cla, ac), ln_7_79(V, b, a, Cla, ac))
    close(sa.ln_W3(V), W3_7_56)  # (7.80)


def _embed(m2: np.ndarray, rows: bool = True, cols: bool = True) -> np.ndarray:
    """Insert the zero bending-slope (φ) row/column of the element forms [h, φ, α]."""
    m = np.insert(m2, 1, 0.0, axis=0) if rows else m2
    return np.insert(m, 1, 0.0, axis=1) if cols else m


@SETTINGS
@given(rho=rho_s, V=V_s, b=b_s, a=a_s, h0=st.floats(-1, 1), alpha0=st.floats(-0.3, 0.3))
def test_appendix_element_matrices_C39_to_C51_and_D3_to_D15(rho, V, b, a, h0, alpha0):
    """Element forms [h, φ, α] of appendices C.2.4 (Wagner) and D.1 (Leishman–Nguyen)."""
    args = (rho, V, b, a, 2 * PI, -0.5)
    P0, Pd0 = phi0(), phidot0(V, b)
    M_C39 = np.array(
        [[-PI * rho * b**2, 0, PI * rho * b**3 * a], [0, 0, 0], [PI * rho * b**3 * a, 0, -PI * rho * b**4 * (1 / 8 + a**2)]]
    )
    C_C41 = np.array(
        [
            [-2 * PI * rho * b * V * P0, 0, -PI * rho * b**2 * V - 2 * PI * rho * b**2 * V * (0.5 - a) * P0],
            [0, 0, 0],
            [
                2 * PI * rho * b * V * P0 * b * (a + 0.5),
                0,
                -PI * rho * b**3 * V * (0.5 - a) + 2 * PI * rho * b**2 * V * (0.5 - a) * P0 * b * (a + 0.5),
            ],
        ]
    )
    K_C43 = np.array(
        [
            [-2 * PI * rho * b * V * Pd0, 0, -2 * PI * rho * b * V**2 * P0 - 2 * PI * rho * b**2 * V * (0.5 - a) * Pd0],
            [0, 0, 0],
            [
                2 * PI * rho * b * V * Pd0 * b * (a + 0.5),
                0,
                2 * PI * rho * b * V**2 * P0 * b * (a + 0.5)
                + 2 * PI * rho * b**2 * V * (0.5 - a) * Pd0 * b * (a + 0.5),
            ],
        ]
    )
    # (C.45) prints the φ row with three zeros for four columns; it is the zero row 0_{1×4}.
    W0_C45 = 2 * PI * rho * b * V * np.array(
        [
            [
                PSI1 * (EPS1 * V / b) ** 2,
                PSI2 * (EPS2 * V / b) ** 2,
                -PSI1 * EPS1 * V**2 / b * (1 - EPS1 * (0.5 - a)),
                -PSI2 * EPS2 * V**2 / b * (1 - EPS2 * (0.5 - a)),
            ],
            [0, 0, 0, 0],
            [
                -PSI1 * (EPS1 * V / b) ** 2 * b * (a + 0.5),
                -PSI2 * (EPS2 * V / b) ** 2 * b * (a + 0.5),
                PSI1 * EPS1 * V**2 / b * (1 - EPS1 * (0.5 - a)) * b * (a + 0.5),
                PSI2 * EPS2 * V**2 / b * (1 - EPS2 * (0.5 - a)) * b * (a + 0.5),
            ],
        ]
    )
    # C.47, g = G [h(0), α(0)]: G compared entry by entry (the product cancels exactly where
    # h0 + b(½ − a)α0 = 0, leaving only rounding to compare).
    G_C47 = 2 * PI * rho * b * V * np.outer([1.0, 0.0, -b * (a + 0.5)], [1.0, b * (0.5 - a)])
    W1_C49 = np.array([[1, 0, 0], [1, 0, 0], [0, 0, 1], [0, 0, 1]], dtype=float)
    W2_C51 = np.diag([-EPS1 * V / b, -EPS2 * V / b, -EPS1 * V / b, -EPS2 * V / b])
    close(_embed(sa.wagner_M(rho, b, a)), M_C39)
    close(_embed(sa.wagner_C(*args)), C_C41)  # consistent with (7.38)
    close(_embed(sa.wagner_K(*args)), K_C43)
    close(_embed(sa.wagner_W0(*args), cols=False), W0_C45)
    close(_embed(sa.wagner_g_ic(*args), cols=False), G_C47)
    close(_embed(sa.wagner_W1(V), rows=False), W1_C49)
    close(sa.wagner_W2(V, b), W2_C51)

    C_D5 = np.array(
        [
            [-PI * rho * b * V, 0, -PI * rho * b**2 * V - PI * rho * b**2 * V * (0.5 - a)],
            [0, 0, 0],
            [
                PI * rho * b * V * b * (a + 0.5),
                0,
                -PI * rho * b**3 * V * (0.5 - a) + PI * rho * b**2 * V * (0.5 - a) * b * (a + 0.5),
            ],
        ]
    )
    # erratum: (D.7) prints K_a,e[α, α] = πρ b V² b² (a + 1/2), derived πρ V² b² (a + 1/2), because
    # the circulatory moment 2πρV²b² (a + 1/2) C α_3/4 with C → 1/2 gives πρV²b²(a + 1/2) α, as
    # printed in (7.52) and (7.76); the extra b makes the entry N·m per unit span instead of N.
    K_D7 = np.array([[0, 0, -PI * rho * b * V**2], [0, 0, 0], [0, 0, PI * rho * V**2 * b**2 * (a + 0.5)]])
    c1 = (PSI1 + PSI2) * EPS1 * EPS2 * (V / b) ** 2
    c2 = (PSI1 * EPS1 + PSI2 * EPS2) * (V / b)
    W0_D9 = 2 * PI * rho * b * V**2 * np.array([[-c1, -c2], [0, 0], [c1 * b * (a + 0.5), c2 * b * (a + 0.5)]])
    W1_D11 = np.array([[0, 1], [-EPS1 * EPS2 * (V / b) ** 2, -(EPS1 + EPS2) * (V / b)]])
    W2_D13 = np.array([[0, 0, 0], [1 / V, 0, b / V * (0.5 - a)]])
    W3_D15 = np.array([[0, 0, 0], [0, 0, 1.0]])
    close(_embed(sa.ln_M(rho, b, a)), M_C39)  # (D.3) = (C.39)
    close(_embed(sa.ln_C(*args)), C_D5)
    close(_embed(sa.ln_K(*args)), K_D7)
    close(_embed(sa.ln_W0(*args), cols=False), W0_D9)
    close(sa.ln_W1(V, b), W1_D11)
    close(_embed(sa.ln_W2(V, b, a, 2 * PI, -0.5), rows=False), W2_D13)
    close(_embed(sa.ln_W3(V), rows=False), W3_D15)


# --------------------------------------------------------------------------------------------
# Physics checks independent of the printed matrices
# --------------------------------------------------------------------------------------------
def theodorsen_jones_loads(s, rho, V, b, a, Cla, ac):
    """[Q_h, Q_α] per unit [h, α] from (7.64–7.66) in Laplace form with Jones' C(s)."""
    C = 1 - PSI1 * s / (s + EPS1 * V / b) - PSI2 * s / (s + EPS2 * V / b)
    dd, ee = Cla / (2 * PI) + ac - a, a - ac
    H = np.zeros((2, 2), dtype=complex)
    for j, (h, al) in enumerate(((1.0, 0.0), (0.0, 1.0))):
        w = s * h + V * al + b * dd * s * al  # (7.66)
        L = PI * rho * b**2 * (s**2 * h + V * s * al - b * a * s**2 * al) + Cla * rho * V * b * C * w
        M = (
            PI * rho * b**2 * (a * b * s**2 * h - V * b * dd * s * al - b**2 * (1 / 8 + a**2) * s**2 * al)
            + Cla * rho * V * b**2 * ee * C * w
        )
        H[:, j] = (-L, M)  # (7.27)
    return H


def wagner_transfer(s, *args):
    rho, V, b, a = args[:4]
    M, C, K = sa.wagner_M(rho, b, a), sa.wagner_C(*args), sa.wagner_K(*args)
    W0, W1, W2 = sa.wagner_W0(*args), sa.wagner_W1(V), sa.wagner_W2(V, b)
    return M * s**2 + C * s + K + W0 @ np.linalg.solve(s * np.eye(4) - W2, W1)


def ln_transfer(s, *args):
    rho, V, b, a, Cla, ac = args
    M, C, K = sa.ln_M(rho, b, a), sa.ln_C(*args), sa.ln_K(*args)
    W0, W1 = sa.ln_W0(*args), sa.ln_W1(V, b)
    W2, W3 = sa.ln_W2(V, b, a, Cla, ac), sa.ln_W3(V)
    return M * s**2 + C * s + K + W0 @ np.linalg.solve(s * np.eye(2) - W1, s * W2 + W3)


@SETTINGS
@given(rho=rho_s, V=V_s, b=b_s, a=a_s, Cla=Cla_s, ac=ac_s, k=st.floats(0.001, 3.0))
def test_both_realisations_give_theodorsen_jones_loads(rho, V, b, a, Cla, ac, k):
    args = (rho, V, b, a, Cla, ac)
    for s in (1j * k * V / b, 0.3j * k * V / b, (-0.05 + 1j) * k * V / b):
        ref = theodorsen_jones_loads(s, *args)
        close(wagner_transfer(s, *args), ref, rtol=1e-9, atol_rel=1e-10)
        close(ln_transfer(s, *args), ref, rtol=1e-9, atol_rel=1e-10)


@SETTINGS
@given(rho=rho_s, V=V_s, b=b_s, a=a_s, Cla=Cla_s, ac=ac_s)
def test_steady_limit_is_quasi_steady_lift_and_moment(rho, V, b, a, Cla, ac):
    args = (rho, V, b, a, Cla, ac)
    lift = Cla * rho * V**2 * b  # L = ½ρV²(2b) C_lα α
    moment = Cla * rho * V**2 * b**2 * (a - ac)  # lift at a_c, moment about the elastic axis
    expected = np.array([[0.0, -lift], [0.0, moment]])  # Q_h = −L, Q_α = M
    for H in (wagner_transfer(0.0, *args), ln_transfer(0.0, *args)):
        close(H, expected, rtol=1e-10, atol_rel=1e-10)


@settings(max_examples=8, deadline=None)
@given(
    V=st.floats(20.0, 120.0),
    b=st.floats(0.2, 1.5),
    a=st.floats(-0.6, 0.6),
    Cla=Cla_s,
    ac=st.floats(-0.6, 0.0),
    omega=st.floats(2.0, 20.0),
    t_end=st.floats(0.05, 1.5),
)
def test_duhamel_integral_equals_state_form_with_initial_condition_term(V, b, a, Cla, ac, omega, t_end):
    """(7.28) by quadrature, for a motion with h(0), α(0) ≠ 0, against Q = ... + W0 w + g Φ̇(t) y(0).

    The states w1..w4 (7.30) are also evaluated by quadrature; with the printed Φ̇(t)
    (exponent +εVt/b) the check fails, which is the evidence for that erratum.
    """
    rho = 1.0
    args = (rho, V, b, a, Cla, ac)
    h = lambda x: 0.02 * np.cos(omega * x) + 0.01 * np.sin(0.7 * omega * x)  # noqa: E731
    hd = lambda x: -0.02 * omega * np.sin(omega * x) + 0.007 * omega * np.cos(0.7 * omega * x)  # noqa: E731
    hdd = lambda x: -0.02 * omega**2 * np.cos(omega * x) - 0.0049 * omega**2 * np.sin(0.7 * omega * x)  # noqa: E731
    al = lambda x: 0.03 * np.cos(1.3 * omega * x + 0.4)  # noqa: E731
    ald = lambda x: -0.039 * omega * np.sin(1.3 * omega * x + 0.4)  # noqa: E731
    aldd = lambda x: -0.0507 * omega**2 * np.cos(1.3 * omega * x + 0.4)  # noqa: E731
    dd, ee = Cla / (2 * PI) + ac - a, a - ac
    w = lambda x: hd(x) + V * al(x) + b * dd * ald(x)  # noqa: E731  (7.66)
    Phi = lambda x: 1 - PSI1 * np.exp(-EPS1 * V * x / b) - PSI2 * np.exp(-EPS2 * V * x / b)  # (7.29)
    T = t_end
    opts = dict(epsabs=1e-13, epsrel=1e-12, limit=400)
    # (7.28): C w = Φ(0) w(t) − ∫ dΦ(t − t0)/dt0 w(t0) dt0, differentiating (7.29):
    # d/dt0 Φ(t − t0) = −(Ψ1 λ1 e^{−λ1(t−t0)} + Ψ2 λ2 e^{−λ2(t−t0)}).
    lam1, lam2 = EPS1 * V / b, EPS2 * V / b
    dPhi_dt0 = lambda x: -(PSI1 * lam1 * np.exp(-lam1 * (T - x)) + PSI2 * lam2 * np.exp(-lam2 * (T - x)))  # noqa: E731
    Cw = Phi(0.0) * w(T) - quad(lambda x: dPhi_dt0(x) * w(x), 0.0, T, **opts)[0]
    L = PI * rho * b**2 * (hdd(T) + V * ald(T) - b * a * aldd(T)) + Cla * rho * V * b * Cw
    M = PI * rho * b**2 * (a * b * hdd(T) - V * b * dd * ald(T) - b**2 * (1 / 8 + a**2) * aldd(T)) + Cla * rho * V * b**2 * ee * Cw
    Q_duhamel = np.array([-L, M])

    states = np.array(
        [quad(lambda x, f=f, lam=lam: np.exp(-lam * (T - x)) * f(x), 0.0, T, **opts)[0]
         for f, lam in ((h, lam1), (h, lam2), (al, lam1), (al, lam2))]
    )  # (7.30)
    q, qd, qdd = np.array([h(T), al(T)]), np.array([hd(T), ald(T)]), np.array([hdd(T), aldd(T)])
    y0 = h(0.0) + b * dd * al(0.0)
    base = (
        sa.wagner_M(rho, b, a) @ qdd + sa.wagner_C(*args) @ qd + sa.wagner_K(*args) @ q
        + sa.wagner_W0(*args) @ states
    )
    phidot_t = sa.wagner_phidot(V, b, T)[0, 0]
    close(phidot_t, phidot(V, b, T))
    Q_state = base + sa.wagner_g(*args)[:, 0] * phidot_t * y0
    scale = np.abs(Q_duhamel).max() + np.abs(base).max()
    np.testing.assert_allclose(Q_state, Q_duhamel, rtol=1e-8, atol=1e-9 * scale)
    Q_ic = base + sa.wagner_g_ic(*args) @ np.array([h(0.0), al(0.0)]) * phidot_t
    np.testing.assert_allclose(Q_ic, Q_duhamel, rtol=1e-8, atol=1e-9 * scale)
    # The printed Φ̇(t) = Σ Ψi εi V/b e^{+εi V t/b} does not reproduce (7.28).
    printed = PSI1 * lam1 * np.exp(lam1 * T) + PSI2 * lam2 * np.exp(lam2 * T)
    Q_printed = base + sa.wagner_g(*args)[:, 0] * printed * y0
    err_printed = np.abs(Q_printed - Q_duhamel).max()
    assert err_printed > 1e3 * np.abs(Q_state - Q_duhamel).max() + 1e-12 * scale


def test_leishman_nguyen_equals_jones_because_psi1_plus_psi2_is_half():
    """(7.45)+(7.47) with the printed feed-through 1/2 give Jones' C(s) iff Ψ1 + Ψ2 = 1/2."""
    s, lam = sp.symbols("s lambda", positive=True)  # lam = V/b
    P1, P2, e1, e2 = sp.symbols("Psi1 Psi2 epsilon1 epsilon2", positive=True)
    A = sp.Matrix([[0, 1], [-e1 * e2 * lam**2, -(e1 + e2) * lam]])  # (7.47)
    B = sp.Matrix([0, 1])
    Cv = sp.Matrix([[(P1 + P2) * e1 * e2 * lam**2, (P1 * e1 + P2 * e2) * lam]])  # (7.45)
    C_ln = (Cv * (s * sp.eye(2) - A).inv() * B)[0] + sp.Rational(1, 2)
    C_jones = 1 - P1 * s / (s + e1 * lam) - P2 * s / (s + e2 * lam)
    diff = sp.factor(sp.cancel(C_ln - C_jones))
    # The difference is exactly the feed-through mismatch 1/2 − Φ(0) = Ψ1 + Ψ2 − 1/2.
    assert sp.simplify(diff - (P1 + P2 - sp.Rational(1, 2))) == 0
    jones = {P1: sp.Rational(165, 1000), P2: sp.Rational(335, 1000)}
    assert diff.subs(jones) == 0
    assert sp.cancel((C_ln - C_jones).subs({**jones, e1: sp.Rational(455, 10000), e2: sp.Rational(3, 10)})) == 0


def test_derivation_reduces_to_theodorsen_symbolically():
    """With C_lα = 2π, a_c = −1/2 the derived matrices equal (7.37–7.40) and (7.51–7.53) exactly."""
    from derivations import strip_aero as der

    d = der.derive()
    outs = {o.name: o.matrix for o in d.outputs}
    rho, V, b, a = der.rho, der.V, der.b, der.a
    flat = {der.Cla: 2 * sp.pi, der.ac: sp.Rational(-1, 2)}
    half = sp.Rational(1, 2)
    P1, P2, e1, e2 = der.PSI1, der.PSI2, der.EPS1, der.EPS2
    Pd0 = (P1 * e1 + P2 * e2) * V / b
    expected_C = sp.Matrix(
        [
            [-2 * sp.pi * rho * b * V * half, -sp.pi * rho * b**2 * V - 2 * sp.pi * rho * b**2 * V * (half - a) * half],
            [
                2 * sp.pi * rho * b * V * half * b * (a + half),
                -sp.pi * rho * b**3 * V * (half - a) + 2 * sp.pi * rho * b**2 * V * (half - a) * half * b * (a + half),
            ],
        ]
    )
    expected_K = sp.Matrix(
        [
            [-2 * sp.pi * rho * b * V * Pd0, -2 * sp.pi * rho * b * V**2 * half - 2 * sp.pi * rho * b**2 * V * (half - a) * Pd0],
            [
                2 * sp.pi * rho * b * V * Pd0 * b * (a + half),
                2 * sp.pi * rho * b * V**2 * half * b * (a + half) + 2 * sp.pi * rho * b**2 * V * (half - a) * Pd0 * b * (a + half),
            ],
        ]
    )
    assert (outs["wagner_C"].subs(flat) - expected_C).applyfunc(sp.expand) == sp.zeros(2, 2)
    assert (outs["wagner_K"].subs(flat) - expected_K).applyfunc(sp.expand) == sp.zeros(2, 2)
    expected_lnK = sp.Matrix([[0, -sp.pi * rho * b * V**2], [0, sp.pi * rho * V**2 * b**2 * (a + half)]])
    assert (outs["ln_K"].subs(flat) - expected_lnK).applyfunc(sp.expand) == sp.zeros(2, 2)


def test_generated_functions_broadcast():
    rho, V, b = 1.2, np.linspace(10, 100, 5)[:, None], np.array([0.5, 1.0, 1.5])
    args = (rho, V, b, -0.2, 5.8, -0.45)
    assert sa.wagner_C(*args).shape == (5, 3, 2, 2)
    assert sa.wagner_W0(*args).shape == (5, 3, 2, 4)
    assert sa.wagner_W2(V, b).shape == (5, 3, 4, 4)
    assert sa.wagner_W1(V).shape == (5, 1, 4, 2)
    assert sa.ln_W2(V, b, -0.2, 5.8, -0.45).shape == (5, 3, 2, 2)
    # Each slice equals the scalar evaluation.
    close(sa.ln_W0(*args)[3, 1], sa.ln_W0(rho, V[3, 0], b[1], -0.2, 5.8, -0.45))


@pytest.mark.parametrize("name", sorted(sa.OUTPUTS))
def test_output_metadata_labels(name):
    argnames, rows, cols, _ = sa.OUTPUTS[name]
    f = getattr(sa, name)
    vals = {"rho": 1.0, "V": 50.0, "b": 0.5, "a": -0.1, "Cla": 6.0, "ac": -0.5, "t": 0.1,
            "k": 0.3, "F": 0.7, "G": -0.2}
    assert f(*(vals[n] for n in argnames)).shape == (len(rows), len(cols))
