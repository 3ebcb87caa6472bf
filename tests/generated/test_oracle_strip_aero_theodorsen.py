"""Oracle for the generated exact-Theodorsen harmonic loads (strip_aero.theodorsen_*): for
harmonic motion q̂ e^{iωt}, −ω² M_a + iω C_a(k) + K_a(k) must equal Theodorsen's complex section
loads (7.24–7.27, with the modified strip parameters of 7.64–7.66) typed by hand here."""
import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from propwhirl.generated import strip_aero as sa
from propwhirl.model.aerodynamics.theodorsen import theodorsen


def hand_loads(rho, V, b, a, Cla, ac, k):
    """Complex 2×2 matrix of [Q_h, Q_α] = [−L, M] per unit [ĥ, α̂], by hand."""
    w = k * V / b
    C = complex(theodorsen(k))
    d = Cla / (2 * np.pi) + ac - a
    e = a - ac
    # w = ḣ + Vα + b d α̇  ->  per [ĥ, α̂]
    wv = np.array([1j * w, V + 1j * w * b * d])
    L = np.pi * rho * b**2 * np.array([-w**2, 1j * w * V + b * a * w**2]) + Cla * rho * V * b * C * wv
    M = (np.pi * rho * b**2 * np.array([-a * b * w**2, -1j * w * V * b * d + b**2 * (1 / 8 + a**2) * w**2])
         + Cla * rho * V * b**2 * e * C * wv)
    return np.array([-L, M])


@settings(max_examples=60, deadline=None)
@given(rho=st.floats(0.05, 1.5), V=st.floats(1.0, 300.0), b=st.floats(0.05, 3.0),
       a=st.floats(-1.0, 1.0), Cla=st.floats(1.0, 7.0), ac=st.floats(-1.0, 1.0),
       k=st.floats(1e-3, 5.0))
def test_theodorsen_matrices_are_the_complex_section_loads(rho, V, b, a, Cla, ac, k):
    C = complex(theodorsen(k))
    out = sa.theodorsen_blocks(rho=rho, V=V, b=b, a=a, Cla=Cla, ac=ac, k=k, F=C.real, G=C.imag)
    w = k * V / b
    got = -w**2 * out["theodorsen_M"] + 1j * w * out["theodorsen_C"] + out["theodorsen_K"]
    want = hand_loads(rho, V, b, a, Cla, ac, k)
    np.testing.assert_allclose(got, want, rtol=1e-12, atol=1e-12 * np.abs(want).max())
    # the per-matrix functions equal the block function
    np.testing.assert_array_equal(sa.theodorsen_C(rho, V, b, a, Cla, ac, k, C.real, C.imag),
                                  out["theodorsen_C"])
    np.testing.assert_array_equal(sa.theodorsen_M(rho, b, a), sa.wagner_M(rho, b, a))


def test_quasi_steady_limit():
    """C = 1 at k → 0: the stiffness is the steady lift and moment of α, C_lα ρ V² b [1, b e]."""
    rho, V, b, a, Cla, ac = 1.2, 50.0, 0.7, -0.3, 5.5, -0.45
    K = sa.theodorsen_K(rho, V, b, a, Cla, ac, 1e-9, 1.0, 0.0)
    np.testing.assert_allclose(K[:, 1], Cla * rho * V**2 * b * np.array([-1.0, b * (a - ac)]))
    np.testing.assert_allclose(K[:, 0], 0.0, atol=1e-6)
