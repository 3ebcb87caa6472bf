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

import csv
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
from propwhirl.model import validity
from propwhirl.results import Result, SavedDict
from propwhirl.studies import paths as P
from propwhirl.studies.critical import convention, critical_instability, wing_divergence_predicate

#: The factors of the regulations [-]: CS/FAR 25.629 and 14 CFR 23.629.
FACTOR_CS25 = 1.15
FACTOR_CFR23 = 1.2



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


@dataclass(frozen=True)
class MinimumFrequency:
    """The minimum mount frequency of one propeller that clears the requirement.

    propeller: numbered from 1; parameter: "f_theta" or "f_psi"; path: its parameter path;
    current: the model's value [Hz] (None when given as a stiffness); frequency [Hz] (None when
    no frequency of the range clears); status: "found", "at or below the range" (every
    sampled frequency clears: the minimum is ≤ the range's bottom), "none in range";
    critical_speed: V_crit [m/s] at `frequency` (the check; NaN: no instability in range);
    range [Hz]; note: e.g. samples below the minimum that clear too (not monotone);
    analyses: analyses it took.
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

    def to_dict(self) -> dict[str, Any]:
        """The fields (a non-finite number as None)."""
        return _clean(vars(self))

    @classmethod
    def from_dict(cls, d: Any, where: str = "minimum") -> "MinimumFrequency":
        """The entry written by :meth:`to_dict`, checked (a null critical speed as NaN)."""
        r = SavedDict(d, where, [f.name for f in fields(cls)])
        lo, hi = r.array("range", shape=(2,))
        return cls(r.integer("propeller", 1), r.string("parameter", ("f_theta", "f_psi")),
                   r.string("path"), r.number("current", optional=True),
                   r.number("frequency", optional=True),
                   r.string("status", ("found", "at or below the range", "none in range")),
                   r.number_or_nan("critical_speed"), (float(lo), float(hi)), r.string("note"),
                   r.integer("analyses", 0))


@dataclass(frozen=True)
class Clearance(Result):
    """The clearance result (module docstring); ``cleared`` decides the CLI's exit code.

    A :class:`~propwhirl.results.Result` of kind "clearance" (format
    ``propwhirl.clearance/1``): :meth:`save` / :meth:`load`."""

    KIND: ClassVar[str] = "clearance"
    VERSION: ClassVar[int] = 1
    READABLE: ClassVar[tuple[int, ...]] = (1,)
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
            elif q.status == "at or below the range":
                text = f"<= {q.range[0]:g} Hz{cur}: every sampled frequency of {rng} clears"
            else:
                text = f"none in {rng}{cur}: even {q.range[1]:g} Hz does not clear"
            lines.append(f"  propeller {q.propeller} minimum {name}: {text}"
                         + (f"; {q.note}" if q.note else ""))
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
        w = csv.writer(buf, lineterminator="\n")
        w.writerow(["model", "V_D [m/s]", "factor", "V_required [m/s]", "cleared"])
        w.writerow([self.model_name, f"{self.V_D:g}", f"{self.factor:g}", f"{self.V_required:.10g}",
                    "yes" if self.cleared else "no"])
        w.writerow(["section", "kind", "event", "mode", "V [m/s]", "frequency [Hz]", "margin", "counted"])
        for m in self.margins:
            w.writerow(["instability", m.kind, m.event, m.mode, f"{m.V:.10g}", f"{m.frequency_hz:.10g}",
                        f"{m.margin:.10g}", "yes" if m.counted else "no"])
        w.writerow(["section", "propeller", "parameter", "status", "frequency [Hz]", "current [Hz]",
                    "critical_speed [m/s]", "range_low [Hz]", "range_high [Hz]", "note"])
        for q in self.minimum:
            w.writerow(["minimum", q.propeller, q.parameter, q.status,
                        "" if q.frequency is None else f"{q.frequency:.10g}",
                        "" if q.current is None else f"{q.current:.10g}",
                        "" if not math.isfinite(q.critical_speed) else f"{q.critical_speed:.10g}",
                        f"{q.range[0]:g}", f"{q.range[1]:g}", q.note])
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
    number the model's aerodynamics refuse (:data:`propwhirl.model.validity.MACH_REFUSED`)
    and hold at most :data:`propwhirl.limits.MAX_SPEEDS` speeds (one-line InputErrors naming
    V_D, factor x V_D and the largest valid value)."""
    if speeds is not None:
        grid = v.increasing("speeds", speeds, "m/s")
        if grid[-1] <= V_required:
            raise v.InputError(f"speeds end at {grid[-1]:g} m/s: must reach beyond factor V_D = "
                               f"{V_required:.2f} m/s")
        _check_top_speed(model, float(grid[-1]), V_required, "the speeds' end")
        return grid
    lo, hi, step = (float(x) for x in model.flight.speed_range)
    hi = max(hi, 1.05 * V_required)
    _check_top_speed(model, hi, V_required, "1.05 factor x V_D")
    count = limits.grid_count(lo, hi, step)
    if not count <= limits.MAX_SPEEDS:
        raise v.InputError(
            f"factor x V_D = {V_required:g} m/s is invalid: the analyses' speed grid from "
            f"{lo:g} m/s in the model's steps of {step:g} m/s to {hi:g} m/s would hold "
            f"{count:,.0f} speeds, at most {limits.MAX_SPEEDS:,}: give a smaller V_D or speeds")
    n = int(math.ceil((hi - lo) / step - 1e-9))
    return lo + step * np.arange(n + 1)


def _check_top_speed(model: Any, top: float, V_required: float, what: str) -> None:
    """Refuse analyses to `top` [m/s] (`what`) at a Mach number the model's aerodynamics
    refuse."""
    if not validity.has_aerodynamics(model):
        return
    a = float(model.flight.speed_of_sound)
    if top / a >= validity.MACH_REFUSED:
        raise v.InputError(
            f"factor x V_D = {V_required:g} m/s is invalid: the analyses go to {what}, "
            f"{top:g} m/s, Mach {top / a:.3g} at a = {a:g} m/s; the aerodynamics are subsonic "
            f"and propwhirl refuses Mach >= {validity.MACH_REFUSED:g} (V >= "
            f"{validity.MACH_REFUSED * a:.1f} m/s)")


def _analysis_critical(model, speeds, xtol, static_div, low_speed):
    a = analyse(model, speeds, xtol=xtol)
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


def minimum_frequency(model: Any, number: int, name: str, V_required: float, speeds: np.ndarray,
                      *, frequency_range: tuple[float, float] = (1.0, 30.0), n_scan: int = 8,
                      frequency_tol: float = 1e-3, xtol: float = 0.01,
                      static_divergence: bool = True, low_speed: bool = True) -> MinimumFrequency:
    """The minimum `name` ("f_theta"/"f_psi") [Hz] of propeller `number` (its index in the
    model, from 0) clearing `V_required` [m/s] (module docstring)."""
    from propwhirl.studies.sweeps import evaluate

    if name not in ("f_theta", "f_psi"):
        raise v.InputError(f"parameter = {name!r} is invalid: must be 'f_theta' or 'f_psi'")
    par = _frequency_path(model, number, name)
    lo, hi = _check_search(par, frequency_range, n_scan, frequency_tol)
    count = [0]
    vcrit: dict[float, float] = {}

    def V_crit(f: float) -> float:
        if f not in vcrit:
            count[0] += 1
            row = evaluate((par.set(model, f), speeds, xtol, static_divergence, low_speed))
            vcrit[f] = row["critical_speed"]
        return vcrit[f]

    def h(f: float) -> float:  # > 0: cleared
        Vc = V_crit(f)
        return (speeds[-1] if not math.isfinite(Vc) else Vc) - V_required

    def result(freq, status, note=""):
        Vc = float("nan") if freq is None else V_crit(freq)
        return MinimumFrequency(number + 1, name, par.path, par.value(model), freq, status, Vc,
                                (lo, hi), note, count[0])

    if h(hi) <= 0:
        return result(None, "none in range")
    f = np.geomspace(lo, hi, n_scan)
    f[-1] = hi
    ok = [h(float(x)) > 0 for x in f]
    k = len(f) - 1
    while k > 0 and ok[k - 1]:
        k -= 1
    if k == 0:
        return result(lo, "at or below the range")
    below = [f"{x:.3g}" for x, good in zip(f[:k - 1], ok[:k - 1]) if good]
    note = f"also clears at the sampled {', '.join(below)} Hz (not monotone)" if below else ""
    root = brentq(h, float(f[k - 1]), float(f[k]), xtol=frequency_tol)
    freq = math.ceil((root + frequency_tol) / frequency_tol) * frequency_tol
    while h(freq) <= 0 and freq < f[k]:     # the check: the reported frequency clears
        freq = min(freq + frequency_tol, float(f[k]))
    return result(float(freq), "found", note)


def clearance(model: Any, V_D: float, factor: float = FACTOR_CS25, *, speeds=None,
              xtol: float = 0.01, static_divergence: bool = True, low_speed: bool = True,
              minimum: bool = True, frequency_range: tuple[float, float] = (1.0, 30.0),
              n_scan: int = 8, frequency_tol: float = 1e-3) -> Clearance:
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
    """
    v.positive("V_D", V_D, "m/s")
    v.in_range("factor", factor, 1.0, 3.0)
    V_req = float(factor) * float(V_D)
    grid = clearance_speeds(model, V_req, speeds)
    if minimum:              # the search's options, checked before the first analysis
        for pd in model.dof_map().propellers:
            for name in ("f_theta", "f_psi"):
                _check_search(_frequency_path(model, pd.number, name), frequency_range,
                              n_scan, frequency_tol)
    a, is_wing, crit = _analysis_critical(model, grid, xtol, static_divergence, low_speed)

    def margin(e) -> Margin:
        return Margin(e.kind, e.event, e.label, float(e.V), float(e.frequency_hz),
                      float(e.V) / V_req - 1.0, _counted(a, e, is_wing, static_divergence, low_speed))

    margins = tuple(margin(e) for e in a.onsets)
    cmargin = None if crit is None else next(m for e, m in zip(a.onsets, margins) if e is crit)
    cleared = crit is None or crit.V > V_req
    found: list[MinimumFrequency] = []
    if minimum:
        for pd in model.dof_map().propellers:
            for name in ("f_theta", "f_psi"):
                found.append(minimum_frequency(
                    model, pd.number, name, V_req, grid, frequency_range=frequency_range,
                    n_scan=n_scan, frequency_tol=frequency_tol, xtol=xtol,
                    static_divergence=static_divergence, low_speed=low_speed))
    return Clearance(getattr(model, "name", ""), float(V_D), float(factor), V_req, cleared,
                     cmargin, margins, tuple(found), convention(static_divergence, low_speed),
                     (float(grid[0]), float(grid[-1])), 1 + sum(q.analyses for q in found))
