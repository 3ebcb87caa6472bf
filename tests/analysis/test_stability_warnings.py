"""Results outside the methods' validity are recorded, saved, re-read and printed once
(issue 9, item 8); no numpy RuntimeWarning reaches stderr (item 9)."""
import json
import warnings

import numpy as np
import pytest

from propwhirl import io
from propwhirl.analysis.stability import ModelAnalysis, analyse, load
from propwhirl.app.cli import main
from propwhirl.cases.ch09_baseline import isolated_baseline_propeller
from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
from propwhirl.model.flight import FlightCondition


@pytest.fixture(scope="module")
def isolated():
    # backward whirl flutter at 221.5 m/s (Mach 0.67): tips at Mach 1.26
    return analyse(isolated_baseline_propeller(), speeds=[100.0, 200.0, 250.0])


def test_supersonic_tips_at_an_instability_are_flagged_once(isolated):
    assert len(isolated.warnings) == 1
    w = isolated.warnings[0]
    assert w.startswith("propeller 1: helical tip Mach number 1.26 at V = 221.50 m/s "
                        "(flutter onset of backward)")


def test_warnings_are_saved_and_re_read(isolated, tmp_path):
    path = tmp_path / "a.json"
    isolated.save(path)
    assert json.loads(path.read_text())["warnings"] == list(isolated.warnings)
    assert load(path).warnings == isolated.warnings
    assert ModelAnalysis.from_dict({**isolated.to_dict(), "warnings": []}).warnings == ()


def test_a_result_within_validity_is_not_flagged():
    a = analyse(isolated_baseline_propeller(), speeds=[50.0, 100.0, 150.0])
    assert a.critical is None and a.warnings == ()


def test_events_above_mach_07_are_flagged_with_the_first_speed():
    m = isolated_baseline_propeller()
    m = m.with_(flight=FlightCondition(m.flight.density, 300.0))   # flutter above Mach 0.7
    a = analyse(m, speeds=[100.0, 200.0, 250.0])
    V = a.critical.V
    assert V / 300.0 > 0.7
    assert a.warnings[0].startswith(f"V = {V:.2f} m/s (flutter onset of backward) is Mach "
                                    f"{V / 300.0:.2f}: beyond Mach 0.7")


def test_stability_beyond_mach_07_is_not_claimed():
    m = isolated_baseline_propeller()
    m = m.with_(flight=FlightCondition(m.flight.density, 200.0))
    a = analyse(m, speeds=[50.0, 100.0, 150.0])
    assert a.critical is None
    assert a.warnings[-1].startswith("no instability up to V = 150 m/s, but above V = 140.00 m/s")


def test_no_aerodynamics_no_warnings():
    a = analyse(isolated_baseline_propeller().without_aerodynamics(), speeds=[100.0, 400.0])
    assert a.warnings == ()


def test_the_cli_prints_every_warning_once_on_stderr(tmp_path, capsys):
    model = tmp_path / "m.toml"
    io.save_model(isolated_baseline_propeller(), model)
    out = tmp_path / "a.json"
    assert main(["analyse", str(model), "--speeds", "100", "250", "50", "--json", str(out)]) == 0
    err = capsys.readouterr().err.splitlines()
    saved = load(out).warnings
    assert saved and err == [f"propwhirl: warning: {w}" for w in saved]


EXTREME_BUT_VALID = {
    "stiff wing": lambda: _wing(EI=1e9, GJ=1e9),
    "light wing": lambda: _wing(mass_per_length=0.5),
    "soft mount": lambda: wingtip_propeller_wing(
        propeller=isolated_baseline_propeller(f_theta=0.2, f_psi=0.2).propeller),
    "isolated to Mach 4.9": lambda: isolated_baseline_propeller(),
}


def _wing(**changes):
    from dataclasses import replace
    m = wingtip_propeller_wing()
    return m.with_(wing=replace(m.wing, **changes))


@pytest.mark.parametrize("name", list(EXTREME_BUT_VALID))
def test_no_numpy_warning_escapes_an_analysis(name):
    model = EXTREME_BUT_VALID[name]()
    top = 4.9 * model.flight.speed_of_sound if name.startswith("isolated") else 350.0
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        a = analyse(model, speeds=np.linspace(1.0, top, 8))
    assert np.isfinite(a.sweep.eigenvalues).all()
