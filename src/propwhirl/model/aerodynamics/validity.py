"""Validity of the aerodynamic methods: what propwhirl refuses and what it flags (one place).

Both aerodynamic methods are subsonic: the wing's strip theory (Theodorsen, Wagner,
Leishman–Nguyen; §7.2, §7.5) is incompressible (or carries the Prandtl–Glauert lift slope,
:mod:`propwhirl.model.aerodynamics.compressibility`), and the Houbolt–Reed propeller derivatives
(chapter 4) carry a first-order Prandtl–Glauert correction whose singularity at a section Mach
number of 1 is clipped by the Rodden–Rose cut-off (eq. 4.23–4.24).

Refused (:class:`~propwhirl.validate.InputError`), because no number computed there means
anything:

* a free-stream Mach number V/a >= :data:`MACH_REFUSED` (5, the conventional start of
  hypersonic flow) at any analysed speed of a model with aerodynamics on, and in
  :func:`propwhirl.model.propellers.propeller_aero.derivatives`;
* a propeller solidity N_b ∫c dr / (π R²) > 1 (the blades' planform exceeds the disc: they
  overlap) — :func:`propwhirl.model.propellers.propeller_aero.solidity`;
* a wing (or typical-section) lift-curve slope of 0 at every strip with strip aerodynamics on:
  no circulatory lift, only apparent-mass terms (switch the wing aerodynamics off instead).

Flagged, as one line each in :attr:`propwhirl.analysis.stability.ModelAnalysis.warnings`
(saved with the result, printed once by the command line as ``propwhirl: warning: ...``):

* instability events at a free-stream Mach number above :data:`MACH_COMPRESSIBLE` (0.7; the
  incompressible strip theory and the Prandtl–Glauert correction are not valid there), and
  those at Mach >= 1 (supersonic free stream);
* instability events at which a propeller with Houbolt–Reed derivatives has a helical tip
  Mach number sqrt(M² + (ΩR/a)²) above :data:`TIP_MACH` (1: the blade tips are supersonic and
  the derivatives rest on the Rodden–Rose cut-off, not on the subsonic theory);
* an analysis that finds no instability while its range extends beyond Mach 0.7 (stability
  there is not established by these methods).

A wing with doublet-lattice aerodynamics (``aero = "dlm"``, :mod:`propwhirl.model.aerodynamics.dlm`) is
compressible (linear subsonic theory, Mach <= 0.9): with ``dlm_mach = "speed"`` its loads are
at V/a of each speed, speeds beyond Mach 0.9 are refused before any analysis
(:func:`propwhirl.model.aerodynamics.dlm.check_mach`) and the Mach 0.7 warnings above name only the
propellers' Prandtl–Glauert correction (none when no propeller has Houbolt–Reed derivatives);
with a fixed ``dlm_mach`` its loads are at that Mach at every speed, and the events at a V/a
more than :data:`DLM_MACH_MISMATCH` from it are flagged as non-matched (the first one named).

A wing with strip aerodynamics below Mach 0.7 is checked by the analysis itself
(:mod:`propwhirl.analysis.mach_check`, issue 37): each event recomputed on its Prandtl–Glauert
twin, flagged when compressibility moves it by 2 % or more.  A wing with
``compressibility = "prandtl-glauert"`` and a fixed ``strip_mach`` has its events at a V/a more
than :data:`DLM_MACH_MISMATCH` from it flagged as non-matched, as the doublet lattice's.

Free-stream Mach numbers between 1 and 5 are computed and flagged, not refused, because the
thesis itself goes there: its 0–350 m/s range at 8000 ft ends at Mach 1.06, §9.2 reports a
constant-speed whirl-flutter speed of 428 m/s (Mach 1.29) and the chapter-11 isolated
propeller is swept to 1000 m/s (Mach 3.0).  Python's :mod:`warnings` module is not used: the
warnings are part of the result (one mechanism, no stderr noise from library calls).
"""
from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from propwhirl import validate as v
from propwhirl.model.aerodynamics import compressibility as pg

#: Free-stream Mach number from which nothing is computed (hypersonic flow).
MACH_REFUSED = 5.0
#: Free-stream Mach number above which results are flagged (compressibility beyond the
#: incompressible strip theory and the Prandtl–Glauert correction).
MACH_COMPRESSIBLE = 0.7
#: Helical tip Mach number above which results are flagged (supersonic blade tips).
TIP_MACH = 1.0
#: A doublet-lattice wing with a fixed Mach (``dlm_mach``) is flagged when an event's V/a
#: differs from it by more than this (one Mach step of the tables).
DLM_MACH_MISMATCH = 0.05


def _mach(M: float) -> str:
    """A Mach number for a message: two decimals ("7.00"), 3 significant digits when huge
    (a speed of 1e300 m/s must not print a 300-digit number)."""
    return f"{M:.2f}" if abs(M) < 1e4 else f"{M:.3g}"


def check_mach(V, speed_of_sound: float) -> None:
    """Refuse airspeeds V [m/s] at a free-stream Mach number >= :data:`MACH_REFUSED`.

    >>> check_mach([100.0, 350.0], 50.0)
    Traceback (most recent call last):
    ...
    propwhirl.validate.InputError: V = 350 m/s is Mach 7.00 at a = 50 m/s: the strip and Houbolt-Reed aerodynamics are subsonic; propwhirl refuses Mach >= 5 (here V >= 250 m/s) and flags results above Mach 0.7
    """
    Va = np.atleast_1d(np.asarray(V, dtype=float))
    a = float(speed_of_sound)
    top = float(np.max(Va)) if Va.size else 0.0
    if top / a >= MACH_REFUSED:
        raise v.InputError(
            f"V = {top:g} m/s is Mach {_mach(top / a)} at a = {a:g} m/s: the strip and "
            f"Houbolt-Reed aerodynamics are subsonic; propwhirl refuses Mach >= "
            f"{MACH_REFUSED:g} (here V >= {MACH_REFUSED * a:g} m/s) and flags results above "
            f"Mach {MACH_COMPRESSIBLE:g}")


def check_propeller(n_blades: int, radius: float, blade_area: float, airspeed, mach) -> None:
    """Refuse a propeller the Houbolt–Reed strip theory cannot represent.

    Solidity σ = N_b ∫c dr / (π R²) above 1 (blade area [m²] over the disc of radius R [m]:
    the blades would overlap, while strip theory treats every blade section as isolated), and
    a free-stream Mach number (array, with the airspeeds V [m/s]) >= :data:`MACH_REFUSED`.
    """
    sigma = n_blades * blade_area / (np.pi * radius ** 2)
    if not sigma <= 1.0:
        raise v.InputError(
            f"propeller solidity N_b int(c dr)/(pi R^2) = {sigma:.4g} (n_blades = {n_blades}, "
            f"radius = {radius:g} m, blade area {blade_area:.4g} m^2) is invalid: must be <= 1 "
            "(the blades would overlap in the disc)")
    M = np.atleast_1d(np.asarray(mach, dtype=float))
    if M.size and float(np.max(M)) >= MACH_REFUSED:
        t = int(np.argmax(M))
        Va = np.broadcast_to(np.atleast_1d(np.asarray(airspeed, dtype=float)), M.shape)
        raise v.InputError(
            f"Mach {_mach(M[t])} (V = {Va[t]:g} m/s) is invalid: the Houbolt-Reed derivatives are "
            f"a subsonic method; propwhirl refuses Mach >= {MACH_REFUSED:g} and flags results "
            f"above Mach {MACH_COMPRESSIBLE:g}")


def operating_point_warnings(V, mach, advance_ratio) -> tuple[str, ...]:
    """Warnings for propeller operating points (airspeed V [m/s], free-stream Mach, advance
    ratio μ = V/(ΩR), arrays of one shape) beyond :data:`MACH_COMPRESSIBLE` or with a helical
    tip Mach number M sqrt(1 + 1/μ²) above :data:`TIP_MACH`; each names the first such V."""
    V, M, mu = (np.ravel(np.asarray(x, dtype=float)) for x in (V, mach, advance_ratio))
    out = []
    hi = np.flatnonzero(M > MACH_COMPRESSIBLE)
    if hi.size:
        t = hi[np.argmin(V[hi])]
        out.append(f"V = {V[t]:g} m/s is Mach {M[t]:.2f}{' (supersonic)' if M[t] >= 1 else ''}"
                   f": beyond Mach {MACH_COMPRESSIBLE:g} the Prandtl-Glauert correction is not "
                   "valid")
    with np.errstate(over="ignore", divide="ignore"):
        tip = M * np.sqrt(1.0 + 1.0 / mu ** 2)
    hi = np.flatnonzero(tip > TIP_MACH)
    if hi.size:
        t = hi[np.argmin(V[hi])]
        out.append(f"helical tip Mach number {tip[t]:.3g} at V = {V[t]:g} m/s: above "
                   f"{TIP_MACH:g} the blade tips are supersonic and the derivatives rest on the "
                   "Rodden-Rose cut-off, not on the subsonic theory")
    return tuple(out)


def check_lift_slope(values, name: str, instead: str) -> None:
    """Refuse strip aerodynamics whose lift-curve slope [1/rad] is 0 at every strip.

    Without circulatory lift the strip theory leaves only apparent-mass terms: no aerodynamic
    stiffness, no aerodynamic damping — not a wing in an airflow.  `instead` names the switch
    that removes the aerodynamics.
    """
    vals = np.asarray(values, dtype=float)
    if vals.size and not np.any(vals > 0):
        raise v.InputError(
            f"{name} = 0 1/rad at every strip is invalid with strip aerodynamics on: no "
            "circulatory lift, hence no aerodynamic stiffness or damping (only apparent-mass "
            f"terms); give a lift-curve slope > 0 (thin aerofoil: 2 pi) or set {instead}")


def has_aerodynamics(model) -> bool:
    """True if any aerodynamic load of `model` is on (wing, section or propeller)."""
    if getattr(model, "wing_aero", False) or getattr(model, "aero", False) is True:
        return True
    if hasattr(model, "propellers"):
        return bool(model.propeller_aero and any(getattr(i, "has_aero", i.aero)
                                                 for i in model.propellers))
    return bool(getattr(model, "propeller_aero", False))


def houbolt_reed_propellers(model) -> list[tuple[int, object]]:
    """(index, propeller) of the propellers whose loads come from the Houbolt–Reed method."""
    if hasattr(model, "propellers"):
        if not model.propeller_aero:
            return []
        return [(j, i.propeller) for j, i in enumerate(model.propellers)
                if getattr(i, "has_aero", i.aero) and (i.propeller.derivatives is None
                                                       or getattr(i, "state", "") == "feathered")]
    p = getattr(model, "propeller", None)
    if p is not None and getattr(model, "propeller_aero", False) and p.derivatives is None:
        return [(0, p)]
    return []


def tip_mach(propeller, V, speed_of_sound: float) -> np.ndarray:
    """Helical tip Mach number sqrt(V² + (ΩR)²)/a of `propeller` at airspeeds V [m/s]."""
    Va = np.asarray(V, dtype=float)
    omega_r = propeller.rotational_speed(Va) * propeller.radius
    return np.hypot(Va, omega_r) / float(speed_of_sound)


def analysis_warnings(model, speed_range: tuple[float, float],
                      events: Sequence[tuple[float, str]], unstable: bool) -> tuple[str, ...]:
    """The validity warnings of an analysis (one line each, see the module docstring).

    speed_range: (first, last) analysed airspeed [m/s]; events: (V [m/s], description) of
    every instability event, description e.g. "flutter onset of backward"; unstable: whether
    any event makes the system unstable.
    """
    if not has_aerodynamics(model):
        return ()
    a = float(model.flight.speed_of_sound)
    out = []
    ev = sorted(events)
    dlm = _dlm_wing(model)
    strip = (getattr(model, "wing_aero", False) or getattr(model, "aero", False) is True) \
        and dlm is None
    high = [(V, d) for V, d in ev if V / a > MACH_COMPRESSIBLE]
    wing = getattr(model, "wing", None)
    strip_name = ("the Prandtl-Glauert strip aerodynamics" if pg.is_compressible(wing)
                  else "the incompressible strip aerodynamics")
    what = [w for w, on in ((strip_name, strip),
                            ("the Prandtl-Glauert correction of the propeller derivatives",
                             bool(houbolt_reed_propellers(model)))) if on]
    if not what and dlm is None:
        what = ["the aerodynamics"]
    if high and what:
        V0, d0 = high[0]
        sup = [V for V, _ in high if V / a >= 1.0]
        n = len(high) - 1
        more = f" ({n} more event{'s' if n > 1 else ''} above it)" if n else ""
        tail = (f"; {len(sup)} at Mach >= 1 (supersonic free stream, from V = {sup[0]:.2f} m/s)"
                if sup else "")
        out.append(
            f"V = {V0:.2f} m/s ({d0}) is Mach {V0 / a:.2f}{more}{tail}: beyond Mach "
            f"{MACH_COMPRESSIBLE:g} {' and '.join(what)} {'is' if len(what) == 1 else 'are'} "
            "not valid")
    tips: dict[str, list[int]] = {}       # one line per text, listing its propellers
    for j, p in houbolt_reed_propellers(model):
        installs = getattr(model, "propellers", ())
        if installs and not getattr(installs[j], "spinning", True):
            continue                      # a feathered rotor: its tips move with the free stream
        hits = [(V, d, float(tip_mach(p, V, a))) for V, d in ev]
        hits = [h for h in hits if h[2] > TIP_MACH]
        if hits:
            V0, d0, mt = hits[0]
            n = len(hits) - 1
            more = f" ({n} more event{'s' if n > 1 else ''} above it)" if n else ""
            tips.setdefault(
                f"helical tip Mach number {mt:.2f} at V = {V0:.2f} m/s "
                f"({d0}){more}: above {TIP_MACH:g} the blade tips are supersonic and the "
                "Houbolt-Reed derivatives rest on the Rodden-Rose cut-off, not on the "
                "subsonic theory", []).append(j + 1)
    for text, numbers in tips.items():
        who = (f"propeller {numbers[0]}" if len(numbers) == 1
               else "propellers " + ", ".join(str(k) for k in numbers))
        out.append(f"{who}: {text}")
    far = [] if dlm is None or dlm == "speed" else [
        (V, d) for V, d in ev if abs(V / a - dlm) > DLM_MACH_MISMATCH]
    if far:
        V0, d0 = far[0]
        n = len(far) - 1
        more = f" ({n} more such event{'s' if n > 1 else ''} above it)" if n else ""
        out.append(
            f"V = {V0:.2f} m/s ({d0}) is Mach {V0 / a:.2f}{more}, but the doublet-lattice "
            f"wing's loads are at the fixed Mach {dlm:g} (dlm_mach) at every speed: a "
            f"non-matched analysis (the compressibility of the wing's loads is Mach {dlm:g}'s); "
            "set dlm_mach = \"speed\" for V/a")
    fixed = getattr(wing, "strip_mach", pg.MATCHED)
    far = [] if not (strip and pg.is_compressible(wing)) or isinstance(fixed, str) else [
        (V, d) for V, d in ev if abs(V / a - float(fixed)) > DLM_MACH_MISMATCH]
    if far:
        V0, d0 = far[0]
        n = len(far) - 1
        more = f" ({n} more such event{'s' if n > 1 else ''} above it)" if n else ""
        out.append(
            f"V = {V0:.2f} m/s ({d0}) is Mach {V0 / a:.2f}{more}, but the wing's "
            f"Prandtl-Glauert strips are at the fixed Mach {float(fixed):g} (strip_mach) at "
            "every speed: a non-matched analysis; set strip_mach = \"speed\" for V/a")
    last = float(speed_range[1])
    if not unstable and last / a > MACH_COMPRESSIBLE and what:
        which = ("the subsonic aerodynamics are" if dlm is None else   # a DLM wing: the rest
                 f"{' and '.join(what)} {'is' if len(what) == 1 else 'are'}")
        out.append(
            f"no instability up to V = {last:g} m/s, but above V = "
            f"{MACH_COMPRESSIBLE * a:.2f} m/s (Mach {MACH_COMPRESSIBLE:g}) {which} not valid: "
            "stability there is not established")
    return tuple(out)


def _dlm_wing(model):
    """The ``dlm_mach`` of ``model``'s wing (or modal model's: its own ``aero`` and
    ``dlm_mach``) ("speed" or a number) when it has doublet-lattice aerodynamics on, else
    None."""
    wing = getattr(model, "wing", model)
    if not getattr(model, "wing_aero", False) or getattr(wing, "aero", "strip") != "dlm":
        return None
    m = getattr(wing, "dlm_mach", "speed")
    return m if isinstance(m, str) else float(m)
