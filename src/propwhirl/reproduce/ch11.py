"""Chapter 11: the tabulated parametric cases on the wingtip-mounted propeller wing (Figure 11.3,
Tables 11.2–11.6) and the §11.6 mode switch; the cases are :mod:`propwhirl.cases.ch11_parametric`.

The ids name the mode the thesis names ("critical speed, forward whirl", ...): each value is
that mode's flutter onset.  The wingtip models also have a static divergence near 140–145 m/s
that the thesis does not report (docs/validation.md, chapter 10); it is not what these ids
measure.
"""
from __future__ import annotations

from propwhirl.analysis.stability import speed_and_frequency
from propwhirl.cases.ch11_parametric import (
    TABLE_11_1_CASES,
    TABLE_11_3_CASES,
    TABLE_11_5_CASES,
    cg_and_pivot_moved,
    cg_moved,
    pivot_moved,
    stiff_nacelle,
    wingtip_with,
)
from propwhirl.generated import prop_flexwing
from propwhirl.model.propellers.propeller import Propeller
from propwhirl.reproduce.harness import ANALYSIS_METHOD, analyse, register
from propwhirl.studies.parametric import blade_angle_mode_switch


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


#: Table 11.2: the mode the thesis names as critical in each case.
TABLE_11_2_MODES = {1: "forward 1", 2: "wing 2", 3: "forward 1"}


def mode_onset(propeller: Propeller, label: str) -> tuple[float, float]:
    """(V [m/s], f [Hz]) of the flutter onset of mode `label` of the wingtip model with `propeller`."""
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
    switch = blade_angle_mode_switch((60.0, 80.0), xtol=0.1, method=ANALYSIS_METHOD)
    return {"s11.6/critical_mode_switch_beta": switch.beta}
