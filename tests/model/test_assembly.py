"""Physics of the beam element and the assembled cantilever (§7.1, §7.4.1)."""
import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from propwhirl.model.structure.assembly import wing_structure
from propwhirl.cases.ch07_patil import patil_wing
from propwhirl.generated import beam_element
from propwhirl.analysis.vibration import classify_wing_modes

pos = st.floats(min_value=1e-2, max_value=1e3)


@given(l=st.floats(0.05, 10.0), m=pos, Ip=pos, frac=st.floats(-0.9, 0.9), EI=pos, GJ=pos)
def test_element_mass_symmetric_positive_definite_stiffness_symmetric(l, m, Ip, frac, EI, GJ):
    # a physical static unbalance satisfies S² < m·I_p (parallel-axis theorem)
    xb = frac * np.sqrt(Ip / m)
    M = beam_element.mass(l, m, Ip, xb)
    K = beam_element.stiffness(l, EI, GJ)
    np.testing.assert_allclose(M, M.T, rtol=1e-13, atol=0)
    np.testing.assert_allclose(K, K.T, rtol=1e-13, atol=0)
    assert np.linalg.eigvalsh(M).min() > 0
    # the free element has exactly three rigid-body modes: heave, roll (bending slope), twist
    ev = np.linalg.eigvalsh(K)
    assert np.sum(np.abs(ev) < 1e-9 * np.abs(ev).max()) == 3


def test_global_mass_positive_definite_and_rayleigh_damping():
    wing = patil_wing(n_elements=6)
    M, C, K = wing_structure(wing)
    assert np.linalg.eigvalsh(M).min() > 0
    assert np.all(C == 0)
    from dataclasses import replace
    M2, C2, K2 = wing_structure(replace(wing, rayleigh=(0.5, 0.01)))
    np.testing.assert_allclose(C2, 0.5 * M2 + 0.01 * K2)


def analytical_patil():
    """Uniform cantilever: bending (7.60) and torsion (7.62) frequencies [rad/s]."""
    EI, GJ, m, Ip, L = 2e4, 1e4, 0.75, 0.1, 16.0
    bend = np.array([1.8751, 4.69409, 7.85476]) ** 2 * np.sqrt(EI / (m * L**4))
    tors = np.pi / (2 * L) * np.sqrt(GJ / Ip)
    return bend, tors


@pytest.mark.parametrize("n", [2, 3, 5, 10, 20])
def test_frequencies_above_exact_and_converging(n):
    bend, tors = analytical_patil()
    modes = dict(classify_wing_modes(patil_wing(n_elements=n), count=6))
    fem_b = np.array([modes.get(f"bending {i}", np.inf) for i in (1, 2, 3)])
    # Rayleigh–Ritz with consistent mass: frequencies are upper bounds
    assert np.all(fem_b[:2] >= bend[:2] * (1 - 1e-5))
    assert modes["torsion 1"] >= tors * (1 - 1e-9)


def test_convergence_to_analytical_frequencies():
    bend, tors = analytical_patil()
    errors = []
    for n in (4, 8, 16):
        modes = dict(classify_wing_modes(patil_wing(n_elements=n), count=6))
        fem = np.array([modes["bending 1"], modes["bending 2"], modes["bending 3"], modes["torsion 1"]])
        errors.append(np.abs(fem / np.r_[bend, tors] - 1))
    errors = np.array(errors)
    assert np.all(np.diff(errors, axis=0) < 0)  # monotone convergence in every mode
    # linear torsion elements: error ∝ 1/n² → quarter per doubling
    ratio = errors[1, 3] / errors[2, 3]
    assert 3.5 < ratio < 4.5
    assert errors[-1].max() < 2e-3
