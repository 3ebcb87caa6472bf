"""analysis.reduced: the reduced analysis against the dense full-order reference."""
import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from helpers.brute_force import detect_crossings, engine_crossings, fixed_grid_sweep, match_crossings
from propwhirl.analysis import analyse
from propwhirl.analysis.reduced import REDUCED_ABOVE, LiftedEigenvectors, choose_method
from propwhirl.cases.ch09_baseline import (baseline_flight, baseline_propeller, baseline_wing,
                                           isolated_baseline_propeller)
from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
from propwhirl.model.systems import Installation, PropellerWing
from propwhirl.validate import InputError


def wing_with(n_el: int, stations, f_mount=(7.0,), rng=None) -> PropellerWing:
    wing = baseline_wing(n_el)
    props = []
    for k, y in enumerate(stations):
        f = f_mount[k % len(f_mount)]
        props.append(Installation(baseline_propeller(f_theta=f, f_psi=0.9 * f), float(y),
                                  "flexible"))
    return PropellerWing(wing, baseline_flight(), tuple(props))


def assert_same_events(red, den):
    """Same events; speeds within 0.05 %, frequencies within 0.1 % (issue 10.3)."""
    a = [(e.kind, e.event) for e in red.events]
    b = [(e.kind, e.event) for e in den.events]
    assert sorted(a) == sorted(b), (red.events, den.events)
    for e in den.events:
        match = [r for r in red.events if (r.kind, r.event) == (e.kind, e.event)
                 and abs(r.V - e.V) <= 5e-4 * e.V]
        assert match, (e, red.events)
        r = min(match, key=lambda r: abs(r.V - e.V))
        assert abs(r.frequency_hz - e.frequency_hz) <= 1e-3 * max(e.frequency_hz, 1e-9) + 1e-9


def test_wingtip_model_reduced_equals_dense():
    m = wingtip_propeller_wing()
    red, den = analyse(m, method="reduced"), analyse(m, method="dense")
    assert_same_events(red, den)
    assert red.critical.label == den.critical.label
    assert red.criticals.stats["corrected"] == len(red.criticals.points)
    assert red.sweep.stats["reduced_states"] < m.dof_map().n_states


@pytest.mark.long
@settings(max_examples=3, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.too_slow])
@given(n_el=st.integers(24, 40), n_prop=st.integers(2, 5), seed=st.integers(0, 10_000))
def test_random_wings_reduced_equals_dense(n_el, n_prop, seed):
    """Random distributed-propeller wings (positions anywhere, mount frequencies 5–9 Hz)."""
    rng = np.random.default_rng(seed)
    ys = np.sort(rng.uniform(0.5, 5.7, n_prop))
    ys = ys[np.r_[True, np.diff(ys) > 0.3]]
    m = wing_with(n_el, ys, tuple(rng.uniform(5.0, 9.0, n_prop)))
    assert_same_events(analyse(m, method="reduced"), analyse(m, method="dense"))


@pytest.mark.long
def test_no_instability_missed_against_a_dense_brute_force_scan():
    """Every sign change of Re λ of the full-order roots on a 2 m/s grid (the thesis's
    detection) is an event of the reduced analysis."""
    m = wing_with(30, (1.2, 2.6, 4.0, 5.7), (6.0, 7.0, 8.0))
    red = analyse(m, method="reduced")
    grid = fixed_grid_sweep(m.state_matrix, np.arange(1.0, 351.0, 2.0))
    brute = detect_crossings(grid.V, grid.eigenvalues)
    assert brute
    pairs, _, missed = match_crossings(engine_crossings(red), brute, dV=2.0)
    assert not missed, missed


def test_method_is_checked_and_auto_reduces_every_wing():
    """issue 26.1: "auto" reduces every wing model whatever its size (the thesis's 204 states
    too); the models that cannot be reduced stay dense."""
    small = wingtip_propeller_wing()
    assert small.dof_map().n_states < REDUCED_ABOVE
    assert choose_method(small, "auto") == "reduced"
    assert choose_method(small, "dense") == "dense"
    big = wing_with(60, (1.0, 2.0, 3.0, 4.0, 5.0, 5.7))
    assert choose_method(big, "auto") == "reduced"
    assert choose_method(isolated_baseline_propeller(), "auto") == "dense"
    with pytest.raises(InputError, match="method = 'sparse' is invalid"):
        analyse(small, method="sparse")
    with pytest.raises(InputError, match="an isolated propeller has two degrees of freedom: there is nothing to reduce"):
        analyse(isolated_baseline_propeller(), method="reduced")


@pytest.fixture(scope="module")
def wingtip_dense():
    m = wingtip_propeller_wing()
    return m, analyse(m, method="dense")


def test_the_default_analysis_of_the_wingtip_model_is_reduced_and_equals_dense(wingtip_dense):
    """The default (auto) keeps the reduced analysis: every crossing corrected on the full
    order, the frequency-zero event (Table 10.4's whirl divergence at 321 m/s) checked on the
    full order; the events those of the dense reference."""
    m, den = wingtip_dense
    auto = analyse(m)
    assert auto.sweep.stats["reduced_states"] < m.dof_map().n_states
    assert auto.criticals.stats["corrected"] == len(auto.criticals.points)
    assert any(e.event == "frequency-zero" for e in auto.events)
    assert_same_events(auto, den)
    assert [e.label for e in auto.events] == [e.label for e in den.events]
    assert auto.warnings == den.warnings          # validity notes only: nothing unconverged


def test_auto_analyses_dense_where_a_crossing_does_not_converge_on_the_full_order(
        monkeypatch, wingtip_dense):
    """A crossing whose full-order correction fails: "reduced" keeps the reduced speed with a
    warning; "auto" does not keep it and analyses the model dense (the reference's events)."""
    import propwhirl.analysis.reduced as R

    m, den = wingtip_dense
    monkeypatch.setattr(R, "correct_crossing", lambda *a, **k: None)
    red, auto = analyse(m, method="reduced"), analyse(m)
    assert any("not converged on the full-order model" in w for w in red.warnings)
    assert "reduced_states" in red.sweep.stats
    assert "reduced_states" not in auto.sweep.stats
    assert auto.sweep.n_modes > red.sweep.n_modes
    assert auto.warnings == den.warnings
    assert [(e.kind, e.event, e.V) for e in auto.events] == [(e.kind, e.event, e.V) for e in den.events]


def test_a_frequency_zero_bracket_without_the_full_order_branch_point_is_refused(wingtip_dense):
    """frequency_zero_on_full_order: True where the full-order pair turns real inside the
    reduced event's bracket, False for the same bracket moved by 2 xtol or 5 m/s either way
    (auto then analyses dense); the full-order branch point (the dense analysis's event) is
    inside the reduced bracket."""
    from propwhirl.analysis.participation import branch_point_shape
    from propwhirl.analysis.reduced import frequency_zero_on_full_order, reduced_engine_analysis
    from propwhirl.engine import frequency_zero_points

    m, den = wingtip_dense
    dm = m.dof_map()
    run = reduced_engine_analysis(m, m.flight.speeds(), displacement=dm.displacement,
                                  state_labels=dm.state_labels, xtol=0.01)
    R, sw = run.model, run.analysis.sweep
    (p,) = frequency_zero_points(sw, R.state_matrix, xtol=0.01)
    (full,) = [e for e in den.events if e.event == "frequency-zero"]
    assert abs(full.V - p.V) <= 0.01

    def shape(q):
        return branch_point_shape(m, sw, q.mode, q.bracket[0], R.state_matrix, R.lift)

    assert frequency_zero_on_full_order([p], [shape(p)], R)
    for shift in (-5.0, -0.02, 0.02, 5.0):
        moved = type(p)(p.mode, p.label, p.V + shift,
                        (p.bracket[0] + shift, p.bracket[1] + shift))
        assert not frequency_zero_on_full_order([moved], [shape(moved)], R), shift
    assert frequency_zero_on_full_order([], [], R)


def test_lifted_eigenvectors_index_like_the_array():
    rng = np.random.default_rng(0)
    Xr = rng.standard_normal((3, 4, 4)) + 1j * rng.standard_normal((3, 4, 4))
    L = rng.standard_normal((7, 4))
    X = LiftedEigenvectors(Xr, L)
    full = np.asarray(X)
    assert X.shape == full.shape == (3, 7, 4)
    np.testing.assert_allclose(X[1], full[1])
    np.testing.assert_allclose(X[2, :, 3], full[2, :, 3])
    mask = np.array([True, False] * 3 + [True])
    np.testing.assert_allclose(X[0][mask], full[0][mask])


def test_event_vectors_are_full_state():
    m = wingtip_propeller_wing()
    red = analyse(m, method="reduced")
    n = m.dof_map().n_states
    for p in red.criticals.points:
        assert p.eigenvector.shape == (n,)
    assert red.sweep.eigenvectors[0].shape[0] == n


def test_a_reduced_analysis_is_saved_and_read_back_with_its_eigenvectors(tmp_path):
    from propwhirl.analysis.stability import load

    m = wingtip_propeller_wing()
    red = analyse(m, method="reduced")
    red.save(tmp_path / "r.json", include_eigenvectors=True)
    back = load(tmp_path / "r.json")
    assert back.sweep.eigenvectors.shape == (red.sweep.V.size, m.dof_map().n_states,
                                             red.sweep.n_modes)
    np.testing.assert_array_equal(back.sweep.eigenvectors, np.asarray(red.sweep.eigenvectors))
    assert [e.V for e in back.events] == [e.V for e in red.events]


def test_a_crossing_not_converged_on_the_full_order_is_a_warning(monkeypatch):
    """If the full-order correction fails, the reduced crossing is kept and the analysis says
    so (never a silent reduced value)."""
    import propwhirl.analysis.reduced as R

    monkeypatch.setattr(R, "correct_crossing", lambda *a, **k: None)
    red = analyse(wingtip_propeller_wing(), method="reduced")
    assert red.criticals.stats["corrected"] == 0
    notes = [w for w in red.warnings if "not converged on the full-order model" in w]
    assert len(notes) == len(red.criticals.points) > 0


def _variant(name):
    p = baseline_propeller()
    w = baseline_wing(24)
    return {
        "wing alone": PropellerWing(w, baseline_flight(), ()),
        "wagner": PropellerWing(baseline_wing(24, "wagner"), baseline_flight(),
                                (Installation(p, 5.7, "flexible"),)),
        "rigid and flexible": PropellerWing(w, baseline_flight(), (
            Installation(p, 2.85, "rigid"), Installation(p, 5.7, "flexible"))),
        "no wing aerodynamics": PropellerWing(w, baseline_flight(),
                                              (Installation(p, 5.7, "flexible"),),
                                              wing_aero=False),
        "not rotating": PropellerWing(w, baseline_flight(), (Installation(p, 5.7, "flexible"),),
                                      rotating=False),
    }[name]


@pytest.mark.long
@pytest.mark.parametrize("name", ["wing alone", "wagner", "rigid and flexible",
                                  "no wing aerodynamics", "not rotating"])
def test_model_variants_reduced_equal_dense(name):
    """Every switch and aerodynamic model of the wing reduces: the same events as dense."""
    m = _variant(name)
    assert_same_events(analyse(m, method="reduced"), analyse(m, method="dense"))


def test_a_wing_with_a_propeller_without_aerodynamics_is_reduced():
    """The wingtip model with propeller_aero off (Table 10.4): the propeller modes have no
    aerodynamic stiffness, so their static corrections are zero vectors — dropped from the
    basis (they made it NaN: "array must not contain infs or NaNs"); the default analysis is
    reduced and equals the dense reference."""
    m = wingtip_propeller_wing(propeller_aero=False)
    auto = analyse(m)
    assert auto.sweep.stats["reduced_states"] < m.dof_map().n_states
    assert_same_events(auto, analyse(m, method="dense"))


def test_an_analysis_assembles_its_model_once(monkeypatch):
    """The in-vacuo modes, their names, the content and the participation read the structure
    from the analysis's own assembly (``in_vacuo``): one PropellerWingAssembly.build per
    analysis, reduced or dense (five before: each of them assembled the model again)."""
    from propwhirl.model.systems import PropellerWingAssembly

    built = []
    real = PropellerWingAssembly.build.__func__
    monkeypatch.setattr(PropellerWingAssembly, "build",
                        classmethod(lambda cls, m, *tables: built.append(m.name)
                                    or real(cls, m, *tables)))
    m = wingtip_propeller_wing()
    for method in ("auto", "dense"):
        built.clear()
        a = analyse(m, method=method)
        assert len(built) == 1, (method, built)
        assert any(e.event == "frequency-zero" for e in a.events)


def test_the_folded_x57_cruise_is_not_refined_at_its_stopped_mounts():
    """examples/x57_like_folded.toml: six equal stopped propellers have one mount eigenvalue
    at every speed (their copies' "approach" is rounding, engine/linking._approach): 11 nodes
    and nothing unresolved (720 nodes, every step unresolved, 4.1 s CPU before), the same
    event as before (244.5787 m/s, measured at 132e3e1)."""
    from pathlib import Path

    from propwhirl.io import load_model

    m = load_model(Path(__file__).resolve().parents[2] / "examples" / "x57_like_folded.toml")
    a = analyse(m)
    assert a.sweep.unresolved == ()
    assert a.sweep.stats["nodes"] <= 40, a.sweep.stats
    assert [(e.kind, e.event, e.label) for e in a.events] == [("divergence", "onset", "wing 1")]
    assert abs(a.events[0].V - 244.5787) <= 0.01


def test_an_analysis_evaluates_its_structure_once(monkeypatch):
    """The reduced basis, the in-vacuo modes, the Ω-follow of their names, the content and the
    participation read the structure (M, K and the gyroscopic G(0), ∂G/∂Ω) of one evaluation
    of the model without aerodynamics (analysis.modes.InVacuo, passed explicitly); five before
    (the basis, the modes, the Ω-follow, the content, the events' mass at their speeds)."""
    from propwhirl.model.systems import PropellerWingAssembly

    quiet = []
    real = {k: getattr(PropellerWingAssembly, k) for k in ("second_order", "second_order_blocks")}

    def counted(name):
        def f(self, *a, **k):
            if not (self.model.wing_aero or self.model.propeller_aero):
                quiet.append(name)
            return real[name](self, *a, **k)
        return f

    for name in real:
        monkeypatch.setattr(PropellerWingAssembly, name, counted(name))
    m = wingtip_propeller_wing()
    a = analyse(m, method="reduced")
    assert len(a.events) == 4 and all(e.participation is not None for e in a.events)
    assert quiet == ["second_order"], quiet
