"""Chapter 10: the baseline wing with a wingtip-mounted propeller and with two propellers
(inboard at 1.6 m and wingtip), §10.1–10.2; 25 elements, baseline propellers."""
from __future__ import annotations

from propwhirl.cases.ch09_baseline import baseline_wing, inboard_y, propeller_wing
from propwhirl.model import PropellerWing
from propwhirl.reproduce import register
from propwhirl.vibration import label_modes


def tip_y() -> float:
    """Spanwise position of the wingtip node [m]."""
    return baseline_wing().semi_span


def wingtip_propeller_wing(mount: str = "flexible", **kwargs) -> PropellerWing:
    """§10.1: baseline wing with the baseline propeller at the wing tip (the headline case).

    kwargs: `propeller` (a modified baseline propeller) and the switches wing_aero,
    propeller_aero, rotating.
    """
    return propeller_wing((tip_y(),), mount, **kwargs)


def two_propeller_wing(mount: str = "flexible", **kwargs) -> PropellerWing:
    """§10.2: baseline propellers at 1.6 m (node 8 of 25) and at the wing tip."""
    return propeller_wing((inboard_y(), tip_y()), mount, **kwargs)


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
