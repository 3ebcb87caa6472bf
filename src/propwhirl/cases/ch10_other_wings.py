"""Chapter 10: the baseline wing with a wingtip-mounted propeller and with two propellers
(inboard at 1.6 m and wingtip), §10.1–10.2; 25 elements, baseline propellers.

Their results (Tables 10.1–10.8, Figures 10.6 and 10.14) are recomputed in
:mod:`propwhirl.reproduce.ch10`.
"""
from __future__ import annotations

from propwhirl.cases.ch09_baseline import baseline_wing, inboard_y, propeller_wing
from propwhirl.model.systems import PropellerWing


def tip_y() -> float:
    """Spanwise position of the wingtip node [m]."""
    return baseline_wing().semi_span


def wingtip_propeller_wing(mount: str = "flexible", **kwargs) -> PropellerWing:
    """§10.1: baseline wing with the baseline propeller at the wing tip (the headline case).

    kwargs: `propeller` (a modified baseline propeller) and the switches wing_aero,
    propeller_aero, rotating.
    """
    kwargs.setdefault("name", f"wingtip-mounted propeller wing ({mount} mount, §10.1)")
    return propeller_wing((tip_y(),), mount, **kwargs)


def two_propeller_wing(mount: str = "flexible", **kwargs) -> PropellerWing:
    """§10.2: baseline propellers at 1.6 m (node 8 of 25) and at the wing tip."""
    kwargs.setdefault("name", f"two-propeller wing ({mount} mounts, §10.2)")
    return propeller_wing((inboard_y(), tip_y()), mount, **kwargs)
