"""The assembled propeller–wing model (chapter 8, appendix D): structure, switches, errors."""
import numpy as np
import pytest

from propwhirl.cases.ch07_patil import PATIL_DENSITY, patil_wing
from propwhirl.cases.ch09_baseline import baseline_propeller, baseline_wing, baseline_flight, propeller_wing
from propwhirl.cases.ch10_other_wings import tip_y, two_propeller_wing, wingtip_propeller_wing
from propwhirl.model.systems import FlightCondition, Installation, PropellerWing, node_at
from propwhirl.model.propellers.propeller import MeasuredDerivatives
from propwhirl.validate import InputError
from propwhirl.analysis.vibration import campbell, label_modes

NO_AERO = MeasuredDerivatives({})


def quiet(model):
    return model.with_(wing_aero=False, propeller_aero=False)


def test_propeller_off_node_names_nearest_nodes():
    wing = baseline_wing(25)
    with pytest.raises(InputError) as exc:
        node_at(wing, 1.6)
    msg = str(exc.value)
    assert "1.6" in msg and "nearest nodes are 7" in msg and "8" in msg


@pytest.mark.parametrize("y", [-0.1, 6.0])
def test_propeller_outside_wing(y):
    with pytest.raises(InputError, match="outside the wing"):
        node_at(baseline_wing(25), y)


def test_propeller_at_root_rejected():
    with pytest.raises(InputError, match="clamped root"):
        node_at(baseline_wing(25), 0.0)


def test_two_propellers_at_one_node_rejected():
    with pytest.raises(InputError, match="two propellers at node 25"):
        propeller_wing((tip_y(), tip_y()))


def test_density_must_be_positive():
    with pytest.raises(InputError, match="density = 0.0"):
        FlightCondition(0.0)


def test_nonpositive_speed_rejected():
    with pytest.raises(InputError, match="airspeed V"):
        wingtip_propeller_wing().second_order(np.array([0.0, 10.0]))


def test_dof_counts_and_labels():
    model = two_propeller_wing()
    s = model.second_order(np.array([50.0]))
    assert s.n_dof == 3 * 25 + 4 and s.n_lag == 2 * 25
    assert s.q_labels[:3] == ("node 1 h", "node 1 phi", "node 1 alpha")
    assert s.q_labels[-4:] == ("propeller 1 theta", "propeller 1 psi", "propeller 2 theta", "propeller 2 psi")
    rigid = two_propeller_wing("rigid").second_order(np.array([50.0]))
    assert rigid.n_dof == 3 * 25


def test_gyroscopic_terms_skew_symmetric_and_vanish_at_rest():
    model = quiet(wingtip_propeller_wing(propeller=baseline_propeller(damping_theta=0.0, damping_psi=0.0)))
    S2 = model.second_order(np.array([150.0])).S2[0]
    np.testing.assert_allclose(S2, -S2.T, atol=1e-12)
    assert np.abs(S2).max() > 1.0  # Ω(150 m/s) gives I_Ω Ω ≈ 500 N m s
    still = model.with_(rotating=False).second_order(np.array([150.0])).S2[0]
    assert np.abs(still).max() == 0.0


def test_omega_zero_removes_pitch_yaw_coupling():
    model = quiet(wingtip_propeller_wing()).with_(rotating=False)
    s = model.second_order(np.array([100.0]))
    th, ps = s.q_labels.index("propeller 1 theta"), s.q_labels.index("propeller 1 psi")
    for Mx in (s.S1[0], s.S2[0], s.S3[0]):
        assert Mx[th, ps] == 0.0 and Mx[ps, th] == 0.0
        # yaw couples to nothing at rest: no lateral wing motion
        assert np.count_nonzero(Mx[ps]) <= 1


def test_structural_mass_symmetric_positive_definite():
    S1 = quiet(two_propeller_wing()).second_order(np.array([1.0])).S1[0]
    np.testing.assert_allclose(S1, S1.T, atol=1e-12)
    assert np.linalg.eigvalsh(S1).min() > 0


def test_campbell_backward_falls_forward_rises():
    model = wingtip_propeller_wing()
    f = campbell(model, np.array([0.0, 2000.0, 4000.0])).frequency_hz
    labels = [lab for lab, _ in label_modes(model)]
    b, fw = labels.index("backward 1"), labels.index("forward 1")
    assert f[2, b] < f[1, b] < f[0, b]
    assert f[2, fw] > f[1, fw] > f[0, fw]


def patil_model(aero_model):
    return PropellerWing(patil_wing(20, aero_model=aero_model), FlightCondition(PATIL_DENSITY))


def test_wagner_and_leishman_nguyen_have_the_same_aeroelastic_roots():
    """Both realise Jones' C(s) exactly: the physical eigenvalues coincide (Wagner adds only
    uncontrollable lag roots at −ε_i V/b)."""
    V = np.array([20.0, 33.0])
    ln = np.linalg.eigvals(patil_model("leishman-nguyen").state_matrix(V))
    wa = np.linalg.eigvals(patil_model("wagner").state_matrix(V))
    for k in range(len(V)):
        for lam in ln[k]:
            assert np.min(np.abs(wa[k] - lam)) < 1e-6 * max(1.0, abs(lam))


def test_patil_divergence_matches_closed_form_strip_theory():
    """q_D = (π/2L)² GJ / (e c C_lα), e = 0.25 m: V_D = 37.15 m/s (Table 7.3 note)."""
    e, c, GJ, L = 0.25, 1.0, 1e4, 16.0
    VD = np.sqrt(2 * (np.pi / (2 * L)) ** 2 * GJ / (e * c * 2 * np.pi) / PATIL_DENSITY)
    assert abs(VD - 37.15) < 0.01
    lam = np.linalg.eigvals(patil_model("leishman-nguyen").state_matrix(np.array([0.995 * VD, 1.005 * VD])))
    real = lambda row: row[np.abs(row.imag) < 1e-9].real  # noqa: E731
    assert real(lam[0]).max() < 0 < real(lam[1]).max()


def test_per_propeller_aero_switch():
    """Switching one propeller's aerodynamics off equals zero derivatives for that propeller."""
    from dataclasses import replace

    base = two_propeller_wing()
    off = replace(base, propellers=(base.propellers[0], replace(base.propellers[1], aero=False)))
    zero = replace(base, propellers=(base.propellers[0], replace(
        base.propellers[1], propeller=replace(base.propellers[1].propeller, derivatives=NO_AERO))))
    V = np.array([80.0, 200.0])
    np.testing.assert_allclose(off.state_matrix(V), zero.state_matrix(V), rtol=1e-12, atol=1e-9)
    assert not np.allclose(off.state_matrix(V), base.state_matrix(V))


@pytest.mark.parametrize("model_fn", [
    lambda r: wingtip_propeller_wing(propeller=baseline_propeller(rotation=r)),
    lambda r: __import__("propwhirl.cases.ch09_baseline", fromlist=["x"]).isolated_baseline_propeller(rotation=r),
])
def test_mirror_image_propeller_has_the_same_eigenvalues(model_fn):
    """A clockwise propeller is the mirror image (ψ → −ψ) of the counter-clockwise one: the
    gyroscopic terms and the cross-coupling derivatives change sign, the roots do not."""
    V = np.array([60.0, 160.0, 300.0])
    ccw = np.sort_complex(np.linalg.eigvals(model_fn(1).state_matrix(V)))
    cw = np.sort_complex(np.linalg.eigvals(model_fn(-1).state_matrix(V)))
    np.testing.assert_allclose(cw, ccw, rtol=1e-8, atol=1e-8)
    assert not np.allclose(model_fn(1).state_matrix(V), model_fn(-1).state_matrix(V))


@pytest.mark.parametrize("bad, words", [
    ((0.0, 350.0, 10.0), "speed_range[0] = 0.0 m/s is outside the valid range (0, 10000] m/s"),
    ((100.0, 50.0, 10.0), "last speed = 50.0"),
    ((1.0, 350.0, -1.0), "speed_range[2] = -1.0 m/s"),
    ((1.0, 2.0), "[first, last, step]"),
])
def test_flight_condition_speed_range_validated(bad, words):
    with pytest.raises(InputError) as exc:
        FlightCondition(1.0, speed_range=bad)
    assert words in str(exc.value)


def test_flight_condition_default_grid_covers_the_thesis_range():
    V = FlightCondition(1.0).speeds()
    assert V[0] == 1.0 and V[-1] == 350.0 and np.all(np.diff(V) > 0)


def test_analysis_describes_modes_by_content():
    from propwhirl.analysis.stability import analyse
    from propwhirl.cases.ch09_baseline import baseline_wing_model

    a = analyse(baseline_wing_model(), np.arange(100.0, 200.0, 10.0))
    assert a.describe("wing 1") == "wing 1 (bending)" and a.describe("wing 2") == "wing 2 (torsion)"
    assert a.first("wing 2", "flutter").V == pytest.approx(149.88, abs=0.02)


def test_vgf_sweep_evaluates_every_grid_speed_and_finds_the_same_events():
    from propwhirl.analysis.stability import analyse

    model = wingtip_propeller_wing()
    grid = model.flight.speeds()
    fast, full = analyse(model), analyse(model, vgf=True)
    assert set(grid) <= set(full.sweep.V) and len(fast.sweep.V) < len(grid)
    assert [(e.label, e.event) for e in fast.events] == [(e.label, e.event) for e in full.events]
    for a, b in zip(fast.events, full.events):
        assert abs(a.V - b.V) <= 0.02
