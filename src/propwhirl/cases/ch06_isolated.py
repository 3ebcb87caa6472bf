"""Chapter 6: the propeller on a rigid wing — Bennett & Bland's configurations (Tables 6.1, 6.2).

The propeller (4 blades, R = 0.8438 ft; planform as inferred for Table 4.1: constant chord
0.1823 ft, hub ratio 0.22, aspect ratio 3.61) pivots at e = 0.346 R (configuration A) or
0.691 R (B) behind the propeller plane with I_Y = I_Z = 0.0634 slug ft² (A) or 0.0937 (B);
the spin inertia I_Ω = 0.00858 slug ft² is Table 8.1's.  Damping is the viscous equivalent
2ζ of Tables 6.1/6.2.  Windmilling at β_0.75: μ = 0.75 tan(β + 3°) (the relation inferred for
Table 4.1; Figure 6.2's result is insensitive to it, docs/validation.md).  Speed of sound
1116 ft/s.  Houbolt–Reed derivatives with wake, compressibility and aspect-ratio correction.
Figure 6.2's whirl flutter speed is recomputed in :mod:`propwhirl.reproduce.ch06`.
"""
from __future__ import annotations

from dataclasses import dataclass

from propwhirl.cases.ch04_propeller_aero import BB_RADIUS, FT, RR_SPEED_OF_SOUND, bennett_bland_geometry
from propwhirl.model.propellers import propeller_aero as aero
from propwhirl.model.propellers.propeller import PointMass, Propeller
from propwhirl.model.systems import FlightCondition, IsolatedPropeller
from propwhirl.validate import InputError

SLUG = 14.593903  # kg
SLUG_FT2 = SLUG * FT**2  # kg m²
SLUG_FT3 = SLUG / FT**3  # kg/m³
SPIN_INERTIA = 0.00858 * SLUG_FT2


@dataclass(frozen=True)
class BBCase:
    """One row of Tables 6.1/6.2."""

    beta_deg: float
    f_theta: float
    f_psi: float
    two_zeta_theta: float
    two_zeta_psi: float
    density_slug_ft3: float


#: Table 6.1, configuration (A): e = 0.346 R, I_Y = I_Z = 0.0634 slug ft²
CONFIG_A = {
    1: BBCase(35, 9.20, 9.12, 0.0060, 0.0090, 0.00211),
    2: BBCase(35, 10.96, 10.96, 0.0150, 0.0238, 0.00217),
    3: BBCase(46, 10.96, 10.96, 0.0150, 0.0238, 0.00218),
    4: BBCase(52, 10.96, 10.96, 0.0150, 0.0238, 0.00209),
    5: BBCase(58, 10.96, 10.96, 0.0150, 0.0238, 0.00209),
    6: BBCase(58, 10.71, 10.28, 0.0300, 0.0393, 0.00220),
}
#: Table 6.2, configuration (B): e = 0.691 R, I_Y = I_Z = 0.0937 slug ft²
CONFIG_B = {
    7: BBCase(35, 7.60, 7.60, 0.0056, 0.0053, 0.00227),
    8: BBCase(46, 7.60, 7.60, 0.0056, 0.0053, 0.00226),
    9: BBCase(52, 7.60, 7.60, 0.0056, 0.0053, 0.00226),
    10: BBCase(27.5, 7.64, 7.68, 0.0060, 0.0074, 0.00226),
    11: BBCase(35, 7.64, 7.68, 0.0060, 0.0074, 0.00220),
    12: BBCase(46, 7.64, 7.68, 0.0060, 0.0074, 0.00220),
    13: BBCase(58, 7.64, 7.68, 0.0060, 0.0062, 0.00220),
}


def bennett_bland_propeller(case: int, settings: aero.AeroSettings = aero.AeroSettings(),
                            advance_rule: aero.AdvanceRule = "blade_element") -> IsolatedPropeller:
    """Bennett & Bland's isolated propeller, case 1–13 of Tables 6.1/6.2 (SI)."""
    if case in CONFIG_A:
        c, e, inertia = CONFIG_A[case], 0.346, 0.0634
    elif case in CONFIG_B:
        c, e, inertia = CONFIG_B[case], 0.691, 0.0937
    else:
        raise InputError(f"case = {case!r} is invalid: Tables 6.1/6.2 have cases 1 to 13")
    R = BB_RADIUS
    prop = Propeller(
        name=f"Bennett & Bland propeller, case {case}",
        radius=R, n_blades=4, rotor=PointMass(1.0, 0.0),
        pivot_pitch=e * R, pivot_yaw=e * R,  # pivot behind the propeller plane
        inertia={"I_theta_P": inertia * SLUG_FT2, "I_psi_P": inertia * SLUG_FT2},
        spin_inertia=SPIN_INERTIA,
        f_theta=c.f_theta, f_psi=c.f_psi, damping="zeta",
        damping_theta=c.two_zeta_theta / 2, damping_psi=c.two_zeta_psi / 2,
        beta_075_deg=c.beta_deg, zero_lift_angle_deg=-3.0, advance_rule=advance_rule,
        rotation=1,
        derivatives=aero.HouboltReedSource(bennett_bland_geometry(), settings),
    )
    return IsolatedPropeller(prop, FlightCondition(c.density_slug_ft3 * SLUG_FT3, RR_SPEED_OF_SOUND,
                                                   speed_range=(1.0, 60.0, 2.0)),
                             name=prop.name)
