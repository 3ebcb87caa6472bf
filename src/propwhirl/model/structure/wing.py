"""The flexible cantilever wing (thesis chapter 7): geometry, properties, discretisation.

A :class:`Wing` is an unswept, possibly tapered beam clamped at the root (y = 0) and free at the
tip (y = semi_span), discretised into Euler–Bernoulli elements (§7.1): `n_elements` equal ones
by default, or a mesh whose nodes include given `stations` with elements no longer than
`max_element_length` (the rule: :mod:`propwhirl.model.structure.mesh`; the mesh is built once, on
construction, and :attr:`Wing.mesh` holds it).  Per-element properties (mass, inertia,
stiffness, centre of gravity) are evaluated at element mid-span, so a property that changes at a
station is constant over each element; strip-aerodynamic properties (chord, elastic axis,
aerodynamic centre, lift-curve slope) at the nodes, where the thesis applies the aerodynamic
loads (§7.2), each node's strip reaching half-way to its neighbours.

Every spanwise property accepts a scalar (uniform), an array with one value per element, or a
callable of the spanwise position y [m].  Chordwise positions are fractions of the local chord
from the leading edge.  SI units.
"""
from __future__ import annotations

import functools
from dataclasses import dataclass, field, replace
from typing import Callable, Literal, Union

import numpy as np

from propwhirl import limits
from propwhirl import validate as v
from propwhirl.model.structure import mesh as meshing
from propwhirl.model.fields import check_fields, check_values, spec
from propwhirl.model.structure.mesh import Mesh

#: highest Mach number of the doublet-lattice tables: the DLM is a subsonic linear theory
DLM_MACH_MAX = 0.9

#: the ``dlm_mach`` of a wing whose doublet-lattice Mach is V / a of each analysed speed
DLM_MATCHED = "speed"


def check_dlm_mach(value) -> None:
    """InputError unless ``value`` (a wing's ``dlm_mach``) is "speed" or a number in
    [0, :data:`DLM_MACH_MAX`]."""
    check_mach_setting("dlm_mach", value)


def check_mach_setting(name: str, value) -> None:
    """InputError unless ``value`` (a wing's Mach setting ``name``: ``dlm_mach``,
    ``strip_mach``) is "speed" or a number in [0, :data:`DLM_MACH_MAX`]."""
    if isinstance(value, str):
        ok = value == DLM_MATCHED
    else:
        ok = (isinstance(value, (int, float, np.integer, np.floating))
              and not isinstance(value, (bool, np.bool_))
              and bool(np.isfinite(value)) and 0.0 <= float(value) <= DLM_MACH_MAX)
    if ok:
        return
    if isinstance(value, (int, float, np.integer, np.floating)) and np.isfinite(value) \
            and not isinstance(value, (bool, np.bool_)):
        raise v.InputError(f"{name} = {value!r:.40} is outside the valid range "
                           f"[0, {DLM_MACH_MAX:g}] (one Mach for every speed; or "
                           f"\"{DLM_MATCHED}\": Mach V/a at each analysed speed)")
    raise v.InputError(f"{name} = {value!r:.40} is invalid: must be \"{DLM_MATCHED}\" "
                       f"(Mach V/a at each analysed speed) or a number in "
                       f"[0, {DLM_MACH_MAX:g}] (one Mach for every speed)")


Spanwise = Union[float, np.ndarray, Callable[[np.ndarray], np.ndarray]]
LiftSlope = Union[float, Literal["elliptic"], Callable[[np.ndarray], np.ndarray]]

TWO_PI = 2.0 * np.pi


#: Errors a user's function of y may raise; they become an InputError naming the property.
_CALL_ERRORS = (TypeError, ValueError, ArithmeticError, AttributeError, IndexError, KeyError)


def _call(name: str, fn: Callable, y: np.ndarray) -> np.ndarray:
    """fn(y) as real numbers; an InputError naming the property if the function fails."""
    try:
        out = fn(y)
    except _CALL_ERRORS as exc:
        raise v.InputError(f"{name}(y) failed on y in [{y.min():.6g}, {y.max():.6g}] m: "
                           f"{type(exc).__name__}: {exc}") from exc
    return v.real(f"{name}(y)", out)


def _count_text(n: int, uniform: bool) -> str:
    """How an error states the element count: "n_elements = 25" or "25 elements (its mesh)"."""
    return f"n_elements = {n}" if uniform else f"{n} elements (its mesh)"


def _spanwise(name: str, value: Spanwise, y: np.ndarray, n_elements: int, unit: str,
              uniform: bool = True) -> np.ndarray:
    """Evaluate a spanwise property at element mid-points `y` (scalar, per element, callable)."""
    if callable(value):
        out = _call(name, value, y)
        if out.shape != y.shape:
            raise v.InputError(
                f"{name}(y) must return one value per position, got shape {out.shape} for {y.shape}"
            )
        return v.finite(name, out, unit)
    arr = np.asarray(value, dtype=float)
    if arr.ndim == 0:
        return np.full(y.shape, v.finite(name, arr, unit))
    if arr.shape != (n_elements,):
        raise v.InputError(
            f"{name} has {arr.size} values but the wing has {_count_text(n_elements, uniform)}: "
            f"give a scalar, one value per element, or a function of y"
        )
    return v.finite(name, arr, unit)


#: doublet-lattice panels along the chord by default (the wing's ``dlm_chordwise_panels``)
DEFAULT_CHORDWISE = 8
#: largest panel aspect ratio (width / chordwise length) of the default spanwise count: half
#: the usual limit of 4, which the steady lift of low-aspect-ratio wings shows too coarse
#: (docs/validation.md, "Doublet-lattice aerodynamics")
MAX_ASPECT = 2.0
#: most panels of a half-wing (the mirrored AIC is (2n)² complex numbers per k)
MAX_PANELS = 2000


def panel_counts(wing, n_chord: int | None = None, n_span: int | None = None) -> tuple[int, int]:
    """(n_chord, n_span) of the wing's DLM mesh: the given counts (default the wing's
    ``dlm_chordwise_panels`` / ``dlm_spanwise_panels``), the spanwise one by default the fewest
    equal strips no wider than :data:`MAX_ASPECT` times the shortest panel length.
    InputError for a count < 1 or more than :data:`MAX_PANELS` panels."""
    n_chord = wing.dlm_chordwise_panels if n_chord is None else n_chord
    n_chord = v.integer_at_least("dlm_chordwise_panels", n_chord, 1)
    given = wing.dlm_spanwise_panels if n_span is None else n_span
    if given is None:
        c_min = float(np.min(2.0 * wing.node_properties()["b"]))
        given = int(np.ceil(wing.semi_span * n_chord / (MAX_ASPECT * c_min) - 1e-9))
    n_span = v.integer_at_least("dlm_spanwise_panels", given, 1)
    if n_chord * n_span > MAX_PANELS:
        raise v.InputError(
            f"dlm_chordwise_panels x dlm_spanwise_panels = {n_chord} x {n_span} = "
            f"{n_chord * n_span} panels is invalid: must be at most {MAX_PANELS} (give fewer "
            "panels, or dlm_spanwise_panels explicitly)")
    return n_chord, n_span


@dataclass(frozen=True)
class Wing:
    """Cantilever wing; SI units, chordwise positions as fractions of chord from the LE.

    A spanwise property (`mass_per_length`, `EI`, `GJ`, `polar_inertia`, `radius_of_gyration`,
    `elastic_axis`, `centre_of_gravity`, `aerodynamic_centre`, `EI_chordwise`) is a number
    (uniform), an array with one value per element, or a function of the spanwise position
    y [m]; element properties are taken at element mid-span, strip properties at the nodes.

    Parameters
    ----------
    semi_span : float
        Root-to-tip length [m].
    mass_per_length : float, array_like or callable
        Mass per unit span m_W [kg/m].
    EI, GJ : float, array_like or callable
        Bending and torsional rigidity [N m²].
    root_chord, tip_chord : float
        Chord at the root and at the tip [m] (linear taper; `tip_chord` None: the root chord).
    chord : callable, optional
        Chord [m] as a function of y [m], overriding `root_chord` and `tip_chord` (tabulated
        data: ``numpy.interp`` in a lambda); not saved in model files.
    polar_inertia : float, array_like or callable, optional
        ρI_p about the elastic axis [kg m]; or give `radius_of_gyration` instead.
    radius_of_gyration : float, array_like or callable, optional
        Radius of gyration about the centre of gravity [fraction of the chord].
    elastic_axis : float, array_like or callable
        Elastic-axis position [fraction of the chord from the LE] (0.5: mid-chord).
    centre_of_gravity : float, array_like or callable
        Centre-of-gravity position [fraction of the chord from the LE].
    lift_slope : float, "elliptic" or callable
        Section lift-curve slope C_lα [1/rad]: a number, "elliptic" (2π√(1−(y/L)²), eq. 7.81)
        or a function of y [m].
    aerodynamic_centre : float, array_like or callable
        Aerodynamic-centre position [fraction of the chord from the LE] (0.25: quarter chord,
        a_c = −1/2).
    n_elements : int
        Number of equal beam elements; with `stations`, the target count (each interval between
        stations gets ⌈length n_elements / semi_span⌉ equal elements); not used when
        `max_element_length` is given.
    stations : tuple of float, optional
        Spanwise positions [m] in (0, semi_span] that must be nodes (where properties change,
        where output is wanted); a :class:`~propwhirl.model.systems.PropellerWing` adds its
        propellers' positions.
    max_element_length : float, optional
        Longest element [m]; each interval between stations is divided evenly into the fewest
        elements not longer than it.
    aero_model : {"leishman-nguyen", "wagner"}
        Unsteady strip aerodynamics: 2 (Leishman–Nguyen) or 4 (Wagner) lag states per node.
    rayleigh : tuple of float
        (μ [1/s], λ [s]) of Rayleigh damping C = μM + λK (eq. 7.22); (0, 0): undamped.
    EI_chordwise : float, array_like or callable, optional
        In-plane (chordwise) bending rigidity [N m²]; given, the wing bends in its plane too
        (in-plane displacement v and slope χ per node, derivations/beam_inplane.py) and the
        propellers' side force, yaw and gyroscopic moments load it there; None (the default):
        rigid in its plane, the thesis's model.
    aero : {"strip", "dlm"}
        "strip" (default: Theodorsen strips at the nodes, finite-state lag states, the thesis's
        model) or "dlm" (doublet-lattice panels of the planform,
        :mod:`propwhirl.model.aerodynamics.dlm`: analysed by its Roger state space,
        :mod:`propwhirl.model.aerodynamics.dlm_rfa`, or by the p-k method with method "pk").
    dlm_chordwise_panels, dlm_spanwise_panels : int
        The doublet-lattice panel counts (aero = "dlm"); spanwise None: the fewest with a panel
        aspect ratio <= 2 (:func:`panel_counts`).
    dlm_mach : float or "speed"
        The Mach number of the doublet-lattice loads (aero = "dlm"): "speed" (the default;
        matched, V/a of each analysed speed: speeds beyond Mach 0.9 refused) or a number in
        [0, 0.9], the same Mach at every speed (non-matched: the usual way of published DLM
        flutter results, e.g. the Goland wing at Mach 0; one Mach column of AICs instead of one
        per Mach step crossed).
    compressibility : {"none", "prandtl-glauert"}
        Compressibility of the strip aerodynamics (aero = "strip"): "none" (the default,
        incompressible: the thesis's model) or "prandtl-glauert" (every strip's lift-curve
        slope divided by β = √(1 − M²) at the Mach of `strip_mach`,
        :mod:`propwhirl.model.aerodynamics.compressibility`).
    strip_mach : float or "speed"
        The Mach number of the Prandtl–Glauert strips, as `dlm_mach`: "speed" (the default;
        V/a of each analysed speed, up to Mach 0.9) or one number in [0, 0.9] for every speed.
    name : str
        Label.

    Raises
    ------
    InputError
        A value outside its range, a missing or doubly given property: one line naming it.

    Examples
    --------
    A uniform 6 m wing, its mesh holding a station at 4.5 m, and its first bending frequency
    against the beam's 1.875² √(EI/m) / (2π L²) = 1.554 Hz:

    >>> import math
    >>> from propwhirl.model import Wing
    >>> w = Wing(semi_span=6.0, mass_per_length=20.0, EI=2.0e5, GJ=1.0e5,
    ...          radius_of_gyration=0.25, n_elements=6, stations=(4.5,))
    >>> w.element_count, [round(float(y), 2) for y in w.node_y]
    (7, [0.0, 0.9, 1.8, 2.7, 3.6, 4.5, 5.25, 6.0])
    >>> from propwhirl.analysis.vibration import classify_wing_modes
    >>> name, omega = classify_wing_modes(w, 1)[0]
    >>> name, round(omega / (2 * math.pi), 3)
    ('bending 1', 1.554)
    """

    semi_span: float = field(metadata=spec("semi_span_m", "m", "root-to-tip length",
                                           range=(1e-2, 1e3)))
    mass_per_length: Spanwise = field(metadata=spec(
        "mass_per_length_kg_per_m", "kg/m", "mass per unit span m_W", form="spanwise",
        range=(1e-4, 1e5)))
    EI: Spanwise = field(metadata=spec("EI_N_m2", "N m^2", "bending rigidity", form="spanwise",
                                       range=(1e-3, 1e12)))
    GJ: Spanwise = field(metadata=spec("GJ_N_m2", "N m^2", "torsional rigidity", form="spanwise",
                                       range=(1e-3, 1e12)))
    root_chord: float = field(default=1.0, metadata=spec(
        "root_chord_m", "m", "chord at the root", default="physical", file_required=True,
        range=(1e-3, 1e2)))
    tip_chord: float | None = field(default=None, metadata=spec(
        "tip_chord_m", "m", "chord at the tip (linear taper); omitted: the root chord",
        default="none", range=(1e-3, 1e2)))
    chord: Callable[[np.ndarray], np.ndarray] | None = field(default=None, metadata=spec(
        None, "m", "chord as a function of y: not saved, use root_chord/tip_chord (linear taper)",
        default="none", form="unsaved", range=(1e-3, 1e2)))
    polar_inertia: Spanwise | None = field(default=None, metadata=spec(
        "polar_inertia_kg_m", "kg m", "polar inertia rho I_p about the elastic axis "
        "(or radius_of_gyration)", default="none", form="spanwise", range=(1e-8, 1e7)))
    radius_of_gyration: Spanwise | None = field(default=None, metadata=spec(
        "radius_of_gyration_chord", "chord", "radius of gyration about the centre of gravity "
        "(or polar_inertia)", default="none", form="spanwise", range=(1e-3, 1.0)))
    elastic_axis: Spanwise = field(default=0.5, metadata=spec(
        "elastic_axis_chord", "chord", "elastic-axis position", default="physical",
        form="spanwise", file_required=True, range=(0.0, 1.0)))
    centre_of_gravity: Spanwise = field(default=0.5, metadata=spec(
        "centre_of_gravity_chord", "chord", "centre-of-gravity position", default="physical",
        form="spanwise", file_required=True, range=(0.0, 1.0)))
    lift_slope: LiftSlope = field(default=TWO_PI, metadata=spec(
        "lift_slope_per_rad", "1/rad", "section lift-curve slope C_l_alpha, or \"elliptic\" "
        "(eq. 7.81); omitted: 2 pi (thin aerofoil)", default="physical", form="number_or_string",
        range=(0.0, 4.0 * np.pi), ends="(]"))
    aerodynamic_centre: Spanwise = field(default=0.25, metadata=spec(
        "aerodynamic_centre_chord", "chord", "aerodynamic-centre position; omitted: quarter "
        "chord (thin aerofoil)", default="physical", form="spanwise", range=(0.0, 1.0)))
    n_elements: int = field(default=20, metadata=spec(
        "n_elements", "", "number of equal beam elements; with stations_m, the target count "
        "(element length semi_span / n_elements); not used with max_element_length_m",
        default="setting"))
    stations: tuple[float, ...] | None = field(default=None, metadata=spec(
        "stations_m", "m", "spanwise positions that must be nodes (where properties change, "
        "where output is wanted; the propellers' positions are added); omitted: none",
        default="none", form="numbers", range=(0.0, 1e3), ends="(]"))
    max_element_length: float | None = field(default=None, metadata=spec(
        "max_element_length_m", "m", "longest beam element: each interval between stations "
        "divided evenly; omitted: semi_span / n_elements", default="none",
        range=(1e-4, 1e3)))
    aero_model: Literal["leishman-nguyen", "wagner"] = field(default="leishman-nguyen", metadata=spec(
        "aero_model", "", "unsteady strip aerodynamics: 2 (Leishman-Nguyen) or 4 (Wagner) lag "
        "states per node", default="setting"))
    rayleigh: tuple[float, float] = field(default=(0.0, 0.0), metadata=spec(
        ("rayleigh_mu_per_s", "rayleigh_lambda_s"), ("1/s", "s"),
        "Rayleigh damping C = mu M + lambda K (eq. 7.22); omitted: undamped (conservative)",
        default="physical", form="split", range=((0.0, 1e3), (0.0, 1.0))))
    EI_chordwise: Spanwise | None = field(default=None, metadata=spec(
        "EI_chordwise_N_m2", "N m^2", "in-plane (chordwise) bending rigidity: the wing bends "
        "in its plane too (in-plane displacement and slope per node); omitted: rigid in its "
        "plane (the thesis's model)", default="none", form="spanwise", range=(1e-3, 1e14)))
    aero: Literal["strip", "dlm"] = field(default="strip", metadata=spec(
        "aero", "", "wing aerodynamics: \"strip\" (Theodorsen strips, finite-state lag states; "
        "the thesis's) or \"dlm\" (doublet-lattice panels: Roger state space, or p-k with "
        "method pk; needs the dlm extra)", default="setting"))
    dlm_chordwise_panels: int = field(default=DEFAULT_CHORDWISE, metadata=spec(
        "dlm_chordwise_panels", "", "doublet-lattice panels along the chord (aero = \"dlm\")",
        default="setting"))
    dlm_mach: Union[float, Literal["speed"]] = field(default="speed", metadata=spec(
        "dlm_mach", "", "Mach number of the doublet-lattice loads (aero = \"dlm\"): "
        "\"speed\" (matched: V/a at each analysed speed) or one number for every speed "
        "(the non-matched analysis of most published DLM results)", default="setting",
        form="number_or_string", range=(0.0, DLM_MACH_MAX)))
    dlm_spanwise_panels: int | None = field(default=None, metadata=spec(
        "dlm_spanwise_panels", "", "doublet-lattice panels along the semi-span (aero = "
        "\"dlm\"); omitted: the fewest with a panel aspect ratio (width / length) <= 2",
        default="none"))
    compressibility: Literal["none", "prandtl-glauert"] = field(default="none", metadata=spec(
        "compressibility", "", "compressibility of the strip aerodynamics: \"none\" "
        "(incompressible, the thesis's) or \"prandtl-glauert\" (lift-curve slope C_l_alpha / "
        "sqrt(1 - M^2) at the Mach of strip_mach)", default="setting"))
    strip_mach: Union[float, Literal["speed"]] = field(default="speed", metadata=spec(
        "strip_mach", "", "Mach number of the Prandtl-Glauert strips (compressibility = "
        "\"prandtl-glauert\"), as dlm_mach: \"speed\" (matched: V/a at each analysed speed, "
        "up to Mach 0.9) or one number for every speed", default="setting",
        form="number_or_string", range=(0.0, DLM_MACH_MAX)))
    name: str = field(default="wing", metadata=spec("name", "", "label", default="setting"))
    _mesh: Mesh | None = field(default=None, init=False, repr=False, compare=False, metadata=spec(
        None, "", "the mesh (derived from the fields above)", default="none", form="derived"))

    def __post_init__(self) -> None:
        check_dlm_mach(self.dlm_mach)  # before check_fields: its own one-line message
        check_mach_setting("strip_mach", self.strip_mach)
        if not (isinstance(self.compressibility, str)
                and self.compressibility in ("none", "prandtl-glauert")):
            raise v.InputError(f"compressibility = {self.compressibility!r:.40} is invalid: must "
                               "be \"none\" (incompressible strips) or \"prandtl-glauert\" "
                               "(lift-curve slope / sqrt(1 - M^2))")
        check_fields(self)  # types and the declared ranges of every field
        v.integer_at_least("n_elements", self.n_elements, 1)
        limits.check_elements(self.n_elements)
        v.integer_at_least("dlm_chordwise_panels", self.dlm_chordwise_panels, 1)
        if self.dlm_spanwise_panels is not None:
            v.integer_at_least("dlm_spanwise_panels", self.dlm_spanwise_panels, 1)
        if self.stations is not None and len(self.stations) == 0:
            object.__setattr__(self, "stations", None)  # no stations (saved as an omitted key)
        object.__setattr__(self, "_mesh", meshing.build(
            self.semi_span, self.n_elements, self.stations or (), self.max_element_length))
        if (self.polar_inertia is None) == (self.radius_of_gyration is None):
            raise v.InputError("give exactly one of polar_inertia [kg m] or radius_of_gyration")
        # Evaluate everything once so bad input fails at construction, naming the parameter.
        self.element_properties()
        self.node_properties()
        self.inplane_properties()
        if self.aero == "dlm":                      # the panel counts, before any analysis
            panel_counts(self)

    # ------------------------------------------------------------------ discretisation
    @property
    def mesh(self) -> Mesh:
        """The mesh (:func:`propwhirl.model.structure.mesh.build`), built once on construction."""
        return self._mesh

    @property
    def uniform(self) -> bool:
        """True for the `n_elements` equal elements (no stations, no maximum length)."""
        return not self.stations and self.max_element_length is None

    @property
    def element_count(self) -> int:
        """Number of elements of the mesh (= `n_elements` without stations and maximum length)."""
        return self._mesh.n_elements

    @property
    def n_nodes(self) -> int:
        return self._mesh.n_elements + 1

    @property
    def node_y(self) -> np.ndarray:
        """Spanwise node positions [m], root (node 0) to tip (a copy)."""
        return self._mesh.node_y.copy()

    @property
    def element_length(self) -> np.ndarray:
        """Element lengths [m] (non-uniform with stations)."""
        return self._mesh.element_length

    @property
    def element_y(self) -> np.ndarray:
        """Element mid-span positions [m]."""
        return self._mesh.element_y

    def with_stations(self, stations, names=None, paths=None) -> "Wing":
        """This wing with the positions `stations` [m] added to its own stations (one already
        a station, or given twice, is added once); the mesh is rebuilt by the rule of
        :mod:`propwhirl.model.structure.mesh`.  Errors (outside (0, semi_span], an element too short)
        name a position by `names` (default ``stations[i]``) and carry `paths`."""
        own = tuple(self.stations or ())
        names = list(names) if names is not None else [
            f"stations[{len(own) + i}]" for i in range(len(stations))]
        paths = list(paths) if paths is not None else [(n,) for n in names]
        tol = meshing.tolerance(self.semi_span)
        extra: list[int] = []
        for i, y in enumerate(stations):
            meshing.check_station(names[i], y, self.semi_span, paths[i])
            if all(abs(y - s) > tol for s in own + tuple(stations[k] for k in extra)):
                extra.append(i)
        if not extra:
            return self
        new = tuple(float(stations[i]) for i in extra)
        meshing.build(self.semi_span, self.n_elements, own + new, self.max_element_length,
                      [f"stations[{i}]" for i in range(len(own))] + [names[i] for i in extra],
                      [("stations", i) for i in range(len(own))] + [paths[i] for i in extra])
        return replace(self, stations=own + new)

    def chord_at(self, y: np.ndarray) -> np.ndarray:
        """Local chord [m] at spanwise positions y [m]."""
        y = np.asarray(y, dtype=float)
        if self.chord is not None:
            c = _call("chord", self.chord, y)
            if c.shape != y.shape:
                raise v.InputError(f"chord(y) must return one value per position, got {c.shape}")
            return check_values(Wing, "chord", c, y)
        tip = self.root_chord if self.tip_chord is None else self.tip_chord
        return self.root_chord + (tip - self.root_chord) * y / self.semi_span

    # ------------------------------------------------------------------ properties
    def element_properties(self) -> dict[str, np.ndarray]:
        """Per-element beam properties at element mid-span (arguments of the beam element).

        Returns length [m], m [kg/m], rho_Ip [kg m] (about the elastic axis), x_alpha_b [m]
        (centre of gravity aft of the elastic axis), EI, GJ [N m²].
        """
        y, n = self.element_y, self.element_count
        c = self.chord_at(y)
        def prop(name: str, unit: str) -> np.ndarray:  # every value within the declared range
            return check_values(Wing, name, _spanwise(name, getattr(self, name), y, n, unit,
                                                      self.uniform), y)

        m = prop("mass_per_length", "kg/m")
        ea = prop("elastic_axis", "")
        cg = prop("centre_of_gravity", "")
        xab = (cg - ea) * c
        if self.polar_inertia is not None:
            Ip = prop("polar_inertia", "kg m")
        else:
            rg = prop("radius_of_gyration", "")
            Ip = m * ((rg * c) ** 2 + xab**2)  # parallel-axis theorem: about the elastic axis
        return {
            "length": self.element_length,
            "m": m,
            "rho_Ip": Ip,
            "x_alpha_b": xab,
            "EI": prop("EI", "N m^2"),
            "GJ": prop("GJ", "N m^2"),
        }

    @property
    def in_plane(self) -> bool:
        """True when the wing bends in its plane (`EI_chordwise` given)."""
        return self.EI_chordwise is not None

    def inplane_properties(self) -> dict[str, np.ndarray] | None:
        """Per-element in-plane beam properties (arguments of the generated in-plane element,
        derivations/beam_inplane.py), None when the wing is rigid in its plane.

        Returns length [m], m [kg/m], rho_Iz [kg m] (the in-plane rotary inertia about the
        vertical axis through the elastic axis: the polar inertia ρI_p, the thin-section value
        the derivation states) and EI_chordwise [N m²].
        """
        if self.EI_chordwise is None:
            return None
        p = self.element_properties()
        y, n = self.element_y, self.element_count
        EIc = check_values(Wing, "EI_chordwise", _spanwise(
            "EI_chordwise", self.EI_chordwise, y, n, "N m^2", self.uniform), y)
        return {"length": p["length"], "m": p["m"], "rho_Iz": p["rho_Ip"], "EI_chordwise": EIc}

    def node_properties(self) -> dict[str, np.ndarray]:
        """Per-node strip-aerodynamic properties (thesis §7.2, §7.5).

        Returns y [m], strip width [m] (tributary length: half of each adjacent element),
        b (semichord) [m], a (elastic axis, semichords aft of mid-chord), ac (aerodynamic
        centre, semichords aft of mid-chord) and Cla [1/rad] — read-only arrays, computed once
        per wing (every evaluation of a model's matrices asks for them).
        """
        return dict(self._node_properties)

    @functools.cached_property
    def _node_properties(self) -> dict[str, np.ndarray]:
        out = {k: np.array(x, dtype=float) for k, x in self._compute_node_properties().items()}
        for x in out.values():
            x.flags.writeable = False
        return out

    def _compute_node_properties(self) -> dict[str, np.ndarray]:
        y = self.node_y
        n = self.n_nodes
        c = self.chord_at(y)
        le = self.element_length
        width = np.zeros(n)
        width[:-1] += 0.5 * le
        width[1:] += 0.5 * le
        ea = check_values(Wing, "elastic_axis", _node_value(
            "elastic_axis", self.elastic_axis, y, self.element_y, self.uniform), y)
        xac = check_values(Wing, "aerodynamic_centre", _node_value(
            "aerodynamic_centre", self.aerodynamic_centre, y, self.element_y, self.uniform), y)
        return {
            "y": y,
            "width": width,
            "b": 0.5 * c,
            "a": 2.0 * ea - 1.0,
            "ac": 2.0 * xac - 1.0,
            "Cla": self.lift_slope_at(y),
        }

    def lift_slope_at(self, y: np.ndarray) -> np.ndarray:
        """Section lift-curve slope C_lα [1/rad] at y (eq. 7.81 for "elliptic")."""
        y = np.asarray(y, dtype=float)
        if isinstance(self.lift_slope, str):
            x = np.clip(y / self.semi_span, 0.0, 1.0)
            return TWO_PI * np.sqrt(1.0 - x**2)
        if callable(self.lift_slope):
            out = _call("lift_slope", self.lift_slope, y)
            if out.shape != y.shape:
                raise v.InputError(f"lift_slope(y) must return one value per position, got {out.shape}")
            return check_values(Wing, "lift_slope", out, y)
        return np.full(y.shape, float(self.lift_slope))


def _node_value(name: str, value: Spanwise, y_nodes: np.ndarray, y_elem: np.ndarray,
                uniform: bool = True) -> np.ndarray:
    """A spanwise property at the nodes: callables are evaluated there; per-element arrays are
    interpolated linearly between element mid-points (held constant beyond them)."""
    if callable(value):
        out = _call(name, value, y_nodes)
        if out.shape != y_nodes.shape:
            raise v.InputError(f"{name}(y) must return one value per position, got {out.shape}")
        return v.finite(name, out)
    arr = np.asarray(value, dtype=float)
    if arr.ndim == 0:
        return np.full(y_nodes.shape, v.finite(name, arr))
    if arr.shape != y_elem.shape:
        raise v.InputError(
            f"{name} has {arr.size} values but the wing has {_count_text(y_elem.size, uniform)}: "
            f"give a scalar, one value per element, or a function of y"
        )
    return np.interp(y_nodes, y_elem, v.finite(name, arr))
