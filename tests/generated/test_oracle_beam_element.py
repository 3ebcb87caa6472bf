"""Oracle: the generated beam element equals the thesis's printed matrices (7.11–7.15).

The oracles below are transcribed by hand from the thesis, in its own block layout
(bending [h1, φ1, h2, φ2], torsion [α1, α2]), with the misprints corrected as recorded in
docs/errata.md:
  7.11  entry (2,3) printed 13/430, derived 13/420 (the matrix must be symmetric: (3,2) is 13/420)
  7.14  printed as EI·[12EI/l², ...]: EI appears twice and the (1,1) power is l² instead of l³
  7.10  K_t printed with dN/dξ; the torsion shape functions T (7.8) belong there, which is what
        the printed result 7.15 (GJ/l [1, −1; −1, 1]) is.
"""
import numpy as np
from hypothesis import given
from hypothesis import strategies as st

from propwhirl.generated import beam_element

BEND = [0, 1, 3, 4]  # h1, φ1, h2, φ2 in the generated [h1, φ1, α1, h2, φ2, α2]
TORS = [2, 5]        # α1, α2

pos = st.floats(min_value=1e-2, max_value=1e3, allow_nan=False)
length = st.floats(min_value=0.05, max_value=20.0)
offset = st.floats(min_value=-0.5, max_value=0.5)


def Mb_oracle(l, m):  # 7.11 (13/430 corrected to 13/420)
    return np.array([
        [13 / 35 * l * m, 11 / 210 * l**2 * m, 9 / 70 * l * m, -13 / 420 * l**2 * m],
        [11 / 210 * l**2 * m, 1 / 105 * l**3 * m, 13 / 420 * l**2 * m, -1 / 140 * l**3 * m],
        [9 / 70 * l * m, 13 / 420 * l**2 * m, 13 / 35 * l * m, -11 / 210 * l**2 * m],
        [-13 / 420 * l**2 * m, -1 / 140 * l**3 * m, -11 / 210 * l**2 * m, 1 / 105 * l**3 * m],
    ])


def Mt_oracle(l, Ip):  # 7.12
    return np.array([[Ip * l / 3, Ip * l / 6], [Ip * l / 6, Ip * l / 3]])


def Mtb_oracle(l, m, xb):  # 7.13, rows α1, α2; columns h1, φ1, h2, φ2
    return m * xb * np.array([
        [7 / 20 * l, 1 / 20 * l**2, 3 / 20 * l, -1 / 30 * l**2],
        [3 / 20 * l, 1 / 30 * l**2, 7 / 20 * l, -1 / 20 * l**2],
    ])


def Kb_oracle(l, EI):  # 7.14 as it should read
    return EI * np.array([
        [12 / l**3, 6 / l**2, -12 / l**3, 6 / l**2],
        [6 / l**2, 4 / l, -6 / l**2, 2 / l],
        [-12 / l**3, -6 / l**2, 12 / l**3, -6 / l**2],
        [6 / l**2, 2 / l, -6 / l**2, 4 / l],
    ])


def Kt_oracle(l, GJ):  # 7.15
    return GJ / l * np.array([[1.0, -1.0], [-1.0, 1.0]])


@given(l=length, m=pos)
def test_bending_mass_matches_7_11(l, m):
    M = beam_element.mass(l, m, 1.0, 0.0)
    np.testing.assert_allclose(M[np.ix_(BEND, BEND)], Mb_oracle(l, m), rtol=1e-12, atol=0)


@given(l=length, Ip=pos)
def test_torsion_mass_matches_7_12(l, Ip):
    M = beam_element.mass(l, 1.0, Ip, 0.0)
    np.testing.assert_allclose(M[np.ix_(TORS, TORS)], Mt_oracle(l, Ip), rtol=1e-12)


@given(l=length, m=pos, xb=offset)
def test_coupling_mass_matches_7_13(l, m, xb):
    M = beam_element.mass(l, m, 1.0, xb)
    scale = m * l * max(l, 1.0) ** 2
    np.testing.assert_allclose(M[np.ix_(TORS, BEND)], Mtb_oracle(l, m, xb), rtol=1e-12, atol=1e-14 * scale)
    np.testing.assert_allclose(M[np.ix_(BEND, TORS)], Mtb_oracle(l, m, xb).T, rtol=1e-12, atol=1e-14 * scale)


@given(l=length, EI=pos, GJ=pos)
def test_stiffness_matches_7_14_7_15(l, EI, GJ):
    K = beam_element.stiffness(l, EI, GJ)
    np.testing.assert_allclose(K[np.ix_(BEND, BEND)], Kb_oracle(l, EI), rtol=1e-12)
    np.testing.assert_allclose(K[np.ix_(TORS, TORS)], Kt_oracle(l, GJ), rtol=1e-12)
    assert np.all(K[np.ix_(BEND, TORS)] == 0) and np.all(K[np.ix_(TORS, BEND)] == 0)


@given(l=st.lists(length, min_size=1, max_size=5), m=pos)
def test_vectorised_over_elements(l, m):
    """Arrays of element properties in, all element matrices out (..., 6, 6)."""
    l = np.array(l)
    M = beam_element.mass(l, m, 0.3, 0.01)
    assert M.shape == (l.size, 6, 6)
    for i, li in enumerate(l):
        np.testing.assert_array_equal(M[i], beam_element.mass(li, m, 0.3, 0.01))
