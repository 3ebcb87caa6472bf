"""Physical properties of the generated propeller models (thesis chapters 6 and 8).

- the structural mass over [θ, ψ, h_P, α_P] is symmetric and positive semi-definite, singular
  only along the "still shaft" motion, and positive definite once the wing node has mass;
- the gyroscopic matrices are skew-symmetric, the damping part symmetric and dissipative;
- Ω = 0 removes every pitch–yaw coupling of the structural matrices;
- with h_P = α_P = 0 chapter 8 reduces to chapter 6 with e_θ(ch.6) = −e_θ(ch.8);
- a motion that leaves the shaft still produces no aerodynamic load and no virtual work;
- the inertia parameters of Tables 9.4, 11.1, 11.3, 11.5 follow from the two point masses.
"""
from __future__ import annotations

import sys

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from propwhirl.generated import prop_flexwing as g8
from propwhirl.generated import prop_rigid as g6
from propwhirl.reproduce.harness import load_references

SETTINGS = settings(max_examples=40, deadline=None)
DERIVS = tuple(f"{c}_{v}" for c in ("CZ", "Cm", "CY", "Cn") for v in ("theta", "psi", "q", "r"))
THETA, PSI, H, ALPHA = range(4)


def fl(lo: float, hi: float) -> st.SearchStrategy[float]:
    return st.floats(lo, hi, allow_nan=False, allow_infinity=False, allow_subnormal=False)


def call(func, p: dict) -> np.ndarray:
    names = sys.modules[func.__module__].OUTPUTS[func.__name__][0]
    return func(*(p[n] for n in names))


def point_mass_parameters(m, x, l_theta, l_psi, ab) -> dict:
    """Inertia parameters (8.5–8.6) as plain sums over point masses m at shaft positions x."""
    m, x = np.asarray(m, float), np.asarray(x, float)
    return dict(
        M_P=m.sum(),
        S_theta_P=(m * (x - l_theta)).sum(),
        I_theta_P=(m * (x - l_theta) ** 2).sum(),
        I_psi_P=(m * (x - l_psi) ** 2).sum(),
        S_alpha_P=(m * (x - ab)).sum(),
        I_alpha_P=(m * (x - ab) ** 2).sum(),
        I_theta_alpha_P=(m * (x - ab) * (x - l_theta)).sum(),
        l_theta=l_theta,
        a_P_b_P=ab,
    )


@st.composite
def shaft(draw) -> dict:
    """2–5 point masses on the shaft at distinct positions (≥ 5 cm apart), pivots, elastic axis."""
    n = draw(st.integers(2, 5))
    m = draw(st.lists(fl(0.5, 50.0), min_size=n, max_size=n))
    x0 = draw(fl(-3.0, 0.0))
    gaps = draw(st.lists(fl(0.05, 0.8), min_size=n - 1, max_size=n - 1))
    x = np.concatenate([[x0], x0 + np.cumsum(gaps)])
    l_theta, l_psi, ab = draw(fl(-1.0, 1.0)), draw(fl(-1.0, 1.0)), draw(fl(-0.5, 0.5))
    p = point_mass_parameters(m, x, l_theta, l_psi, ab)
    p.update(
        x=x, m=np.asarray(m), l_psi=l_psi,
        I_Omega=draw(fl(0.01, 5.0)), Omega=draw(fl(-400.0, 400.0)),
        K_theta=draw(fl(1e2, 1e6)), K_psi=draw(fl(1e2, 1e6)),
        g_theta=draw(fl(0.0, 0.1)), g_psi=draw(fl(0.0, 0.1)), omega=draw(fl(1.0, 300.0)),
        zeta_theta=draw(fl(0.0, 0.1)), zeta_psi=draw(fl(0.0, 0.1)),
    )
    # Hub at the foremost mass: signed, rearward-positive distances (8.35).
    p["e_theta"] = x[0] - l_theta
    p["e_psi"] = x[0] - l_psi
    return p


AERO = st.fixed_dictionaries(
    dict(rho=fl(0.05, 1.5), V=fl(5.0, 300.0), R=fl(0.2, 3.0), **{d: fl(-3.0, 3.0) for d in DERIVS})
)


def aero_bound(p: dict) -> float:
    """Upper bound of any single term of the aerodynamic matrices (k·C·lengths/speeds)."""
    S = np.pi * p["R"] ** 2
    k = p["rho"] * p["V"] ** 2 * S * (0.5 + p["R"])
    e = max(abs(p[n]) for n in ("e_theta", "e_psi", "e_alpha") if n in p)
    cmax = max(abs(p[d]) for d in DERIVS)
    return k * cmax * (1 + (e + p["R"] + 1) / p["V"]) ** 2 * (1 + e)


def mass4(p) -> np.ndarray:
    """Structural mass over [θ, ψ, h_P, α_P] assembled from A_s, B_s, F_s, G_s (8.13)."""
    return np.block([[call(g8.As, p), call(g8.Bs, p)], [call(g8.Fs, p), call(g8.Gs, p)]])


def damping4(p, reading: str = "hysteretic") -> np.ndarray:
    """Structural damping over [θ, ψ, h_P, α_P] from C_s, D_s, H_s (8.13)."""
    Cs = call(getattr(g8, f"Cs_{reading}"), p)
    return np.block([[Cs, call(g8.Ds, p)], [call(g8.Hs, p), np.zeros((2, 2))]])


def aero4(p) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Aerodynamic (mass, damping, stiffness) over [θ, ψ, h_P, α_P] from (8.27) and (8.36)."""
    def blk(a, b, c, d):
        return np.block([[call(a, p), call(b, p)], [call(c, p), call(d, p)]])
    return (blk(g8.Aa, g8.Ba, g8.P1, g8.P2), blk(g8.Ca, g8.Da, g8.P3, g8.P4),
            blk(g8.Ea, g8.Fa, g8.P5, g8.P6))


def still_shaft(p) -> np.ndarray:
    """[θ, ψ, h_P, α_P] = [1, 0, l_θ − a_P b_P, −1]: wing node and pivot move, shaft does not."""
    return np.array([1.0, 0.0, p["l_theta"] - p["a_P_b_P"], -1.0])


@SETTINGS
@given(shaft(), fl(0.1, 50.0), fl(0.01, 20.0), fl(-0.9, 0.9))
def test_structural_mass_symmetric_psd_and_pd_with_wing(p, m_w, I_w, r):
    M = mass4(p)
    np.testing.assert_array_equal(M, M.T)
    lam = np.linalg.eigvalsh(M)
    scale = lam[-1]
    # Point masses on one axis give the z-motion two freedoms (translation, rotation) for the
    # three coordinates θ, h_P, α_P: exactly one zero eigenvalue, along the still-shaft motion.
    assert lam[0] > -1e-10 * scale
    assert abs(lam[0]) < 1e-10 * scale
    assert lam[1] > 1e-8 * scale
    n = still_shaft(p)
    np.testing.assert_allclose(M @ n, 0.0, atol=1e-10 * scale)
    # Kinetic energy of the point masses equals ½ q̇ᵀ M q̇ for any rates.
    rates = np.array([0.3, -0.7, 1.1, 0.5])
    z = rates[H] + (p["x"] - p["a_P_b_P"]) * rates[ALPHA] + (p["x"] - p["l_theta"]) * rates[THETA]
    y = -(p["x"] - p["l_psi"]) * rates[PSI]
    T_points = 0.5 * np.sum(p["m"] * (z**2 + y**2))
    np.testing.assert_allclose(0.5 * rates @ M @ rates, T_points, rtol=1e-10)
    # Any wing-node mass (positive-definite section mass/inertia) makes the total PD.
    S_w = r * np.sqrt(m_w * I_w)
    total = M.copy()
    total[np.ix_([H, ALPHA], [H, ALPHA])] += [[m_w, S_w], [S_w, I_w]]
    np.linalg.cholesky(total)


@SETTINGS
@given(shaft())
def test_gyroscopic_skew_and_damping_dissipative(p):
    # Chapter 6: G skew, C_s − G the symmetric (diagonal) damping.
    p6 = dict(p, I_X=p["I_Omega"], I_Y=p["I_theta_P"], I_Z=p["I_psi_P"])
    G = call(g6.G, p6)
    np.testing.assert_array_equal(G, -G.T)
    assert G[0, 1] == p["I_Omega"] * p["Omega"]
    for reading in ("hysteretic", "viscous"):
        Cd = getattr(g6, f"Cs_{reading}")
        D = call(Cd, p6) - G
        np.testing.assert_array_equal(D, np.diag(np.diag(D)))
        assert np.all(np.diag(D) >= 0)
    # Chapter 8: the gyroscopic part of C_s + D_s + H_s over [θ, ψ, h_P, α_P] is skew.
    undamped = dict(p, g_theta=0.0, g_psi=0.0, zeta_theta=0.0, zeta_psi=0.0)
    C0 = damping4(undamped)
    np.testing.assert_array_equal(C0, -C0.T)
    IO = p["I_Omega"] * p["Omega"]
    expected = np.zeros((4, 4))
    expected[THETA, PSI] = expected[ALPHA, PSI] = IO
    expected[PSI, THETA] = expected[PSI, ALPHA] = -IO
    np.testing.assert_allclose(C0, expected, rtol=1e-15)
    rates = np.array([0.4, -1.3, 0.8, 2.1])
    assert abs(rates @ C0 @ rates) <= 1e-12 * abs(IO) * rates @ rates  # gyroscopic: no power
    for reading in ("hysteretic", "viscous"):
        C = damping4(p, reading)
        np.testing.assert_allclose((C - C.T) / 2, C0, rtol=1e-15)
        sym = (C + C.T) / 2
        assert np.all(np.linalg.eigvalsh(sym) >= -1e-12 * np.abs(sym).max(initial=1.0))
        np.testing.assert_array_equal(sym[2:, :], 0.0)  # no damping on the wing node here


@SETTINGS
@given(shaft())
def test_no_spin_no_pitch_yaw_coupling(p):
    p = dict(p, Omega=0.0)
    M, C, K = mass4(p), damping4(p), np.block([[call(g8.Es, p), np.zeros((2, 2))],
                                                [np.zeros((2, 4))]])
    others = [THETA, H, ALPHA]
    for A in (M, C, K):
        np.testing.assert_array_equal(A[PSI, others], 0.0)
        np.testing.assert_array_equal(A[others, PSI], 0.0)
    np.testing.assert_array_equal(call(g8.Ds, p), 0.0)
    np.testing.assert_array_equal(call(g8.Hs, p), 0.0)
    p6 = dict(p, I_X=p["I_Omega"], I_Y=p["I_theta_P"], I_Z=p["I_psi_P"])
    for f in (g6.Ms, g6.Cs_hysteretic, g6.Cs_viscous, g6.Ks, g6.G):
        A = call(f, p6)
        assert A[0, 1] == 0.0 and A[1, 0] == 0.0
    # With spin the coupling is there (the test can fail).
    spun = dict(p, Omega=100.0)
    assert damping4(spun)[THETA, PSI] != 0.0


@SETTINGS
@given(shaft(), AERO)
def test_flexible_wing_reduces_to_rigid_wing(p, a):
    """h_P = α_P = 0: the θ, ψ rows of chapter 8 are chapter 6 with e(ch.6) = −e(ch.8)."""
    p8 = dict(p, **a, e_alpha=call(g8.e_alpha_geometry, dict(p, **a))[0, 0])
    p6 = dict(p, **a, I_X=p["I_Omega"], I_Y=p["I_theta_P"], I_Z=p["I_psi_P"],
              e_theta=-p["e_theta"], e_psi=-p["e_psi"])
    pairs = [(g8.As, g6.Ms), (g8.Cs_hysteretic, g6.Cs_hysteretic),
             (g8.Cs_viscous, g6.Cs_viscous), (g8.Es, g6.Ks), (g8.Aa, g6.Ma),
             (g8.Ca, g6.Ca), (g8.Ea, g6.Ka)]
    for f8, f6 in pairs:
        A8, A6 = call(f8, p8), call(f6, p6)
        bound = aero_bound(p8) + np.abs(A6).max()
        np.testing.assert_allclose(A8, A6, rtol=1e-12, atol=1e-13 * bound,
                                   err_msg=f"{f8.__name__} vs {f6.__name__}")


@SETTINGS
@given(shaft(), AERO)
def test_still_shaft_motion_has_no_aerodynamic_load(p, a):
    """Virtual work (8.24) of a displacement that does not move the shaft vanishes, and that
    motion changes neither the effective angles (8.26) nor the loads — given e_α of (8.35)."""
    pa = dict(p, **a)
    pa["e_alpha"] = call(g8.e_alpha_geometry, pa)[0, 0]
    n = still_shaft(pa)
    for A in aero4(pa):
        scale = aero_bound(pa) * (2 + abs(n[H]))
        np.testing.assert_allclose(A @ n, 0.0, atol=1e-13 * scale)  # no load
        np.testing.assert_allclose(n @ A, 0.0, atol=1e-13 * scale)  # no virtual work
    # Gyroscopic and inertial loads vanish as well; only the pivot spring sees the motion.
    np.testing.assert_allclose(damping4(dict(pa, g_theta=0.0, g_psi=0.0)) @ n, 0.0, atol=1e-9)
    # A wrong e_α breaks it (the test can fail).
    wrong = dict(pa, e_alpha=pa["e_alpha"] + 0.1)
    _, Ca, _ = aero4(wrong)
    if abs(a["CZ_theta"]) > 1e-3:
        assert np.abs(Ca @ n).max() > 1e-9 * np.abs(Ca).max()


@SETTINGS
@given(shaft())
def test_inertia_output_matches_point_mass_sums(p):
    got = call(g8.inertia, p)[:, 0]
    expected = [p["S_alpha_P"], p["I_alpha_P"], p["I_theta_alpha_P"]]
    np.testing.assert_allclose(got, expected, rtol=1e-11, atol=1e-11 * max(map(abs, expected)))


# ------------------------------------------------------------- Tables 9.4, 11.1, 11.3, 11.5
ROTOR, MOTOR = 8.0, 35.0  # kg (Table 9.4)


def table_parameters(x_rotor, x_motor, l_theta, ab=0.0) -> dict:
    p = point_mass_parameters([ROTOR, MOTOR], [x_rotor, x_motor], l_theta, l_theta, ab)
    S_a, I_a, I_ta = call(g8.inertia, p)[:, 0]
    e_theta = x_rotor - l_theta
    return dict(I_theta_P=p["I_theta_P"], S_theta_P=p["S_theta_P"], I_theta_alpha_P=I_ta,
                I_alpha_P=I_a, S_alpha_P=S_a, e_theta=e_theta,
                e_alpha=call(g8.e_alpha_geometry, dict(e_theta=e_theta, l_theta=l_theta,
                                                       a_P_b_P=ab))[0, 0])


def test_reference_inertia_values():
    """Ids t9.4/*, t11.3/case1/*, t11.5/case4/* of thesis_values.toml (a_P b_P = 0)."""
    refs = {r.id: r for r in load_references()}
    base = table_parameters(-1.16, -0.86, 0.0)
    case113 = table_parameters(-1.16, -0.86, 0.20)  # pivot moved +0.20 m
    case115 = table_parameters(-1.16 - 0.60, -0.86 - 0.60, -0.60)  # CG and pivot −0.60 m
    computed = {
        "t9.4/I_theta_P": base["I_theta_P"],
        "t9.4/S_theta_P": base["S_theta_P"],
        "t11.3/case1/I_theta_alpha_P": case113["I_theta_alpha_P"],
        "t11.5/case4/I_alpha_P": case115["I_alpha_P"],
    }
    for key, value in computed.items():
        ref = refs[key]
        assert abs(value - ref.target) <= ref.tol * abs(ref.target), (key, value, ref.target)


# (rotor CG, motor CG, l_θ) → printed (e_θ, I_θ,P, S_θ,P, I_θα,P, I_α,P, S_α,P); a_P b_P = 0.
TABLE_ROWS = {
    "9.4 baseline": ((-1.16, -0.86, 0.0), (-1.16, 36.65, -39.38, 36.65, 36.65, -39.38)),
    "11.1 case 1": ((-1.56, -1.26, 0.0), (-1.56, 75.03, -56.58, 75.03, 75.03, -56.58)),
    "11.1 case 2": ((-0.70, -0.40, 0.0), (-0.70, 9.52, -19.60, 9.52, 9.52, -19.60)),
    # Table 11.1 prints the case-3 motor-nacelle CG at −0.40 m, but its inertia values
    # (12.16, −16.28) are those of a motor CG at −0.20 m (at −0.40 m: 16.37, −23.28).
    "11.1 case 3": ((-1.16, -0.20, 0.0), (-1.16, 12.16, -16.28, 12.16, 12.16, -16.28)),
    "11.3 case 1": ((-1.16, -0.86, 0.20), (-1.36, 54.12, -47.98, 44.53, 36.65, -39.39)),
    "11.3 case 2": ((-1.16, -0.86, -0.20), (-0.96, 22.62, -30.78, 28.77, 36.65, -39.38)),
    "11.3 case 3": ((-1.16, -0.86, -0.40), (-0.76, 12.03, -22.18, 20.90, 36.65, -39.38)),
    "11.3 case 4": ((-1.16, -0.86, -0.60), (-0.56, 4.87, -13.58, 13.02, 36.65, -39.38)),
    "11.5 case 1": ((-0.96, -0.66, 0.20), (-1.16, 36.65, -39.38, 28.77, 22.62, -30.78)),
    "11.5 case 2": ((-1.36, -1.06, -0.20), (-1.16, 36.65, -39.38, 44.53, 54.12, -47.98)),
    "11.5 case 3": ((-1.56, -1.26, -0.40), (-1.16, 36.65, -39.38, 52.40, 75.03, -56.58)),
    "11.5 case 4": ((-1.76, -1.46, -0.60), (-1.16, 36.65, -39.38, 60.28, 99.39, -65.18)),
}


@pytest.mark.parametrize("row", sorted(TABLE_ROWS))
def test_tabulated_inertia_parameters(row):
    """Every printed row, recomputed from the two point masses (printed to 2 decimals; 0.5%)."""
    (xr, xm, l_theta), printed = TABLE_ROWS[row]
    p = table_parameters(xr, xm, l_theta)
    names = ("e_theta", "I_theta_P", "S_theta_P", "I_theta_alpha_P", "I_alpha_P", "S_alpha_P")
    for name, value in zip(names, printed):
        assert p[name] == pytest.approx(value, rel=0.005), (row, name, p[name], value)
    # The tables take the elastic axis at mid-chord (a_P b_P = 0): e_α is then the hub position.
    assert p["e_alpha"] == pytest.approx(xr, abs=1e-12)
