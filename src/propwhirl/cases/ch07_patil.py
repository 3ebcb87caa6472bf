"""Chapter 7: the Patil et al. HALE wing (Table 7.1), the verification case of the wing model.

Half span 16 m, chord 1 m, m = 0.75 kg/m, polar inertia 0.1 kg m, elastic axis and centre of
gravity at mid-chord, EI = 2e4 N m², GJ = 1e4 N m², air density 0.0889 kg/m³ (20 km).
"""
from __future__ import annotations

import numpy as np

from propwhirl.analysis.stability import analyse, first_of_kind, speed_and_frequency
from propwhirl.model.systems import FlightCondition, PropellerWing
from propwhirl.reproduce.harness import register
from propwhirl.analysis.vibration import classify_wing_modes
from propwhirl.model.wing import LiftSlope, Wing

#: Air density at 20 km used with the Patil wing (Table 7.1) [kg/m³]
PATIL_DENSITY = 0.0889


def patil_wing(n_elements: int = 20, lift_slope: LiftSlope = 2 * np.pi,
               aero_model: str = "leishman-nguyen") -> Wing:
    """The Patil wing of Table 7.1 (lift_slope="elliptic" gives the §7.5 variant, Table 7.4)."""
    return Wing(
        name="Patil HALE wing (Table 7.1)",
        semi_span=16.0,
        root_chord=1.0,
        mass_per_length=0.75,
        polar_inertia=0.1,
        elastic_axis=0.5,
        centre_of_gravity=0.5,
        EI=2.0e4,
        GJ=1.0e4,
        aerodynamic_centre=0.25,
        lift_slope=lift_slope,
        n_elements=n_elements,
        aero_model=aero_model,
    )


@register("t7.2")
def table_7_2() -> dict[str, float]:
    """Table 7.2: in-vacuo frequencies [rad/s] of the Patil wing with 3 beam elements."""
    modes = dict(classify_wing_modes(patil_wing(n_elements=3), count=4))
    return {
        "t7.2/first_bending": modes["bending 1"],
        "t7.2/second_bending": modes["bending 2"],
        "t7.2/third_bending": modes["bending 3"],
        "t7.2/first_torsion": modes["torsion 1"],
    }


def patil_model(n_elements: int = 20, lift_slope: LiftSlope = 2 * np.pi,
                aero_model: str = "leishman-nguyen") -> PropellerWing:
    """The Patil wing with its flight condition (ρ = 0.0889 kg/m³) as an aeroelastic model."""
    return PropellerWing(patil_wing(n_elements, lift_slope, aero_model),
                         FlightCondition(PATIL_DENSITY, speed_range=(1.0, 60.0, 2.0)),
                         name="Patil wing")


def _flutter_divergence(prefix: str, lift_slope) -> dict[str, float]:
    a = analyse(patil_model(20, lift_slope))
    Vf, ff = speed_and_frequency(first_of_kind(a, "flutter"))
    Vd, _ = speed_and_frequency(first_of_kind(a, "divergence"))
    return {f"{prefix}/flutter_speed": Vf, f"{prefix}/flutter_frequency": 2 * np.pi * ff,
            f"{prefix}/divergence_speed": Vd}


@register("t7.3")
def table_7_3() -> dict[str, float]:
    """Table 7.3: flutter speed [m/s], frequency [rad/s] and divergence speed, 20 elements."""
    return _flutter_divergence("t7.3", 2 * np.pi)


@register("t7.4")
def table_7_4() -> dict[str, float]:
    """Table 7.4: as 7.3 with the elliptic lift-curve slope 2π√(1 − x²) (eq. 7.81)."""
    return _flutter_divergence("t7.4", "elliptic")
