"""The 50 × 50 map of the wingtip model's critical speed over (f_θ, f_ψ) (issue 12, item 8).

Run from the repository root (``make bench-map`` does this and writes the table into
docs/performance.md)::

    .venv/bin/python benchmarks/map_speed.py --markdown docs/performance.md
    .venv/bin/python benchmarks/map_speed.py --n 10 --reference full     # a quick run

The map: the wingtip propeller-wing of §10.1 (``wingtip_propeller_wing()``), the pitch and yaw
mount frequencies ``propellers[0].propeller.f_theta`` and ``…f_psi`` each at ``n`` values from
3 to 12 Hz, the critical speed of every point to 0.01 m/s over the model's speed range
(1–350 m/s), on ``--processes`` local worker processes (BLAS one thread in each).  Measured
side by side in one run, the machine's core count printed with the results:

* **fast**: ``critical_map(..., method="reduced", warm_start=True)`` (the defaults since
  issue 26: method "auto" reduces a wing) — the reduced-order
  analysis of every point (crossings converged on the full-order model), warm-started
  (:mod:`propwhirl.studies.warmstart`: a coarse pass over every 5th point, the others over a
  speed range clipped at 1.05 × their coarse corners' highest speed);
* **reference**: the brute-force reference, ``critical_map(..., method="dense",
  warm_start=False)`` (the default before issue 26) — the dense engine over the whole
  range at every point (``--reference full``: every point; ``--reference sample``: ``--sample``
  points spread over the map, the full map's time extrapolated from their mean — said so).

Reported: wall and CPU time of both (CPU of this process and its workers), the number of
analyses of each pass, and the agreement of the two on the points both computed (same kind,
mode, event; the largest difference of critical speed [m/s] and frequency [Hz]).
``--plot PNG`` draws the fast map.
"""
from __future__ import annotations

import argparse
import os
import resource
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from markdown_section import replace_section  # noqa: E402
from engine_vs_fixed_grid import machine_info  # noqa: E402

BEGIN = "<!-- map_speed:begin -->"
END = "<!-- map_speed:end -->"
TITLE = "## A 50 × 50 map of the wingtip model (issue 12, item 8)"
PATHS = ("propellers[0].propeller.f_theta", "propellers[0].propeller.f_psi")
TARGET_S = 60.0


def _cpu() -> float:
    """CPU time [s] of this process and its finished children."""
    me, ch = resource.getrusage(resource.RUSAGE_SELF), resource.getrusage(resource.RUSAGE_CHILDREN)
    return me.ru_utime + me.ru_stime + ch.ru_utime + ch.ru_stime


def timed(fn):
    w0, c0 = time.perf_counter(), _cpu()
    out = fn()
    return out, time.perf_counter() - w0, _cpu() - c0


def run(n: int, processes: int, reference: str, sample: int):
    from threadpoolctl import threadpool_limits

    from propwhirl.analysis import analyse
    from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
    from propwhirl.studies import paths as P
    from propwhirl.studies.sweeps import critical_map, run_points

    model = wingtip_propeller_wing()
    values = np.linspace(3.0, 12.0, n)
    axes = [(PATHS[0], values), (PATHS[1], values)]
    with threadpool_limits(1):
        analyse(model)                                   # imports, generated code
    stats: dict = {}
    fast, wf, cf = timed(lambda: critical_map(model, axes, method="reduced", warm_start=True,
                                              processes=processes, stats=stats))
    res = {"n": n, "processes": processes, "fast": (wf, cf), "stats": stats, "map": fast}
    if reference == "full":
        ref, wr, cr = timed(lambda: critical_map(model, axes, method="dense", warm_start=False,
                                                 processes=processes))
        idx = np.arange(n * n)
        res.update(ref=(wr, cr), ref_points=n * n, extrapolated=False)
        ref_rows = {c: ref.columns[c].ravel() for c in ref.columns}
    else:
        idx = np.unique(np.linspace(0, n * n - 1, sample).round().astype(int))
        grid = [(values[i // n], values[i % n]) for i in idx]
        variants = [P.set_values(model, {PATHS[0]: a, PATHS[1]: b}) for a, b in grid]
        rows, wr, cr = timed(lambda: run_points(variants, processes=processes, method="dense"))
        res.update(ref=(wr * n * n / idx.size, cr * n * n / idx.size), ref_points=idx.size,
                   extrapolated=True, ref_measured=(wr, cr))
        ref_rows = {c: np.array([r[c] for r in rows]) for c in rows[0]}
    got = {c: fast.columns[c].ravel()[idx] for c in fast.columns}
    same = {c: int(np.sum(got[c] == ref_rows[c])) for c in ("kind", "critical_mode", "event")}
    dV = np.abs(got["critical_speed"] - ref_rows["critical_speed"])
    df = np.abs(got["critical_frequency"] - ref_rows["critical_frequency"])
    res.update(compared=idx.size, same=same, max_dV=float(np.nanmax(dV)),
               max_df=float(np.nanmax(df)),
               nan_same=bool(np.array_equal(np.isnan(got["critical_speed"]),
                                            np.isnan(ref_rows["critical_speed"]))))
    return res


def report(res: dict) -> str:
    info = machine_info()
    n, wf, cf = res["n"], *res["fast"]
    wr, cr = res["ref"]
    st = res["stats"]
    kinds, counts = np.unique(res["map"].columns["kind"], return_counts=True)
    V = res["map"].critical_speed
    lines = [
        f"Machine: **{info['nproc']} cores** (os.cpu_count), {info['cpu']}; load average "
        f"(1, 5, 15 min) {info['load average (1, 5, 15 min)']}; python {info['python']}, numpy "
        f"{info['numpy']}, scipy {info['scipy']}; BLAS one thread per worker; "
        f"{res['processes']} worker processes.",
        "",
        f"Map: wingtip propeller-wing (§10.1), f_θ × f_ψ = {n} × {n} values from 3 to 12 Hz "
        f"({n * n} points), critical speed to 0.01 m/s over 1–350 m/s.",
        "",
        "| method | analyses | wall [s] | CPU [s] | wall per point [ms] | target < 60 s |",
        "|---|---|---|---|---|---|",
        f"| reference: brute force (dense, whole range){' — extrapolated from ' + str(res['ref_points']) + ' points' if res['extrapolated'] else ''} "
        f"| {n * n} | {wr:.1f} | {cr:.1f} | {1e3 * wr / n / n:.1f} | |",
        f"| reduced, warm-started | {st['coarse']} coarse + {st['fine']} fine ({st['clipped']} "
        f"clipped) + {st['again']} again | {wf:.1f} | {cf:.1f} | {1e3 * wf / n / n:.1f} | "
        f"{('met' if wf < TARGET_S else 'NOT met') if n == 50 else '(n = 50 only)'} |",
        "",
        f"Speed-up (wall): **{wr / wf:.1f}×**.  Compared on {res['compared']} points: same kind "
        f"{res['same']['kind']}, same mode {res['same']['critical_mode']}, same event "
        f"{res['same']['event']}; max |ΔV| = {res['max_dV']:.4f} m/s, max |Δf| = "
        f"{res['max_df']:.5f} Hz; the same points without an instability: {res['nan_same']}.",
    ]
    if res["extrapolated"]:
        mw, mc = res["ref_measured"]
        lines.append(f"(Reference measured on {res['ref_points']} points: {mw:.1f} s wall, "
                     f"{mc:.1f} s CPU.)")
    lines += ["", "Fast map: critical speed " + f"{np.nanmin(V):.2f}–{np.nanmax(V):.2f} m/s; "
              + ", ".join(f"{k}: {c} points" for k, c in zip(kinds, counts)) + "."]
    return "\n".join(lines)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=50, help="values per axis (default 50)")
    ap.add_argument("--processes", type=int, default=os.cpu_count() or 1)
    ap.add_argument("--reference", choices=("full", "sample"), default="full")
    ap.add_argument("--sample", type=int, default=100, help="reference points with --reference sample")
    ap.add_argument("--markdown", type=Path, help="write the table into this file's section")
    ap.add_argument("--plot", type=Path, help="draw the fast map into this PNG")
    args = ap.parse_args(argv)
    res = run(args.n, args.processes, args.reference, args.sample)
    body = report(res)
    print(body)
    if args.markdown:
        replace_section(args.markdown, body, BEGIN, END, TITLE)
        print(f"wrote {args.markdown}")
    if args.plot:
        from propwhirl.app import plots

        plots.critical_map(res["map"], path=args.plot)
        print(f"wrote {args.plot}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
