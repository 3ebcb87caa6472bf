"""The margin of an analysis to a required speed factor · V_D: the one place that decides it.

The requirement of CS/FAR 25.629 (factor 1.15) and 14 CFR 23.629 (factor 1.2): no aeroelastic
instability at speeds up to the required speed ``factor · V_D``
(:func:`propwhirl.certification.required_speed`, the one definition, checks V_D and the
factor); :func:`speed_margin` gives the critical instability's margin V_crit − factor · V_D
[m/s] and V_crit / (factor · V_D) − 1, and the least damping g = 2ζ of the oscillatory modes
(those with an event and the :data:`DAMPING_MODES` of lowest frequency) at the sweep's speeds
up to the required speed, with its mode and speed.

Used by ``propwhirl analyse --vd``, :func:`propwhirl.studies.clearance.clearance` and the
campaign (:mod:`propwhirl.studies.campaign`), so all three give the same numbers.
"""
from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from propwhirl import certification
from propwhirl.certification import (  # noqa: F401 (re-exported: their old home)
    FACTOR_CFR23, FACTOR_CS25, FACTOR_RANGE)
from propwhirl import validate as v
from propwhirl.analysis.damping_requirement import judged_damping

#: The damping results consider the modes with an event and this many oscillatory modes of
#: lowest frequency (:meth:`propwhirl.analysis.stability.ModelAnalysis.modes_of_interest`).
DAMPING_MODES = 8


def required_speed(V_D: Any, factor: Any = FACTOR_CS25, *, vd_name: str = "V_D",
                   factor_name: str = "factor") -> float:
    """factor · V_D [m/s]: the speed of :func:`propwhirl.certification.required_speed` (the
    one definition, which checks V_D > 0 and the factor in :data:`FACTOR_RANGE` and also
    gives its rule) without the rule, as this name has always returned it.

    >>> required_speed(100.0, 1.2)
    120.0
    """
    return certification.required_speed(V_D, factor, vd_name=vd_name,
                                         factor_name=factor_name)[0]


def oscillatory_damping(sweep: Any, modes: Sequence[int]) -> tuple[np.ndarray, np.ndarray]:
    """ζ (T, n) of the sweep's physical oscillatory modes among `modes` (NaN elsewhere) and
    dζ/dV [s/m]."""
    lam = np.asarray(sweep.eigenvalues)
    dlam = np.asarray(sweep.dlam_dV)
    mag = np.abs(lam)
    osc = np.asarray(sweep.physical, dtype=bool) & (lam.imag > 1e-9 * np.maximum(mag, 1.0))
    with np.errstate(invalid="ignore", divide="ignore"):
        zeta = -lam.real / mag
        dmag = (lam.real * dlam.real + lam.imag * dlam.imag) / mag
        dzeta = -(dlam.real * mag - lam.real * dmag) / mag**2
    keep = np.zeros(lam.shape[1], dtype=bool)
    keep[list(modes)] = True
    osc &= keep[None, :]
    zeta = np.where(osc, zeta, np.nan)
    return zeta, np.where(osc, dzeta, np.nan)


def least_damping(zeta: np.ndarray, V: np.ndarray, top: float,
                  labels: Sequence[str]) -> dict[str, Any]:
    """The least ζ at the sweep's speeds V <= top [m/s]: {zeta, V, mode} (None when none)."""
    rows = V <= top * (1 + 1e-12)
    z = np.where(rows[:, None], zeta, np.nan)
    if not np.isfinite(z).any():
        return {"zeta": None, "V": None, "mode": ""}
    t, k = np.unravel_index(np.nanargmin(z), z.shape)
    return {"zeta": float(z[t, k]), "V": float(V[t]), "mode": labels[k]}


@dataclass(frozen=True)
class SpeedMargin:
    """An analysis's margin to factor · V_D (module docstring): speeds [m/s]; margin [-]
    (V_crit / V_required − 1); least_g = 2ζ [-] and its speed [m/s]; None where there is none
    (no instability in the analysed range, no oscillatory mode below the required speed)."""

    V_D: float
    factor: float
    V_required: float
    analysed_to: float
    critical: str
    critical_speed: float | None
    least_g: float | None
    least_g_V: float | None
    least_g_mode: str
    #: the first analysed speed [m/s] and the least aerodynamic increment of g above each
    #: mode's damping there (:func:`propwhirl.analysis.damping_requirement.judged_damping`),
    #: its speed [m/s] and mode (issue 35 item 2: which damping the line reads)
    first_V: float | None = None
    aero_g: float | None = None
    aero_g_V: float | None = None
    aero_g_mode: str = ""

    @property
    def margin_m_per_s(self) -> float | None:
        """V_crit − factor · V_D [m/s]."""
        return None if self.critical_speed is None else self.critical_speed - self.V_required

    @property
    def margin(self) -> float | None:
        """V_crit / (factor · V_D) − 1 [-]."""
        return None if self.critical_speed is None else self.critical_speed / self.V_required - 1.0

    def format(self) -> str:
        """One line: the required speed, the critical instability's margin, the least damping
        (text where there is none, never NaN)."""
        head = (f"margin to {self.factor:g} V_D = {self.factor:g} x {self.V_D:g} = "
                f"{self.V_required:.2f} m/s: ")
        if self.critical_speed is None:
            crit = (f"no instability up to {self.analysed_to:.2f} m/s (none in the analysed "
                    f"range), margin > {self.analysed_to - self.V_required:+.2f} m/s")
        else:
            crit = (f"{self.critical} at {self.critical_speed:.2f} m/s, margin "
                    f"{self.margin_m_per_s:+.2f} m/s ({100 * self.margin:+.1f} %)")
        start = "" if self.first_V is None else (f" from {self.first_V:.2f} m/s (the first "
                                                  "analysed speed)")
        if self.least_g is None:
            least = "no oscillatory mode below it"
        else:
            least = (f"least total damping (structural included){start} to it g = 2 zeta = "
                     f"{self.least_g:.4f} ({self.least_g_mode} at {self.least_g_V:.2f} m/s)")
            if self.aero_g is not None:
                least += (f"; its aerodynamic increment above each mode's damping at "
                          f"{self.first_V:.2f} m/s: least {self.aero_g:+.4f} "
                          f"({self.aero_g_mode}, {self.aero_g_V:.2f} m/s)")
        return head + crit + "; " + least


def speed_margin(a: Any, V_D: float, factor: float = FACTOR_CS25, critical: Any = "default",
                 describe=str) -> SpeedMargin:
    """The margin of analysis `a` (:class:`propwhirl.analysis.stability.ModelAnalysis`) to
    ``factor · V_D`` [m/s] (module docstring).  `critical`: the critical instability (default
    ``a.critical``, the one definition; None: none); `describe` names a mode label."""
    V_req = required_speed(V_D, factor)
    crit = a.critical if isinstance(critical, str) and critical == "default" else critical
    sweep = a.sweep
    V = np.asarray(sweep.V, dtype=float)
    labels = tuple(sweep.mode_labels)
    zeta, _ = oscillatory_damping(sweep, a.modes_of_interest(DAMPING_MODES))
    least = least_damping(zeta, V, V_req, labels)
    aero = judged_damping(V, zeta, np.isfinite(zeta), labels, (), V_req, "aerodynamic")
    return SpeedMargin(
        float(V_D), float(factor), V_req, float(V[-1]),
        "" if crit is None else f"{crit.kind} ({crit.event}) of {describe(crit.label)}",
        None if crit is None else float(crit.V),
        None if least["zeta"] is None else 2.0 * least["zeta"], least["V"], least["mode"],
        float(V[0]), aero["g"], aero["V"], aero["mode"])
