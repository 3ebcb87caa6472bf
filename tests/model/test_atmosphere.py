"""The ISA (propwhirl.model.atmosphere) against the standard's own table.

Table values: ICAO Doc 7488/3, *Manual of the ICAO Standard Atmosphere* (1993), Table 5
(metric, by geometric altitude z; the geopotential altitude H stands beside it), as transcribed
in the test data of the ambiance package (github.com/airinnova/ambiance, tests/table_data.py).
Rows whose H is a round number are looked up by H, the others by z converted to H with the
standard's relation (geopotential_altitude).  Each value must agree to every digit printed
(within half a unit of its last digit) up to 2e-6 relative: the table was computed with the
standard's rounded constants and differs from its closed-form equations by up to 1.8e-6 above
11 km (22632.06 Pa there in the U.S. Standard Atmosphere 1976, 22632.04 Pa from g0 and R;
5474.87 Pa tabulated at 20 km, 5474.877 Pa from the equations).
"""
from decimal import Decimal

import numpy as np
import pytest

from propwhirl.model import atmosphere as atm
from propwhirl.model.flight import SPEED_OF_SOUND_8000FT, FlightCondition
from propwhirl.validate import InputError

# (kind, altitude [m], T [K], p [Pa], rho [kg/m^3], a [m/s]) as printed in the table
TABLE = [
    ("H", "-5000", "320.650", "1.77687e5", "1.93047", "358.972"),
    ("z", "-2500", "304.406", "1.35205e5", "1.54731", "349.761"),
    ("H", "0", "288.150", "1.01325e5", "1.22500", "340.294"),
    ("z", "1000", "281.651", "8.98763e4", "1.11166", "336.435"),
    ("z", "2000", "275.154", "7.95014e4", "1.00655", "332.532"),
    ("z", "11000", "216.774", "2.26999e4", "3.64801e-1", "295.154"),
    ("H", "11000", "216.650", "2.26320e4", "3.63918e-1", "295.069"),
    ("z", "15000", "216.650", "1.21118e4", "1.94755e-1", "295.069"),
    ("z", "20000", "216.650", "5.52929e3", "8.89097e-2", "295.069"),
    ("H", "20000", "216.650", "5.47487e3", "8.80345e-2", "295.069"),
    ("z", "25000", "221.552", "2.54921e3", "4.00837e-2", "298.389"),
    ("H", "32000", "228.650", "8.68014e2", "1.32249e-2", "303.131"),
]


#: Relative difference allowed beyond the table's rounding (see the module docstring)
CONSTANTS_ROUNDING = 2e-6


def _half_unit(text: str) -> float:
    """Half a unit of the last printed digit of `text`."""
    return 0.5 * 10.0 ** Decimal(text).as_tuple().exponent


def _H(kind: str, alt: str) -> float:
    return float(alt) if kind == "H" else atm.geopotential_altitude(float(alt))


@pytest.mark.parametrize("row", TABLE, ids=[f"{r[0]}={r[1]}" for r in TABLE])
def test_every_printed_digit_of_the_standards_table(row):
    kind, alt, *printed = row
    s = atm.isa(_H(kind, alt))
    for name, text in zip(("temperature", "pressure", "density", "speed_of_sound"), printed):
        got = getattr(s, name)
        allowed = _half_unit(text) + CONSTANTS_ROUNDING * abs(float(text))
        assert abs(got - float(text)) <= allowed, (name, got, text)


def test_the_functions_agree_with_isa_and_are_vectorised():
    h = np.array([[0.0, 1000.0, 2438.4], [11000.0, 15000.0, 20000.0]])
    s = atm.isa(h)
    assert s.density.shape == h.shape
    np.testing.assert_array_equal(atm.temperature(h), s.temperature)
    np.testing.assert_array_equal(atm.pressure(h), s.pressure)
    np.testing.assert_array_equal(atm.density(h), s.density)
    np.testing.assert_array_equal(atm.speed_of_sound(h), s.speed_of_sound)
    for i, x in np.ndenumerate(h):  # element by element = all at once
        assert atm.density(float(x)) == s.density[i]
    assert isinstance(atm.density(1000.0), float)


def test_8000_ft_is_the_thesis_flight_condition():
    """Table 9.1: 8000 ft, rho = 0.962870 kg/m^3 (six digits); the speed of sound is the
    default the thesis's cases use, bit for bit."""
    s = atm.isa(altitude_ft=8000.0)
    assert s.altitude == 2438.4
    assert abs(s.density - 0.962870) <= 0.5e-6
    assert s.speed_of_sound == SPEED_OF_SOUND_8000FT
    assert abs(s.temperature - 272.3004) < 1e-9   # 288.15 K - 6.5 K/km * 2.4384 km


def test_pressure_and_temperature_are_continuous_at_the_layer_boundaries():
    for hb in (11000.0, 20000.0):
        below, above = atm.isa(np.array([hb - 1e-6, hb + 1e-6])).pressure
        assert above == pytest.approx(below, rel=1e-9)
    # hydrostatic: dp/dH = -rho g0 (checked by a central difference in each layer)
    for h in (-3000.0, 5000.0, 15000.0, 25000.0):
        dp = (atm.pressure(h + 0.5) - atm.pressure(h - 0.5)) / 1.0
        assert dp == pytest.approx(-atm.density(h) * atm.G0, rel=1e-6)


@pytest.mark.parametrize("kw, message", [
    ({"altitude_m": 32000.5}, "altitude_m = 32000.5 m is outside the valid range [-5000, 32000] m"),
    ({"altitude_m": -5001.0}, "altitude_m = -5001.0 m is outside the valid range [-5000, 32000] m"),
    ({"altitude_ft": 2e5}, "altitude_ft = 200000.0 ft is outside the valid range"),
    ({"altitude_m": [0.0, float("nan")]}, "altitude_m = nan m is invalid: must be finite"),
    ({"altitude_m": 1000.0, "altitude_ft": 3000.0}, "give exactly one of altitude_m or altitude_ft (both"),
    ({}, "give exactly one of altitude_m or altitude_ft (neither"),
])
def test_refused_outside_the_valid_range(kw, message):
    with pytest.raises(InputError) as err:
        atm.isa(**kw)
    assert message in str(err.value)
    assert "\n" not in str(err.value)


def test_flight_condition_from_altitude():
    fc = FlightCondition.from_altitude(altitude_m=5000.0, speed_range=(10.0, 200.0, 5.0))
    assert fc.density == atm.density(5000.0)
    assert fc.speed_of_sound == atm.speed_of_sound(5000.0)
    assert fc.speed_range == (10.0, 200.0, 5.0)
    ft = FlightCondition.from_altitude(altitude_ft=8000.0)
    assert ft.speed_of_sound == SPEED_OF_SOUND_8000FT
    assert ft.speed_range == FlightCondition(1.0).speed_range
    with pytest.raises(InputError, match="give exactly one of altitude_m or altitude_ft"):
        FlightCondition.from_altitude(altitude_m=1.0, altitude_ft=1.0)
    with pytest.raises(InputError, match="altitude_m = 40000.0 m is outside"):
        FlightCondition.from_altitude(altitude_m=40000.0)
    with pytest.raises(InputError, match="altitude_m"):
        FlightCondition.from_altitude(altitude_m=[0.0, 1.0])  # one altitude, not an array
