"""The ICAO standard atmosphere (ISA): temperature, pressure, density and speed of sound.

The ISA of ICAO Doc 7488/3 (1993), identical below 32 km to the U.S. Standard Atmosphere 1976,
for dry air as a perfect gas in hydrostatic equilibrium.  Temperature is piecewise linear in
the *geopotential* altitude H (the altitude of the standard's tables and of an altimeter set to
1013.25 hPa, i.e. the pressure altitude):

===============  ================  =================  =============================
layer            H [m]             base T [K]         lapse dT/dH [K/m]
===============  ================  =================  =============================
troposphere      -5000 … 11000     288.15 (H = 0)     -0.0065
tropopause       11000 … 20000     216.65             0
stratosphere     20000 … 32000     216.65             +0.001
===============  ================  =================  =============================

with p = p_b (T/T_b)^(-g0/(R L)) in a layer of lapse L ≠ 0, p = p_b exp(-g0 (H - H_b)/(R T_b))
in the isothermal one, ρ = p/(R T) and a = √(γ R T); the base pressures p_b follow from the sea-
level pressure 101325 Pa layer by layer.  Altitudes outside [-5000, 32000] m are refused.  A
geometric height z (above mean sea level) converts with :func:`geopotential_altitude`; below
20 km the two differ by less than 0.32 %.

Every function takes a number or an array of altitudes and returns a float or an array of the
same shape.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from propwhirl import validate as v

#: Standard acceleration of gravity g0 [m/s²] (ICAO Doc 7488/3; US 1976)
G0 = 9.80665
#: Specific gas constant of dry air R = R*/M0 = 8314.32/28.9644 [J/(kg K)]
R_AIR = 287.05287
#: Ratio of specific heats of air γ [-]
GAMMA = 1.4
#: Earth radius r0 of the geopotential altitude [m]
EARTH_RADIUS = 6356766.0
#: Sea-level temperature [K] and pressure [Pa]
SEA_LEVEL_TEMPERATURE = 288.15
SEA_LEVEL_PRESSURE = 101325.0
#: Metres per foot (exact, international foot)
FT = 0.3048

#: Lower and upper end of the atmosphere modelled here, geopotential altitude [m]
MIN_ALTITUDE = -5000.0
MAX_ALTITUDE = 32000.0
#: The same range in feet, rounded inwards [ft]
MIN_ALTITUDE_FT = -16400.0
MAX_ALTITUDE_FT = 104980.0

#: (base geopotential altitude [m], base temperature [K], lapse rate [K/m]) of each layer
_LAYERS: tuple[tuple[float, float, float], ...] = (
    (0.0, SEA_LEVEL_TEMPERATURE, -0.0065),
    (11000.0, 216.65, 0.0),
    (20000.0, 216.65, 0.001),
)


def _layer_pressure(p_base: float, t_base: float, lapse: float, dh, t):
    """Pressure [Pa] at height dh [m] above a layer's base (temperature t there [K])."""
    if lapse == 0.0:
        return p_base * np.exp(-G0 * dh / (R_AIR * t_base))
    return p_base * (t / t_base) ** (-G0 / (R_AIR * lapse))


def _base_pressures() -> tuple[float, ...]:
    """p_b of each layer [Pa], from the sea-level pressure upwards."""
    out = [SEA_LEVEL_PRESSURE]
    for (h0, t0, lapse), (h1, _, _) in zip(_LAYERS, _LAYERS[1:]):
        t1 = t0 + lapse * (h1 - h0)
        out.append(float(_layer_pressure(out[-1], t0, lapse, h1 - h0, t1)))
    return tuple(out)


_BASE_PRESSURES = _base_pressures()


def altitude_of(altitude_m=None, altitude_ft=None, name: str = "altitude"):
    """The geopotential altitude [m] given in metres *or* in feet (exactly one of them).

    `name` prefixes the parameter names in the messages (``altitude`` → ``altitude_m``,
    ``altitude_ft``).  Returns a float for a number, an array for an array.

    Examples
    --------
    >>> altitude_of(altitude_ft=8000.0)
    2438.4
    """
    if (altitude_m is None) == (altitude_ft is None):
        raise v.InputError(f"give exactly one of {name}_m or {name}_ft "
                           f"({'both' if altitude_m is not None else 'neither'} given)")
    if altitude_m is not None:
        h = v.in_range(f"{name}_m", altitude_m, MIN_ALTITUDE, MAX_ALTITUDE, "m")
        return _out(h, altitude_m)
    ft = v.in_range(f"{name}_ft", altitude_ft, MIN_ALTITUDE_FT, MAX_ALTITUDE_FT, "ft")
    return _out(ft * FT, altitude_ft)


def _out(x: np.ndarray, like):
    """A float for a scalar input, else the array."""
    return float(x) if np.ndim(like) == 0 else x


def _altitude(h, name: str = "altitude_m") -> np.ndarray:
    return v.in_range(name, h, MIN_ALTITUDE, MAX_ALTITUDE, "m")


def _temperature(h: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(layer index, temperature [K]) at geopotential altitudes h [m] (checked)."""
    bases = np.array([layer[0] for layer in _LAYERS])
    i = np.searchsorted(bases[1:], h, side="right")
    t = np.empty_like(h)
    for k, (h0, t0, lapse) in enumerate(_LAYERS):
        m = i == k
        t[m] = t0 + lapse * (h[m] - h0)
    return i, t


def _pressure(h: np.ndarray, i: np.ndarray, t: np.ndarray) -> np.ndarray:
    p = np.empty_like(h)
    for k, (h0, t0, lapse) in enumerate(_LAYERS):
        m = i == k
        if m.any():
            p[m] = _layer_pressure(_BASE_PRESSURES[k], t0, lapse, h[m] - h0, t[m])
    return p


def temperature(altitude_m):
    """ISA temperature [K] at geopotential altitude(s) `altitude_m` [m], in [-5000, 32000].

    Examples
    --------
    >>> round(temperature(11000.0), 3)
    216.65
    """
    return _out(_temperature(_altitude(altitude_m))[1], altitude_m)


def pressure(altitude_m):
    """ISA static pressure [Pa] at geopotential altitude(s) `altitude_m` [m].

    Examples
    --------
    >>> round(pressure(11000.0))          # the standard's table: 22632 Pa
    22632
    """
    h = _altitude(altitude_m)
    return _out(_pressure(h, *_temperature(h)), altitude_m)


def density(altitude_m):
    """ISA air density ρ = p/(R T) [kg/m³] at geopotential altitude(s) `altitude_m` [m].

    Examples
    --------
    >>> round(density(0.0), 4)
    1.225
    >>> density([0.0, 2438.4]).round(5)    # sea level and 8000 ft (thesis Table 9.1: 0.962870)
    array([1.225  , 0.96287])
    """
    return _out(isa(altitude_m).density, altitude_m)


def speed_of_sound(altitude_m):
    """ISA speed of sound a = √(γ R T) [m/s] at geopotential altitude(s) `altitude_m` [m].

    Examples
    --------
    >>> round(speed_of_sound(0.0), 3)
    340.294
    """
    return _out(np.sqrt(GAMMA * R_AIR * _temperature(_altitude(altitude_m))[1]), altitude_m)


def geopotential_altitude(geometric_m):
    """Geopotential altitude H = r0 z/(r0 + z) [m] of a geometric height `z` [m] above mean sea
    level (r0 = 6356766 m, the standard's Earth radius).

    Examples
    --------
    >>> round(geopotential_altitude(11019.0), 0)
    11000.0
    """
    z = v.in_range("geometric altitude", geometric_m, -1e5, 1e6, "m")
    return _out(EARTH_RADIUS * z / (EARTH_RADIUS + z), geometric_m)


@dataclass(frozen=True)
class Atmosphere:
    """The ISA state at one altitude (floats) or at an array of altitudes (arrays).

    Attributes: `altitude` geopotential [m], `temperature` [K], `pressure` [Pa],
    `density` [kg/m³], `speed_of_sound` [m/s].
    """

    altitude: float | np.ndarray
    temperature: float | np.ndarray
    pressure: float | np.ndarray
    density: float | np.ndarray
    speed_of_sound: float | np.ndarray


def isa(altitude_m=None, *, altitude_ft=None) -> Atmosphere:
    """The ISA state at a geopotential altitude in metres or in feet (exactly one given).

    Parameters
    ----------
    altitude_m : float or array_like, optional
        Geopotential (pressure) altitude [m], in [-5000, 32000].
    altitude_ft : float or array_like, optional
        The same in feet (1 ft = 0.3048 m), in [-16400, 104980].

    Returns
    -------
    Atmosphere
        Temperature [K], pressure [Pa], density [kg/m³] and speed of sound [m/s]; floats for
        a number, arrays of the input's shape for an array.

    Raises
    ------
    propwhirl.validate.InputError
        Both or neither altitude given, or an altitude outside the valid range.

    Examples
    --------
    >>> s = isa(altitude_ft=8000.0)          # the thesis's altitude (chapters 9-11)
    >>> round(s.temperature, 2), round(s.pressure), round(s.density, 6), round(s.speed_of_sound, 2)
    (272.3, 75262, 0.96287, 330.8)
    >>> isa([0.0, 11000.0, 20000.0]).pressure.round(0)
    array([101325.,  22632.,   5475.])
    >>> isa(40000.0)
    Traceback (most recent call last):
    ...
    propwhirl.validate.InputError: altitude_m = 40000.0 m is outside the valid range [-5000, 32000] m
    """
    given = altitude_m if altitude_ft is None else altitude_ft
    h = np.asarray(altitude_of(altitude_m, altitude_ft), dtype=float)
    i, t = _temperature(h)
    p = _pressure(h, i, t)
    rho = p / (R_AIR * t)
    a = np.sqrt(GAMMA * R_AIR * t)
    return Atmosphere(*(_out(x, given) for x in (h, t, p, rho, a)))


