"""Compressibility of the strip aerodynamics: the Prandtl–Glauert lift-curve slope (issue 37,
item 5).

The wing's strips (Theodorsen, Wagner, Leishman–Nguyen; thesis §7.2, §7.5) are incompressible.
With ``compressibility = "prandtl-glauert"`` on a :class:`~propwhirl.model.structure.wing.Wing`
every strip's lift-curve slope is divided by β = √(1 − M²), the Prandtl–Glauert factor of
linear subsonic flow:

    C_lα(M) = C_lα / β,        β = √(1 − M²)

in Yates' modified strip analysis (7.64–7.66; ``derivations/strip_aero.py``), which takes the
section's steady lift slope and aerodynamic centre from a steady theory — here Prandtl–Glauert's
(Yates 1966, "Modified-strip-analysis method for predicting wing flutter at subsonic to
hypersonic speeds", J. Aircraft 3(1)).  The slope is a symbol of the derivation (``Cla``), so the
factor enters where the generated functions take it: every circulatory load and the downwash
point b d, d = C_lα/(2π) + a_c − a (7.66), follow from the derivation; the apparent-mass terms do
not change.  The steady (k → 0) lift and moment scale by 1/β exactly
(``tests/model/test_strip_compressibility.py``); the unsteady lag (Wagner's function) stays
incompressible.

The Mach number M is the wing's ``strip_mach``, the same notion as its doublet lattice's
``dlm_mach``: "speed" (the default; matched, V/a at each analysed speed) or one number in
[0, :data:`MACH_MAX`] for every speed (non-matched).  A matched speed beyond Mach
:data:`MACH_MAX` is refused in one line (β → 0 at Mach 1: the theory's singularity).  With the
default ``compressibility = "none"`` nothing changes (the thesis's model): :func:`lift_slope_factor`
returns None and the strips' arguments are the wing's own.

What it cannot do: a three-dimensional effect that grows with Mach (the doublet lattice's whirl
hump on the wingtip model, docs/validation.md, "Why the 6 Hz whirl drops: compressibility") is
not the section's; the strips with 2π/β capture the section's part only.
"""
from __future__ import annotations

import numpy as np

from propwhirl import validate as v

#: the incompressible strips (the thesis's, the default)
NONE = "none"
#: the Prandtl–Glauert lift-curve slope C_lα / √(1 − M²)
PRANDTL_GLAUERT = "prandtl-glauert"
#: the values of a wing's ``compressibility``
COMPRESSIBILITY = (NONE, PRANDTL_GLAUERT)
#: the ``strip_mach`` of a Mach V / a at each analysed speed (as ``dlm_mach``)
MATCHED = "speed"
#: highest Mach number of the Prandtl–Glauert strips (the doublet lattice's limit too)
MACH_MAX = 0.9


def beta(mach) -> np.ndarray:
    """The Prandtl–Glauert factor β = √(1 − M²) [-] of Mach numbers ``mach`` in [0, 1)."""
    M = np.asarray(mach, dtype=float)
    return np.sqrt(1.0 - M * M)


def is_compressible(wing) -> bool:
    """Whether ``wing``'s strips carry the Prandtl–Glauert slope (its ``compressibility``)."""
    return getattr(wing, "compressibility", NONE) == PRANDTL_GLAUERT


def strip_mach(wing, V, speed_of_sound: float) -> np.ndarray:
    """The Mach number [-] of ``wing``'s strip loads at the airspeeds V [m/s] (its fixed
    ``strip_mach``, or V/a with ``strip_mach = "speed"``); InputError (one line) for a matched
    Mach beyond :data:`MACH_MAX`."""
    Va = np.atleast_1d(np.asarray(V, dtype=float))
    m = getattr(wing, "strip_mach", MATCHED)
    if not isinstance(m, str):
        return np.full(Va.shape, float(m))
    M = Va / float(speed_of_sound)
    if Va.size and float(np.max(M)) > MACH_MAX:
        i = int(np.argmax(M))
        raise v.InputError(
            f"V = {Va[i]:g} m/s is Mach {M[i]:.3f} at a = {float(speed_of_sound):g} m/s: the "
            f"Prandtl-Glauert strips (compressibility = \"{PRANDTL_GLAUERT}\", strip_mach = "
            f"\"{MATCHED}\") stop at Mach {MACH_MAX:g} (here V <= "
            f"{MACH_MAX * float(speed_of_sound):.2f} m/s); analyse lower speeds, give a fixed "
            "strip_mach, or set compressibility = \"none\"")
    return M


def lift_slope_factor(wing, V, speed_of_sound: float) -> np.ndarray | None:
    """1/β [-] of ``wing``'s strips at each airspeed V [m/s] (shape of ``np.atleast_1d(V)``), or
    None with ``compressibility = "none"`` (the strips take the wing's own slopes, unchanged)."""
    if not is_compressible(wing):
        return None
    return 1.0 / beta(strip_mach(wing, V, speed_of_sound))


def lift_slopes(cla: np.ndarray, factor: np.ndarray | None) -> np.ndarray:
    """The strips' lift-curve slopes [1/rad] at each speed: ``cla`` (n_strips,) itself when
    ``factor`` is None, else (nV, n_strips) = factor[:, None] · cla."""
    if factor is None:
        return cla
    return np.asarray(factor, dtype=float)[:, None] * np.asarray(cla, dtype=float)[None, :]


def check_speeds(model, V) -> None:
    """InputError (one line), before any analysis, when ``model``'s wing has Prandtl–Glauert
    strips matched to V/a and one of the airspeeds V [m/s] is beyond Mach :data:`MACH_MAX`;
    nothing for any other model."""
    wing = getattr(model, "wing", None)
    if wing is None or not getattr(model, "wing_aero", False) or not is_compressible(wing) \
            or getattr(wing, "aero", "strip") != "strip":
        return
    strip_mach(wing, V, model.flight.speed_of_sound)

