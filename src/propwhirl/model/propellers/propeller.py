"""Flexibly mounted propeller (thesis chapters 6, 8, §9.2): inertia, mounts, operation, aerodynamics.

Positions along the shaft are measured from the wing mid-chord axis, positive REARWARD (thesis
Table 9.4, Figure 8.1): a tractor propeller ahead of the leading edge has negative positions.
The pitch/yaw pivots are at `pivot_pitch` (l_θ) and `pivot_yaw` (l_ψ); the propeller plane (hub)
at `hub`, so e_θ = hub − l_θ and e_ψ = hub − l_ψ (negative for a tractor, chapter 8 sign
convention; chapter 6 uses the distances −e_θ, −e_ψ).

Inertia parameters about the pivots follow from the point masses (8.5–8.6):
M_P = Σ m, S_θ,P = Σ m (x − l_θ), I_θ,P = Σ m (x − l_θ)², I_ψ,P = Σ m (x − l_ψ)², and
S_α,P, I_α,P, I_θα,P from the generated `prop_flexwing.inertia` (relative to the wing's elastic
axis at a_P b_P).  The spin inertia I_Ω is given, or M_r R²/3 with the rotor mass M_r (9.2).

Mount stiffness: K given [N m/rad], or the uncoupled frequency f [Hz] with K = I (2π f)²
(ω_θ = √(K_θ/I_θ,P), §8.1).  Structural damping (6.4–6.7): `damping="g"` reads the values as
structural damping coefficients g in the viscous-equivalent form c = K g/ω_θ (6.6 with
ω = ω_θ, i.e. ζ = g/2); `damping="zeta"` reads them as viscous damping ratios ζ
(c = 2 ζ ω_θ I).

Operation: "fixed-pitch" windmilling (advance ratio μ = V/(ΩR) fixed by the blade angle,
eq. 9.1, so Ω rises with V) or "constant-speed" (Ω fixed, μ varies with V).
"""
from __future__ import annotations

import functools
from dataclasses import dataclass, field
from typing import Callable, Literal, Mapping, Protocol

import numpy as np

from propwhirl import validate as v
from propwhirl.model.fields import Entry, check_fields, spec
from propwhirl.model.propellers.propeller_aero import (
    DERIVATIVE_NAMES,
    AdvanceRule,
    AeroSettings,
    advance_ratio_from_blade_angle,
    houbolt_reed_source,
)



#: Derivatives coupling pitch with yaw: they change sign with the sense of rotation.
CROSS_DERIVATIVES = ("CZ_psi", "CZ_r", "Cm_psi", "Cm_r", "CY_theta", "CY_q", "Cn_theta", "Cn_q")


#: The fields a Propeller must be given (no default stands for them), as a model file must:
#: field → None (always) or the condition of :data:`propwhirl.model.fields.REQUIRED_WHEN`
#: ("houbolt-reed": derivatives from the blades, derivatives=None; "fixed-pitch").
REQUIRED: dict[str, str | None] = {
    "pivot_pitch": None, "pivot_yaw": None, "rotation": None,
    "n_blades": "houbolt-reed", "hub_radius": "houbolt-reed", "blade_chord": "houbolt-reed",
    "beta_075_deg": "fixed-pitch", "zero_lift_angle_deg": "fixed-pitch",
}
_REQUIRED_DOC = {
    "pivot_pitch": "pitch pivot position l_theta [m], aft of the wing mid-chord",
    "pivot_yaw": "yaw pivot position l_psi [m], aft of the wing mid-chord",
    "rotation": "+1 counter-clockwise seen from the front, -1 clockwise",
    "n_blades": "number of blades, for Houbolt-Reed derivatives (derivatives = None)",
    "hub_radius": "hub radius r0 [m], for Houbolt-Reed derivatives (derivatives = None)",
    "blade_chord": "blade chord [m], for Houbolt-Reed derivatives (derivatives = None)",
    "beta_075_deg": "blade angle at 0.75 R [deg], for operation = 'fixed-pitch' (the default)",
    "zero_lift_angle_deg": "blade-section zero-lift angle [deg], for operation = 'fixed-pitch' "
                           "(the default)",
}


class DerivativeSource(Protocol):
    """Gives the 16 propeller aerodynamic derivatives (4.25) at airspeeds V [m/s] and
    rotational speeds Ω [rad/s] (arrays of equal shape), for a propeller of radius R [m]."""

    def __call__(self, V: np.ndarray, Omega: np.ndarray, speed_of_sound: float) -> dict[str, np.ndarray]: ...


@dataclass(frozen=True)
class MeasuredDerivatives:
    """User-supplied derivatives (any subset of the 16; the rest are zero), constant in V.

    Example: Bennett & Bland's measured set (§6.2, §8.4).  Keys are DERIVATIVE_NAMES.

    Parameters
    ----------
    values : mapping of str to float
        The dimensionless derivatives of eq. 4.25 [-] by name (``"CZ_theta"``, ``"Cm_q"``, ...,
        :data:`DERIVATIVE_NAMES`), any subset; the rest are zero.

    Examples
    --------
    >>> import numpy as np
    >>> from propwhirl.model import MeasuredDerivatives
    >>> d = MeasuredDerivatives({"CZ_theta": -0.2, "CY_psi": 0.2})
    >>> out = d(np.array([50.0, 100.0]), np.array([150.0, 300.0]), 340.0)
    >>> out["CZ_theta"].tolist(), out["Cm_q"].tolist()
    ([-0.2, -0.2], [0.0, 0.0])
    """

    values: Mapping[str, float] = field(metadata=spec(
        "values", "", "the derivatives of eq. 4.25 (any subset; the rest are zero)",
        form="mapping", entries=tuple(Entry(k, k, "", "dimensionless derivative (eq. 4.25)",
                                            (-1e3, 1e3)) for k in DERIVATIVE_NAMES)))

    def __post_init__(self) -> None:
        check_fields(self)  # a dict of the known names, each a number in its range

    def __call__(self, V, Omega, speed_of_sound):
        V = np.asarray(V, dtype=float)
        return {k: np.full(V.shape, float(self.values.get(k, 0.0))) for k in DERIVATIVE_NAMES}


@dataclass(frozen=True)
class PointMass:
    """A concentrated mass [kg] on the propeller shaft at x [m] from the wing mid-chord, aft positive.

    Parameters
    ----------
    mass : float
        Mass [kg].
    x : float
        Position on the shaft [m], aft of the wing mid-chord (a tractor's masses are ahead: x < 0).

    Examples
    --------
    >>> from propwhirl.model import PointMass
    >>> rotor = PointMass(8.0, -1.16)
    >>> rotor.mass, rotor.x
    (8.0, -1.16)
    """

    mass: float = field(metadata=spec("mass_kg", "kg", "mass", range=(1e-4, 1e5)))
    x: float = field(metadata=spec("x_m", "m", "position on the shaft, aft of the wing mid-chord",
                                   range=(-100.0, 100.0)))

    def __post_init__(self) -> None:
        check_fields(self)


@dataclass(frozen=True)
class Propeller:
    """A flexibly mounted tractor propeller (SI units; positions aft of the wing mid-chord).

    Required, as in a model file (no default stands for a value of the aircraft; one
    InputError names every missing one, :data:`REQUIRED`): radius, rotor, pivot_pitch,
    pivot_yaw, rotation, a mount stiffness or frequency per axis; n_blades, hub_radius and
    blade_chord when the derivatives come from the blades (derivatives = None); beta_075_deg
    and zero_lift_angle_deg for fixed-pitch operation (the default).

    Parameters
    ----------
    radius : float
        Rotor radius R [m].
    rotor : PointMass
        Rotor (blades + spinner) point mass [kg] at x [m]; its position is the propeller plane
        (hub).
    masses : tuple of PointMass
        Further point masses on the shaft (motor, nacelle, ...).
    pivot_pitch, pivot_yaw : float
        Pivot positions l_θ, l_ψ [m] aft of the wing mid-chord.
    f_theta, f_psi : float, optional
        Uncoupled mount frequencies [Hz]; or give `K_theta`, `K_psi`.
    K_theta, K_psi : float, optional
        Mount stiffnesses [N m/rad]; or give `f_theta`, `f_psi`.
    damping_theta, damping_psi : float
        Mount damping values [-], read according to `damping`; 0: undamped (conservative).
    damping : {"g", "zeta"}
        "g": structural coefficients (viscous equivalent c = K g/ω, ζ = g/2); "zeta": viscous
        damping ratios.
    spin_inertia : float, optional
        Spin inertia I_Ω [kg m²]; default M_r R²/3 (eq. 9.2).
    n_blades : int, optional
        Number of blades (≥ 3: the method assumes polar symmetry).
    hub_radius : float, optional
        Hub radius r0 [m] (η0 = r0/R), < `radius`.
    blade_chord : float or callable, optional
        Blade chord [m], a number or a function of η = r/R (Houbolt–Reed input).
    operation : {"fixed-pitch", "constant-speed"}
        "fixed-pitch" (windmilling: μ from the blade angle, Ω rises with V) or
        "constant-speed" (`rpm` fixed).
    beta_075_deg, zero_lift_angle_deg : float, optional
        Blade angle at 0.75 R and blade-section zero-lift angle [deg] (fixed-pitch operation).
    advance_rule : {"thesis_eq_9_1", "blade_element"}
        "thesis_eq_9_1" (μ = tan(β + α_0L), eq. 9.1 as chapters 9–11 use it) or
        "blade_element" (zero lift at 0.75 R: μ = 0.75 tan(β − α_0L), Table 4.1).
    inertia : mapping of str to float, optional
        Measured inertia about the pivots overriding the point-mass values, any of M_P [kg],
        S_theta_P [kg m], I_theta_P, I_psi_P [kg m²] (e.g. Bennett & Bland's I_Y = I_Z); the
        point masses still place the propeller plane (the rotor's x).
    rpm : float, optional
        Rotational speed of constant-speed operation [rev/min].
    derivatives : DerivativeSource, optional
        Aerodynamic derivatives (e.g. :class:`MeasuredDerivatives`); None: Houbolt–Reed
        (:mod:`propwhirl.model.propellers.propeller_aero`) for this propeller's blades with
        `aero_settings`.
    aero_settings : AeroSettings
        Houbolt–Reed switches (wake, compressibility, aspect ratio, ...); the thesis's
        defaults.
    rotation : {1, -1}
        +1 if the rotor turns counter-clockwise seen from the front (the thesis's sense,
        Figure 6.1), −1 for clockwise: the mirror image about the vertical plane through the
        shaft (ψ → −ψ), which reverses the gyroscopic terms (Ω → −Ω) and the eight
        cross-coupling Houbolt–Reed derivatives (C_Zψ, C_Zr, C_mψ, C_mr, C_Yθ, C_Yq, C_nθ,
        C_nq); user-supplied `derivatives` are taken as given for the actual propeller.
    name : str
        Label.

    Raises
    ------
    InputError
        A missing required value, a value outside its range, or both (or neither) of a
        frequency and a stiffness of one axis.

    Examples
    --------
    The baseline propeller of Tables 9.3–9.4 (also ``propwhirl.cases.ch09_baseline.
    baseline_propeller()``): windmilling at μ = tan(35° − 3°), its mounts at 7 Hz.

    >>> from propwhirl.model import PointMass, Propeller
    >>> p = Propeller(radius=0.762, rotor=PointMass(8.0, -1.16), masses=(PointMass(35.0, -0.86),),
    ...               pivot_pitch=0.0, pivot_yaw=0.0, f_theta=7.0, f_psi=7.0, rotation=1,
    ...               n_blades=3, hub_radius=0.125, blade_chord=0.094,
    ...               beta_075_deg=35.0, zero_lift_angle_deg=-3.0)
    >>> round(p.advance_ratio, 4), round(p.I_Omega, 3)       # μ; I_Ω = M_r R²/3 [kg m²]
    (0.6249, 1.548)
    >>> [round(k) for k in p.stiffness()]                    # K_θ, K_ψ [N m/rad]
    [70899, 70899]
    >>> round(float(p.spin_rate(100.0)), 1)                  # Ω = V/(μR) [rad/s] at 100 m/s
    210.0
    """

    radius: float = field(metadata=spec("radius_m", "m", "rotor radius R", range=(1e-2, 20.0)))
    rotor: PointMass = field(metadata=spec(
        "rotor", "", "rotor (blades + spinner) point mass; its x is the propeller plane"))
    masses: tuple[PointMass, ...] = field(default=(), metadata=spec(
        "masses", "", "further point masses on the shaft (motor, nacelle, ...)",
        default="physical"))
    pivot_pitch: float | None = field(default=None, metadata=spec(
        "pivot_pitch_m", "m", "pitch pivot position l_theta", default="none",
        file_required=True, range=(-100.0, 100.0)))
    pivot_yaw: float | None = field(default=None, metadata=spec(
        "pivot_yaw_m", "m", "yaw pivot position l_psi", default="none", file_required=True,
        range=(-100.0, 100.0)))
    f_theta: float | None = field(default=None, metadata=spec(
        "f_theta_hz", "Hz", "uncoupled pitch frequency (or K_theta)", default="none",
        range=(1e-3, 1e3)))
    f_psi: float | None = field(default=None, metadata=spec(
        "f_psi_hz", "Hz", "uncoupled yaw frequency (or K_psi)", default="none",
        range=(1e-3, 1e3)))
    K_theta: float | None = field(default=None, metadata=spec(
        "K_theta_N_m_per_rad", "N m/rad", "pitch mount stiffness (or f_theta)", default="none",
        range=(1e-6, 1e12)))
    K_psi: float | None = field(default=None, metadata=spec(
        "K_psi_N_m_per_rad", "N m/rad", "yaw mount stiffness (or f_psi)", default="none",
        range=(1e-6, 1e12)))
    damping_theta: float = field(default=0.0, metadata=spec(
        "damping_theta", "", "pitch mount damping, read according to damping; omitted: "
        "undamped (conservative)", default="physical", range=(0.0, 2.0)))
    damping_psi: float = field(default=0.0, metadata=spec(
        "damping_psi", "", "yaw mount damping, read according to damping; omitted: undamped "
        "(conservative)", default="physical", range=(0.0, 2.0)))
    damping: Literal["g", "zeta"] = field(default="g", metadata=spec(
        "damping", "", "g: structural coefficients (zeta = g/2); zeta: viscous damping ratios",
        default="setting"))
    spin_inertia: float | None = field(default=None, metadata=spec(
        "spin_inertia_kg_m2", "kg m^2", "spin inertia I_Omega; omitted: M_r R^2/3 (eq. 9.2)",
        default="none", range=(0.0, 1e6)))
    n_blades: int | None = field(default=None, metadata=spec(
        "n_blades", "", "number of blades (>= 3)", default="none",
        file_required="houbolt-reed", range=(3, 20)))
    hub_radius: float | None = field(default=None, metadata=spec(
        "hub_radius_m", "m", "hub radius r0 (< radius)", default="none",
        file_required="houbolt-reed", range=(0.0, 20.0)))
    blade_chord: float | Callable[[np.ndarray], np.ndarray] | None = field(
        default=None, metadata=spec(
            "blade_chord", "m", "blade chord (Houbolt-Reed input; required when derivatives "
            "is None)", default="none", form="distribution", number_key="blade_chord_m",
            value_key="chord_m", file_required="houbolt-reed", range=(1e-3, 5.0)))
    operation: Literal["fixed-pitch", "constant-speed"] = field(default="fixed-pitch", metadata=spec(
        "operation", "", "fixed-pitch windmilling (Omega rises with V) or constant-speed (rpm)",
        default="setting"))
    beta_075_deg: float | None = field(default=None, metadata=spec(
        "beta_075_deg", "deg", "blade angle at 0.75 R", default="none",
        file_required="fixed-pitch", range=(-90.0, 90.0)))
    zero_lift_angle_deg: float | None = field(default=None, metadata=spec(
        "zero_lift_angle_deg", "deg", "blade-section zero-lift angle", default="none",
        file_required="fixed-pitch", range=(-30.0, 30.0)))
    advance_rule: AdvanceRule = field(default="thesis_eq_9_1", metadata=spec(
        "advance_rule", "", "advance ratio of fixed-pitch operation: eq. 9.1 as the thesis uses "
        "it, or zero lift at 0.75 R (Table 4.1)", default="setting"))
    inertia: Mapping[str, float] | None = field(default=None, metadata=spec(
        "inertia", "", "measured inertia about the pivots, overriding the point masses' values",
        default="none", form="mapping", entries=(
            Entry("M_P", "M_P_kg", "kg", "propeller mass M_P", (1e-4, 1e5)),
            Entry("S_theta_P", "S_theta_P_kg_m", "kg m", "static moment about the pitch pivot",
                  (-1e7, 1e7)),
            Entry("I_theta_P", "I_theta_P_kg_m2", "kg m^2", "inertia about the pitch pivot",
                  (1e-8, 1e9)),
            Entry("I_psi_P", "I_psi_P_kg_m2", "kg m^2", "inertia about the yaw pivot",
                  (1e-8, 1e9)))))
    rpm: float | None = field(default=None, metadata=spec(
        "rpm", "rev/min", "rotational speed of constant-speed operation", default="none",
        range=(1.0, 1e5)))
    derivatives: DerivativeSource | None = field(default=None, compare=False, metadata=spec(
        "derivatives", "", "aerodynamic derivative source; omitted: Houbolt-Reed for these blades "
        "with aero_settings", default="none", form="derivatives"))
    aero_settings: AeroSettings = field(default=AeroSettings(), metadata=spec(
        "aero_settings", "", "Houbolt-Reed switches", default="setting"))
    rotation: int | None = field(default=None, metadata=spec(
        "rotation", "", "+1 counter-clockwise seen from the front (the thesis's sense), -1 "
        "clockwise", default="none", file_required=True))
    name: str = field(default="propeller", metadata=spec("name", "", "label", default="setting"))

    def __post_init__(self) -> None:
        self._check_required()
        check_fields(self)  # types and the declared ranges of every field
        if self.hub_radius is not None and not self.hub_radius < self.radius:
            raise v.fail("hub_radius", self.hub_radius,
                         f"invalid: must be < radius = {self.radius!r} m", "m")
        if (self.f_theta is None) == (self.K_theta is None):
            raise v.InputError("give exactly one of f_theta [Hz] or K_theta [N m/rad]")
        if (self.f_psi is None) == (self.K_psi is None):
            raise v.InputError("give exactly one of f_psi [Hz] or K_psi [N m/rad]")
        if self.operation == "constant-speed":
            if self.rpm is None:
                raise v.InputError("rpm is required for operation = 'constant-speed'")
        else:
            if self.rpm is not None:  # windmilling: Ω = V/(μR) from the blade angle, rpm unused
                raise v.fail("rpm", self.rpm, "invalid with operation = 'fixed-pitch', which "
                             "ignores it (the windmilling rotor turns at Omega = V/(mu R), mu "
                             "from the blade angle): remove rpm or give operation = "
                             "'constant-speed'", "rev/min")
            try:
                self.advance_ratio  # validates the blade angle (inflow angle in (0°, 90°))
            except v.InputError as exc:  # restated with the field's name
                raise v.fail("beta_075_deg", self.beta_075_deg,
                             f"invalid: {str(exc).split(' is invalid: ', 1)[-1]}",
                             "deg") from None
        if self.rotation not in (1, -1):
            raise v.fail("rotation", self.rotation, "invalid: must be +1 or -1")

    def _check_required(self) -> None:
        """The values of the aircraft that no default stands for, as a model file requires
        them (:data:`REQUIRED`): one InputError naming every missing one."""
        missing = [name for name, when in REQUIRED.items()
                   if getattr(self, name) is None and (
                       when is None or (when == "houbolt-reed" and self.derivatives is None)
                       or (when == "fixed-pitch" and self.operation != "constant-speed"))]
        if missing:
            described = "; ".join(f"{n} ({_REQUIRED_DOC[n]})" for n in missing)
            raise v.InputError(f"Propeller: missing {described}: a value of the aircraft has no "
                               "default (a model file requires the same keys)")

    # ------------------------------------------------------------------ inertia (8.5–8.6)
    @property
    def all_masses(self) -> tuple[PointMass, ...]:
        return (self.rotor,) + tuple(self.masses)

    @property
    def hub(self) -> float:
        """Position of the propeller plane (the rotor mass) [m]."""
        return self.rotor.x

    @property
    def e_theta(self) -> float:
        """Pitch pivot to propeller plane, chapter-8 sign (negative for a tractor) [m]."""
        return self.hub - self.pivot_pitch

    @property
    def e_psi(self) -> float:
        return self.hub - self.pivot_yaw

    def pivot_inertia(self) -> dict[str, float]:
        """M_P [kg], S_θ,P [kg m], I_θ,P, I_ψ,P [kg m²] about the pivots (8.5–8.6)."""
        m = np.array([p.mass for p in self.all_masses])
        x = np.array([p.x for p in self.all_masses])
        out = {
            "M_P": float(m.sum()),
            "S_theta_P": float(np.sum(m * (x - self.pivot_pitch))),
            "I_theta_P": float(np.sum(m * (x - self.pivot_pitch) ** 2)),
            "I_psi_P": float(np.sum(m * (x - self.pivot_yaw) ** 2)),
        }
        out.update({k: float(val) for k, val in (self.inertia or {}).items()})
        return out

    @property
    def I_Omega(self) -> float:
        """Spin inertia I_Ω [kg m²]: given, or M_r R²/3 (9.2)."""
        if self.spin_inertia is not None:
            return float(self.spin_inertia)
        return self.rotor.mass * self.radius**2 / 3.0

    def stiffness(self) -> tuple[float, float]:
        """(K_θ, K_ψ) [N m/rad], from the frequencies with K = I (2π f)² where given."""
        inertia = self.pivot_inertia()
        Kt = self.K_theta if self.K_theta is not None else inertia["I_theta_P"] * (2 * np.pi * self.f_theta) ** 2
        Kp = self.K_psi if self.K_psi is not None else inertia["I_psi_P"] * (2 * np.pi * self.f_psi) ** 2
        return float(Kt), float(Kp)

    def viscous_damping_ratios(self) -> tuple[float, float]:
        """(ζ_θ, ζ_ψ) of the viscous-equivalent damping (6.4–6.6)."""
        if self.damping == "zeta":
            return float(self.damping_theta), float(self.damping_psi)
        return 0.5 * float(self.damping_theta), 0.5 * float(self.damping_psi)

    # ------------------------------------------------------------------ operation
    @property
    def advance_ratio(self) -> float:
        """μ = V/(ΩR) of fixed-pitch windmilling from the blade angle (J = πμ).

        "thesis_eq_9_1": tan(β_0.75 + α_0L) — eq. 9.1 as printed and used in chapters 9–11
        (J = π tan(β − 3°) = 1.96 at 35°, Table 9.3; 221 m/s at 4433 RPM, Table 9.5);
        "blade_element": 0.75 tan(β_0.75 − α_0L), zero lift at 0.75 R (Table 4.1).
        """
        return self._advance_ratio

    @functools.cached_property
    def _advance_ratio(self) -> float:
        """:attr:`advance_ratio`, computed once per propeller (it is immutable; every
        evaluation of a windmilling propeller's blocks asks for it)."""
        return float(advance_ratio_from_blade_angle(
            np.radians(self.beta_075_deg), np.radians(self.zero_lift_angle_deg), self.advance_rule))

    def rotational_speed(self, V: np.ndarray) -> np.ndarray:
        """Ω [rad/s] at airspeeds V [m/s]."""
        V = np.asarray(V, dtype=float)
        if self.operation == "constant-speed":
            return np.full(V.shape, self.rpm * 2 * np.pi / 60.0)
        return V / (self.advance_ratio * self.radius)

    def spin_rate(self, V: np.ndarray) -> np.ndarray:
        """Signed Ω [rad/s] of the gyroscopic terms: rotation × rotational speed."""
        return self.rotation * self.rotational_speed(V)

    def aerodynamic_derivatives(self, V: np.ndarray, speed_of_sound: float) -> dict[str, np.ndarray]:
        """The 16 derivatives at airspeeds V (arrays over V)."""
        V = np.asarray(V, dtype=float)
        if self.derivatives is not None:
            return self.derivatives(V, self.rotational_speed(V), speed_of_sound)
        d = self.default_derivatives()(V, self.rotational_speed(V), speed_of_sound)
        if self.rotation == -1:  # mirror image of the counter-clockwise rotor
            d = {k: (-x if k in CROSS_DERIVATIVES else x) for k, x in d.items()}
        return d

    def default_derivatives(self) -> DerivativeSource:
        """Houbolt–Reed for this propeller's blades with `aero_settings` (chapter 4)."""
        return self._houbolt_reed

    @functools.cached_property
    def _houbolt_reed(self) -> DerivativeSource:
        """:meth:`default_derivatives`, built once per propeller (it is immutable; every
        evaluation of the model's matrices asks for it)."""
        return houbolt_reed_source(self, self.aero_settings)
