"""The flight condition of an analysis: air density, speed of sound, the airspeed range.

:data:`DEFAULT_SPEED_OF_SOUND` is propwhirl's one default speed of sound (the
:class:`FlightCondition` default and that of ``propwhirl derivatives``): the ISA value at
8000 ft, the altitude of the thesis's analyses.  :meth:`FlightCondition.from_altitude` takes
density and speed of sound from the ISA (:mod:`propwhirl.model.atmosphere`).
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from propwhirl import limits
from propwhirl import validate as v
from propwhirl.model import atmosphere
from propwhirl.model.fields import check_fields, spec

#: The altitude of the thesis's analyses (chapters 9–11, Table 9.1): 8000 ft [m]
THESIS_ALTITUDE_M = 2438.4
#: The one default speed of sound [m/s]: ISA at 8000 ft, T = 272.30 K, a = √(γ R T) = 330.80 m/s
DEFAULT_SPEED_OF_SOUND: float = atmosphere.speed_of_sound(THESIS_ALTITUDE_M)
#: The name the thesis's cases use for it [m/s]
SPEED_OF_SOUND_8000FT = DEFAULT_SPEED_OF_SOUND


@dataclass(frozen=True)
class FlightCondition:
    """Air density [kg/m³], speed of sound [m/s] and the airspeed range of an analysis.

    `speed_range` = (first, last, step) [m/s] is the initial grid of a V-g-f sweep
    (propwhirl.analysis.stability.analyse refines it); the thesis analyses 0–350 m/s.  The first speed
    must be > 0 (the aerodynamic matrices carry 1/V).  :meth:`from_altitude` builds one from the
    ISA; a model file does the same with ``altitude_m`` or ``altitude_ft`` in ``[flight]``.

    Parameters
    ----------
    density : float
        Air density ρ [kg/m³].
    speed_of_sound : float
        Speed of sound a [m/s] (default :data:`DEFAULT_SPEED_OF_SOUND`, 330.80 m/s: ISA at
        8000 ft, the thesis's altitude).
    speed_range : tuple of float
        (first, last, step) [m/s]: the initial grid of the V-g-f sweep, first > 0, last >
        first (default 1–350 m/s in 10 m/s steps).

    Examples
    --------
    >>> from propwhirl.model import FlightCondition
    >>> fc = FlightCondition(0.96287, speed_range=(10.0, 300.0, 10.0))
    >>> round(fc.speed_of_sound, 2), fc.speeds()[:3].tolist(), fc.speeds().size
    (330.8, [10.0, 20.0, 30.0], 30)
    """

    density: float = field(metadata=spec("density_kg_per_m3", "kg/m^3", "air density",
                                         range=(1e-4, 10.0)))
    speed_of_sound: float = field(default=DEFAULT_SPEED_OF_SOUND, metadata=spec(
        "speed_of_sound_m_per_s", "m/s", "speed of sound (Python default and that of `propwhirl "
        "derivatives`: 330.80 m/s, ISA at 8000 ft, the thesis's altitude)", default="physical", file_required=True, range=(100.0, 1000.0)))
    speed_range: tuple[float, float, float] = field(default=(1.0, 350.0, 10.0), metadata=spec(
        "speed_range_m_per_s", "m/s", "[first, last, step]: initial grid of the V-g-f sweep",
        default="setting", form="numbers", length=3, range=(0.0, 1e4), ends="(]"))

    def __post_init__(self) -> None:
        check_fields(self)  # types and ranges (every speed in (0, 1e4] m/s)
        first, last, step = self.speed_range
        if not last > first:
            raise v.InputError(
                f"speed_range last speed = {last!r} m/s is invalid: must be > the first, {first!r} m/s")
        limits.check_speed_count(f"speed_range = {list(self.speed_range)!r} m/s",
                                 limits.grid_count(first, last, step))

    @classmethod
    def from_altitude(cls, altitude_m: float | None = None, *, altitude_ft: float | None = None,
                      speed_range: tuple[float, float, float] | None = None) -> "FlightCondition":
        """The flight condition at an ISA altitude: density and speed of sound of the standard
        atmosphere (:func:`propwhirl.model.atmosphere.isa`).

        Parameters
        ----------
        altitude_m, altitude_ft : float
            Geopotential (pressure) altitude [m] or [ft]: exactly one, in [-5000, 32000] m.
        speed_range : (first, last, step), optional
            Initial airspeed grid [m/s] (default: the class default, 1–350 m/s in 10 m/s steps).

        Examples
        --------
        >>> fc = FlightCondition.from_altitude(altitude_ft=8000.0)   # the thesis's altitude
        >>> round(fc.density, 6), round(fc.speed_of_sound, 2)
        (0.96287, 330.8)
        """
        for name, x in (("altitude_m", altitude_m), ("altitude_ft", altitude_ft)):
            if x is not None and not v.is_finite_number(x):
                raise v.InputError(f"{name} = {v.short_repr(x)} is invalid: must be one finite number")
        air = atmosphere.isa(altitude_m, altitude_ft=altitude_ft)
        extra = {} if speed_range is None else {"speed_range": tuple(speed_range)}
        return cls(air.density, air.speed_of_sound, **extra)

    def speeds(self) -> np.ndarray:
        """The initial grid [m/s]: first, first + step, ..., with the last speed included."""
        first, last, step = (float(x) for x in self.speed_range)
        grid = np.arange(first, last, step)
        return np.append(grid, last) if grid[-1] < last else grid
