"""Clearance of the wingtip model (§10.1): pass/fail logic, margins, minimum mount frequency."""
from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from propwhirl.analysis.stability import analyse
from propwhirl.cases.registry import case_model
from propwhirl.studies import paths as P
from propwhirl.studies.clearance import clearance, clearance_speeds, minimum_frequency
from propwhirl.studies.critical import critical_instability, wing_divergence_predicate
from propwhirl.validate import InputError


@pytest.fixture(scope="module")
def model():
    return case_model("wingtip")


@pytest.fixture(scope="module")
def failed(model):
    return clearance(model, 130.0, 1.15, minimum=False)


@pytest.fixture(scope="module")
def thesis(model):
    return clearance(model, 130.0, 1.15, minimum=False, static_divergence=False, low_speed=False)


def test_the_wing_divergence_below_1_15_vd_fails(failed):
    assert failed.V_required == pytest.approx(149.5)
    assert not failed.cleared
    c = failed.critical
    assert (c.kind, c.mode) == ("divergence", "wing 1")
    assert c.margin == pytest.approx(c.V / 149.5 - 1.0) and c.margin < 0
    # every instability of the range is listed, each with its margin, sorted as analysed
    assert [m.kind for m in failed.margins][:2] == ["divergence", "flutter"]
    assert all(m.margin == pytest.approx(m.V / 149.5 - 1) for m in failed.margins)
    assert all(m.counted for m in failed.margins)
    assert "NOT CLEARED" in failed.format()


def test_the_thesis_convention_clears_on_the_whirl_flutter(thesis, failed):
    assert thesis.cleared
    c = thesis.critical
    assert c.kind == "flutter" and c.margin > 0
    div = [m for m in thesis.margins if m.kind == "divergence" and m.event == "onset"]
    assert div and not div[0].counted           # listed, but the convention leaves it out
    assert thesis.critical.V == pytest.approx(failed.margins[1].V)


def test_a_lower_vd_clears_and_the_factor_1_2(model):
    r = clearance(model, 100.0, minimum=False)
    assert r.cleared and r.critical.margin == pytest.approx(r.critical.V / 115.0 - 1)
    r = clearance(model, 100.0, 1.2, minimum=False)
    assert r.V_required == pytest.approx(120.0) and r.cleared


def test_the_speed_range_reaches_beyond_factor_vd(model):
    s = clearance_speeds(model, 400.0)
    assert s[-1] >= 420.0 and s[0] == model.flight.speed_range[0]
    with pytest.raises(InputError, match="must reach beyond"):
        clearance_speeds(model, 400.0, np.arange(1.0, 300.0, 10.0))


def _critical_speed(model, speeds):
    a = analyse(model, speeds)
    e = critical_instability(a, static_divergence=False, low_speed=False,
                             is_wing_divergence=wing_divergence_predicate(model, a))
    return math.inf if e is None else e.V


def test_the_minimum_pitch_frequency_really_clears(model, thesis):
    speeds = clearance_speeds(model, thesis.V_required)
    q = minimum_frequency(model, 0, "f_theta", thesis.V_required, speeds,
                          frequency_range=(3.0, 9.0), n_scan=3, frequency_tol=0.01,
                          static_divergence=False, low_speed=False)
    assert q.status == "found" and 3.0 < q.frequency < 9.0 and q.current == 7.0
    par = P.resolve(model, "propellers[0].propeller.f_theta")
    assert _critical_speed(par.set(model, q.frequency), speeds) > thesis.V_required
    assert _critical_speed(par.set(model, q.frequency - 0.05), speeds) <= thesis.V_required
    assert q.critical_speed > thesis.V_required


def test_no_frequency_in_the_range_clears_a_wing_divergence(model, failed):
    speeds = clearance_speeds(model, failed.V_required)
    q = minimum_frequency(model, 0, "f_psi", failed.V_required, speeds, frequency_range=(3.0, 12.0))
    assert q.status == "none in range" and q.frequency is None and q.analyses == 1


def test_files(failed, tmp_path):
    import json

    failed.save_json(tmp_path / "c.json")
    d = json.loads((tmp_path / "c.json").read_text())
    assert d["cleared"] is False and d["critical"]["mode"] == "wing 1"
    text = failed.to_csv(tmp_path / "c.csv")
    assert text.splitlines()[1].endswith(",no") and "instability,divergence,onset,wing 1" in text


def test_the_minimum_frequency_says_what_decides_it(model, thesis, failed):
    """Issue 35 item 7: each minimum names the instability that sets it (kind, mode, speed):
    the critical instability of the model at that frequency, as an analysis of it finds;
    where none clears, the one at the range's top; and the text says it."""
    from propwhirl.studies import sweeps

    speeds = clearance_speeds(model, thesis.V_required)
    q = minimum_frequency(model, 0, "f_theta", thesis.V_required, speeds,
                          frequency_range=(3.0, 9.0), n_scan=3, frequency_tol=0.01,
                          static_divergence=False, low_speed=False)
    par = P.resolve(model, "propellers[0].propeller.f_theta")
    row = sweeps.evaluate((par.set(model, q.frequency), speeds, 0.01, False, False))
    assert (q.kind, q.mode) == (row["kind"], row["critical_mode"]) and q.kind == "flutter"
    assert q.critical_speed == pytest.approx(row["critical_speed"], abs=0.02)
    r = dataclasses.replace(thesis, minimum=(q,))
    line = [x for x in r.format().splitlines() if "minimum pitch" in x][0]
    assert f"; set by flutter of {q.mode} at {q.critical_speed:.2f} m/s" in line
    again = type(r).from_dict(r.to_dict())
    assert again.minimum[0].kind == q.kind and again.minimum[0].mode == q.mode
    none = minimum_frequency(model, 0, "f_psi", failed.V_required,
                             clearance_speeds(model, failed.V_required),
                             frequency_range=(3.0, 12.0))
    assert none.status == "none in range" and none.kind == "divergence"
    text = dataclasses.replace(failed, minimum=(none,)).format()
    assert f"; fails by divergence of {none.mode} (at the range's top)" in text


def test_a_progress_callback_sees_one_count_over_the_minimum_search(model):
    """Issue 35 item 8: the three phases of the minimum-frequency search (top, scan, refine)
    were three counts (8, then 24, then 0 of the four-propeller wing); now one, whose total
    never falls and which ends done."""
    seen = []
    clearance(model, 100.0, frequency_range=(3.0, 12.0), n_scan=3,
              progress=lambda done, total: seen.append((done, total)))
    totals = [t for _, t in seen]
    dones = [d for d, _ in seen]
    assert totals[0] == 2 * (3 + 1) and totals == sorted(totals)
    assert dones == sorted(dones) and seen[-1][0] == seen[-1][1]
