"""Speed and accuracy of the stability engine against the thesis's fixed-grid method (issue 4.7).

One run of ``python -m propwhirl.benchmark`` times, side by side on the same machine,

(a) the engine — :func:`propwhirl.analysis.stability.analyse` with its default grid (1–350 m/s every
    10 m/s; :func:`propwhirl.engine.analyse` evaluates the grid speeds ~50 m/s apart first
    and adds speeds only where tracking needs them; crossings refined to 0.01 m/s) — locating
    every critical speed of the wingtip propeller-wing model of §10.1 (25 elements,
    Leishman–Nguyen, baseline propeller, 0–350 m/s);
(b) the thesis's method (§5.2.1): a fixed ΔV = 1 m/s sweep from 1 to 350 m/s with a full
    eigendecomposition per speed (``numpy.linalg.eig``, eigenvectors included, as the thesis
    orders the modes with the MAC, §5.2.3), crossings detected as sign changes of Re λ between
    consecutive speeds (accuracy ±1 m/s);

both with BLAS limited to one thread (threadpoolctl), and (b) again with two threads.  It then
checks that every crossing the engine reports is found by (b) and vice versa (same event and
kind, speed within ±1 m/s, frequency within 0.05 Hz + 2 %), and computes a *converged* value of
each crossing by a local brute force — bisection of the bracket of (b) on the number of
eigenvalues with Re λ > 0 (or, for a frequency-zero event, with Re λ > 0 and Im λ ≠ 0), each
step a full ``eigvals`` of A(V), down to 1e-4 m/s — and reports the engine's error against it.

Timing: wall-clock (``time.perf_counter``) and process CPU time (``time.process_time``); on a
shared machine the CPU time of a one-thread run is the steadier number.  The engine is run once
untimed first (imports, generated-code loading, caches); then ``repeats`` rounds alternate one
timed engine run and one timed one-thread fixed-grid sweep, so that both sample the same
spells of load from other jobs, and the minimum of each is reported (the sweep with the
smaller CPU time); the two-thread sweep is run once (each is ~350 identical evaluations, so it
averages itself).

Reproduce::

    cd /work/main && .venv/bin/python -m propwhirl.benchmark --markdown docs/performance.md

The brute-force helpers (:func:`fixed_grid_sweep`, :func:`detect_crossings`,
:func:`converge_crossing`, :func:`engine_crossings`, :func:`match_crossings`) are used by the
tests of the engine on the real model as well.
"""
from __future__ import annotations

import argparse
import cProfile
import os
import platform
import pstats
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import scipy
from scipy.optimize import linear_sum_assignment
from threadpoolctl import threadpool_info, threadpool_limits

from propwhirl import validate as v

__all__ = [
    "Crossing", "FixedGridResult", "Timing", "fixed_grid_sweep", "detect_crossings",
    "count_unstable", "converge_crossing", "engine_crossings", "match_crossings",
    "machine_info", "time_engine", "engine_variants", "profile_engine", "run_benchmark",
    "report", "main",
]

#: The thesis's sweep: ΔV = 1 m/s from 1 to 350 m/s (§5.2.1; 0–350 m/s in chapters 9–11) [m/s]
THESIS_SPEEDS = np.arange(1.0, 351.0, 1.0)


# ----------------------------------------------------------------------------------------------
# Crossings
# ----------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Crossing:
    """One critical point: a sign change of Re λ or an unstable pair turning real.

    kind:         "flutter" (complex pair crosses) or "divergence" (real root through zero, or
                  an unstable pair whose frequency falls to zero).
    event:        "onset" (Re λ − → +), "recovery" (+ → −) or "frequency-zero".
    V:            speed [m/s] (engine: refined value; fixed grid: Re λ interpolated linearly
                  inside the bracket).
    frequency_hz: |Im λ|/2π at V [Hz] (0 for divergence).
    bracket:      (lo, hi) [m/s] known to contain the event.
    label:        mode name where known.
    """

    kind: str
    event: str
    V: float
    frequency_hz: float
    bracket: tuple[float, float]
    label: str = ""


@dataclass
class Timing:
    """Wall-clock and process-CPU time [s] of one measured task."""

    wall: float
    cpu: float

    @classmethod
    def measure(cls, fn: Callable[[], Any]) -> tuple["Timing", Any]:
        t0, c0 = time.perf_counter(), time.process_time()
        out = fn()
        return cls(time.perf_counter() - t0, time.process_time() - c0), out


@dataclass
class FixedGridResult:
    """Eigenvalues of a fixed-grid sweep and the cost of its parts.

    V (T,) [m/s]; eigenvalues (T, n) complex [1/s] in LAPACK order; times of the state-matrix
    assembly, the eigendecompositions and the crossing detection; threads: BLAS threads used.
    """

    V: np.ndarray
    eigenvalues: np.ndarray
    assembly: Timing
    eig: Timing
    detection: Timing = field(default_factory=lambda: Timing(0.0, 0.0))
    crossings: tuple[Crossing, ...] = ()
    threads: int = 1

    @property
    def total(self) -> Timing:
        return Timing(self.assembly.wall + self.eig.wall + self.detection.wall,
                      self.assembly.cpu + self.eig.cpu + self.detection.cpu)


def fixed_grid_sweep(state_matrix: Callable[[np.ndarray], np.ndarray], speeds=THESIS_SPEEDS, *,
                     threads: int = 1, chunk: int = 25, vectors: bool = True,
                     detect: bool = True) -> FixedGridResult:
    """The thesis's method (§5.2.1): a full eigendecomposition of A(V) at every speed.

    ``state_matrix(V)`` is vectorised over speeds [m/s]; it is evaluated in chunks of
    ``chunk`` speeds (memory), each followed by ``numpy.linalg.eig`` of the chunk (eigenvectors
    computed when ``vectors``, as the thesis's MAC ordering needs them, then dropped).  BLAS is
    limited to ``threads`` threads.  With ``detect`` the crossings are found by
    :func:`detect_crossings` (timed separately).
    """
    V = v.increasing("speeds", speeds, "m/s")
    v.integer_at_least("threads", threads, 1)
    v.integer_at_least("chunk", chunk, 1)
    lam_parts = []
    t_asm = Timing(0.0, 0.0)
    t_eig = Timing(0.0, 0.0)
    with threadpool_limits(limits=threads):
        for i in range(0, V.size, chunk):
            Vc = V[i:i + chunk]
            ta, A = Timing.measure(lambda: state_matrix(Vc))
            if vectors:
                te, (w, _X) = Timing.measure(lambda: np.linalg.eig(A))
            else:
                te, w = Timing.measure(lambda: np.linalg.eigvals(A))
            lam_parts.append(np.asarray(w, dtype=complex))
            t_asm = Timing(t_asm.wall + ta.wall, t_asm.cpu + ta.cpu)
            t_eig = Timing(t_eig.wall + te.wall, t_eig.cpu + te.cpu)
    lam = np.concatenate(lam_parts)
    res = FixedGridResult(V, lam, t_asm, t_eig, threads=threads)
    if detect:
        res.detection, res.crossings = Timing.measure(lambda: detect_crossings(V, lam))
    return res


def _match_eigenvalues(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """perm with b[perm[i]] the continuation of a[i] (optimal assignment on |λ_a − λ_b|)."""
    cost = np.abs(a[:, None] - b[None, :])
    _, perm = linear_sum_assignment(cost)
    return perm


def _det_sign(lam: np.ndarray) -> int:
    """sign(det A) = (−1)^(number of negative real eigenvalues); complex pairs contribute +."""
    return -1 if np.count_nonzero((lam.imag == 0) & (lam.real < 0)) % 2 else 1


def detect_crossings(V: np.ndarray, lam: np.ndarray) -> tuple[Crossing, ...]:
    """Sign changes of Re λ between consecutive speeds of a fixed grid (the thesis's detection).

    Eigenvalues are followed from one speed to the next by an optimal assignment on their
    distance (on a 1 m/s grid they move little compared with their separations); every matched
    pair whose real part changes sign (Re λ = 0 counts as stable, like
    :func:`count_unstable`) is a crossing, reported once per complex-conjugate pair
    (by its Im > 0 member).  Kind: flutter if the root is complex at both ends, divergence if
    real at both ends; a root complex at one end only is a divergence when sign(det A) flips in
    the interval (a real root went through zero), otherwise flutter.  Frequency-zero events
    are intervals where the number of unstable complex roots falls by two while the number of
    unstable real roots rises by two (an unstable pair turns into two real roots).
    ``V`` (T,) [m/s], ``lam`` (T, n).
    """
    V = np.asarray(V, dtype=float)
    lam = np.asarray(lam, dtype=complex)
    out: list[Crossing] = []
    for t in range(V.size - 1):
        a, b = lam[t], lam[t + 1]
        perm = _match_eigenvalues(a, b)
        bb = b[perm]
        flips = np.nonzero((a.real > 0) != (bb.real > 0))[0]   # Re λ = 0 counts as stable
        for i in flips:
            la, lb = a[i], bb[i]
            onset = lb.real > la.real
            hot = lb if onset else la                  # the unstable end
            ca, cb = la.imag != 0, lb.imag != 0
            if ca and cb:
                kind = "flutter"
            elif not (ca or cb):
                kind = "divergence"
            else:
                kind = "divergence" if _det_sign(a) != _det_sign(b) else "flutter"
            if kind == "flutter" and (hot.imag < 0 or (hot.imag == 0 and min(la.imag, lb.imag) < 0)):
                continue                               # the conjugate of a reported root
            s = la.real / (la.real - lb.real)
            Vc = float(V[t] + s * (V[t + 1] - V[t]))
            f = 0.0 if kind == "divergence" else float(
                abs(la.imag + s * (lb.imag - la.imag)) / (2 * np.pi))
            out.append(Crossing(kind, "onset" if onset else "recovery", Vc, f,
                                (float(V[t]), float(V[t + 1]))))
        ua = ((a.real > 0) & (a.imag != 0)).sum(), ((a.real > 0) & (a.imag == 0)).sum()
        ub = ((b.real > 0) & (b.imag != 0)).sum(), ((b.real > 0) & (b.imag == 0)).sum()
        if ub[0] == ua[0] - 2 and ub[1] == ua[1] + 2:
            out.append(Crossing("divergence", "frequency-zero", float(V[t + 1]), 0.0,
                                (float(V[t]), float(V[t + 1]))))
    return tuple(out)


def count_unstable(A: np.ndarray, complex_only: bool = False) -> np.ndarray:
    """Number of eigenvalues with Re λ > 0 of each matrix of a stack (full ``eigvals``).

    ``complex_only``: count only those with Im λ ≠ 0 (a frequency-zero event changes it).
    """
    w = np.linalg.eigvals(np.asarray(A))
    unstable = w.real > 0
    if complex_only:
        unstable &= w.imag != 0
    return unstable.sum(axis=-1)


def converge_crossing(state_matrix: Callable[[np.ndarray], np.ndarray], lo: float, hi: float,
                      *, xtol: float = 1e-4, complex_only: bool = False) -> tuple[float, float]:
    """Converged location of a crossing in [lo, hi] [m/s] by brute-force bisection.

    Each step evaluates A(V) and its full ``eigvals`` and halves the bracket on whether the
    number of eigenvalues with Re λ > 0 (:func:`count_unstable`; ``complex_only`` for a
    frequency-zero event) equals its value at ``lo``.  Needs the count to differ at the ends;
    with a single event inside the bracket the result is within ``xtol``/2 of it.  Returns
    (V, half-width) [m/s].
    """
    lo, hi = float(v.finite("lo", lo, "m/s")), float(v.finite("hi", hi, "m/s"))
    if not hi > lo:
        raise v.InputError(f"bracket ({lo!r}, {hi!r}) m/s is invalid: must have hi > lo")
    v.positive("xtol", xtol, "m/s")
    with threadpool_limits(limits=1):
        n_lo, n_hi = count_unstable(state_matrix(np.array([lo, hi])), complex_only)
        if n_lo == n_hi:
            raise v.InputError(f"no change of the unstable-root count between {lo} and {hi} m/s "
                               f"({n_lo} at both ends): not a single crossing")
        while hi - lo > xtol:
            mid = 0.5 * (lo + hi)
            n_mid = count_unstable(state_matrix(np.array([mid])), complex_only)[0]
            if n_mid == n_lo:
                lo = mid
            else:
                hi = mid
    return 0.5 * (lo + hi), 0.5 * (hi - lo)


def engine_crossings(analysis) -> tuple[Crossing, ...]:
    """Crossings of a :class:`propwhirl.analysis.stability.ModelAnalysis`: onsets, recoveries and
    frequency-zero events (``unstable-at-start`` is not a crossing and is left out)."""
    bracket = {(p.mode, float(p.V)): tuple(map(float, p.bracket))
               for p in analysis.criticals.points}
    return tuple(Crossing(e.kind, e.event, float(e.V), float(e.frequency_hz),
                          bracket.get((e.mode, float(e.V)), (float(e.V), float(e.V))), e.label)
                 for e in analysis.events if e.event != "unstable-at-start")


def match_crossings(found: Sequence[Crossing], reference: Sequence[Crossing], *,
                    dV: float = 1.0, df_abs: float = 0.05, df_rel: float = 0.02
                    ) -> tuple[list[tuple[Crossing, Crossing]], list[Crossing], list[Crossing]]:
    """One-to-one matching of two crossing lists: same event and kind, |ΔV| ≤ dV [m/s],
    |Δf| ≤ df_abs [Hz] + df_rel·f.  Returns (pairs, unmatched found, unmatched reference);
    the assignment minimises Σ|ΔV| (optimal, not greedy)."""
    nf, nr = len(found), len(reference)
    if nf == 0 or nr == 0:
        return [], list(found), list(reference)
    big = 1e9
    cost = np.full((nf, nr), big)
    for i, a in enumerate(found):
        for j, b in enumerate(reference):
            ok = (a.event == b.event and a.kind == b.kind and abs(a.V - b.V) <= dV
                  and abs(a.frequency_hz - b.frequency_hz)
                  <= df_abs + df_rel * max(a.frequency_hz, b.frequency_hz))
            if ok:
                cost[i, j] = abs(a.V - b.V)
    rows, cols = linear_sum_assignment(cost)
    pairs = [(found[i], reference[j]) for i, j in zip(rows, cols) if cost[i, j] < big]
    used_f = {i for i, j in zip(rows, cols) if cost[i, j] < big}
    used_r = {j for i, j in zip(rows, cols) if cost[i, j] < big}
    return (pairs, [c for i, c in enumerate(found) if i not in used_f],
            [c for j, c in enumerate(reference) if j not in used_r])


# ----------------------------------------------------------------------------------------------
# Engine timing and profile
# ----------------------------------------------------------------------------------------------
def time_engine(model, repeats: int = 3, speeds=None, options=None,
                warm: bool = True) -> tuple[list[Timing], Any]:
    """Run :func:`propwhirl.analysis.stability.analyse` once untimed (unless ``warm`` is False), then
    ``repeats`` times timed (BLAS one thread).  Returns the timings and the last analysis."""
    from propwhirl.analysis.stability import analyse

    v.integer_at_least("repeats", repeats, 1)
    with threadpool_limits(limits=1):
        an = analyse(model, speeds, options=options) if warm else None
        times = []
        for _ in range(repeats):
            t, an = Timing.measure(lambda: analyse(model, speeds, options=options))
            times.append(t)
    return times, an


#: variants of the engine's core (:func:`propwhirl.engine.analyse` on the default grid):
#: (name, initial_step [m/s] or None for every grid speed, TrackingOptions changes)
ENGINE_VARIANTS: tuple[tuple[str, float | None, dict[str, Any]], ...] = (
    ("default (initial step 50 m/s)", 50.0, {}),
    ("every grid speed (10 m/s)", None, {}),
    ("initial step 25 m/s", 25.0, {}),
    ("initial step 100 m/s", 100.0, {}),
    ("MAC always required", 50.0, {"decisive_ratio": 0.0}),
    ("no Hermite margin (sign test)", 50.0, {"margin": 0.0}),
)


def engine_variants(model, converged: Sequence[tuple[Crossing, float, float]],
                    repeats: int = 2) -> list[tuple[str, Timing, int, float, int]]:
    """The engine's core, :func:`propwhirl.engine.analyse` alone (no mode names, no
    frequency-zero events), on the default grid with the variants of :data:`ENGINE_VARIANTS`:
    how the initial subset of the grid and the tracking options change the cost and the
    result.  Rows: (name, best time, speeds evaluated, max |V − converged| over the
    onsets/recoveries [m/s] (inf: one was missed), unresolved intervals)."""
    from propwhirl.engine import TrackingOptions, analyse as engine_analyse

    grid = model.flight.speeds()
    s = model.second_order(np.array([float(grid[0])]))
    rows = []
    for name, step, changes in ENGINE_VARIANTS:
        opts = TrackingOptions(**changes)

        def run():
            return engine_analyse(model.state_matrix, grid, n_dof=s.n_dof, state_labels=s.labels,
                                  options=opts, xtol=0.01, initial_step=step)

        with threadpool_limits(limits=1):
            run()
            times = []
            for _ in range(repeats):
                t, an = Timing.measure(run)
                times.append(t)
        best = Timing(min(t.wall for t in times), min(t.cpu for t in times))
        err = 0.0
        for c, Vc, _ in converged:
            if c.event == "frequency-zero":
                continue                 # an event of analysis.py, not of the core
            same = [p for p in an.criticals.points if p.direction == c.event
                    and p.kind == c.kind and abs(p.V - c.V) <= 1.0]
            err = max(err, min((abs(p.V - Vc) for p in same), default=float("inf")))
        rows.append((name, best, int(an.sweep.V.size), err, len(an.sweep.unresolved)))
    return rows


#: Engine functions whose cumulative time the profile reports: (module file tail, function)
_PROFILE_PARTS = (
    ("state-matrix assembly (all calls)", "propwhirl/model.py", "state_matrix"),
    ("sweep: full eig (LAPACK geev)", "numpy/linalg/_linalg.py", "eig"),
    ("sweep: dλ/dV (diagonal of X⁻¹ A' X)", "propwhirl/stability.py", "_eig_derivative"),
    ("sweep: linking speeds (MAC, assignment)", "propwhirl/stability.py", "_link"),
    ("  of which: clusters through branch points", "propwhirl/stability.py",
     "_cluster_continuations"),
    ("sweep: branch points of unstable pairs", "propwhirl/stability.py", "_branch_point_speeds"),
    ("sweep: collecting the result", "propwhirl/stability.py", "_assemble"),
    ("crossing refinement (inverse iteration)", "propwhirl/stability.py", "_critical_points"),
    ("mode names (in-vacuo modes, MAC)", "propwhirl/analysis.py", "_mode_names"),
    ("frequency-zero events", "propwhirl/analysis.py", "_frequency_zero_events"),
)


def profile_engine(model) -> tuple[float, list[tuple[str, float, int]]]:
    """cProfile one engine run: total [s] and (part, cumulative time [s], calls) rows.

    The parts overlap (assembly is also called inside the sweep and the refinement); the
    profiler's own overhead inflates Python-heavy parts.
    """
    from propwhirl.analysis.stability import analyse

    prof = cProfile.Profile()
    with threadpool_limits(limits=1):
        analyse(model)
        prof.enable()
        t0 = time.perf_counter()
        analyse(model)
        total = time.perf_counter() - t0
        prof.disable()
    stats = pstats.Stats(prof).stats  # type: ignore[attr-defined]
    rows = []
    for name, tail, func in _PROFILE_PARTS:
        ct = calls = 0
        for (fname, _line, fn), (_cc, nc, _tt, cum, _callers) in stats.items():
            if fn == func and fname.replace(os.sep, "/").endswith(tail):
                ct += cum
                calls += nc
        rows.append((name, ct, calls))
    return total, rows


# ----------------------------------------------------------------------------------------------
# Machine
# ----------------------------------------------------------------------------------------------
def machine_info() -> dict[str, str]:
    """nproc, CPU model (/proc/cpuinfo), load average, Python/NumPy/SciPy and BLAS versions."""
    cpu = platform.processor() or "unknown"
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.lower().startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    blas = "; ".join(sorted({f"{i.get('internal_api')} {i.get('version')}"
                             for i in threadpool_info()})) or "unknown"
    try:
        load = " ".join(f"{x:.2f}" for x in os.getloadavg())
    except OSError:
        load = "n/a"
    return {"nproc": str(os.cpu_count()), "cpu": cpu, "load average (1, 5, 15 min)": load,
            "python": platform.python_version(), "numpy": np.__version__,
            "scipy": scipy.__version__, "blas": blas, "platform": platform.platform()}


# ----------------------------------------------------------------------------------------------
# The benchmark
# ----------------------------------------------------------------------------------------------
@dataclass
class BenchmarkResult:
    """Everything one benchmark run measured (see :func:`run_benchmark`)."""

    machine: dict[str, str]
    n_states: int
    engine_times: list[Timing]
    engine_nodes: int
    engine_stats: dict[str, Any]
    fixed: dict[int, FixedGridResult]
    engine: tuple[Crossing, ...]
    pairs: list[tuple[Crossing, Crossing]]
    engine_only: list[Crossing]
    fixed_only: list[Crossing]
    converged: list[tuple[Crossing, float, float]]     # (engine crossing, V_conv, half-width)
    profile_total: float
    profile: list[tuple[str, float, int]]
    per_speed: Timing                                  # fixed grid cost per speed, 1 thread
    variants: list[tuple[str, Timing, int, float, int]] = field(default_factory=list)

    @property
    def engine_best(self) -> Timing:
        return Timing(min(t.wall for t in self.engine_times), min(t.cpu for t in self.engine_times))

    def speedup(self, threads: int = 1, cpu: bool = False) -> float:
        f = self.fixed[threads].total
        e = self.engine_best
        return (f.cpu / e.cpu) if cpu else (f.wall / e.wall)

    @property
    def max_error(self) -> float:
        return max((abs(c.V - Vc) for c, Vc, _ in self.converged), default=float("nan"))

    @property
    def all_found(self) -> bool:
        return not self.engine_only and not self.fixed_only


def run_benchmark(model=None, repeats: int = 3, two_threads: bool = True,
                  profile: bool = True, variants: bool = True) -> BenchmarkResult:
    """Time (a) the engine and (b) the thesis's fixed-grid method on ``model`` (default: the
    wingtip propeller-wing of §10.1), compare their crossings and converge each crossing."""
    if model is None:
        from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing

        model = wingtip_propeller_wing()
    fn = model.state_matrix
    v.integer_at_least("repeats", repeats, 1)
    engine_times, runs = [], []
    _, an = time_engine(model, 1)                      # warm-up and a first timed run
    for _ in range(repeats):                           # alternate: same spells of load
        times, an = time_engine(model, 1, warm=False)
        engine_times += times
        runs.append(fixed_grid_sweep(fn, THESIS_SPEEDS, threads=1))
    fixed = {1: min(runs, key=lambda r: r.total.cpu)}
    if two_threads:
        fixed[2] = fixed_grid_sweep(fn, THESIS_SPEEDS, threads=2)
    eng = engine_crossings(an)
    pairs, e_only, f_only = match_crossings(eng, fixed[1].crossings)
    converged = []
    for e, f in pairs:
        Vc, hw = converge_crossing(fn, *f.bracket, complex_only=e.event == "frequency-zero")
        converged.append((e, Vc, hw))
    ptotal, prow = profile_engine(model) if profile else (float("nan"), [])
    var = engine_variants(model, converged) if variants else []
    f1 = fixed[1].total
    n = int(fixed[1].eigenvalues.shape[1])
    return BenchmarkResult(
        machine=machine_info(), n_states=n, engine_times=engine_times,
        engine_nodes=int(an.sweep.V.size),
        engine_stats={**dict(an.sweep.stats), **{f"refine_{k}": val
                                                 for k, val in an.criticals.stats.items()}},
        fixed=fixed, engine=eng, pairs=pairs, engine_only=e_only, fixed_only=f_only,
        converged=converged, profile_total=ptotal, profile=prow,
        per_speed=Timing(f1.wall / THESIS_SPEEDS.size, f1.cpu / THESIS_SPEEDS.size),
        variants=var)


def _fmt_t(t: Timing) -> str:
    return f"{t.wall:8.3f} {t.cpu:8.3f}"


def report(res: BenchmarkResult) -> str:
    """Plain-text tables of a :class:`BenchmarkResult`."""
    L = []
    L.append("Machine: " + ", ".join(f"{k} {val}" for k, val in res.machine.items()))
    L.append(f"Model: wingtip propeller-wing (§10.1), {res.n_states} states; range 1-350 m/s")
    L.append("")
    L.append(f"{'method':58s} {'wall [s]':>8s} {'cpu [s]':>8s}")
    e = res.engine_best
    L.append(f"{'(a) engine analyse(), default grid, 1 thread (best of %d)' % len(res.engine_times):58s} "
             f"{_fmt_t(e)}")
    L.append(f"{'    all repeats (wall)':58s} " + " ".join(f"{t.wall:.3f}" for t in res.engine_times))
    L.append(f"{'    speeds evaluated (full eig)':58s} {res.engine_nodes:8d}")
    for th, f in res.fixed.items():
        L.append(f"{'(b) fixed ΔV = 1 m/s, %d speeds, eig+vectors, %d thread(s)' % (f.V.size, th):58s} "
                 f"{_fmt_t(f.total)}")
        L.append(f"{'      state-matrix assembly':58s} {_fmt_t(f.assembly)}")
        L.append(f"{'      numpy.linalg.eig':58s} {_fmt_t(f.eig)}")
        L.append(f"{'      sign-change detection':58s} {_fmt_t(f.detection)}")
    for th in res.fixed:
        L.append(f"speed-up (b, {th} thread(s)) / (a): wall {res.speedup(th):.1f}x, "
                 f"cpu {res.speedup(th, cpu=True):.1f}x")
    n001 = int(round(349 / 0.01)) + 1
    est = res.per_speed.cpu * n001
    L.append(f"fixed grid to the engine's accuracy (ΔV = 0.01 m/s, {n001} speeds), estimated "
             f"from the measured cost per speed ({res.per_speed.cpu * 1e3:.1f} ms cpu): "
             f"{est:.0f} s cpu = {est / e.cpu:.0f}x the engine")
    L.append("")
    L.append("Crossings (engine vs fixed grid vs converged):")
    L.append(f"  {'event':15s} {'kind':10s} {'mode':11s} {'V engine':>10s} {'f engine':>9s} "
             f"{'V grid':>8s} {'f grid':>7s} {'V converged':>12s} {'engine err':>10s}")
    conv = {id(c): (Vc, hw) for c, Vc, hw in res.converged}
    for a, b in res.pairs:
        Vc, hw = conv.get(id(a), (float("nan"), float("nan")))
        L.append(f"  {a.event:15s} {a.kind:10s} {a.label:11s} {a.V:10.4f} {a.frequency_hz:9.4f} "
                 f"{b.V:8.2f} {b.frequency_hz:7.3f} {Vc:12.4f} {a.V - Vc:+10.4f}")
    for c in res.engine_only:
        L.append(f"  engine only: {c}")
    for c in res.fixed_only:
        L.append(f"  fixed grid only: {c}")
    L.append(f"every crossing found by both: {res.all_found}; "
             f"max |engine - converged| = {res.max_error:.4f} m/s (converged to ±0.00005 m/s)")
    if res.profile:
        L.append("")
        L.append(f"Engine profile (cProfile, one run, {res.profile_total:.3f} s with profiler; "
                 "parts overlap):")
        for name, ct, calls in res.profile:
            L.append(f"  {name:45s} {ct:7.3f} s  {calls:5d} calls")
    L.append(f"Engine counters: {res.engine_stats}")
    if res.variants:
        L.append("")
        L.append("Variants of the engine's core (propwhirl.engine.analyse alone, default grid; "
                 "error over onsets/recoveries, inf = one missed):")
        L.append(f"  {'variant':32s} {'wall [s]':>8s} {'cpu [s]':>8s} {'speeds':>6s} "
                 f"{'(b)/variant':>11s} {'max err [m/s]':>13s} {'unresolved':>10s}")
        f1 = res.fixed[1].total
        for name, t, nodes, err, unres in res.variants:
            L.append(f"  {name:32s} {_fmt_t(t)} {nodes:6d} {f1.cpu / t.cpu:10.1f}x "
                     f"{err:13.4f} {unres:10d}")
    return "\n".join(L)


def main(argv: Sequence[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m propwhirl.benchmark", description=__doc__.split("\n")[0])
    ap.add_argument("--repeats", type=int, default=3, help="timed engine runs (default 3)")
    ap.add_argument("--no-two-threads", action="store_true", help="skip (b) with 2 BLAS threads")
    ap.add_argument("--no-profile", action="store_true", help="skip the cProfile breakdown")
    ap.add_argument("--no-variants", action="store_true",
                    help="skip the variants of the engine's core (initial step, options)")
    ap.add_argument("--markdown", type=Path, default=None,
                    help="also write the tables (as a fenced block) to this file's "
                         "'<!-- benchmark -->' section")
    args = ap.parse_args(argv)
    res = run_benchmark(repeats=args.repeats, two_threads=not args.no_two_threads,
                        profile=not args.no_profile, variants=not args.no_variants)
    text = report(res)
    print(text)
    if args.markdown is not None:
        _write_markdown(args.markdown, text)
    return 0


_BEGIN, _END = "<!-- benchmark:begin -->", "<!-- benchmark:end -->"


def _write_markdown(path: Path, text: str) -> None:
    """Replace the text between the benchmark markers of ``path`` (appended if absent)."""
    block = f"{_BEGIN}\n```text\n{text}\n```\n{_END}"
    old = path.read_text() if path.exists() else ""
    if _BEGIN in old and _END in old:
        new = old[: old.index(_BEGIN)] + block + old[old.index(_END) + len(_END):]
    else:
        new = old + ("\n" if old and not old.endswith("\n") else "") + block + "\n"
    path.write_text(new)


if __name__ == "__main__":
    raise SystemExit(main())
