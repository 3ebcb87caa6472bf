"""The Mach warning derived from the case (issue 37, item 5; propwhirl.analysis.mach_check):
each event of an incompressible strip wing recomputed on its Prandtl–Glauert twin from the
event's own root, warned when it moves by 2 % or more; a near-neutral hump likewise."""
import dataclasses

import numpy as np
import pytest

from propwhirl.analysis import analyse, mach_check
from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
from propwhirl.cases.registry import case_model
from propwhirl.model.flight import FlightCondition


def wingtip_at(altitude_m: float):
    m = wingtip_propeller_wing()
    return m.with_(flight=FlightCondition.from_altitude(altitude_m))


def compressibility_lines(a):
    return [w for w in a.warnings if "compressibility" in w]


def test_wingtip_at_6000_m_warns_with_the_recomputed_speeds():
    """At 6000 m the wingtip model's divergence and flutter lie at Mach 0.55–0.61 (below the
    fixed 0.7 of the old warning, which says nothing): each is named with its Mach and the
    twin's speed, which is the onset of the whole analysis with compressibility on (oracle)."""
    model = wingtip_at(6000.0)
    a_sound = model.flight.speed_of_sound
    speeds = np.arange(100.0, 0.68 * a_sound, 5.0)
    a = analyse(model, speeds=speeds)
    assert all(e.V / a_sound < 0.7 for e in a.events)
    assert not any("beyond Mach 0.7" in w for w in a.warnings)
    lines = compressibility_lines(a)
    onsets = [e for e in a.events if e.event == "onset"]
    assert onsets and len(lines) == len(onsets)
    comp = analyse(model.with_(wing=dataclasses.replace(
        model.wing, compressibility="prandtl-glauert")), speeds=speeds)
    assert not compressibility_lines(comp)             # already compressible: nothing to say
    for e, line in zip(onsets, lines):
        assert f"V = {e.V:.2f} m/s ({e.kind} onset of {e.label}) is Mach {e.V / a_sound:.2f}" \
            in line
        assert 'compressibility = "prandtl-glauert"' in line and "\n" not in line
        twin = float(line.split("with compressible strips it is at ")[1].split(" m/s")[0])
        same = [c for c in comp.events if c.kind == e.kind and c.event == "onset"
                and c.label == e.label]
        assert same and abs(twin - same[0].V) <= 0.05
        assert twin < e.V                              # unconservative strips, said so
        assert "unconservative" in line


def test_low_mach_case_does_not_warn():
    """The Patil wing (HALE, 20 km: its flutter at Mach 0.11) moves by less than 2 %."""
    a = analyse(case_model("patil"))
    assert a.events and all(e.V / 300.0 < 0.15 for e in a.events)
    assert compressibility_lines(a) == []


def test_work_is_bounded(monkeypatch):
    """A few pencils per event, no second analysis: at most MAX_STEPS + 1 per event (the
    secant and the confirmation beyond its last point) and one per mode (its hump)."""
    calls = []
    real = mach_check._root
    monkeypatch.setattr(mach_check, "_root", lambda *a: calls.append(a[1]) or real(*a))
    model = wingtip_at(6000.0)
    a = analyse(model, speeds=np.arange(100.0, 210.0, 5.0))
    n = sum(e.event in ("onset", "recovery") for e in a.events)
    assert 0 < len(calls) <= n * (mach_check.MAX_STEPS + 1) + a.sweep.eigenvalues.shape[1]


def test_near_neutral_hump_is_named():
    """The inboard model with its propeller's structural damping raised to g = 0.02: the
    forward whirl's hump peaks at g ≈ −0.0005 near 184 m/s (Mach 0.56) without crossing; the
    Prandtl–Glauert twin's g there is about −0.036 (the hump moves a lot with Mach; this time
    away from instability, which the warning says)."""
    m = case_model("inboard")
    inst = m.propellers[0]
    p = dataclasses.replace(inst.propeller, damping_theta=0.02, damping_psi=0.02)
    m = m.with_(propellers=(dataclasses.replace(inst, propeller=p),))
    a = analyse(m, speeds=np.arange(100.0, 261.0, 5.0))
    assert not any(e.label == "forward 1" for e in a.events)
    hump = [w for w in a.warnings if w.startswith("mode forward 1 comes within g = ")]
    assert len(hump) == 1 and "Mach 0.5" in hump[0]
    assert "further from instability" in hump[0]


@pytest.mark.parametrize("change", [dict(compressibility="prandtl-glauert"),
                                    dict(aero="dlm")])
def test_not_checked_when_already_compressible(change):
    m = wingtip_propeller_wing()
    assert mach_check.applies(m)
    assert not mach_check.applies(m.with_(wing=dataclasses.replace(m.wing, **change)))


def test_fixed_strip_mach_far_from_the_events_is_flagged_non_matched():
    m = wingtip_propeller_wing()
    fixed = m.with_(wing=dataclasses.replace(m.wing, compressibility="prandtl-glauert",
                                             strip_mach=0.3))
    a = analyse(fixed, speeds=np.arange(100.0, 200.0, 5.0))
    lines = [w for w in a.warnings if "non-matched" in w]
    first = a.events[0]
    assert len(lines) == 1 and lines[0].startswith(f"V = {first.V:.2f} m/s")
    assert "fixed Mach 0.3 (strip_mach)" in lines[0] and 'strip_mach = "speed"' in lines[0]
    matched = m.with_(wing=dataclasses.replace(m.wing, compressibility="prandtl-glauert"))
    b = analyse(matched, speeds=np.arange(100.0, 200.0, 5.0))
    assert not [w for w in b.warnings if "non-matched" in w or "compressibility" in w]


def test_pk_analysis_is_checked_by_the_pk_on_the_twin():
    """method="pk": each onset recomputed by the p-k on the Prandtl-Glauert twin, equal to
    the whole compressible p-k analysis's onset (wingtip, 8000 ft: 143.15 -> 137.31,
    160.55 -> 152.68 m/s computed) — on the Galerkin basis the analysis's sweep kept (the
    twin's static correction spans the same vectors: its steady loads are the model's times
    1/β), the same warnings word for word as the twin's p-k on every DOF."""
    m = wingtip_propeller_wing()
    speeds = np.arange(100.0, 231.0, 10.0)
    a = analyse(m, speeds=speeds, method="pk")
    comp = analyse(m.with_(wing=dataclasses.replace(m.wing, compressibility="prandtl-glauert")),
                   speeds=speeds, method="pk")
    lines = compressibility_lines(a)
    onsets = [e for e in a.events if e.event == "onset"]
    assert len(onsets) == 2 and len(lines) == 2
    for e, line in zip(onsets, lines):
        assert line.startswith(f"V = {e.V:.2f} m/s ({e.kind} onset of {e.label})")
        twin = float(line.split("with compressible strips it is at ")[1].split(" m/s")[0])
        same = [c for c in comp.events if c.kind == e.kind and c.event == "onset"
                and c.label == e.label]
        assert same and abs(twin - same[0].V) <= 0.05
    assert list(mach_check.pk_warnings(m, a.events, float(speeds[-1]))) == lines
    assert not compressibility_lines(analyse(m, speeds=speeds, method="pk",
                                             compressibility_check=False))
