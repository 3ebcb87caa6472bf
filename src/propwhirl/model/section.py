"""The typical section: the 2-DOF pitch–plunge aerofoil on springs with the wing's strip
aerodynamics (§7.2, §7.5; the generated `typical_section` and `strip_aero` modules)."""
from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import Literal

import numpy as np

from propwhirl import validate as v
from propwhirl.generated import strip_aero, typical_section
from propwhirl.model.aerodynamics import validity
from propwhirl.model.protocol import COMMANDS, REASONS, Capabilities
from propwhirl.model.structure.assembly import LAG_STATES, STRIP_AERO, call_blocks
from propwhirl.model.base import StateSpaceModel
from propwhirl.model.fields import check_fields, spec
from propwhirl.model.flight import FlightCondition
from propwhirl.model.protocol import DofMap
from propwhirl.model.statespace import SecondOrder


@dataclass(frozen=True)
class TypicalSection(StateSpaceModel):
    """The 2-DOF pitch–plunge aerofoil on springs with the wing's strip aerodynamics.

    Per unit span, SI units; lengths in semichords b where stated.

    Parameters
    ----------
    b : float
        Semichord [m].
    a : float
        Elastic axis [semichords aft of mid-chord], in [−1, 1].
    x_alpha : float
        Centre of gravity aft of the elastic axis [semichords].
    r_alpha : float
        Radius of gyration about the elastic axis [semichords], > |x_alpha|.
    m : float
        Mass per unit span [kg/m].
    omega_h, omega_alpha : float
        Uncoupled plunge and pitch frequencies [rad/s].
    flight : FlightCondition
        Density [kg/m³] and speed of sound [m/s].
    Cla : float
        Lift-curve slope C_lα [1/rad] (default 2π).
    ac : float
        Aerodynamic centre [semichords from mid-chord] (default −1/2: quarter chord).
    aero_model : {"leishman-nguyen", "wagner"}
        Unsteady strip aerodynamics: 2 or 4 lag states.
    name : str
        Label.
    aero : bool
        Strip aerodynamics on (False: the structural system alone, no lag states).

    Examples
    --------
    A section of mass ratio m/(πρb²) = 20 with ω_h/ω_α = 0.4 flutters at U/(bω_α) = 2.2:

    >>> import math
    >>> from propwhirl.model import FlightCondition, TypicalSection
    >>> s = TypicalSection(b=1.0, a=-0.2, x_alpha=0.1, r_alpha=0.5, m=20 * math.pi * 1.225,
    ...                    omega_h=4.0, omega_alpha=10.0, flight=FlightCondition(1.225))
    >>> s.dof_map().state_labels
    ('h', 'alpha', 'd/dt h', 'd/dt alpha', 'w1', 'w2')
    >>> from propwhirl.analysis import analyse
    >>> c = analyse(s, speeds=[5.0, 10.0, 15.0, 20.0, 25.0, 30.0]).critical
    >>> c.kind, c.label, round(c.V, 1), round(c.frequency_hz, 2)
    ('flutter', 'pitch', 22.0, 1.03)
    """

    # Not saved in model files (key None): the specs declare the ranges checked on construction.
    b: float = field(metadata=spec(None, "m", "semichord", range=(5e-4, 50.0)))
    a: float = field(metadata=spec(None, "", "elastic axis, semichords aft of mid-chord",
                                   range=(-1.0, 1.0)))
    x_alpha: float = field(metadata=spec(None, "", "centre of gravity aft of the elastic axis, "
                                         "semichords", range=(-2.0, 2.0)))
    r_alpha: float = field(metadata=spec(None, "", "radius of gyration about the elastic axis, "
                                         "semichords", range=(1e-3, 10.0)))
    m: float = field(metadata=spec(None, "kg/m", "mass per unit span", range=(1e-4, 1e5)))
    omega_h: float = field(metadata=spec(None, "rad/s", "uncoupled plunge frequency",
                                         range=(1e-3, 1e4)))
    omega_alpha: float = field(metadata=spec(None, "rad/s", "uncoupled pitch frequency",
                                             range=(1e-3, 1e4)))
    flight: FlightCondition = field(metadata=spec(None, "", "the flight condition"))
    Cla: float = field(default=2 * np.pi, metadata=spec(
        None, "1/rad", "lift-curve slope", default="physical", range=(0.0, 4.0 * np.pi),
        ends="(]"))
    ac: float = field(default=-0.5, metadata=spec(
        None, "", "aerodynamic centre, semichords from mid-chord", default="physical",
        range=(-1.0, 1.0)))
    aero_model: Literal["leishman-nguyen", "wagner"] = field(default="leishman-nguyen",
                                                             metadata=spec(
        None, "", "unsteady strip aerodynamics", default="setting"))
    name: str = field(default="typical section", metadata=spec(None, "", "label",
                                                               default="setting"))
    #: strip aerodynamics on (False: the structural system alone, no lag states)
    aero: bool = field(default=True, metadata=spec(None, "", "strip aerodynamics on",
                                                   default="setting"))

    def __post_init__(self) -> None:
        check_fields(self)  # types and the declared ranges of every field
        if self.r_alpha**2 <= self.x_alpha**2:
            raise v.InputError(
                f"r_alpha = {self.r_alpha!r} is invalid: must exceed |x_alpha| = {abs(self.x_alpha)!r}"
                " (inertia about the elastic axis includes the centre-of-gravity offset)"
            )
        if self.aero_model not in LAG_STATES:
            raise v.InputError(f"aero_model = {self.aero_model!r} is invalid: must be one of {tuple(LAG_STATES)}")

    def with_(self, **changes) -> "TypicalSection":
        return replace(self, **changes)

    def second_order(self, V) -> SecondOrder:
        """S1 q̈ + S2 q̇ + S3 q = S4 w of the section at airspeeds V [m/s] (array); checks as
        :meth:`PropellerWing.second_order`."""
        V = np.atleast_1d(v.positive("airspeed V", V, "m/s"))
        if self.aero:
            validity.check_mach(V, self.flight.speed_of_sound)
            validity.check_lift_slope(np.array([self.Cla]), "Cla", "aero = False")
        with np.errstate(all="ignore"):
            sys = self._assemble(V)
        return self._checked(sys, V, {})

    def _assemble(self, V: np.ndarray) -> SecondOrder:
        nV = V.shape[0]
        S = self.m * self.x_alpha * self.b
        I = self.m * (self.r_alpha * self.b) ** 2
        structure = typical_section.blocks(
            m=self.m, S=S, I_alpha=I, K_h=self.m * self.omega_h**2, K_alpha=I * self.omega_alpha**2
        )
        Ms, Ks = structure["mass"], structure["stiffness"]
        if not self.aero:
            Ms, Ks = np.broadcast_to(Ms, (nV, 2, 2)), np.broadcast_to(Ks, (nV, 2, 2))
            return SecondOrder(Ms, np.zeros((nV, 2, 2)), Ks, np.zeros((nV, 2, 0)),
                               np.zeros((nV, 0, 0)), np.zeros((nV, 0, 2)), np.zeros((nV, 0, 2)),
                               ("h", "alpha"), ())
        values = dict(rho=self.flight.density, V=V, b=self.b, a=self.a, Cla=self.Cla, ac=self.ac)
        group, roles = STRIP_AERO[self.aero_model]
        get = call_blocks(strip_aero, group, (nV,), **values).__getitem__
        Ma, Ca, Ka, W0, Ww, Wq = (get(roles[r]) for r in ("M", "C", "K", "W0", "Ww", "Wq"))
        Wv = get(roles["Wv"]) if "Wv" in roles else np.zeros_like(Wq)
        k = LAG_STATES[self.aero_model]
        return SecondOrder(Ms - Ma, -Ca, Ks - Ka, W0, Ww, Wv, Wq, ("h", "alpha"),
                           tuple(f"w{j + 1}" for j in range(k)))

    def without_aerodynamics(self) -> "TypicalSection":
        """The same section with its strip aerodynamics off (no lag states)."""
        return replace(self, aero=False)

    def capabilities(self) -> Capabilities:
        """What this model can do (:class:`~propwhirl.model.protocol.Capabilities`): the
        Python API's analysis, dense or p-k (with its aerodynamics on); no model file holds a
        typical section, so no command runs it."""
        why = {f: REASONS["section-file"] for f in COMMANDS if f != "analyse"}
        why["analyse"] = REASONS["section-file"]
        why["reduced"] = REASONS["section-reduced"]
        why["sensitivity"] = why["exact-sensitivity"] = REASONS["section-file"]
        if not self.aero:
            why["pk"] = REASONS["no-wing-aero-pk"]
        return Capabilities("typical section", "section", "strip" if self.aero else "none",
                            "none", "none", tuple(why.items()))

    def dof_map(self) -> DofMap:
        """Plunge h [m] and pitch α [rad] (and rates), then the lag states w1…wk."""
        k = LAG_STATES[self.aero_model] if self.aero else 0
        return DofMap(("h", "alpha"), ("plunge", "pitch"), (-1, -1), (-1, -1),
                      tuple(f"w{j + 1}" for j in range(k)), (-1,) * k)
