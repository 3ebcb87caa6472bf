"""Stability boundaries in a parameter plane, traced by continuation (the whirl-flutter
stability diagram).

Two curves of a plane of two parameters p = (p₁, p₂) of a model (any numeric fields, by
their paths, :mod:`propwhirl.studies.paths`; e.g. f_θ–f_ψ or K_θ–K_ψ of a propeller):

* the **neutral-stability curve** at one airspeed V — where the least stable mode of the
  state matrix A(V) (eq. 5.4, 6.18, 7.59) is neutrally stable: g(p) = max Re λ(A(V; p)) = 0.
  One evaluation is one eigen-solution of A (:func:`propwhirl.engine.eigenvalues`, the
  engine's).  Every eigenvalue counts (the physical modes, Im λ ≥ 0, carry every real part);
  with ``oscillatory=True`` only complex ones (flutter, not divergence: e.g. the classical
  whirl-flutter diagram of a wing whose static divergence lies below V);
* the **critical-speed contour** V_crit(p) = V_target — g(p) = V_crit(p) − V_target, one
  evaluation one analysis (:func:`propwhirl.studies.sweeps.evaluate`, the studies' one
  definition of the critical speed, with the thesis's exclusions as options).  A point without
  an instability in the analysed range counts as V_crit = the top of that range.

Both are traced by the predictor–corrector (pseudo-arclength) continuation of
:mod:`propwhirl.studies.continuation` from a start point found by a bracketing search along a
line, to the plane's bounds or until the curve closes — not read off a grid.  :func:`grid_map`
samples the same g on a grid and :func:`grid_agreement` compares the two (the check of the
tests, and the coarse map under the plotted curve).

Examples
--------
>>> from propwhirl.cases.registry import case_model
>>> from propwhirl.studies.boundary import neutral_curve
>>> b = neutral_curve(case_model("isolated-propeller"), ("propeller.f_theta", "propeller.f_psi"),
...                   (3.0, 3.0), (12.0, 12.0), V=220.0)
>>> len(b.curves), b.stops[0]
(1, ('bounds', 'bounds'))
>>> b.evaluations < 250      # eigen-solutions (a 50 x 50 map: 2500)
True
"""
from __future__ import annotations

import dataclasses
import io
import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable, ClassVar, Sequence

import numpy as np

from propwhirl import fileio
from propwhirl import validate as v
from propwhirl.engine import eigenvalues
from propwhirl.studies import paths as P
from propwhirl.model.aerodynamics import validity
from propwhirl.model.aerodynamics.dlm import DlmTables
from propwhirl.results import Result, SavedDict
from propwhirl.studies import execution, sweeps
from propwhirl.studies.continuation import ContinuationOptions, Counted, point_key, trace

#: A variant of the model at a point of the plane: ``variant(p) -> Model``.
Variant = Callable[[np.ndarray], Any]

#: Format of the saved boundaries.


def path_variant(model: Any, parameters: Sequence[str]) -> tuple[Variant, tuple[P.Parameter, ...]]:
    """``variant(p)``: `model` with the two parameter paths set to p (and the resolved paths).

    Parameters
    ----------
    model : Model
        The model.
    parameters : sequence of str
        Two parameter paths (:mod:`propwhirl.studies.paths`) that can vary together.

    Returns
    -------
    variant : callable
        ``variant(p) -> model`` with the paths set to p = (p₁, p₂) [their units].
    parameters : tuple of Parameter
        The resolved paths (unit, valid range, meaning).

    Examples
    --------
    >>> from propwhirl.studies import path_variant
    >>> from propwhirl.cases.ch09_baseline import isolated_baseline_propeller
    >>> variant, params = path_variant(isolated_baseline_propeller(),
    ...                                ["propeller.f_theta", "propeller.f_psi"])
    >>> [p.unit for p in params]
    ['Hz', 'Hz']
    >>> m = variant([5.0, 6.0])
    >>> m.propeller.f_theta, m.propeller.f_psi
    (5.0, 6.0)
    """
    if len(parameters) != 2:
        raise v.InputError(f"parameters = {list(parameters)!r} is invalid: give two paths")
    params = tuple(P.resolve(model, p) for p in parameters)
    P.check_independent(params)      # the same value twice, or f_theta with K_theta

    def variant(p: np.ndarray) -> Any:
        m = model
        for par, x in zip(params, p):
            m = par.set(m, float(x))
        return m

    return variant, params


# ============================================================================ level functions
def _least_stable(task: tuple) -> complex:
    """The least stable eigenvalue λ [1/s] of A(V) of a model (task: model, V [m/s],
    oscillatory: only complex eigenvalues count) — one evaluation of :class:`DampingLevel`,
    a module-level function so that it runs on worker processes."""
    model, V, oscillatory = task
    lam = eigenvalues(model.state_matrix(np.array([V])))[0]
    if oscillatory:
        lam = lam[np.abs(lam.imag) > 1e-9 * np.maximum(1.0, np.abs(lam))]
        if lam.size == 0:
            raise v.InputError("oscillatory = True but the model has no complex eigenvalue")
    return complex(lam[int(np.argmax(lam.real))])


def _batch(func: Callable[[Any], Any], tasks: list, level: Any, desc: str) -> list:
    """``[func(t) for t in tasks]`` on the level's processes or Dask cluster, with its
    progress (:func:`propwhirl.studies.execution.map_analyses`)."""
    return execution.map_analyses(func, tasks, level.processes, client=level.client,
                                  progress=level.progress, desc=desc)


@dataclass
class DampingLevel:
    """g(p) = max Re λ [1/s] of A(V) of ``variant(p)``; the least stable eigenvalue of every
    evaluated point is kept (``eigenvalue``), so the curve's mode frequency is known.
    processes, client, progress: how :meth:`batch` runs a batch of points
    (:func:`propwhirl.studies.execution.map_analyses`)."""

    variant: Variant
    V: float
    oscillatory: bool = False
    eigenvalue: dict = field(default_factory=dict, repr=False)
    processes: int = 1
    client: Any = None
    progress: Any = None

    def __call__(self, p: np.ndarray) -> float:
        lam = _least_stable((self.variant(p), self.V, self.oscillatory))
        self.eigenvalue[point_key(p)] = lam
        return float(lam.real)

    def batch(self, points: Sequence[np.ndarray], desc: str = "boundary points") -> list[float]:
        """g at every point, as one batch of independent eigen-solutions (in parallel on
        ``processes`` or the Dask cluster, with progress)."""
        lams = _batch(_least_stable, [(self.variant(p), self.V, self.oscillatory)
                                      for p in points], self, desc)
        for p, lam in zip(points, lams):
            self.eigenvalue[point_key(p)] = lam
        return [float(lam.real) for lam in lams]

    def info(self, p: np.ndarray) -> dict[str, Any]:
        lam = self.eigenvalue.get(point_key(p))
        if lam is None:
            self(p)
            lam = self.eigenvalue[point_key(p)]
        return {"frequency_hz": abs(lam.imag) / (2 * math.pi), "real": lam.real}


@dataclass
class CriticalSpeedLevel:
    """g(p) = V_crit(p) − V_target [m/s], V_crit of one analysis of ``variant(p)``
    (:func:`propwhirl.studies.sweeps.evaluate`); no instability: V_crit = the range's top.
    processes, client, progress: how :meth:`batch` runs a batch of points."""

    variant: Variant
    V_target: float
    speeds: np.ndarray | None = None
    xtol: float = 0.01
    static_divergence: bool = True
    low_speed: bool = True
    rows: dict = field(default_factory=dict, repr=False)
    #: the doublet-lattice tables of this level's analyses (one set of AICs per planform)
    tables: DlmTables = field(default_factory=DlmTables, repr=False)
    processes: int = 1
    client: Any = None
    progress: Any = None

    def _task(self, p: np.ndarray) -> tuple:
        return (self.variant(p), self.speeds, self.xtol, self.static_divergence, self.low_speed,
                "auto", self.tables)

    def _value(self, p: np.ndarray, row: dict[str, Any], model: Any) -> float:
        self.rows[point_key(p)] = row
        Vc = row["critical_speed"]
        if not math.isfinite(Vc):
            top = self.speeds[-1] if self.speeds is not None else model.flight.speed_range[1]
            Vc = float(top)
        return Vc - self.V_target

    def __call__(self, p: np.ndarray) -> float:
        task = self._task(p)
        return self._value(p, sweeps.evaluate(task), task[0])

    def batch(self, points: Sequence[np.ndarray], desc: str = "boundary points") -> list[float]:
        """g at every point, as one batch of independent analyses (in parallel on
        ``processes`` or the Dask cluster, with progress)."""
        tasks = [self._task(p) for p in points]
        rows = _batch(sweeps.evaluate, tasks, self, desc)
        return [self._value(p, row, t[0]) for p, row, t in zip(points, rows, tasks)]

    def info(self, p: np.ndarray) -> dict[str, Any]:
        row = self.rows.get(point_key(p))
        if row is None:
            self(p)
            row = self.rows[point_key(p)]
        return {"critical_speed": row["critical_speed"], "kind": row["kind"],
                "mode": row["critical_mode"], "frequency_hz": row["critical_frequency"]}


# ============================================================================ result
@dataclass(frozen=True)
class Boundary(Result):
    """A traced boundary in a parameter plane.

    A :class:`~propwhirl.results.Result` of kind "boundary" (format ``propwhirl.boundary/1``):
    :meth:`save` / :meth:`load`.

    kind: "neutral-stability" (max Re λ = 0 at `speed`) or "critical-speed" (V_crit = `speed`);
    parameters, units: the two paths and their units; lower, upper: the plane's bounds;
    curves: one (N, 2) array per curve; closed: per curve; stops: per curve, why each end
    stopped ("bounds", "closed", "max_points", "corrector failed"); info: per curve, per point
    the critical mode's data (frequency [Hz]; for the contour also kind and mode);
    evaluations: number of eigen-solutions (neutral curve) or analyses (contour), start search
    included; starts: the start points; model_name; settings: the options used.
    """

    kind: str
    parameters: tuple[str, str]
    units: tuple[str, str]
    speed: float
    lower: tuple[float, float]
    upper: tuple[float, float]
    curves: tuple[np.ndarray, ...]
    closed: tuple[bool, ...]
    stops: tuple[tuple[str, ...], ...]
    info: tuple[tuple[dict[str, Any], ...], ...]
    evaluations: int
    starts: np.ndarray
    model_name: str = ""
    settings: dict[str, Any] = field(default_factory=dict)

    KIND: ClassVar[str] = "boundary"
    VERSION: ClassVar[int] = 1
    READABLE: ClassVar[tuple[int, ...]] = (1,)
    WHAT: ClassVar[str] = "boundary file"

    @property
    def evaluation_name(self) -> str:
        return "eigen-solutions" if self.kind == "neutral-stability" else "analyses"

    def format(self) -> str:
        """A text summary: the curves, where they stop, the evaluations, the points."""
        what = (f"neutral-stability curve at V = {self.speed:g} m/s" if self.kind == "neutral-stability"
                else f"critical-speed contour V_crit = {self.speed:g} m/s")
        lines = [f"{self.model_name}: {what} in ({self.parameters[0]}, {self.parameters[1]})",
                 f"  plane: {self.parameters[0]} in [{self.lower[0]:g}, {self.upper[0]:g}] {self.units[0]}, "
                 f"{self.parameters[1]} in [{self.lower[1]:g}, {self.upper[1]:g}] {self.units[1]}",
                 f"  {self.evaluations} {self.evaluation_name} (a 50 x 50 grid map: 2500)"]
        if not self.curves:
            lines.append("  no boundary: no sign change on the start search lines "
                         "(the plane is stable or unstable throughout them)")
        n = len(self.curves)
        if n:
            seeded = self.settings.get("seeded_from_grid")
            lines.append(f"  {n} branch{'es' if n > 1 else ''}, "
                         + (f"every sign change of a {seeded} grid map on one of them"
                            if seeded else "from the start search lines only "
                            "(a branch they miss is not here: a grid map seeds every branch, "
                            "`propwhirl boundary --grid N`)"))
        for i, (c, closed, stops) in enumerate(zip(self.curves, self.closed, self.stops)):
            end = "closed" if closed else "ends " + " and ".join(
                f"at ({p[0]:.4g}, {p[1]:.4g}): {self._end(p, why)}"
                for p, why in zip((c[0], c[-1]), stops))
            lines.append(f"  curve {i + 1}: {len(c)} points, {end}")
            for p, inf in zip(c[:: max(1, len(c) // 12)], self.info[i][:: max(1, len(c) // 12)]):
                extra = f"  f = {inf['frequency_hz']:.3f} Hz" if "frequency_hz" in inf else ""
                if "mode" in inf:
                    extra += f"  {inf['kind']} of {inf['mode']}"
                lines.append(f"    {p[0]:10.4f} {p[1]:10.4f}{extra}")
        return "\n".join(lines)

    def _end(self, p: np.ndarray, why: str) -> str:
        """Why a curve ends at `p`: on which edge of the plane ("bounds"), or the reason."""
        if why != "bounds":
            return why
        edges = [f"{name} = {'lower' if k == 0 else 'upper'}"
                 for j, name in enumerate(self.parameters)
                 for k, edge in enumerate((self.lower[j], self.upper[j]))
                 if abs(p[j] - edge) <= 1e-6 * max(1.0, abs(self.upper[j] - self.lower[j]))]
        return "the plane's edge " + (" and ".join(edges) if edges else "")

    def encode(self) -> dict[str, Any]:
        def clean(x: Any) -> Any:
            if isinstance(x, float) and not math.isfinite(x):
                return None
            return x

        return {"kind": self.kind, "model_name": self.model_name,
                "parameters": list(self.parameters), "units": list(self.units),
                "speed": self.speed, "lower": list(self.lower), "upper": list(self.upper),
                "evaluations": self.evaluations, "evaluation": self.evaluation_name,
                "starts": self.starts.tolist(), "settings": dict(self.settings),
                "curves": [{"points": c.tolist(), "closed": cl, "stops": list(st),
                            "info": [{k: clean(x) for k, x in d.items()} for d in inf]}
                           for c, cl, st, inf in zip(self.curves, self.closed, self.stops, self.info)]}

    @classmethod
    def decode(cls, d: Mapping[str, Any], version: int, where: str = "") -> "Boundary":
        """Every key checked (a frequency written as null — not finite — is read back as
        NaN)."""
        r = SavedDict(d, where, ("kind", "parameters", "units", "speed", "lower", "upper",
                                 "evaluations", "starts", "curves"),
                      ("model_name", "settings", "evaluation"))
        kind = r.string("kind", ("neutral-stability", "critical-speed"))
        curves, closed, stops, info = [], [], [], []
        for w, c in r.items("curves"):
            cr = SavedDict(c, w, ("points", "closed", "stops", "info"))
            pts = cr.array("points", ndim=2, shape=(None, 2))
            curves.append(pts)
            closed.append(cr.boolean("closed"))
            stops.append(cr.strings("stops"))
            rows = cr.items("info")
            if len(rows) != len(pts):
                raise v.InputError(f"{cr.name('info')}: has {len(rows)} entries, need one per "
                                   f"point ({len(pts)})")
            info.append(tuple(_info_entry(x, wi) for wi, x in rows))
        return cls(kind, r.strings("parameters", 2), r.strings("units", 2), r.number("speed"),
                   tuple(float(x) for x in r.array("lower", shape=(2,))),
                   tuple(float(x) for x in r.array("upper", shape=(2,))),
                   tuple(curves), tuple(closed), tuple(stops), tuple(info),
                   r.integer("evaluations", 0), r.array("starts", ndim=2, shape=(None, 2)),
                   r.string("model_name") if r.has("model_name") else "",
                   _settings(r) if r.has("settings") else {})

    def save_json(self, path: str | Path) -> Path:
        """Alias of :meth:`save` (the name of earlier releases)."""
        return self.save(path)

    def to_csv(self, path: str | Path | None = None) -> str:
        """One row per point: curve (from 1), point, the two parameters, the mode's data."""
        buf = io.StringIO()
        w = fileio.csv_writer(buf, lineterminator="\n")
        keys = sorted({k for inf in self.info for d in inf for k in d})
        heads = ["curve", "point"] + [f"{p} [{u}]" if u else p for p, u in zip(self.parameters, self.units)]
        w.writerow(heads + keys)
        for i, (c, inf) in enumerate(zip(self.curves, self.info)):
            for j, (p, d) in enumerate(zip(c, inf)):
                w.writerow([i + 1, j, f"{p[0]:.10g}", f"{p[1]:.10g}"]
                           + [f"{d[k]:.10g}" if isinstance(d.get(k), float) else d.get(k, "") for k in keys])
        text = buf.getvalue()
        if path is not None:
            fileio.write_text(path, text, what="boundary table")
        return text



#: The format tag of the boundary file (:class:`Boundary`; the name of earlier releases).
FORMAT = Boundary.format_name()


def _info_entry(x: Any, where: str) -> dict[str, Any]:
    """One point's data of a boundary file: names → a number (null: NaN) or a string."""
    if not isinstance(x, dict):
        raise v.InputError(f"{where}: must be an object")
    out = {}
    for k, y in x.items():
        if isinstance(y, str):
            out[k] = y
        elif y is None:
            out[k] = math.nan
        elif isinstance(y, (int, float)) and not isinstance(y, bool) and math.isfinite(y):
            out[k] = y
        else:
            raise v.InputError(f"{where}.{k}: must be a finite number, null or a string, got "
                               f"{v.short_repr(y)}")
    return out


def _settings(r: SavedDict) -> dict[str, Any]:
    """The options a boundary was traced with: names → true/false, a number, a string or null."""
    x = r.raw("settings")
    if not isinstance(x, dict) or not all(
            y is None or isinstance(y, (bool, str)) or
            (isinstance(y, (int, float)) and math.isfinite(y)) for y in x.values()):
        raise v.InputError(f"{r.name('settings')}: must be an object of options (true/false, "
                           "numbers, strings)")
    return dict(x)


def _check_plane(lower: Sequence[float], upper: Sequence[float],
                 params: Sequence[P.Parameter] = ()) -> tuple[np.ndarray, np.ndarray]:
    """The plane's bounds (lo, hi), checked: two finite values each, upper > lower, a finite
    width, and — given the parameters — inside each path's declared range."""
    lo = np.asarray(v.finite("lower", lower), dtype=float).reshape(-1)
    hi = np.asarray(v.finite("upper", upper), dtype=float).reshape(-1)
    if lo.shape != (2,) or hi.shape != (2,) or not np.all(hi > lo):
        raise v.InputError(f"plane bounds lower = {lo.tolist()}, upper = {hi.tolist()} are "
                           "invalid: two values each, upper > lower")
    with np.errstate(over="ignore"):
        wide = ~np.isfinite(hi - lo)
    if wide.any():
        k = int(np.argmax(wide))
        raise v.InputError(f"plane bounds lower = {lo.tolist()}, upper = {hi.tolist()} are "
                           f"invalid: the width of axis {k + 1} overflows (not a finite number)")
    for k, p in enumerate(params):
        p.check_values([lo[k], hi[k]], "bounds")
    return lo, hi


def _check_speed(model: Any, name: str, V: Any) -> float:
    """`V` [m/s] (argument `name`): > 0 and below the Mach number the model's aerodynamics
    refuse (:func:`propwhirl.model.aerodynamics.validity.check_mach`), checked before any evaluation."""
    V = float(v.positive(name, V, "m/s"))
    flight = getattr(model, "flight", None)
    if flight is not None and validity.has_aerodynamics(model):
        a = float(flight.speed_of_sound)
        if V / a >= validity.MACH_REFUSED:
            raise v.InputError(
                f"{name} = {V:g} m/s is invalid: Mach {V / a:.3g} at a = {a:g} m/s; the "
                f"aerodynamics are subsonic and propwhirl refuses Mach >= "
                f"{validity.MACH_REFUSED:g} (V >= {validity.MACH_REFUSED * a:.1f} m/s)")
    return V


def _traced(kind: str, level: DampingLevel | CriticalSpeedLevel, speed: float, names, units,
            lo, hi, line, options, model_name: str, settings: dict) -> Boundary:
    counted = Counted(level)
    tr = trace(counted, lo, hi, line=line, options=options)
    info = tuple(tuple(level.info(p) for p in b.points) for b in tr.branches)
    return Boundary(kind, tuple(names), tuple(units), float(speed), tuple(map(float, lo)),
                    tuple(map(float, hi)), tuple(b.points for b in tr.branches),
                    tuple(b.closed for b in tr.branches), tuple(b.stops for b in tr.branches),
                    info, counted.calls, tr.starts, model_name, settings)


def neutral_curve(model: Any, parameters: Sequence[str], lower: Sequence[float],
                  upper: Sequence[float], V: float, *, oscillatory: bool = False,
                  line: tuple[Sequence[float], Sequence[float]] | None = None,
                  options: ContinuationOptions = ContinuationOptions(),
                  variant: Variant | None = None, processes: int = 1, client=None,
                  progress=None) -> Boundary:
    """The neutral-stability curve max Re λ(A(V)) = 0 in the plane of two parameter paths.

    Parameters
    ----------
    model : Model
        The model (any, :mod:`propwhirl.model.protocol`).
    parameters : two paths
        E.g. ``("propellers[0].propeller.f_theta", "propellers[0].propeller.f_psi")``.
    lower, upper : (2,)
        The plane's bounds, in the parameters' units.
    V : float
        Airspeed [m/s].
    oscillatory : bool
        Only complex eigenvalues count (flutter; leaves out divergence roots).
    line : pair of points, optional
        The start search line (default: the diagonals, then the mid-lines).
    variant : callable, optional
        ``variant(p) -> model`` instead of the paths (the paths then only name the axes).
    processes, client, progress : optional
        How the batches of independent evaluations run — the samples of each start search
        line (and :func:`grid_map` of :func:`level_of`): local processes, a Dask cluster, a
        progress bar (:func:`propwhirl.studies.execution.map_analyses`); the continuation's
        steps, each depending on the last, run in this process.
    """
    V = _check_speed(model, "V", V)
    v.integer_at_least("processes", processes, 1)
    if variant is None:
        variant, params = path_variant(model, parameters)
        lo, hi = _check_plane(lower, upper, params)
        names, units = [p.path for p in params], [p.unit for p in params]
    else:
        lo, hi = _check_plane(lower, upper)
        names, units = list(parameters), ["", ""]
    level = DampingLevel(variant, float(V), bool(oscillatory), processes=processes,
                         client=client, progress=progress)
    return _traced("neutral-stability", level, V, names, units, lo, hi, line, options,
                   getattr(model, "name", ""), {"oscillatory": bool(oscillatory)})


def speed_contour(model: Any, parameters: Sequence[str], lower: Sequence[float],
                  upper: Sequence[float], V_target: float, *, speeds=None, xtol: float = 0.01,
                  static_divergence: bool = True, low_speed: bool = True,
                  line: tuple[Sequence[float], Sequence[float]] | None = None,
                  options: ContinuationOptions = ContinuationOptions(tol=2e-4),
                  variant: Variant | None = None, processes: int = 1, client=None,
                  progress=None) -> Boundary:
    """The contour V_crit(p) = `V_target` [m/s] in the plane of two parameter paths (one
    analysis per evaluation; see :func:`neutral_curve` for the other arguments).

    speeds: the analyses' initial speed grid [m/s] (default: the model's range); xtol [m/s]:
    accuracy of each critical speed; static_divergence, low_speed: the thesis's exclusions
    (:func:`propwhirl.studies.critical.critical_instability`); processes, client, progress:
    as :func:`neutral_curve` (the start search's analyses in parallel).
    """
    V_target = float(v.positive("V_target", V_target, "m/s"))
    v.integer_at_least("processes", processes, 1)
    grid = None if speeds is None else v.increasing("speeds", speeds, "m/s")
    first, last = ((float(grid[0]), float(grid[-1])) if grid is not None
                   else (float(model.flight.speed_range[0]), float(model.flight.speed_range[1])))
    if not first < V_target < last:       # V_crit never crosses it: no contour, only analyses
        raise v.InputError(f"V_target = {V_target:g} m/s is outside the analysed speeds "
                           f"({first:g}, {last:g}) m/s: no critical speed can equal it (give "
                           "speeds that span it)")
    if variant is None:
        variant, params = path_variant(model, parameters)
        lo, hi = _check_plane(lower, upper, params)
        names, units = [p.path for p in params], [p.unit for p in params]
    else:
        lo, hi = _check_plane(lower, upper)
        names, units = list(parameters), ["", ""]
    level = CriticalSpeedLevel(variant, float(V_target), grid, xtol, bool(static_divergence),
                               bool(low_speed), processes=processes, client=client,
                               progress=progress)
    return _traced("critical-speed", level, V_target, names, units, lo, hi, line, options,
                   getattr(model, "name", ""),
                   {"static_divergence": bool(static_divergence), "low_speed": bool(low_speed),
                    "xtol": xtol})


# ======================================================================= every branch
def grid_seeds(grid: "GridMap") -> list[tuple[np.ndarray, np.ndarray]]:
    """The grid's zero set as seeds of :func:`propwhirl.studies.continuation.trace`: every
    edge between neighbouring grid points across which the level changes sign (a zero at
    one end counts), as a pair of points in the plane's units, ordered along x then y."""
    X, Y, g = grid.x, grid.y, grid.values
    out = []
    for axis in (0, 1):
        a = g[:-1, :] if axis == 0 else g[:, :-1]
        b = g[1:, :] if axis == 0 else g[:, 1:]
        i, j = np.nonzero((a * b < 0) | ((a == 0) ^ (b == 0)))
        for ii, jj in zip(i, j):
            p = np.array([X[ii], Y[jj]])
            q = np.array([X[ii + 1], Y[jj]]) if axis == 0 else np.array([X[ii], Y[jj + 1]])
            out.append((p, q))
    return out


def add_branches(boundary: "Boundary", model: Any, grid: "GridMap",
                 variant: Variant | None = None, *, processes: int = 1, client=None,
                 progress=None) -> "Boundary":
    """`boundary` with every branch of its level set that a grid map of the same level
    (:func:`grid_map` of :func:`level_of`) shows and the tracing from the search lines missed
    (issue 35, item 6): each sign change of the grid (:func:`grid_seeds`) farther than one
    grid cell's diagonal from the curves traced so far starts another curve, traced as the
    first (its zero found on the grid edge; the grid's values reused, not evaluated again).
    An L-shaped boundary whose corner stops the corrector, or an island between the search
    lines, gets all its branches.  The evaluations of the new branches are added to the
    boundary's (the grid's own are the grid's); ``settings["seeded_from_grid"]`` says the
    grid's size.

    Parameters
    ----------
    boundary : Boundary
        A traced boundary (:func:`neutral_curve`, :func:`speed_contour`).
    model : Model
        Its model (or `variant`, as there).
    grid : GridMap
        Its level function on a grid of its plane.
    processes, client, progress : optional
        As :func:`neutral_curve`.

    Returns
    -------
    Boundary
        Its curves, then the new ones (their starts appended to ``starts``).
    """
    if not isinstance(grid, GridMap):
        raise v.fail("grid", grid, "invalid: must be a GridMap (grid_map(level_of(boundary, "
                     f"model), lower, upper, n)), got {type(grid).__name__}")
    lo, hi = np.array(boundary.lower), np.array(boundary.upper)
    if not (np.isclose(grid.x[0], lo[0]) and np.isclose(grid.x[-1], hi[0])
            and np.isclose(grid.y[0], lo[1]) and np.isclose(grid.y[-1], hi[1])):
        raise v.InputError("grid is of another plane than the boundary: give the grid map of "
                           f"its bounds {list(boundary.lower)} to {list(boundary.upper)}")
    level = level_of(boundary, model, variant, processes=processes, client=client,
                     progress=progress)
    counted = Counted(level)
    counted.remember([np.array([a, b]) for a in grid.x for b in grid.y], grid.values.ravel())
    spacing = float(np.hypot(1.0 / (len(grid.x) - 1), 1.0 / (len(grid.y) - 1)))
    options = (ContinuationOptions() if boundary.kind == "neutral-stability"
               else ContinuationOptions(tol=2e-4))
    tr = trace(counted, lo, hi, options=options, seeds=grid_seeds(grid), seed_spacing=spacing,
               known=boundary.curves, search=False)
    info = tuple(tuple(level.info(p) for p in b.points) for b in tr.branches)
    starts = np.vstack([boundary.starts.reshape(-1, 2), tr.starts])
    settings = dict(boundary.settings, seeded_from_grid=f"{len(grid.x)} x {len(grid.y)}")
    return dataclasses.replace(
        boundary, curves=boundary.curves + tuple(b.points for b in tr.branches),
        closed=boundary.closed + tuple(b.closed for b in tr.branches),
        stops=boundary.stops + tuple(b.stops for b in tr.branches), info=boundary.info + info,
        evaluations=boundary.evaluations + counted.calls, starts=starts, settings=settings)


# ============================================================================ grid check
@dataclass(frozen=True)
class GridMap:
    """g sampled on an n₁ × n₂ grid: ``values[i, j] = g(x[i], y[j])``."""

    x: np.ndarray
    y: np.ndarray
    values: np.ndarray

    @property
    def evaluations(self) -> int:
        return int(self.values.size)


def grid_map(g: Callable[[np.ndarray], float], lower: Sequence[float], upper: Sequence[float],
             n: int | tuple[int, int] = 21) -> GridMap:
    """g on a regular grid of the plane (n points per axis, or (n₁, n₂)); a level function
    of this module (:func:`level_of`) evaluates the grid as one batch of independent tasks on
    its processes or Dask cluster, with progress."""
    lo, hi = _check_plane(lower, upper)
    n1, n2 = (n, n) if isinstance(n, int) else n
    v.integer_at_least("n", n1, 2)
    v.integer_at_least("n", n2, 2)
    x, y = np.linspace(lo[0], hi[0], n1), np.linspace(lo[1], hi[1], n2)
    points = [np.array([a, b]) for a in x for b in y]
    batch = getattr(g, "batch", None)
    values = batch(points, desc="grid map") if batch is not None else [g(p) for p in points]
    return GridMap(x, y, np.array(values, dtype=float).reshape(n1, n2))


def level_of(boundary: Boundary, model: Any, variant: Variant | None = None, *,
             processes: int = 1, client=None,
             progress=None) -> Callable[[np.ndarray], float]:
    """The level function g of a traced boundary (for :func:`grid_map` of the same plane;
    processes, client, progress: how its batches run, as :func:`neutral_curve`)."""
    v.integer_at_least("processes", processes, 1)
    if variant is None:
        variant, _ = path_variant(model, boundary.parameters)
    run = dict(processes=processes, client=client, progress=progress)
    if boundary.kind == "neutral-stability":
        return DampingLevel(variant, boundary.speed, bool(boundary.settings.get("oscillatory")),
                            **run)
    s = boundary.settings
    return CriticalSpeedLevel(variant, boundary.speed, None, s.get("xtol", 0.01),
                              s.get("static_divergence", True), s.get("low_speed", True), **run)


def _sign_cells(grid: GridMap) -> np.ndarray:
    """Centres (K, 2) of the grid cells whose four corners do not all have one sign."""
    s = np.sign(grid.values)
    c = np.stack([s[:-1, :-1], s[1:, :-1], s[:-1, 1:], s[1:, 1:]])
    mixed = (c.max(axis=0) > 0) & (c.min(axis=0) <= 0)
    i, j = np.nonzero(mixed)
    return np.column_stack([0.5 * (grid.x[i] + grid.x[i + 1]), 0.5 * (grid.y[j] + grid.y[j + 1])])


def grid_agreement(boundary: Boundary, grid: GridMap) -> tuple[float, float]:
    """How far the traced curves and the grid's boundary are apart, in grid cells (the cell
    size of each axis as the unit): (largest distance of a traced point to the centre of a grid
    cell with a sign change, largest distance of such a cell centre to the traced curves).
    Agreement within the grid's resolution: both ≤ about 1 (a cell's half-diagonal is 0.71)."""
    cells = _sign_cells(grid)
    dx = np.array([grid.x[1] - grid.x[0], grid.y[1] - grid.y[0]])
    pts = np.vstack(boundary.curves) / dx if boundary.curves else np.zeros((0, 2))
    cen = cells / dx
    if len(pts) == 0 or len(cen) == 0:
        return (math.inf, math.inf) if len(pts) or len(cen) else (0.0, 0.0)
    d1 = max(float(np.min(np.hypot(*(cen - p).T))) for p in pts)
    segs = [(a / dx, b / dx) for c in boundary.curves for a, b in zip(c[:-1], c[1:])]

    def to_curve(q: np.ndarray) -> float:
        best = math.inf
        for a, b in segs:
            ab = b - a
            x = float(np.clip(np.dot(q - a, ab) / max(np.dot(ab, ab), 1e-30), 0.0, 1.0))
            best = min(best, float(np.hypot(*(a + x * ab - q))))
        return best

    d2 = max(to_curve(q) for q in cen)
    return d1, d2
