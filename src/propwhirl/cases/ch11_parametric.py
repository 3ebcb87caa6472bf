"""Chapter 11: parametric studies on the wingtip-mounted propeller wing (Tables 11.1–11.6).

Positions are measured from the wing mid-chord, positive aft (Table 9.4).  The cases here are
the thesis's tabulated ones (Figure 11.3, Tables 11.1–11.6); their results, and the §11.6 mode
switch, are recomputed in :mod:`propwhirl.reproduce.ch11`; the swept curves of Figures
11.1–11.15 are functions of :mod:`propwhirl.studies.parametric`.
"""
from __future__ import annotations

from propwhirl.cases.ch09_baseline import baseline_propeller
from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
from propwhirl.model.propellers.propeller import PointMass, Propeller
from propwhirl.model.systems import PropellerWing


def cg_moved(rotor_x: float, motor_x: float) -> Propeller:
    """§11.4.1 (Table 11.1): rotor and motor-nacelle moved (pivot stays at mid-chord)."""
    return baseline_propeller(rotor=PointMass(8.0, rotor_x), masses=(PointMass(35.0, motor_x),))


def pivot_moved(l: float) -> Propeller:
    """§11.4.2 (Table 11.3): pitch and yaw pivots moved to l [m] (masses stay)."""
    return baseline_propeller(pivot_pitch=l, pivot_yaw=l)


def cg_and_pivot_moved(l: float) -> Propeller:
    """§11.4.3 (Table 11.5): masses and pivots shifted together by l [m]."""
    return baseline_propeller(
        rotor=PointMass(8.0, -1.16 + l), masses=(PointMass(35.0, -0.86 + l),),
        pivot_pitch=l, pivot_yaw=l,
    )


#: Table 11.3: pivot position l [m] of each case (pivot_moved).
TABLE_11_3_CASES = {1: 0.20, 2: -0.20, 3: -0.40, 4: -0.60}
#: Table 11.5: shift l [m] of masses and pivots together in each case (cg_and_pivot_moved).
TABLE_11_5_CASES = {1: 0.20, 2: -0.20, 3: -0.40, 4: -0.60}

#: Table 11.1: (rotor x, motor x) [m] of the CG-moved cases.  Case 3 as printed (motor at
#: −0.40 m, "the motor-nacelle CG moved to the wing's leading edge", which at the tip chord of
#: 0.8 m is −0.40 m from mid-chord); the printed inertia values of that row (12.16 kg m²,
#: −16.28 kg m) belong to −0.20 m instead — see TABLE_11_1_CASE3_INERTIA_READING.
TABLE_11_1_CASES = {1: (-1.56, -1.26), 2: (-0.70, -0.40), 3: (-1.16, -0.40)}
#: The other reading of Table 11.1 case 3: the motor position implied by its inertia values.
TABLE_11_1_CASE3_INERTIA_READING = (-1.16, -0.20)


def stiff_nacelle(f: float = 50.0) -> Propeller:
    """Figure 11.3: the baseline propeller with f_θ = f_ψ = `f` [Hz] (50 Hz in the thesis)."""
    return baseline_propeller(f_theta=f, f_psi=f)


def wingtip_with(propeller: Propeller) -> PropellerWing:
    """The wingtip propeller-wing (§10.1, flexible mount, all aerodynamics) with `propeller`."""
    return wingtip_propeller_wing(propeller=propeller)
