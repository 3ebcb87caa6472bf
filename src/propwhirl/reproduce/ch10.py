"""Chapter 10: the wingtip-mounted and the two-propeller wings (Tables 10.1–10.8, Figures 10.6
and 10.14; the cases are :mod:`propwhirl.cases.ch10_other_wings`)."""
from __future__ import annotations

from propwhirl.analysis.stability import speed_and_frequency
from propwhirl.analysis.vibration import label_modes
from propwhirl.cases.ch10_other_wings import two_propeller_wing, wingtip_propeller_wing
from propwhirl.reproduce.harness import analyse, register


@register("t10.1")
def table_10_1() -> dict[str, float]:
    """Table 10.1: rigid, non-rotating wingtip propeller [Hz]."""
    modes = dict(label_modes(wingtip_propeller_wing("rigid", rotating=False)))
    return {f"t10.1/freq{i}": modes[f"wing {i}"] for i in range(1, 6)}


@register("t10.3")
def table_10_3() -> dict[str, float]:
    """Table 10.3: flexibly mounted wingtip propeller, Ω = 0 [Hz]."""
    modes = dict(label_modes(wingtip_propeller_wing()))
    out = {f"t10.3/wing{i}": modes[f"wing {i}"] for i in range(1, 6)}
    out["t10.3/backward"] = modes["backward 1"]
    out["t10.3/forward"] = modes["forward 1"]
    return out


@register("t10.5")
def table_10_5() -> dict[str, float]:
    """Table 10.5: two rigid, non-rotating propellers [Hz]."""
    modes = dict(label_modes(two_propeller_wing("rigid", rotating=False)))
    return {f"t10.5/freq{i}": modes[f"wing {i}"] for i in range(1, 6)}


@register("t10.7")
def table_10_7() -> dict[str, float]:
    """Table 10.7: two flexibly mounted propellers, Ω = 0 [Hz]."""
    modes = dict(label_modes(two_propeller_wing()))
    out = {f"t10.7/wing{i}": modes[f"wing {i}"] for i in range(1, 6)}
    out["t10.7/backward1"] = modes["backward 1"]
    out["t10.7/backward2"] = modes["backward 2"]
    return out


# ----------------------------------------------------------------------------- aeroelastic results
@register("t10.2")
def table_10_2() -> dict[str, float]:
    """Table 10.2: rigid, non-rotating wingtip propeller: flutter of the second wing mode."""
    a = analyse(wingtip_propeller_wing("rigid", rotating=False, propeller_aero=False))
    V, f = speed_and_frequency(a.first("wing 2", "flutter"))
    return {"t10.2/flutter_speed": V, "t10.2/flutter_frequency": f}


def _table_10_4(prefix: str, **switches) -> dict[str, float]:
    a = analyse(wingtip_propeller_wing(**switches))
    Vf, ff = speed_and_frequency(a.first("forward 1", "flutter"))
    Vb, fb = speed_and_frequency(a.first("backward 1", "flutter"))
    out = {f"{prefix}/fw_whirl_flutter_speed": Vf, f"{prefix}/fw_whirl_flutter_frequency": ff,
           f"{prefix}/bw_whirl_flutter_speed": Vb, f"{prefix}/bw_whirl_flutter_frequency": fb}
    if switches.get("propeller_aero", True):
        div = a.first("forward 1", event="frequency-zero")
        out[f"{prefix}/fw_divergence_speed"] = speed_and_frequency(div)[0]
    return out


@register("t10.4")
def table_10_4() -> dict[str, float]:
    """Table 10.4: flexibly mounted rotating wingtip propeller, without and with propeller aero.

    The forward-whirl divergence is where the (already fluttering) forward whirl mode's
    frequency falls to zero (§10.1.2)."""
    return {**_table_10_4("t10.4/no_prop_aero", propeller_aero=False), **_table_10_4("t10.4/full")}


@register("f10.6")
def figure_10_6() -> dict[str, float]:
    """Figure 10.6: wingtip propeller wing without wing aerodynamics: backward whirl flutter."""
    a = analyse(wingtip_propeller_wing(wing_aero=False))
    V, f = speed_and_frequency(a.first("backward 1", "flutter"))
    return {"f10.6/no_wing_aero/bw_whirl_flutter_speed": V, "f10.6/no_wing_aero/bw_whirl_flutter_frequency": f}


@register("t10.6")
def table_10_6() -> dict[str, float]:
    """Table 10.6: two rigid, non-rotating propellers: flutter of the fourth wing mode."""
    a = analyse(two_propeller_wing("rigid", rotating=False, propeller_aero=False))
    V, f = speed_and_frequency(a.first("wing 4", "flutter"))
    return {"t10.6/flutter_speed": V, "t10.6/flutter_frequency": f}


def _table_10_8(prefix: str, **switches) -> dict[str, float]:
    a = analyse(two_propeller_wing(**switches))
    Vf, ff = speed_and_frequency(a.first("forward 2", "flutter"))
    Vb, fb = speed_and_frequency(a.first("backward 2", "flutter"))
    return {f"{prefix}/fw2_whirl_flutter_speed": Vf, f"{prefix}/fw2_whirl_flutter_frequency": ff,
            f"{prefix}/bw2_whirl_flutter_speed": Vb, f"{prefix}/bw2_whirl_flutter_frequency": fb}


@register("t10.8")
def table_10_8() -> dict[str, float]:
    """Table 10.8: two flexibly mounted rotating propellers, without and with propeller aero."""
    return {**_table_10_8("t10.8/no_prop_aero", propeller_aero=False), **_table_10_8("t10.8/full")}


@register("f10.14")
def figure_10_14() -> dict[str, float]:
    """Figure 10.14: two-propeller wing without wing aerodynamics: backward whirl flutter."""
    a = analyse(two_propeller_wing(wing_aero=False))
    out = {}
    for k in (1, 2):
        V, f = speed_and_frequency(a.first(f"backward {k}", "flutter"))
        out[f"f10.14/no_wing_aero/bw{k}_whirl_flutter_speed"] = V
        out[f"f10.14/no_wing_aero/bw{k}_whirl_flutter_frequency"] = f
    return out
