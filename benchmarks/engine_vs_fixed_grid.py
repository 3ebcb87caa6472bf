"""Speed and accuracy of the stability engine against the thesis's fixed-grid method (issue 4.7).

Run from the repository root (``make bench`` does this and writes the tables into
docs/performance.md)::

    .venv/bin/python benchmarks/engine_vs_fixed_grid.py --markdown docs/performance.md

It times, side by side on the same machine,

(a) the engine — :func:`propwhirl.analysis.stability.analyse` with its default grid (1–350 m/s
    every 10 m/s; :func:`propwhirl.engine.analyse` evaluates the grid speeds ~50 m/s apart first
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
Method (b) and the brute force are the test suite's oracles (``tests/helpers/brute_force.py``),
imported from there.

Timing: wall-clock (``time.perf_counter``) and process CPU time (``time.process_time``); on a
shared machine the CPU time of a one-thread run is the steadier number.  The engine is run once
untimed first (imports, generated-code loading, caches); then ``repeats`` rounds alternate one
timed engine run and one timed one-thread fixed-grid sweep, so that both sample the same
spells of load from other jobs, and the minimum of each is reported (the sweep with the
smaller CPU time); the two-thread sweep is run once (each is ~350 identical evaluations, so it
averages itself).  The profile reports the engine's self time per module (cProfile), so it
names no private function and follows the package's layout.
"""
from __future__ import annotations

import argparse
import cProfile
import os
import platform
import pstats
import sys
import time
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import scipy
from threadpoolctl import threadpool_info, threadpool_limits

from propwhirl import engine
from propwhirl import validate as v

# the brute-force oracles live with the tests (tests/helpers/brute_force.py)
sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
from helpers.brute_force import (  # noqa: E402
    THESIS_SPEEDS,
    Crossing,
    FixedGridResult,
    Timing,
    converge_crossing,
    engine_crossings,
    fixed_grid_sweep,
    match_crossings,
)

__all__ = [
    "time_engine", "engine_variants", "profile_engine", "machine_info", "BenchmarkResult",
    "run_benchmark", "report", "main",
]


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
    grid = model.flight.speeds()
    s = model.second_order(np.array([float(grid[0])]))
    rows = []
    fn = model.assembly().state_matrix             # built once, as an analysis does
    for name, step, changes in ENGINE_VARIANTS:
        opts = engine.TrackingOptions(**changes)

        def run():
            return engine.analyse(fn, grid, n_dof=s.n_dof, state_labels=s.labels,
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
                continue                 # an event of analysis.stability, not of the core
            same = [p for p in an.criticals.points if p.direction == c.event
                    and p.kind == c.kind and abs(p.V - c.V) <= 1.0]
            err = max(err, min((abs(p.V - Vc) for p in same), default=float("inf")))
        rows.append((name, best, int(an.sweep.V.size), err, len(an.sweep.unresolved)))
    return rows


def _module_of(filename: str, files: dict[str, str]) -> str:
    """The profile group of a source file: the propwhirl module, numpy.linalg (LAPACK),
    scipy.linalg, scipy.optimize, or the top-level package of anything else."""
    name = files.get(os.path.realpath(filename), "")
    if not name:
        return "built-in / other"
    if name.startswith("propwhirl."):
        return name
    for group in ("numpy.linalg", "scipy.linalg", "scipy.optimize"):
        if name == group or name.startswith(group + "."):
            return group
    return name.split(".")[0]


def profile_engine(model) -> tuple[float, list[tuple[str, float, int]]]:
    """cProfile one engine run: total [s] and (module, self time [s], calls) rows, largest
    first — the time spent in each module's own code (LAPACK's time counts for numpy.linalg,
    whose Python wrappers call it; the generated code for propwhirl.generated.*).

    The profiler's own overhead inflates Python-heavy modules.
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
    files = {os.path.realpath(f): name for name, mod in list(sys.modules.items())
             if isinstance(f := getattr(mod, "__file__", None), str)}
    stats = pstats.Stats(prof).stats  # type: ignore[attr-defined]
    groups: dict[str, list[float]] = {}
    for (fname, _line, _fn), (_cc, nc, tt, _cum, _callers) in stats.items():
        g = groups.setdefault(_module_of(fname, files), [0.0, 0])
        g[0] += tt
        g[1] += nc
    rows = sorted(((k, t, int(n)) for k, (t, n) in groups.items()), key=lambda r: -r[1])
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
    fn = model.assembly().state_matrix          # built once, as an analysis does
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
                 "self time per module):")
        for name, ct, calls in res.profile:
            if ct >= 0.0005:
                L.append(f"  {name:45s} {ct:7.3f} s  {calls:6d} calls")
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
    ap = argparse.ArgumentParser(prog="benchmarks/engine_vs_fixed_grid.py", description=__doc__.split("\n")[0])
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
    from markdown_section import replace_section

    replace_section(path, f"```text\n{text}\n```", _BEGIN, _END)


if __name__ == "__main__":
    raise SystemExit(main())
