"""Appendix E: the propeller-wings with constant-speed propellers (Tables E.1–E.3; the cases are
:mod:`propwhirl.cases.appE_constant_speed`)."""
from __future__ import annotations

from propwhirl.analysis.stability import first_of_kind, speed_and_frequency
from propwhirl.cases.appE_constant_speed import (
    inboard_constant_speed,
    two_propeller_constant_speed,
    wingtip_constant_speed,
)
from propwhirl.reproduce.harness import analyse, register


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
