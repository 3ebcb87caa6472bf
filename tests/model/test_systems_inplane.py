"""In-plane (chordwise) wing bending (issue 14): assembly, DOF map, physics checks.

* without EI_chordwise nothing changes; with it, a wing without propellers is today's wing plus
  an uncoupled in-plane beam;
* cantilever in-plane frequencies against Euler–Bernoulli: ω_n = (β_n L)² √(EI_c / (m L⁴));
* aerodynamics and damping off, rotor spinning: the spectrum is purely imaginary (energy
  conserved, gyroscopic coupling skew);
* as EI_chordwise grows the critical speeds converge to today's;
* the propeller's side force, yaw and gyroscopic moments reach the in-plane DOFs.
"""
from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest
import scipy.linalg as sla

from propwhirl.analysis.stability import analyse
from propwhirl.cases.ch07_patil import patil_wing
from propwhirl.cases.ch09_baseline import baseline_flight
from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
from propwhirl.model.systems import FlightCondition, PropellerWing
from propwhirl.validate import InputError

BETA_L = np.array([1.8751040687, 4.6940911330, 7.8547574382, 10.9955407349])


def with_inplane(model: PropellerWing, EIc) -> PropellerWing:
    return model.with_(wing=replace(model.wing, EI_chordwise=EIc))


def in_vacuo_hz(model: PropellerWing, idx=None) -> np.ndarray:
    s = model.without_aerodynamics().with_(rotating=False).second_order(np.array([10.0]))
    M, K = s.S1[0], s.S3[0]
    if idx is not None:
        M, K = M[np.ix_(idx, idx)], K[np.ix_(idx, idx)]
    return np.sqrt(np.abs(sla.eigh(K, M, eigvals_only=True))) / (2 * np.pi)


def test_dof_map_names_the_inplane_dofs():
    m = with_inplane(wingtip_propeller_wing(), 1.4e7)
    dm = m.dof_map()
    n = m.wing.n_nodes
    assert dm.n_dof == 5 * (n - 1) + 2
    assert dm.dofs("v").size == n - 1 and dm.dofs("chi").size == n - 1
    i = dm.dofs("chi")[-1]
    assert dm.q_labels[i] == f"node {n - 1} chi" and dm.q_node[i] == n - 1
    assert set(dm.groups()) == {"bending", "torsion", "chordwise", "pitch", "yaw"}
    assert dm.propellers[0].theta == 5 * (n - 1) and dm.propellers[0].psi == 5 * (n - 1) + 1
    assert m.second_order(np.array([50.0])).S1.shape == (1, dm.n_dof, dm.n_dof)


def test_without_propellers_the_planes_are_independent():
    """Patil's wing with its published chordwise rigidity 4e6 N m² (Patil, Hodges & Cesnik
    2001): the bending–torsion block (aerodynamics on) is today's matrix, unchanged, and the
    in-plane block couples to nothing."""
    flight = FlightCondition(0.0889, 300.0)
    m0 = PropellerWing(patil_wing(), flight)
    m1 = PropellerWing(replace(patil_wing(), EI_chordwise=4e6), flight)
    V = np.array([20.0, 35.0])
    s0, s1 = m0.second_order(V), m1.second_order(V)
    nq0 = s0.S1.shape[1]
    for a, b in ((s0.S1, s1.S1), (s0.S2, s1.S2), (s0.S3, s1.S3)):
        np.testing.assert_array_equal(b[:, :nq0, :nq0], a)
        assert not np.any(b[:, :nq0, nq0:]) and not np.any(b[:, nq0:, :nq0])
    np.testing.assert_array_equal(s1.S4[:, :nq0], s0.S4)


def _cantilever_inplane_hz(n_el: int, L=8.0, m=12.0, EIc=3.0e6) -> np.ndarray:
    wing = replace(patil_wing(n_elements=n_el), semi_span=L, mass_per_length=m,
                   polar_inertia=1e-8, EI_chordwise=EIc)
    model = PropellerWing(wing, FlightCondition(1.0, 340.0), wing_aero=False)
    return in_vacuo_hz(model, model.dof_map().dofs("v", "chi"))[:4]


def test_cantilever_inplane_frequencies_match_euler_bernoulli():
    """A uniform cantilever without rotary inertia (tiny polar inertia): the first four
    in-plane frequencies approach (β_n L)² √(EI_c/(m L⁴)) / 2π from above (the consistent-mass
    Hermite element is an upper bound) at the O(h⁴) rate of the cubic element: within 1e-4
    with 20 elements, the error falling 12–20× from 10 to 20 elements."""
    L, m, EIc = 8.0, 12.0, 3.0e6
    exact = BETA_L**2 * np.sqrt(EIc / (m * L**4)) / (2 * np.pi)
    e10 = _cantilever_inplane_hz(10) / exact - 1
    e20 = _cantilever_inplane_hz(20) / exact - 1
    assert np.all(e10 > 0) and np.all(e20 > 0)
    assert np.all(e20 < 1e-4), e20
    assert np.all((e10 / e20 > 12) & (e10 / e20 < 20)), e10 / e20


def test_rotary_inertia_lowers_the_inplane_frequencies():
    """The section's in-plane rotary inertia (ρI_p, thin section) lowers the frequencies
    (Rayleigh beam), the more so the higher the mode."""
    base = replace(patil_wing(), EI_chordwise=4e6)
    idx = PropellerWing(base, baseline_flight(), wing_aero=False).dof_map().dofs("v", "chi")
    g = [in_vacuo_hz(PropellerWing(replace(base, polar_inertia=Ip), baseline_flight(),
                                   wing_aero=False), idx)[:3] for Ip in (1e-8, 10.0)]
    drop = 1 - g[1] / g[0]
    assert np.all(drop > 0) and drop[2] > drop[1] > drop[0]


def test_energy_conserved_without_aerodynamics_and_damping():
    """Aerodynamics off, no wing or mount damping, rotor spinning: the structural system
    M q̈ + G q̇ + K q = 0 with M, K symmetric positive definite and G skew has a purely
    imaginary spectrum (to round-off)."""
    m = wingtip_propeller_wing()
    prop = replace(m.propellers[0].propeller, damping_theta=0.0, damping_psi=0.0)
    m = m.with_(propellers=(replace(m.propellers[0], propeller=prop),))
    m = with_inplane(m, 20 * m.wing.EI).without_aerodynamics()
    s = m.second_order(np.array([150.0]))
    M, C, K = s.S1[0], s.S2[0], s.S3[0]
    np.testing.assert_allclose(M, M.T, rtol=0, atol=1e-12 * np.abs(M).max())
    np.testing.assert_allclose(K, K.T, rtol=0, atol=1e-12 * np.abs(K).max())
    np.testing.assert_allclose(C, -C.T, rtol=0, atol=1e-12 * max(np.abs(C).max(), 1e-300))
    assert np.abs(C).max() > 0                   # the gyroscopic terms are there
    lam = np.linalg.eigvals(m.state_matrix(np.array([150.0]))[0])
    assert np.max(np.abs(lam.real)) < 1e-9 * np.max(np.abs(lam))


def test_propeller_loads_reach_the_inplane_dofs():
    """The χ row of the propeller node carries the side force and yaw moment (stiffness and
    damping depend on V); the gyroscopic coupling with the twist rate is ±I_Ω Ω."""
    m = with_inplane(wingtip_propeller_wing(), 1.4e7)
    dm = m.dof_map()
    node = m.nodes[0]
    chi = dm.wing_dof(node, "chi")
    alpha = dm.wing_dof(node, "alpha")
    psi = dm.propellers[0].psi
    s = m.second_order(np.array([100.0, 200.0]))
    assert abs(s.S3[1, chi, psi]) > 1.5 * abs(s.S3[0, chi, psi]) > 0       # ~ V²
    quiet = m.without_aerodynamics().second_order(np.array([100.0]))
    p = m.propellers[0].propeller
    G = p.I_Omega * p.spin_rate(np.array([100.0]))[0]
    assert quiet.S2[0, alpha, chi] == pytest.approx(G) and quiet.S2[0, chi, alpha] == pytest.approx(-G)


def test_rigid_mount_carries_the_inplane_block():
    m = with_inplane(wingtip_propeller_wing(mount="rigid"), 1.4e7)
    s = m.second_order(np.array([100.0]))
    dm = m.dof_map()
    v = dm.wing_dof(m.nodes[0], "v")
    ref = with_inplane(PropellerWing(m.wing, m.flight), 1.4e7).second_order(np.array([100.0]))
    assert s.S1[0, v, v] - ref.S1[0, v, v] == pytest.approx(m.propellers[0].propeller.pivot_inertia()["M_P"])


@pytest.mark.long
def test_critical_speeds_converge_to_the_rigid_in_plane_model():
    """EI_chordwise → ∞: every critical speed tends to today's (the differences fall like
    1/EI_chordwise: by more than 10× from a factor 1e3 to 1e5 of EI)."""
    m0 = wingtip_propeller_wing()
    ref = analyse(m0, method="dense")
    diffs = []
    for factor in (1e3, 1e5):
        r = analyse(with_inplane(m0, factor * m0.wing.EI), method="dense")
        assert [(e.kind, e.event) for e in r.events] == [(e.kind, e.event) for e in ref.events]
        diffs.append(max(abs(a.V - b.V) for a, b in zip(r.events, ref.events)))
    assert diffs[1] < 0.02 and diffs[1] < diffs[0] / 10 + 0.01


def test_inplane_needs_a_positive_rigidity():
    with pytest.raises(InputError, match="EI_chordwise"):
        replace(patil_wing(), EI_chordwise=-1.0)
    with pytest.raises(InputError, match="EI_chordwise"):
        replace(patil_wing(), EI_chordwise=np.ones(3))
