"""Where a doublet-lattice analysis spends its time, and how much (issue 37, item 2).

Run from the repository root (needs the ``dlm`` extra, PanelAero; one BLAS thread; every case
in a fresh interpreter, first run, no ``PROPWHIRL_DLM_CACHE``)::

    .venv/bin/python benchmarks/dlm_speed.py --markdown docs/performance.md
    ... --quick                  # without the 16 x 28 Goland panels
    ... --case x57 --method auto # one case, its numbers as JSON on stdout
    # before/after, alternately in one run (the before: another revision's package)
    git archive REV src | tar -x -C /tmp/old
    ... --before /tmp/old/src --skip x57:pk --markdown docs/performance.md

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
8 x 14, 16 x 16 and 16 x 28 panels; the wingtip model of section 10.1 (25 elements, 8 x 29
panels) Mach-matched over 120-280 m/s, and its wing alone (no propeller, NASTRAN-95's case)
at a fixed Mach 0 and 0.5 over 100-350 m/s.  Each row also keeps every onset (kind, mode,
speed, frequency), so that a before/after table shows whether any answer moved.
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
         "goland16x16": "Goland DLM 16 x 16, Mach 0",
         "goland16x28": "Goland DLM 16 x 28, Mach 0",
         "wingtip": "wingtip model (25 elements), DLM 8 x 29, Mach V/a, 120-280 m/s",
         "wingtip_alone0": "wingtip wing alone, DLM 8 x 29, Mach 0, 100-350 m/s",
         "wingtip_alone05": "wingtip wing alone, DLM 8 x 29, Mach 0.5, 100-350 m/s"}
WINGTIP_SPEEDS = np.arange(120.0, 281.0, 10.0)
ALONE_SPEEDS = np.arange(100.0, 351.0, 10.0)
GOLAND_SPEEDS = np.arange(120.0, 201.0, 10.0)


def build(case: str):
    """(model, speeds or None) of a case."""
    if case == "x57":
        from propwhirl.io.model_files import load_model
        m = load_model(ROOT / "examples" / "x57_like.toml")
        return m.with_(wing=dataclasses.replace(m.wing, aero="dlm", dlm_chordwise_panels=8)), None
    if case.startswith("wingtip"):
        from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
        m = wingtip_propeller_wing()
        if case == "wingtip":
            return m.with_(wing=dataclasses.replace(m.wing, aero="dlm")), WINGTIP_SPEEDS
        mach = {"wingtip_alone0": 0.0, "wingtip_alone05": 0.5}[case]
        return (m.with_(wing=dataclasses.replace(m.wing, aero="dlm", dlm_mach=mach),
                        propellers=()), ALONE_SPEEDS)
    from dlm_goland import RHO_SHARPY, goland_wing
    from propwhirl.model import FlightCondition, PropellerWing
    nc, ns = {"goland4x7": (4, 7), "goland8x14": (8, 14), "goland16x16": (16, 16),
              "goland16x28": (16, 28)}[case]
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
            "onsets": [[e.kind, e.label, e.V, e.frequency_hz] for e in a.events
                       if e.event in ("onset", "unstable-at-start")],
            "critical": None if c is None else [c.kind, c.label, c.V, c.frequency_hz]}


def nastran_available() -> bool:
    try:
        import nastran95  # noqa: F401
    except ImportError:
        return False
    return True


def measure(case: str, method: str, src: Path | None = None) -> dict:
    """:func:`run_case` in a fresh interpreter (first run: empty tables, nothing imported);
    with ``src`` the package from that source tree (``PYTHONPATH``: e.g. a revision's ``src``
    extracted with ``git archive``), the side-by-side "before"."""
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1", MKL_NUM_THREADS="1")
    env.pop("PROPWHIRL_DLM_CACHE", None)
    env.pop("PYTHONPATH", None)
    if src is not None:
        env["PYTHONPATH"] = str(Path(src).resolve())
    out = subprocess.run([sys.executable, __file__, "--case", case, "--method", method],
                         capture_output=True, text=True, check=True, env=env, cwd=ROOT)
    return json.loads(out.stdout.strip().splitlines()[-1])


def side_by_side(pairs: list[tuple[dict, dict]], label: str, load: tuple[float, float]) -> str:
    """The before/after table: CPU (process + workers) and peak RSS of each case and method,
    measured alternately in one run, with every onset's speed before and after."""
    lines = [f"Measured by `benchmarks/dlm_speed.py --before` (each case a fresh interpreter, "
             f"first run, no AIC cache, one BLAS thread; before and after alternately in one run; "
             f"{os.cpu_count()} cores shared with other sessions, load average {load[0]:.1f} "
             f"before, {load[1]:.1f} after). Before: {label}. CPU: the whole process (start-up "
             "included) plus its AIC worker processes (`resource.getrusage`, self + children); "
             "`analyse`: `time.process_time()` around the call plus the workers' CPU; peak "
             "RSS: the largest of the process and its workers.", "",
             "| case | method | CPU before [s] | CPU after [s] | ratio | `analyse` before [s] "
             "| `analyse` after [s] | peak RSS before [MB] "
             "| after [MB] | AICs before / after | critical before → after [m/s] |",
             "|---|---|---:|---:|---:|---:|---:|---:|---:|---|---|"]
    for b, a in pairs:
        def crit(r):
            c = r["critical"]
            return "none" if c is None else f"{c[2]:.4f}"
        lines.append(f"| {CASES[a['case']]} | {a['method']} | {b['process_cpu_s']:.1f} | "
                     f"{a['process_cpu_s']:.1f} | {b['process_cpu_s'] / a['process_cpu_s']:.1f}x | "
                     f"{b['cpu_s'] + b['children_cpu_s']:.1f} | "
                     f"{a['cpu_s'] + a['children_cpu_s']:.1f} | "
                     f"{b['peak_rss_mb']:.0f} | {a['peak_rss_mb']:.0f} | "
                     f"{b['aics']} / {a['aics']} | "
                     f"{crit(b)} → {crit(a)} |")
    moved = [abs(x[2] - y[2]) for b, a in pairs for x, y in zip(b.get("onsets", []),
                                                              a.get("onsets", []))]
    same = all(len(b.get("onsets", [])) == len(a.get("onsets", [])) and
               all(x[:2] == y[:2] for x, y in zip(b["onsets"], a["onsets"])) for b, a in pairs)
    if moved:
        lines += ["", f"Every onset of every row ({len(moved)}): the same kind and mode "
                      f"{'in every row' if same else '— NOT in every row'}; largest change of "
                      f"speed {max(moved):.2g} m/s."]
    return "\n".join(lines)


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
    p.add_argument("--before", type=Path, metavar="SRC",
                   help="also measure every case with the package of this source tree (e.g. "
                        "git archive REV src | tar -x -C /tmp/old: /tmp/old/src), alternately, "
                        "and write the before/after table")
    p.add_argument("--before-label", default="the source tree given with --before")
    p.add_argument("--methods", default="auto,pk", help="comma-separated (default auto,pk)")
    p.add_argument("--skip", default="", help="comma-separated case:method pairs not measured")
    p.add_argument("--from-json", type=Path, metavar="FILE",
                   help="write the before/after table of a --before run's --json FILE again "
                        "(no measurement; with --load BEFORE,AFTER as then measured)")
    p.add_argument("--load", default="nan,nan", help="with --from-json: the load averages")
    args = p.parse_args()
    if args.from_json is not None:
        pairs = [tuple(x) for x in json.loads(args.from_json.read_text())]
        lo, hi = (float(x) for x in args.load.split(","))
        text = side_by_side(pairs, args.before_label, (lo, hi))
        print(text)
        if args.markdown:
            from markdown_section import replace_section
            replace_section(args.markdown, text, BEGIN, END, TITLE)
        return
    if args.case:
        print(json.dumps(run_case(args.case, args.method)))
        return
    cases = [c for c in CASES if not (args.quick and c == "goland16x28")
             and (args.only is None or c in args.only.split(","))]
    rows, before = [], os.getloadavg()[0]
    pairs = []
    for case in cases:
        for method in args.methods.split(","):
            if f"{case}:{method}" in args.skip.split(","):
                continue
            if args.before is not None:
                old = measure(case, method, args.before)
                print(json.dumps(dict(old, before=True)), flush=True)
            rows.append(measure(case, method))
            print(json.dumps(rows[-1]), flush=True)
            if args.before is not None:
                pairs.append((old, rows[-1]))
    if args.json:
        args.json.write_text(json.dumps(pairs if pairs else rows, indent=1))
    text = (table(rows, before) if args.before is None else
            side_by_side(pairs, args.before_label, (before, os.getloadavg()[0])))
    print(text)
    if args.markdown:
        from markdown_section import replace_section
        replace_section(args.markdown, text, BEGIN, END, TITLE)


if __name__ == "__main__":
    main()
