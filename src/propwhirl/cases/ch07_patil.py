"""Chapter 7: the Patil et al. HALE wing (Table 7.1), the verification case of the wing model.

Half span 16 m, chord 1 m, m = 0.75 kg/m, polar inertia 0.1 kg m, elastic axis and centre of
gravity at mid-chord, EI = 2e4 N m², GJ = 1e4 N m², air density 0.0889 kg/m³ (20 km).
Tables 7.2–7.4 are recomputed in :mod:`propwhirl.reproduce.ch07`.
"""
from __future__ import annotations

import numpy as np

from propwhirl.model.systems import FlightCondition, PropellerWing
from propwhirl.model.structure.wing import LiftSlope, Wing

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


def patil_model(n_elements: int = 20, lift_slope: LiftSlope = 2 * np.pi,
                aero_model: str = "leishman-nguyen") -> PropellerWing:
    """The Patil wing with its flight condition (ρ = 0.0889 kg/m³) as an aeroelastic model."""
    return PropellerWing(patil_wing(n_elements, lift_slope, aero_model),
                         FlightCondition(PATIL_DENSITY, speed_range=(1.0, 60.0, 2.0)),
                         name="Patil wing")
