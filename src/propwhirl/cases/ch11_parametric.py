"""Chapter 11: parametric studies on the wingtip-mounted propeller wing (Tables 11.1–11.6).

Positions are measured from the wing mid-chord, positive aft (Table 9.4).  The cases here are
the thesis's tabulated ones (Figure 11.3, Tables 11.1–11.6, the §11.6 mode switch); the swept
curves of Figures 11.1–11.15 are functions of :mod:`propwhirl.studies.parametric`.
"""
from __future__ import annotations

from propwhirl.cases.ch09_baseline import baseline_propeller
from propwhirl.generated import prop_flexwing
from propwhirl.model.propeller import PointMass, Propeller
from propwhirl.reproduce.harness import register


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


# ----------------------------------------------------------------------------- aeroelastic results
# The ids name the mode the thesis names ("critical speed, forward whirl", ...): each value is
# that mode's flutter onset.  The wingtip models also have a static divergence near 140–145 m/s
# that the thesis does not report (docs/validation.md, chapter 10); it is not what these ids
# measure.

#: Table 11.1: (rotor x, motor x) [m] of the CG-moved cases.  Case 3 as printed (motor at
#: −0.40 m, "the motor-nacelle CG moved to the wing's leading edge", which at the tip chord of
#: 0.8 m is −0.40 m from mid-chord); the printed inertia values of that row (12.16 kg m²,
#: −16.28 kg m) belong to −0.20 m instead — see TABLE_11_1_CASE3_INERTIA_READING.
TABLE_11_1_CASES = {1: (-1.56, -1.26), 2: (-0.70, -0.40), 3: (-1.16, -0.40)}
#: The other reading of Table 11.1 case 3: the motor position implied by its inertia values.
TABLE_11_1_CASE3_INERTIA_READING = (-1.16, -0.20)
#: Table 11.2: the mode the thesis names as critical in each case.
TABLE_11_2_MODES = {1: "forward 1", 2: "wing 2", 3: "forward 1"}


def stiff_nacelle(f: float = 50.0) -> Propeller:
    """Figure 11.3: the baseline propeller with f_θ = f_ψ = `f` [Hz] (50 Hz in the thesis)."""
    return baseline_propeller(f_theta=f, f_psi=f)


def wingtip_with(propeller: Propeller):
    """The wingtip propeller-wing (§10.1, flexible mount, all aerodynamics) with `propeller`."""
    from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing

    return wingtip_propeller_wing(propeller=propeller)


def mode_onset(propeller: Propeller, label: str) -> tuple[float, float]:
    """(V [m/s], f [Hz]) of the flutter onset of mode `label` of the wingtip model with `propeller`."""
    from propwhirl.analysis.stability import analyse, speed_and_frequency

    return speed_and_frequency(analyse(wingtip_with(propeller)).first(label, "flutter"))


@register("f11.3")
def figure_11_3() -> dict[str, float]:
    """Figure 11.3: f_θ = f_ψ = 50 Hz — the whirl modes decouple and the second wing mode flutters."""
    V, f = mode_onset(stiff_nacelle(50.0), "wing 2")
    return {"f11.3/stiff_nacelle/flutter_speed": V, "f11.3/stiff_nacelle/flutter_frequency": f}


@register("t11.2")
def table_11_2() -> dict[str, float]:
    """Table 11.2: propeller CG moved (Table 11.1): onset of the mode the thesis names."""
    out = {}
    for case, (rotor_x, motor_x) in TABLE_11_1_CASES.items():
        V, f = mode_onset(cg_moved(rotor_x, motor_x), TABLE_11_2_MODES[case])
        out[f"t11.2/case{case}/critical_speed"] = V
        out[f"t11.2/case{case}/critical_frequency"] = f
    return out


@register("t11.4")
def table_11_4() -> dict[str, float]:
    """Table 11.4: pivot moved (Table 11.3): forward whirl flutter (cases 1–3), backward whirl
    flutter (case 4, which goes unstable before the forward whirl mode)."""
    out = {}
    for case, l in TABLE_11_3_CASES.items():
        V, f = mode_onset(pivot_moved(l), "backward 1" if case == 4 else "forward 1")
        out[f"t11.4/case{case}/critical_speed"] = V
        if case == 4:
            out["t11.4/case4/critical_frequency"] = f
    return out


@register("t11.6")
def table_11_6() -> dict[str, float]:
    """Table 11.6: CG and pivot moved together (Table 11.5): forward whirl flutter."""
    return {f"t11.6/case{case}/critical_speed": mode_onset(cg_and_pivot_moved(l), "forward 1")[0]
            for case, l in TABLE_11_5_CASES.items()}


@register("s11.6")
def section_11_6() -> dict[str, float]:
    """§11.6: blade angle at which the wingtip model's critical whirl mode switches from forward
    to backward whirl (bisection on β between 60° and 80°, 0.1° accuracy)."""
    from propwhirl.studies.parametric import blade_angle_mode_switch

    return {"s11.6/critical_mode_switch_beta": blade_angle_mode_switch((60.0, 80.0), xtol=0.1).beta}
