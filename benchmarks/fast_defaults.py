"""Fast by default (issue 26): what a user gets without options, measured side by side in one run
on one BLAS thread per process.

Run from the repository root (the lead's full run, which writes the tables into
docs/performance.md)::

    .venv/bin/python benchmarks/fast_defaults.py --n 50 --markdown docs/performance.md
    .venv/bin/python benchmarks/fast_defaults.py --n 20               # a shorter map, see (b)

(a) **The wingtip model's default analysis against the thesis's method** — ``analyse(model)``
    with no options (method "auto": the reduced analysis, crossings converged on the full order)
    of the wingtip propeller-wing of §10.1, ``method="dense"`` (the reference), and the thesis's
    fixed grid: ΔV = 1 m/s from 1 to 350 m/s, ``numpy.linalg.eig`` with vectors of the state
    matrix at every speed (350 eigen-solutions).  CPU time (``time.process_time``), the three
    alternated in each of ``--rounds`` rounds (a fresh model per run), median and best; the
    ratio fixed grid / default (target ≥ 50×).
(b) **The n × n map of the wingtip model's mount frequencies** f_θ × f_ψ, 3–12 Hz, with the
    default options of ``critical_map`` (method "auto", warm-started) on ``--processes``
    processes (default 2): wall and CPU time (this process and its workers), the analyses of
    each pass.  With ``--n`` below 50 the 50 × 50 map's wall time is *extrapolated* (× 2500/n²)
    on a line that says so (target < 60 s measured at n = 50).
(c) **The seven-propeller clearance** — ``clearance(model, V_D, processes=2)`` of
    examples/x57_like.toml (= ``propwhirl clearance examples/x57_like.toml --vd V_D
    --processes 2``): wall and CPU time, the number of analyses; and one default and one dense
    analysis of the model (CPU, alternated), what each of the clearance's analyses costs.

Every table starts with the machine: its core count and load average.
"""
from __future__ import annotations

import argparse
import os
import resource
import statistics
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from engine_vs_fixed_grid import machine_info  # noqa: E402
from markdown_section import replace_section  # noqa: E402

BEGIN = "<!-- fast_defaults:begin -->"
END = "<!-- fast_defaults:end -->"
TITLE = "## Fast by default (issue 26)"
PATHS = ("propellers[0].propeller.f_theta", "propellers[0].propeller.f_psi")
X57 = Path(__file__).resolve().parent.parent / "examples" / "x57_like.toml"
#: design dive speed of the clearance [m/s]: 1.15 V_D = 74.75 m/s is below the critical 80.0 m/s,
#: so the model clears and the minimum f_θ and f_ψ of every propeller are searched
X57_VD = 65.0


def _cpu_all() -> float:
    """CPU time [s] of this process and its finished (reaped) children."""
    me, ch = resource.getrusage(resource.RUSAGE_SELF), resource.getrusage(resource.RUSAGE_CHILDREN)
    return me.ru_utime + me.ru_stime + ch.ru_utime + ch.ru_stime


def _cpu(fn):
    t = time.process_time()
    out = fn()
    return time.process_time() - t, out


def _wall_cpu(fn):
    w, c = time.perf_counter(), _cpu_all()
    out = fn()
    return out, time.perf_counter() - w, _cpu_all() - c


def _load() -> str:
    try:
        return " ".join(f"{x:.2f}" for x in os.getloadavg())
    except OSError:
        return "n/a"


# ------------------------------------------------------------------------------------ (a)
def analysis_vs_fixed_grid(rounds: int) -> dict:
    from propwhirl.analysis import analyse
    from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing

    analyse(wingtip_propeller_wing())                   # imports, generated code
    V = np.arange(1.0, 351.0, 1.0)

    def fixed_grid():
        fn = wingtip_propeller_wing().assembly().state_matrix
        for v in V:
            np.linalg.eig(fn(np.array([v]))[0])

    t = {"default": [], "dense": [], "fixed": []}
    events = {}
    for _ in range(rounds):                             # alternated: the same load for all
        for name, run in (("default", lambda: analyse(wingtip_propeller_wing())),
                          ("dense", lambda: analyse(wingtip_propeller_wing(), method="dense")),
                          ("fixed", fixed_grid)):
            c, out = _cpu(run)
            t[name].append(c)
            if out is not None:
                events[name] = [(e.kind, e.event, e.label, e.V) for e in out.events]
                if name == "default":
                    events["reduced_states"] = out.sweep.stats.get("reduced_states")
    same = [a[:3] for a in events["default"]] == [b[:3] for b in events["dense"]]
    dV = max(abs(a[3] - b[3]) for a, b in zip(events["default"], events["dense"]))
    return {"times": t, "same": same, "max_dV": dV, "reduced_states": events["reduced_states"],
            "n_events": len(events["default"])}


# ------------------------------------------------------------------------------------ (b)
def default_map(n: int, processes: int) -> dict:
    from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
    from propwhirl.studies.sweeps import critical_map

    model = wingtip_propeller_wing()
    values = np.linspace(3.0, 12.0, n)
    stats: dict = {}
    m, wall, cpu = _wall_cpu(lambda: critical_map(model, [(PATHS[0], values), (PATHS[1], values)],
                                                  processes=processes, stats=stats))
    kinds, counts = np.unique(m.columns["kind"], return_counts=True)
    return {"n": n, "processes": processes, "wall": wall, "cpu": cpu, "stats": stats,
            "kinds": dict(zip(kinds.tolist(), counts.tolist()))}


# ------------------------------------------------------------------------------------ (c)
def x57_clearance(processes: int, rounds: int) -> dict:
    from propwhirl.analysis import analyse
    from propwhirl.io import load_model
    from propwhirl.studies.clearance import clearance

    model = load_model(X57)
    per = {"default": [], "dense": []}
    for _ in range(rounds):
        for name, method in (("default", "auto"), ("dense", "dense")):
            c, _ = _cpu(lambda: analyse(load_model(X57), method=method))
            per[name].append(c)
    r, wall, cpu = _wall_cpu(lambda: clearance(model, X57_VD, processes=processes))
    return {"wall": wall, "cpu": cpu, "analyses": r.analyses, "cleared": r.cleared,
            "per": per, "states": model.dof_map().n_states, "processes": processes,
            "minimum": [(q.propeller, q.parameter, q.frequency, q.status) for q in r.minimum]}


# ------------------------------------------------------------------------------------ report
def report(a: dict | None, m: dict | None, c: dict | None, info: dict, loads: list[str]) -> str:
    L = [f"Machine: **{info['nproc']} cores** (os.cpu_count), {info['cpu']}; python "
         f"{info['python']}, numpy {info['numpy']}, scipy {info['scipy']}; BLAS one thread per "
         f"process.  Load average (1, 5, 15 min) at the start of each part: "
         + "; ".join(loads) + " (the machine was shared: CPU times are the measure, wall times "
         "depend on the load)."]
    if a is not None:
        t = a["times"]
        med = {k: statistics.median(x) for k, x in t.items()}
        best = {k: min(x) for k, x in t.items()}
        L += ["", f"**(a) The wingtip model (204 states): `analyse(model)` with no options "
              f"against the thesis's fixed grid** (350 × `numpy.linalg.eig` with vectors, "
              f"ΔV = 1 m/s, 1–350 m/s); CPU time, {len(t['default'])} rounds alternated, a fresh "
              "model per run:", "",
              "| run | median CPU [s] | best CPU [s] | fixed grid / run (median) | (best) |",
              "|---|---:|---:|---:|---:|"]
        for k, name in (("default", f"`analyse(model)` (auto: reduced, {a['reduced_states']} "
                                    "states)"),
                        ("dense", '`analyse(model, method="dense")` (the reference)'),
                        ("fixed", "thesis's fixed grid")):
            L.append(f"| {name} | {med[k]:.3f} | {best[k]:.3f} | {med['fixed'] / med[k]:.1f}× | "
                     f"{best['fixed'] / best[k]:.1f}× |")
        L += ["", f"Default against dense: the same {a['n_events']} events (kind, event, mode): "
              f"{a['same']}; largest |ΔV| {a['max_dV']:.4f} m/s.  Target ≥ 50×: "
              f"{'met' if med['fixed'] / med['default'] >= 50 else 'NOT met'} (median)."]
    if m is not None:
        n, st = m["n"], m["stats"]
        L += ["", f"**(b) The {n} × {n} map of the wingtip model's mount frequencies** "
              f"(f_θ × f_ψ, 3–12 Hz, {n * n} points, critical speed to 0.01 m/s over 1–350 m/s), "
              f"`critical_map` with its default options (method auto, warm-started) on "
              f"{m['processes']} processes:", "",
              "| map | analyses | wall [s] | CPU [s] (all processes) | target < 60 s wall |",
              "|---|---|---:|---:|---|",
              f"| {n} × {n}, measured | {st.get('coarse', 0)} coarse + {st.get('fine', 0)} fine "
              f"({st.get('clipped', 0)} clipped) + {st.get('again', 0)} again | {m['wall']:.1f} | "
              f"{m['cpu']:.1f} | {('met' if m['wall'] < 60 else 'NOT met') if n == 50 else '(50 × 50 only)'} |"]
        if n != 50:
            f = 2500 / (n * n)
            L.append(f"| 50 × 50, **extrapolated** from the {n} × {n} map (× {f:.2f}; not "
                     f"measured: run `--n 50`) | ≈ {round(f * n * n)} | ≈ {m['wall'] * f:.0f} | "
                     f"≈ {m['cpu'] * f:.0f} | (not measured) |")
        L += ["", "Points by kind: " + ", ".join(f"{k} {v}" for k, v in m["kinds"].items()) + "."]
    if c is not None:
        per = {k: statistics.median(x) for k, x in c["per"].items()}
        L += ["", f"**(c) The seven-propeller clearance** — `propwhirl clearance "
              f"examples/x57_like.toml --vd {X57_VD:g} --processes {c['processes']}` "
              f"({c['states']} states; the minimum f_θ and f_ψ of each of the 7 propellers):", "",
              "| run | analyses | wall [s] | CPU [s] (all processes) |", "|---|---:|---:|---:|",
              f"| clearance, {c['processes']} processes, default options | {c['analyses']} | "
              f"{c['wall']:.1f} | {c['cpu']:.1f} |", "",
              f"One analysis of the model (CPU, median of {len(c['per']['default'])}, alternated): "
              f"default {per['default']:.2f} s, dense {per['dense']:.2f} s "
              f"({per['dense'] / per['default']:.1f}×).  Cleared: {c['cleared']}."]
    return "\n".join(L)


def main(argv=None) -> int:
    from threadpoolctl import threadpool_limits

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=50, help="values per axis of the map (default 50)")
    ap.add_argument("--processes", type=int, default=2, help="processes of (b) and (c) (default 2)")
    ap.add_argument("--rounds", type=int, default=5, help="rounds of (a) (default 5)")
    ap.add_argument("--only", choices=("analysis", "map", "clearance"), action="append",
                    help="run only these parts (repeatable; default all)")
    ap.add_argument("--markdown", type=Path, help="write the tables into this file's section")
    args = ap.parse_args(argv)
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
    parts = set(args.only or ("analysis", "map", "clearance"))
    info, loads, a, m, c = machine_info(), [], None, None, None
    with threadpool_limits(limits=1):
        if "analysis" in parts:
            loads.append(f"(a) {_load()}")
            a = analysis_vs_fixed_grid(args.rounds)
        if "map" in parts:
            loads.append(f"(b) {_load()}")
            m = default_map(args.n, args.processes)
        if "clearance" in parts:
            loads.append(f"(c) {_load()}")
            c = x57_clearance(args.processes, max(1, args.rounds // 2))
    body = report(a, m, c, info, loads)
    print(body)
    if args.markdown:
        replace_section(args.markdown, body, BEGIN, END, TITLE)
        print(f"wrote {args.markdown}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
