"""Chapter 9: the baseline models (Tecnam P2006T / X-57 based), Table 9.1 onwards.

Baseline wing (Table 9.1): span 11.4 m (semi-span 5.7 m), root chord 1.25 m, tip chord 0.8 m,
m = 25 kg/m, radius of gyration about the centre of gravity 25 % chord, elastic axis and centre
of gravity at 50 % chord, EI = 7e5 N m², GJ = 2e5 N m², aerodynamic centre 25 % chord,
C_lα = 2π; flight condition 8000 ft, ρ = 0.962870 kg/m³.  20 beam elements alone, 25 with
propellers (§9.3).  The chapter's results (Tables 9.2–9.9, §9.2, Figure 9.19) are recomputed
in :mod:`propwhirl.reproduce.ch09`.
"""
from __future__ import annotations

import numpy as np

from propwhirl.model.propellers.propeller import PointMass, Propeller
from propwhirl.model.systems import (
    SPEED_OF_SOUND_8000FT,
    FlightCondition,
    Installation,
    IsolatedPropeller,
    PropellerWing,
)
from propwhirl.model.structure.wing import Wing

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


def baseline_wing_model(n_elements: int = 20) -> PropellerWing:
    """The baseline wing alone at 8000 ft (§9.1)."""
    return PropellerWing(baseline_wing(n_elements), baseline_flight(), name="baseline wing")


# ----------------------------------------------------------------------------- §9.2 propeller
def baseline_propeller(**changes) -> Propeller:
    """The baseline propeller of Tables 9.3–9.4 (X-57 cruise propeller, simplified).

    3 blades, R = 0.762 m, hub radius 0.125 m, constant chord 0.094 m, β_0.75 = 35°,
    fixed pitch windmilling with J = π tan(β − 3°) = 1.96 (eq. 9.1); rotor 8 kg at −1.16 m
    (the propeller plane), motor-nacelle 35 kg at −0.86 m, pitch and yaw pivots on the wing
    mid-chord axis (l = 0, e = −1.16 m), f_θ = f_ψ = 7 Hz, g_θ = g_ψ = 0.005; I_Ω = M_r R²/3.
    Keyword arguments replace any field (e.g. f_psi=4.0, operation="constant-speed", rpm=2250).
    """
    base = dict(
        name="baseline propeller (Tables 9.3-9.4)",
        radius=0.762,
        hub_radius=0.125,
        blade_chord=0.094,
        n_blades=3,
        rotor=PointMass(8.0, -1.16),
        masses=(PointMass(35.0, -0.86),),
        pivot_pitch=0.0,
        pivot_yaw=0.0,
        f_theta=7.0,
        f_psi=7.0,
        damping_theta=0.005,
        damping_psi=0.005,
        damping="g",
        beta_075_deg=35.0,
        zero_lift_angle_deg=-3.0,
        rotation=1,
    )
    base.update(changes)
    return Propeller(**base)


def baseline_flight() -> FlightCondition:
    """8000 ft: ρ = 0.962870 kg/m³ (Table 9.1), ISA speed of sound 330.8 m/s."""
    return FlightCondition(BASELINE_DENSITY, SPEED_OF_SOUND_8000FT)


def isolated_baseline_propeller(**changes) -> IsolatedPropeller:
    """The baseline propeller on a rigid wing (§9.2, chapter 6 model)."""
    return IsolatedPropeller(baseline_propeller(**changes), baseline_flight())


# ----------------------------------------------------------------------------- §9.3 prop-wing
N_ELEMENTS_WITH_PROPELLERS = 25
INBOARD_NODE = 7  # the thesis's node 8 counting the root as node 1: y = 7·5.7/25 = 1.596 m


def inboard_y(n_elements: int = N_ELEMENTS_WITH_PROPELLERS) -> float:
    """Spanwise position [m] of the inboard propeller node (≈ 1.6 m, node 8 of 25 in the thesis)."""
    return baseline_wing(n_elements).node_y[INBOARD_NODE * n_elements // N_ELEMENTS_WITH_PROPELLERS]


def propeller_wing(positions: tuple[float, ...], mount: str = "flexible",
                   propeller: Propeller | None = None, name: str = "propeller-wing",
                   **switches) -> PropellerWing:
    """Baseline wing (25 elements) with baseline propellers at the given node positions [m].

    `switches`: wing_aero, propeller_aero, rotating (all True by default).
    """
    prop = baseline_propeller() if propeller is None else propeller
    return PropellerWing(
        baseline_wing(N_ELEMENTS_WITH_PROPELLERS),
        baseline_flight(),
        tuple(Installation(prop, y, mount) for y in positions),
        name=name,
        **switches,
    )


def inboard_propeller_wing(mount: str = "flexible", **switches) -> PropellerWing:
    """§9.3: baseline wing with the baseline propeller at 1.6 m (node 8 of 25)."""
    switches.setdefault("name", f"inboard propeller wing ({mount} mount, §9.3)")
    return propeller_wing((inboard_y(),), mount, **switches)
