"""The failure-case envelope of CS/14 CFR 25.629(b)(2) in a campaign (issue 24): the (ii) line
against hand ISA values, which cases are failures, the required speed and its rule of each
case, a failure case that clears at V_D but not at 1.15 V_D, and the rule in every output."""
from __future__ import annotations

import dataclasses
import json
import math
from pathlib import Path

import pytest

from propwhirl.analysis.stability import analyse
from propwhirl.app.report import report_html
from propwhirl.io import load_model
from propwhirl.studies import campaign as C
from propwhirl.validate import InputError

ROOT = Path(__file__).resolve().parents[2]
ALTITUDE = 2438.4

# ------------------------------------------------------------------ the ISA, by hand
_R, _G, _L, _T0, _RHO0 = 287.05287, 9.80665, 0.0065, 288.15, 1.225
_N = _G / (_R * _L)                 # 5.25588: p ~ T^n in the troposphere


def _isa(h: float) -> tuple[float, float]:
    """(speed of sound [m/s], density ratio σ) of the ISA at geopotential h [m] <= 20 km."""
    if h <= 11000.0:
        T = _T0 - _L * h
        sigma = (T / _T0) ** (_N - 1.0)
    else:
        T = _T0 - _L * 11000.0
        sigma = (T / _T0) ** (_N - 1.0) * math.exp(-_G * (h - 11000.0) / (_R * T))
    return math.sqrt(1.4 * _R * T), sigma


def _mach_eas(M: float, h: float) -> float:
    a, sigma = _isa(h)
    return M * a * math.sqrt(sigma)


def _root(f, lo: float, hi: float) -> float:
    for _ in range(200):                  # bisection: f(lo) > 0 > f(hi)
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if f(mid) > 0 else (lo, mid)
    return 0.5 * (lo + hi)


def test_the_b2_ii_line_against_hand_isa_values():
    """V_C = 130 m/s EAS, M_C = 0.5: 1.15 V_C up to h1 (1.15 V_C = M_C there), linear in EAS to
    M_C + 0.05 at h2 (V_C = M_C there), then M_C + 0.05 at constant altitude."""
    V_C, M_C = 130.0, 0.5
    h1 = _root(lambda h: _mach_eas(M_C, h) - 1.15 * V_C, 0.0, 11000.0)
    h2 = _root(lambda h: _mach_eas(M_C, h) - V_C, 0.0, 11000.0)
    assert 1500.0 < h1 < 2500.0 < h2 < 5000.0           # the hand numbers are where they should be
    top = _mach_eas(M_C + 0.05, h2)
    mid = 0.5 * (h1 + h2)
    alts = [-1000.0, 0.0, 1000.0, h1 - 1.0, mid, h2 + 1.0, 8000.0, 12000.0]
    want = [1.15 * V_C, 1.15 * V_C, 1.15 * V_C, 1.15 * V_C, 0.5 * (1.15 * V_C + top),
            _mach_eas(0.55, h2 + 1.0), _mach_eas(0.55, 8000.0), _mach_eas(0.55, 12000.0)]
    got = C.failure_line(alts, V_C, M_C)
    assert [eas for eas, _ in got] == pytest.approx(want, rel=2e-5)
    assert [part for _, part in got] == ["1.15 V_C"] * 4 + ["V_C-M_C line"] + ["M_C + 0.05"] * 3
    # as the envelope's points: the line as a true airspeed, V_TAS = V_EAS / sqrt(sigma)
    pts = C.envelope(200.0, [0.0, 8000.0], V_C=V_C, M_C=M_C)
    assert pts[1].V_line == pytest.approx(_mach_eas(0.55, 8000.0) / math.sqrt(_isa(8000.0)[1]),
                                          rel=2e-5)
    assert pts[1].V_line == pytest.approx(0.55 * _isa(8000.0)[0], rel=2e-5)   # = M a(h) as TAS
    # without M_C: 1.15 V_C at every altitude; V_C per altitude: each its own
    assert C.failure_line([0.0, 9000.0], 130.0) == [(149.5, "1.15 V_C")] * 2
    assert [x for x, _ in C.failure_line([0.0, 9000.0], [100.0, 120.0])] == \
        pytest.approx([115.0, 138.0])


def test_which_cases_are_failures():
    assert not C.Case("nominal").is_failure
    for kw in ({"mount_stiffness": 0.5}, {"mount_damping": 0.0}, {"state": "feathered"},
               {"state": "stopped"}, {"rpm_factor": 1.1}):
        assert C.Case("x", **kw).is_failure, kw
    for kw in ({"reverse_rotation": True}, {"added_masses": ((20.0, -0.5),)},
               {"wing_damping": 0.5}, {"operation": "windmilling"}, {"mount_stiffness": 2.0}):
        assert not C.Case("x", **kw).is_failure, kw
    assert C.Case("x", reverse_rotation=True, failure=True).is_failure
    assert not C.Case("x", mount_damping=0.0, failure=False).is_failure
    assert C.Case("a", reverse_rotation=True).combine(C.Case("b", mount_damping=0.0)).is_failure
    with pytest.raises(InputError, match="failure = 'yes' is invalid"):
        C.Case("x", failure="yes")


def test_required_speed_and_rule_of_each_regulation(model):
    pts = C.envelope(100.0, [0.0, 9000.0], airspeed="TAS", V_C=80.0, M_C=0.4)
    nominal, failed = C.Case("nominal"), C.Case("damper", mount_damping=0.0)
    c = C.Campaign("c", model, (nominal, failed), pts, "cs25", 1.15)
    assert c.required_speed(nominal, pts[0]) == (pytest.approx(115.0), "25.629(b)(1) 1.15 V_D")
    assert c.required_speed(failed, pts[0]) == (100.0, "25.629(b)(2)(i) V_D")  # 92 EAS < V_D
    V, rule = c.required_speed(failed, pts[1])       # 0.45 a(9000 m) = 136.5 m/s TAS > V_D
    assert rule == "25.629(b)(2)(ii) M_C + 0.05" and V == pytest.approx(0.45 * 303.79, rel=1e-3)
    # Part 23 and explicit factors: every case, failure or not, at the factor times V_D
    pts23 = C.envelope(100.0, [0.0], airspeed="TAS")
    for reg, f, rule in (("far23", 1.2, "23.629 1.2 V_D"), ("explicit", 1.25, "1.25 V_D")):
        c = C.Campaign("c", model, (nominal, failed), pts23, reg, f)
        assert c.required_speed(failed, pts23[0]) == (pytest.approx(100.0 * f), rule)
    with pytest.raises(InputError, match="V_C is invalid with regulation 'far23'"):
        C.Campaign("c", model, (failed,), pts, "far23", 1.2)


@pytest.fixture(scope="module")
def model():
    """The wingtip model, coarse (8 elements: a fraction of a second per analysis)."""
    m = load_model(ROOT / "examples" / "wingtip.toml")
    return dataclasses.replace(m, wing=dataclasses.replace(m.wing, n_elements=8))


def test_failure_case_clears_at_V_D_but_not_at_115_V_D(model, tmp_path):
    """V_crit between V_D and 1.15 V_D: the nominal model does not clear (1.15 V_D), the same
    model as a failure case does (V_D, 25.629(b)(2)(i)); with a V_C whose 1.15 V_C lies above
    V_crit the failure case is held to that line and does not clear."""
    vcrit = float(analyse(C.at_altitude(model, ALTITUDE)).critical.V)
    V_D = vcrit / 1.075
    cases = (C.Case("nominal"), C.Case("nominal as a failure", failure=True))
    r = C.run_campaign(C.Campaign("c", model, cases, C.envelope(V_D, [ALTITUDE],
                                                                airspeed="TAS")))
    nominal, failure = r.rows
    assert nominal.critical_speed == pytest.approx(vcrit, abs=0.02)
    assert failure.critical_speed == pytest.approx(nominal.critical_speed, abs=1e-9)
    assert not nominal.cleared and nominal.rule == "25.629(b)(1) 1.15 V_D"
    assert failure.cleared and failure.rule == "25.629(b)(2)(i) V_D"
    assert failure.V_required == V_D and failure.margin_percent == pytest.approx(7.5, abs=0.05)
    # the rule and the required speed in every output
    assert "rule" in r.to_csv().splitlines()[0].split(",")
    assert "25.629(b)(2)(i) V_D" in r.to_csv() and "25.629(b)(2)(i) V_D" in r.format()
    assert "failure cases: 25.629(b)(2)" in r.format()
    page = report_html(r, figures=False)
    assert "<th>rule</th>" in page and "25.629(b)(2)(i) V_D" in page
    r.save(tmp_path / "c.json")
    back = C.CampaignResult.load(tmp_path / "c.json")
    assert [x.rule for x in back.rows] == [nominal.rule, failure.rule]
    # a file written before the rule (no "rule" key) reads with rule ""
    doc = json.loads((tmp_path / "c.json").read_text())
    for row in doc["rows"]:
        del row["rule"]
    (tmp_path / "old.json").write_text(json.dumps(doc))
    assert [x.rule for x in C.CampaignResult.load(tmp_path / "old.json").rows] == ["", ""]
    # 1.15 V_C (EAS) 2 % above V_crit: the failure case is held to it
    sigma = _isa(ALTITUDE)[1]
    V_C = 1.02 * vcrit * math.sqrt(sigma) / 1.15
    r = C.run_campaign(C.Campaign("c", model, cases[1:], C.envelope(
        V_D, [ALTITUDE], airspeed="TAS", V_C=V_C)))
    (row,) = r.rows
    assert row.rule == "25.629(b)(2)(ii) 1.15 V_C" and not row.cleared
    assert row.V_required == pytest.approx(1.02 * vcrit, rel=1e-4)


def test_one_required_speed_and_one_regulation_table(model):
    """Issue 38 item 2: the required speed and the regulations are defined once
    (propwhirl.certification); the margin, the clearance, the campaign and the campaign files
    use that one."""
    from propwhirl import certification
    from propwhirl.analysis import margin
    from propwhirl.io import campaign_files
    from propwhirl.studies import clearance
    # the old names keep their old returns, through the one definition: the speed alone
    # (analysis.margin, studies.clearance) and the campaign's (speed, rule) of a case at a point
    assert margin.required_speed is clearance.required_speed
    assert margin.required_speed(130.0, 1.2) == certification.required_speed(130.0, 1.2)[0]
    (p,) = C.envelope(100.0, [0.0], airspeed="TAS")
    nominal = C.Case("nominal")
    c = C.Campaign("c", model, (nominal,), (p,), "cs25", 1.15)
    assert C.required_speed(c, nominal, p) == c.required_speed(nominal, p) \
        == (pytest.approx(115.0), "25.629(b)(1) 1.15 V_D")
    assert C.REGULATIONS is certification.REGULATIONS
    assert campaign_files.FACTOR_RANGES is certification.CASE_FACTORS
    assert certification.required_speed(130.0) == (pytest.approx(149.5), "1.15 V_D")
    assert certification.required_speed(130.0, 1.2, "far23", failure=True) == (
        pytest.approx(156.0), "23.629 1.2 V_D")
    with pytest.raises(InputError, match=r"^--vd = -1\.0 m/s is invalid: must be > 0$"):
        certification.required_speed(-1.0, vd_name="--vd")
