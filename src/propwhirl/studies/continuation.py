"""Pseudo-arclength continuation of a level curve g(p) = 0 in a rectangle of a parameter plane.

Model-agnostic: the curve is the zero set of a scalar function ``g(p: ndarray(2)) -> float``
(:mod:`propwhirl.studies.boundary` builds g from a model: the damping of the least stable mode
at one airspeed, or the critical speed minus a target).  The algorithm:

* **start** — a bracketing search along a line (by default the two diagonals of the
  rectangle, then its two mid-lines): g sampled at ``n_search`` points (one batch:
  :meth:`Counted.prefetch`, in parallel where g has a ``batch``), each sign change refined by
  Brent's method to ``tol``;
* **predictor** — a step of length h along the unit tangent (the secant of the last two
  points; at the start the normal of the finite-difference gradient), in coordinates scaled to
  the rectangle (u = (p − lower)/(upper − lower), so one tolerance fits both axes);
* **corrector** — the pseudo-arclength condition t·(u − ũ) = 0 keeps the corrected point on
  the line through the prediction normal to the tangent, where the 1-D equation
  g(ũ + s n) = 0 is solved by a secant iteration (first slope: the previous point's), safeguarded
  by bisection once a sign change brackets the root, converged when the step in s is below
  ``tol``;
* **step control** — h grows ×1.5 after an easy corrector (≤ 3 evaluations) up to ``max_step``,
  is halved after a failed corrector (no convergence, |s| > h, or a turn of the tangent above
  ``max_turn``) down to ``min_step``;
* **stop** — at the rectangle's edge (the last prediction shortened to the edge and corrected
  along it) or when the curve closes (it comes back to its start point); the other direction
  from the start is then traced too (unless the curve closed).

Every evaluation of g is counted (:attr:`Trace.evaluations`), the quantity the issue compares
with a 50 × 50 grid map (2500 evaluations).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Callable, Sequence

import numpy as np
from scipy.optimize import brentq

from propwhirl import validate as v

LevelFunction = Callable[[np.ndarray], float]


def point_key(p: np.ndarray) -> tuple[float, ...]:
    """A memo key of a point of the plane: its coordinates rounded to 12 decimals (huge ones,
    beyond 1e200, as they are: rounding them would overflow)."""
    x = np.asarray(p, dtype=float)
    small = np.abs(x) < 1e200
    return tuple(np.where(small, np.round(np.where(small, x, 0.0), 12), x).tolist())


@dataclass
class Counted:
    """``g`` with a count of its evaluations (``calls``) and a memo of the values by point."""

    g: LevelFunction
    calls: int = 0
    _memo: dict = field(default_factory=dict, repr=False)

    def __call__(self, p: np.ndarray) -> float:
        key = point_key(p)
        if key not in self._memo:
            self.calls += 1
            value = float(self.g(np.asarray(p, dtype=float)))
            if math.isnan(value):
                raise v.InputError(f"the level function is NaN at p = {list(key)}")
            self._memo[key] = value
        return self._memo[key]

    def remember(self, points: Sequence[np.ndarray], values: Sequence[float]) -> None:
        """Values of g already known at the points (a grid map of the same g): kept in the
        memo, not counted as evaluations."""
        for p, value in zip(points, values):
            self._memo.setdefault(point_key(p), float(value))

    def prefetch(self, points: Sequence[np.ndarray]) -> None:
        """Evaluate g at the points not yet in the memo at once: by ``g.batch(points)`` (a list
        of values; e.g. the level functions of :mod:`propwhirl.studies.boundary`, which run
        them as one batch of independent tasks on the study's processes or Dask cluster)
        when g has it, else one by one.  Counted like single calls."""
        todo, seen = [], set()
        for p in points:
            key = point_key(p)
            if key not in self._memo and key not in seen:
                seen.add(key)
                todo.append(np.asarray(p, dtype=float))
        batch = getattr(self.g, "batch", None)
        if not todo or batch is None:
            return
        values = batch(todo)
        for p, value in zip(todo, values):
            value = float(value)
            if math.isnan(value):
                raise v.InputError(f"the level function is NaN at p = {list(point_key(p))}")
            self.calls += 1
            self._memo[point_key(p)] = value


@dataclass(frozen=True)
class Branch:
    """One traced curve: its points (N, 2) in the parameter plane, whether it closed, and why
    each of its two ends stopped ("bounds", "closed", "max_points", "corrector failed")."""

    points: np.ndarray
    closed: bool
    stops: tuple[str, ...]


@dataclass(frozen=True)
class Trace:
    """The curves found (one per start bracket not lying on an already traced curve) and the
    number of evaluations of g they took (start search included); starts: the search lines'
    zeros and the seeds' zeros that started a curve."""

    branches: tuple[Branch, ...]
    evaluations: int
    starts: np.ndarray


@dataclass(frozen=True)
class ContinuationOptions:
    """Tuning of :func:`trace` (lengths in coordinates scaled to the rectangle, 1 = its side).

    step: first step; min_step, max_step: its bounds; tol: corrector and start accuracy;
    max_turn [rad]: largest turn of the tangent accepted in one step; max_points: per
    direction; n_search: samples of g on a search line; max_iterations: of one corrector.
    """

    step: float = 0.04
    min_step: float = 2e-3
    max_step: float = 0.12
    tol: float = 1e-4
    max_turn: float = 0.5
    max_points: int = 400
    n_search: int = 9
    max_iterations: int = 8

    def __post_init__(self) -> None:
        for name in ("step", "min_step", "max_step", "tol", "max_turn"):
            v.positive(name, getattr(self, name))
        if not self.min_step <= self.step <= self.max_step:
            raise v.InputError(f"step = {self.step!r} is invalid: must be in [min_step, max_step]"
                               f" = [{self.min_step!r}, {self.max_step!r}]")
        v.integer_at_least("max_points", self.max_points, 2)
        v.integer_at_least("n_search", self.n_search, 2)
        v.integer_at_least("max_iterations", self.max_iterations, 2)


def _perp(t: np.ndarray) -> np.ndarray:
    return np.array([-t[1], t[0]])


def _unit(t: np.ndarray) -> np.ndarray:
    n = float(np.hypot(*t))
    return t / n if n > 0 else t


def _inside(u: np.ndarray, eps: float = 1e-12) -> bool:
    return bool(np.all(u >= -eps) and np.all(u <= 1 + eps))


def _to_edge(u: np.ndarray, t: np.ndarray) -> float:
    """Largest h ≥ 0 with u + h t inside the unit square."""
    h = math.inf
    for k in range(2):
        if t[k] > 1e-15:
            h = min(h, (1.0 - u[k]) / t[k])
        elif t[k] < -1e-15:
            h = min(h, -u[k] / t[k])
    return max(h, 0.0)


class _Tracer:
    """The continuation of one level function over the unit square (scaled coordinates)."""

    def __init__(self, g: Counted, lower: np.ndarray, upper: np.ndarray, opts: ContinuationOptions):
        self.g, self.lower, self.span, self.o = g, lower, upper - lower, opts

    def f(self, u: np.ndarray) -> float:
        return self.g(self.lower + np.clip(u, 0.0, 1.0) * self.span)

    # ------------------------------------------------------------------ 1-D root on a line
    def root_on_line(self, u0: np.ndarray, d: np.ndarray, slope: float | None, limit: float
                     ) -> tuple[float, float] | None:
        """s with f(u0 + s d) = 0 and |s| ≤ limit, and the slope df/ds there: secant steps
        (the first with `slope`), bisection once a sign change brackets the root; None when
        not found within ``max_iterations`` evaluations or the line leaves the square."""
        o = self.o
        s_prev, f_prev = 0.0, self.f(u0)
        if f_prev == 0.0:
            return 0.0, slope or 1.0
        neg = (s_prev, f_prev) if f_prev < 0 else None   # latest point with f < 0
        pos = (s_prev, f_prev) if f_prev > 0 else None   # latest point with f > 0
        usable = slope is not None and math.isfinite(slope) and slope != 0.0
        s = -f_prev / slope if usable else 10 * o.tol
        for _ in range(o.max_iterations):
            s = float(np.clip(s, -limit, limit))
            if s == s_prev or not _inside(u0 + s * d):
                return None
            fs = self.f(u0 + s * d)
            secant = (fs - f_prev) / (s - s_prev)
            if fs == 0.0:
                return s, secant
            if fs < 0:
                neg = (s, fs)
            else:
                pos = (s, fs)
            nxt = s - fs / secant if secant != 0.0 and math.isfinite(secant) else math.nan
            if neg is not None and pos is not None:
                a, b = sorted((neg[0], pos[0]))
                if not a < nxt < b:
                    nxt = 0.5 * (a + b)
            elif not math.isfinite(nxt):
                return None
            if abs(nxt - s) < o.tol:
                return nxt, secant
            s_prev, f_prev, s = s, fs, nxt
        return None

    # ------------------------------------------------------------------ start
    def starts(self, lines: Sequence[tuple[np.ndarray, np.ndarray]]) -> list[np.ndarray]:
        """Every zero of g on the first search line that has a sign change (scaled coords)."""
        for a, b in lines:
            s = np.linspace(0.0, 1.0, self.o.n_search)
            # the samples of a line are independent: one batch (in parallel where g can)
            self.g.prefetch([self.lower + np.clip(a + x * (b - a), 0.0, 1.0) * self.span
                             for x in s])
            vals = [self.f(a + x * (b - a)) for x in s]
            found = []
            for k in range(len(s) - 1):
                if vals[k] == 0.0:
                    found.append(a + s[k] * (b - a))
                elif vals[k] * vals[k + 1] < 0:
                    x = brentq(lambda x: self.f(a + x * (b - a)), s[k], s[k + 1],
                               xtol=self.o.tol / max(float(np.hypot(*(b - a))), 1e-12))
                    found.append(a + x * (b - a))
            if found:
                return found
        return []

    def gradient(self, u: np.ndarray) -> np.ndarray:
        """Forward-difference gradient of f at u (two evaluations; steps into the square)."""
        h = max(10 * self.o.tol, 1e-3)
        f0 = self.f(u)
        out = np.zeros(2)
        for k in range(2):
            e = np.zeros(2)
            e[k] = h if u[k] + h <= 1.0 else -h
            out[k] = (self.f(u + e) - f0) / e[k]
        return out

    # ------------------------------------------------------------------ one direction
    def _edge_line(self, u: np.ndarray, t: np.ndarray, edge: float, slope: float
                   ) -> tuple[np.ndarray, np.ndarray, float]:
        """The prediction on the square's edge along t, the edge's direction (oriented like
        the normal of t) and the slope of f along it."""
        pred = u + edge * t
        k = int(np.argmin([min(abs(pred[j]), abs(1 - pred[j])) for j in range(2)]))
        pred[k] = round(pred[k])
        d = np.zeros(2)
        d[1 - k] = 1.0
        c = float(np.dot(d, _perp(t)))
        if c < 0:
            d, c = -d, -c
        return pred, d, slope * max(c, 0.2)

    def follow(self, u_start: np.ndarray, t0: np.ndarray, slope0: float
               ) -> tuple[list[np.ndarray], str]:
        """Points from `u_start` along the curve in direction `t0` (slope0: df along the
        normal of t0) until an edge, the start again, or a failure."""
        o = self.o
        pts = [u_start]
        t, h, slope = t0, o.step, slope0
        travelled = 0.0
        while len(pts) < o.max_points:
            u = pts[-1]
            edge = _to_edge(u, t)
            if edge < 1e-9:
                return pts, "bounds"
            at_edge = edge <= h
            calls = self.g.calls
            if at_edge:
                pred, d, d_slope = self._edge_line(u, t, edge, slope)
                hh = edge
            else:
                hh = h
                pred, d, d_slope = u + h * t, _perp(t), slope
            res = self.root_on_line(pred, d, d_slope, max(hh, 4 * o.tol))
            new = None if res is None else pred + res[0] * d
            if new is not None:
                step = new - u
                turn = math.acos(float(np.clip(np.dot(_unit(step), t), -1.0, 1.0)))
                if float(np.hypot(*step)) < 0.2 * hh or (turn > o.max_turn and h > o.min_step):
                    new = None
            if new is None and not at_edge and h <= o.min_step and edge <= 2 * o.max_step:
                # the curve leaves the square before the next normal line: land on the edge
                at_edge = True
                pred, d, d_slope = self._edge_line(u, t, edge, slope)
                res = self.root_on_line(pred, d, d_slope, max(edge, 4 * o.tol))
                new = None if res is None else pred + res[0] * d
            if new is None:
                if h <= o.min_step:
                    return pts, "corrector failed"
                h = max(0.5 * h, o.min_step)
                continue
            t_new = _unit(new - u)
            travelled += float(np.hypot(*(new - u)))
            if travelled > 3 * o.step and len(pts) > 2:   # closed: back at the start
                ab = new - u
                x = float(np.clip(np.dot(u_start - u, ab) / max(np.dot(ab, ab), 1e-30), 0, 1))
                if float(np.hypot(*(u + x * ab - u_start))) < max(0.5 * hh, 5 * o.tol):
                    pts.append(u_start)
                    return pts, "closed"
            pts.append(new)
            if at_edge:
                return pts, "bounds"
            if res[1] != 0.0 and math.isfinite(res[1]):
                slope = res[1] * (1.0 if np.dot(_perp(t_new), _perp(t)) > 0 else -1.0)
            t = t_new
            if self.g.calls - calls <= 3:
                h = min(1.5 * h, o.max_step)
        return pts, "max_points"


def default_lines() -> list[tuple[np.ndarray, np.ndarray]]:
    """Search lines (scaled coordinates): the two diagonals, then the two mid-lines."""
    return [(np.array([0.0, 0.0]), np.array([1.0, 1.0])), (np.array([0.0, 1.0]), np.array([1.0, 0.0])),
            (np.array([0.0, 0.5]), np.array([1.0, 0.5])), (np.array([0.5, 0.0]), np.array([0.5, 1.0]))]


def _near_curve(u: np.ndarray, branches: list[np.ndarray], dist: float) -> bool:
    for pts in branches:
        if len(pts) == 1 and float(np.hypot(*(pts[0] - u))) < dist:
            return True
        for a, b in zip(pts[:-1], pts[1:]):
            ab = b - a
            x = float(np.clip(np.dot(u - a, ab) / max(np.dot(ab, ab), 1e-30), 0.0, 1.0))
            if float(np.hypot(*(a + x * ab - u))) < dist:
                return True
    return False


def trace(g: LevelFunction, lower: Sequence[float], upper: Sequence[float], *,
          line: tuple[Sequence[float], Sequence[float]] | None = None,
          options: ContinuationOptions = ContinuationOptions(),
          seeds: Sequence[tuple[Sequence[float], Sequence[float]]] = (),
          seed_spacing: float = 0.0, known: Sequence[np.ndarray] = (),
          search: bool = True) -> Trace:
    """The curves g(p) = 0 in the rectangle ``lower ≤ p ≤ upper`` (module docstring).

    Parameters
    ----------
    g : callable
        ``g(p) -> float`` with ``p`` an array (2,) in the plane's units; must not be NaN.
    lower, upper : (2,) sequences
        The rectangle (upper > lower).
    line : pair of points, optional
        The start search line (in the plane's units); default: :func:`default_lines`.
    options : ContinuationOptions
    seeds : sequence of point pairs, optional
        Segments (a, b) in the plane's units across which g changes sign — the edges of a
        grid map's zero set (:func:`propwhirl.studies.boundary.grid_seeds`): after the
        curves met by the search lines, each segment farther than `seed_spacing` from every
        curve traced so far starts another (its zero found on the segment), so a branch the
        search lines miss — the second arm of an L-shaped boundary, whose corner stops the
        corrector, or an island — is traced too.
    seed_spacing : float
        The grid's cell diagonal in coordinates scaled to the rectangle (1 = its side): a
        seed this close to a traced curve belongs to it.
    known : sequence of (N, 2) arrays
        Curves traced before (the plane's units): no start near them is traced again.
    search : bool
        Search the lines for starts (False: the seeds only, as when branches are added to
        curves traced before).

    Returns
    -------
    Trace
        One :class:`Branch` per curve met by the search line or a seed (none: no sign change
        of g on the search lines nor a seed), points in the plane's units.
    """
    lo = np.asarray(v.finite("lower", lower), dtype=float)
    hi = np.asarray(v.finite("upper", upper), dtype=float)
    with np.errstate(over="ignore", invalid="ignore"):
        wide = lo.shape == hi.shape and not np.all(np.isfinite(hi - lo))
    if wide:
        raise v.InputError(f"bounds lower = {lo.tolist()}, upper = {hi.tolist()} are invalid: "
                           "their difference overflows (not a finite number)")
    if lo.shape != (2,) or hi.shape != (2,) or not np.all(hi > lo):
        raise v.InputError(f"bounds lower = {lo.tolist()}, upper = {hi.tolist()} are invalid: "
                           "two values each, upper > lower")
    counted = g if isinstance(g, Counted) else Counted(g)
    tr = _Tracer(counted, lo, hi, options)
    if line is None:
        lines = default_lines()
    else:
        a, b = (np.asarray(v.finite("line", x), dtype=float) for x in line)
        lines = [((a - lo) / (hi - lo), (b - lo) / (hi - lo))]
    starts = tr.starts(lines) if search else []
    branches: list[Branch] = []
    traced: list[np.ndarray] = [(np.asarray(c, dtype=float) - lo) / (hi - lo) for c in known]
    scaled = [tuple((np.asarray(x, dtype=float) - lo) / (hi - lo) for x in pair)
              for pair in seeds]
    near = max(2 * options.min_step, 0.1 * options.max_step)
    seeded: list[np.ndarray] = []
    for u0, is_seed in _starts_then_seeds(tr, starts, scaled, traced, float(seed_spacing)):
        if _near_curve(u0, traced, near):
            continue
        grad = tr.gradient(u0)
        norm = float(np.hypot(*grad))
        if norm == 0.0:
            continue
        t0 = _perp(grad / norm)
        fwd, why_f = tr.follow(u0, t0, -norm)   # d f/ds along perp(t0) = -|grad|
        if why_f == "closed":
            pts, stops = fwd, ("closed",)
        else:
            back, why_b = tr.follow(u0, -t0, norm)
            pts, stops = back[::-1] + fwd[1:], (why_b, why_f)
        arr = np.array(pts)
        traced.append(arr)
        if is_seed and len(arr) < 2:       # a seed at a corner the corrector cannot leave
            continue
        if is_seed:
            seeded.append(u0)
        branches.append(Branch(lo + arr * (hi - lo), stops == ("closed",), stops))
    return Trace(tuple(branches), counted.calls,
                 np.array([lo + u * (hi - lo) for u in [*starts, *seeded]]).reshape(-1, 2))


def _starts_then_seeds(tr: _Tracer, starts: list[np.ndarray], seeds: list[tuple],
                       traced: list[np.ndarray], spacing: float):
    """The search lines' start points, then each seed segment's zero — a segment whose
    middle lies within `spacing` of a curve traced by then is skipped before any evaluation
    (`traced` grows while this is consumed); each with whether it is a seed's."""
    for u in starts:
        yield u, False
    for a, b in seeds:
        if _near_curve(0.5 * (a + b), traced, spacing):
            continue
        fa, fb = tr.f(a), tr.f(b)
        if fa == 0.0 or fb == 0.0:
            yield (a if fa == 0.0 else b), True
        elif fa * fb < 0:
            x = brentq(lambda x: tr.f(a + x * (b - a)), 0.0, 1.0,
                       xtol=tr.o.tol / max(float(np.hypot(*(b - a))), 1e-12))
            yield a + x * (b - a), True
