"""Design-size models: the reduced-order analysis against the dense engine and the thesis's grid (issue 10).

Run from the repository root (``make bench-design`` does this and writes the table into
docs/performance.md)::

    .venv/bin/python benchmarks/design_size.py --markdown docs/performance.md
    .venv/bin/python benchmarks/design_size.py --quick      # smoke run: no dense 100/12

The design models are the thesis's baseline wing (§9.1, ``baseline_wing(n_el)``), flight
condition and propeller with ``n_prop`` flexibly mounted propellers evenly spaced along the span,
the last at the tip (:func:`design`).  Measured side by side in one run, BLAS limited to one
thread (threadpoolctl), the machine's core count printed with the results:

(a) the 100-element, 12-propeller wing analysed by :func:`propwhirl.analysis.analyse` with its
    default method (reduced above 400 states) and with ``method="dense"`` (every root of the
    full-order A(V) at each speed): time ratio, and every crossing of both (matched one to one:
    same event and kind, within 1 m/s) with its speed and frequency from both and the difference;
(b) the default analysis of the design models 25/1, 25/4, 50/8, 100/1, 100/12 and 200/12
    (elements / propellers): states, reduced states (``a.sweep.stats["reduced_states"]``, "-"
    when dense), time; and the ratio of the 200/12 time to the 25/1 time;
(c) the wingtip propeller-wing of §10.1 (``wingtip_propeller_wing()``, 204 states, analysed
    dense by default) with ``method="reduced"`` and with the default, against the thesis's fixed
    ΔV = 1 m/s grid of full eigendecompositions (one thread); the error of every crossing
    against its converged value (bisection of the grid's bracket on the exact unstable-root
    count).  The grid sweep and the convergence are those of ``engine_vs_fixed_grid.py``
    (the test suite's oracles, imported through it);
(d) the peak memory of the 200/12 analysis: ``tracemalloc`` peak (Python and NumPy
    allocations) and the growth of the process's maximum resident set size (``ru_maxrss``)
    during it; measured in a run of its own (tracemalloc slows the run down), before any
    larger analysis has raised the process's peak.

Timing: wall-clock and process CPU time (``Timing.measure``); an untimed analysis of a small
model first (imports, generated code); every timed run analyses a freshly built model (the model
build itself is not timed).  The short configurations (under ``short`` seconds) are the best of
``repeats`` runs, the long ones are timed once.  Ratios are given for both CPU and wall time;
on a shared machine the CPU time of a one-thread run is the steadier figure.
"""
from __future__ import annotations

import argparse
import resource
import sys
import tracemalloc
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from threadpoolctl import threadpool_limits

sys.path.insert(0, str(Path(__file__).resolve().parent))
from markdown_section import replace_section  # noqa: E402
import engine_vs_fixed_grid as evfg  # noqa: E402  (also puts tests/ on sys.path)

Timing = evfg.Timing

BEGIN = "<!-- design_size:begin -->"
END = "<!-- design_size:end -->"
TITLE = "## Design-size models: reduced-order analysis (issue 10)"

#: (elements, propellers) of table (b)
CONFIGS: tuple[tuple[int, int], ...] = ((25, 1), (25, 4), (50, 8), (100, 1), (100, 12), (200, 12))
#: the model of (a), the numerator and denominator of (b)'s ratio, the model of (d)
CASE_A, BIG, SMALL = (100, 12), (200, 12), (25, 1)
#: targets of issue 10
TARGET_A, TARGET_B, TARGET_C, TARGET_C_ERR = 20.0, 12.0, 50.0, 0.01

__all__ = ["design", "time_analysis", "design_table", "wingtip_vs_grid", "memory_peak",
           "DesignResult", "run", "report", "write_markdown", "main"]


def design(n_el: int, n_prop: int):
    """The baseline wing of ``n_el`` elements with ``n_prop`` baseline propellers (flexible
    mounts) evenly spaced along the span, the last at the tip (issue 10)."""
    from propwhirl.cases.ch09_baseline import baseline_flight, baseline_propeller, baseline_wing
    from propwhirl.model.systems import Installation, PropellerWing

    wing = baseline_wing(n_el)
    ys = wing.node_y
    idx = np.unique(np.round(np.linspace(0, n_el, n_prop + 1)[1:]).astype(int))
    prop = baseline_propeller()
    return PropellerWing(wing, baseline_flight(),
                         tuple(Installation(prop, float(ys[i]), "flexible") for i in idx),
                         name=f"{n_el} elements / {n_prop} propellers")


def _best(times: Sequence[Timing]) -> Timing:
    return Timing(min(t.wall for t in times), min(t.cpu for t in times))


def time_analysis(build: Callable[[], Any], method: str = "auto", repeats: int = 3,
                  short: float = 5.0, speeds=None) -> tuple[Timing, int, Any]:
    """Time ``analyse(build(), method=method)`` (one BLAS thread; a fresh model per run): once,
    and if it took less than ``short`` seconds of CPU, ``repeats`` − 1 more times.  Returns the
    best time, the number of timed runs and the last analysis."""
    from propwhirl.analysis import analyse

    times, an = [], None
    with threadpool_limits(limits=1):
        for i in range(max(1, repeats)):
            model = build()
            t, an = Timing.measure(lambda: analyse(model, speeds, method=method))
            times.append(t)
            if t.cpu >= short:
                break
    return _best(times), len(times), an


@dataclass
class Row:
    """One configuration of table (b)."""

    n_el: int
    n_prop: int
    n_props_placed: int
    states: int
    reduced_states: int | None
    method: str
    time: Timing
    runs: int
    analysis: Any = field(repr=False, default=None)

    @property
    def name(self) -> str:
        return f"{self.n_el}/{self.n_prop}"


def _method_of(an) -> str:
    return "reduced" if "reduced_states" in an.sweep.stats else "dense"


def design_table(configs: Sequence[tuple[int, int]] = CONFIGS, *, repeats: int = 3,
                 short: float = 5.0, build: Callable[[int, int], Any] = design,
                 speeds=None) -> list[Row]:
    """Table (b): the default analysis of each (elements, propellers) configuration."""
    rows = []
    for n_el, n_prop in configs:
        model = build(n_el, n_prop)
        t, runs, an = time_analysis(lambda: build(n_el, n_prop), "auto", repeats, short, speeds)
        rs = an.sweep.stats.get("reduced_states")
        rows.append(Row(n_el, n_prop, len(model.propellers), int(model.dof_map().n_states),
                        None if rs is None else int(rs), _method_of(an), t, runs, an))
    return rows


def _crossings_vs_converged(an, grid, fn) -> list[tuple[Any, float, float]]:
    """(crossing of ``an``, converged V, V − converged) for every crossing of ``an`` matched to
    one of the fixed grid (same event/kind, within 1 m/s); unmatched ones get nan."""
    eng = evfg.engine_crossings(an)
    pairs, only, _ = evfg.match_crossings(eng, grid.crossings)
    out = []
    for e, f in pairs:
        Vc, _hw = evfg.converge_crossing(fn, *f.bracket, complex_only=e.event == "frequency-zero")
        out.append((e, Vc, e.V - Vc))
    out += [(e, float("nan"), float("nan")) for e in only]
    return sorted(out, key=lambda r: r[0].V)


@dataclass
class WingtipResult:
    """(c): the wingtip model, reduced and default analysis vs the fixed grid."""

    states: int
    reduced_states: int | None
    reduced: Timing
    default: Timing
    default_method: str
    runs: tuple[int, int]
    grid: Any                                   # FixedGridResult
    errors: dict[str, list[tuple[Any, float, float]]]
    grid_only: dict[str, list[Any]]
    name: str = ""


def wingtip_vs_grid(model_factory: Callable[[], Any] | None = None, repeats: int = 3,
                    speeds=None) -> WingtipResult:
    """(c): ``method="reduced"`` and the default analysis of the wingtip model vs the thesis's
    fixed ΔV = 1 m/s grid (one thread), every crossing against its converged value."""
    if model_factory is None:
        from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing as model_factory
    grid_speeds = evfg.THESIS_SPEEDS if speeds is None else np.asarray(speeds, float)
    t_red, n_red, a_red = time_analysis(model_factory, "reduced", repeats, short=1e9, speeds=None)
    t_def, n_def, a_def = time_analysis(model_factory, "auto", repeats, short=1e9, speeds=None)
    model = model_factory()
    fn = model.assembly().state_matrix          # built once, as an analysis does
    runs = [evfg.fixed_grid_sweep(fn, grid_speeds, threads=1) for _ in range(max(1, repeats))]
    grid = min(runs, key=lambda r: r.total.cpu)
    errors, grid_only = {}, {}
    for name, an in (("reduced", a_red), ("default", a_def)):
        errors[name] = _crossings_vs_converged(an, grid, fn)
        _, _, fo = evfg.match_crossings(evfg.engine_crossings(an), grid.crossings)
        grid_only[name] = fo
    rs = a_red.sweep.stats.get("reduced_states")
    return WingtipResult(int(model.dof_map().n_states), None if rs is None else int(rs), t_red,
                         t_def, _method_of(a_def), (n_red, n_def), grid, errors, grid_only,
                         model.name)


def _maxrss_mb() -> float:
    """The process's maximum resident set size [MB] (Linux: ru_maxrss in kB)."""
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def memory_peak(build: Callable[[], Any], speeds=None) -> dict[str, float]:
    """(d): tracemalloc peak [MB] of one default analysis of ``build()`` (model built before the
    measurement starts), and the growth of ru_maxrss [MB] during it."""
    from propwhirl.analysis import analyse

    model = build()
    rss0 = _maxrss_mb()
    with threadpool_limits(limits=1):
        tracemalloc.start()
        try:
            tracemalloc.reset_peak()
            base, _ = tracemalloc.get_traced_memory()
            analyse(model, speeds)
            _, peak = tracemalloc.get_traced_memory()
        finally:
            tracemalloc.stop()
    rss1 = _maxrss_mb()
    return {"tracemalloc_peak_mb": (peak - base) / 2**20, "maxrss_before_mb": rss0,
            "maxrss_after_mb": rss1, "maxrss_growth_mb": rss1 - rss0}


@dataclass
class DesignResult:
    """Everything one run measured (see :func:`run`)."""

    machine: dict[str, str]
    memory: dict[str, float]
    memory_case: tuple[int, int]
    rows: list[Row]
    dense_a: Row | None                      # (a): the dense analysis of CASE_A (None: skipped)
    case_a: tuple[int, int]
    wingtip: WingtipResult | None
    ratio_pair: tuple[tuple[int, int], tuple[int, int]]

    def row(self, cfg: tuple[int, int]) -> Row | None:
        return next((r for r in self.rows if (r.n_el, r.n_prop) == tuple(cfg)), None)


def run(configs: Sequence[tuple[int, int]] = CONFIGS, *, case_a: tuple[int, int] | None = CASE_A,
        big: tuple[int, int] = BIG, small: tuple[int, int] = SMALL, wingtip: bool = True,
        repeats: int = 3, short: float = 5.0, build: Callable[[int, int], Any] = design,
        wingtip_factory: Callable[[], Any] | None = None, speeds=None,
        grid_speeds=None) -> DesignResult:
    """Measure (d), (b), (a) and (c) in that order (see the module docstring).  ``case_a``
    None skips the dense analysis of (a) (``--quick``)."""
    from propwhirl.analysis import analyse

    with threadpool_limits(limits=1):
        analyse(build(*small), speeds)                       # warm-up: imports, generated code
    mem = memory_peak(lambda: build(*big), speeds)
    rows = design_table(configs, repeats=repeats, short=short, build=build, speeds=speeds)
    dense = None
    if case_a is not None:
        model = build(*case_a)
        t, runs, an = time_analysis(lambda: build(*case_a), "dense", repeats, short, speeds)
        dense = Row(case_a[0], case_a[1], len(model.propellers),
                    int(model.dof_map().n_states), None, "dense", t, runs, an)
    wt = None
    if wingtip:
        wt = wingtip_vs_grid(wingtip_factory, repeats, grid_speeds)
    return DesignResult(evfg.machine_info(), mem, tuple(big), rows, dense,
                        tuple(case_a) if case_a else tuple(CASE_A), wt, (tuple(big), tuple(small)))


def _met(ok: bool) -> str:
    return "met" if ok else "NOT met"


def _ratio(num: Timing, den: Timing) -> tuple[float, float]:
    return num.cpu / den.cpu, num.wall / den.wall


def report(res: DesignResult) -> str:
    """The tables of a :class:`DesignResult` (markdown)."""
    L = []
    m = res.machine
    L.append(f"Machine: **{m['nproc']} cores** (os.cpu_count), {m['cpu']}; load average "
             f"(1, 5, 15 min) {m['load average (1, 5, 15 min)']}; python {m['python']}, numpy "
             f"{m['numpy']}, scipy {m['scipy']}, BLAS {m['blas']} limited to 1 thread "
             "(threadpoolctl). Times: wall / CPU [s].")
    L.append("")
    # (b)
    L.append("**(b) Default analysis (`analyse(model)`, method \"auto\") of the design models**")
    L.append("")
    L.append("| elements / propellers | propellers placed | states | method | reduced states "
             "| runs | wall [s] | CPU [s] |")
    L.append("|---|---|---|---|---|---|---|---|")
    for r in res.rows:
        L.append(f"| {r.name} | {r.n_props_placed} | {r.states} | {r.method} | "
                 f"{'-' if r.reduced_states is None else r.reduced_states} | {r.runs} | "
                 f"{r.time.wall:.3f} | {r.time.cpu:.3f} |")
    big, small = res.row(res.ratio_pair[0]), res.row(res.ratio_pair[1])
    if big is not None and small is not None:
        rc, rw = _ratio(big.time, small.time)
        L.append("")
        L.append(f"Ratio {big.name} / {small.name}: **{rc:.1f}× CPU** ({rw:.1f}× wall); target "
                 f"≤ {TARGET_B:g}×: {_met(rc <= TARGET_B)} (CPU).")
    L.append("")
    # (a)
    red_a = res.row(res.case_a)
    if res.dense_a is not None and red_a is not None:
        d = res.dense_a
        rc, rw = _ratio(d.time, red_a.time)
        kept = "" if red_a.reduced_states is None else f"{red_a.reduced_states} of "
        L.append(f"**(a) {red_a.name}: default ({red_a.method}, {kept}{red_a.states} states) "
                 "vs `method=\"dense\"`**")
        L.append("")
        L.append(f"Time: {red_a.method} {red_a.time.wall:.2f} s wall / {red_a.time.cpu:.2f} s CPU; "
                 f"dense {d.time.wall:.2f} s wall / {d.time.cpu:.2f} s CPU ({d.runs} run(s)). "
                 f"Ratio dense / {red_a.method}: **{rc:.1f}× CPU** ({rw:.1f}× wall); target "
                 f"≥ {TARGET_A:g}×: {_met(rc >= TARGET_A)} (CPU).")
        L.append("")
        er = evfg.engine_crossings(red_a.analysis)
        ed = evfg.engine_crossings(d.analysis)
        pairs, r_only, d_only = evfg.match_crossings(er, ed)
        L.append(f"| event | kind | mode ({red_a.method}) | V {red_a.method} [m/s] | V dense [m/s] "
                 f"| ΔV [m/s] | f {red_a.method} [Hz] | f dense [Hz] | Δf [Hz] |")
        L.append("|---|---|---|---|---|---|---|---|---|")
        dv = []
        for a, b in sorted(pairs, key=lambda p: p[1].V):
            dv.append(abs(a.V - b.V))
            L.append(f"| {a.event} | {a.kind} | {a.label} | {a.V:.4f} | {b.V:.4f} | "
                     f"{a.V - b.V:+.4f} | {a.frequency_hz:.4f} | {b.frequency_hz:.4f} | "
                     f"{a.frequency_hz - b.frequency_hz:+.4f} |")
        for c in r_only:
            L.append(f"| {c.event} | {c.kind} | {c.label} | {c.V:.4f} | (none) | | "
                     f"{c.frequency_hz:.4f} | | |")
        for c in d_only:
            L.append(f"| {c.event} | {c.kind} | {c.label} (dense) | (none) | {c.V:.4f} | | | "
                     f"{c.frequency_hz:.4f} | |")
        same = not r_only and not d_only
        L.append("")
        L.append(f"Same crossings: **{same}** ({len(pairs)} matched, {len(r_only)} "
                 f"{red_a.method} only, {len(d_only)} dense only); max |ΔV| = "
                 f"{max(dv, default=float('nan')):.4f} m/s.")
        L.append("")
    elif red_a is not None:
        L.append(f"**(a)** skipped (--quick): the dense analysis of {red_a.name} was not run.")
        L.append("")
    # (c)
    w = res.wingtip
    if w is not None:
        g = w.grid.total
        step = float(np.min(np.diff(w.grid.V))) if w.grid.V.size > 1 else float("nan")
        L.append(f"**(c) {w.name} ({w.states} states) vs the thesis's fixed grid "
                 f"(ΔV = {step:g} m/s, {w.grid.V.size} speeds, `numpy.linalg.eig` with vectors, "
                 "1 thread)**")
        L.append("")
        L.append("| method | states | wall [s] | CPU [s] | grid / method (CPU) | grid / method "
                 "(wall) | target ≥ 50× | max \\|V − converged\\| [m/s] | within 0.01 m/s |")
        L.append("|---|---|---|---|---|---|---|---|---|")
        L.append(f"| fixed grid | {w.states} | {g.wall:.3f} | {g.cpu:.3f} | 1 | 1 | | | |")
        for name, t, st in (("reduced", w.reduced, w.reduced_states),
                            (f"default ({w.default_method})", w.default,
                             w.reduced_states if w.default_method == "reduced" else w.states)):
            key = "reduced" if name == "reduced" else "default"
            errs = [abs(e) for _, _, e in w.errors[key]]
            mx = max(errs, default=float("nan"))
            ok = bool(errs) and all(e <= TARGET_C_ERR for e in errs) and not w.grid_only[key]
            rc, rw = _ratio(g, t)
            L.append(f"| {name} | {st} | {t.wall:.3f} | {t.cpu:.3f} | {rc:.1f}× | {rw:.1f}× | "
                     f"{_met(rc >= TARGET_C)} | {mx:.4f} | {ok} |")
        L.append("")
        L.append("| event | kind | mode | V converged [m/s] | V reduced − converged [m/s] "
                 "| V default − converged [m/s] |")
        L.append("|---|---|---|---|---|---|")
        red = w.errors["reduced"]
        dfl = list(w.errors["default"])
        for c, Vc, e in red:
            j = next((k for k, (c2, Vc2, _) in enumerate(dfl)
                      if c2.event == c.event and c2.kind == c.kind and Vc2 == Vc), None)
            e2 = dfl.pop(j)[2] if j is not None else float("nan")
            L.append(f"| {c.event} | {c.kind} | {c.label} | {Vc:.4f} | {e:+.4f} | {e2:+.4f} |")
        for c, Vc, e in dfl:
            L.append(f"| {c.event} | {c.kind} | {c.label} | {Vc:.4f} | (none) | {e:+.4f} |")
        for key in ("reduced", "default"):
            for c in w.grid_only[key]:
                L.append(f"| {c.event} | {c.kind} | grid only, missed by {key} | ({c.V:.2f}) | | |")
        L.append("")
    # (d)
    mm = res.memory
    L.append(f"**(d) Peak memory of the {res.memory_case[0]}/{res.memory_case[1]} default "
             f"analysis** (a run of its own): tracemalloc peak **{mm['tracemalloc_peak_mb']:.1f} MB**;"
             f" ru_maxrss {mm['maxrss_before_mb']:.1f} → {mm['maxrss_after_mb']:.1f} MB "
             f"(growth {mm['maxrss_growth_mb']:.1f} MB).")
    return "\n".join(L)


def write_markdown(path: Path, body: str) -> None:
    """Replace the text between this benchmark's markers in ``path`` (append the section if
    absent): :func:`markdown_section.replace_section`."""
    replace_section(path, body, BEGIN, END, TITLE)


def main(argv: Sequence[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="benchmarks/design_size.py",
                                 description=__doc__.split("\n")[0])
    ap.add_argument("--markdown", type=Path, default=None,
                    help=f"also write the tables between {BEGIN} / {END} of this file")
    ap.add_argument("--quick", action="store_true",
                    help="skip the dense analysis of 100/12 (a smoke run)")
    ap.add_argument("--repeats", type=int, default=3,
                    help="timed runs of the short configurations (default 3)")
    args = ap.parse_args(argv)
    res = run(case_a=None if args.quick else CASE_A, repeats=args.repeats)
    text = report(res)
    print(text)
    if args.markdown is not None:
        write_markdown(args.markdown, text)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
