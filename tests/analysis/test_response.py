"""Time response (§9.2, Figures 9.11–9.12) and Campbell tables (§8.4.1, §9.3.2, §10.1.2).

Time response: the isolated baseline propeller released from θ = 1° at 77, 222 and 250 m/s
(symmetric f_θ = f_ψ = 7 Hz, and f_ψ = 4 Hz).  Checked against the model's own eigenvalues
(independent of the integration): decay below the flutter speed, growth above it, a nearly
constant whirl near it; the envelope's growth rate equals Re λ of the backward whirl mode; the
modal coordinates grow exactly as e^{λt} (eq. 5.8); the path is clockwise in the (θ, ψ) plane
while the rotor turns counter-clockwise (backward whirl, §9.2); exact transition matrices agree
with an RK45 integration (the thesis's ode45).

Campbell (propwhirl.analysis.vibration.campbell, tracked from rpm = 0): at Ω = 0 the tracked
frequencies equal Tables 9.8, 10.3 and 10.7 (reference values and tolerances from
thesis_values.toml) and are the in-vacuo modes; backward whirl falls and forward whirl rises
with the rotational speed, modes below the backward whirl fall and modes above the forward
whirl rise (§10.1.2); curves never cross (they veer, §8.4.1, §9.3.2), also far beyond the
operating range where the whirl modes meet the wing modes; at every speed the tracked
frequencies are the eigenvalues of the gyroscopic state matrix (an independent eigvals).
"""
from __future__ import annotations

import numpy as np
import pytest

from propwhirl.analysis.stability import analyse
from propwhirl.cases.ch09_baseline import inboard_propeller_wing, isolated_baseline_propeller
from propwhirl.cases.ch10_other_wings import two_propeller_wing, wingtip_propeller_wing
from propwhirl.reproduce.harness import load_references
from propwhirl.analysis.response import rotation_sign, simulate
from propwhirl.reproduce.ch09 import THESIS_RESPONSE_SPEEDS, baseline_propeller_responses
from propwhirl.validate import InputError
from propwhirl.analysis.vibration import campbell, label_modes, model_modes
from propwhirl.model.statespace import SecondOrder, state_matrix

TH, PS = "propeller 1 theta", "propeller 1 psi"
T_SETTLED = 2.0        # [s] the forward whirl mode (Re λ ≈ −2.4 … −2.9 1/s at 222–250 m/s) is gone


@pytest.fixture(scope="module")
def responses():
    return {f_psi: baseline_propeller_responses(f_psi=f_psi) for f_psi in (7.0, 4.0)}


@pytest.fixture(scope="module")
def flutter_speeds():
    out = {}
    for f_psi in (7.0, 4.0):
        a = analyse(isolated_baseline_propeller(f_psi=f_psi))
        out[f_psi] = a.first("backward", "flutter").V
    return out


def backward_eigenvalue(r) -> complex:
    """The least stable oscillatory root of A(V) (the backward whirl mode at these speeds)."""
    lam = r.eigenvalues[r.eigenvalues.imag > 0]
    return complex(lam[np.argmax(lam.real)])


def envelope(r, t0: float, t1: float) -> float:
    """Largest whirl radius √(θ² + ψ²) in [t0, t1] s."""
    sel = (r.t >= t0) & (r.t <= t1)
    return float(r.amplitude([TH, PS])[sel].max())


# ----------------------------------------------------------------------------------------------
# time response
# ----------------------------------------------------------------------------------------------
def test_setting_of_figures_9_11_and_9_12(responses):
    for f_psi, rs in responses.items():
        assert tuple(rs) == THESIS_RESPONSE_SPEEDS
        for V, r in rs.items():
            assert r.V == V and r.t[0] == 0.0 and r.t[-1] == pytest.approx(10.0)
            assert r[TH][0] == pytest.approx(np.radians(1.0)) and r[PS][0] == 0.0
            assert set(r.dofs) == {TH, PS} and set(r.rates) == {TH, PS}
            tab = r.table()
            assert tab["value"].size == 2 * r.t.size and set(tab["dof"]) == {TH, PS}


def test_flutter_speeds_bracket_the_thesis_speeds(flutter_speeds):
    """77 m/s is below and 250 m/s above both flutter speeds; 222 m/s is just above the
    symmetric propeller's (221.0 m/s in Table 9.5) and below the unsymmetric one's (242 m/s)."""
    assert 77.0 < flutter_speeds[7.0] < 222.0 < 250.0
    assert abs(222.0 - flutter_speeds[7.0]) < 1.0
    assert 222.0 < flutter_speeds[4.0] < 250.0


def test_decay_below_growth_above_neutral_near(responses, flutter_speeds):
    for f_psi, rs in responses.items():
        for V, r in rs.items():
            start = envelope(r, 0.0, 1.0)
            settled = envelope(r, T_SETTLED, T_SETTLED + 1.0)
            end = envelope(r, 9.0, 10.0)
            if V < flutter_speeds[f_psi] - 1.0:
                assert end < 0.5 * start and end < settled
            elif V > flutter_speeds[f_psi] + 1.0:
                assert end > 1.2 * settled
            else:   # within 1 m/s of the flutter speed: neither decays nor grows over 8 s
                assert abs(np.log(end / settled)) < 0.05


@pytest.mark.parametrize("f_psi, V", [(7.0, 77.0), (7.0, 222.0), (7.0, 250.0),
                                      (4.0, 222.0), (4.0, 250.0)])
def test_envelope_grows_at_the_backward_whirl_rate(responses, f_psi, V):
    """After the forward whirl mode has died out, log-envelope slope = Re λ (eq. 5.8).

    (f_ψ = 4 Hz at 77 m/s is left out: there the pitch-dominated forward mode, which the
    initial pitch excites most, decays at −0.41 1/s against −0.27 1/s of the backward mode,
    so neither dominates the 10 s record.  At 77 m/s the symmetric propeller's forward mode
    decays at −0.50 1/s against −0.22 1/s, so its share falls only as e^{−0.28 t}: the fit
    starts at 5 s there.)"""
    r = responses[f_psi][V]
    sigma = backward_eigenvalue(r).real
    t_from = 5.0 if V == 77.0 else T_SETTLED
    for label in (TH, PS):
        fit = r.growth_rate(label, t_from=t_from)
        assert fit == pytest.approx(sigma, rel=0.03, abs=1e-4)


def test_modal_coordinates_grow_like_the_eigenvalues(responses):
    """η_k(t) = η_k(0) e^{λ_k t}: every mode's amplitude follows its own Re λ exactly."""
    for rs in responses.values():
        for r in rs.values():
            eta = r.modal()
            expect = eta[0][None, :] * np.exp(np.outer(r.t, r.eigenvalues))
            np.testing.assert_allclose(eta, expect, atol=1e-9 * np.abs(eta[0]).max())


def test_backward_whirl_clockwise_against_counter_clockwise_rotation(responses):
    """§9.2: 'the motion occurs in the clockwise direction while the blade rotation is in the
    counter-clockwise direction' (θ on X, ψ on Y) — all three speeds of Figure 9.11, and the
    unsymmetric propeller once its backward mode dominates (222, 250 m/s)."""
    assert rotation_sign(isolated_baseline_propeller()) == 1       # counter-clockwise rotor
    for f_psi, rs in responses.items():
        for V, r in rs.items():
            if f_psi == 4.0 and V == 77.0:
                continue
            assert r.orbit_area(TH, PS, t_from=T_SETTLED) < 0
            # the orbit sense per cycle equals the backward mode's (whirl_sense of its shape)
            k = int(np.argmax(np.where(r.eigenvalues.imag > 0, r.eigenvalues.real, -np.inf)))
            x = r.eigenvectors[:, k]
            assert np.imag(np.conj(x[0]) * x[1]) > 0                 # clockwise shape (5.12)


def test_unsymmetric_path_is_an_ellipse(responses):
    """Figure 9.12: with f_ψ = 4 Hz the path is elliptical (θ and ψ not 90° apart): the radius
    varies within a cycle, unlike the circular path of the symmetric propeller."""
    def ripple(r):
        sel = (r.t >= 8.0) & (r.t <= 10.0)
        rad = r.amplitude([TH, PS])[sel]
        trend = np.exp(np.polyval(np.polyfit(r.t[sel], np.log(rad), 1), r.t[sel]))
        return float(np.ptp(rad / trend))
    assert ripple(responses[7.0][250.0]) < 0.01
    assert ripple(responses[4.0][250.0]) > 0.2


def test_expm_agrees_with_rk45():
    """The exact transition matrix against scipy's RK45 (the thesis used MATLAB's ode45)."""
    m = isolated_baseline_propeller()
    init = {TH: np.radians(1.0)}
    a = simulate(m, 250.0, init, duration=3.0, dt=0.005)
    b = simulate(m, 250.0, init, duration=3.0, dt=0.005, method="ivp")
    np.testing.assert_allclose(a.x, b.x, atol=1e-8)


def test_wing_model_response_is_labelled_and_consistent():
    """A propeller-wing model: tip deflection released from rest; histories labelled by DOF
    (SI) and the modal coordinates follow e^{λt}."""
    m = wingtip_propeller_wing()
    r = simulate(m, 100.0, {"node 25 h": 0.01}, duration=0.5, dt=0.001)
    assert r["node 25 h"][0] == 0.01 and "propeller 1 theta" in r.dofs
    assert "d/dt node 25 h" in r.labels and any(lab.endswith("w1") for lab in r.labels)
    eta = r.modal()
    expect = eta[0][None, :] * np.exp(np.outer(r.t, r.eigenvalues))
    np.testing.assert_allclose(eta, expect, atol=1e-8 * np.abs(eta[0]).max())


def test_bad_input():
    m = isolated_baseline_propeller()
    with pytest.raises(InputError, match="no state labelled 'theta'"):
        simulate(m, 100.0, {"theta": 0.01})
    with pytest.raises(InputError, match="V = "):
        simulate(m, -1.0, {TH: 0.01})
    with pytest.raises(InputError, match="dt"):
        simulate(m, 100.0, {TH: 0.01}, duration=1.0, dt=2.0)
    with pytest.raises(InputError, match="at least one"):
        simulate(m, 100.0, {})
    with pytest.raises(InputError, match="must be finite"):
        simulate(m, 100.0, {TH: float("nan")})
    with pytest.raises(InputError, match="method"):
        simulate(m, 100.0, {TH: 0.01}, method="euler")
    r = simulate(m, 100.0, {TH: 0.01}, duration=0.1)
    with pytest.raises(InputError, match="fewer than 3"):
        r.growth_rate(TH, t_from=0.099)


# ----------------------------------------------------------------------------------------------
# Campbell
# ----------------------------------------------------------------------------------------------
REFS = {r.id: r for r in load_references()}
MODELS = {
    # table prefix: (model factory, {label in the table: reference id suffix})
    "t9.8": (inboard_propeller_wing, {"backward 1": "prop_pitch", "forward 1": "prop_yaw"}),
    "t10.3": (wingtip_propeller_wing, {"backward 1": "backward", "forward 1": "forward"}),
    "t10.7": (two_propeller_wing, {"backward 1": "backward1", "backward 2": "backward2"}),
}


@pytest.fixture(scope="module")
def campbells():
    return {key: (factory(), campbell(factory(), max_frequency_hz=60.0))
            for key, (factory, _) in MODELS.items()}


def curves(c):
    return c.rpm, c.frequency_hz, list(c.labels)


def sorted_gyroscopic_frequencies(model, rpm):
    """Independent oracle: all natural frequencies [Hz] of the undamped gyroscopic system,
    sorted per speed, from a full eigvals of its first-order state matrix."""
    quiet = model.with_(wing_aero=False, propeller_aero=False, rotating=True)
    omega = np.asarray(rpm, dtype=float) * 2.0 * np.pi / 60.0
    V = np.ones_like(omega)
    s = quiet.second_order(V, omega)
    G = 0.5 * (s.S2 - np.swapaxes(s.S2, -1, -2))
    A = state_matrix(SecondOrder(s.S1, G, s.S3, s.S4, s.Ww, s.Wv, s.Wq, s.q_labels,
                                 s.w_labels), V)
    lam = np.linalg.eigvals(A)
    f = np.where(lam.imag > 0, lam.imag / (2 * np.pi), np.inf)
    return np.sort(f, axis=1)[:, : s.n_dof]


@pytest.mark.parametrize("key", list(MODELS))
def test_frequencies_at_zero_rpm_equal_the_tables(campbells, key):
    _, c = campbells[key]
    rpm, F, labels = curves(c)
    assert rpm[0] == 0.0
    at0 = dict(zip(labels, F[0]))
    ids = {f"wing {i}": f"wing{i}" for i in range(1, 6)} | MODELS[key][1]
    for label, suffix in ids.items():
        ref = REFS[f"{key}/{suffix}"]
        assert at0[label] == pytest.approx(ref.thesis, rel=ref.tol), (label, ref.id)


@pytest.mark.parametrize("key", list(MODELS))
def test_at_zero_rpm_the_tracked_modes_are_the_in_vacuo_modes(campbells, key):
    """No offset: the first tracked speed is rpm = 0, where the curves start at the in-vacuo
    frequencies (K x = ω² M x) with the in-vacuo names."""
    model, c = campbells[key]
    modes, _ = model_modes(model)
    K = c.n_modes
    np.testing.assert_allclose(c.frequency_hz[0], modes.frequency_hz[:K], rtol=1e-9)
    assert list(c.labels) == [lab for lab, _ in label_modes(model)][:K]


@pytest.mark.parametrize("key", list(MODELS))
def test_whirl_modes_split_and_wing_modes_follow(campbells, key):
    """Backward whirl falls, forward whirl rises (§9.2, §9.3.2); wing modes below the backward
    whirl mode fall and those above the forward whirl mode rise (§10.1.2)."""
    model, c = campbells[key]
    rpm, F, labels = curves(c)
    assert c.resolved.all() and not c.unresolved
    dF = np.diff(F, axis=0)
    back = [i for i, lab in enumerate(labels) if lab.startswith("backward")]
    fwd = [i for i, lab in enumerate(labels) if lab.startswith("forward")]
    assert len(back) == len(fwd) == len(model.flexible)
    lowest_whirl = F[0, back].min()
    highest_whirl = F[0, fwd].max()
    for i, lab in enumerate(labels):
        if i in back or (lab.startswith("wing") and F[0, i] < lowest_whirl):
            assert np.all(dF[:, i] < 0), lab
            assert np.all(c.slope_hz_per_rpm[1:, i] < 0), lab
        elif i in fwd or (lab.startswith("wing") and F[0, i] > highest_whirl):
            assert np.all(dF[:, i] > 0), lab
            assert np.all(c.slope_hz_per_rpm[1:, i] > 0), lab
    # a clear split over the operating range (0-6000 rpm; 4433 rpm at Table 9.5's flutter)
    assert np.all(F[-1, back] < F[0, back] - 1.0) and np.all(F[-1, fwd] > F[0, fwd] + 1.0)


@pytest.mark.parametrize("key", list(MODELS))
def test_tracked_frequencies_are_the_gyroscopic_eigenvalues(campbells, key):
    model, c = campbells[key]
    ref = sorted_gyroscopic_frequencies(model, c.rpm)
    np.testing.assert_allclose(np.sort(c.frequency_hz, axis=1), ref[:, : c.n_modes], rtol=1e-6)


def test_slopes_are_the_derivative_of_the_curves():
    """The exact slopes df/d(rpm) agree with a central difference of the tracked curves."""
    model = wingtip_propeller_wing()
    h = 1.0
    c = campbell(model, [3000.0 - h, 3000.0, 3000.0 + h], max_frequency_hz=30.0)
    fd = (c.frequency_hz[2] - c.frequency_hz[0]) / (2 * h)
    np.testing.assert_allclose(c.slope_hz_per_rpm[1], fd, rtol=1e-5, atol=1e-12)
    assert abs(c.slope_hz_per_rpm[1, c.labels.index("backward 1")]) > 1e-4


def test_curves_veer_instead_of_crossing():
    """§8.4.1: 'when the frequency of a propeller mode comes close to the frequency of a wing
    mode, they do not cross, instead, they split following an asymptote'.  Spun far beyond the
    operating range the wingtip propeller's backward whirl mode runs into the first wing mode
    and the forward whirl mode towards the second: the tracked curves keep their order and
    the first wing mode is pushed down by the backward whirl mode."""
    c = campbell(wingtip_propeller_wing(), np.arange(0.0, 60001.0, 1000.0),
                 max_frequency_hz=30.0)
    rpm, F, labels = curves(c)
    assert c.resolved.all()
    order = np.argsort(F, axis=1)
    assert np.all(order == order[0])                         # never cross
    w1, b1 = labels.index("wing 1"), labels.index("backward 1")
    gap = F[:, b1] - F[:, w1]
    assert gap.min() > 0.5                                   # a repelled, not crossing, pair
    assert F[-1, w1] < 0.5 * F[0, w1]                        # wing 1 pushed far down
    assert F[-1, b1] > 0.25 * F[0, b1]                       # backward whirl held up


def test_result_table_and_dict():
    c = campbell(wingtip_propeller_wing(), [0.0, 1000.0], max_frequency_hz=10.0)
    tab = c.table()
    assert list(tab["rpm"]) == [0.0] * 3 + [1000.0] * 3
    assert list(tab["label"][:3]) == ["wing 1", "backward 1", "forward 1"]
    np.testing.assert_array_equal(tab["frequency_hz"], c.frequency_hz.reshape(-1))
    np.testing.assert_array_equal(c.curve("forward 1"), c.frequency_hz[:, 2])
    d = c.to_dict()
    assert d["labels"] == list(c.labels) and d["rpm"] == [0.0, 1000.0]
    with pytest.raises(InputError, match="label"):
        c.curve("wing 9")


def test_campbell_bad_input():
    with pytest.raises(InputError, match="flexibly mounted"):
        campbell(wingtip_propeller_wing("rigid"))
    with pytest.raises(InputError, match="rpm"):
        campbell(wingtip_propeller_wing(), [0.0, -10.0])
    with pytest.raises(InputError, match="increasing"):
        campbell(wingtip_propeller_wing(), [100.0, 50.0])
