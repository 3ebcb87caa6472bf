"""The typical section: time-domain strip aerodynamics against the exact Theodorsen flutter
determinant (an independent frequency-domain solution, V-g method), and structure oracles."""
import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from propwhirl.model.propellers.propeller_aero import theodorsen
from propwhirl.generated import typical_section
from propwhirl.model.systems import FlightCondition, TypicalSection
from propwhirl.validate import InputError

RHO = 1.225


def section(**kw):
    """Hodges & Pierce's example: μ = 20, a = −1/5, x_α = 1/10, r² = 6/25, σ = ω_h/ω_α = 2/5."""
    b = 1.0
    base = dict(b=b, a=-0.2, x_alpha=0.1, r_alpha=np.sqrt(6 / 25), m=20 * np.pi * RHO * b**2,
                omega_h=0.4 * 50.0, omega_alpha=50.0, flight=FlightCondition(RHO))
    base.update(kw)
    return TypicalSection(**base)


def theodorsen_flutter(sec: TypicalSection) -> tuple[float, float]:
    """V-g solution with the exact C(k): returns (flutter speed [m/s], frequency [rad/s])."""
    b, a, rho = sec.b, sec.a, sec.flight.density
    m, S, I = sec.m, sec.m * sec.x_alpha * b, sec.m * (sec.r_alpha * b) ** 2
    M = np.array([[m, S], [S, I]])
    K = np.diag([m * sec.omega_h**2, I * sec.omega_alpha**2])

    def g_and_omega(k):
        C = complex(theodorsen(k))
        V = b / k  # per unit ω: every load term scales with ω² at fixed k
        c = b * (0.5 - a)
        circ = 2 * np.pi * rho * V * b * C * np.array([1j, V + 1j * c])  # × [h, α]
        L = np.pi * rho * b**2 * np.array([-1.0, 1j * V + b * a]) + circ
        Mo = np.pi * rho * b**2 * np.array([-b * a, -1j * V * c + b**2 * (1 / 8 + a**2)]) \
            + b * (a + 0.5) * circ
        A = np.array([-L, Mo])
        lam = np.linalg.eigvals(np.linalg.solve(M + A, K))  # λ = ω²/(1 + i g)
        inv = 1 / lam
        omega2 = 1 / inv.real
        order = np.argsort(omega2)  # follow the modes by frequency
        return (inv.imag * omega2)[order], np.sqrt(omega2)[order]

    from scipy.optimize import brentq

    ks = np.geomspace(2.0, 0.05, 400)
    g = np.array([g_and_omega(k)[0] for k in ks])
    found = []
    for j in range(2):
        s = np.where((g[:-1, j] < 0) & (g[1:, j] >= 0))[0]
        if s.size:
            kf = brentq(lambda k: g_and_omega(k)[0][j], ks[s[0]], ks[s[0] + 1], xtol=1e-12)
            w = g_and_omega(kf)[1][j]
            found.append((w * b / kf, w))
    assert found, "no flutter found"
    return min(found)


def time_domain_flutter(sec: TypicalSection, Vmax: float) -> tuple[float, float]:
    V = np.linspace(1.0, Vmax, 4000)
    lam = np.linalg.eigvals(sec.state_matrix(V))
    re = np.where(np.abs(lam.imag) > 1e-6, lam.real, -np.inf).max(axis=1)
    i = int(np.argmax(re > 0))
    Vf = V[i - 1] - re[i - 1] * (V[i] - V[i - 1]) / (re[i] - re[i - 1])
    row = lam[i]
    j = np.argmax(np.where(np.abs(row.imag) > 1e-6, row.real, -np.inf))
    return Vf, abs(row[j].imag)


@pytest.mark.parametrize("model", ["leishman-nguyen", "wagner"])
def test_flutter_agrees_with_exact_theodorsen_determinant(model):
    sec = section(aero_model=model)
    Vt, wt = theodorsen_flutter(sec)
    Vs, ws = time_domain_flutter(sec, 2 * Vt)
    # Jones' two-pole approximation of C(k) is accurate to ~1 %: flutter speeds agree closely
    assert Vs == pytest.approx(Vt, rel=0.02)
    assert ws == pytest.approx(wt, rel=0.02)
    # Hodges & Pierce's example flutters near U/(b ω_α) ≈ 2.2 (Theodorsen theory)
    assert 2.0 < Vt / (sec.b * sec.omega_alpha) < 2.4


def test_modified_strip_parameters_change_flutter_speed_as_expected():
    base = time_domain_flutter(section(), 400)[0]
    weaker = time_domain_flutter(section(Cla=0.8 * 2 * np.pi), 400)[0]
    assert weaker > base  # less lift, later flutter


@given(m=st.floats(0.1, 1e3), S=st.floats(-5, 5), I=st.floats(0.1, 1e3),
       Kh=st.floats(1.0, 1e6), Ka=st.floats(1.0, 1e6))
def test_structure_matrices(m, S, I, Kh, Ka):
    np.testing.assert_array_equal(typical_section.mass(m, S, I), [[m, S], [S, I]])
    np.testing.assert_array_equal(typical_section.stiffness(Kh, Ka), [[Kh, 0], [0, Ka]])


def test_bad_section_input():
    with pytest.raises(InputError, match="r_alpha"):
        section(r_alpha=0.05)
    with pytest.raises(InputError, match="b = 0"):
        section(b=0.0)
