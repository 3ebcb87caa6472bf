"""Validity of the subsonic aerodynamics (issue 9, item 8): what is refused, what is flagged."""
import math
import warnings
from dataclasses import replace

import numpy as np
import pytest

from propwhirl.app.cli import main
from propwhirl.cases.ch09_baseline import baseline_wing_model, isolated_baseline_propeller
from propwhirl.model.propellers import propeller_aero as aero
from propwhirl.model.aerodynamics import validity
from propwhirl.model.flight import FlightCondition
from propwhirl.model.systems import TypicalSection
from propwhirl.validate import InputError

GEO = aero.PropellerGeometry(3, 0.762, 0.125 / 0.762, 0.094)


def test_solidity_is_blade_area_over_disc_area():
    assert aero.solidity(GEO) == pytest.approx(3 * 0.094 * (0.762 - 0.125) / (math.pi * 0.762**2))


@pytest.mark.parametrize("changes", [dict(n_blades=20, chord=0.5), dict(n_blades=8, chord=1.0)])
def test_overlapping_blades_are_refused(changes):
    """Each value inside its own range, the combination not (solidity > 1)."""
    geo = replace(GEO, **changes)
    with pytest.raises(InputError, match=r"solidity .* is invalid: must be <= 1 \(the blades"):
        aero.derivatives(geo, 100.0, 200.0, speed_of_sound=330.0)


def test_100_blades_or_a_huge_chord_are_refused_by_their_ranges():
    with pytest.raises(InputError, match=r"n_blades = 100 is outside the valid range \[3, 20\]"):
        isolated_baseline_propeller(n_blades=100)
    with pytest.raises(InputError, match=r"chord = 1e\+300 m is outside the valid range"):
        replace(GEO, chord=1e300)


def test_overlapping_blades_are_refused_in_an_analysis():
    m = isolated_baseline_propeller(n_blades=20, blade_chord=0.5)
    with pytest.raises(InputError, match=r"solidity .* = 3\.492 \(n_blades = 20, radius = 0\.762 m"):
        m.state_matrix(np.array([100.0]))


@pytest.mark.parametrize("kw", [dict(mach=7.0), dict(speed_of_sound=10.0)])
def test_hypersonic_derivatives_are_refused(kw):
    with pytest.raises(InputError, match=r"Mach (7|10)\.00 \(V = 100 m/s\) is invalid"):
        aero.derivatives(GEO, 100.0, 200.0, **kw)


def test_speed_of_sound_50_is_refused_by_its_range():
    with pytest.raises(InputError, match=r"speed_of_sound = 50.0 m/s is outside the valid range"):
        FlightCondition(0.96, 50.0)


def test_hypersonic_speeds_are_refused_naming_speed_and_mach():
    m = baseline_wing_model().with_(flight=FlightCondition(0.96, 100.0))
    with pytest.raises(InputError, match=r"V = 700 m/s is Mach 7.00 at a = 100 m/s: .*subsonic"):
        m.state_matrix(np.array([10.0, 700.0]))


def test_speeds_to_10000_m_per_s_are_refused():
    with pytest.raises(InputError, match=r"V = 10000 m/s is Mach 30.2"):
        isolated_baseline_propeller().state_matrix(np.array([100.0, 10000.0]))


def test_without_aerodynamics_mach_plays_no_part():
    m = isolated_baseline_propeller().without_aerodynamics()
    assert np.isfinite(m.state_matrix(np.array([10000.0]))).all()


def test_zero_wing_lift_slope_is_refused():
    """Refused at construction by its range (0, 4π]; the analysis-time rule (every strip at
    zero, with the way out wing_aero = false) guards what a function of y may still give."""
    m = baseline_wing_model()
    with pytest.raises(InputError, match=r"lift_slope = 0.0 1/rad is outside the valid range \(0,"):
        replace(m.wing, lift_slope=0.0)


def test_zero_section_lift_slope_is_refused():
    with pytest.raises(InputError, match=r"Cla = 0.0 1/rad is outside the valid range \(0,"):
        TypicalSection(b=1.0, a=-0.2, x_alpha=0.1, r_alpha=0.5, m=100.0, omega_h=10.0,
                       omega_alpha=25.0, flight=FlightCondition(1.225), Cla=0.0)


def test_mach_3_derivatives_are_computed_and_flagged_once_each():
    d = aero.derivatives(GEO, np.array([100.0, 200.0]), 300.0, mach=np.array([3.0, 3.0]))
    w = aero.validity_warnings(d)
    assert len(w) == 2
    assert w[0].startswith("V = 100 m/s is Mach 3.00 (supersonic)")
    assert w[1].startswith("helical tip Mach number") and "V = 100 m/s" in w[1]


def test_subsonic_operating_points_are_not_flagged():
    d = aero.derivatives(GEO, np.array([50.0, 100.0]), 300.0, speed_of_sound=340.0)
    assert aero.validity_warnings(d) == ()


def test_the_cli_prints_each_derivative_warning_once_on_stderr(capsys):
    code = main(["derivatives", "--blades", "3", "--radius", "1", "--chord", "0.1",
                 "--speed", "100", "200", "--rpm", "2000", "--mach", "3"])
    err = capsys.readouterr().err.splitlines()
    assert code == 0
    assert len(err) == 2 and all(e.startswith("propwhirl: warning: ") for e in err)


def test_the_cli_refuses_mach_5(capsys):
    code = main(["derivatives", "--blades", "3", "--radius", "1", "--chord", "0.1",
                 "--speed", "100", "--rpm", "2000", "--mach", "5"])
    assert code == 2
    assert "Mach 5.00 (V = 100 m/s) is invalid" in capsys.readouterr().err


def test_extreme_but_valid_operating_points_raise_no_numpy_warning():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        for V, om in ((1e-3, 1e4), (1e3, 1e-3), (340.0 * 4.9, 1.0)):
            d = aero.derivatives(GEO, V, om, speed_of_sound=340.0)
            assert all(np.isfinite(x).all() for x in d.derivatives().values())
        aero.validity_warnings(d)


def test_tip_mach_of_the_windmilling_baseline():
    p = isolated_baseline_propeller().propeller
    mu = p.advance_ratio
    assert validity.tip_mach(p, 221.5, 330.8) == pytest.approx(221.5 / 330.8 * math.hypot(1, 1 / mu))
