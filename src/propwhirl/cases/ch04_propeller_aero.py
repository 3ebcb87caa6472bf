"""Chapter 4 cases: the Bennett & Bland / Rodden & Rose propeller and Table 4.1's operating data.

The thesis (§4.2) validates its Houbolt–Reed implementation against Rodden & Rose's
derivatives for "the Bennett & Bland propeller with twice the chord": 4 blades,
R = 0.8438 ft, 1800 RPM, speed of sound 1116 ft/s, wake + compressibility + aspect-ratio
correction.  It prints neither the planform nor how β_0.75R sets the advance ratio; the
values below were inferred by numerical experiment (docs/validation.md, "Chapter 4"):

* chord: constant; the 0.1823 ft that §4.2 calls a *semichord* is the Bennett & Bland
  *chord* (solidity at 0.75R: 4 · 0.1823 / (2π · 0.75 · 0.8438) = 0.1834, as printed), so
  Rodden & Rose's chord is 2 · 0.1823 = 0.3646 ft;
* aspect ratio A of eq. 4.20: that of the physical Bennett & Bland blade, eq. 4.21 with the
  0.1823 ft chord, A = R(1 − η0)/0.1823 ft (not recomputed for the doubled chord);
* hub ratio η0 = 0.22;
* windmilling advance ratio μ = 0.75 tan(β_0.75R + 3°) (zero lift at the 0.75R section
  with α_0L = −3°, rule "blade_element" of :func:`propwhirl.model.propellers.propeller_aero.advance_ratio_from_blade_angle`).

Table 4.1's values and the sensitivity of the inference are recomputed in
:mod:`propwhirl.reproduce.ch04`.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from propwhirl.model.propellers import propeller_aero as aero

FT = 0.3048  # m per ft

#: Bennett & Bland propeller (NASA TN D-2399 model, as quoted in §4.2), SI.
BB_RADIUS = 0.8438 * FT
BB_CHORD = 0.1823 * FT
BB_BLADES = 4
#: Inferred (docs/validation.md): hub ratio and zero-lift angle of the windmilling relation.
BB_HUB_RATIO = 0.22
BB_ZERO_LIFT_ANGLE = math.radians(-3.0)
BB_ADVANCE_RULE: aero.AdvanceRule = "blade_element"

#: Table 4.1 operating data (§4.2).
RR_RPM = 1800.0
RR_SPEED_OF_SOUND = 1116.0 * FT
TABLE_4_1_BETAS = (25, 35, 46, 52, 58)


@dataclass(frozen=True)
class Table41Assumptions:
    """The inferred, unprinted data of Table 4.1 (defaults: the inference of this module).

    hub_ratio         η0
    chord_factor      R&R chord = chord_factor · 0.1823 ft (2: "twice the chord")
    aspect_ratio_rule "physical": A = R(1−η0)/0.1823 ft (eq. 4.21 with the B&B chord);
                      "eq_4_21": eq. 4.21 with the doubled chord
    taper             c_tip/c_root of a linear chord with c(0.75) = the chord (1: constant)
    zero_lift_deg     α_0L [deg] of the windmilling relation
    advance_rule      see :func:`propwhirl.model.propellers.propeller_aero.advance_ratio_from_blade_angle`
    settings          model switches (default: wake + compressibility + aspect ratio)
    speed_of_sound    [m/s]
    """

    hub_ratio: float = BB_HUB_RATIO
    chord_factor: float = 2.0
    aspect_ratio_rule: str = "physical"
    taper: float = 1.0
    zero_lift_deg: float = -3.0
    advance_rule: aero.AdvanceRule = BB_ADVANCE_RULE
    settings: aero.AeroSettings = aero.AeroSettings()
    speed_of_sound: float = RR_SPEED_OF_SOUND


def _chord(c75: float, taper: float) -> float | aero.Distribution:
    if taper == 1.0:
        return c75
    root = c75 / (1.0 + 0.75 * (taper - 1.0))
    return aero.Distribution.linear(root, root * taper, 0.0, name="chord")


def rodden_rose_geometry(a: Table41Assumptions = Table41Assumptions()) -> aero.PropellerGeometry:
    """Rodden & Rose's propeller: the Bennett & Bland propeller with `chord_factor` × chord."""
    chord = _chord(a.chord_factor * BB_CHORD, a.taper)
    if a.aspect_ratio_rule == "physical":
        A = BB_RADIUS * (1.0 - a.hub_ratio) / BB_CHORD
    elif a.aspect_ratio_rule == "eq_4_21":
        A = None
    else:
        raise ValueError(f"unknown aspect_ratio_rule {a.aspect_ratio_rule!r}")
    return aero.PropellerGeometry(BB_BLADES, BB_RADIUS, a.hub_ratio, chord, aspect_ratio=A)


def table_4_1_derivatives(a: Table41Assumptions = Table41Assumptions()) -> aero.PropellerDerivatives:
    """Derivatives at the five blade angles of Table 4.1 (1800 RPM, constant speed)."""
    omega = RR_RPM * 2.0 * math.pi / 60.0
    mu = aero.advance_ratio_from_blade_angle(
        np.radians(TABLE_4_1_BETAS), math.radians(a.zero_lift_deg), a.advance_rule)
    geo = rodden_rose_geometry(a)
    return aero.constant_speed(geo, mu * omega * geo.radius, omega,
                               speed_of_sound=a.speed_of_sound, settings=a.settings)


def bennett_bland_geometry(hub_ratio: float = BB_HUB_RATIO) -> aero.PropellerGeometry:
    """The Bennett & Bland propeller with its normal chord (Tables 6.1/6.2), A by eq. 4.21."""
    return aero.PropellerGeometry(BB_BLADES, BB_RADIUS, hub_ratio, BB_CHORD)


def config_a_derivatives(airspeed, blade_angle_deg: float = 35.0,
                         speed_of_sound: float = RR_SPEED_OF_SOUND,
                         settings: aero.AeroSettings = aero.AeroSettings(),
                         zero_lift_deg: float = -3.0,
                         rule: aero.AdvanceRule = BB_ADVANCE_RULE) -> aero.PropellerDerivatives:
    """Derivatives of configuration (A) of Table 6.1 (Bennett & Bland, normal chord).

    Windmilling fixed-pitch propeller at β_0.75R = `blade_angle_deg` (case 1: 35°), airspeed
    V [m/s] (array allowed; Figure 6.2 case 1 is at 95 ft/s = 28.956 m/s).  Defaults: the
    advance-ratio relation inferred from Table 4.1 (μ = 0.75 tan(β + 3°)), speed of sound
    1116 ft/s, wake + compressibility + aspect-ratio correction (thesis default, §4.2).
    """
    geo = bennett_bland_geometry()
    return aero.windmilling(geo, airspeed, math.radians(blade_angle_deg),
                            speed_of_sound=speed_of_sound,
                            zero_lift_angle=math.radians(zero_lift_deg), rule=rule,
                            settings=settings)
