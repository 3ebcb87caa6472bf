"""Verification runs of exact sensitivities: central differences of the critical speed.

An aeroelastician checks an exact derivative against a finite difference before trusting it.
For each parameter p of a :class:`~propwhirl.analysis.sensitivity.CriticalSensitivities`,
:func:`verify_sensitivities` analyses the model at p + h and p − h, with the same method, speed
grid and crossing accuracy as the analysis the sensitivities came from, finds the same critical
event in both (same kind and event; the same mode name, nearest the exact critical speed), and
forms the central difference

    dV/dp ≈ (V(p + h) − V(p − h)) / 2h       [m/s per unit of p],

h = δ |p| (δ = :data:`REL_STEP` = 1e-3 relative), or δ s for a parameter whose value is 0 and
which has a scale s (a position: the propeller radius, the chord; :func:`~propwhirl.analysis.
sensitivity.scale_of`), or δ in p's own unit when neither.  The truncation error is of order δ²
(1e-6 relative); the rounding error is the crossings' accuracy divided by 2h.

Every one of the 2N analyses runs in ONE batch through
:func:`propwhirl.studies.execution.map_analyses` (in this process, on local processes or on a
Dask cluster, with a progress bar); a variant that cannot be built (a value outside a field's
range, a path the model cannot set) or analysed is recorded in its parameter's row, never
dropped, and the others go on.

The check (:data:`RTOL`, :data:`NORMALISED_ATOL`):

    |exact − FD| ≤ RTOL |FD| + NORMALISED_ATOL · V_crit / s_p,

s_p the parameter's normalising scale (its value, or the scale of a position; 1 unit when
both are 0): 1 % of the derivative plus 1e-4 in normalised units (% of V_crit per % of p), the
level below which a sensitivity is negligible and a difference of the two is the crossings'
rounding.  A row is flagged when it exceeds the tolerance, when a perturbed analysis has no
event of the same kind with the same mode name (the critical mode changed: the central
difference is not of the same event), or when a variant failed.

Parameters are set as :mod:`propwhirl.analysis.sensitivity` names them
(:func:`set_parameter`): the per-element, per-node and propeller parameters by
:func:`propwhirl.model.derivatives.with_value` (a per-element value of a uniform property makes
it a per-element array: ``wing.GJ[3]`` is not a path of :mod:`propwhirl.studies.paths`, whose
``wing.GJ`` is one number for a uniform wing), the whole-distribution factors ``wing.EI*`` ...
and ``flight.density`` by :func:`propwhirl.studies.paths.set_value`.
"""
from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, replace
from typing import Any, ClassVar

import numpy as np

from propwhirl import validate as v
from propwhirl.analysis.sensitivity import CriticalSensitivities, Sensitivity
from propwhirl.analysis.stability import ModelAnalysis, analyse
from propwhirl.analysis.summary import text_table
from propwhirl.engine import XTOL
from propwhirl.model import derivatives as D
from propwhirl.model.aerodynamics.dlm import DlmTables
from propwhirl.model.parameter_paths import parameter_paths
from propwhirl.progress import ProgressCallback
from propwhirl.results import Result, SavedDict
from propwhirl.studies import execution
from propwhirl.studies import paths as P

#: δ: the relative step of the central differences (h = δ |p|)
REL_STEP = 1e-3
#: relative tolerance of the check: |exact − FD| ≤ RTOL |FD| + ...
RTOL = 0.01
#: absolute tolerance of the check in normalised units [% of V_crit per % of p]
NORMALISED_ATOL = 1e-4
#: the statuses of a check; only "ok" passes
STATUSES = ("ok", "differs", "event changed", "no event", "failed")


# ----------------------------------------------------------------------------- setting
def set_parameter(model: Any, path: str, value: float) -> Any:
    """`model` with the sensitivity parameter `path` (of
    :func:`~propwhirl.analysis.sensitivity.sensitivity_parameters`) set to `value` [its unit]:
    the factors and the density through the studies' paths, every other parameter as the
    derivatives name it (:func:`propwhirl.model.derivatives.with_value`).  The path must be
    one of the model contract's (:func:`propwhirl.model.parameter_paths.parameter_paths`): another
    is an InputError."""
    known = {p.path: p for p in parameter_paths(model)}
    if path not in known:
        raise v.InputError(f"parameter = {v.short_repr(path)} is invalid: not a parameter with "
                           "sensitivities of this model (propwhirl.model.protocol."
                           "parameter_paths(model) lists them)")
    p = known[path]
    if p.kind in ("factor", "flight", "modal") or not hasattr(model, "second_order_blocks"):
        return P.set_value(model, path, value)          # a modal model's: the studies' paths
    return D.with_value(model, path, value)


# ----------------------------------------------------------------------------- the batch
@dataclass(frozen=True)
class _Run:
    """One perturbed analysis (a picklable task): the model, the parameter's path and value,
    the analysis settings and the event looked for."""

    model: Any
    path: str
    value: float
    speeds: np.ndarray
    method: str
    xtol: float
    kind: str
    event: str
    label: str
    V: float
    #: the batch's doublet-lattice tables (one set of AICs for every variant of a planform in
    #: this process; sent to a worker process, they arrive empty)
    tables: DlmTables | None = None


def same_event(analysis: ModelAnalysis, kind: str, event: str, label: str,
               V: float) -> tuple[float, str, bool] | None:
    """The event of `analysis` that is the critical event (kind, event, mode `label`, at `V`
    [m/s]) of a nearby model: (its speed [m/s], its mode name, changed).  Among the events of
    the same kind and event, the one with the same mode name nearest `V` (changed False); when
    no mode has that name, the nearest one of any name (changed True); None when there is no
    event of that kind."""
    cands = [e for e in analysis.events if e.kind == kind and e.event == event]
    same = [e for e in cands if e.label == label]
    pool = same or cands
    if not pool:
        return None
    e = min(pool, key=lambda x: (abs(x.V - V), x.V))
    return float(e.V), e.label, not same


def _run(t: _Run) -> dict[str, Any]:
    """Analyse the variant, return {"V": speed [m/s] or None, "label", "changed"}."""
    a = analyse(set_parameter(t.model, t.path, t.value), t.speeds, xtol=t.xtol, method=t.method,
                compressibility_check=False, dlm_tables=t.tables)
    got = same_event(a, t.kind, t.event, t.label, t.V)
    if got is None:
        return {"V": None, "label": "", "changed": True}
    return {"V": got[0], "label": got[1], "changed": got[2]}


# ----------------------------------------------------------------------------- the result
@dataclass(frozen=True)
class SensitivityCheck:
    """The check of one parameter's dV_crit/dp.

    path, unit, value [unit]; step h [unit]; scale [unit] the normalising scale of a position
    (None: the value); dV_dp the exact derivative [m/s per unit]; V_plus, V_minus the critical
    speeds at p ± h [m/s] (None: not found or failed); fd the central difference [m/s per unit]
    (None when either is missing); status one of :data:`STATUSES`; note why (the mode found,
    the error of a failed variant)."""

    path: str
    unit: str
    value: float
    step: float
    scale: float | None
    dV_dp: float
    V_plus: float | None
    V_minus: float | None
    fd: float | None
    status: str
    note: str = ""

    @property
    def passed(self) -> bool:
        """Whether the check passes (status "ok")."""
        return self.status == "ok"

    @property
    def rel_diff(self) -> float | None:
        """(exact − FD) / |FD| [-] (None without a central difference or when it is 0)."""
        if self.fd is None or self.fd == 0.0:
            return None
        return (self.dV_dp - self.fd) / abs(self.fd)

    def to_dict(self) -> dict[str, Any]:
        """Every field, the units in the keys (a part of a sensitivity-check file)."""
        return {"path": self.path, "unit": self.unit, "value": self.value,
                "step": self.step, "scale": self.scale,
                "dV_dp_exact_m_s_per_unit": self.dV_dp, "V_plus_m_s": self.V_plus,
                "V_minus_m_s": self.V_minus, "dV_dp_fd_m_s_per_unit": self.fd,
                "rel_diff": self.rel_diff, "status": self.status, "note": self.note}

    @classmethod
    def from_dict(cls, d: Any, where: str = "check") -> "SensitivityCheck":
        """The entry written by :meth:`to_dict`, checked (InputError naming the key)."""
        r = SavedDict(d, where, ("path", "unit", "value", "step", "scale",
                                 "dV_dp_exact_m_s_per_unit", "V_plus_m_s", "V_minus_m_s",
                                 "dV_dp_fd_m_s_per_unit", "rel_diff", "status", "note"))
        step = r.number("step")
        if step <= 0:
            raise v.InputError(f"{r.name('step')} = {step!r} is invalid: must be > 0")
        return cls(r.string("path"), r.string("unit"), r.number("value"), step,
                   r.number("scale", optional=True), r.number("dV_dp_exact_m_s_per_unit"),
                   r.number("V_plus_m_s", optional=True), r.number("V_minus_m_s", optional=True),
                   r.number("dV_dp_fd_m_s_per_unit", optional=True),
                   r.string("status", STATUSES), r.string("note"))


@dataclass(frozen=True)
class SensitivityVerification(Result):
    """The verification of exact sensitivities by central differences
    (:func:`verify_sensitivities`): the sensitivities checked (the critical point and their
    entries), the settings of the perturbed analyses (method, speed grid [m/s], crossing
    accuracy xtol [m/s]), the relative step δ, the tolerance (rtol, normalised atol), the number
    of analyses run (2 per parameter) and one :class:`SensitivityCheck` per parameter.

    A :class:`~propwhirl.results.Result` of kind "sensitivity-check" (format
    ``propwhirl.sensitivity-check/1``; ``propwhirl sensitivity --verify --json`` writes it):
    ``{"sensitivities": <a propwhirl.sensitivities file's content>, "method", "speeds_m_s",
    "xtol_m_s", "rel_step", "rtol", "normalised_atol", "analyses", "passed", "checks"}``."""

    sensitivities: CriticalSensitivities
    method: str
    speeds: np.ndarray
    xtol: float
    rel_step: float
    rtol: float
    atol: float
    analyses: int
    checks: tuple[SensitivityCheck, ...]

    KIND: ClassVar[str] = "sensitivity-check"
    VERSION: ClassVar[int] = 1
    READABLE: ClassVar[tuple[int, ...]] = (1,)
    WHAT: ClassVar[str] = "sensitivity-check file"

    @property
    def passed(self) -> bool:
        """Whether every check passes."""
        return all(c.passed for c in self.checks)

    @property
    def failed(self) -> list[SensitivityCheck]:
        """The checks flagged (status other than "ok")."""
        return [c for c in self.checks if not c.passed]

    def encode(self) -> dict[str, Any]:
        return {"sensitivities": self.sensitivities.to_dict(),
                "method": self.method, "speeds_m_s": [float(x) for x in self.speeds],
                "xtol_m_s": self.xtol, "rel_step": self.rel_step, "rtol": self.rtol,
                "normalised_atol": self.atol, "analyses": self.analyses,
                "passed": self.passed, "checks": [c.to_dict() for c in self.checks]}

    @classmethod
    def decode(cls, d: Mapping[str, Any], version: int,
               where: str = "") -> "SensitivityVerification":
        r = SavedDict(d, where, ("sensitivities", "method", "speeds_m_s", "xtol_m_s",
                                 "rel_step", "rtol", "normalised_atol", "analyses", "passed",
                                 "checks"))
        cs = CriticalSensitivities.from_dict(r.raw("sensitivities"), r.name("sensitivities"))
        checks = tuple(SensitivityCheck.from_dict(x, w) for w, x in r.items("checks"))
        out = cls(cs, r.string("method"), r.array("speeds_m_s"), r.number("xtol_m_s"),
                  r.number("rel_step"), r.number("rtol"), r.number("normalised_atol"),
                  r.integer("analyses", 0), checks)
        if r.boolean("passed") != out.passed:
            raise v.InputError(f"{r.name('passed')} does not match the checks' statuses")
        return out

    def format(self) -> str:
        """A text table: per parameter the exact and finite-difference dV/dp, their relative
        difference and the check."""
        cs = self.sensitivities
        head = (f"verification by central differences: {self.analyses} analyses (method "
                f"{self.method}, {self.speeds[0]:g}-{self.speeds[-1]:g} m/s, xtol {self.xtol:g} "
                f"m/s) at p(1 +- {self.rel_step:g}); {cs.kind} {cs.event} of {cs.mode} at "
                f"V = {cs.V:.2f} m/s; tolerance |exact - FD| <= {self.rtol:g} |FD| + "
                f"{self.atol:g} in normalised units")
        rows = []
        for c in self.checks:
            rel = c.rel_diff
            rows.append([c.path, f"{c.value:.6g}", c.unit or "-", f"{c.step:.3g}",
                         f"{c.dV_dp:.6g}", "-" if c.fd is None else f"{c.fd:.6g}",
                         "-" if rel is None else f"{rel:+.1e}",
                         c.status + (f" ({c.note})" if c.note else "")])
        # a model without exact derivatives: the sensitivities checked are central
        # differences of its state matrix or, on a doublet-lattice wing's p-k crossing, of
        # the p-k root (analysis/sensitivity.py), not exact ones
        routes = {x.derivative for x in cs.sensitivities}
        derived = ("dV/dp exact" if routes == {"exact"} else "dV/dp (diff. of p-k root)"
                   if any(r.endswith("(p-k)") for r in routes) else "dV/dp (diff. of A)")
        table = text_table(rows, ["parameter", "value", "unit", "step", derived,
                                  "dV/dp FD", "rel. diff.", "check"], "lrlrrrrl")
        bad = self.failed
        tail = (f"all {len(self.checks)} within tolerance" if not bad else
                f"{len(bad)} of {len(self.checks)} flagged: {', '.join(c.path for c in bad)}")
        return head + "\n" + table + "\n" + tail


def _check_row(s: Sensitivity, V: float, h: float, up: Any, down: Any, label: str,
               rtol: float, atol: float) -> SensitivityCheck:
    """The check of `s` from its two runs (dicts of :func:`_run` or TaskErrors)."""
    scale = s.scale
    ref = abs(scale if scale is not None else s.value) or 1.0
    errors = [r for r in (up, down) if not isinstance(r, Mapping)]
    if errors:
        e = errors[0]
        return SensitivityCheck(s.path, s.unit, s.value, h, scale, s.dV_dp, None, None, None,
                                "failed", f"{e.kind}: {e.message}")
    Vp, Vm = up["V"], down["V"]
    if Vp is None or Vm is None:
        return SensitivityCheck(s.path, s.unit, s.value, h, scale, s.dV_dp, Vp, Vm, None,
                                "no event", "a perturbed analysis has no event of this kind")
    fd = (Vp - Vm) / (2.0 * h)
    if up["changed"] or down["changed"]:
        names = sorted({r["label"] for r in (up, down) if r["changed"]})
        return SensitivityCheck(s.path, s.unit, s.value, h, scale, s.dV_dp, Vp, Vm, fd,
                                "event changed", f"no {label} event: nearest {', '.join(names)}")
    ok = abs(s.dV_dp - fd) <= rtol * abs(fd) + atol * V / ref
    return SensitivityCheck(s.path, s.unit, s.value, h, scale, s.dV_dp, Vp, Vm, fd,
                            "ok" if ok else "differs")


def step_of(s: Sensitivity, rel_step: float = REL_STEP) -> float:
    """The step h [p's unit] of the central difference of `s`: δ |p|, or δ s for a value 0 with
    a scale s (a position), or δ [unit] when neither."""
    if s.value != 0.0:
        return rel_step * abs(s.value)
    return rel_step * (s.scale if s.scale is not None else 1.0)


def verify_sensitivities(model: Any, analysis: ModelAnalysis, sensitivities: CriticalSensitivities,
                         params=None, *, top: int | None = None, method: str = "auto",
                         speeds=None, xtol: float = XTOL, rel_step: float = REL_STEP,
                         rtol: float = RTOL, atol: float = NORMALISED_ATOL,
                         processes: int = 1, client=None,
                         progress: bool | ProgressCallback | None = None,
                         dlm_tables: DlmTables | None = None) -> SensitivityVerification:
    """Check the exact dV_crit/dp of `sensitivities` (of `analysis`, an analysis of `model`)
    against central differences of the critical speed (the module docstring).

    Parameters
    ----------
    model, analysis :
        The model (a PropellerWing) and its analysis, from which `sensitivities` were computed
        (:func:`~propwhirl.analysis.sensitivity.critical_sensitivities`).
    sensitivities : CriticalSensitivities
        The exact sensitivities.
    params : sequence of str, optional
        The paths checked (entries of `sensitivities`); default the `top` ranked ones (all when
        `top` is None).
    top : int, optional
        Without `params`: check the `top` entries ranked by |normalised sensitivity|.
    method, speeds, xtol :
        Those of the perturbed analyses (:func:`~propwhirl.analysis.stability.analyse`): give
        the ones `analysis` was made with; default method "auto", the speed grid `analysis`
        asked for (``analysis.sweep.grid``) [m/s], the default crossing accuracy [m/s].
    rel_step : float
        δ, the relative step (default :data:`REL_STEP`, 1e-3).
    rtol, atol :
        The tolerance: relative, and absolute in normalised units (:data:`RTOL`,
        :data:`NORMALISED_ATOL`).
    processes, client, progress :
        How the 2N analyses run, in one batch
        (:func:`propwhirl.studies.execution.map_analyses`).
    dlm_tables : DlmTables, optional
        A doublet-lattice wing's tables (the analysis's), read by every perturbed analysis in
        this process (the variants have the model's panels: no AIC computed again); None:
        new ones for the batch.  Worker processes fill their own.

    Returns
    -------
    SensitivityVerification
        One check per parameter; ``.passed`` when all pass.

    Examples
    --------
    The critical speed of the baseline wing on 4 elements with its tip propeller against the
    pitch-mount frequency: the exact derivative and the central difference agree.

    >>> from propwhirl.analysis import analyse, critical_sensitivities
    >>> from propwhirl.studies import verify_sensitivities
    >>> from propwhirl.model import FlightCondition, Installation, PropellerWing
    >>> from propwhirl.cases.ch09_baseline import baseline_propeller, baseline_wing
    >>> model = PropellerWing(baseline_wing(n_elements=4),       # 4 elements, 100-200 m/s
    ...                       FlightCondition(0.96287, speed_range=(100.0, 200.0, 20.0)),
    ...                       (Installation(baseline_propeller(), 5.7),))
    >>> a = analyse(model)
    >>> cs = critical_sensitivities(model, a, params=["propellers[0].propeller.f_theta"])
    >>> check = verify_sensitivities(model, a, cs)
    >>> check.passed, check.analyses
    (True, 2)
    """
    if not isinstance(sensitivities, CriticalSensitivities):
        raise v.InputError(f"sensitivities = {v.short_repr(sensitivities)} is invalid: must be "
                           "a CriticalSensitivities (propwhirl.analysis.critical_sensitivities)")
    if not isinstance(analysis, ModelAnalysis):
        raise v.InputError(f"analysis = {v.short_repr(analysis)} is invalid: must be the "
                           "ModelAnalysis of the model")
    name = getattr(model, "name", None)
    if name is not None and analysis.model_name != name:
        raise v.InputError(f"the analysis is of {analysis.model_name!r}, the model is {name!r}")
    if not (isinstance(rel_step, (int, float)) and 0.0 < rel_step <= 0.1):
        raise v.InputError(f"rel_step = {v.short_repr(rel_step)} is invalid: must be in (0, 0.1]")
    v.positive("rtol", rtol)
    if not (isinstance(atol, (int, float)) and math.isfinite(atol) and atol >= 0.0):
        raise v.InputError(f"atol = {v.short_repr(atol)} is invalid: must be >= 0")
    v.positive("xtol", xtol, "m/s")
    if top is not None:
        v.integer_at_least("top", top, 1)
    grid = analysis.sweep.grid if speeds is None else v.increasing("speeds", speeds, "m/s")
    grid = np.asarray(grid, dtype=float)
    by_path = {s.path: s for s in sensitivities.sensitivities}
    if params is None:
        chosen = sensitivities.ranked(top)
    else:
        if isinstance(params, str):
            params = [params]
        bad = [p for p in params if p not in by_path]
        if bad:
            raise v.InputError(f"parameter = {v.short_repr(bad[0])} is invalid: not one of the "
                               "sensitivities given")
        chosen = [by_path[p] for p in dict.fromkeys(params)]
    cs = sensitivities
    tables = DlmTables() if dlm_tables is None else dlm_tables
    tasks, keys = [], []
    for s in chosen:
        h = step_of(s, rel_step)
        for sign, tag in ((1.0, "+"), (-1.0, "-")):
            tasks.append(_Run(model, s.path, s.value + sign * h, grid, method, float(xtol),
                              cs.kind, cs.event, cs.mode, cs.V, tables))
            keys.append(f"{s.path}{tag}")
    runs = execution.map_analyses(_run, tasks, processes, client=client, progress=progress,
                                  errors="record", keys=keys, desc="sensitivity checks")
    checks = tuple(_check_row(s, cs.V, step_of(s, rel_step), runs[2 * k], runs[2 * k + 1],
                              cs.mode, rtol, atol) for k, s in enumerate(chosen))
    checked = replace(cs, sensitivities=tuple(chosen))
    return SensitivityVerification(checked, method, grid, float(xtol), float(rel_step),
                                   float(rtol), float(atol), len(tasks), checks)


__all__ = ["REL_STEP", "RTOL", "NORMALISED_ATOL", "STATUSES", "SensitivityCheck",
           "SensitivityVerification", "same_event", "set_parameter", "step_of",
           "verify_sensitivities"]
