"""Where a doublet-lattice analysis spends its time, and how much (issue 37, item 2).

Run from the repository root (needs the ``dlm`` extra, PanelAero; one BLAS thread; every case
in a fresh interpreter, first run, no ``PROPWHIRL_DLM_CACHE``)::

    .venv/bin/python benchmarks/dlm_speed.py --markdown docs/performance.md
    ... --quick                  # without the 16 x 28 Goland panels
    ... --case x57 --method auto # one case, its numbers as JSON on stdout

Each case: ``analyse(model)`` (the default, ``method="auto"``: the modal Roger state space
tracks, the p-k converges every crossing) and ``analyse(model, method="pk")``, with the CPU
time of the process and of any worker processes it started (``resource.getrusage``: self +
children), its peak resident memory, the doublet-lattice AICs computed (the analysis's
:class:`~propwhirl.model.aerodynamics.dlm.DlmTables`) and the critical speed.  The NASTRAN-95
column is filled only where the optional ``nastran95`` package is importable (it is not on the
machine this table was last written on: "not installed").

Cases: ``examples/x57_like.toml`` with ``aero = "dlm"`` on 8 chordwise panels (8 x 37 on the
half-wing), Mach V/a at each speed, its own speeds 1-250 m/s; the Goland wing (10 beam
elements, rho = 1.02 kg/m^3, Mach 0, 120-200 m/s: ``benchmarks/dlm_goland.py``) on 4 x 7,
8 x 14 and 16 x 28 panels.
"""
from __future__ import annotations

import argparse
import dataclasses
import json
import os
import resource
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "benchmarks"))

BEGIN = "<!-- dlm_speed: begin (benchmarks/dlm_speed.py writes this block) -->"
END = "<!-- dlm_speed: end -->"
TITLE = "## Doublet-lattice analyses: where the time goes (issue 37, item 2)"
CASES = {"x57": "x57_like, DLM 8 x 37, Mach V/a, 1-250 m/s",
         "goland4x7": "Goland DLM 4 x 7, Mach 0", "goland8x14": "Goland DLM 8 x 14, Mach 0",
         "goland16x28": "Goland DLM 16 x 28, Mach 0"}
GOLAND_SPEEDS = np.arange(120.0, 201.0, 10.0)


def build(case: str):
    """(model, speeds or None) of a case."""
    if case == "x57":
        from propwhirl.io.model_files import load_model
        m = load_model(ROOT / "examples" / "x57_like.toml")
        return m.with_(wing=dataclasses.replace(m.wing, aero="dlm", dlm_chordwise_panels=8)), None
    from dlm_goland import RHO_SHARPY, goland_wing
    from propwhirl.model import FlightCondition, PropellerWing
    nc, ns = {"goland4x7": (4, 7), "goland8x14": (8, 14), "goland16x28": (16, 28)}[case]
    wing = dataclasses.replace(goland_wing("dlm", (nc, ns)), dlm_mach=0.0)
    return PropellerWing(wing, FlightCondition(RHO_SHARPY)), GOLAND_SPEEDS


def run_case(case: str, method: str) -> dict:
    """The numbers of one case in this (fresh) process."""
    from propwhirl.analysis import analyse
    from propwhirl.model.aerodynamics.dlm import DlmTables
    model, speeds = build(case)
    tables = DlmTables()
    t0 = time.process_time()
    a = analyse(model, speeds, method=method, dlm_tables=tables)
    cpu = time.process_time() - t0
    child = resource.getrusage(resource.RUSAGE_CHILDREN)
    own = resource.getrusage(resource.RUSAGE_SELF)
    rss = max(own.ru_maxrss, child.ru_maxrss) / 1024
    c = a.critical
    return {"case": case, "method": method, "cpu_s": cpu,
            "children_cpu_s": child.ru_utime + child.ru_stime, "peak_rss_mb": rss,
            "process_cpu_s": own.ru_utime + own.ru_stime + child.ru_utime + child.ru_stime,
            "aics": tables.aero(model.wing).evaluations,
            "critical": None if c is None else [c.kind, c.label, c.V, c.frequency_hz]}


def nastran_available() -> bool:
    try:
        import nastran95  # noqa: F401
    except ImportError:
        return False
    return True


def measure(case: str, method: str) -> dict:
    """:func:`run_case` in a fresh interpreter (first run: empty tables, nothing imported)."""
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1", MKL_NUM_THREADS="1")
    env.pop("PROPWHIRL_DLM_CACHE", None)
    out = subprocess.run([sys.executable, __file__, "--case", case, "--method", method],
                         capture_output=True, text=True, check=True, env=env, cwd=ROOT)
    return json.loads(out.stdout.strip().splitlines()[-1])


def table(rows: list[dict], load_before: float | None = None) -> str:
    load = os.getloadavg()[0]
    loads = f"{load:.1f}" if load_before is None else f"{load_before:.1f} before, {load:.1f} after"
    lines = [f"Measured by `benchmarks/dlm_speed.py` (each case a fresh interpreter, first run, "
             f"no AIC cache, one BLAS thread; {os.cpu_count()} cores, load average "
             f"{loads}). CPU: the analysis's process plus any worker processes "
             "it started. NASTRAN-95: " + ("measured side by side." if nastran_available()
                                           else "not installed here (the optional "
                                                "`nastran95` package), column empty."),
             "", "| case | method | CPU of `analyse` [s] | whole process CPU [s] | peak RSS [MB] "
                 "| AICs | critical [m/s] | NASTRAN-95 PK [s] |",
             "|---|---|---:|---:|---:|---:|---|---:|"]
    for r in rows:
        c = r["critical"]
        crit = "none" if c is None else f"{c[2]:.2f} ({c[0]}, {c[3]:.3f} Hz)"
        lines.append(f"| {CASES[r['case']]} | {r['method']} | "
                     f"{r['cpu_s'] + r['children_cpu_s']:.1f} | {r['process_cpu_s']:.1f} | "
                     f"{r['peak_rss_mb']:.0f} | "
                     f"{r['aics']} | {crit} | – |")
    return "\n".join(lines)


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--case", choices=sorted(CASES))
    p.add_argument("--method", default="auto", choices=["auto", "pk"])
    p.add_argument("--quick", action="store_true", help="without the 16 x 28 Goland panels")
    p.add_argument("--only", help="comma-separated cases (default: all)")
    p.add_argument("--json", type=Path, help="also keep the rows in this JSON file")
    p.add_argument("--markdown", type=Path, help="write the table into this file")
    args = p.parse_args()
    if args.case:
        print(json.dumps(run_case(args.case, args.method)))
        return
    cases = [c for c in CASES if not (args.quick and c == "goland16x28")
             and (args.only is None or c in args.only.split(","))]
    rows, before = [], os.getloadavg()[0]
    for case in cases:
        for method in ("auto", "pk"):
            rows.append(measure(case, method))
            print(json.dumps(rows[-1]), flush=True)
    if args.json:
        args.json.write_text(json.dumps(rows, indent=1))
    text = table(rows, before)
    print(text)
    if args.markdown:
        from markdown_section import replace_section
        replace_section(args.markdown, text, BEGIN, END, TITLE)


if __name__ == "__main__":
    main()
