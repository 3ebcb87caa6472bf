"""The flight envelope of a clearance campaign: ISA altitudes, V_D given as an equivalent or a
true airspeed (limited by M_D), and the failure-case line of CS/FAR 25.629(b)(2)(ii)
(:func:`failure_line`) — what :mod:`propwhirl.studies.campaign` analyses each case at, one
:class:`EnvelopePoint` each (moved out of campaign.py, issue 38: the envelope is its own job).
SI units: altitudes [m], speeds [m/s].
"""
from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from propwhirl import validate as v
from propwhirl.certification import AIRSPEEDS, FACTOR_VC_FAILURE  # noqa: F401 (re-exported)
from propwhirl.model import atmosphere

#: Sea-level ISA density ρ0 [kg/m³] (the reference of an equivalent airspeed).
RHO0 = float(atmosphere.density(0.0))
#: The Mach number added to M_C above the lowest V_C/M_C intersection in 25.629(b)(2)(ii).
DELTA_M_C = 0.05


@dataclass(frozen=True)
class EnvelopePoint:
    """One point of the flight envelope: an ISA altitude [m] and V_D there.

    V_D: the design dive speed as a true airspeed [m/s] (what the analyses use);
    V_D_given: as given [m/s] (`airspeed`: "EAS" or "TAS"); mach_limited: V_D = M_D · a(h)
    (M_D is the lower bound at this altitude); V_line: the failure-case line of
    25.629(b)(2)(ii) at this altitude as a true airspeed [m/s] (None: no V_C given) and
    line_part: which part of it ("1.15 V_C", "V_C-M_C line", "M_C + 0.05";
    :func:`failure_line`)."""

    altitude_m: float
    V_D: float
    V_D_given: float
    airspeed: str
    mach_limited: bool = False
    V_line: float | None = None
    line_part: str = ""


def true_airspeed(V: float, airspeed: str, altitude_m: float) -> float:
    """V [m/s] as a true airspeed at the ISA `altitude_m` [m]: V_TAS = V_EAS · sqrt(ρ0 / ρ(h))
    for an equivalent airspeed ("EAS"), V itself for "TAS"."""
    if airspeed not in AIRSPEEDS:
        raise v.InputError(f"airspeed = {v.short_repr(airspeed)} is invalid: must be one of "
                           f"{', '.join(AIRSPEEDS)}")
    if airspeed == "TAS":
        return float(V)
    return float(V) * math.sqrt(RHO0 / float(atmosphere.density(altitude_m)))


def mach_eas(M: float, altitude_m: float) -> float:
    """The equivalent airspeed [m/s] of Mach `M` at the ISA `altitude_m` [m]:
    M a(h) sqrt(ρ(h) / ρ0)."""
    h = float(altitude_m)
    return float(M) * float(atmosphere.speed_of_sound(h)) * math.sqrt(
        float(atmosphere.density(h)) / RHO0)


def _crossing(f: Any) -> float | None:
    """The lowest ISA altitude [m] where f(h) changes from > 0 to <= 0 (f continuous), None
    when f > 0 over the whole ISA range; -inf when f <= 0 already at its bottom."""
    from scipy.optimize import brentq

    grid = np.linspace(atmosphere.MIN_ALTITUDE, atmosphere.MAX_ALTITUDE, 371)
    vals = [f(h) for h in grid]
    if vals[0] <= 0.0:
        return -math.inf
    for i in range(1, grid.size):
        if vals[i] <= 0.0:
            return float(brentq(f, grid[i - 1], grid[i], xtol=1e-6))
    return None


def failure_line(altitudes_m: Sequence[float], V_C: float | Sequence[float],
                 M_C: float | None = None,
                 V_C_altitudes_m: Sequence[float] | None = None) -> list[tuple[float, str]]:
    """The altitude-airspeed envelope of 25.629(b)(2)(ii) at each ISA altitude [m]:
    (equivalent airspeed [m/s], which part of the line) —

    * "1.15 V_C": 15 % above V_C (EAS) at constant altitude, from sea level (and below) to h1,
      the altitude where 1.15 V_C meets the extension of the M_C line (M_C a(h) in EAS:
      :func:`mach_eas`);
    * "V_C-M_C line": linear in EAS against altitude from 1.15 V_C at h1 to M_C + 0.05 at h2,
      the altitude of the lowest V_C/M_C intersection;
    * "M_C + 0.05": above h2, (M_C + 0.05) a(h) at constant altitude.

    V_C [m/s] is an EAS, one for every altitude or one per altitude of `V_C_altitudes_m`
    (default `altitudes_m`; linear between them, constant beyond).  Without M_C the line is
    1.15 V_C at every altitude.  An M_C whose line lies below 1.15 V_C already at the ISA's
    lowest altitude, or whose V_C/M_C intersection is above its highest with h1 below it, is
    an InputError."""
    alts = np.atleast_1d(np.asarray(altitudes_m, dtype=float))
    vc = np.atleast_1d(np.asarray(V_C, dtype=float))
    at = alts if V_C_altitudes_m is None else np.atleast_1d(np.asarray(V_C_altitudes_m, float))
    if vc.size == 1:
        vc, at = np.full(1, vc[0]), np.zeros(1)
    if vc.size != at.size:
        raise v.InputError(f"V_C has {vc.size} speeds for {at.size} altitudes: give one V_C or "
                           "one per altitude")
    order = np.argsort(at)
    at, vc = at[order], vc[order]

    def V_C_at(h: float) -> float:
        return float(np.interp(h, at, vc))

    k, vc_part = FACTOR_VC_FAILURE, f"{FACTOR_VC_FAILURE:g} V_C"     # 1.15 V_C
    if M_C is None:
        return [(k * V_C_at(h), vc_part) for h in alts]
    h1 = _crossing(lambda h: mach_eas(M_C, h) - k * V_C_at(h))
    h2 = _crossing(lambda h: mach_eas(M_C, h) - V_C_at(h))
    if h1 == -math.inf:
        raise v.InputError(f"M_C = {M_C:g} is invalid with V_C = {vc.min():g} m/s (EAS): its "
                           f"line is below {vc_part} "
                           f"already at {atmosphere.MIN_ALTITUDE:g} m (M_C is the cruise Mach "
                           "number above the V_C/M_C intersection)")
    if h1 is None:                            # the M_C line never reaches 1.15 V_C
        return [(k * V_C_at(h), vc_part) for h in alts]
    if h2 is None:
        raise v.InputError(f"M_C = {M_C:g} is invalid with V_C = {vc.min():g} m/s (EAS): "
                           f"{vc_part} meets its line at "
                           f"{h1:.0f} m but V_C does not below {atmosphere.MAX_ALTITUDE:g} m")
    top = mach_eas(M_C + DELTA_M_C, h2)
    start = k * V_C_at(h1)
    out = []
    for h in alts:
        if h <= h1:
            out.append((k * V_C_at(h), vc_part))
        elif h <= h2:
            w = (h - h1) / (h2 - h1) if h2 > h1 else 1.0
            out.append((float(start + w * (top - start)), "V_C-M_C line"))
        else:
            out.append((mach_eas(M_C + DELTA_M_C, h), "M_C + 0.05"))
    return out


def envelope(V_D: float | Sequence[float], altitudes_m: Sequence[float], *,
             airspeed: str = "EAS", M_D: float | None = None,
             V_C: float | Sequence[float] | None = None,
             M_C: float | None = None) -> tuple[EnvelopePoint, ...]:
    """The envelope points: V_D [m/s] (one for all altitudes, or one per altitude: a
    V–altitude line) as `airspeed` at each ISA altitude [m], limited by M_D · a(h) [m/s]
    when M_D is given; with V_C (an EAS [m/s], one or one per altitude) and optionally M_C,
    each point's failure-case line of 25.629(b)(2)(ii) (:func:`failure_line`) as a true
    airspeed.

    Parameters
    ----------
    V_D : float or sequence of float
        Design dive speed [m/s] (as `airspeed`), one for all altitudes or one per altitude.
    altitudes_m : sequence of float
        ISA altitudes [m].
    airspeed : {"EAS", "TAS"}
        What V_D (and V_C) are.
    M_D : float, optional
        Design dive Mach number: V_D at most M_D · a(h).
    V_C : float or sequence of float, optional
        Design cruise speed, EAS [m/s] (the failure-case line).
    M_C : float, optional
        Design cruise Mach number (with V_C).

    Returns
    -------
    tuple of EnvelopePoint
        Per altitude: altitude [m], V_D as a true airspeed [m/s] (what the analyses use), as
        given, whether M_D limits it, the failure-case line [m/s].

    Examples
    --------
    V_D = 100 m/s EAS is 129 m/s true at 5000 m, unless M_D = 0.3 limits it:

    >>> from propwhirl.studies import envelope
    >>> [round(p.V_D, 1) for p in envelope(100.0, [0.0, 5000.0])]
    [100.0, 129.0]
    >>> [(round(p.V_D, 1), p.mach_limited) for p in envelope(100.0, [0.0, 5000.0], M_D=0.3)]
    [(100.0, False), (96.2, True)]
    """
    alts = np.atleast_1d(np.asarray(v.finite("altitudes_m", altitudes_m, "m"), dtype=float))
    if alts.ndim != 1 or alts.size == 0:
        raise v.InputError("altitudes_m is invalid: give one or more altitudes")
    v.in_range("altitudes_m", alts, -5000.0, 32000.0)
    vd = np.atleast_1d(np.asarray(v.positive("V_D", V_D, "m/s"), dtype=float))
    if vd.size == 1:
        vd = np.full(alts.size, float(vd[0]))
    if vd.shape != alts.shape:
        raise v.InputError(f"V_D has {vd.size} speeds for {alts.size} altitudes: give one V_D "
                           "or one per altitude")
    if M_D is not None:
        v.in_range("M_D", M_D, 0.01, 0.95)
    line: list[tuple[float | None, str]] = [(None, "")] * alts.size
    if V_C is not None:
        v.in_range("V_C", V_C, 1.0, 1000.0)
        if M_C is not None:
            v.in_range("M_C", M_C, 0.01, 0.95)
        line = list(failure_line(alts, V_C, M_C))
    elif M_C is not None:
        raise v.InputError("M_C needs V_C (the failure-case envelope of 25.629(b)(2)(ii))")
    out = []
    for h, V, (eas, part) in zip(alts, vd, line):
        tas = true_airspeed(float(V), airspeed, float(h))
        limited = False
        if M_D is not None:
            vm = float(M_D) * float(atmosphere.speed_of_sound(float(h)))
            if vm < tas:
                tas, limited = vm, True
        out.append(EnvelopePoint(float(h), tas, float(V), airspeed, limited,
                                 None if eas is None else true_airspeed(eas, "EAS", float(h)),
                                 part))
    return tuple(out)
