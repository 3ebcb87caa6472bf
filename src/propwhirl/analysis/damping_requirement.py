"""A damping requirement read as the campaign says (issue 35, item 2): which damping, above which
speed, of which modes.

"g = 2ζ ≥ 0.03" has two common readings, and they decide different things:

* ``applies_to="total"``: the damping of the aeroelastic system, structural damping included
  (g = 2ζ of the tracked mode, as the V-g-f draws it).  A model whose mounts have g = 0.02 of
  structural damping fails g ≥ 0.03 at the first speed analysed, before the air does anything;
* ``applies_to="aerodynamic"``: the increment the air adds above the structural damping (the
  NASTRAN V-g reading, whose g is the damping the structure would need), here
  g_aero(V) = 2 (ζ(V) − ζ(V_0)) of each mode, ζ(V_0) its damping at the lowest analysed speed
  V_0 (the structural damping, with the small aerodynamic part at V_0 in it: the analysis has
  no speed 0).

Either is judged at the analysed speeds from ``above_m_per_s`` up to V_D, on ``modes="all"``
(every oscillatory mode of interest: those with an event and the
:data:`~propwhirl.analysis.margin.DAMPING_MODES` of lowest frequency) or ``modes="critical"``
(those with an instability in the analysed range, MIL-A-8870C's "critical flutter mode").
``source`` names where the reading comes from (MIL-A-8870C 3.1.1, company practice, ...): the
report prints it beside the requirement.
"""
from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from propwhirl import validate as v
from propwhirl.certification import DAMPING_APPLIES_TO as APPLIES_TO
from propwhirl.certification import DAMPING_MODES as MODES


@dataclass(frozen=True)
class DampingRequirement:
    """g ≥ `g_min` [-] (g = 2ζ) of `applies_to` damping at the analysed speeds from
    `above_m_per_s` [m/s] to V_D, on `modes` (module docstring); `source`: where the reading
    comes from ("" when not said).

    Examples
    --------
    >>> r = DampingRequirement(0.03, "aerodynamic", 20.0, "all", "MIL-A-8870C 3.1.1")
    >>> r.describe()
    'g = 2ζ ≥ 0.03 [-] of the aerodynamic increment (above the damping at the lowest analysed speed) of every oscillatory mode of interest, from 20 m/s to V_D (MIL-A-8870C 3.1.1)'
    """

    g_min: float
    applies_to: str = "total"
    above_m_per_s: float = 0.0
    modes: str = "all"
    source: str = ""

    def __post_init__(self) -> None:
        v.in_range("min_damping_g", self.g_min, 0.0, 1.0)
        for key, choices in (("applies_to", APPLIES_TO), ("modes", MODES)):
            if getattr(self, key) not in choices:
                raise v.fail(key, getattr(self, key), f"invalid: must be one of "
                             f"{', '.join(choices)}")
        v.in_range("above_m_per_s", self.above_m_per_s, 0.0, 1000.0)
        if not isinstance(self.source, str):
            raise v.fail("source", self.source, "invalid: must be a str")

    def describe(self) -> str:
        """The requirement in words (the report's and the summary's)."""
        what = ("of the total damping (structural damping included)" if self.applies_to == "total"
                else "of the aerodynamic increment (above the damping at the lowest analysed "
                "speed)")
        modes = ("of every oscillatory mode of interest" if self.modes == "all" else
                 "of the modes with an instability in the analysed range")
        speeds = (f"from {self.above_m_per_s:g} m/s to V_D" if self.above_m_per_s > 0 else
                  "at every analysed speed up to V_D")
        source = f" ({self.source})" if self.source else " (its source not given)"
        return f"g = 2ζ ≥ {self.g_min:g} [-] {what} {modes}, {speeds}{source}"

    def to_dict(self) -> dict[str, Any]:
        return {"min_damping_g": self.g_min, "applies_to": self.applies_to,
                "above_m_per_s": self.above_m_per_s, "modes": self.modes, "source": self.source}


def judged_damping(V: np.ndarray, zeta: np.ndarray, oscillatory: np.ndarray,
                   labels: Sequence[str], unstable: Sequence[str], top: float,
                   applies_to: str = "total", above: float = 0.0,
                   modes: str = "all") -> dict[str, Any]:
    """The least judged g = 2ζ [-] at the speeds V (T,) [m/s] in [`above`, `top`], of the
    modes `labels` (n) whose ζ (T, n) is defined where `oscillatory` (T, n): {g, V [m/s],
    mode}, None and "" when no mode is judged there.  `applies_to`: "total" (2ζ) or
    "aerodynamic" (2 (ζ − ζ at the mode's first oscillatory speed)); `modes`: "all" or
    "critical" (those named in `unstable`)."""
    V = np.asarray(V, dtype=float)
    osc = np.asarray(oscillatory, dtype=bool)
    z = np.where(osc, np.asarray(zeta, dtype=float), np.nan)
    if applies_to == "aerodynamic":
        first = np.argmax(osc, axis=0)                       # each mode's first oscillatory row
        z0 = np.where(osc.any(axis=0), z[first, np.arange(z.shape[1])], np.nan)
        z = z - z0[None, :]
    rows = (V >= above * (1 - 1e-12)) & (V <= top * (1 + 1e-12))
    cols = np.ones(z.shape[1], dtype=bool) if modes == "all" else np.isin(list(labels),
                                                                          list(unstable))
    z = np.where(rows[:, None] & cols[None, :], z, np.nan)
    if not np.isfinite(z).any():
        return {"g": None, "V": None, "mode": ""}
    t, k = np.unravel_index(np.nanargmin(z), z.shape)
    return {"g": 2.0 * float(z[t, k]), "V": float(V[t]), "mode": labels[k]}
