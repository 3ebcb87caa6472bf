"""Houbolt–Reed propeller aerodynamic derivatives (thesis chapter 4).

Strip theory with quasi-steady lift, corrected for compressibility and finite blade length
(eq. 4.18–4.24) and for wake (lift-lag) effects with Theodorsen's function (eq. 4.31–4.38).
All sixteen derivatives of eq. 4.25 follow from six blade integrals (eq. 4.39–4.42):

    C_Yψ = −C_Zθ =  4Ωc0/V · I1      C_Yθ = C_Zψ = −4Ωc0/V · J1
    C_Yq =  C_Zr = −4Ωc0/V · I2      C_Yr = −C_Zq = −4Ωc0/V · J2
    C_mψ = −C_nθ =  2Ωc0/V · I2      C_mθ = C_nψ = −2Ωc0/V · J2
    C_mq =  C_nr = −2Ωc0/V · I3      C_mr = −C_nq = −2Ωc0/V · J3   (thesis sign, §4.1.6)

with (eq. 4.42 generalised; for a = 2π it reduces to eq. 4.40/4.41)

    I_n, J_n = N_b/4 · μ^{p_n}/c0 · ∫_{η0}^{1} η^{q_n} c(η) g(η) {F(k), G(k)} / sqrt(μ² + η²) dη
    (p, q) = (2, 0), (1, 2), (0, 4)  for n = 1, 2, 3,
    g(η)   = a(η)/(2π) · 1/sqrt(1 − M_r²) · A'/(A' + 2),   A' = A sqrt(1 − M_r²)   (4.18–4.20)
    M_r²   = M² (1 + η²/μ²),  M = V/a_sound,  μ = V/(ΩR)                            (4.20)
    k      = Ω c(η) / (2U),   U = sqrt(V² + (Ωr)²)                                    (§4.1.4)

For a = 2π the product of the Prandtl–Glauert and aspect-ratio factors is
A/(2 + A sqrt(1 − M_r²)) (eq. 4.20); A is the blade aspect ratio of eq. 4.21 unless given.
Where a section goes supersonic, M_r² is held at 1 − (a0/a_m)² with a0 = 2π, a_m = 4π
(Rodden–Rose cut-off, eq. 4.23–4.24), and the result reports where that happened.

The reference chord c0 cancels from every derivative (it enters I_n, J_n as 1/c0 and the
prefactors as c0); it only scales the reported integrals.

Units: SI (m, s, rad).  Angles in radians unless a name says ``_deg``.
"""
from __future__ import annotations

import functools

import math
from dataclasses import dataclass, field, fields
from typing import Callable, Literal

import numpy as np

from propwhirl import limits
from propwhirl import validate as v
from propwhirl.model.aerodynamics import validity
from propwhirl.model.fields import check_fields, check_values, spec
from propwhirl.model.aerodynamics.theodorsen import theodorsen

#: The sixteen derivatives in the order of eq. 4.25 (F_Z, M_Y, F_Y, M_Z rows).
DERIVATIVE_NAMES: tuple[str, ...] = (
    "CZ_theta", "CZ_psi", "CZ_q", "CZ_r",
    "Cm_theta", "Cm_psi", "Cm_q", "Cm_r",
    "CY_theta", "CY_psi", "CY_q", "CY_r",
    "Cn_theta", "Cn_psi", "Cn_q", "Cn_r",
)

#: 2π [1/rad]: the thin-aerofoil lift-curve slope (the blade's default, the cut-off's reference)
TWO_PI = 2.0 * math.pi

# ----------------------------------------------------------------------------- geometry
@dataclass(frozen=True)
class Distribution:
    """A radial distribution f(η), piecewise linear through the points (eta, values).

    Build one with :meth:`constant`, :meth:`linear` (taper) or :meth:`tabulated`.
    `eta` is r/R (strictly increasing); `values` in the unit of the quantity (m for a
    chord, 1/rad for a lift-curve slope).  Evaluation outside the table is an error caught
    when the geometry is checked (the table must cover [η0, 1]).
    """

    eta: tuple[float, ...]
    values: tuple[float, ...]
    name: str = "distribution"

    def __post_init__(self) -> None:
        eta = v.increasing(f"{self.name} eta", self.eta)
        vals = v.positive(f"{self.name} values", self.values)
        if vals.shape != eta.shape:
            raise v.InputError(
                f"{self.name}: {vals.size} values given for {eta.size} eta stations; "
                "must be one value per station"
            )
        object.__setattr__(self, "eta", tuple(float(x) for x in eta))
        object.__setattr__(self, "values", tuple(float(x) for x in vals))

    @classmethod
    def constant(cls, value: float, name: str = "distribution") -> "Distribution":
        """f(η) = value on [0, 1]."""
        val = float(v.positive(name, value))
        return cls((0.0, 1.0), (val, val), name)

    @classmethod
    def linear(cls, value_root: float, value_tip: float, eta_root: float = 0.0,
               name: str = "distribution") -> "Distribution":
        """Linear taper from `value_root` at η = eta_root to `value_tip` at η = 1."""
        v.in_range(f"{name} eta_root", eta_root, 0.0, 1.0, high_open=True)
        return cls((float(eta_root), 1.0), (value_root, value_tip), name)

    @classmethod
    def tabulated(cls, eta, values, name: str = "distribution") -> "Distribution":
        """Piecewise linear through (eta[i], values[i]); eta strictly increasing."""
        return cls(tuple(np.ravel(v.finite(f"{name} eta", eta))),
                   tuple(np.ravel(v.finite(f"{name} values", values))), name)

    def __call__(self, eta) -> np.ndarray:
        return np.interp(eta, self.eta, self.values)

    @property
    def knots(self) -> np.ndarray:
        return np.asarray(self.eta)


@dataclass(frozen=True)
class PropellerGeometry:
    """Blade geometry for the Houbolt–Reed method.

    n_blades        N_b ≥ 3 (polar symmetry of the disc is assumed, eq. 4.12/4.41)
    radius          R [m]
    hub_ratio       η0 = r0/R ∈ [0, 1)
    chord           c(η) [m]: a number (constant chord), a :class:`Distribution`, or any
                    vectorised callable η ↦ c(η) (assumed smooth: no panel breaks)
    lift_slope      a(η) [1/rad]: None for the theoretical 2π, or a :class:`Distribution`
    reference_chord c0 [m]; None → c(0.75) (only scales the reported integrals)
    aspect_ratio    A of eq. 4.20; None → eq. 4.21, A = R(1−η0)² / ∫_{η0}^{1} c dη
    """

    n_blades: int = field(metadata=spec("n_blades", "", "number of blades N_b (>= 3)",
                                        range=(3, 20)))
    radius: float = field(metadata=spec("radius_m", "m", "rotor radius R", range=(1e-2, 20.0)))
    hub_ratio: float = field(metadata=spec("hub_ratio", "", "eta0 = r0/R", range=(0.0, 1.0),
                                           ends="[)"))
    chord: float | Distribution | Callable[[np.ndarray], np.ndarray] = field(metadata=spec(
        "chord", "m", "blade chord c(eta)",
        form="distribution", number_key="chord_m", value_key="chord_m", range=(1e-3, 5.0)))
    lift_slope: Distribution | None = field(default=None, metadata=spec(
        "lift_slope", "1/rad", "lift-curve slope a(eta); omitted: 2 pi",
        default="none", form="distribution", value_key="lift_slope_per_rad",
        range=(0.0, 4.0 * math.pi), ends="(]"))
    reference_chord: float | None = field(default=None, metadata=spec(
        "reference_chord_m", "m", "reference chord c0; omitted: c(0.75)", default="none",
        range=(1e-3, 5.0)))
    aspect_ratio: float | None = field(default=None, metadata=spec(
        "aspect_ratio", "", "blade aspect ratio A of eq. 4.20; omitted: eq. 4.21", default="none",
        range=(1e-2, 1e3)))

    def __post_init__(self) -> None:
        check_fields(self)  # types and the declared ranges of every field
        object.__setattr__(self, "radius", float(self.radius))
        eta0 = float(self.hub_ratio)
        object.__setattr__(self, "hub_ratio", eta0)
        chord = self.chord
        if callable(chord) and not isinstance(chord, Distribution):
            sample = np.linspace(eta0, 1.0, 101)
            try:
                values = np.broadcast_to(v.real("chord(eta)", chord(sample)), sample.shape)
            except (TypeError, ValueError, ArithmeticError, AttributeError, IndexError,
                    KeyError) as exc:
                if isinstance(exc, v.InputError):
                    raise
                raise v.InputError(f"chord function failed on eta in [{eta0}, 1]: {exc}") from exc
            check_values(PropellerGeometry, "chord", values, sample, "eta", "")
        elif not isinstance(chord, Distribution):
            chord = Distribution.constant(float(chord), "chord")
        object.__setattr__(self, "chord", chord)
        for dist, label in ((chord, "chord"), (self.lift_slope, "lift_slope")):
            if dist is None or (label == "chord" and not isinstance(dist, Distribution)):
                continue
            if not isinstance(dist, Distribution):
                raise v.InputError(f"{label} = {dist!r} is invalid: must be a Distribution")
            if dist.eta[0] > eta0 or dist.eta[-1] < 1.0:
                raise v.InputError(
                    f"{label} table covers eta in [{dist.eta[0]}, {dist.eta[-1]}] which is "
                    f"invalid: must cover the blade, [hub_ratio, 1] = [{eta0}, 1.0]"
                )
        if self.reference_chord is not None:
            object.__setattr__(self, "reference_chord", float(self.reference_chord))
        if self.aspect_ratio is not None:
            object.__setattr__(self, "aspect_ratio", float(self.aspect_ratio))

    @property
    def c0(self) -> float:
        """Reference chord c0 [m] (default: chord at 0.75R)."""
        if self.reference_chord is not None:
            return self.reference_chord
        return float(self.chord(0.75))

    @functools.cached_property
    def knots(self) -> np.ndarray:
        """Breaks of the piecewise-linear distributions strictly inside (η0, 1) (read-only;
        computed once per geometry, which is immutable)."""
        pts = [self.chord.knots] if isinstance(self.chord, Distribution) else []
        if self.lift_slope is not None:
            pts.append(self.lift_slope.knots)
        k = np.unique(np.concatenate(pts)) if pts else np.empty(0)
        k = k[(k > self.hub_ratio) & (k < 1.0)]
        k.flags.writeable = False
        return k

    def blade_area(self) -> float:
        """∫_{r0}^{R} c dr [m²] (exact for a piecewise-linear chord; 64-point Gauss else)."""
        return self._blade_area

    @functools.cached_property
    def _blade_area(self) -> float:
        """:meth:`blade_area`, computed once per geometry (every analysis speed asks for it)."""
        edges = np.concatenate(([self.hub_ratio], self.knots, [1.0]))
        if isinstance(self.chord, Distribution):
            c = self.chord(edges)
            return float(self.radius * np.sum(0.5 * (c[1:] + c[:-1]) * np.diff(edges)))
        eta, w = quadrature_nodes(edges[None, :], 64)
        return float(self.radius * np.sum(w * self.chord(eta)))

    @property
    def blade_aspect_ratio(self) -> float:
        """A used in eq. 4.20: the given value, else eq. 4.21 R(1−η0)²/∫_{η0}^{1} c dη."""
        if self.aspect_ratio is not None:
            return self.aspect_ratio
        return self.radius ** 2 * (1.0 - self.hub_ratio) ** 2 / self.blade_area()


# ----------------------------------------------------------------------------- settings
@dataclass(frozen=True)
class AeroSettings:
    """Switches of the Houbolt–Reed model.

    wake                Theodorsen lift lag F(k) + iG(k) (§4.1.4); off: F = 1, G = 0 (eq. 4.28)
    compressibility     Prandtl–Glauert 1/sqrt(1 − M_r²) and A' = A sqrt(1 − M_r²) (4.18–4.19),
                        with the Rodden–Rose cut-off (4.23–4.24); off: M_r = 0
    aspect_ratio_correction  finite-blade factor A'/(A' + 2) (4.19); off: factor 1
    cnq_sign            "thesis": C_nq = −C_mr = +2Ωc0/V J3 (eq. 4.39);
                        "rodden_rose": C_nq = −C_mr = −2Ωc0/V J3 (§4.1.6)
    method              "houbolt_reed" (eq. 4.39–4.42) or "bennett_bland" (§4.2, eq. 4.43–4.46):
                        no wake, M = 0, aspect-ratio factor as set; C_Zψ = C_Yψ tan δ and
                        C_mθ = C_mψ tan δ with δ = atan(−G/F) at k_0.75R (eq. 4.45); the
                        rate derivatives that only the wake produces (C_Zq = −C_Yr,
                        C_mr = −C_nq) are zero, as in Bennett & Bland and Rodden & Rose.
    cutoff_lift_slope   a_m of eq. 4.23–4.24 [1/rad] (default 4π; a0 = 2π)
    quadrature_order    Gauss–Legendre points per panel (panels split at the breaks of the
                        tabulated distributions and at the cut-off radius; the integration
                        variable is t = asinh(η/μ), which makes the integrand smooth)
    """

    wake: bool = field(default=True, metadata=spec(
        "wake", "", "Theodorsen lift lag F + iG (section 4.1.4)", default="setting"))
    compressibility: bool = field(default=True, metadata=spec(
        "compressibility", "", "Prandtl-Glauert with the Rodden-Rose cut-off (eq. 4.18-4.24)",
        default="setting"))
    aspect_ratio_correction: bool = field(default=True, metadata=spec(
        "aspect_ratio_correction", "", "finite-blade factor A'/(A'+2) (eq. 4.19)",
        default="setting"))
    cnq_sign: Literal["thesis", "rodden_rose"] = field(default="thesis", metadata=spec(
        "cnq_sign", "", "sign of C_nq = -C_mr (eq. 4.39 or section 4.1.6)", default="setting"))
    method: Literal["houbolt_reed", "bennett_bland"] = field(default="houbolt_reed", metadata=spec(
        "method", "", "Houbolt-Reed (eq. 4.39-4.42) or Bennett-Bland (section 4.2)",
        default="setting"))
    cutoff_lift_slope: float = field(default=4.0 * math.pi, metadata=spec(
        "cutoff_lift_slope_per_rad", "1/rad", "a_m of the cut-off (eq. 4.23-4.24); omitted: "
        "4 pi (Rodden-Rose)", default="physical", range=(TWO_PI, 1e3), ends="(]"))
    quadrature_order: int = field(default=32, metadata=spec(
        "quadrature_order", "", "Gauss-Legendre points per panel", default="setting"))

    def __post_init__(self) -> None:
        check_fields(self)  # types, choices and the range of the cut-off slope (> a0 = 2π)
        object.__setattr__(self, "cutoff_lift_slope", float(self.cutoff_lift_slope))
        v.integer_at_least("quadrature_order", self.quadrature_order, 2)
        limits.check_quadrature_order(self.quadrature_order)


# ----------------------------------------------------------------------------- result
@dataclass(frozen=True)
class PropellerDerivatives:
    """Houbolt–Reed derivatives over a set of operating points (arrays of one shape).

    The 16 derivatives follow eq. 4.25 (F_Z and F_Y per ½ρV²S'; M_Y and M_Z per ρV²S'R;
    angles θ, ψ and rates θ̇R/V, ψ̇R/V).  I1..J3 are the blade integrals (eq. 4.41/4.42,
    in 1/m through 1/c0), `advance_ratio` μ = V/(ΩR), `mach` M = V/a, and `cutoff_applied`
    tells where the Rodden–Rose cut-off (eq. 4.23–4.24) clipped the blade tip region.
    """

    airspeed: np.ndarray
    omega: np.ndarray
    advance_ratio: np.ndarray
    mach: np.ndarray
    cutoff_applied: np.ndarray
    I1: np.ndarray
    I2: np.ndarray
    I3: np.ndarray
    J1: np.ndarray
    J2: np.ndarray
    J3: np.ndarray
    CZ_theta: np.ndarray
    CZ_psi: np.ndarray
    CZ_q: np.ndarray
    CZ_r: np.ndarray
    Cm_theta: np.ndarray
    Cm_psi: np.ndarray
    Cm_q: np.ndarray
    Cm_r: np.ndarray
    CY_theta: np.ndarray
    CY_psi: np.ndarray
    CY_q: np.ndarray
    CY_r: np.ndarray
    Cn_theta: np.ndarray
    Cn_psi: np.ndarray
    Cn_q: np.ndarray
    Cn_r: np.ndarray
    reference_chord: float = field(default=0.0)
    aspect_ratio: float = field(default=0.0)

    def derivatives(self) -> dict[str, np.ndarray]:
        """The sixteen derivatives by name (order of :data:`DERIVATIVE_NAMES`)."""
        return {n: getattr(self, n) for n in DERIVATIVE_NAMES}

    def at(self, index: int) -> dict[str, float]:
        """All scalar fields at one operating point (for tables and JSON)."""
        out = {}
        for f in fields(self):
            val = getattr(self, f.name)
            out[f.name] = (val.flat[index].item() if isinstance(val, np.ndarray)
                           else val)
        return out


# ----------------------------------------------------------------------------- numerics
def panel_edges(geometry: PropellerGeometry, cut_eta: np.ndarray) -> np.ndarray:
    """Panel edges, shape (n_points, n_panels + 1): hub, breaks, cut-off radius, tip.

    The cut-off radius (per operating point) is clipped into [η0, 1]; a panel of zero width
    then carries zero weight, so every operating point has the same number of panels.
    """
    eta0 = geometry.hub_ratio
    fixed = np.concatenate(([eta0], geometry.knots, [1.0]))
    if not np.any(cut_eta < 1.0):                     # no section reaches the cut-off
        return np.broadcast_to(fixed, (cut_eta.shape[0], fixed.size))
    cut = np.clip(cut_eta, eta0, 1.0)[:, None]
    edges = np.concatenate((np.broadcast_to(fixed, (cut.shape[0], fixed.size)), cut), axis=1)
    return np.sort(edges, axis=1)


@functools.lru_cache(maxsize=32)
def _gauss_legendre(order: int) -> tuple[np.ndarray, np.ndarray]:
    """Gauss–Legendre nodes and weights on [−1, 1] (read-only; computed once per order)."""
    x, w = np.polynomial.legendre.leggauss(order)
    x.flags.writeable = w.flags.writeable = False
    return x, w


def quadrature_nodes(edges: np.ndarray, order: int) -> tuple[np.ndarray, np.ndarray]:
    """Composite Gauss–Legendre nodes and weights on each row's panels, (n_points, m)."""
    x, w = _gauss_legendre(order)
    a, b = edges[:, :-1, None], edges[:, 1:, None]
    eta = 0.5 * (a + b) + 0.5 * (b - a) * x
    wt = 0.5 * (b - a) * w
    n = edges.shape[0]
    return eta.reshape(n, -1), wt.reshape(n, -1)


def _lift_factor(geometry: PropellerGeometry, settings: AeroSettings, eta: np.ndarray,
                 mr2: np.ndarray, A: float) -> np.ndarray:
    """g(η) of eq. 4.42: a(η)/(2π) · 1/sqrt(1 − M_r²) · A'/(A' + 2) (4.18–4.20), for the
    sections at η with squared relative Mach numbers ``mr2`` (already cut off, 4.23–4.24)."""
    slope_ratio = 1.0 if geometry.lift_slope is None else geometry.lift_slope(eta) / TWO_PI
    beta = np.sqrt(1.0 - mr2)
    pg = 1.0 / beta                                                    # eq. 4.18
    arf = (A * beta) / (A * beta + 2.0) if settings.aspect_ratio_correction else 1.0  # 4.19
    return slope_ratio * pg * arf


def _integrals(geometry: PropellerGeometry, settings: AeroSettings, mu: np.ndarray,
               omega: np.ndarray, airspeed: np.ndarray, mach: np.ndarray,
               wake: bool) -> tuple[np.ndarray, ...]:
    """I1, I2, I3, J1, J2, J3 (eq. 4.40–4.42) and the cut-off flag, 1-D over the points."""
    A = geometry.blade_aspect_ratio
    mr2_max = 1.0 - (TWO_PI / settings.cutoff_lift_slope) ** 2       # eq. 4.23–4.24
    m2 = mach ** 2
    with np.errstate(divide="ignore"):
        # η where M_r² reaches the cut-off: M²(1 + η²/μ²) = 1 − (a0/a_m)²
        cut_eta = np.where(m2 > 0, mu * np.sqrt(np.maximum(mr2_max / np.where(m2 > 0, m2, 1.0)
                                                           - 1.0, 0.0)), np.inf)
    cutoff = m2 * (1.0 + 1.0 / mu ** 2) > mr2_max                      # tip beyond cut-off
    mu_, om_, V_, m2_ = (x[:, None] for x in (mu, omega, airspeed, m2))
    # Substitution η = μ sinh t: dη/sqrt(μ² + η²) = dt removes the near-singularity of the
    # integrand at η = ±iμ (close to the hub for small μ); Gauss–Legendre in t per panel.
    t_edges = np.arcsinh(panel_edges(geometry, cut_eta) / mu_)
    t, w = quadrature_nodes(t_edges, settings.quadrature_order)
    eta = mu_ * np.sinh(t)

    chord = geometry.chord(eta)
    mr2 = np.minimum(m2_ * (1.0 + eta ** 2 / mu_ ** 2), mr2_max)       # eq. 4.20, 4.24
    g = _lift_factor(geometry, settings, eta, mr2, A)

    base = w * chord * g                                               # w · dη/sqrt(μ²+η²)
    if wake:
        U = V_ * np.cosh(t)                                            # sqrt(V² + (Ωr)²)
        k = om_ * chord / (2.0 * U)                                    # §4.1.4
        C = theodorsen(k)
        F, G = C.real, C.imag
    else:
        F, G = 1.0, 0.0
    scale = geometry.n_blades / 4.0 / geometry.c0                      # eq. 4.41
    e2, e4 = eta ** 2, eta ** 4
    I1 = scale * mu ** 2 * np.sum(base * F, axis=1)
    I2 = scale * mu * np.sum(base * e2 * F, axis=1)
    I3 = scale * np.sum(base * e4 * F, axis=1)
    if wake:
        J1 = scale * mu ** 2 * np.sum(base * G, axis=1)
        J2 = scale * mu * np.sum(base * e2 * G, axis=1)
        J3 = scale * np.sum(base * e4 * G, axis=1)
    else:
        J1 = J2 = J3 = np.zeros_like(I1)
    return I1, I2, I3, J1, J2, J3, cutoff


# ----------------------------------------------------------------------------- public API
def derivatives(geometry: PropellerGeometry, airspeed, omega, speed_of_sound=None,
                mach=None, settings: AeroSettings = AeroSettings()) -> PropellerDerivatives:
    """The sixteen Houbolt–Reed derivatives (eq. 4.39) at the operating points (V, Ω).

    airspeed        V [m/s] > 0, any shape
    omega           Ω [rad/s] > 0, broadcastable with V (constant speed: a scalar)
    speed_of_sound  a [m/s] > 0 (M = V/a), or give `mach` (broadcastable with V); needed
                    when compressibility is on and the method is Houbolt–Reed
    Returns arrays of the broadcast shape of V and Ω (no loop over operating points).
    """
    shape, Vf, omf, Mf, d, mu, cutoff, integrals = _evaluate(
        geometry, settings, airspeed, omega, speed_of_sound, mach)
    r = lambda x: np.asarray(x, dtype=float).reshape(shape)            # noqa: E731
    bennett_bland = settings.method == "bennett_bland"
    return PropellerDerivatives(
        airspeed=r(Vf), omega=r(omf), advance_ratio=r(mu), mach=r(Mf),
        cutoff_applied=np.asarray(cutoff & settings.compressibility & (not bennett_bland),
                                  dtype=bool).reshape(shape),
        **{n: r(x) for n, x in integrals.items()},
        **{n: r(x) for n, x in d.items()},
        reference_chord=geometry.c0, aspect_ratio=geometry.blade_aspect_ratio,
    )


def _evaluate(geometry: PropellerGeometry, settings: AeroSettings, airspeed, omega,
              speed_of_sound, mach):
    """What :func:`derivatives` computes, before it is wrapped: the broadcast shape of V and
    Ω, the flat V [m/s], Ω [rad/s] and M, the sixteen derivatives, μ, the cut-off flag and
    the six integrals (flat arrays); the inputs checked and the derivatives checked finite."""
    V = v.positive("airspeed", airspeed, "m/s")
    om = v.positive("omega", omega, "rad/s")
    try:
        V, om = np.broadcast_arrays(V, om)
    except ValueError as exc:
        raise v.InputError(f"airspeed shape {V.shape} and omega shape {om.shape} are invalid: "
                           "must broadcast together") from exc
    shape = V.shape
    if mach is not None and speed_of_sound is not None:
        raise v.InputError("give either speed_of_sound or mach, not both")
    if speed_of_sound is not None or mach is not None:
        a = (v.positive("speed_of_sound", speed_of_sound, "m/s") if mach is None
             else v.non_negative("mach", mach))
        try:
            M = np.broadcast_to(V / a if mach is None else a, shape)
        except ValueError as exc:
            raise v.InputError(f"{'mach' if mach is not None else 'speed_of_sound'} shape "
                               f"{a.shape} is invalid: must broadcast to the airspeed shape "
                               f"{shape}") from exc
    else:
        if settings.compressibility and settings.method == "houbolt_reed":
            raise v.InputError(
                "speed_of_sound (or mach) is missing: required with compressibility on")
        M = np.zeros(shape)
    Vf, omf, Mf = (np.ascontiguousarray(x, dtype=float).ravel() for x in (V, om, M))
    validity.check_propeller(geometry.n_blades, geometry.radius, geometry.blade_area(), Vf, Mf)
    with np.errstate(over="ignore", under="ignore", invalid="ignore", divide="ignore"):
        d, mu, cutoff, integrals = _derivatives(geometry, settings, Vf, omf, Mf)
    _check_finite(geometry, d, Vf, omf, mu)
    return shape, Vf, omf, Mf, d, mu, cutoff, integrals


def solidity(geometry: PropellerGeometry) -> float:
    """Disc solidity σ = N_b ∫_{r0}^{R} c dr / (π R²) (blade planform over disc area)."""
    return geometry.n_blades * geometry.blade_area() / (math.pi * geometry.radius ** 2)


def validity_warnings(d: PropellerDerivatives) -> tuple[str, ...]:
    """One line per validity bound the operating points of `d` exceed
    (:func:`propwhirl.model.aerodynamics.validity.operating_point_warnings`)."""
    return validity.operating_point_warnings(d.airspeed, d.mach, d.advance_ratio)


def _check_finite(geometry: PropellerGeometry, d: dict[str, np.ndarray], V: np.ndarray,
                  omega: np.ndarray, mu: np.ndarray) -> None:
    """InputError naming the derivative and the operating point where one is not finite."""
    if np.isfinite(np.concatenate(list(d.values()))).all():
        return                               # one test of all of them: every one finite
    for name, x in d.items():
        if not np.isfinite(x).all():
            t = int(np.argmax(~np.isfinite(x)))
            raise v.InputError(
                f"Houbolt-Reed derivative {name} is not finite at V = {V[t]:g} m/s, Omega = "
                f"{omega[t]:g} rad/s (advance ratio V/(Omega R) = {mu[t]:.4g}, radius = "
                f"{geometry.radius:g} m, reference chord {geometry.c0:g} m): the operating "
                "point or the blade geometry is outside what the method can represent")


def _derivatives(geometry: PropellerGeometry, settings: AeroSettings, Vf: np.ndarray,
                 omf: np.ndarray, Mf: np.ndarray):
    """The sixteen derivatives (flat arrays), μ, the cut-off flag and the six integrals."""
    mu = Vf / (omf * geometry.radius)

    bennett_bland = settings.method == "bennett_bland"
    use_m = Mf if (settings.compressibility and not bennett_bland) else np.zeros_like(Mf)
    I1, I2, I3, J1, J2, J3, cutoff = _integrals(
        geometry, settings, mu, omf, Vf, use_m, wake=settings.wake and not bennett_bland)
    if bennett_bland:
        # eq. 4.43–4.46: phase lag δ at k_0.75R = c_0.75/(2R sqrt(0.75² + μ²)) (eq. 4.45)
        k75 = geometry.chord(0.75) / (2.0 * geometry.radius * np.sqrt(0.5625 + mu ** 2))
        C = theodorsen(k75)
        tan_delta = -C.imag / C.real                                   # eq. 4.44
        # equivalent J's reproduce C_Zψ = C_Yψ tan δ and C_mθ = C_mψ tan δ through eq. 4.39
        J1, J2 = -I1 * tan_delta, -I2 * tan_delta
        J3 = np.zeros_like(I1)
    f = omf * geometry.c0 / Vf                                          # Ωc0/V = c0/(μR)
    CY_psi = 4 * f * I1
    CZ_psi = -4 * f * J1
    CY_q = -4 * f * I2
    CY_r = -4 * f * J2
    Cm_psi = 2 * f * I2
    Cm_theta = -2 * f * J2
    Cm_q = -2 * f * I3
    Cm_r = -2 * f * J3 if settings.cnq_sign == "thesis" else 2 * f * J3
    if bennett_bland:
        CY_r = np.zeros_like(CY_r)                                     # no wake derivatives
    d = dict(
        CZ_theta=-CY_psi, CZ_psi=CZ_psi, CZ_q=-CY_r, CZ_r=CY_q,        # eq. 4.27
        Cm_theta=Cm_theta, Cm_psi=Cm_psi, Cm_q=Cm_q, Cm_r=Cm_r,
        CY_theta=CZ_psi, CY_psi=CY_psi, CY_q=CY_q, CY_r=CY_r,
        Cn_theta=-Cm_psi, Cn_psi=Cm_theta, Cn_q=-Cm_r, Cn_r=Cm_q,
    )
    return d, mu, cutoff, dict(I1=I1, I2=I2, I3=I3, J1=J1, J2=J2, J3=J3)


def stopped_blades(geometry: PropellerGeometry, airspeed, speed_of_sound=None,
                   settings: AeroSettings = AeroSettings()) -> dict[str, np.ndarray]:
    """The sixteen derivatives (eq. 4.25) of a stopped rotor whose blades lie along the free
    stream (feathered): the limit Ω → 0 at fixed V of eq. 4.39–4.42, arrays of V's shape.

    With μ = V/(ΩR) → ∞ the windmilling blade's inflow angle tends to 90°, so the limit is
    the feathered blade (chord along the shaft), and the blade-element terms become:
    k = Ωc/(2U) → 0, so F → 1 and G → 0 (every J_n term vanishes); M_r² → M² (4.20);
    Ωc0/V · I2 and Ωc0/V · I3 → 0 (they carry one and two powers of Ω more than I1);
    and 4Ωc0/V · I1 = N_b μ/R ∫ c g F/sqrt(μ² + η²) dη → N_b/R ∫_{η0}^{1} c(η) g(η) dη.
    What remains is C_Yψ = −C_Zθ = N_b/R ∫ c g dη: each blade is a fin, and a nacelle angle ψ
    (or θ) gives the blade at azimuth φ the cross-flow angle ψ sin φ, so the N_b blades give
    the side force ½ρV² · N_b/2 · ∫_{r0}^{R} a c A'/(A'+2)/sqrt(1 − M²) dr per radian
    (with C_Yψ per ½ρV²πR², eq. 4.25).  The Bennett–Bland method has the same limit (its
    phase lag δ → 0) with M = 0.

    airspeed        V [m/s] > 0, any shape
    speed_of_sound  a [m/s] > 0 (M = V/a); needed when compressibility is on
    """
    V = v.positive("airspeed", airspeed, "m/s")
    bennett_bland = settings.method == "bennett_bland"
    if settings.compressibility and not bennett_bland:
        if speed_of_sound is None:
            raise v.InputError(
                "speed_of_sound is missing: required with compressibility on")
        M = V / v.positive("speed_of_sound", speed_of_sound, "m/s")
    else:
        M = np.zeros(V.shape)
    Vf, Mf = (np.ascontiguousarray(x, dtype=float).ravel() for x in (V, M))
    validity.check_propeller(geometry.n_blades, geometry.radius, geometry.blade_area(), Vf, Mf)
    mr2_max = 1.0 - (TWO_PI / settings.cutoff_lift_slope) ** 2       # eq. 4.23–4.24
    edges = np.concatenate(([geometry.hub_ratio], geometry.knots, [1.0]))[None, :]
    eta, w = quadrature_nodes(edges, settings.quadrature_order)      # (1, m)
    mr2 = np.minimum(Mf[:, None] ** 2, mr2_max)                        # (n, 1): M_r = M
    g = _lift_factor(geometry, settings, eta, mr2, geometry.blade_aspect_ratio)
    cy_psi = geometry.n_blades / geometry.radius * np.sum(w * geometry.chord(eta) * g, axis=1)
    cy_psi = cy_psi.reshape(V.shape)
    out = {n: np.zeros(V.shape) for n in DERIVATIVE_NAMES}
    out["CY_psi"], out["CZ_theta"] = cy_psi, -cy_psi                   # eq. 4.27
    return out


def constant_speed(geometry: PropellerGeometry, airspeed, omega: float, speed_of_sound=None,
                   mach=None, settings: AeroSettings = AeroSettings()) -> PropellerDerivatives:
    """Constant-speed propeller: Ω fixed [rad/s], the advance ratio μ = V/(ΩR) varies with V."""
    om = v.positive("omega", omega, "rad/s")
    if om.ndim:
        raise v.InputError(f"omega has shape {om.shape}, invalid: a constant speed is a scalar")
    return derivatives(geometry, airspeed, om, speed_of_sound, mach, settings)


AdvanceRule = Literal["thesis_eq_9_1", "blade_element"]


def advance_ratio_from_blade_angle(blade_angle, zero_lift_angle: float = math.radians(-3.0),
                                   rule: AdvanceRule = "thesis_eq_9_1") -> np.ndarray:
    """Windmilling advance ratio μ = V/(ΩR) of a fixed-pitch propeller from β_0.75R [rad].

    rule "thesis_eq_9_1": eq. 9.1 as the thesis prints and uses it (chapter 9),
        J = π tan(β_0.75 + α_0L), μ = J/π = tan(β_0.75 + α_0L)   (α_0L = −3°: tan(β − 3°)).
    rule "blade_element": zero lift at the 0.75R section, β − φ = α_0L with
        tan φ = V/(0.75 ΩR), i.e. μ = 0.75 tan(β_0.75 − α_0L)   (= 0.75 tan(β + 3°)).
        This is the relation that reproduces Table 4.1 (docs/validation.md).
    """
    beta = v.finite("blade_angle", blade_angle, "rad")
    a0l = float(v.finite("zero_lift_angle", zero_lift_angle, "rad"))
    if rule == "thesis_eq_9_1":
        phi, scale = beta + a0l, 1.0
    elif rule == "blade_element":
        phi, scale = beta - a0l, 0.75
    else:
        raise v.InputError(
            f"rule = {rule!r} is invalid: must be 'thesis_eq_9_1' or 'blade_element'")
    bad = (phi <= 0) | (phi >= 0.5 * math.pi)
    if np.any(bad):
        b_deg = float(np.degrees(np.ravel(beta)[np.ravel(bad)][0]))
        p_deg = float(np.degrees(np.ravel(phi)[np.ravel(bad)][0]))
        raise v.InputError(
            f"blade_angle = {b_deg:.6g} deg is invalid: the inflow angle φ = {p_deg:.6g} deg "
            f"(rule {rule!r}, zero_lift_angle {math.degrees(a0l):.6g} deg) must be in (0, 90) deg")
    return scale * np.tan(phi)


def windmilling(geometry: PropellerGeometry, airspeed, blade_angle: float,
                speed_of_sound=None, mach=None, zero_lift_angle: float = math.radians(-3.0),
                rule: AdvanceRule = "thesis_eq_9_1",
                settings: AeroSettings = AeroSettings()) -> PropellerDerivatives:
    """Fixed-pitch windmilling propeller: μ fixed by the blade angle, Ω = V/(μR) rises with V.

    blade_angle β_0.75R [rad]; see :func:`advance_ratio_from_blade_angle` for `rule`.
    """
    mu = advance_ratio_from_blade_angle(blade_angle, zero_lift_angle, rule)
    V = v.positive("airspeed", airspeed, "m/s")
    return derivatives(geometry, V, V / (mu * geometry.radius), speed_of_sound, mach, settings)


@dataclass(frozen=True)
class HouboltReedSource:
    """Houbolt–Reed derivatives as a derivative source: ``source(V, Ω, a) -> {name: array}``.

    V [m/s] and Ω [rad/s] are arrays of one shape, `a` the speed of sound [m/s] (None: M = 0,
    allowed only with compressibility off).
    """

    geometry: PropellerGeometry = field(metadata=spec(
        "geometry", "", "blade geometry (its keys sit in this table)", form="flat"))
    settings: AeroSettings = field(default=AeroSettings(), metadata=spec(
        "settings", "", "Houbolt-Reed switches", default="setting"))

    def __post_init__(self) -> None:
        check_fields(self)

    def __call__(self, V, Omega, speed_of_sound=None) -> dict[str, np.ndarray]:
        """The sixteen derivatives of :func:`derivatives` (the same values), without its
        :class:`PropellerDerivatives` (the model's matrices need only the derivatives and
        ask at every evaluation)."""
        shape, *_, d, _mu, _cutoff, _integrals = _evaluate(
            self.geometry, self.settings, V, Omega, speed_of_sound, None)
        return {n: np.asarray(d[n], dtype=float).reshape(shape) for n in DERIVATIVE_NAMES}


def houbolt_reed_source(propeller, settings: AeroSettings = AeroSettings(),
                        aspect_ratio: float | None = None) -> HouboltReedSource:
    """Derivative source for an object with ``n_blades``, ``radius`` [m], ``hub_radius`` [m]
    and ``blade_chord`` (a number [m], a :class:`Distribution` or a callable of η = r/R),
    such as :class:`propwhirl.model.propellers.propeller.Propeller`.  Thesis settings by default."""
    radius = float(v.positive("radius", propeller.radius, "m"))
    geo = PropellerGeometry(
        n_blades=propeller.n_blades, radius=radius,
        hub_ratio=float(v.non_negative("hub_radius", propeller.hub_radius, "m")) / radius,
        chord=propeller.blade_chord, aspect_ratio=aspect_ratio)
    return HouboltReedSource(geo, settings)
