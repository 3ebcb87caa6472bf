"""Chapter 9: the baseline models (Tecnam P2006T / X-57 based), Table 9.1 onwards.

Baseline wing (Table 9.1): span 11.4 m (semi-span 5.7 m), root chord 1.25 m, tip chord 0.8 m,
m = 25 kg/m, radius of gyration about the centre of gravity 25 % chord, elastic axis and centre
of gravity at 50 % chord, EI = 7e5 N m², GJ = 2e5 N m², aerodynamic centre 25 % chord,
C_lα = 2π; flight condition 8000 ft, ρ = 0.962870 kg/m³.  20 beam elements alone, 25 with
propellers (§9.3).
"""
from __future__ import annotations

import numpy as np

from propwhirl.reproduce import register
from propwhirl.vibration import wing_modes
from propwhirl.wing import Wing

#: Air density at 8000 ft used throughout chapters 9–11 (Table 9.1) [kg/m³]
BASELINE_DENSITY = 0.962870


def baseline_wing(n_elements: int = 20, aero_model: str = "leishman-nguyen") -> Wing:
    """The baseline wing of Table 9.1."""
    return Wing(
        name="baseline wing (Table 9.1)",
        semi_span=5.7,
        root_chord=1.25,
        tip_chord=0.8,
        mass_per_length=25.0,
        radius_of_gyration=0.25,
        elastic_axis=0.5,
        centre_of_gravity=0.5,
        EI=7.0e5,
        GJ=2.0e5,
        aerodynamic_centre=0.25,
        lift_slope=2 * np.pi,
        n_elements=n_elements,
        aero_model=aero_model,
    )


@register("t9.2/freq")
def table_9_2_frequencies() -> dict[str, float]:
    """Table 9.2a: the first five natural frequencies [Hz] of the baseline wing (20 elements)."""
    f = wing_modes(baseline_wing()).frequency_hz
    return {f"t9.2/freq{i + 1}": float(f[i]) for i in range(5)}
