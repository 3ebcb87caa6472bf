"""Verification runs of exact sensitivities (issue 26, item 3): central differences of the
critical speed at p(1 ± 1e-3) agree with the exact dV_crit/dp within the stated tolerance, in
exactly 2N analyses run as one batch; a wrong exact value, a changed critical mode and a
variant that cannot be built are flagged in the result, never an exception."""
from __future__ import annotations

import json
from dataclasses import replace

import pytest

from propwhirl.analysis import analyse, critical_sensitivities
from propwhirl.cases.ch09_baseline import baseline_flight, baseline_propeller, baseline_wing
from propwhirl.model.systems import Installation, PropellerWing
from propwhirl.studies import execution
from propwhirl.studies import sensitivity_check as SC
from propwhirl.validate import InputError

PIVOT = "propellers[0].propeller.pivot_pitch"       # value 0: the absolute step δ R


@pytest.fixture(scope="module")
def small():
    """A 5-element wingtip-propeller model, its analysis and the sensitivities of its critical
    point (the wing's divergence onset, 142.95 m/s)."""
    m = PropellerWing(baseline_wing(5), baseline_flight(),
                      (Installation(baseline_propeller(), 5.7),), name="small tip model")
    a = analyse(m)
    return m, a, critical_sensitivities(m, a)


@pytest.fixture(scope="module")
def verified(small):
    """The top 4 and the pivot (value 0) checked, the analyses counted (one batch)."""
    m, a, cs = small
    counts = {"analyses": 0, "batches": 0}
    real_analyse, real_map = SC.analyse, execution.map_analyses

    def counting_analyse(*args, **kw):
        counts["analyses"] += 1
        return real_analyse(*args, **kw)

    def counting_map(*args, **kw):
        counts["batches"] += 1
        return real_map(*args, **kw)

    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(SC, "analyse", counting_analyse)
        mp.setattr(execution, "map_analyses", counting_map)
        r = SC.verify_sensitivities(m, a, cs, [PIVOT, *(s.path for s in cs.ranked(4))])
    return r, counts


def test_central_differences_agree_with_the_exact_sensitivities(small, verified):
    m, a, cs = small
    r, _ = verified
    assert r.passed and [c.status for c in r.checks] == ["ok"] * 5
    assert [c.path for c in r.checks] == [PIVOT, *(s.path for s in cs.ranked(4))]
    for c in r.checks:
        assert abs(c.rel_diff) < 1e-3, (c.path, c.rel_diff)   # well inside the 1 % tolerance
        exact = next(s for s in cs.sensitivities if s.path == c.path)
        assert c.dV_dp == exact.dV_dp
        assert c.fd == (c.V_plus - c.V_minus) / (2 * c.step)
    pivot = r.checks[0]
    assert pivot.value == 0.0 and pivot.step == pytest.approx(1e-3 * pivot.scale)
    assert r.checks[1].step == pytest.approx(1e-3 * abs(r.checks[1].value))
    assert "all 5 within tolerance" in r.format()


def test_the_work_is_two_analyses_per_parameter_in_one_batch(verified):
    r, counts = verified
    assert counts == {"analyses": 10, "batches": 1}
    assert r.analyses == 10


def test_a_wrong_exact_value_is_flagged(small):
    m, a, cs = small
    top = cs.ranked(2)
    wrong = replace(cs, sensitivities=(replace(top[0], dV_dp=1.05 * top[0].dV_dp), top[1]))
    r = SC.verify_sensitivities(m, a, wrong)
    assert [c.status for c in r.checks] == ["differs", "ok"]
    assert not r.passed and r.failed == [r.checks[0]]
    assert abs(r.checks[0].rel_diff) == pytest.approx(0.05, rel=1e-3)
    assert f"1 of 2 flagged: {top[0].path}" in r.format()


def test_a_parameter_that_cannot_be_set_is_said_so_and_the_others_run(small):
    """A path the model cannot set (here an invented one) is a failed check naming the error;
    a value outside its field's range likewise."""
    m, a, cs = small
    s = cs.ranked(1)[0]
    ghost = replace(s, path="wing.no_such_field")
    r = SC.verify_sensitivities(m, a, replace(cs, sensitivities=(ghost, s)))
    assert [c.status for c in r.checks] == ["failed", "ok"]
    assert "InputError" in r.checks[0].note and r.checks[0].fd is None
    assert "failed (InputError" in r.format()


def test_a_changed_critical_mode_is_flagged(small, monkeypatch):
    """When a perturbed analysis has no event of the mode, the nearest of another name is
    used and the check says so."""
    m, a, cs = small
    monkeypatch.setattr(SC, "same_event", lambda an, kind, event, label, V: (V, "wing 2", True))
    r = SC.verify_sensitivities(m, a, cs, top=1)
    assert r.checks[0].status == "event changed" and "wing 2" in r.checks[0].note
    assert not r.passed


def test_same_event_prefers_the_mode_then_the_nearest(small):
    m, a, cs = small
    assert SC.same_event(a, "flutter", "onset", "forward 1", 150.0)[1:] == ("forward 1", False)
    V, label, changed = SC.same_event(a, "flutter", "onset", "forward 9", 270.0)
    assert (label, changed) == ("backward 1", True)
    assert SC.same_event(a, "flutter", "recovery", "forward 1", 150.0) is None


def test_the_result_saves_and_loads(verified, tmp_path):
    r, _ = verified
    path = r.save(tmp_path / "check.json")
    doc = json.loads(path.read_text())
    assert doc["format"] == "propwhirl.sensitivity-check/1"
    assert doc["sensitivities"]["format"] == "propwhirl.sensitivities/2"
    assert set(doc["checks"][0]) >= {"dV_dp_exact_m_s_per_unit", "dV_dp_fd_m_s_per_unit",
                                     "V_plus_m_s", "V_minus_m_s", "rel_diff", "status"}
    back = SC.SensitivityVerification.load(path)
    assert back.to_dict() == r.to_dict()
    doc["passed"] = False
    with pytest.raises(InputError, match="passed"):
        SC.SensitivityVerification.from_dict(doc)


def test_inputs_are_checked_before_any_analysis(small):
    m, a, cs = small
    with pytest.raises(InputError, match="not one of the sensitivities"):
        SC.verify_sensitivities(m, a, cs, ["wing.nope"])
    with pytest.raises(InputError, match="rel_step"):
        SC.verify_sensitivities(m, a, cs, top=1, rel_step=0.5)
    with pytest.raises(InputError, match="CriticalSensitivities"):
        SC.verify_sensitivities(m, a, {"V": 1.0})
