"""Chapter 6: Bennett & Bland's isolated propeller (case of :mod:`propwhirl.cases.ch06_isolated`)."""
from __future__ import annotations

from propwhirl.analysis.stability import speed_and_frequency
from propwhirl.cases.ch04_propeller_aero import FT
from propwhirl.cases.ch06_isolated import bennett_bland_propeller
from propwhirl.reproduce.harness import analyse, register


@register("f6.2")
def figure_6_2() -> dict[str, float]:
    """Figure 6.2: configuration (A) case 1, whirl flutter speed [ft/s]."""
    a = analyse(bennett_bland_propeller(1))
    V, _ = speed_and_frequency(a.first("backward", "flutter"))
    return {"f6.2/configA_case1/whirl_flutter_speed": V / FT}
