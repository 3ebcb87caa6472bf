"""Oracle tests: generated propeller matrices against the thesis's printed matrices.

The oracles below are hand transcriptions of the PRINTED equations (not of the derivation):
chapter 6, eqs. 6.6, 6.12–6.17 (propeller on a rigid wing, e_θ, e_ψ > 0 distances), and
chapter 8, eqs. 8.5–8.6, 8.10, 8.15–8.23, 8.28–8.42 and appendix C (C.6, C.8, C.11, C.13,
C.15, C.20, C.22, C.24, C.27, C.29, C.31, C.33, C.35, C.37) (signed distances, positive
rearward).  k1 = ½ρV²S', k2 = ρV²S'R, S' = πR².  Random physical values and random values of
all sixteen aerodynamic derivatives (no symmetry relations 4.27 imposed).
"""
from __future__ import annotations

import sys

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from propwhirl.generated import prop_flexwing as g8
from propwhirl.generated import prop_rigid as g6

SETTINGS = settings(max_examples=40, deadline=None)

DERIVS = tuple(f"{c}_{v}" for c in ("CZ", "Cm", "CY", "Cn") for v in ("theta", "psi", "q", "r"))


def fl(lo: float, hi: float) -> st.SearchStrategy[float]:
    return st.floats(lo, hi, allow_nan=False, allow_infinity=False, allow_subnormal=False)


def strat(**ranges) -> st.SearchStrategy[dict]:
    return st.fixed_dictionaries({k: fl(*v) for k, v in ranges.items()})


AERO_RANGES = dict(rho=(0.05, 1.5), V=(1.0, 300.0), R=(0.1, 3.0),
                   **{d: (-3.0, 3.0) for d in DERIVS})
CH6_AERO = strat(e_theta=(0.01, 3.0), e_psi=(0.01, 3.0), **AERO_RANGES)
CH8_AERO = strat(e_theta=(-3.0, 1.0), e_psi=(-3.0, 1.0), e_alpha=(-3.0, 1.0), **AERO_RANGES)
CH6_STRUCT = strat(
    I_X=(1e-3, 5.0), I_Y=(1e-2, 100.0), I_Z=(1e-2, 100.0), Omega=(-400.0, 400.0),
    K_theta=(1.0, 1e6), K_psi=(1.0, 1e6), g_theta=(0.0, 0.2), g_psi=(0.0, 0.2),
    omega=(0.1, 500.0), zeta_theta=(0.0, 0.2), zeta_psi=(0.0, 0.2),
)
CH8_STRUCT = strat(
    I_Omega=(1e-3, 5.0), M_P=(0.1, 200.0), S_theta_P=(-100.0, 100.0), I_theta_P=(1e-2, 100.0),
    I_psi_P=(1e-2, 100.0), S_alpha_P=(-100.0, 100.0), I_alpha_P=(1e-2, 200.0),
    I_theta_alpha_P=(-100.0, 100.0), Omega=(-400.0, 400.0), K_theta=(1.0, 1e6),
    K_psi=(1.0, 1e6), g_theta=(0.0, 0.2), g_psi=(0.0, 0.2), omega=(0.1, 500.0),
    zeta_theta=(0.0, 0.2), zeta_psi=(0.0, 0.2),
)


def call(func, p: dict) -> np.ndarray:
    """Call a generated function with the arguments it declares, taken from `p`."""
    names = sys.modules[func.__module__].OUTPUTS[func.__name__][0]
    return func(*(p[n] for n in names))


def close(actual: np.ndarray, expected, what: str, magnitude: float | None = None) -> None:
    """actual == expected to rtol 1e-12, plus an absolute slack of 1e-13 × `magnitude` (a bound
    on the size of the terms that are summed, so exact cancellations do not fail on rounding)."""
    expected = np.asarray(expected, dtype=float)
    assert actual.shape == expected.shape, what
    if magnitude is None:
        magnitude = float(np.max(np.abs(expected)))
    np.testing.assert_allclose(actual, expected, rtol=1e-12, atol=1e-13 * magnitude, err_msg=what)


def aero_magnitude(p: dict) -> float:
    """Upper bound of any single term of the aerodynamic matrices (k·C·lengths/speeds)."""
    k1, k2 = ks(p)
    e = max(abs(p[k]) for k in ("e_theta", "e_psi", "e_alpha") if k in p)
    cmax = max(abs(p[d]) for d in DERIVS)
    return (k1 + k2) * cmax * (1 + (e + p["R"] + 1) / p["V"]) ** 2 * (1 + e)


def ks(p: dict) -> tuple[float, float]:
    S = np.pi * p["R"] ** 2
    return 0.5 * p["rho"] * p["V"] ** 2 * S, p["rho"] * p["V"] ** 2 * S * p["R"]


# ----------------------------------------------------------------------------- chapter 6 oracles


def ch6_Ms(p):  # (6.12)
    return [[p["I_Y"], 0.0], [0.0, p["I_Z"]]]


def ch6_Cs(p, c_theta, c_psi):  # (6.13) with the damping coefficients given
    IO = p["I_X"] * p["Omega"]
    return [[c_theta, IO], [-IO, c_psi]]


def ch6_Ks(p):
    # erratum: (6.14) prints K_tt in the (2,2) entry; it is the yaw stiffness K_ψ (typo, cf. 6.3,
    # 6.8 and 8.19).
    return [[p["K_theta"], 0.0], [0.0, p["K_psi"]]]


def ch6_Ma(p):  # (6.15)
    k1, k2 = ks(p)
    R, V, et, ep = p["R"], p["V"], p["e_theta"], p["e_psi"]
    return [
        [-k2 * p["Cm_q"] * R / V * et / V + et * k1 * p["CZ_q"] * R / V * et / V,
         -k2 * p["Cm_r"] * R / V * ep / V + et * k1 * p["CZ_r"] * R / V * ep / V],
        [-k2 * p["Cn_q"] * R / V * et / V - ep * k1 * p["CY_q"] * R / V * et / V,
         -k2 * p["Cn_r"] * R / V * ep / V - ep * k1 * p["CY_r"] * R / V * ep / V],
    ]


def ch6_Ca(p):  # (6.16)
    k1, k2 = ks(p)
    R, V, et, ep = p["R"], p["V"], p["e_theta"], p["e_psi"]
    return [
        [-k2 * p["Cm_theta"] * et / V + k2 * p["Cm_q"] * R / V
         + et * k1 * p["CZ_theta"] * et / V - et * k1 * p["CZ_q"] * R / V,
         -k2 * p["Cm_psi"] * ep / V + k2 * p["Cm_r"] * R / V
         + et * k1 * p["CZ_psi"] * ep / V - et * k1 * p["CZ_r"] * R / V],
        [-k2 * p["Cn_theta"] * et / V + k2 * p["Cn_q"] * R / V
         - ep * k1 * p["CY_theta"] * et / V + ep * k1 * p["CY_q"] * R / V,
         -k2 * p["Cn_psi"] * ep / V + k2 * p["Cn_r"] * R / V
         - ep * k1 * p["CY_psi"] * ep / V + ep * k1 * p["CY_r"] * R / V],
    ]


def ch6_Ka(p):  # (6.17)
    k1, k2 = ks(p)
    et, ep = p["e_theta"], p["e_psi"]
    return [
        [k2 * p["Cm_theta"] - et * k1 * p["CZ_theta"], k2 * p["Cm_psi"] - et * k1 * p["CZ_psi"]],
        [k2 * p["Cn_theta"] + ep * k1 * p["CY_theta"], k2 * p["Cn_psi"] + ep * k1 * p["CY_psi"]],
    ]


@SETTINGS
@given(CH6_STRUCT)
def test_ch6_structural_matrices(p):
    close(call(g6.Ms, p), ch6_Ms(p), "Ms (6.12)")
    close(call(g6.Ks, p), ch6_Ks(p), "Ks (6.14)")
    hyst = (p["K_theta"] * p["g_theta"] / p["omega"], p["K_psi"] * p["g_psi"] / p["omega"])
    close(call(g6.Cs_hysteretic, p), ch6_Cs(p, *hyst), "Cs hysteretic (6.13)")
    # (6.6): K g/ω → 2 ζ ω_θ I_Y with ω_θ = √(K_θ/I_Y); likewise in yaw with I_Z.
    visc = (2 * p["zeta_theta"] * np.sqrt(p["K_theta"] / p["I_Y"]) * p["I_Y"],
            2 * p["zeta_psi"] * np.sqrt(p["K_psi"] / p["I_Z"]) * p["I_Z"])
    close(call(g6.Cs_viscous, p), ch6_Cs(p, *visc), "Cs viscous (6.6, 6.13)")
    close(call(g6.G, p), ch6_Cs(p, 0.0, 0.0), "G (6.8)")


@SETTINGS
@given(CH6_AERO)
def test_ch6_aerodynamic_matrices(p):
    close(call(g6.Ma, p), ch6_Ma(p), "Ma (6.15)", aero_magnitude(p))
    close(call(g6.Ca, p), ch6_Ca(p), "Ca (6.16)", aero_magnitude(p))
    close(call(g6.Ka, p), ch6_Ka(p), "Ka (6.17)", aero_magnitude(p))


# ----------------------------------------------------------------------------- chapter 8 oracles


def ch8_structural(p) -> dict[str, list]:
    IO = p["I_Omega"] * p["Omega"]
    return {
        "As": [[p["I_theta_P"], 0.0], [0.0, p["I_psi_P"]]],  # (8.15)
        "Bs": [[p["S_theta_P"], p["I_theta_alpha_P"]], [0.0, 0.0]],  # (8.16)
        "Cs_hysteretic": [[p["K_theta"] * p["g_theta"] / p["omega"], IO],  # (8.17)
                          [-IO, p["K_psi"] * p["g_psi"] / p["omega"]]],
        # (8.17) with the viscous reading of (8.10)/(6.6): ω_θ = √(K_θ/I_θ,P), ω_ψ = √(K_ψ/I_ψ,P)
        "Cs_viscous": [[2 * p["zeta_theta"] * np.sqrt(p["K_theta"] / p["I_theta_P"])
                        * p["I_theta_P"], IO],
                       [-IO, 2 * p["zeta_psi"] * np.sqrt(p["K_psi"] / p["I_psi_P"])
                        * p["I_psi_P"]]],
        "Ds": [[0.0, 0.0], [0.0, -IO]],  # (8.18)
        "Es": [[p["K_theta"], 0.0], [0.0, p["K_psi"]]],  # (8.19)
        "Fs": [[p["S_theta_P"], 0.0], [p["I_theta_alpha_P"], 0.0]],  # (8.21)
        "Gs": [[p["M_P"], p["S_alpha_P"]], [p["S_alpha_P"], p["I_alpha_P"]]],  # (8.22)
        "Hs": [[0.0, 0.0], [0.0, IO]],  # (8.23)
    }


def ch8_propeller_aero(p) -> dict[str, list]:
    k1, k2 = ks(p)
    R, V, et, ep, ea = p["R"], p["V"], p["e_theta"], p["e_psi"], p["e_alpha"]
    c = p
    return {
        "Aa": [  # (8.28)
            [k2 * c["Cm_q"] * R / V * et / V + et * k1 * c["CZ_q"] * R / V * et / V,
             k2 * c["Cm_r"] * R / V * ep / V + et * k1 * c["CZ_r"] * R / V * ep / V],
            [k2 * c["Cn_q"] * R / V * et / V - ep * k1 * c["CY_q"] * R / V * et / V,
             k2 * c["Cn_r"] * R / V * ep / V - ep * k1 * c["CY_r"] * R / V * ep / V],
        ],
        "Ba": [  # (8.29)
            [k2 * c["Cm_q"] * R / V / V + et * k1 * c["CZ_q"] * R / V / V,
             k2 * c["Cm_q"] * R / V * ea / V + et * k1 * c["CZ_q"] * R / V * ea / V],
            [k2 * c["Cn_q"] * R / V / V - ep * k1 * c["CY_q"] * R / V / V,
             k2 * c["Cn_q"] * R / V * ea / V - ep * k1 * c["CY_q"] * R / V * ea / V],
        ],
        "Ca": [  # (8.30)
            [k2 * c["Cm_theta"] * et / V + k2 * c["Cm_q"] * R / V
             + et * k1 * c["CZ_theta"] * et / V + et * k1 * c["CZ_q"] * R / V,
             k2 * c["Cm_psi"] * ep / V + k2 * c["Cm_r"] * R / V
             + et * k1 * c["CZ_psi"] * ep / V + et * k1 * c["CZ_r"] * R / V],
            [k2 * c["Cn_theta"] * et / V + k2 * c["Cn_q"] * R / V
             - ep * k1 * c["CY_theta"] * et / V - ep * k1 * c["CY_q"] * R / V,
             k2 * c["Cn_psi"] * ep / V + k2 * c["Cn_r"] * R / V
             - ep * k1 * c["CY_psi"] * ep / V - ep * k1 * c["CY_r"] * R / V],
        ],
        "Da": [  # (8.31)
            [k2 * c["Cm_theta"] / V + et * k1 * c["CZ_theta"] / V,
             k2 * c["Cm_theta"] * ea / V + k2 * c["Cm_q"] * R / V
             + et * k1 * c["CZ_theta"] * ea / V + et * k1 * c["CZ_q"] * R / V],
            [k2 * c["Cn_theta"] / V - ep * k1 * c["CY_theta"] / V,
             k2 * c["Cn_theta"] * ea / V + k2 * c["Cn_q"] * R / V
             - ep * k1 * c["CY_theta"] * ea / V - ep * k1 * c["CY_q"] * R / V],
        ],
        "Ea": [  # (8.32)
            [k2 * c["Cm_theta"] + et * k1 * c["CZ_theta"],
             k2 * c["Cm_psi"] + et * k1 * c["CZ_psi"]],
            [k2 * c["Cn_theta"] - ep * k1 * c["CY_theta"],
             k2 * c["Cn_psi"] - ep * k1 * c["CY_psi"]],
        ],
        "Fa": [  # (8.33)
            [0.0, k2 * c["Cm_theta"] + et * k1 * c["CZ_theta"]],
            [0.0, k2 * c["Cn_theta"] - ep * k1 * c["CY_theta"]],
        ],
    }


def ch8_wing_aero(p) -> dict[str, list]:
    k1, k2 = ks(p)
    R, V, et, ep, ea = p["R"], p["V"], p["e_theta"], p["e_psi"], p["e_alpha"]
    c = p
    return {
        "P1": [  # (8.37)
            [k1 * c["CZ_q"] * R / V * et / V, k1 * c["CZ_r"] * R / V * ep / V],
            [k2 * c["Cm_q"] * R / V * et / V + ea * k1 * c["CZ_q"] * R / V * et / V,
             k2 * c["Cm_r"] * R / V * ep / V + ea * k1 * c["CZ_r"] * R / V * ep / V],
        ],
        "P2": [  # (8.38)
            [k1 * c["CZ_q"] * R / V / V, k1 * c["CZ_q"] * R / V * ea / V],
            [k2 * c["Cm_q"] * R / V / V + ea * k1 * c["CZ_q"] * R / V / V,
             k2 * c["Cm_q"] * R / V * ea / V + ea * k1 * c["CZ_q"] * R / V * ea / V],
        ],
        "P3": [  # (8.39)
            [k1 * c["CZ_theta"] * et / V + k1 * c["CZ_q"] * R / V,
             k1 * c["CZ_psi"] * ep / V + k1 * c["CZ_r"] * R / V],
            [k2 * c["Cm_theta"] * et / V + k2 * c["Cm_q"] * R / V
             + ea * k1 * c["CZ_theta"] * et / V + ea * k1 * c["CZ_q"] * R / V,
             k2 * c["Cm_psi"] * ep / V + k2 * c["Cm_r"] * R / V
             + ea * k1 * c["CZ_psi"] * ep / V + ea * k1 * c["CZ_r"] * R / V],
        ],
        "P4": [  # (8.40)
            [k1 * c["CZ_theta"] / V, k1 * c["CZ_theta"] * ea / V + k1 * c["CZ_q"] * R / V],
            [k2 * c["Cm_theta"] / V + ea * k1 * c["CZ_theta"] / V,
             k2 * c["Cm_theta"] * ea / V + k2 * c["Cm_q"] * R / V
             + ea * k1 * c["CZ_theta"] * ea / V + ea * k1 * c["CZ_q"] * R / V],
        ],
        "P5": [  # (8.41)
            [k1 * c["CZ_theta"], k1 * c["CZ_psi"]],
            [k2 * c["Cm_theta"] + ea * k1 * c["CZ_theta"],
             k2 * c["Cm_psi"] + ea * k1 * c["CZ_psi"]],
        ],
        "P6": [  # (8.42)
            [0.0, k1 * c["CZ_theta"]],
            [0.0, k2 * c["Cm_theta"] + ea * k1 * c["CZ_theta"]],
        ],
    }


@SETTINGS
@given(CH8_STRUCT)
def test_ch8_propeller_structural_rows(p):
    expected = ch8_structural(p)
    for name in ("As", "Bs", "Cs_hysteretic", "Cs_viscous", "Ds", "Es"):
        close(call(getattr(g8, name), p), expected[name], f"{name} (8.15–8.19)")


@SETTINGS
@given(CH8_STRUCT)
def test_ch8_wing_structural_rows(p):
    expected = ch8_structural(p)
    for name in ("Fs", "Gs", "Hs"):
        close(call(getattr(g8, name), p), expected[name], f"{name} (8.21–8.23)")


@SETTINGS
@given(CH8_AERO)
def test_ch8_propeller_aerodynamic_matrices(p):
    expected = ch8_propeller_aero(p)
    for name in ("Aa", "Ba", "Ca", "Da", "Ea", "Fa"):
        close(call(getattr(g8, name), p), expected[name], f"{name} (8.28–8.33)",
              aero_magnitude(p))


@SETTINGS
@given(CH8_AERO)
def test_ch8_propeller_loads_on_wing(p):
    expected = ch8_wing_aero(p)
    for name in ("P1", "P2", "P3", "P4", "P5", "P6"):
        close(call(getattr(g8, name), p), expected[name], f"{name} (8.37–8.42)",
              aero_magnitude(p))


@SETTINGS
@given(strat(M_P=(0.1, 200.0), S_theta_P=(-100.0, 100.0), I_theta_P=(1e-2, 100.0),
             l_theta=(-2.0, 2.0), a_P_b_P=(-1.0, 1.0), e_theta=(-3.0, 1.0)))
def test_ch8_inertia_identities_and_e_alpha(p):
    d = p["l_theta"] - p["a_P_b_P"]
    M, S, I = p["M_P"], p["S_theta_P"], p["I_theta_P"]
    expected = [[S + d * M],  # (8.5) S_α,P
                [I + d**2 * M + 2 * d * S],  # (8.5) I_α,P
                [I + d * S]]  # (8.6) I_θα,P
    close(call(g8.inertia, p), expected, "inertia (8.5–8.6)",
          I + d**2 * M + 2 * abs(d * S))
    close(call(g8.e_alpha_geometry, p), [[p["e_theta"] + p["l_theta"] - p["a_P_b_P"]]],
          "e_alpha (8.35)", abs(p["e_theta"]) + abs(p["l_theta"]) + abs(p["a_P_b_P"]))


def with_phi(block, rows: bool, cols: bool) -> np.ndarray:
    """Insert the zero bending-slope φ row/column between h and α (appendix C layout)."""
    b = np.asarray(block, dtype=float)
    if cols:
        b = np.insert(b, 1, 0.0, axis=-1)
    if rows:
        b = np.insert(b, 1, 0.0, axis=-2)
    return b


@SETTINGS
@given(CH8_STRUCT, CH8_AERO)
def test_appendix_c_element_blocks(ps, pa):
    """Appendix C restructures the blocks onto the node dofs [h, φ, α]: C.6, C.8, C.11, C.13,
    C.15 (propeller rows) and C.20, C.22, C.24, C.27, C.29, C.31, C.33, C.35, C.37 (wing rows),
    transcribed here with their printed zero φ rows/columns."""
    k1, k2 = ks(pa)
    R, V, et, ep, ea = pa["R"], pa["V"], pa["e_theta"], pa["e_psi"], pa["e_alpha"]
    c = pa
    IO = ps["I_Omega"] * ps["Omega"]
    structural = {  # name: (printed 3-dof block, rows carry φ, cols carry φ)
        # C.6
        "Bs": ([[ps["S_theta_P"], 0.0, ps["I_theta_alpha_P"]], [0.0, 0.0, 0.0]], False, True),
        "Ds": ([[0.0, 0.0, 0.0], [0.0, 0.0, -IO]], False, True),  # C.8
        # C.20
        "Fs": ([[ps["S_theta_P"], 0.0], [0.0, 0.0], [ps["I_theta_alpha_P"], 0.0]], True, False),
        "Gs": ([[ps["M_P"], 0.0, ps["S_alpha_P"]], [0.0, 0.0, 0.0],
                [ps["S_alpha_P"], 0.0, ps["I_alpha_P"]]], True, True),  # C.22
        "Hs": ([[0.0, 0.0], [0.0, 0.0], [0.0, IO]], True, False),  # C.24
    }
    aero = {
        "Ba": ([[k2 * c["Cm_q"] * R / V / V + et * k1 * c["CZ_q"] * R / V / V, 0.0,  # C.11
                 k2 * c["Cm_q"] * R / V * ea / V + et * k1 * c["CZ_q"] * R / V * ea / V],
                [k2 * c["Cn_q"] * R / V / V - ep * k1 * c["CY_q"] * R / V / V, 0.0,
                 k2 * c["Cn_q"] * R / V * ea / V - ep * k1 * c["CY_q"] * R / V * ea / V]],
               False, True),
        "Da": ([[k2 * c["Cm_theta"] / V + et * k1 * c["CZ_theta"] / V, 0.0,  # C.13
                 k2 * c["Cm_theta"] * ea / V + k2 * c["Cm_q"] * R / V
                 + et * k1 * c["CZ_theta"] * ea / V + et * k1 * c["CZ_q"] * R / V],
                [k2 * c["Cn_theta"] / V - ep * k1 * c["CY_theta"] / V, 0.0,
                 k2 * c["Cn_theta"] * ea / V + k2 * c["Cn_q"] * R / V
                 - ep * k1 * c["CY_theta"] * ea / V - ep * k1 * c["CY_q"] * R / V]],
               False, True),
        # erratum: (C.15) prints e_w in the (2,3) entry; it is e_ψ (typo, cf. 8.33).
        "Fa": ([[0.0, 0.0, k2 * c["Cm_theta"] + et * k1 * c["CZ_theta"]],  # C.15
                [0.0, 0.0, k2 * c["Cn_theta"] - ep * k1 * c["CY_theta"]]], False, True),
        # C.27
        "P1": ([[k1 * c["CZ_q"] * R / V * et / V, k1 * c["CZ_r"] * R / V * ep / V], [0.0, 0.0],
                [k2 * c["Cm_q"] * R / V * et / V + ea * k1 * c["CZ_q"] * R / V * et / V,
                 k2 * c["Cm_r"] * R / V * ep / V + ea * k1 * c["CZ_r"] * R / V * ep / V]],
               True, False),
        "P2": ([[k1 * c["CZ_q"] * R / V / V, 0.0, k1 * c["CZ_q"] * R / V * ea / V],  # C.29
                [0.0, 0.0, 0.0],
                [k2 * c["Cm_q"] * R / V / V + ea * k1 * c["CZ_q"] * R / V / V, 0.0,
                 k2 * c["Cm_q"] * R / V * ea / V + ea * k1 * c["CZ_q"] * R / V * ea / V]],
               True, True),
        "P3": ([[k1 * c["CZ_theta"] * et / V + k1 * c["CZ_q"] * R / V,  # C.31
                 k1 * c["CZ_psi"] * ep / V + k1 * c["CZ_r"] * R / V], [0.0, 0.0],
                [k2 * c["Cm_theta"] * et / V + k2 * c["Cm_q"] * R / V
                 + ea * k1 * c["CZ_theta"] * et / V + ea * k1 * c["CZ_q"] * R / V,
                 k2 * c["Cm_psi"] * ep / V + k2 * c["Cm_r"] * R / V
                 + ea * k1 * c["CZ_psi"] * ep / V + ea * k1 * c["CZ_r"] * R / V]],
               True, False),
        "P4": ([[k1 * c["CZ_theta"] / V, 0.0,  # C.33 (printed with the label C.32)
                 k1 * c["CZ_theta"] * ea / V + k1 * c["CZ_q"] * R / V], [0.0, 0.0, 0.0],
                [k2 * c["Cm_theta"] / V + ea * k1 * c["CZ_theta"] / V, 0.0,
                 k2 * c["Cm_theta"] * ea / V + k2 * c["Cm_q"] * R / V
                 + ea * k1 * c["CZ_theta"] * ea / V + ea * k1 * c["CZ_q"] * R / V]],
               True, True),
        "P5": ([[k1 * c["CZ_theta"], k1 * c["CZ_psi"]], [0.0, 0.0],  # C.35
                [k2 * c["Cm_theta"] + ea * k1 * c["CZ_theta"],
                 k2 * c["Cm_psi"] + ea * k1 * c["CZ_psi"]]], True, False),
        "P6": ([[0.0, 0.0, k1 * c["CZ_theta"]], [0.0, 0.0, 0.0],  # C.37
                [0.0, 0.0, k2 * c["Cm_theta"] + ea * k1 * c["CZ_theta"]]], True, True),
    }
    for table, p in ((structural, ps), (aero, pa)):
        for name, (printed, rows, cols) in table.items():
            close(with_phi(call(getattr(g8, name), p), rows, cols), printed,
                  f"appendix C block for {name}", aero_magnitude(p) if p is pa else None)
