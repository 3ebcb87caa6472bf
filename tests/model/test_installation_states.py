"""Per-installation propeller state and sense of rotation (issue 25, item 3).

`Installation.state`: "operating" (the propeller's own operation), "stopped" (Ω = 0, no
propeller aerodynamics, the mount and masses kept), "feathered" (Ω = 0, the Ω → 0 limit of the
Houbolt–Reed blade elements: the blades as fins).  `Installation.rotation` overrides the
propeller's sense.  Checked against the models they must equal, a hand estimate of the fin
force, the model file, and a two-propeller wing cut from examples/x57_like.toml.
"""
from __future__ import annotations

import math
import tomllib
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
import tomli_w
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from propwhirl.analysis.campbell import campbell, operating_rpm_ratio
from propwhirl.io import dumps, loads
from propwhirl.model.propellers.propeller import MeasuredDerivatives
from propwhirl.model.propellers.propeller_aero import AeroSettings, derivatives, stopped_blades
from propwhirl.model.systems import Installation
from propwhirl.validate import InputError

ROOT = Path(__file__).resolve().parents[2]


def small_x57(states=("operating", "operating"), wing_aero=True, **inst):
    """Two high-lift propellers of examples/x57_like.toml (y = 0.95 and 2.15 m) on a 4-element
    wing: the x57 check of issue 25 on a model small enough for a test."""
    doc = tomllib.loads((ROOT / "examples" / "x57_like.toml").read_text())
    doc["wing"]["n_elements"] = 4
    doc["wing"]["semi_span_m"] = 2.4
    doc["installations"] = [dict(doc["installations"][k], state=s, **inst)
                            for k, s in zip((0, 2), states)]
    del doc["propellers"]["cruise"]
    doc.pop("groups", None)                 # named groups of the seven installations
    model = loads(tomli_w.dumps(doc), "small_x57.toml")
    return model.with_(wing_aero=wing_aero)


def _small_doc() -> dict:
    doc = tomllib.loads((ROOT / "examples" / "x57_like.toml").read_text())
    doc["wing"].update(n_elements=2, semi_span_m=2.4)
    doc["installations"] = [doc["installations"][k] for k in (0, 2)]
    del doc["propellers"]["cruise"]
    doc.pop("groups", None)
    return doc


_SMALL_DOC = _small_doc()


def _system(model, V):
    s = model.second_order(np.atleast_1d(np.asarray(V, dtype=float)))
    return s.S1, s.S2, s.S3


def _pitch_yaw_frequencies(model, V: float) -> np.ndarray:
    """Frequencies [Hz] of the modes whose displacement lies mostly (> 50 %) in the
    propellers' pitch and yaw DOFs, at airspeed V [m/s]."""
    A = model.state_matrix(np.array([V]))[0]
    lam, X = np.linalg.eig(A)
    labels = model.dof_map().q_labels
    idx = [k for k, lab in enumerate(labels) if lab.startswith("propeller")]
    q = np.abs(X[:len(labels)]) ** 2
    share = q[idx].sum(axis=0) / q.sum(axis=0)
    keep = (lam.imag > 1e-6) & (share > 0.5)
    return np.sort(lam.imag[keep] / (2 * np.pi))


# ----------------------------------------------------------------------------- stopped
def test_stopped_is_the_propeller_without_spin_or_aerodynamics():
    base = small_x57()
    stopped = small_x57(("stopped", "stopped"))
    plain = base.with_(rotating=False, propellers=tuple(replace(i, aero=False)
                                                        for i in base.propellers))
    for a, b in zip(_system(stopped, [40.0, 160.0]), _system(plain, [40.0, 160.0])):
        np.testing.assert_array_equal(a, b)
    assert not any(p.spinning for p in stopped.dof_map().propellers)


def test_stopped_mount_modes_do_not_move_with_airspeed():
    """Issue 25: with the rotors stopped, the pitch/yaw modes are mount modes: without wing
    aerodynamics nothing of the system depends on V; the operating rotors' do (Ω ∝ V)."""
    stopped = small_x57(("stopped", "stopped"), wing_aero=False)
    for a, b in zip(_system(stopped, 50.0), _system(stopped, 200.0)):
        np.testing.assert_array_equal(a, b)
    turning = small_x57(wing_aero=False)
    assert not np.allclose(_system(turning, 50.0)[1], _system(turning, 200.0)[1])


def test_x57_forward_whirl_no_longer_climbs_when_stopped():
    """The x57 check on two propellers (their four lowest pitch/yaw modes): operating, the
    forward-whirl branches climb with V (Ω ∝ V: 16 → 36 Hz from 50 to 200 m/s); stopped,
    they are mount modes near the 12 Hz mounts that do not move with V."""
    turning = small_x57()
    f50, f200 = (_pitch_yaw_frequencies(turning, V)[:4] for V in (50.0, 200.0))
    assert f200.max() > 1.5 * f50.max() > 1.5 * 12.0
    stopped = small_x57(("stopped", "stopped"))
    f50, f200 = (_pitch_yaw_frequencies(stopped, V)[:4] for V in (50.0, 200.0))
    assert np.all(np.abs(f50 - 12.0) < 2.5) and np.all(np.abs(f200 - 12.0) < 2.5), (f50, f200)
    assert np.max(np.abs(f200 - f50)) < 0.5


# ----------------------------------------------------------------------------- feathered
def _fin_propeller():
    """A propeller whose blades are plain fins: constant chord, a = 2π, no compressibility
    or aspect-ratio factor (so the fin estimate is exact)."""
    m = small_x57()
    p = m.propellers[0].propeller
    return m, replace(p, aero_settings=AeroSettings(compressibility=False,
                                                    aspect_ratio_correction=False))


def test_feathered_blades_are_the_omega_to_zero_limit_of_houbolt_reed():
    """stopped_blades is the limit Ω → 0 of the blade-element derivatives (evaluated by the
    runtime's own integrals at ever smaller Ω: the error falls in proportion to Ω)."""
    p = small_x57().propellers[0].propeller
    geo = p.default_derivatives().geometry
    V = np.array([60.0, 180.0])
    limit = stopped_blades(geo, V, 320.0, p.aero_settings)
    err = []
    for om in (1e-1, 1e-2):
        d = derivatives(geo, V, om, 320.0, settings=p.aero_settings).derivatives()
        err.append(max(float(np.max(np.abs(d[k] - limit[k]))) for k in d))
    assert err[1] < 0.2 * err[0] and err[1] < 1e-4 * float(np.max(limit["CY_psi"]))
    assert set(k for k, x in limit.items() if np.any(x != 0)) == {"CY_psi", "CZ_theta"}


def test_feathered_side_force_is_the_fin_estimate():
    """Each blade a fin: side force per radian of nacelle yaw q N_b c (R − r0) a/2 at the hub;
    in the model its moment about the yaw pivot softens the yaw mount by that force × |e_ψ|
    (tractor: hub ahead of the pivot), and likewise pitch."""
    model, p = _fin_propeller()
    V, rho = 120.0, model.flight.density
    q = 0.5 * rho * V ** 2
    force = q * p.n_blades * p.blade_chord * (p.radius - p.hub_radius) * 2 * math.pi / 2
    d = stopped_blades(p.default_derivatives().geometry, np.array([V]), None, p.aero_settings)
    assert d["CY_psi"][0] * q * math.pi * p.radius ** 2 == pytest.approx(force, rel=1e-12)
    inst = replace(model.propellers[0], propeller=p)
    feathered = model.with_(propellers=(replace(inst, state="feathered"),))
    stopped = model.with_(propellers=(replace(inst, state="stopped"),))
    labels = feathered.dof_map().q_labels
    t, s = labels.index("propeller 1 theta"), labels.index("propeller 1 psi")
    dK = _system(feathered, V)[2][0] - _system(stopped, V)[2][0]
    assert dK[s, s] == pytest.approx(-force * abs(p.e_psi), rel=1e-9)
    assert dK[t, t] == pytest.approx(-force * abs(p.e_theta), rel=1e-9)
    assert dK[t, s] == 0.0 and dK[s, t] == 0.0          # no cross-coupling: nothing turns
    G = _system(feathered, V)[1][0]
    assert G[t, s] == G[s, t]                           # Ω = 0: no gyroscopic (skew) part


def test_feathered_needs_the_blade_geometry():
    p = small_x57().propellers[0].propeller
    measured = replace(p, derivatives=MeasuredDerivatives({"CY_psi": 0.1}), blade_chord=None)
    Installation(measured, 1.0, state="stopped")        # stopped needs no blades
    with pytest.raises(InputError, match=r"^state = 'feathered' is invalid.*blade_chord"):
        Installation(measured, 1.0, state="feathered")


# ----------------------------------------------------------------------------- rotation
def test_rotation_override_equals_a_mirrored_propeller_table():
    base = small_x57()
    inst = base.propellers[0]
    over = base.with_(propellers=(replace(inst, rotation=-1), base.propellers[1]))
    table = base.with_(propellers=(replace(inst, propeller=replace(inst.propeller, rotation=-1)),
                                   base.propellers[1]))
    for a, b in zip(_system(over, [70.0, 140.0]), _system(table, [70.0, 140.0])):
        np.testing.assert_array_equal(a, b)
    assert [p.rotation for p in over.dof_map().propellers] == [-1, 1]
    assert not np.allclose(_system(over, 70.0)[2], _system(base, 70.0)[2])


def test_rotation_override_mirrors_measured_derivatives():
    base = small_x57(wing_aero=False)
    inst = base.propellers[0]
    values = {"CY_psi": 0.3, "CZ_psi": 0.05, "Cm_psi": 0.02, "CY_theta": 0.05}
    p = replace(inst.propeller, derivatives=MeasuredDerivatives(values))
    mirrored = MeasuredDerivatives({k: (-x if k in ("CZ_psi", "Cm_psi", "CY_theta") else x)
                                    for k, x in values.items()})
    over = base.with_(propellers=(replace(inst, propeller=p, rotation=-1),))
    table = base.with_(propellers=(replace(inst, propeller=replace(p, rotation=-1,
                                                                     derivatives=mirrored)),))
    for a, b in zip(_system(over, 90.0), _system(table, 90.0)):
        np.testing.assert_allclose(a, b, rtol=0, atol=0)


@pytest.mark.parametrize("field,value,match", [
    ("rotation", 0, r"^rotation = 0 is invalid: must be \+1 or -1"),
    ("rotation", 2, r"^rotation = 2 is invalid"),
    ("rotation", True, r"^rotation = True is invalid"),
    ("rotation", 1.0, r"^rotation = 1\.0 is invalid"),
    ("rotation", "cw", r"^rotation = 'cw' is invalid"),
    ("state", "folded", r"^state = 'folded' is invalid"),
    ("state", "windmilling", r"^state = 'windmilling' is invalid: windmilling is state = "
                             r"'operating' of a propeller with operation = 'fixed-pitch'"),
    ("state", None, r"^state = None is invalid"),
])
def test_bad_state_or_rotation_is_a_one_line_error(field, value, match):
    p = small_x57().propellers[0].propeller
    with pytest.raises(InputError, match=match) as exc:
        Installation(p, 1.0, **{field: value})
    assert "\n" not in str(exc.value)


# ----------------------------------------------------------------------------- model file
def test_model_file_keys_round_trip_and_old_files_keep_loading():
    m = small_x57(("feathered", "stopped"), rotation=-1)
    assert [(i.state, i.rotation, i.sense) for i in m.propellers] == [
        ("feathered", -1, -1), ("stopped", -1, -1)]
    assert loads(dumps(m)) == m
    old = loads((ROOT / "examples" / "x57_like.toml").read_text(), "x57_like.toml")
    assert {(i.state, i.rotation) for i in old.propellers} == {("operating", None)}


@pytest.mark.parametrize("key,value,match", [
    ("state", "windmilling", "must be one of operating, feathered, stopped"),
    ("state", 1, "must be a string"),
    ("rotation", 0, r"must be \+1 or -1"),
    ("rotation", -1.0, "must be an integer"),
    ("rotation", "ccw", "must be an integer"),
])
def test_model_file_bad_values_name_the_installation(key, value, match):
    doc = tomllib.loads((ROOT / "examples" / "x57_like.toml").read_text())
    doc["installations"][3][key] = value
    with pytest.raises(InputError, match=rf"^x57\.toml: \[installations\[3\]\] {key} = .*{match}"):
        loads(tomli_w.dumps(doc), "x57.toml")


# ----------------------------------------------------------------------------- Campbell
def test_campbell_with_a_stopped_propeller_has_it_at_zero_rpm():
    m = small_x57(("stopped", "operating"), wing_aero=False)
    assert operating_rpm_ratio(m) == (0.0, 1.0)
    assert operating_rpm_ratio(small_x57(("stopped", "stopped"))) == (0.0, 0.0)
    with np.errstate(all="raise"):
        c = campbell(m, [0.0, 3000.0, 6000.0], max_frequency_hz=40.0)
    assert c.rpm_ratio == (0.0, 1.0)
    assert np.all(np.isfinite(c.frequency_hz))


# ----------------------------------------------------------------------------- sensitivities
def test_parameter_derivatives_follow_the_states_and_the_override():
    """Exact parameter derivatives (propwhirl.model.derivatives) of a feathered, a stopped
    and a reversed installation equal central differences; only the turning rotor has
    rotation parameters, and a reversed rotor's measured derivatives enter mirrored."""
    from helpers.derivative_checks import assert_matches_central_differences
    from propwhirl.model import derivatives as D

    base = small_x57(("feathered", "operating"), wing_aero=False)
    third = replace(base.propellers[1], y=2.4, state="stopped")
    measured = replace(base.propellers[1].propeller, derivatives=MeasuredDerivatives(
        {"CY_psi": 0.3, "CZ_psi": 0.05, "Cm_psi": 0.02, "Cn_q": -0.1}))
    reversed_ = replace(base.propellers[1], propeller=measured, rotation=-1)
    model = base.with_(propellers=(base.propellers[0], reversed_, third))
    pars = D.parameters(model)
    rotation = {(p.index, p.name) for p in pars if p.kind == "rotation"}
    assert rotation == {(1, "beta_075_deg"), (1, "zero_lift_angle_deg")}
    chosen = [p for p in pars if p.kind in ("propeller", "rotation") and (
        p.name.startswith(("pivot", "K_", "C")) or p.kind == "rotation")]
    assert {p.index for p in chosen} == {0, 1, 2}
    assert any(p.name == "CZ_psi" and p.index == 1 for p in chosen)
    Vs = np.array([60.0, 140.0])
    derivs = D.second_order_derivatives(model, Vs, chosen)
    for par in chosen:
        assert_matches_central_differences(model, par, derivs[par.path], Vs)


def test_mode_names_count_only_the_turning_rotors():
    """A stopped rotor's pitch and yaw do not split into backward and forward whirl: with one
    of two propellers stopped, one backward and one forward mode are named (before: two of
    each, one pair of them arbitrary)."""
    from propwhirl.analysis.modes import label_modes

    kinds = [lab.split()[0] for lab, _ in label_modes(small_x57(("stopped", "operating")))]
    assert kinds.count("backward") == 1 and kinds.count("forward") == 1
    kinds = [lab.split()[0] for lab, _ in label_modes(small_x57(("stopped", "stopped")))]
    assert set(kinds) == {"wing"}


# ----------------------------------------------------------------------------- fuzz-style
_ANY = st.one_of(st.integers(-3, 3), st.floats(allow_nan=True, allow_infinity=True),
                 st.booleans(), st.text(max_size=12),
                 st.sampled_from(["operating", "feathered", "stopped", "windmilling",
                                  "Stopped", " stopped"]),
                 st.lists(st.integers(-1, 1), max_size=2),
                 st.dictionaries(st.sampled_from(["a", "state"]), st.integers(), max_size=1))


@settings(max_examples=60, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.too_slow])
@given(state=st.one_of(st.none(), _ANY), rotation=st.one_of(st.none(), _ANY),
       which=st.integers(0, 1))
def test_any_state_or_rotation_in_a_file_loads_or_is_one_line(state, rotation, which):
    """Whatever a file gives as state and rotation of an installation: the model it means
    (a valid state and ±1), or an InputError of one line per error (a reader that reports
    every error of a file at once gives one line each), each naming the file and the
    installation."""
    doc = dict(_SMALL_DOC, installations=[dict(i) for i in _SMALL_DOC["installations"]])
    for key, value in (("state", state), ("rotation", rotation)):
        if value is not None:
            doc["installations"][which][key] = value
    try:
        m = loads(tomli_w.dumps(doc), "fz.toml")
    except InputError as exc:
        lines = getattr(exc, "errors", None) or [str(exc)]
        assert "\n".join(lines) == str(exc)
        for msg in lines:
            assert "\n" not in msg and msg.startswith(f"fz.toml: [installations[{which}]] ")
        return
    inst = m.propellers[which]
    assert inst.state == (state if state is not None else "operating")
    assert inst.rotation == rotation and inst.sense in (1, -1)
    assert type(inst.rotation) in (int, type(None))


def test_campbell_command_names_the_turning_propeller(tmp_path, capsys):
    """`propwhirl campbell` with the first propeller stopped: the RPM axis is the turning
    propeller's and the stopped one is said to be still (before: "RPM of propeller 1", the
    stopped one)."""
    from propwhirl.app import cli

    path = tmp_path / "m.toml"
    path.write_text(dumps(small_x57(("stopped", "operating"))))
    assert cli.main(["campbell", str(path), "--rpm", "0", "3000", "2"]) == 0
    out = capsys.readouterr().out.splitlines()
    assert out[1] == "  RPM of propeller 2; propeller 1 not turning (stopped or feathered)"


def test_reversing_one_rotor_is_a_mirror_image_without_in_plane_bending():
    """Without in-plane bending nothing of the wing moves sideways, so reversing one rotor
    (gyroscopic sign and the eight cross derivatives together) is the mirror image ψ → −ψ of
    its yaw: the same eigenvalues.  In-plane bending couples the yaw to the wing (χ_P): then
    the sense matters."""
    def eig(model):
        return np.sort(np.abs(np.linalg.eigvals(model.state_matrix(np.array([150.0]))[0])))

    base = small_x57()
    flip = base.with_(propellers=(replace(base.propellers[0], rotation=-1), base.propellers[1]))
    np.testing.assert_allclose(eig(flip), eig(base), rtol=1e-9)
    inplane = base.with_(wing=replace(base.wing, EI_chordwise=5e6))
    flip_ip = inplane.with_(propellers=(replace(inplane.propellers[0], rotation=-1),
                                        inplane.propellers[1]))
    assert not np.allclose(eig(flip_ip), eig(inplane), rtol=1e-6)


def test_tip_mach_warning_names_only_the_turning_rotors():
    """The helical-tip-Mach warning is about turning blades: a feathered rotor's tips move
    with the free stream, a stopped one has no propeller aerodynamics."""
    from propwhirl.model.aerodynamics import validity

    for states in (("feathered", "operating"), ("stopped", "operating")):
        m = small_x57(states)
        (tip,) = [w for w in validity.analysis_warnings(m, (1.0, 250.0), [(240.0, "x")], True)
                  if "tip Mach" in w]
        assert tip.startswith("propeller 2: helical tip Mach number")
