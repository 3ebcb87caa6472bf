"""Whirl-flutter clearance of a model: is it free of instabilities up to factor · V_D?

The requirement of CS/FAR 25.629 (factor 1.15) and 14 CFR 23.629 (factor 1.2): no aeroelastic
instability at speeds up to ``factor · V_D``.  :func:`clearance` analyses the model
(:func:`propwhirl.analysis.stability.analyse`, the speed range extended to beyond
factor · V_D when the model's own ends below it) and reports

* pass or fail: the critical instability (the one definition,
  :func:`propwhirl.analysis.stability.critical`, or the thesis's exclusions —
  ``static_divergence=False``, ``low_speed=False``,
  :func:`propwhirl.studies.critical.critical_instability`) lies above factor · V_D, or there is
  none in the range;
* the margin of every instability in the range, V_event / (factor · V_D) − 1, with its kind,
  event and mode, and whether the convention counts it;
* for each flexibly mounted propeller, the minimum pitch (f_θ) and yaw (f_ψ) mount frequency
  [Hz] that clears the requirement with every other parameter fixed: the critical speed is
  sampled at ``n_scan`` frequencies of ``frequency_range`` (geometric), the lowest sample above
  which every sample clears is found, and V_crit(f) − factor · V_D = 0 is solved by Brent's
  method (:func:`scipy.optimize.brentq`) in the interval below it, one analysis per
  evaluation.  The frequency reported is the root rounded up to ``frequency_tol``, and is
  checked by one more analysis there (it clears).  When even the top of the range does not
  clear, or every sample clears (the minimum lies at or below the range's bottom), that is
  said instead.
"""
from __future__ import annotations

import io
import math
from collections.abc import Mapping
from dataclasses import dataclass, fields, replace
from pathlib import Path
from typing import Any, ClassVar

import numpy as np
from scipy.optimize import brentq

from propwhirl import fileio, limits
from propwhirl import validate as v
from propwhirl.analysis.stability import ModelAnalysis, analyse
from propwhirl.model.aerodynamics import validity
from propwhirl.model.aerodynamics.dlm import DlmTables
from propwhirl.progress import Cumulative
from propwhirl.results import Result, SavedDict
from propwhirl.studies import execution
from propwhirl.studies import paths as P
from propwhirl.studies import sweeps
from propwhirl.studies.critical import convention, critical_instability, wing_divergence_predicate

from propwhirl.analysis.margin import required_speed  # noqa: F401 (re-exported)
from propwhirl.certification import FACTOR_CFR23, FACTOR_CS25  # noqa: F401



def _clean(d: dict[str, Any]) -> dict[str, Any]:
    """A dataclass's fields for JSON: a non-finite float as None, a tuple as a list."""
    return {k: (None if isinstance(x, float) and not math.isfinite(x) else
                list(x) if isinstance(x, tuple) else x) for k, x in d.items()}


@dataclass(frozen=True)
class Margin:
    """One instability in the analysed range: kind, event, mode (label), V [m/s], frequency
    [Hz], margin = V / (factor · V_D) − 1, counted: whether the convention counts it."""

    kind: str
    event: str
    mode: str
    V: float
    frequency_hz: float
    margin: float
    counted: bool

    def to_dict(self) -> dict[str, Any]:
        """The fields (a non-finite number as None).  ``mode`` is the mode's name (the
        ``label`` of an :class:`~propwhirl.analysis.stability.Instability`)."""
        return _clean(vars(self))

    @classmethod
    def from_dict(cls, d: Any, where: str = "margin") -> "Margin":
        """The margin written by :meth:`to_dict`, checked (null numbers read as NaN)."""
        r = SavedDict(d, where, [f.name for f in fields(cls)])
        return cls(r.string("kind"), r.string("event"), r.string("mode"), r.number_or_nan("V"),
                   r.number_or_nan("frequency_hz"), r.number_or_nan("margin"),
                   r.boolean("counted"))


#: The outcomes of a minimum-frequency search (:class:`MinimumFrequency`).
STATUSES = ("found", "at or below the range", "none in range", "not monotone")


@dataclass(frozen=True)
class MinimumFrequency:
    """The minimum mount frequency of one propeller that clears the requirement.

    propeller: numbered from 1; parameter: "f_theta" or "f_psi"; path: its parameter path;
    current: the model's value [Hz] (None when given as a stiffness); frequency [Hz] (None when
    no frequency of the range clears); status: "found", "at or below the range" (every
    sampled frequency clears: the minimum is ≤ the range's bottom), "none in range", "not
    monotone" (samples below the frequency found clear too, others between do not: V_crit(f)
    switches critical mode — the frequency is the lowest above which every sample clears,
    not a single minimum, and not a margin);
    critical_speed: V_crit [m/s] at `frequency` (the check; NaN: no instability in range);
    range [Hz]; note: e.g. samples below the minimum that clear too (not monotone);
    analyses: analyses it took; kind, mode: what decides it (issue 35 item 7) — the critical
    instability at `frequency` ("found", "not monotone": the one that sets the minimum, its
    speed `critical_speed` just above the required speed; "at or below the range": at the
    range's bottom), or at the range's top ("none in range": the one even the top frequency
    does not clear); "" in files written before them, "none" for no instability in range.
    """

    propeller: int
    parameter: str
    path: str
    current: float | None
    frequency: float | None
    status: str
    critical_speed: float
    range: tuple[float, float]
    note: str
    analyses: int
    kind: str = ""
    mode: str = ""

    def to_dict(self) -> dict[str, Any]:
        """The fields (a non-finite number as None)."""
        return _clean(vars(self))

    @classmethod
    def from_dict(cls, d: Any, where: str = "minimum") -> "MinimumFrequency":
        """The entry written by :meth:`to_dict`, checked (a null critical speed as NaN)."""
        later = ("kind", "mode")                 # written since issue 35 item 7
        r = SavedDict(d, where, [f.name for f in fields(cls) if f.name not in later], later)
        lo, hi = r.array("range", shape=(2,))
        return cls(r.integer("propeller", 1), r.string("parameter", ("f_theta", "f_psi")),
                   r.string("path"), r.number("current", optional=True),
                   r.number("frequency", optional=True),
                   r.string("status", STATUSES),
                   r.number_or_nan("critical_speed"), (float(lo), float(hi)), r.string("note"),
                   r.integer("analyses", 0), *(r.string(k) if r.has(k) else "" for k in later))


@dataclass(frozen=True)
class Clearance(Result):
    """The clearance result (module docstring); ``cleared`` decides the CLI's exit code.

    A :class:`~propwhirl.results.Result` of kind "clearance" (format
    ``propwhirl.clearance/2``; version 2 added the minimum-frequency status "not monotone",
    which a reader of version 1 does not know; version-1 files are read):
    :meth:`save` / :meth:`load`."""

    KIND: ClassVar[str] = "clearance"
    VERSION: ClassVar[int] = 2
    READABLE: ClassVar[tuple[int, ...]] = (1, 2)
    WHAT: ClassVar[str] = "clearance file"

    model_name: str
    V_D: float
    factor: float
    V_required: float
    cleared: bool
    critical: Margin | None
    margins: tuple[Margin, ...]
    minimum: tuple[MinimumFrequency, ...]
    convention: str
    speed_range: tuple[float, float]
    analyses: int

    def format(self) -> str:
        """A text report."""
        verdict = "CLEARED" if self.cleared else "NOT CLEARED"
        lines = [f"{self.model_name}: clearance to {self.factor:g} V_D = {self.factor:g} x "
                 f"{self.V_D:g} = {self.V_required:.2f} m/s: {verdict}",
                 f"  critical instability: {self.convention}; analysed "
                 f"{self.speed_range[0]:g}-{self.speed_range[1]:g} m/s"]
        if self.critical is None:
            lines.append("  no instability counted in the analysed range")
        else:
            c = self.critical
            lines.append(f"  critical: {c.kind} ({c.event}) of {c.mode} at {c.V:.2f} m/s, "
                         f"margin {100 * c.margin:+.1f} %")
        if self.margins:
            lines.append("  instabilities in the range (margin = V / (factor V_D) - 1):")
            for m in self.margins:
                lines.append(f"    {m.kind:10s} {m.event:17s} {m.mode:14s} {m.V:8.2f} m/s "
                             f"{m.frequency_hz:7.3f} Hz  {100 * m.margin:+7.1f} %"
                             + ("" if m.counted else "  (not counted)"))
        for q in self.minimum:
            name = {"f_theta": "pitch f_theta", "f_psi": "yaw f_psi"}[q.parameter]
            rng = f"[{q.range[0]:g}, {q.range[1]:g}] Hz"
            cur = "" if q.current is None else f" (now {q.current:g} Hz)"
            if q.status == "found":
                Vc = "no instability" if not math.isfinite(q.critical_speed) else f"V_crit = {q.critical_speed:.2f} m/s"
                text = f"{q.frequency:.3f} Hz{cur}: {Vc}"
            elif q.status == "not monotone":
                text = (f"NOT MONOTONE{cur}: every sample above {q.frequency:.3f} Hz clears, "
                        "but there is no single minimum")
            elif q.status == "at or below the range":
                text = f"<= {q.range[0]:g} Hz{cur}: every sampled frequency of {rng} clears"
            else:
                text = f"none in {rng}{cur}: even {q.range[1]:g} Hz does not clear"
            lines.append(f"  propeller {q.propeller} minimum {name}: {text}"
                         + _decided(q) + (f"; {q.note}" if q.note else ""))
        lines.append(f"  {self.analyses} analyses")
        return "\n".join(lines)

    def encode(self) -> dict[str, Any]:
        return {"model_name": self.model_name, "V_D": self.V_D,
                "factor": self.factor, "V_required": self.V_required, "cleared": self.cleared,
                "convention": self.convention, "speed_range": list(self.speed_range),
                "critical": None if self.critical is None else self.critical.to_dict(),
                "margins": [m.to_dict() for m in self.margins],
                "minimum_frequencies": [q.to_dict() for q in self.minimum],
                "analyses": self.analyses}

    @classmethod
    def decode(cls, d: Mapping[str, Any], version: int, where: str = "") -> "Clearance":
        """Every key checked (a speed written as null — not finite — is read back as NaN)."""
        r = SavedDict(d, where, ("model_name", "V_D", "factor", "V_required", "cleared",
                                 "convention", "speed_range", "critical", "margins",
                                 "minimum_frequencies", "analyses"))
        crit = r.raw("critical")
        lo, hi = r.bracket("speed_range")
        return cls(r.string("model_name"), r.number("V_D"), r.number("factor"),
                   r.number("V_required"), r.boolean("cleared"),
                   None if crit is None else Margin.from_dict(crit, r.name("critical")),
                   tuple(Margin.from_dict(m, w) for w, m in r.items("margins")),
                   tuple(MinimumFrequency.from_dict(q, w)
                         for w, q in r.items("minimum_frequencies")),
                   r.string("convention"), (lo, hi), r.integer("analyses", 0))

    def save_json(self, path: str | Path) -> Path:
        """Alias of :meth:`save` (the name of earlier releases)."""
        return self.save(path)

    def to_csv(self, path: str | Path | None = None) -> str:
        """Two tables in one CSV: the instabilities (section "instability") and the minimum
        frequencies (section "minimum"), with the verdict in the first row."""
        buf = io.StringIO()
        w = fileio.csv_writer(buf, lineterminator="\n")
        w.writerow(["model", "V_D [m/s]", "factor", "V_required [m/s]", "cleared"])
        w.writerow([self.model_name, f"{self.V_D:g}", f"{self.factor:g}", f"{self.V_required:.10g}",
                    "yes" if self.cleared else "no"])
        w.writerow(["section", "kind", "event", "mode", "V [m/s]", "frequency [Hz]", "margin", "counted"])
        for m in self.margins:
            w.writerow(["instability", m.kind, m.event, m.mode, f"{m.V:.10g}", f"{m.frequency_hz:.10g}",
                        f"{m.margin:.10g}", "yes" if m.counted else "no"])
        w.writerow(["section", "propeller", "parameter", "status", "frequency [Hz]", "current [Hz]",
                    "critical_speed [m/s]", "range_low [Hz]", "range_high [Hz]", "note",
                    "decided_by_kind", "decided_by_mode"])
        for q in self.minimum:
            w.writerow(["minimum", q.propeller, q.parameter, q.status,
                        "" if q.frequency is None else f"{q.frequency:.10g}",
                        "" if q.current is None else f"{q.current:.10g}",
                        "" if not math.isfinite(q.critical_speed) else f"{q.critical_speed:.10g}",
                        f"{q.range[0]:g}", f"{q.range[1]:g}", q.note, q.kind, q.mode])
        text = buf.getvalue()
        if path is not None:
            fileio.write_text(path, text, what="clearance table")
        return text


#: The format tag of the clearance file (:class:`Clearance`; the name of earlier releases).
FORMAT = Clearance.format_name()


def clearance_speeds(model: Any, V_required: float, speeds=None) -> np.ndarray:
    """The analyses' speed grid [m/s]: `speeds`, or the model's speed range extended (same
    step) to at least 1.05 · V_required.

    Checked before any analysis: the grid must reach beyond V_required, stay below the Mach
    number the model's aerodynamics refuse (:data:`propwhirl.model.aerodynamics.validity.MACH_REFUSED`)
    and hold at most :data:`propwhirl.limits.MAX_SPEEDS` speeds (one-line InputErrors naming
    V_D, factor x V_D and the largest valid value)."""
    aero, a = validity.has_aerodynamics(model), float(model.flight.speed_of_sound)
    if speeds is not None:
        grid = v.increasing("speeds", speeds, "m/s")
        if grid[-1] <= V_required:
            raise v.InputError(f"speeds end at {grid[-1]:g} m/s: must reach beyond factor V_D = "
                               f"{V_required:.2f} m/s")
        _check_top_speed(aero, a, float(grid[-1]), V_required, "the speeds' end")
        return grid
    return speed_grid(model.flight.speed_range, V_required, a, aero)


def speed_grid(speed_range, V_required: float, speed_of_sound: float,
               aerodynamic: bool = True) -> np.ndarray:
    """:func:`clearance_speeds`' grid [m/s] without its model: the speed range
    (first, last, step) [m/s] extended to at least 1.05 · V_required, its checks made with the
    speed of sound [m/s] (and only when the model has `aerodynamic` loads).  A campaign makes
    its points' grids with it once per distinct range, speed of sound and V_required."""
    lo, hi, step = (float(x) for x in speed_range)
    hi = max(hi, 1.05 * V_required)
    _check_top_speed(aerodynamic, float(speed_of_sound), hi, V_required, "1.05 factor x V_D")
    count = limits.grid_count(lo, hi, step)
    if not count <= limits.MAX_SPEEDS:
        raise v.InputError(
            f"factor x V_D = {V_required:g} m/s is invalid: the analyses' speed grid from "
            f"{lo:g} m/s in the model's steps of {step:g} m/s to {hi:g} m/s would hold "
            f"{count:,.0f} speeds, at most {limits.MAX_SPEEDS:,}: give a smaller V_D or speeds")
    n = int(math.ceil((hi - lo) / step - 1e-9))
    return lo + step * np.arange(n + 1)


def _check_top_speed(aerodynamic: bool, a: float, top: float, V_required: float,
                     what: str) -> None:
    """Refuse analyses to `top` [m/s] (`what`) at a Mach number (speed of sound `a` [m/s])
    the aerodynamics refuse (none without `aerodynamic` loads)."""
    if not aerodynamic:
        return
    if top / a >= validity.MACH_REFUSED:
        raise v.InputError(
            f"factor x V_D = {V_required:g} m/s is invalid: the analyses go to {what}, "
            f"{top:g} m/s, Mach {top / a:.3g} at a = {a:g} m/s; the aerodynamics are subsonic "
            f"and propwhirl refuses Mach >= {validity.MACH_REFUSED:g} (V >= "
            f"{validity.MACH_REFUSED * a:.1f} m/s)")


def _analysis_critical(model, speeds, xtol, static_div, low_speed):
    a = analyse(model, speeds, xtol=xtol, compressibility_check=False)  # no warnings kept
    is_wing = wing_divergence_predicate(model, a)
    crit = critical_instability(a, static_divergence=static_div, low_speed=low_speed,
                                is_wing_divergence=is_wing)
    return a, is_wing, crit


def _counted(a: ModelAnalysis, e, is_wing, static_div: bool, low_speed: bool) -> bool:
    only = replace(a, events=tuple(x for x in a.events if x is e or x.event == "recovery"))
    return critical_instability(only, static_divergence=static_div, low_speed=low_speed,
                                is_wing_divergence=is_wing) is e


def _frequency_path(model: Any, number: int, name: str) -> P.Parameter:
    for text in (f"propellers[{number}].propeller.{name}", f"propeller.{name}"):
        try:
            return P.resolve(model, text)
        except v.InputError:
            continue
    raise v.InputError(f"propeller {number + 1}: no parameter path to its {name}")


def _check_search(par: P.Parameter, frequency_range: Any, n_scan: Any,
                  frequency_tol: Any) -> tuple[float, float]:
    """(lo, hi) [Hz] of the minimum-frequency search, checked: an increasing pair inside the
    frequency path's declared range, n_scan >= 2, frequency_tol > 0."""
    rng = np.asarray(v.positive("frequency_range", frequency_range, "Hz"), dtype=float)
    if rng.shape != (2,):
        raise v.InputError(f"frequency_range = {v.short_repr(frequency_range)} Hz is invalid: "
                           "give two frequencies (low, high)")
    lo, hi = float(rng[0]), float(rng[1])
    if not hi > lo:
        raise v.InputError(f"frequency_range = ({lo:g}, {hi:g}) Hz is invalid: must be increasing")
    par.check_values(rng, "frequency_range")
    v.integer_at_least("n_scan", n_scan, 2)
    v.positive("frequency_tol", frequency_tol, "Hz")
    return lo, hi


#: The phases of the minimum-frequency searches, each one batch of independent analyses
#: (and its own partial-results file beside the clearance's): the top of every range, the
#: rest of the scans whose top clears, the root refinements.
PHASES = ("top", "scan", "refine")


def phase_checkpoints(checkpoint: Any) -> list:
    """The partial-results files of the phases of a clearance whose file is `checkpoint` (to
    remove them with it once the result is written)."""
    return [] if checkpoint is None else [_phase_checkpoint(checkpoint, n) for n in PHASES]


def _phase_checkpoint(checkpoint: Any, name: str) -> Any:
    if checkpoint is None:
        return None
    from dataclasses import replace as _replace

    path = Path(checkpoint.path)
    return _replace(checkpoint, path=path.with_name(f"{path.name}.{name}")).with_entries(
        phase=name)


@dataclass(frozen=True)
class _Refine:
    """One root refinement (a picklable task): the frequency path, the bracket [Hz] and the
    critical speeds known at its ends [m/s]."""

    model: Any
    path: str
    V_required: float
    speeds: np.ndarray
    bracket: tuple[float, float]
    known: tuple[tuple[float, float], ...]
    frequency_tol: float
    xtol: float
    static_divergence: bool
    low_speed: bool


def _refine(t: _Refine) -> dict[str, Any]:
    """Brent's method on V_crit(f) − V_required in the bracket, the root rounded up to the
    tolerance and checked (it clears); {frequency, critical_speed (None: none in range),
    analyses}."""
    par = P.resolve(t.model, t.path)
    vcrit = dict(t.known)
    rows: dict[float, dict[str, Any]] = {}
    count = [0]
    top = float(t.speeds[-1])
    tables = DlmTables()                      # one search's doublet-lattice tables

    def h(f: float) -> float:
        if f not in vcrit:
            count[0] += 1
            rows[f] = sweeps.evaluate((par.set(t.model, f), t.speeds, t.xtol,
                                       t.static_divergence, t.low_speed, "auto", tables))
            vcrit[f] = rows[f]["critical_speed"]
        Vc = vcrit[f]
        return (top if not math.isfinite(Vc) else Vc) - t.V_required

    lo, hi = t.bracket
    tol = t.frequency_tol
    root = brentq(h, lo, hi, xtol=tol)
    freq = math.ceil((root + tol) / tol) * tol
    while h(freq) <= 0 and freq < hi:     # the check: the reported frequency clears
        freq = min(freq + tol, hi)
    Vc = vcrit[freq]
    row = rows.get(freq, {})
    return {"frequency": float(freq), "critical_speed": None if not math.isfinite(Vc) else Vc,
            "analyses": count[0], "kind": row.get("kind", ""),
            "mode": row.get("critical_mode", "")}


def _minimum_frequencies(model: Any, searches: list[tuple[int, str]], V_required: float,
                         speeds: np.ndarray, *, frequency_range, n_scan: int,
                         frequency_tol: float, xtol: float, static_divergence: bool,
                         low_speed: bool, processes: int = 1, client=None, progress=None,
                         checkpoint=None) -> list[MinimumFrequency]:
    """The searches (propeller index from 0, "f_theta"/"f_psi"), their analyses run in three
    batches (:data:`PHASES`) by :func:`propwhirl.studies.execution.map_analyses`."""
    pars = [_frequency_path(model, n, name) for n, name in searches]
    lo, hi = 0.0, 0.0
    for par in pars:
        lo, hi = _check_search(par, frequency_range, n_scan, frequency_tol)
    f = np.geomspace(lo, hi, n_scan)
    f[-1] = hi
    grid = [float(x) for x in f]
    tables = DlmTables()                      # the searches' doublet-lattice tables
    vcrit: list[dict[float, float]] = [{} for _ in pars]
    modes: list[dict[float, str]] = [{} for _ in pars]
    kinds: list[dict[float, str]] = [{} for _ in pars]
    if checkpoint is not None:
        checkpoint = checkpoint.with_entries(
            study="clearance minimum frequencies", model=execution.content_digest(model),
            speeds=execution.content_digest(list(map(float, speeds))),
            V_required=float(V_required), xtol=float(xtol), frequencies=grid,
            frequency_tol=float(frequency_tol), paths=[p.path for p in pars],
            convention=convention(static_divergence, low_speed))

    # a callable sees one count over the three phases, against their most from the start
    passes = (Cumulative(progress, len(pars) * (n_scan + 1))
              if callable(progress) and not isinstance(progress, (bool, np.bool_)) else None)

    def phase_progress():
        return progress if passes is None else passes.stage()

    def batch(items: list[tuple[int, float]], phase: str) -> None:
        if not items:
            return
        rows = execution.map_analyses(
            sweeps.evaluate, [(pars[i].set(model, x), speeds, xtol, static_divergence, low_speed,
                               "auto", tables)
                              for i, x in items], processes, client=client,
            progress=phase_progress(),
            checkpoint=None if checkpoint is None else
            _phase_checkpoint(checkpoint, phase).with_entries(sweeps.STUDY_ROW),
            keys=[f"{pars[i].path}={x!r}" for i, x in items],
            desc=f"minimum frequencies ({phase})")
        for (i, x), row in zip(items, rows):
            vcrit[i][x] = row["critical_speed"]
            modes[i][x] = row["critical_mode"]
            kinds[i][x] = row["kind"]

    def clears(i: int, x: float) -> bool:
        Vc = vcrit[i][x]
        return (float(speeds[-1]) if not math.isfinite(Vc) else Vc) > V_required

    batch([(i, hi) for i in range(len(pars))], "top")
    alive = [i for i in range(len(pars)) if clears(i, hi)]
    batch([(i, x) for i in alive for x in grid[:-1]], "scan")
    plan: dict[int, tuple[str, int]] = {}
    for i in range(len(pars)):
        if i not in alive:
            plan[i] = ("none in range", 0)
            continue
        ok = [clears(i, x) for x in grid]
        k = len(grid) - 1
        while k > 0 and ok[k - 1]:
            k -= 1
        if k == 0:
            plan[i] = ("at or below the range", 0)
        else:
            plan[i] = ("not monotone" if any(ok[:k - 1]) else "found", k)
    refine = [i for i in range(len(pars)) if plan[i][0] in ("found", "not monotone")]
    refined = execution.map_analyses(
        _refine, [_Refine(model, pars[i].path, float(V_required), speeds,
                          (grid[plan[i][1] - 1], grid[plan[i][1]]),
                          tuple(vcrit[i].items()), float(frequency_tol), float(xtol),
                          bool(static_divergence), bool(low_speed)) for i in refine],
        processes, client=client, progress=phase_progress(),
        checkpoint=None if checkpoint is None or not refine else
        _phase_checkpoint(checkpoint, "refine"),
        keys=[pars[i].path for i in refine], desc="minimum frequencies (refine)")
    done = dict(zip(refine, refined))
    if passes is not None and passes.done < passes.total:    # phases that needed fewer
        progress(passes.total, passes.total)
    out = []
    for i, ((number, name), par) in enumerate(zip(searches, pars)):
        status, k = plan[i]
        count = len(vcrit[i])
        note, freq, Vc = "", None, math.nan
        kind, mode = kinds[i].get(hi, ""), modes[i].get(hi, "")   # none in range: at the top
        if status == "at or below the range":
            freq, Vc = lo, vcrit[i][lo]
            kind, mode = kinds[i][lo], modes[i][lo]
        elif status in ("found", "not monotone"):
            r = done[i]
            freq = r["frequency"]
            Vc = math.nan if r["critical_speed"] is None else r["critical_speed"]
            count += r["analyses"]
            kind, mode = ((r["kind"], r["mode"]) if r.get("kind") else
                          (kinds[i].get(freq, ""), modes[i].get(freq, "")))
        if status == "not monotone":
            good = [x for x in grid[:k - 1] if clears(i, x)]
            bad = [x for x in grid[:k] if not clears(i, x)]
            seq = []
            for x in grid:
                m = modes[i][x] or "none"
                if not seq or seq[-1] != m:
                    seq.append(m)
            note = (f"V_crit(f) is not monotone: the sampled {_hz(good)} Hz clear too and "
                    f"{_hz(bad)} Hz do not (critical mode over the samples: "
                    f"{' -> '.join(seq)}); {freq:.3f} Hz is the lowest frequency above which "
                    "every sample clears, not a margin")
        out.append(MinimumFrequency(number + 1, name, par.path, par.value(model), freq, status,
                                    float(Vc), (lo, hi), note, count, kind, mode))
    return out


def _decided(q: MinimumFrequency) -> str:
    """'; set by flutter of backward 1 (at 149.62 m/s)': what decides a minimum frequency
    (its kind and mode; "" when unknown)."""
    if not q.kind:
        return ""
    if q.kind == "none":
        return "; no instability in the analysed range there"
    where = ("at the range's top" if q.status == "none in range" else
             "at the range's bottom" if q.status == "at or below the range" else "")
    speed = (f" at {q.critical_speed:.2f} m/s" if math.isfinite(q.critical_speed) and
             q.status != "none in range" else "")
    verb = "fails by" if q.status == "none in range" else "set by"
    return f"; {verb} {q.kind} of {q.mode}{speed}" + (f" ({where})" if where else "")


def _hz(xs: list[float]) -> str:
    return ", ".join(f"{x:.3g}" for x in xs)


def minimum_frequency(model: Any, number: int, name: str, V_required: float, speeds: np.ndarray,
                      *, frequency_range: tuple[float, float] = (1.0, 30.0), n_scan: int = 8,
                      frequency_tol: float = 1e-3, xtol: float = 0.01,
                      static_divergence: bool = True, low_speed: bool = True,
                      processes: int = 1, client=None, progress=None,
                      checkpoint=None) -> MinimumFrequency:
    """The minimum `name` ("f_theta"/"f_psi") [Hz] of propeller `number` (its index in the
    model, from 0) clearing `V_required` [m/s] (module docstring); processes, client,
    progress, checkpoint: :func:`propwhirl.studies.execution.map_analyses`."""
    if name not in ("f_theta", "f_psi"):
        raise v.InputError(f"parameter = {name!r} is invalid: must be 'f_theta' or 'f_psi'")
    (q,) = _minimum_frequencies(
        model, [(number, name)], V_required, speeds, frequency_range=frequency_range,
        n_scan=n_scan, frequency_tol=frequency_tol, xtol=xtol,
        static_divergence=static_divergence, low_speed=low_speed, processes=processes,
        client=client, progress=progress, checkpoint=checkpoint)
    return q


def _check_propellers(model: Any, propellers: Any) -> list[int] | None:
    """`propellers` (numbers from 1, None: all) as model indices from 0, checked."""
    if propellers is None:
        return None
    numbers = [pd.number for pd in model.dof_map().propellers]
    items = list(propellers) if not isinstance(propellers, (int, str)) else [propellers]
    if not items:
        raise v.InputError("propellers = [] is invalid: give one or more propeller numbers")
    out = []
    for x in items:
        if isinstance(x, bool) or not isinstance(x, (int, np.integer)) or x - 1 not in numbers:
            valid = ", ".join(str(n + 1) for n in numbers) or "none: no flexibly mounted propeller"
            raise v.InputError(f"propellers = {v.short_repr(x)} is invalid: the flexibly mounted "
                               f"propellers of the model are {valid}")
        out.append(int(x) - 1)
    return sorted(set(out))


def clearance(model: Any, V_D: float, factor: float = FACTOR_CS25, *, speeds=None,
              xtol: float = 0.01, static_divergence: bool = True, low_speed: bool = True,
              minimum: bool = True, frequency_range: tuple[float, float] = (1.0, 30.0),
              n_scan: int = 8, frequency_tol: float = 1e-3, propellers=None,
              processes: int = 1, client=None, progress=None,
              checkpoint=None) -> Clearance:
    """Clearance of `model` to ``factor · V_D`` (module docstring).

    Parameters
    ----------
    model : Model
    V_D : float
        Design dive speed [m/s].
    factor : float
        1.15 (CS/FAR 25.629, the default) or 1.2 (14 CFR 23.629), or any factor ≥ 1.
    speeds : array, optional
        The analyses' initial speed grid [m/s] (default :func:`clearance_speeds`).
    xtol : float
        Accuracy of each critical speed [m/s].
    static_divergence, low_speed : bool
        The thesis's exclusions (:func:`propwhirl.studies.critical.critical_instability`).
    minimum : bool
        Also find each propeller's minimum clearing f_θ and f_ψ (:func:`minimum_frequency`,
        in `frequency_range` [Hz], ``n_scan`` samples, to ``frequency_tol`` [Hz]).
    propellers : sequence of int, optional
        The propellers (numbered from 1) whose minimum frequencies are searched (default all).
    processes, client, progress, checkpoint
        How the searches' analyses run (:func:`propwhirl.studies.execution.map_analyses`:
        local processes, a Dask cluster, a progress bar, partial-results files beside
        ``checkpoint.path`` per phase, :func:`phase_checkpoints`, resumed with
        ``resume=True``).  The model's own analysis runs in this process.
    """
    V_req = required_speed(V_D, factor)
    grid = clearance_speeds(model, V_req, speeds)
    chosen = _check_propellers(model, propellers)
    v.integer_at_least("processes", processes, 1)
    searches = [(pd.number, name) for pd in model.dof_map().propellers
                if chosen is None or pd.number in chosen for name in ("f_theta", "f_psi")]
    if minimum:              # the search's options, checked before the first analysis
        for number, name in searches:
            _check_search(_frequency_path(model, number, name), frequency_range,
                          n_scan, frequency_tol)
    a, is_wing, crit = _analysis_critical(model, grid, xtol, static_divergence, low_speed)

    def margin(e) -> Margin:
        return Margin(e.kind, e.event, e.label, float(e.V), float(e.frequency_hz),
                      float(e.V) / V_req - 1.0, _counted(a, e, is_wing, static_divergence, low_speed))

    margins = tuple(margin(e) for e in a.onsets)
    cmargin = None if crit is None else next(m for e, m in zip(a.onsets, margins) if e is crit)
    cleared = crit is None or crit.V > V_req
    found: list[MinimumFrequency] = []
    if minimum and searches:
        found = _minimum_frequencies(
            model, searches, V_req, grid, frequency_range=frequency_range, n_scan=n_scan,
            frequency_tol=frequency_tol, xtol=xtol, static_divergence=static_divergence,
            low_speed=low_speed, processes=processes, client=client, progress=progress,
            checkpoint=checkpoint)
    return Clearance(getattr(model, "name", ""), float(V_D), float(factor), V_req, cleared,
                     cmargin, margins, tuple(found), convention(static_divergence, low_speed),
                     (float(grid[0]), float(grid[-1])), 1 + sum(q.analyses for q in found))
