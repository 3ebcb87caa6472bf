"""The one definition of the critical instability (issue 8, item 3)."""
import json

import numpy as np
import pytest

from propwhirl.analysis import Instability, analyse, critical, load
from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
from propwhirl.validate import InputError


def _ev(kind, event, mode, V, f=1.0, label=None):
    return Instability(kind, event, mode, label or f"mode {mode}", V, f)


def test_lowest_speed_of_any_kind_divergence_included():
    ev = [_ev("flutter", "onset", 3, 159.39), _ev("divergence", "onset", 0, 143.15, 0.0),
          _ev("flutter", "recovery", 3, 200.0)]
    assert critical(ev).V == 143.15
    assert critical(ev, exclude="divergence").V == 159.39
    assert critical(ev, exclude=("divergence", "flutter")) is None
    assert critical(ev, exclude=lambda e: e.mode == 0).mode == 3


def test_unstable_at_start_is_critical_at_the_first_speed():
    ev = [_ev("flutter", "onset", 2, 159.39), _ev("divergence", "unstable-at-start", 5, 150.0, 0.0)]
    c = critical(ev)
    assert c.event == "unstable-at-start" and c.V == 150.0


def test_recoveries_are_never_critical_and_ties_go_to_the_lower_mode():
    assert critical([_ev("flutter", "recovery", 1, 10.0)]) is None
    assert critical([]) is None
    ev = [_ev("flutter", "unstable-at-start", 4, 1.0), _ev("flutter", "unstable-at-start", 2, 1.0)]
    assert critical(ev).mode == 2


def test_bad_exclusion_is_an_input_error():
    with pytest.raises(InputError, match="kinds are 'flutter' and 'divergence'"):
        critical([], exclude="static")


@pytest.fixture(scope="module")
def from_150():
    return analyse(wingtip_propeller_wing(), np.arange(150.0, 351.0, 10.0))


def test_range_starting_in_an_unstable_state_reports_it(from_150, tmp_path):
    """The wingtip model diverges at 143.15 m/s: analysed from 150 m/s, the diverged mode is
    critical at 150 m/s, not skipped in favour of the 159.39 m/s flutter."""
    c = from_150.critical
    assert c.event == "unstable-at-start" and c.V == 150.0 and c.kind == "divergence"
    line = from_150.summary().splitlines()[-1]
    assert "unstable from V = 150 m/s, the start of the range" in line
    # the diverged real root is not an aerodynamic lag: named "static 1", by its content
    assert c.label == "static 1" and "divergence of static 1 (bending)" in line
    # the saved analysis names the same critical instability
    p = tmp_path / "a.json"
    from_150.save(p)
    d = json.loads(p.read_text())
    assert d["critical"]["V"] == 150.0 and d["critical"]["event"] == "unstable-at-start"
    assert load(p).critical == c


def test_full_range_critical_is_the_static_divergence():
    a = analyse(wingtip_propeller_wing())
    assert a.critical.kind == "divergence" and a.critical.V == pytest.approx(143.15, abs=0.01)
    fl = a.critical_excluding("divergence")
    assert fl.kind == "flutter" and fl.V == pytest.approx(159.39, abs=0.01)
