"""Appendix E: the propeller-wing models with constant-speed propellers at 2250 RPM.

The baseline propeller (Tables 9.3–9.4) with `operation="constant-speed"`, Ω fixed at the
cruise 2250 RPM and the advance ratio varying with V (§9.2, "Another method for windmilling").
At very low speeds these propellers are unstable (the advance ratio tends to zero, §9.2); those
instabilities recover within a few m/s and are not what the appendix reports.
"""
from __future__ import annotations

from propwhirl.analysis.stability import analyse, first_of_kind, speed_and_frequency
from propwhirl.cases.ch09_baseline import baseline_propeller, inboard_y, propeller_wing
from propwhirl.cases.ch10_other_wings import two_propeller_wing, wingtip_propeller_wing
from propwhirl.model.systems import PropellerWing
from propwhirl.model.propeller import Propeller
from propwhirl.reproduce.harness import register

#: Cruise rotational speed of appendix E [rev/min] (Table 9.3)
CRUISE_RPM = 2250.0


def constant_speed_propeller(rpm: float = CRUISE_RPM) -> Propeller:
    """The baseline propeller as a constant-speed propeller at `rpm` [rev/min]."""
    return baseline_propeller(operation="constant-speed", rpm=rpm)


def inboard_constant_speed() -> PropellerWing:
    """§E.1: the baseline (inboard, y ≈ 1.6 m) propeller-wing with a constant-speed propeller."""
    return propeller_wing((inboard_y(),), propeller=constant_speed_propeller())


def wingtip_constant_speed() -> PropellerWing:
    """§E.2: the wingtip-mounted propeller-wing with a constant-speed propeller."""
    return wingtip_propeller_wing(propeller=constant_speed_propeller())


def two_propeller_constant_speed() -> PropellerWing:
    """§E.3: the two-propeller wing with constant-speed propellers."""
    return two_propeller_wing(propeller=constant_speed_propeller())


@register("tE.1")
def table_E_1() -> dict[str, float]:
    """Table E.1: wing divergence speed of the inboard model (a real root through zero)."""
    return {"tE.1/divergence_speed": speed_and_frequency(first_of_kind(analyse(inboard_constant_speed()),
                                                                       "divergence"))[0]}


@register("tE.2")
def table_E_2() -> dict[str, float]:
    """Table E.2: forward whirl flutter of the wingtip model."""
    V, f = speed_and_frequency(analyse(wingtip_constant_speed()).first("forward 1", "flutter"))
    return {"tE.2/fw_whirl_flutter_speed": V, "tE.2/fw_whirl_flutter_frequency": f}


@register("tE.3")
def table_E_3() -> dict[str, float]:
    """Table E.3: second forward whirl flutter of the two-propeller wing."""
    V, f = speed_and_frequency(analyse(two_propeller_constant_speed()).first("forward 2", "flutter"))
    return {"tE.3/fw2_whirl_flutter_speed": V, "tE.3/fw2_whirl_flutter_frequency": f}
