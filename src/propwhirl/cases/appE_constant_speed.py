"""Appendix E: the propeller-wing models with constant-speed propellers at 2250 RPM.

The baseline propeller (Tables 9.3–9.4) with `operation="constant-speed"`, Ω fixed at the
cruise 2250 RPM and the advance ratio varying with V (§9.2, "Another method for windmilling").
At very low speeds these propellers are unstable (the advance ratio tends to zero, §9.2); those
instabilities recover within a few m/s and are not what the appendix reports.  Tables E.1–E.3
are recomputed in :mod:`propwhirl.reproduce.appE`.
"""
from __future__ import annotations

from propwhirl.cases.ch09_baseline import baseline_propeller, inboard_y, propeller_wing
from propwhirl.cases.ch10_other_wings import two_propeller_wing, wingtip_propeller_wing
from propwhirl.model.propellers.propeller import Propeller
from propwhirl.model.systems import PropellerWing

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
