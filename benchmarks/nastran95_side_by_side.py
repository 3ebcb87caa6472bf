"""propwhirl and NASTRAN-95 side by side on the cases of issue 37's table (item 2): CPU and
critical speeds, in one run.

Run from the repository root::

    make bench-nastran95             # builds .venv-bench312 (Python 3.12, nastran95) and runs:
    .venv-bench312/bin/python benchmarks/nastran95_side_by_side.py --markdown docs/performance.md
    ... --only goland4x7,goland8x14  # some cases
    ... --quick                      # without the 16 x 28 Goland panels

Where the ``nastran95`` package is not importable (it needs Python >= 3.12; the main
``.venv`` is 3.11) the NASTRAN-95 column is left empty and the output says so.

Each case, in this order:

* **NASTRAN-95 PK** (``nastran95``, its ``nastrn`` executable as a subprocess; CPU = user +
  system of that process, ``resource.getrusage(RUSAGE_CHILDREN)`` around it): the deck of
  ``benchmarks/nastran95_decks.py`` — propwhirl's own structure as its 6 lowest in-vacuo modes,
  propwhirl's spline, NASTRAN's own doublet-lattice boxes (or strips), its whole table of AICs
  (one Mach, the k of ``MKAERO1``: propwhirl's table nodes up to the highest mode's k at the
  lowest speed), the PK solution at the same speeds as propwhirl's.  Its critical speed: the
  first sign change of g, linear in V between the speeds; then *refined* by a second run
  (not in the CPU column: its own CPU is listed) at speeds 0.05 m/s apart within ±1 m/s of it.
* **propwhirl p-k** (``analyse(model, speeds, method="pk")``) and **propwhirl default**
  (``analyse(model, speeds)``), each in a fresh interpreter (first run, nothing imported, no
  ``PROPWHIRL_DLM_CACHE``, one BLAS thread): CPU of ``analyse`` (the process and any worker
  processes it started) and of the whole process (start-up and imports included), the
  critical speed.

Cases (issue 37's table): the Goland wing (``benchmarks/dlm_goland.py``, 10 beam elements)
with strips at ρ = 1.225 kg/m³ (NASTRAN: 80 strips, Theodorsen, C_lα = 2π) and with
doublet-lattice panels 4 × 7, 8 × 14, 16 × 16, 16 × 28 at ρ = 1.02, Mach 0, 120–200 m/s every
10; the wingtip model's wing without its propeller
(``propwhirl.cases.ch10_other_wings.wingtip_propeller_wing``, 25 elements, DLM 8 × 29) at
Mach 0 and at a fixed Mach 0.5, 100–350 m/s every 10.
"""
from __future__ import annotations

import argparse
import dataclasses
import json
import os
import platform
import resource
import subprocess
import sys
import time
from importlib import metadata
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "benchmarks"))

BEGIN = "<!-- nastran95_side_by_side: begin (benchmarks/nastran95_side_by_side.py writes this block) -->"
END = "<!-- nastran95_side_by_side: end -->"
TITLE = "## propwhirl and NASTRAN-95 side by side (issue 37, item 2)"

GOLAND_SPEEDS = np.arange(120.0, 201.0, 10.0)
WINGTIP_SPEEDS = np.arange(100.0, 351.0, 10.0)
#: case: (label, NASTRAN-95 deck keywords)
CASES = {
    "goland_strips": ("Goland, strips (NASTRAN: 80), ρ 1.225", {"strips": 80}),
    "goland4x7": ("Goland DLM 4 × 7, ρ 1.02, Mach 0", {}),
    "goland8x14": ("Goland DLM 8 × 14, ρ 1.02, Mach 0", {}),
    "goland16x16": ("Goland DLM 16 × 16, ρ 1.02, Mach 0", {}),
    "goland16x28": ("Goland DLM 16 × 28, ρ 1.02, Mach 0", {}),
    "wingtip_m0": ("wingtip wing alone, DLM 8 × 29, Mach 0", {}),
    "wingtip_m05": ("the same, fixed Mach 0.5", {}),
}
#: modes of the NASTRAN-95 deck (issue 37: "its structure is 6 modes")
N_MODES = 6
#: the refinement run: ± this [m/s] around the first crossing, every REFINE_STEP
REFINE_HALF, REFINE_STEP = 1.0, 0.05


def build(case: str):
    """(model, speeds [m/s], Mach of its loads) of a case."""
    from propwhirl.model import FlightCondition, PropellerWing
    if case.startswith("goland"):
        from dlm_goland import RHO_SEA, RHO_SHARPY, goland_wing
        if case == "goland_strips":
            return PropellerWing(goland_wing(), FlightCondition(RHO_SEA)), GOLAND_SPEEDS, 0.0
        nc, ns = {"goland4x7": (4, 7), "goland8x14": (8, 14), "goland16x16": (16, 16),
                  "goland16x28": (16, 28)}[case]
        wing = dataclasses.replace(goland_wing("dlm", (nc, ns)), dlm_mach=0.0)
        return PropellerWing(wing, FlightCondition(RHO_SHARPY)), GOLAND_SPEEDS, 0.0
    from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
    mach = {"wingtip_m0": 0.0, "wingtip_m05": 0.5}[case]
    model = wingtip_propeller_wing().with_(propellers=())
    wing = dataclasses.replace(model.wing, aero="dlm", dlm_mach=mach)
    return model.with_(wing=wing), WINGTIP_SPEEDS, mach


# --------------------------------------------------------------------------- propwhirl side
def run_propwhirl(case: str, method: str) -> dict:
    """One analysis in this (fresh) process: its CPU, the whole process's, the critical."""
    from propwhirl.analysis import analyse
    model, speeds, _ = build(case)
    t0 = time.process_time()
    c0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    a = analyse(model, speeds, method=method)
    c1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = time.process_time() - t0 + (c1.ru_utime - c0.ru_utime) + (c1.ru_stime - c0.ru_stime)
    own = resource.getrusage(resource.RUSAGE_SELF)
    c = a.critical
    return {"case": case, "side": method, "cpu_s": cpu,
            "process_cpu_s": own.ru_utime + own.ru_stime + c1.ru_utime + c1.ru_stime,
            "peak_rss_mb": max(own.ru_maxrss, c1.ru_maxrss) / 1024,
            "critical": None if c is None else [c.kind, float(c.V), float(c.frequency_hz)],
            "events": [[e.kind, e.event, float(e.V), float(e.frequency_hz)] for e in a.events]}


def measure_propwhirl(case: str, method: str) -> dict:
    """:func:`run_propwhirl` in a fresh interpreter (first run, one BLAS thread, no cache)."""
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1", MKL_NUM_THREADS="1")
    env.pop("PROPWHIRL_DLM_CACHE", None)
    out = subprocess.run([sys.executable, __file__, "--case", case, "--method", method],
                         capture_output=True, text=True, check=True, env=env, cwd=ROOT)
    return json.loads(out.stdout.strip().splitlines()[-1])


# --------------------------------------------------------------------------- NASTRAN side
def nastran_version() -> str | None:
    """The installed ``nastran95`` package's version, None when it cannot be imported."""
    try:
        import nastran95  # noqa: F401
    except ImportError:
        return None
    return metadata.version("nastran95")


def run_nastran(case: str) -> dict:
    """The case's NASTRAN-95 PK run (timed) and its refinement run (timed apart)."""
    import nastran95_decks as nd
    model, speeds, mach = build(case)
    kw = CASES[case][1]
    text = nd.deck(model, speeds, mach=mach, n_modes=N_MODES, title=case, **kw)
    res, cpu = nd.run_deck(text)
    if not res.completed:
        raise RuntimeError(f"NASTRAN-95 did not complete {case}: {res.output[-2000:]}")
    ks = nd.k_nodes(model, speeds, nd.structural_modes(model, N_MODES))
    cross = nd.crossings(nd.flutter_summary(res.output))
    out = {"case": case, "side": "nastran95", "cpu_s": cpu, "wall_s": res.wall_time,
           "aics": int(ks.size), "speeds": int(speeds.size), "crossings": cross,
           "critical": None, "refine_cpu_s": None}
    out["onsets"], out["refine_cpu_s"] = [], 0.0
    for V0, f0, point, event in cross:
        if event != "onset":
            continue
        fine = np.round(np.arange(V0 - REFINE_HALF, V0 + REFINE_HALF + 1e-9, REFINE_STEP), 6)
        res2, cpu2 = nd.run_deck(nd.deck(model, fine, mach=mach, n_modes=N_MODES, ks=ks,
                                         title=case, **kw))
        out["refine_cpu_s"] += cpu2
        near = [c for c in nd.crossings(nd.flutter_summary(res2.output))
                if c[3] == "onset" and c[2] == point]
        V, f = (near[0][0], near[0][1]) if near else (V0, f0)
        out["onsets"].append(["divergence" if f == 0.0 else "flutter", V, f, bool(near)])
    if out["onsets"]:
        out["critical"] = min(out["onsets"], key=lambda o: o[1])[:3]
    return out


# --------------------------------------------------------------------------- the table
def versions() -> str:
    def v(name: str) -> str:
        try:
            return metadata.version(name)
        except metadata.PackageNotFoundError:
            return "not installed"
    try:
        rev = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True,
                             text=True, cwd=ROOT).stdout.strip() or "?"
    except OSError:
        rev = "?"
    return (f"Python {platform.python_version()}, NumPy {v('numpy')}, SciPy {v('scipy')}, "
            f"PanelAero {v('panelaero')}, nastran95 {v('nastran95')}, propwhirl {rev}")


def _crit(c) -> str:
    return "none" if c is None else f"{c[1]:.2f} ({c[0]}, {c[2]:.3f} Hz)"


def _same_events(n: dict, pw: dict) -> list[str]:
    """Each NASTRAN-95 onset against propwhirl's onset of the same kind nearest in speed:
    the difference in V (and f), or that propwhirl has none within 2 %."""
    out = []
    for kind, V, f, _ in n.get("onsets", []):
        same = [e for e in pw["events"] if e[0] == kind and e[1] == "onset"]
        e = min(same, key=lambda e: abs(e[2] - V)) if same else None
        if e is None or abs(e[2] / V - 1) > 0.02:
            out.append(f"{kind} {V:.2f}: none in propwhirl")
            continue
        df = "" if f == 0 else f", f {100 * (e[3] / f - 1):+.2f} %"
        out.append(f"{kind} {100 * (e[2] / V - 1):+.3f} %{df}")
    return out


def _s(x: float) -> str:
    """CPU seconds: two decimals below 1 s (the small rows' ratios are read from them)."""
    return f"{x:.2f}" if x < 1 else f"{x:.1f}"


def table(rows: dict, load: tuple[float, float], have_nastran: bool) -> str:
    lines = [f"Measured by `benchmarks/nastran95_side_by_side.py` on {time.strftime('%Y-%m-%d')}: "
             f"{os.cpu_count()} cores, load average {load[0]:.1f} before and {load[1]:.1f} "
             f"after the run (a machine shared with other sessions: CPU seconds, not wall); "
             f"{versions()}.  Each propwhirl analysis in a fresh interpreter (first run, no "
             "AIC cache, one BLAS thread; CPU of `analyse` with any worker processes, and of "
             "the whole process in brackets); NASTRAN-95: the CPU of its process for one PK "
             f"solution with its {N_MODES} modes and its whole AIC table (the AICs: their "
             "count), at propwhirl's speeds."
             + ("" if have_nastran else "  **NASTRAN-95 not measured: the optional `nastran95` "
                "package (Python >= 3.12: `make bench-nastran95`) is not installed here.**"),
             "", "| case | NASTRAN-95 PK [s] (AICs) | propwhirl p-k [s] | propwhirl default [s] "
                 "| p-k / NASTRAN | default / NASTRAN | critical: NASTRAN-95 [m/s] "
                 "| propwhirl p-k | propwhirl default | p-k − NASTRAN, each NASTRAN onset |",
             "|---|---:|---:|---:|---:|---:|---|---|---|---:|"]
    for case, r in rows.items():
        n, pk, auto = r.get("nastran95"), r["pk"], r["auto"]
        ncpu = "–" if n is None else f"{n['cpu_s']:.2f} ({n['aics']})"
        ratio = (lambda x: "–" if n is None or n["cpu_s"] <= 0 else f"{x / n['cpu_s']:.2f}")
        ncrit = "–" if n is None else _crit(n["critical"])
        dv = "–" if n is None else "; ".join(_same_events(n, pk)) or "–"
        lines.append(f"| {CASES[case][0]} | {ncpu} | {_s(pk['cpu_s'])} ({_s(pk['process_cpu_s'])}) "
                     f"| {_s(auto['cpu_s'])} ({_s(auto['process_cpu_s'])}) | {ratio(pk['cpu_s'])} "
                     f"| {ratio(auto['cpu_s'])} | {ncrit} | {_crit(pk['critical'])} "
                     f"| {_crit(auto['critical'])} | {dv} |")
    if have_nastran:
        ref = [f"{CASES[c][0]}: {r['nastran95']['refine_cpu_s']:.2f} s"
               for c, r in rows.items() if r.get("nastran95") and r["nastran95"]["refine_cpu_s"]]
        lines += ["", "NASTRAN-95's onsets (a sign change of g between its speeds, linear in V) "
                      "are each refined by another PK run at speeds "
                      f"{REFINE_STEP} m/s apart within ±{REFINE_HALF} m/s (its AICs computed "
                      "again): CPU of those runs, not in the table: " + "; ".join(ref) + ".  "
                      "Context, not the goal's column: propwhirl's crossings are converged to "
                      "0.01 m/s inside its own CPU; against NASTRAN-95's run and that "
                      "refinement together, p-k / default: " + "; ".join(
                          f"{CASES[c][0]}: {r['pk']['cpu_s'] / tot:.2f} / "
                          f"{r['auto']['cpu_s'] / tot:.2f}"
                          for c, r in rows.items() if r.get("nastran95")
                          and (tot := r["nastran95"]["cpu_s"] + r["nastran95"]["refine_cpu_s"])
                          > 0) + ".  "
                      "The default's differences from NASTRAN-95, each onset: " + "; ".join(
                          f"{CASES[c][0]}: " + ("; ".join(_same_events(r["nastran95"], r["auto"]))
                                                or "–")
                          for c, r in rows.items() if r.get("nastran95")) + "."]
    return "\n".join(lines)


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--case", choices=sorted(CASES), help=argparse.SUPPRESS)
    p.add_argument("--method", default="auto", choices=["auto", "pk"], help=argparse.SUPPRESS)
    p.add_argument("--quick", action="store_true", help="without the 16 x 28 Goland panels")
    p.add_argument("--only", help="comma-separated cases (default: all): " + ", ".join(CASES))
    p.add_argument("--no-propwhirl", action="store_true", help="the NASTRAN-95 side alone")
    p.add_argument("--json", type=Path, help="also keep the rows in this JSON file")
    p.add_argument("--markdown", type=Path, help="write the table into this file")
    args = p.parse_args()
    if args.case:
        from threadpoolctl import threadpool_limits
        with threadpool_limits(1):
            print(json.dumps(run_propwhirl(args.case, args.method)))
        return
    cases = [c for c in CASES if not (args.quick and c == "goland16x28")
             and (args.only is None or c in args.only.split(","))]
    have = nastran_version() is not None
    if not have:
        print("nastran95 is not installed (it needs Python >= 3.12): the NASTRAN-95 column is "
              "left empty; make bench-nastran95 builds .venv-bench312 with it", file=sys.stderr)
    before = os.getloadavg()[0]
    rows: dict = {}
    for case in cases:
        rows[case] = {}
        if have:
            rows[case]["nastran95"] = run_nastran(case)
            print(json.dumps(rows[case]["nastran95"]), flush=True)
        if not args.no_propwhirl:
            for method in ("pk", "auto"):
                rows[case][method] = measure_propwhirl(case, method)
                print(json.dumps(rows[case][method]), flush=True)
    if args.json:
        args.json.write_text(json.dumps(rows, indent=1))
    if args.no_propwhirl:
        return
    text = table(rows, (before, os.getloadavg()[0]), have)
    print(text)
    if args.markdown:
        from markdown_section import replace_section
        replace_section(args.markdown, text, BEGIN, END, TITLE)


if __name__ == "__main__":
    main()
