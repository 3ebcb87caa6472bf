"""Chapter 11: parametric studies on the wingtip-mounted propeller wing (Tables 11.1–11.6).

Positions are measured from the wing mid-chord, positive aft (Table 9.4).
"""
from __future__ import annotations

from propwhirl.cases.ch09_baseline import baseline_propeller
from propwhirl.generated import prop_flexwing
from propwhirl.propeller import PointMass, Propeller
from propwhirl.reproduce import register


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


TABLE_11_3_CASES = {1: 0.20, 2: -0.20, 3: -0.40, 4: -0.60}
TABLE_11_5_CASES = {1: 0.20, 2: -0.20, 3: -0.40, 4: -0.60}


def wing_inertia(p: Propeller, elastic_axis: float = 0.0) -> dict[str, float]:
    """S_α,P, I_α,P, I_θα,P [kg m, kg m², kg m²] about the wing elastic axis at `elastic_axis`
    [m] aft of mid-chord (eq. 8.5–8.6), from the generated `prop_flexwing.inertia`."""
    i = p.pivot_inertia()
    S_a, I_a, I_ta = prop_flexwing.inertia(
        i["M_P"], i["S_theta_P"], i["I_theta_P"], p.pivot_pitch, elastic_axis
    )[..., 0]
    return {"S_alpha_P": float(S_a), "I_alpha_P": float(I_a), "I_theta_alpha_P": float(I_ta)}


@register("t11.3")
def table_11_3() -> dict[str, float]:
    """Table 11.3 case 1 (pivot at +0.20 m): I_θα,P."""
    return {"t11.3/case1/I_theta_alpha_P": wing_inertia(pivot_moved(0.20))["I_theta_alpha_P"]}


@register("t11.5")
def table_11_5() -> dict[str, float]:
    """Table 11.5 case 4 (CG and pivot shifted −0.60 m): I_α,P."""
    return {"t11.5/case4/I_alpha_P": wing_inertia(cg_and_pivot_moved(-0.60))["I_alpha_P"]}
