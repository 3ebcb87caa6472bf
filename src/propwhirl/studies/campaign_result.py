"""The result of a whirl-flutter clearance campaign (:mod:`propwhirl.studies.campaign`): one
:class:`PointRow` per (case, envelope point) — the verdict, the margin, the critical
instability, the least damping and its slope at the required speed — the
:class:`CaseSummary` of each case, and :class:`CampaignResult`, a
:class:`~propwhirl.results.Result` of kind "campaign" (its JSON file, its CSV table and the
plain-text summary ``propwhirl certify`` prints).  Each row keeps, in :class:`PointPlot`, what the
report's figures of it need (:mod:`propwhirl.app.report`): the V-g-f curves of the analysis's
modes of interest and the critical mode's shape."""
from __future__ import annotations

import io
import math
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any, ClassVar

import numpy as np

from propwhirl import fileio
from propwhirl import validate as v
from propwhirl.results import Result, SavedDict

#: The keys of a point's row, and which of them are numbers and strings.
_ROW_KEYS = ("case", "description", "altitude_m", "airspeed", "V_D_given", "V_D", "mach_limited",
             "V_required", "rule", "cleared", "reason", "critical_speed", "margin_m_per_s",
             "margin_percent", "kind", "event", "mode", "frequency_hz", "whirl",
             "propeller_shares", "analysed_to", "least_g", "least_g_V", "least_g_mode",
             "least_g_to_V_D", "least_g_to_V_D_mode", "g_at_required", "dzeta_dV_at_required",
             "mode_at_required", "error", "damping_g", "damping_g_V", "damping_g_mode")
_ROW_NUMBERS = ("critical_speed", "margin_m_per_s", "margin_percent", "frequency_hz",
                "analysed_to", "least_g", "least_g_V", "least_g_to_V_D", "g_at_required",
                "dzeta_dV_at_required")
#: Row keys that files written before them lack (read as "" or None).
_ROW_LATER = ("rule", "damping_g", "damping_g_V", "damping_g_mode")
_ROW_LATER_NUMBERS = ("damping_g", "damping_g_V")
#: The requirements a row can fail, by the start of its reason's parts (:attr:`PointRow.failed`).
REQUIREMENTS = {"speed": "no instability up to the required speed",
                "damping": "the damping requirement", "analysis": "the analysis failed"}
_ROW_STRINGS = ("case", "description", "airspeed", "reason", "kind", "event", "mode", "whirl",
                "least_g_mode", "least_g_to_V_D_mode", "mode_at_required", "error")


@dataclass(frozen=True, eq=False)
class PointPlot:
    """What the report draws of one (case, point): the V-g-f curves and the critical mode.

    V: the analysed speeds [m/s] (the analysis's sweep nodes, T); modes: the names of the
    modes of interest (the modes with an event and the oscillatory modes of lowest frequency,
    n); zeta: (T, n) damping ratio ζ [-] and frequency_hz: (T, n) f [Hz], where `oscillatory`
    (T, n) is true (0 elsewhere), and their exact slopes dzeta_dV [s/m] and dfrequency_dV
    [Hz s/m] (from dλ/dV: the figure draws cubic Hermite curves between the speeds); events: (V [m/s], f [Hz], kind, event, mode) of those modes'
    instabilities; shape: the critical mode's shape (None: no critical instability) —
    {"V": m/s, "eigenvalue": (re, im) [1/s], "y": wing node positions [m], "h", "alpha":
    complex values at the nodes, "propellers": [(number from 1, y [m] or None, θ̂, ψ̂)]},
    normalised to its largest h, α, θ or ψ entry."""

    V: np.ndarray
    modes: tuple[str, ...]
    zeta: np.ndarray
    frequency_hz: np.ndarray
    oscillatory: np.ndarray
    dzeta_dV: np.ndarray
    dfrequency_dV: np.ndarray
    events: tuple[tuple[float, float, str, str, str], ...]
    shape: dict[str, Any] | None

    def __eq__(self, other: object) -> bool:
        return isinstance(other, PointPlot) and self.to_dict() == other.to_dict()

    def to_dict(self) -> dict[str, Any]:
        shape = None
        if self.shape is not None:
            sh = self.shape
            shape = {"V": float(sh["V"]), "eigenvalue": [float(complex(sh["eigenvalue"]).real),
                                                         float(complex(sh["eigenvalue"]).imag)],
                     "y": [float(y) for y in sh["y"]],
                     "h": _complex_dict(sh["h"]), "alpha": _complex_dict(sh["alpha"]),
                     "propellers": [{"number": int(n), "y": None if y is None else float(y),
                                     "theta": [float(complex(t).real), float(complex(t).imag)],
                                     "psi": [float(complex(p).real), float(complex(p).imag)]}
                                    for n, y, t, p in sh["propellers"]]}
        return {"V": [float(x) for x in self.V], "modes": list(self.modes),
                "zeta": np.asarray(self.zeta, float).tolist(),
                "frequency_hz": np.asarray(self.frequency_hz, float).tolist(),
                "oscillatory": np.asarray(self.oscillatory, bool).tolist(),
                "dzeta_dV": np.asarray(self.dzeta_dV, float).tolist(),
                "dfrequency_dV": np.asarray(self.dfrequency_dV, float).tolist(),
                "events": [[float(a), float(b), str(k), str(e), str(m)]
                           for a, b, k, e, m in self.events], "shape": shape}

    @classmethod
    def from_dict(cls, d: Any, where: str = "plot") -> "PointPlot":
        r = SavedDict(d, where, ("V", "modes", "zeta", "frequency_hz", "oscillatory", "dzeta_dV",
                                 "dfrequency_dV", "events", "shape"))
        V = r.array("V")
        modes = r.strings("modes")
        shape = (V.size, len(modes))
        zeta = r.array("zeta", ndim=2, shape=shape)
        freq = r.array("frequency_hz", ndim=2, shape=shape)
        osc = r.array("oscillatory", bool, ndim=2, shape=shape)
        dz = r.array("dzeta_dV", ndim=2, shape=shape)
        df = r.array("dfrequency_dV", ndim=2, shape=shape)
        events = []
        for w, e in r.items("events"):
            if not (isinstance(e, list) and len(e) == 5 and all(
                    isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(x)
                    for x in e[:2]) and all(isinstance(x, str) for x in e[2:])):
                raise v.InputError(f"{w}: must be [V, frequency_hz, kind, event, mode]")
            events.append((float(e[0]), float(e[1]), e[2], e[3], e[4]))
        sh = None
        if r.raw("shape") is not None:
            s = r.sub("shape", ("V", "eigenvalue", "y", "h", "alpha", "propellers"))
            y = s.array("y")
            lam = s.array("eigenvalue", shape=(2,))
            props = []
            for w, p in s.items("propellers"):
                q = SavedDict(p, w, ("number", "y", "theta", "psi"))
                props.append((q.integer("number", 1), q.number("y", optional=True),
                              complex(*q.array("theta", shape=(2,))),
                              complex(*q.array("psi", shape=(2,)))))
            sh = {"V": s.number("V"), "eigenvalue": complex(lam[0], lam[1]), "y": y,
                  "h": s.complex_array("h", 1, (y.size,)),
                  "alpha": s.complex_array("alpha", 1, (y.size,)), "propellers": props}
        return cls(V, modes, zeta, freq, osc, dz, df, tuple(events), sh)


def _complex_dict(x: Any) -> dict[str, list[float]]:
    a = np.asarray(x, dtype=complex)
    return {"re": a.real.tolist(), "im": a.imag.tolist()}


@dataclass(frozen=True)
class PointRow:
    """One (case, envelope point) of a campaign's result.

    Speeds are true airspeeds [m/s]; V_required: the speed the point must clear and rule: the
    rule that sets it (:func:`propwhirl.studies.campaign.required_speed`: "25.629(b)(1) 1.15
    V_D", "25.629(b)(2)(i) V_D", "25.629(b)(2)(ii) 1.15 V_C", "23.629 1.2 V_D", ...; "" in
    files written before it); margin_m_per_s = V_crit − V_required, margin_percent =
    100 (V_crit / V_required − 1) (None when no counted instability lies in the analysed range,
    which ends at `analysed_to` [m/s], beyond V_required); least_g: the least g = 2ζ of the
    oscillatory modes up to V_required (at least_g_V, of least_g_mode); least_g_to_V_D: up to
    V_D (the damping requirement's range); g_at_required and dzeta_dV_at_required [s/m]: the
    least damped mode at V_required and the slope of its ζ; propeller_shares:
    [[propeller, share, whirl], ...] of the critical mode; reason: why it does not clear ("" when
    it does: "; "-separated parts, each starting with the requirement it fails, "speed: ...",
    "damping: ...", or "analysis failed"); error: the message of an analysis that failed; plot:
    what the report draws (:class:`PointPlot`; None in files of version 1 and for a failed
    analysis); damping_g, damping_g_V [m/s], damping_g_mode: the least g the campaign's
    damping requirement judges (its damping, speeds and modes:
    :class:`propwhirl.analysis.damping_requirement.DampingRequirement`; None without one)."""

    case: str
    description: str
    altitude_m: float
    airspeed: str
    V_D_given: float
    V_D: float
    mach_limited: bool
    V_required: float
    cleared: bool
    reason: str
    critical_speed: float | None
    margin_m_per_s: float | None
    margin_percent: float | None
    kind: str
    event: str
    mode: str
    frequency_hz: float | None
    whirl: str
    propeller_shares: tuple[tuple[int, float, str], ...]
    analysed_to: float | None
    least_g: float | None
    least_g_V: float | None
    least_g_mode: str
    least_g_to_V_D: float | None
    least_g_to_V_D_mode: str
    g_at_required: float | None
    dzeta_dV_at_required: float | None
    mode_at_required: str
    error: str
    plot: PointPlot | None = None
    rule: str = ""
    damping_g: float | None = None
    damping_g_V: float | None = None
    damping_g_mode: str = ""

    @property
    def failed(self) -> tuple[str, ...]:
        """The requirements this row fails (keys of :data:`REQUIREMENTS`), from its reason:
        "speed", "damping", "analysis" (files written before the prefixes: a part starting
        "g = " is the damping's, any other the speed's)."""
        out = []
        for part in filter(None, self.reason.split("; ")):
            key = ("analysis" if part.startswith("analysis failed") else
                   "damping" if part.startswith(("damping", "g = ")) else "speed")
            if key not in out:
                out.append(key)
        return tuple(out)

    def to_dict(self) -> dict[str, Any]:
        """The row's numbers (the CSV's columns) and, under "plot", its figures' data."""
        d = {k: getattr(self, k) for k in _ROW_KEYS}
        d["propeller_shares"] = [list(s) for s in self.propeller_shares]
        d = {k: (None if isinstance(x, float) and not math.isfinite(x) else x)
             for k, x in d.items()}
        d["plot"] = None if self.plot is None else self.plot.to_dict()
        return d

    @classmethod
    def from_dict(cls, d: Any, where: str = "row") -> "PointRow":
        r = SavedDict(d, where, [k for k in _ROW_KEYS if k not in _ROW_LATER],
                      ("plot", *_ROW_LATER))
        vals: dict[str, Any] = {}
        for k in _ROW_NUMBERS:
            vals[k] = r.number(k, optional=True)
        for k in _ROW_STRINGS:
            vals[k] = r.string(k)
        for k in _ROW_LATER:
            if k in _ROW_LATER_NUMBERS:
                vals[k] = r.number(k, optional=True) if r.has(k) else None
            else:
                vals[k] = r.string(k) if r.has(k) else ""
        for k in ("altitude_m", "V_D_given", "V_D", "V_required"):
            vals[k] = r.number(k)
        for k in ("mach_limited", "cleared"):
            vals[k] = r.boolean(k)
        shares = []
        for w, s in r.items("propeller_shares"):
            if not (isinstance(s, list) and len(s) == 3 and isinstance(s[0], int)
                    and not isinstance(s[0], bool) and isinstance(s[1], (int, float))
                    and not isinstance(s[1], bool) and math.isfinite(s[1])
                    and isinstance(s[2], str)):
                raise v.InputError(f"{w}: must be [propeller, share, whirl]")
            shares.append((int(s[0]), float(s[1]), str(s[2])))
        vals["propeller_shares"] = tuple(shares)
        if r.has("plot") and r.raw("plot") is not None:
            vals["plot"] = PointPlot.from_dict(r.raw("plot"), r.name("plot"))
        return cls(**vals)


@dataclass(frozen=True)
class CaseSummary:
    """A case over its envelope: cleared (every point), its worst point (the least margin in
    %, or the first that fails) and the number of points that fail."""

    case: str
    cleared: bool
    worst: PointRow
    failing: int


@dataclass(frozen=True)
class CampaignResult(Result):
    """The result of a campaign: one :class:`PointRow` per (case, envelope point), case-major.

    A :class:`~propwhirl.results.Result` of kind "campaign" (``propwhirl.campaign/1``):
    :meth:`save` / :meth:`load`; :meth:`to_csv` the same numbers as a table;
    :meth:`format` the plain-text summary; ``cleared`` decides the exit code of
    ``propwhirl certify``.  Version 2 added each row's ``plot`` (:class:`PointPlot`, the
    report's figures); version-1 files are read with ``plot`` None.

    Attributes
    ----------
    name : str
        The campaign's name.
    model_name : str
        The model's name.
    regulation : str
        "cs25", "far25", "far23" or "explicit".
    factor : float
        The speed factor [-].
    min_damping_g : float or None
        The least g = 2ζ [-] required up to V_D (None: none).
    convention : str
        Which events count as critical.
    rows : tuple of PointRow
        Per (case, point): V_D and V_required [m/s], verdict, critical speed [m/s], margins
        [m/s, %], frequency [Hz], least damping g [-] and dζ/dV [s/m], the figure data.
    analyses : int
        The analyses run.
    damping : dict or None
        The damping requirement's reading as the campaign gave it: min_damping_g [-],
        applies_to ("total", "aerodynamic"), above_m_per_s [m/s], modes ("all",
        "critical"), source (None: not given).
    damping_text : str
        The requirement in words, as the report prints it ("" without one).

    Examples
    --------
    >>> import pathlib, tempfile
    >>> from propwhirl.studies import Campaign, CampaignResult, Case, envelope, run_campaign
    >>> from propwhirl.model import FlightCondition, Installation, PropellerWing
    >>> from propwhirl.cases.ch09_baseline import baseline_propeller, baseline_wing
    >>> model = PropellerWing(baseline_wing(n_elements=4),       # 4 elements, 100-200 m/s
    ...                       FlightCondition(0.96287, speed_range=(100.0, 200.0, 20.0)),
    ...                       (Installation(baseline_propeller(), 5.7),))
    >>> r = run_campaign(Campaign("demo", model, (Case("nominal"),), envelope(120.0, [0.0]),
    ...                           static_divergence=False))
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     again = CampaignResult.load(r.save(pathlib.Path(folder) / "campaign.json"))
    >>> again.cleared, round(again.rows[0].V_required, 1), round(again.rows[0].margin_percent, 1)
    (True, 138.0, 5.4)
    """

    KIND: ClassVar[str] = "campaign"
    VERSION: ClassVar[int] = 2
    READABLE: ClassVar[tuple[int, ...]] = (1, 2)
    WHAT: ClassVar[str] = "campaign result file"

    name: str
    model_name: str
    regulation: str
    factor: float
    min_damping_g: float | None
    convention: str
    rows: tuple[PointRow, ...]
    analyses: int = 0
    #: the damping requirement's reading as the campaign file gave it ({"min_damping_g",
    #: "applies_to", "above_m_per_s", "modes", "source"}; None: not given) and in words
    damping: dict[str, Any] | None = None
    damping_text: str = ""

    @property
    def cleared(self) -> bool:
        return all(r.cleared for r in self.rows)

    def cases(self) -> list[CaseSummary]:
        """Every case's summary, in campaign order."""
        out: dict[str, list[PointRow]] = {}
        for r in self.rows:
            out.setdefault(r.case, []).append(r)

        def key(r: PointRow) -> tuple:
            return (r.cleared, -math.inf if r.error else
                    (math.inf if r.margin_percent is None else r.margin_percent))

        return [CaseSummary(name, all(r.cleared for r in rows), min(rows, key=key),
                            sum(not r.cleared for r in rows)) for name, rows in out.items()]

    def decided_by(self) -> list[tuple[str, int]]:
        """Which requirements the failing rows fail: (the requirement in words,
        :data:`REQUIREMENTS`; the number of (case, point) rows that fail it), most first;
        empty when every row clears."""
        counts: dict[str, int] = {}
        for r in self.rows:
            for key in r.failed:
                counts[key] = counts.get(key, 0) + 1
        return [(REQUIREMENTS[k], n) for k, n in sorted(counts.items(), key=lambda kv: -kv[1])]

    def format(self) -> str:
        """The plain-text summary table: one line per case (its worst envelope point)."""
        g = "" if self.min_damping_g is None else (
            f"; g >= {self.min_damping_g:g} up to V_D" + (
                "" if self.damping is None else
                f" ({self.damping['applies_to']} damping"
                + (f" from {self.damping['above_m_per_s']:g} m/s" if self.damping[
                    "above_m_per_s"] else "") + f", {self.damping['source']})"))
        head = (f"{self.name}: {self.model_name}: clearance to {self.factor:g} V_D "
                f"({self.regulation}{g}); {self.convention}")
        if any(r.rule.startswith("25.629(b)(2)") for r in self.rows):
            head += "; failure cases: 25.629(b)(2)"
        summaries = self.cases()
        w = max([4] + [len(s.case) for s in summaries])
        wr = max([4] + [len(s.worst.rule) for s in summaries])
        lines = [head, f"{'case':{w}s} {'verdict':11s} {'alt [m]':>8s} {'rule':{wr}s} "
                       f"{'V_req':>8s} "
                       f"{'V_crit':>8s} {'margin':>8s} {'margin':>7s} {'min g':>7s} "
                       f"{'dzeta/dV':>9s}  critical", f"{'':{w}s} {'':11s} {'':>8s} {'':{wr}s} "
                       f"{'[m/s]':>8s} {'[m/s]':>8s} {'[m/s]':>8s} {'[%]':>7s} {'':>7s} {'[s/m]':>9s}"]
        for s in summaries:
            r = s.worst
            num = (lambda x, f: "-" if x is None else format(x, f))
            crit = ("analysis failed: " + r.error if r.error else "none in range (to "
                    f"{r.analysed_to:.1f} m/s)" if r.kind == "none" else
                    f"{r.kind} {r.event} of {r.mode}"
                    + (f" at {num(r.frequency_hz, '.2f')} Hz" if r.kind == "flutter" else "")
                    + (f", {r.whirl} whirl" if r.whirl else ""))
            verdict = "cleared" if s.cleared else f"NOT ({s.failing})"
            lines.append(f"{s.case:{w}s} {verdict:11s} {r.altitude_m:8.0f} {r.rule:{wr}s} "
                         f"{r.V_required:8.2f} {num(r.critical_speed, '8.2f'):>8s} "
                         f"{num(r.margin_m_per_s, '+8.2f'):>8s} {num(r.margin_percent, '+7.2f'):>7s} "
                         f"{num(r.least_g, '7.4f'):>7s} {num(r.dzeta_dV_at_required, '+9.2e'):>9s}"
                         f"  {crit}" + (f" ({r.reason})" if r.reason and not r.error else ""))
        n_ok = sum(s.cleared for s in summaries)
        lines.append("(each case's least-margin altitude; every altitude: the CSV)")
        decided = "; ".join(f"{what}: {n} of {len(self.rows)} points"
                            for what, n in self.decided_by())
        lines.append(f"{n_ok} of {len(summaries)} cases cleared; {self.analyses} analyses: "
                     + ("CLEARED" if self.cleared else f"NOT CLEARED (failed: {decided})"))
        return "\n".join(lines)

    def encode(self) -> dict[str, Any]:
        return {"name": self.name, "model_name": self.model_name, "regulation": self.regulation,
                "factor": self.factor, "min_damping_g": self.min_damping_g,
                "convention": self.convention, "cleared": self.cleared,
                "cases": [{"case": s.case, "cleared": s.cleared, "failing_points": s.failing}
                          for s in self.cases()],
                "rows": [r.to_dict() for r in self.rows], "analyses": self.analyses,
                "damping": self.damping, "damping_text": self.damping_text}

    @classmethod
    def decode(cls, d: Mapping[str, Any], version: int, where: str = "") -> "CampaignResult":
        r = SavedDict(d, where, ("name", "model_name", "regulation", "factor", "min_damping_g",
                                 "convention", "cleared", "cases", "rows", "analyses"),
                      ("damping", "damping_text"))
        out = cls(r.string("name"), r.string("model_name"), r.string("regulation"),
                  r.number("factor"), r.number("min_damping_g", optional=True),
                  r.string("convention"),
                  tuple(PointRow.from_dict(x, w) for w, x in r.items("rows")),
                  r.integer("analyses", 0), _damping(r),
                  r.string("damping_text") if r.has("damping_text") else "")
        if r.boolean("cleared") != out.cleared:
            raise v.InputError(f"{r.name('cleared')}: does not match the rows' verdicts")
        return out

    def to_csv(self, path: str | Path | None = None) -> str:
        """Every row's numbers as CSV (one line per (case, point); shares as
        "propeller:share:whirl" joined with spaces; empty for a missing number)."""
        buf = io.StringIO()
        w = fileio.csv_writer(buf, lineterminator="\n")
        w.writerow(_ROW_KEYS)
        for r in self.rows:
            d = r.to_dict()
            del d["plot"]
            d["propeller_shares"] = " ".join(f"{p}:{s:.6g}:{wh}" for p, s, wh in r.propeller_shares)
            w.writerow(["" if d[k] is None else ("yes" if d[k] else "no") if isinstance(d[k], bool)
                        else f"{d[k]:.10g}" if isinstance(d[k], float) else d[k] for k in _ROW_KEYS])
        text = buf.getvalue()
        if path is not None:
            fileio.write_text(path, text, what="campaign table")
        return text


def _damping(r: SavedDict) -> dict[str, Any] | None:
    """The saved damping requirement's reading (None: not given, or a file before it)."""
    if not r.has("damping") or r.raw("damping") is None:
        return None
    s = r.sub("damping", ("min_damping_g", "applies_to", "above_m_per_s", "modes", "source"))
    return {"min_damping_g": s.number("min_damping_g"), "applies_to": s.string("applies_to"),
            "above_m_per_s": s.number("above_m_per_s"), "modes": s.string("modes"),
            "source": s.string("source")}
