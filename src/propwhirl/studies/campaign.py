"""A whirl-flutter clearance campaign: one model, its flight envelope, the failure cases, and
the verdict of a regulation for every (case, envelope point).

A :class:`Campaign` holds

* the model (any propeller-wing model; :func:`propwhirl.io.load_model`);
* the regulation's speed factor (:data:`propwhirl.certification.REGULATIONS`: CS 25.629 and
  14 CFR 25.629 1.15, 14 CFR 23.629 1.2, or an explicit factor) and, optionally, a damping
  requirement: the structural damping coefficient g = 2ζ of every oscillatory mode at least
  ``min_damping_g`` at every speed up to V_D;
* the envelope: :class:`EnvelopePoint` s, each an ISA altitude with its V_D as a true
  airspeed [m/s] (:func:`envelope`: V_D given as EAS is converted with the ISA density,
  V_TAS = V_EAS · sqrt(ρ0 / ρ(h)); an M_D limits it to M_D · a(h)).  The analyses'
  speeds are true airspeeds (:class:`propwhirl.model.flight.FlightCondition`);
* the cases: :class:`Case` s, named model transformations (mount stiffness and damping
  factors, the wing's structural damping, windmilling, feathered or stopped rotors, overspeed,
  reversed rotation, added masses, any parameter path of :mod:`propwhirl.studies.paths`),
  applied to the chosen propellers (numbered from 1; all by default).

:func:`run_campaign` checks every case and point first (:func:`tasks`: each case's model
built once, each altitude's flight condition and speed grid once; each bad case or point is a
one-line InputError before any analysis; a product's combinations are built with their
analyses, :func:`from_spec`), estimates the campaign's time as the studies do
(:func:`propwhirl.limits.check_study`), then runs one analysis per (case, point) with
:func:`propwhirl.studies.execution.map_analyses` (serial, local processes or Dask, a progress
bar, a partial-results file and resume).  Each point's result (:func:`evaluate_point`) holds
the critical instability (:func:`propwhirl.studies.critical.critical_instability`: kind, event,
mode, frequency, whirl sense, every propeller's share), V_crit, the required speed and its rule
(:meth:`Campaign.required_speed`: factor · V_D, or for a failure case of CS/14 CFR
25.629(b)(2) the greater of V_D and the 1.15 V_C / M_C + 0.05 line, :func:`failure_line`),
the margin V_crit − V_required [m/s] and [%], the least damping g = 2ζ of the oscillatory
modes (those with an event and the :data:`DAMPING_MODES` of lowest frequency) up to the required speed and up to V_D (with mode and speed), and the slope dζ/dV [s/m]
of the least damped mode at the required speed ("rapid loss of stability").  A point clears
when no counted instability lies at or below the required speed and, with a damping
requirement, the least damping up to V_D meets it; a case clears when all its points do.
"""
from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from propwhirl import certification, limits
from propwhirl import validate as v
from propwhirl.certification import (  # noqa: F401 (REGULATIONS, regulation_factor re-exported)
    CASE_FACTORS, FACTOR_CS25, FACTOR_RANGE, OPERATIONS, PART25, REGULATIONS, STATES,
    regulation_factor)
from propwhirl.analysis.damping_requirement import DampingRequirement, judged_damping
from propwhirl.analysis.margin import DAMPING_MODES  # noqa: F401 (re-exported)
from propwhirl.analysis.margin import least_damping as _least
from propwhirl.analysis.margin import oscillatory_damping as _damping
from propwhirl.analysis.naming import real_root_at_the_event
from propwhirl.analysis.reduced import choose_method
from propwhirl.analysis.stability import analyse
from propwhirl.model.aerodynamics.dlm import DlmTables
from propwhirl.model.aerodynamics.validity import has_aerodynamics
from propwhirl.model.flight import FlightCondition
from propwhirl.progress import ProgressCallback
from propwhirl.studies import execution
from propwhirl.studies.clearance import clearance_speeds, speed_grid
from propwhirl.studies.critical import convention, critical_instability, wing_divergence_predicate
from propwhirl.studies.flight_envelope import (  # noqa: F401 (re-exported)
    AIRSPEEDS, DELTA_M_C, RHO0, EnvelopePoint, envelope, failure_line, mach_eas, true_airspeed)
from propwhirl.studies.campaign_result import (  # noqa: F401 (re-exported)
    CampaignResult, CaseSummary, PointPlot, PointRow)

from propwhirl.studies.campaign_cases import (  # noqa: F401 (re-exported)
    FAILURE_KINDS, Case, product)


# ============================================================================== campaign
@dataclass(frozen=True)
class Campaign:
    """Everything a campaign runs (module docstring).

    factor: the speed factor [-] (:data:`~propwhirl.certification.REGULATIONS` or explicit);
    regulation: its name ("cs25", "far25", "far23" or "explicit"); min_damping_g: the least
    g = 2ζ required up to V_D (None: no damping requirement); static_divergence, low_speed: the
    convention (:func:`propwhirl.studies.critical.critical_instability`); xtol: accuracy of
    each critical speed [m/s].

    Parameters
    ----------
    name : str
        The campaign's name.
    model : Model
        The nominal model.
    cases : tuple of Case
        The failure cases (at least one; unique names).
    points : tuple of EnvelopePoint
        The envelope points (:func:`envelope`): ISA altitude [m], V_D [m/s].
    regulation : {"cs25", "far25", "far23", "explicit"}
        The regulation of `factor`.
    factor : float
        The speed factor [-], in [1, 3] (1.15: CS/FAR 25.629).
    min_damping_g : float, optional
        The least g = 2ζ [-] required up to V_D (None: no damping requirement).
    static_divergence, low_speed : bool
        The convention (:func:`propwhirl.studies.critical.critical_instability`).
    xtol : float
        Accuracy of each critical speed [m/s].
    damping : DampingRequirement, optional
        How the damping requirement is read (which damping, above which speed [m/s], which
        modes, its source; :mod:`propwhirl.analysis.damping_requirement`); None with
        `min_damping_g`: the total damping of every mode of interest up to V_D.

    Examples
    --------
    >>> from propwhirl.studies import Campaign, Case, envelope
    >>> from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
    >>> c = Campaign("demo", wingtip_propeller_wing(), (Case("nominal"),),
    ...              envelope(100.0, [0.0, 5000.0]))
    >>> c.factor, c.convention
    (1.15, 'every instability counts (propwhirl.analysis.critical)')
    """

    name: str
    model: Any
    cases: tuple[Case, ...]
    points: tuple[EnvelopePoint, ...]
    regulation: str = "cs25"
    factor: float = FACTOR_CS25
    min_damping_g: float | None = None
    static_divergence: bool = True
    low_speed: bool = True
    xtol: float = 0.01
    #: how the damping requirement is read (:class:`DampingRequirement`: which damping, above
    #: which speed, which modes, its source); None with `min_damping_g`: the total damping of
    #: every mode of interest at every analysed speed up to V_D, its source not given
    damping: DampingRequirement | None = None
    #: the names of the cases whose model is built with their analyses, not before (the
    #: combinations of a product: :func:`from_spec`); the others are built by :func:`tasks`
    _deferred: frozenset = field(default=frozenset(), repr=False, compare=False)
    #: what :func:`tasks` made once: each case's model (by name), the tasks and their keys
    #: (not an argument: a campaign made with ``dataclasses.replace`` starts afresh)
    _made: dict = field(default_factory=dict, init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        for key, kind, what in (("cases", Case, "Case"), ("points", EnvelopePoint,
                                                          "EnvelopePoint (envelope(...))")):
            x = getattr(self, key)
            if not isinstance(x, (tuple, list)) or not all(isinstance(i, kind) for i in x):
                raise v.fail(key, x, f"invalid: must be a tuple of {what}")
            object.__setattr__(self, key, tuple(x))
        if not self.cases:
            raise v.InputError("a campaign needs at least one case")
        if not self.points:
            raise v.InputError("a campaign needs at least one envelope point")
        seen: set[str] = set()
        for c in self.cases:
            if c.name in seen:
                raise v.InputError(f"case name {c.name!r} is given twice: every case needs its "
                                   "own name")
            seen.add(c.name)
        if not isinstance(self.name, str):
            raise v.fail("name", self.name, f"invalid: must be a str, got {type(self.name).__name__}")
        for key in ("static_divergence", "low_speed"):
            v.boolean(key, getattr(self, key))
        v.in_range("factor", self.factor, *FACTOR_RANGE)
        if self.regulation not in PART25 and any(p.V_line is not None for p in self.points):
            raise v.InputError(f"V_C is invalid with regulation {self.regulation!r}: the "
                               "failure-case envelope (V_C, M_C) is 25.629(b)(2)'s (cs25, far25); "
                               f"under {self.regulation!r} every case is held to "
                               f"{self.factor:g} V_D")
        if self.min_damping_g is not None:
            v.in_range("min_damping_g", self.min_damping_g, 0.0, 1.0)
        if self.damping is not None:
            if not isinstance(self.damping, DampingRequirement):
                raise v.fail("damping", self.damping, "invalid: must be a DampingRequirement "
                             "or None")
            if self.min_damping_g is None:
                object.__setattr__(self, "min_damping_g", self.damping.g_min)
            elif self.min_damping_g != self.damping.g_min:
                raise v.InputError(f"min_damping_g = {self.min_damping_g!r} differs from the "
                                   f"damping requirement's g_min = {self.damping.g_min!r}: "
                                   "give one")
        v.positive("xtol", self.xtol, "m/s")

    @property
    def convention(self) -> str:
        return convention(self.static_divergence, self.low_speed)

    def required_speed(self, case: Case, p: EnvelopePoint) -> tuple[float, str]:
        """The speed [m/s, TAS] `case` must clear at point `p`, and the rule that sets it:
        :func:`propwhirl.certification.required_speed` (the one definition) of the point's V_D,
        the campaign's factor and regulation, whether the case is a failure
        (:attr:`Case.is_failure`) and the point's failure-case line (:func:`failure_line`):
        "25.629(b)(1) 1.15 V_D", "23.629 1.2 V_D", "1.25 V_D", "25.629(b)(2)(i) V_D",
        "25.629(b)(2)(ii) 1.15 V_C", ...)."""
        return certification.required_speed(
            p.V_D, self.factor, self.regulation, failure=case.is_failure, V_line=p.V_line,
            line_part=p.line_part, mach_limited=p.mach_limited)

    @property
    def damping_requirement(self) -> DampingRequirement | None:
        """The damping requirement as judged (`damping`, or with `min_damping_g` alone the
        total damping of every mode at every speed up to V_D); None without one."""
        if self.min_damping_g is None:
            return None
        return self.damping or DampingRequirement(self.min_damping_g)


def required_speed(c: Campaign, case: Case, p: EnvelopePoint) -> tuple[float, str]:
    """The speed [m/s, TAS] case `case` must clear at point `p` of campaign `c`, and the rule
    that sets it: :meth:`Campaign.required_speed` (kept for callers of this function)."""
    return c.required_speed(case, p)


def at_altitude(model: Any, altitude_m: float) -> Any:
    """The model at the ISA altitude [m] (density and speed of sound; its speed grid kept)."""
    fc = FlightCondition.from_altitude(altitude_m, speed_range=tuple(model.flight.speed_range))
    return dataclasses.replace(model, flight=fc)


def from_spec(spec: Any) -> Campaign:
    """The :class:`Campaign` of a campaign file read by
    :func:`propwhirl.io.campaign_files.load_campaign` (a ``CampaignSpec``): its cases made
    (``each_propeller`` expanded, a product of the groups), its envelope points, every case as
    written built once and every point's speed grid checked (:func:`tasks`) — so every error
    comes now, before any analysis, one line starting with the file's name and naming the
    case's table.  The combinations of a product (of two groups or more) are checked for what
    needs no model (:meth:`Case.check`) and built with their analyses: one the model refuses
    as a whole is recorded in its rows, as a sweep's refused point is.

    Parameters
    ----------
    spec : CampaignSpec
        A campaign file as read (:func:`propwhirl.io.campaign_files.load_campaign` or its
        ``loads``; docs/campaign.md: V_D [m/s], altitudes [m], ...).

    Returns
    -------
    Campaign
        The campaign, ready for :func:`run_campaign`.

    Raises
    ------
    InputError
        A case that cannot be built at a point, naming the file and the case.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> from propwhirl.io import save_model
    >>> from propwhirl.io.campaign_files import loads
    >>> from propwhirl.studies import from_spec
    >>> from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
    >>> text = '''
    ... format = "propwhirl-campaign"
    ... format_version = 1
    ... name = "demo"
    ... model = "wingtip.toml"
    ... [regulation]
    ... name = "cs25"
    ... [envelope]
    ... airspeed = "EAS"
    ... V_D_m_per_s = 100.0
    ... altitudes_m = [0.0, 5000.0]
    ... [[cases]]
    ... name = "nominal"
    ... [[cases]]
    ... name = "soft mounts"
    ... mount_stiffness = 0.5
    ... '''
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     _ = save_model(wingtip_propeller_wing(), pathlib.Path(folder) / "wingtip.toml")
    ...     c = from_spec(loads(text, base=folder))
    >>> [case.name for case in c.cases], [round(p.V_D, 1) for p in c.points], c.factor
    (['nominal', 'soft mounts'], [100.0, 129.0], 1.15)
    """
    missing = [k for k in _SPEC_FIELDS if not hasattr(spec, k)]
    if missing or not isinstance(getattr(spec, "source", None), str):
        raise v.fail("spec", spec, "invalid: must be a CampaignSpec, as "
                     "propwhirl.io.campaign_files.load_campaign(path) or loads(text) read it, "
                     f"got {type(spec).__name__}")
    try:
        return _from_spec(spec)
    except v.InputError as exc:
        raise v.InputError(f"{spec.source}: {' '.join(str(exc).split())}") from None


#: What :func:`from_spec` reads of a ``CampaignSpec`` (:mod:`propwhirl.io.campaign_files`,
#: above the studies: known here by its fields).
_SPEC_FIELDS = ("source", "name", "model", "convention", "combine", "regulation", "factor",
                "min_damping_g", "airspeed", "V_D", "altitudes_m", "M_D", "cases", "V_C", "M_C")


def _from_spec(spec: Any) -> Campaign:
    n = len(spec.model.propellers)
    groups: dict[str, list[Case]] = {}
    cases: list[Case] = []
    models: dict[str, Any] = {}
    for cs in spec.cases:
        try:
            which = [(i,) for i in (cs.propellers or range(1, n + 1))] if cs.each_propeller \
                else [cs.propellers]
            made = [Case(f"{cs.name} (propeller {p[0]})" if cs.each_propeller else cs.name, p,
                         **cs.transform) for p in which]
            for c in made:                 # each case as written, built once and checked
                models[c.name] = c.apply(spec.model)
        except v.InputError as exc:
            raise v.InputError(f"[{cs.table}] {exc}") from None
        groups.setdefault(cs.group, []).extend(made)
        cases.extend(made)
    deferred: frozenset = frozenset()
    if spec.combine == "product":
        cases = list(product(list(groups.values())))
        for c in cases:                    # what a combination is refused for, without a model
            c.check(spec.model)
        if len(groups) > 1:                # the combinations: built with their analyses
            deferred, models = frozenset(c.name for c in cases), {}
    seen: set[str] = set()
    for c in cases:
        if c.name in seen:
            raise v.InputError(f"[[cases]] name {c.name!r} is given twice: every case needs its "
                               "own name")
        seen.add(c.name)
    thesis = spec.convention == "thesis"
    try:
        points = envelope(spec.V_D, spec.altitudes_m, airspeed=spec.airspeed, M_D=spec.M_D,
                          V_C=spec.V_C, M_C=spec.M_C)
    except v.InputError as exc:
        raise v.InputError(f"[envelope] {exc}") from None
    damping = getattr(spec, "damping", None)     # [regulation] damping = {...}
    camp = Campaign(spec.name, spec.model, tuple(cases), points,
                    spec.regulation, spec.factor, spec.min_damping_g,
                    static_divergence=not thesis, low_speed=not thesis, _deferred=deferred,
                    damping=None if damping is None else DampingRequirement(
                        spec.min_damping_g, **damping))
    for name, m in models.items():
        camp._made[("model", name)] = m
    tasks(camp)          # every case's model and every point's speed grid checked now
    return camp


@dataclass(frozen=True)
class _Task:
    """One analysis of a campaign: a (case, point), its speeds and the requirement.

    Its model (:meth:`build`, :attr:`model`) is `source` at the flight condition `flight` of
    the ISA `altitude_m` — `source` the case's model, built once for all the points; or, for
    a combination of a product (`case` given), the campaign's model, which `case` transforms
    when the analysis needs it (so expanding a campaign builds no model per task).  Without
    `flight`, `source` is the model itself.  `tables`: the campaign's doublet-lattice tables,
    shared by its analyses (one set of AICs per planform; sent to a worker process empty)."""

    source: Any
    speeds: np.ndarray
    V_D: float
    V_required: float
    xtol: float
    static_divergence: bool
    low_speed: bool
    case: Case | None = None
    flight: FlightCondition | None = None
    altitude_m: float | None = None
    tables: DlmTables | None = field(default=None, compare=False, repr=False)

    def build(self) -> tuple[Any, np.ndarray]:
        """(the model, its speed grid) of this task (an InputError naming the case when a
        combination is one the model refuses)."""
        m = self.source if self.case is None else self.case.apply(self.source)
        if self.flight is None:
            return m, self.speeds
        if tuple(m.flight.speed_range) == tuple(self.flight.speed_range):
            return dataclasses.replace(m, flight=self.flight), self.speeds

        m = at_altitude(m, float(self.altitude_m))
        return m, clearance_speeds(m, self.V_required)

    @property
    def model(self) -> Any:
        """The task's model (:meth:`build`)."""
        return self.build()[0]


def _case_model(c: Campaign, case: Case) -> Any:
    """`case`'s model (the campaign's model transformed), built once per campaign."""
    key = ("model", case.name)
    if key not in c._made:
        c._made[key] = case.apply(c.model)
    return c._made[key]


def tasks(c: Campaign) -> tuple[list[_Task], list[str]]:
    """Every (case, point) task, case-major, and its key ("case @ altitude"), made once per
    campaign: every case's model built once (a product's combinations: checked without a
    model, built with their analyses), every point's flight condition once, every speed grid
    checked once per distinct (speed range, speed of sound, required speed) — the work grows
    with the cases plus the points, the bookkeeping alone with the tasks; all before any
    analysis."""

    if "tasks" in c._made:
        return list(c._made["tasks"]), list(c._made["keys"])
    out, keys = [], []
    flights: dict[tuple, FlightCondition] = {}
    grids: dict[tuple, np.ndarray] = {}
    common = (c.xtol, c.static_divergence, c.low_speed)
    tables = DlmTables()                      # the campaign's: one set of AICs per planform
    for case in c.cases:
        deferred = case.name in c._deferred
        source = c.model if deferred else _case_model(c, case)
        span = tuple(float(x) for x in source.flight.speed_range)
        aero = True if deferred else has_aerodynamics(source)   # a combination: checked as if
        for p in c.points:
            fc = flights.get((p.altitude_m, span))
            if fc is None:
                fc = flights[p.altitude_m, span] = FlightCondition.from_altitude(
                    p.altitude_m, speed_range=span)
            V_req, _ = c.required_speed(case, p)
            key = (span, aero, float(fc.speed_of_sound), V_req)
            grid = grids.get(key)
            if grid is None:
                try:
                    grid = grids[key] = speed_grid(span, V_req, fc.speed_of_sound, aero)
                except v.InputError as exc:
                    raise v.InputError(f"case {case.name!r} at {p.altitude_m:g} m: {exc}") \
                        from None
                grid.flags.writeable = False
            out.append(_Task(source, grid, p.V_D, V_req, *common,
                             case if deferred else None, fc, p.altitude_m, tables))
            keys.append(f"{case.name} @ {p.altitude_m!r} m")
    c._made["tasks"], c._made["keys"] = tuple(out), tuple(keys)
    return out, keys


# ============================================================================== one point
def _at(zeta: np.ndarray, dzeta: np.ndarray, V: np.ndarray, speed: float,
        labels: Sequence[str]) -> dict[str, Any]:
    """The least damped oscillatory mode at `speed` [m/s] (linear interpolation between the
    sweep's speeds): {zeta, dzeta_dV, mode}."""
    j = int(np.searchsorted(V, speed))
    j = min(max(j, 1), len(V) - 1)
    w = (speed - V[j - 1]) / (V[j] - V[j - 1]) if V[j] > V[j - 1] else 1.0
    z = (1 - w) * zeta[j - 1] + w * zeta[j]
    dz = (1 - w) * dzeta[j - 1] + w * dzeta[j]
    if not np.isfinite(z).any():
        return {"zeta": None, "dzeta_dV": None, "mode": ""}
    k = int(np.nanargmin(z))
    return {"zeta": float(z[k]), "dzeta_dV": float(dz[k]), "mode": labels[k]}


def _event_vector(a: Any, e: Any) -> tuple[np.ndarray, complex, float] | None:
    """(eigenvector, eigenvalue, V [m/s]) of event `e` of analysis `a`: the refined critical
    point's, else the tracked mode's at the nearest sweep speed; None when there is none."""
    if e is None:
        return None
    if a.criticals is not None:
        for p in a.criticals.points:
            if p.mode == e.mode and abs(p.V - e.V) <= 1e-9 * max(1.0, abs(e.V)):
                return np.asarray(p.eigenvector), complex(p.eigenvalue), float(p.V)
    if a.sweep.eigenvectors is not None:
        t = int(np.argmin(np.abs(a.sweep.V - e.V)))
        return (a.sweep.eigenvectors[t, :, e.mode], complex(a.sweep.eigenvalues[t, e.mode]),
                float(a.sweep.V[t]))
    return None


def _critical_shape(a: Any, e: Any) -> dict[str, Any] | None:
    """The shape of the critical instability `e` of analysis `a` (:class:`PointPlot`'s
    ``shape``): :func:`_event_vector`; None when there is none."""
    dm = a.dof_map
    found = None if dm is None else _event_vector(a, e)
    if found is None:
        return None
    x, lam, Ve = found
    x = np.asarray(x, dtype=complex).ravel()[: dm.n_dof]
    motions = dm.whirling()              # own θ, ψ DOFs, or a modal structure's hub grids
    shown = x[[i for i, k in enumerate(dm.q_kinds) if k in ("h", "alpha", "theta", "psi")]]
    shown = np.concatenate([shown, *(p.pitch_yaw(x) for p in motions if p.dofs is None)])
    if not shown.size or not np.abs(shown).max() > 0:
        return None
    x = x / shown[int(np.argmax(np.abs(shown)))]
    return {"V": Ve, "eigenvalue": lam, "y": np.asarray(dm.node_y, dtype=float),
            "h": dm.wing_values(x, "h"), "alpha": dm.wing_values(x, "alpha"),
            "propellers": [(p.number + 1, p.y, *p.pitch_yaw(x)) for p in motions]}


def plot_data(a: Any, modes: Sequence[int], e: Any) -> dict[str, Any]:
    """What the report draws of analysis `a` (:class:`PointPlot` as plain JSON): the V-g-f
    curves of `modes` at the sweep's speeds, their instabilities, the critical mode's shape."""
    sw = a.sweep
    ids = list(modes)
    lam = np.asarray(sw.eigenvalues)[:, ids]
    mag = np.abs(lam)
    osc = np.asarray(sw.physical, dtype=bool)[:, ids] & (lam.imag > 1e-9 * np.maximum(mag, 1.0))
    dlam = np.asarray(sw.dlam_dV)[:, ids]
    m = np.where(mag > 0, mag, 1.0)
    zeta = np.where(osc, -lam.real / m, 0.0)
    freq = np.where(osc, lam.imag / (2.0 * np.pi), 0.0)
    dmag = (lam.real * dlam.real + lam.imag * dlam.imag) / m        # d|λ|/dV
    dzeta = np.where(osc, -(dlam.real * m - lam.real * dmag) / m**2, 0.0)
    dfreq = np.where(osc, dlam.imag / (2.0 * np.pi), 0.0)
    finite = np.isfinite(dzeta) & np.isfinite(dfreq)
    osc, dzeta, dfreq = osc & finite, np.where(finite, dzeta, 0.0), np.where(finite, dfreq, 0.0)
    events = tuple((float(ev.V), float(ev.frequency_hz), ev.kind, ev.event, ev.label)
                   for ev in a.events if ev.mode in ids)
    return PointPlot(np.asarray(sw.V, dtype=float), tuple(sw.mode_labels[k] for k in ids), zeta,
                     freq, osc, dzeta, dfreq, events, _critical_shape(a, e)).to_dict()


def evaluate_point(task: _Task) -> dict[str, Any]:
    """Analyse one (case, point) and return its result row (plain JSON: module docstring),
    with the campaign's doublet-lattice tables (``task.tables``)."""

    model, speeds = task.build()
    a = analyse(model, speeds, xtol=task.xtol, compressibility_check=False,  # no warnings kept
                dlm_tables=task.tables)
    is_wing = wing_divergence_predicate(model, a)
    e = critical_instability(a, static_divergence=task.static_divergence,
                             low_speed=task.low_speed, is_wing_divergence=is_wing)
    sweep = a.sweep
    V = np.asarray(sweep.V, dtype=float)
    labels = tuple(sweep.mode_labels)
    interest = a.modes_of_interest(DAMPING_MODES)
    zeta, dzeta = _damping(sweep, interest)
    least_req = _least(zeta, V, task.V_required, labels)
    least_vd = _least(zeta, V, task.V_D, labels)
    slope = _at(zeta, dzeta, V, task.V_required, labels)
    shares = []
    if e is not None and e.participation is not None:
        shares = [[int(p.propeller), float(p.share), p.whirl or ""]
                  for p in e.participation.propellers]
    Vc = None if e is None else float(e.V)
    mode = "" if e is None else e.label
    if e is not None and e.kind == "divergence" and mode.startswith("lag "):
        found = _event_vector(a, e)       # a real root from a lag state: name it at the event
        if found is not None:
            mode = real_root_at_the_event(model, mode, found[0], found[2])
    return {
        "critical_speed": Vc,
        "kind": "none" if e is None else e.kind,
        "event": "" if e is None else e.event,
        "mode": mode,
        "frequency_hz": None if e is None else float(e.frequency_hz),
        "whirl": "" if e is None or e.whirl is None else e.whirl,
        "propeller_shares": shares,
        "analysed_to": float(V[-1]),
        "least_zeta": least_req["zeta"], "least_zeta_V": least_req["V"],
        "least_zeta_mode": least_req["mode"],
        "least_zeta_to_V_D": least_vd["zeta"], "least_zeta_to_V_D_mode": least_vd["mode"],
        "zeta_at_required": slope["zeta"], "dzeta_dV_at_required": slope["dzeta_dV"],
        "mode_at_required": slope["mode"],
        "plot": plot_data(a, interest, e),
    }


def _row(c: Campaign, case: Case, p: EnvelopePoint, r: Any) -> PointRow:
    """The :class:`PointRow` of one point's result `r` (a dict of :func:`evaluate_point` or a
    TaskError)."""
    V_req, rule = c.required_speed(case, p)
    base = dict(case=case.name, description=case.describe(), altitude_m=p.altitude_m,
                airspeed=p.airspeed, V_D_given=p.V_D_given, V_D=p.V_D,
                mach_limited=p.mach_limited, V_required=V_req, rule=rule)
    if isinstance(r, execution.TaskError):
        return PointRow(**base, cleared=False, reason="analysis failed",
                        critical_speed=None,
                        margin_m_per_s=None, margin_percent=None, kind="error", event="",
                        mode="", frequency_hz=None, whirl="", propeller_shares=(),
                        analysed_to=None, least_g=None, least_g_V=None, least_g_mode="",
                        least_g_to_V_D=None, least_g_to_V_D_mode="", g_at_required=None,
                        dzeta_dV_at_required=None, mode_at_required="", error=str(r))
    Vc = r["critical_speed"]
    g = (lambda z: None if z is None else 2.0 * z)
    reasons = []
    if Vc is not None and not Vc > V_req:
        reasons.append(f"speed: {r['kind']} of {r['mode']} at {Vc:.2f} m/s <= {V_req:.2f} m/s"
                       + (f" ({rule})" if rule else ""))
    least_vd = g(r["least_zeta_to_V_D"])
    plot = None if r.get("plot") is None else PointPlot.from_dict(r["plot"])
    req = c.damping_requirement
    judged = {"g": None, "V": None, "mode": ""}
    if req is not None and plot is not None:
        judged = judged_damping(plot.V, plot.zeta, plot.oscillatory, plot.modes,
                                [ev[4] for ev in plot.events if ev[2] == "flutter"], p.V_D,
                                req.applies_to, req.above_m_per_s, req.modes)
    if req is not None and (judged["g"] is None or judged["g"] < req.g_min):
        reasons.append(f"damping: {req.applies_to} g = " + (
            f"{judged['g']:.4f} < {req.g_min:g} at {judged['V']:.2f} m/s ({judged['mode']})"
            if judged["g"] is not None else f"? < {req.g_min:g}: no judged mode up to V_D")
            + (f", required from {req.above_m_per_s:g} m/s" if req.above_m_per_s > 0 else ""))
    return PointRow(
        **base, cleared=not reasons, reason="; ".join(reasons), critical_speed=Vc,
        margin_m_per_s=None if Vc is None else Vc - V_req,
        margin_percent=None if Vc is None else 100.0 * (Vc / V_req - 1.0),
        kind=r["kind"], event=r["event"], mode=r["mode"], frequency_hz=r["frequency_hz"],
        whirl=r["whirl"], propeller_shares=tuple((int(a), float(b), str(w))
                                                 for a, b, w in r["propeller_shares"]),
        analysed_to=r["analysed_to"], least_g=g(r["least_zeta"]), least_g_V=r["least_zeta_V"],
        least_g_mode=r["least_zeta_mode"], least_g_to_V_D=least_vd,
        least_g_to_V_D_mode=r["least_zeta_to_V_D_mode"], g_at_required=g(r["zeta_at_required"]),
        dzeta_dV_at_required=r["dzeta_dV_at_required"], mode_at_required=r["mode_at_required"],
        error="", plot=plot, damping_g=judged["g"], damping_g_V=judged["V"],
        damping_g_mode=judged["mode"])


def run_campaign(c: Campaign, *, processes: int = 1, client=None,
                 progress: bool | ProgressCallback | None = None,
                 checkpoint: execution.Checkpoint | None = None) -> CampaignResult:
    """Run every (case, point) of `c` (module docstring).

    processes, client, progress: :func:`propwhirl.studies.execution.map_analyses`;
    checkpoint: the partial-results file (its fingerprint gets the content of the model,
    the cases, the points and the regulation, which decide every task: a file of another
    campaign is refused).  Before the first analysis the campaign's time and memory are
    estimated (:func:`propwhirl.limits.check_study`: printed before a long one when `progress`
    is True; one beyond the study time limit refused).  A point whose analysis fails is
    recorded (not cleared, its message in ``error``); the others go on.

    Parameters
    ----------
    c : Campaign
        The campaign.
    processes : int
        Local worker processes.
    client : dask.distributed.Client or str, optional
        Run on that cluster (or scheduler address).
    progress : bool or callable, optional
        A progress bar (True) or ``report(done, total)``.
    checkpoint : Checkpoint, optional
        The partial-results file.

    Returns
    -------
    CampaignResult
        One row per (case, point): verdict, critical speed [m/s], margins [m/s, %], least
        damping g [-], ...; ``cleared`` when every row clears.

    Examples
    --------
    The baseline wing on 4 elements with its tip propeller, 100–200 m/s, the thesis's
    convention (the wing's divergence left out), V_D = 120 m/s EAS at two altitudes:

    >>> from propwhirl.studies import Campaign, Case, envelope, run_campaign
    >>> from propwhirl.model import FlightCondition, Installation, PropellerWing
    >>> from propwhirl.cases.ch09_baseline import baseline_propeller, baseline_wing
    >>> model = PropellerWing(baseline_wing(n_elements=4),       # 4 elements, 100-200 m/s
    ...                       FlightCondition(0.96287, speed_range=(100.0, 200.0, 20.0)),
    ...                       (Installation(baseline_propeller(), 5.7),))
    >>> c = Campaign("demo", model, (Case("nominal"), Case("soft mounts", mount_stiffness=0.5)),
    ...              envelope(120.0, [0.0, 3000.0]), static_divergence=False)
    >>> r = run_campaign(c)
    >>> r.cleared, len(r.rows), r.analyses
    (True, 4, 4)
    >>> [(row.case, row.altitude_m, round(row.critical_speed, 1)) for row in r.rows][:2]
    [('nominal', 0.0, 145.4), ('nominal', 3000.0, 164.1)]
    """
    if not isinstance(c, Campaign):
        raise v.fail("run_campaign: c", c, "invalid: must be a propwhirl.studies.campaign.Campaign "
                     f"(from_spec(load_campaign(path)), or Campaign(...)), got {type(c).__name__}")
    limits.check_study(c.model, len(c.cases) * len(c.points), processes,
                       method=choose_method(c.model, "auto"), cluster=client is not None,
                       progress=progress)
    todo, keys = tasks(c)
    if checkpoint is not None:   # the tasks follow from these (and the version): one digest
        checkpoint = checkpoint.with_entries(
            study="campaign", convention=c.convention, factor=float(c.factor),
            min_damping_g=c.min_damping_g,
            tasks=execution.content_digest(["campaign", c.model, list(c.cases),
                                            list(c.points), c.regulation, c.xtol]))
    results = execution.map_analyses(evaluate_point, todo, processes, client=client,
                                     progress=progress, errors="record", checkpoint=checkpoint,
                                     keys=keys, desc="campaign")
    it = iter(results)
    rows = tuple(_row(c, case, p, next(it)) for case in c.cases for p in c.points)
    req = c.damping_requirement
    return CampaignResult(c.name, str(getattr(c.model, "name", "")), c.regulation,
                          float(c.factor), c.min_damping_g, c.convention, rows, len(todo),
                          damping=None if c.damping is None else c.damping.to_dict(),
                          damping_text="" if req is None else req.describe())
