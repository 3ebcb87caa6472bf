"""The flight condition of an analysis: air density, speed of sound, the airspeed range."""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from propwhirl import limits
from propwhirl import validate as v
from propwhirl.model.fields import check_fields, spec

#: ISA speed of sound at 8000 ft (2438.4 m): T = 272.30 K, a = √(γ R T) [m/s]
SPEED_OF_SOUND_8000FT = float(np.sqrt(1.4 * 287.05287 * (288.15 - 0.0065 * 2438.4)))


@dataclass(frozen=True)
class FlightCondition:
    """Air density [kg/m³], speed of sound [m/s] and the airspeed range of an analysis.

    `speed_range` = (first, last, step) [m/s] is the initial grid of a V-g-f sweep
    (propwhirl.analysis.stability.analyse refines it); the thesis analyses 0–350 m/s.  The first speed
    must be > 0 (the aerodynamic matrices carry 1/V).
    """

    density: float = field(metadata=spec("density_kg_per_m3", "kg/m^3", "air density",
                                         range=(1e-4, 10.0)))
    speed_of_sound: float = field(default=SPEED_OF_SOUND_8000FT, metadata=spec(
        "speed_of_sound_m_per_s", "m/s", "speed of sound (Python default: ISA at 8000 ft, the "
        "thesis's altitude)", default="physical", file_required=True, range=(100.0, 1000.0)))
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

    def speeds(self) -> np.ndarray:
        """The initial grid [m/s]: first, first + step, ..., with the last speed included."""
        first, last, step = (float(x) for x in self.speed_range)
        grid = np.arange(first, last, step)
        return np.append(grid, last) if grid[-1] < last else grid
