"""The p-k analysis beside the finite-state one (analyse(model, method="pk")): the side-by-side
table of every instability (propwhirl.analysis.summary.compare_methods), the finite-state events
kept in the result and its file, and the participation and benignity of the p-k events
(propwhirl.analysis.pk_events.pk_instabilities)."""
import json
from dataclasses import replace

import numpy as np
import pytest

from propwhirl.analysis import analyse, load
from propwhirl.analysis.pk import BENIGNITY_STEP, pk_root
from propwhirl.analysis.stability import Instability, ModelAnalysis
from propwhirl.analysis.summary import FiniteState, compare_methods
from propwhirl.cases.ch07_patil import patil_model
from propwhirl.cases.registry import case_model
from propwhirl.model.systems import FlightCondition, TypicalSection
from propwhirl.validate import InputError

WINGTIP_SPEEDS = np.arange(10.0, 351.0, 20.0)
PATIL_SPEEDS = np.arange(5.0, 50.0, 5.0)


@pytest.fixture(scope="module")
def wingtip():
    m = case_model("wingtip")
    return m, analyse(m, WINGTIP_SPEEDS, method="pk")


@pytest.fixture(scope="module")
def patil():
    m = patil_model()
    return m, analyse(m, PATIL_SPEEDS, method="pk")


def _key(e):
    return (e.mode, e.kind, e.event)


def check_side_by_side(a: ModelAnalysis):
    """The structure of the comparison of a p-k analysis: every p-k event and every
    finite-state event in exactly one row, on the same mode, kind and event, the differences
    those of the two sides."""
    c = a.method_comparison()
    assert c is not None and a.finite_state is not None
    pk_rows = [(r.mode, r.kind, r.event, r.V_pk) for r in c.rows if r.V_pk is not None]
    fs_rows = [(r.mode, r.kind, r.event, r.V_fs) for r in c.rows if r.V_fs is not None]
    assert sorted(pk_rows) == sorted(_key(e) + (e.V,) for e in a.events)
    assert sorted(fs_rows) == sorted(_key(e) + (e.V,) for e in a.finite_state.events)
    by_pk = {(e.V, e.mode): e for e in a.events}
    by_fs = {(e.V, e.mode): e for e in a.finite_state.events}
    for r in c.rows:
        if r.V_pk is not None:
            e = by_pk[(r.V_pk, r.mode)]
            assert (e.label, e.frequency_hz) == (r.label, r.f_pk)
        if r.V_fs is not None:
            g = by_fs[(r.V_fs, r.mode)]
            assert (g.label, g.frequency_hz) == (r.label, r.f_fs)
        if r.found_by == "both":
            assert r.dV == r.V_pk - r.V_fs
            assert r.dV_percent == pytest.approx(100 * (r.V_pk - r.V_fs) / r.V_fs, rel=1e-12)
            assert r.df == r.f_pk - r.f_fs
            if r.f_fs > 0:
                assert r.df_percent == pytest.approx(100 * (r.f_pk - r.f_fs) / r.f_fs, rel=1e-12)
            else:
                assert r.df_percent is None
        else:
            assert r.dV is None and r.df is None and r.dV_percent is None
    speeds = [min(x for x in (r.V_pk, r.V_fs) if x is not None) for r in c.rows]
    assert speeds == sorted(speeds)
    return c


def check_text(a: ModelAnalysis):
    """The summary prints the table: its title naming the finite-state form, one line per row
    with that row's numbers, and the critical instability last."""
    c = a.method_comparison()
    text = a.summary()
    lines = text.splitlines()
    assert "instabilities (p-k method, exact Theodorsen function)" in lines[0]
    head = [i for i, line in enumerate(lines) if "vs finite-state" in line]
    assert len(head) == 1 and f"finite-state ({c.aerodynamics})" in lines[head[0]]
    body = lines[head[0] + 3: head[0] + 3 + len(c.rows)]
    for r, line in zip(c.rows, body):
        cells = line.split()
        assert r.kind == cells[0] and r.event == cells[1] and r.label in line
        want = [x for x in (r.V_pk, r.V_fs) if x is not None]
        for x in want:
            assert f"{x:.2f}" in cells
        if r.found_by == "both":
            assert f"{r.dV:+.2f}" in cells and f"{r.dV_percent:+.2f}" in cells
        else:
            assert cells.count("-") >= 4
    one_sided = [r for r in c.rows if r.found_by != "both"]
    for r in one_sided:
        assert f"{r.kind} {r.event} of {r.label}: found by the" in text
    assert lines[-1].startswith("  critical: ")


def test_wingtip_side_by_side(wingtip):
    _, a = wingtip
    c = check_side_by_side(a)
    check_text(a)
    assert c.aerodynamics == "Leishman-Nguyen"
    flutter = [r for r in c.rows if r.kind == "flutter" and r.event == "onset"]
    assert len(flutter) >= 2 and all(r.found_by == "both" for r in flutter)
    # the expectation: finite state within about 1 % of the exact aerodynamics
    assert all(abs(r.dV_percent) < 1.0 for r in flutter)
    # the finite state's pair turning real is not followed by the p-k continuation
    fz = [r for r in c.rows if r.event == "frequency-zero"]
    assert fz and all(r.found_by == "finite state only" for r in fz)
    assert "the p-k continuation follows oscillatory roots" in a.summary()


def test_patil_side_by_side(patil):
    _, a = patil
    c = check_side_by_side(a)
    check_text(a)
    assert [r.found_by for r in c.rows] == ["both"] * len(c.rows)
    assert {r.kind for r in c.rows} == {"flutter", "divergence"}
    assert all(abs(r.dV_percent) < 1.0 for r in c.rows)


def test_the_finite_state_events_are_those_of_the_dense_analysis(patil):
    m, a = patil
    fs = analyse(m, PATIL_SPEEDS, method="dense")
    assert a.finite_state.events == fs.events
    assert fs.finite_state is None and fs.method_comparison() is None
    assert "vs finite-state" not in fs.summary()


def test_wagner_is_named():
    sec = TypicalSection(b=1.0, a=-0.2, x_alpha=0.1, r_alpha=np.sqrt(6 / 25),
                         m=20 * np.pi * 1.225, omega_h=20.0, omega_alpha=50.0,
                         flight=FlightCondition(1.225), aero_model="wagner")
    a = analyse(sec, np.linspace(5.0, 200.0, 40), method="pk")
    c = check_side_by_side(a)
    assert a.finite_state.aero_model == "wagner" and c.aerodynamics == "Wagner"
    assert "finite-state (Wagner)" in a.summary()
    assert any(r.kind == "flutter" and r.found_by == "both" for r in c.rows)


def test_matching_by_mode_kind_and_event_in_speed_order():
    ev = Instability
    pk = [ev("flutter", "onset", 3, "forward 1", 160.0, 11.0),
          ev("flutter", "onset", 3, "forward 1", 250.0, 10.0),
          ev("divergence", "onset", 0, "wing 1", 143.0, 0.0),
          ev("flutter", "recovery", 3, "forward 1", 200.0, 10.5)]
    fs = [ev("flutter", "onset", 3, "forward 1", 248.0, 10.1),
          ev("flutter", "onset", 3, "forward 1", 159.0, 11.2),
          ev("divergence", "onset", 7, "lag 1", 143.5, 0.0),
          ev("divergence", "frequency-zero", 3, "forward 1", 320.0, 0.0)]
    c = compare_methods(pk, FiniteState("leishman-nguyen", tuple(fs)))
    got = [(r.label, r.event, r.V_pk, r.V_fs, r.found_by) for r in c.rows]
    assert got == [("wing 1", "onset", 143.0, None, "p-k only"),
                   ("lag 1", "onset", None, 143.5, "finite state only"),
                   ("forward 1", "onset", 160.0, 159.0, "both"),
                   ("forward 1", "recovery", 200.0, None, "p-k only"),
                   ("forward 1", "onset", 250.0, 248.0, "both"),
                   ("forward 1", "frequency-zero", None, 320.0, "finite state only")]
    assert c.rows[2].dV == 160.0 - 159.0 and c.rows[2].df == 11.0 - 11.2
    text = c.format()
    assert "onset of wing 1: found by the p-k method only" in text
    assert "onset of lag 1: found by the finite-state analysis only" in text
    with pytest.raises(InputError, match="aero_model = 'jones' is invalid"):
        FiniteState("jones", ())


# ----------------------------------------------------------------------------- files
def test_save_load_round_trip(wingtip, tmp_path):
    _, a = wingtip
    path = tmp_path / "a.json"
    a.save(path)
    doc = json.loads(path.read_text())
    assert doc["finite_state"]["aero_model"] == "leishman-nguyen"
    assert doc["method_comparison"] == a.method_comparison().to_dict()
    b = load(path)
    assert b.finite_state == a.finite_state and b.events == a.events
    assert b.method_comparison() == a.method_comparison()
    assert b.summary() == a.summary()


def test_files_without_finite_state_still_read(wingtip):
    _, a = wingtip
    d = replace(a, finite_state=None).to_dict()
    assert "finite_state" not in d and "method_comparison" not in d   # as files before it
    assert ModelAnalysis.from_dict(d).finite_state is None


@pytest.mark.parametrize("change, message", [
    (lambda d: d["method_comparison"]["rows"][0].update(V_fs=1.0),
     "method_comparison: does not match"),
    (lambda d: d.pop("method_comparison"), "method_comparison: does not match"),
    (lambda d: d["finite_state"].update(aero_model="jones"),
     "finite_state: aero_model = 'jones' is invalid"),
    (lambda d: d["finite_state"].update(events={}), "finite_state.events: must be a list"),
    (lambda d: d["finite_state"]["events"][0].update(label="wing 9"),
     r"finite_state.events\[0\].label = 'wing 9' is not the name of mode"),
])
def test_bad_finite_state_in_a_file_is_named(wingtip, change, message):
    _, a = wingtip
    d = json.loads(json.dumps(a.to_dict()))
    change(d)
    with pytest.raises(InputError, match=message):
        ModelAnalysis.from_dict(d)


# ----------------------------------------------------------------------------- participation
def _total(p):
    return p.wing + p.other + sum(s.share for s in p.propellers)


def test_pk_events_have_participation_summing_to_one(wingtip, patil):
    for _, a in (wingtip, patil):
        for e in a.events:
            assert e.participation is not None
            assert _total(e.participation) == pytest.approx(1.0, abs=1e-12)
            assert e.participation.V == e.V


def test_wingtip_participation(wingtip):
    m, a = wingtip
    forward = [e for e in a.events if e.kind == "flutter" and e.event == "onset"][0]
    lead = forward.participation.leading
    assert lead.propeller == 1 and lead.y == pytest.approx(m.wing.semi_span)
    assert forward.participation.share_of(1) > 0.05          # the propeller whirls
    div = [e for e in a.events if e.kind == "divergence" and e.label == "wing 1"]
    assert len(div) == 1 and div[0].participation.wing > 0.99
    assert div[0].whirl is None and div[0].benignity is None


def test_pk_participation_and_whirl_as_the_finite_state_at_the_same_instability(wingtip):
    """The p-k and finite-state mode shapes of one flutter instability (≈ 1 m/s apart, C(k)
    exact vs Jones) are the same mode: the same whirl sense, propeller shares within 0.02."""
    _, a = wingtip
    fs = {_key(e): e for e in a.finite_state.events}
    pairs = [(e, fs[_key(e)]) for e in a.events if e.kind == "flutter" and _key(e) in fs]
    assert len(pairs) >= 2
    for e, g in pairs:
        assert e.whirl == g.whirl is not None
        for s in e.participation.propellers:
            assert s.share == pytest.approx(g.participation.share_of(s.propeller), abs=0.02)


def test_pk_benignity_is_the_slope_of_the_pk_damping(wingtip):
    """(dζ/dV)⁻¹ at each flutter onset: negative (ζ falls through zero), the same sign as the
    finite state's, and the slope of the p-k damping ratio over a step 5× the one used."""
    m, a = wingtip
    fs = {_key(e): e for e in a.finite_state.events}
    onsets = [e for e in a.events if e.kind == "flutter" and e.event == "onset"]
    assert onsets
    for e in onsets:
        assert e.benignity < 0 and fs[_key(e)].benignity < 0
        h = 5 * BENIGNITY_STEP
        p0 = complex(0.0, 2 * np.pi * e.frequency_hz)
        lo, _ = pk_root(m, e.V - h, p0)
        hi, _ = pk_root(m, e.V + h, p0)
        slope = (-hi.real / abs(hi) + lo.real / abs(lo)) / (2 * h)
        assert 1 / e.benignity == pytest.approx(slope, rel=0.02)
