"""Chapter 11 parametric studies (propwhirl.studies.parametric): table shape, the thesis's robust trends,
parallel == serial, bad input.  Small grids, mostly the (fast) isolated propeller."""
from __future__ import annotations

import json
import math

import numpy as np
import pytest

from propwhirl.studies import parametric as S
from propwhirl.analysis.stability import Instability, ModelAnalysis
from propwhirl.cases.ch09_baseline import baseline_propeller
from propwhirl.validate import InputError


def _speeds(t: S.StudyTable, model: str = "isolated") -> np.ndarray:
    return t.curve(model)[1]


# ----------------------------------------------------------------------------- table
def test_table_shape_columns_and_export(tmp_path):
    t = S.nacelle_stiffness("yaw", [2.0, 7.0, 12.0], models=("isolated",))
    assert len(t) == 3 and t.models == ("isolated",)
    assert t.parameter == "mean_frequency"
    for k in ("model", "f_theta", "f_psi", "mean_frequency", "critical_speed", "critical_frequency",
              "critical_mode", "content", "kind", "event", "whirl", "static_divergence_speed"):
        assert len(t.columns[k]) == 3, k
    np.testing.assert_array_equal(t.columns["f_theta"], [7.0, 7.0, 7.0])
    np.testing.assert_array_equal(t.columns["f_psi"], [2.0, 7.0, 12.0])
    np.testing.assert_array_equal(t.columns["mean_frequency"], [4.5, 7.0, 9.5])
    assert t.units["critical_speed"] == "m/s" and t.units["mean_frequency"] == "Hz"
    # the baseline point is Table 9.5's backward whirl flutter (221 m/s, 5.0 Hz)
    assert t.columns["critical_speed"][1] == pytest.approx(221.0, rel=0.03)
    assert t.columns["critical_frequency"][1] == pytest.approx(5.0, rel=0.05)
    d = t.to_dict()
    json.dumps(d)  # JSON-ready
    assert d["columns"]["critical_mode"][1] == "backward"
    csv = t.to_csv(tmp_path / "t.csv")
    lines = csv.strip().splitlines()
    assert len(lines) == 4 and lines[0].startswith("model,f_theta [Hz],f_psi [Hz]")
    assert (tmp_path / "t.csv").read_text() == csv
    assert "nacelle stiffness" in t.format()


def test_two_models_rows_and_for_model():
    t = S.motor_mass([35.0], models=("isolated", "rigid"), static_divergence=False, low_speed=False)
    assert len(t) == 2 and t.models == ("isolated", "rigid")
    assert "thesis convention" in t.convention and t.convention in t.format()
    r = t.for_model("rigid")
    assert list(r.columns["model"]) == ["rigid"]
    # rigid, non-rotating mount: no whirl modes — the second wing mode flutters (§11.3, Table 10.2)
    assert r.columns["critical_mode"][0] == "wing 2" and r.columns["kind"][0] == "flutter"
    # its static divergence is reported, not counted as critical (the thesis omits it)
    assert r.columns["static_divergence_speed"][0] < r.columns["critical_speed"][0]
    # by default (the one definition) the static divergence is the critical instability
    d = S.motor_mass([35.0], models=("rigid",))
    assert d.convention.startswith("every instability counts")
    assert d.columns["kind"][0] == "divergence"
    assert d.columns["critical_speed"][0] == r.columns["static_divergence_speed"][0]
    with pytest.raises(InputError, match="model"):
        t.for_model("wingtip")


# ----------------------------------------------------------------------------- thesis trends
def test_isolated_symmetric_stiffness_raises_critical_speed():
    """§11.1 (3): with f_θ = f_ψ the critical speed grows monotonically with the stiffness;
    the isolated propeller flutters in backward whirl (Figure 11.1a)."""
    t = S.nacelle_stiffness("both", [2.0, 5.0, 9.0], models=("isolated",))
    V = _speeds(t)
    assert np.all(np.diff(V) > 0)
    assert list(t.columns["critical_mode"]) == ["backward"] * 3
    assert list(t.columns["kind"]) == ["flutter"] * 3


def test_isolated_pitch_and_yaw_are_symmetric():
    """§11.1: the isolated propeller is symmetric — varying yaw = varying pitch (Figure 11.1a),
    and a very soft mount in one direction makes it diverge (the annotated markers)."""
    fy = S.nacelle_stiffness("yaw", [1.0, 4.0], models=("isolated",))
    fp = S.nacelle_stiffness("pitch", [1.0, 4.0], models=("isolated",))
    np.testing.assert_allclose(_speeds(fy), _speeds(fp), rtol=2e-3)
    assert fy.columns["kind"][0] == "divergence" and fy.columns["critical_mode"][0].startswith("backward")
    # unequal stiffness is less critical than equal stiffness at the same mean (§9.2: 242 vs 221)
    sym = S.nacelle_stiffness("both", [5.5], models=("isolated",))
    assert _speeds(fy)[1] > _speeds(sym)[0]


def test_isolated_damping_raises_critical_speed():
    """§11.2: more nacelle damping → higher critical speed, backward whirl throughout."""
    t = S.nacelle_damping("both", [0.0, 0.01, 0.1], models=("isolated",))
    V = _speeds(t)
    assert np.all(np.diff(V) > 0)
    assert set(t.columns["critical_mode"]) == {"backward"}
    # pitch-only and yaw-only damping act alike on the symmetric isolated propeller (Fig. 11.4a)
    p = S.nacelle_damping("pitch", [0.1], models=("isolated",))
    y = S.nacelle_damping("yaw", [0.1], models=("isolated",))
    assert _speeds(p)[0] == pytest.approx(_speeds(y)[0], rel=2e-3)


def test_isolated_motor_mass_and_pivot_length():
    """§11.3: heavier motor stabilises the isolated propeller; §11.4 (Houbolt & Reed): a shorter
    pivoting length (pivot moved forward) destabilises it."""
    m = S.motor_mass([15.0, 35.0, 60.0], models=("isolated",))
    assert np.all(np.diff(_speeds(m)) > 0)
    p = S.pivot_length("pivot", [-0.4, 0.0, 0.2], models=("isolated",))
    assert np.all(np.diff(_speeds(p)) > 0)
    np.testing.assert_allclose(p.columns["pivot_length"], [-0.76, -1.16, -1.36])
    # Table 11.3 inertia columns
    np.testing.assert_allclose(p.columns["I_theta_P"], [12.03, 36.65, 54.12], atol=0.01)


def test_isolated_spin_inertia_and_blade_angle():
    """§11.5: the isolated flutter speed falls with I_Ω (at first); §11.6: a larger blade angle
    (advance ratio) stabilises the fixed-pitch isolated propeller."""
    s = S.spin_inertia([4.0, 8.0, 12.0], models=("isolated",))
    assert np.all(np.diff(_speeds(s)) < 0)
    np.testing.assert_allclose(s.columns["I_Omega"], np.array([4.0, 8.0, 12.0]) * 0.762**2 / 3)
    b = S.blade_angle([25.0, 35.0, 50.0], models=("isolated",))
    assert np.all(np.diff(_speeds(b)) > 0)
    assert b.columns["advance_ratio"][1] == pytest.approx(1.96, abs=0.01)  # Table 9.3


def test_wingtip_soft_yaw_mount_divergence_counts_wing_divergence_does_not():
    """Wingtip model, f_θ = 7 Hz: at f_ψ = 1 Hz the soft yaw mount diverges (the thesis's
    Figure 11.1b: "the backward whirl mode ... diverges") — critical; at f_ψ = 2 Hz the
    divergence near 144 m/s is the wing's static divergence although it happens on the branch
    named "backward 1": its shape decides, it is reported apart, and the forward whirl flutter
    is critical (§11.1: forward whirl drives the wingtip model)."""
    t = S.nacelle_stiffness("yaw", [1.0, 2.0], models=("wingtip",), static_divergence=False,
                            low_speed=False)
    kind, mode, V = (t.columns[k] for k in ("kind", "critical_mode", "critical_speed"))
    assert kind[0] == "divergence" and mode[0] == "backward 1" and 60.0 < V[0] < 120.0
    assert t.columns["content"][0] == "yaw"
    assert kind[1] == "flutter" and mode[1] == "forward 1" and V[1] == pytest.approx(163.0, rel=0.03)
    Vd = t.columns["static_divergence_speed"][1]
    assert 130.0 < Vd < V[1]
    # the one definition counts the wing's static divergence: it is critical at f_ψ = 2 Hz
    d = S.nacelle_stiffness("yaw", [2.0], models=("wingtip",))
    assert d.columns["kind"][0] == "divergence" and d.columns["critical_speed"][0] == Vd


# ----------------------------------------------------------------------------- critical rule
def _analysis(events) -> ModelAnalysis:
    return ModelAnalysis("m", None, tuple(events))  # the rule only reads the events


def test_critical_rule():
    ev = [
        Instability("flutter", "unstable-at-start", 0, "backward", 1.0, 7.0),
        Instability("flutter", "recovery", 0, "backward", 17.0, 6.9),
        Instability("divergence", "onset", 3, "wing 1", 140.0, 0.0),
        Instability("divergence", "onset", 4, "backward'", 150.0, 0.0),
        Instability("flutter", "onset", 1, "forward 1", 160.0, 11.0),
    ]
    a = _analysis(ev)
    thesis = dict(static_divergence=False, low_speed=False)
    assert S.critical_instability(a) == a.critical      # default: the one definition
    assert S.critical_instability(a).V == 1.0
    assert S.critical_instability(a, **thesis).V == 150.0  # whirl divergence counts, wing's not
    assert S.critical_instability(a, static_divergence=True, low_speed=False).V == 140.0
    assert S.critical_instability(a, static_divergence=False, low_speed=True).V == 1.0
    assert S.static_divergence_speed(a) == 140.0
    # an instability present from the first speed that never recovers counts
    b = _analysis([Instability("flutter", "unstable-at-start", 0, "backward", 1.0, 7.0), ev[4]])
    assert S.critical_instability(b, **thesis).V == 1.0
    assert S.critical_instability(_analysis([])) is None
    # a shape-based predicate overrides the names: here the "backward'" divergence is the wing's
    by_shape = lambda e: e.mode == 4  # noqa: E731
    assert S.critical_instability(a, is_wing_divergence=by_shape, **thesis).V == 140.0
    assert S.static_divergence_speed(a, by_shape) == 150.0
    assert math.isnan(S.static_divergence_speed(_analysis([])))


# ----------------------------------------------------------------------------- parallel
def test_parallel_equals_serial():
    grid = [1.0, 3.0, 7.0, 12.0]
    a = S.nacelle_stiffness("yaw", grid, models=("isolated",))
    b = S.nacelle_stiffness("yaw", grid, models=("isolated",), processes=2)
    assert a.columns.keys() == b.columns.keys()
    for k in a.columns:
        x, y = np.asarray(a.columns[k]), np.asarray(b.columns[k])
        if x.dtype == object:
            assert list(x) == list(y), k
        else:
            np.testing.assert_allclose(x, y, rtol=1e-10, equal_nan=True, err_msg=k)


# ----------------------------------------------------------------------------- bad input
@pytest.mark.parametrize(
    "call, match",
    [
        (lambda: S.nacelle_stiffness("both", []), "empty|non-empty"),
        (lambda: S.nacelle_stiffness("both", [2.0, -1.0]), "frequencies = -1.0 Hz is invalid"),
        (lambda: S.nacelle_stiffness("both", [2.0, float("nan")]), "must be finite"),
        (lambda: S.nacelle_stiffness("sideways", [2.0]), "vary"),
        (lambda: S.nacelle_stiffness("yaw", [2.0], fixed_frequency=0.0), "fixed_frequency"),
        (lambda: S.nacelle_damping("both", [-0.1]), "damping values = -0.1 is invalid"),
        (lambda: S.nacelle_damping("both", [0.1], damping="viscous"), "damping"),
        (lambda: S.motor_mass([0.0]), "motor masses = 0.0 kg is invalid"),
        (lambda: S.spin_inertia([-8.0]), "rotor masses"),
        (lambda: S.pivot_length("nose", [0.0]), "variant"),
        (lambda: S.blade_angle([100.0]), "beta|blade|angle"),
        (lambda: S.motor_mass([35.0], models=("wingtip", "wingtip")), "twice"),
        (lambda: S.motor_mass([35.0], models=("canard",)), "model"),
        (lambda: S.motor_mass([35.0], models=()), "model"),
        (lambda: S.motor_mass([35.0], models=("isolated",), processes=0), "processes"),
        (lambda: S.motor_mass([35.0], models=("isolated",), speeds=[10.0, 5.0]), "increasing"),
        (lambda: S.motor_mass([35.0], propeller="baseline"), "propeller"),
        (lambda: S.blade_angle([35.0], propeller=baseline_propeller(operation="constant-speed", rpm=2250.0)),
         "fixed-pitch"),
        (lambda: S.blade_angle_mode_switch((80.0, 60.0)), "increasing"),
    ],
)
def test_bad_input(call, match):
    with pytest.raises(InputError, match=match):
        call()
