"""Two revisions of propwhirl side by side in one run: the same analyses timed alternately in
each revision's own interpreter (CPU time, one BLAS thread, best of the repeats), so a ratio
between them is measured under the same load.

    python benchmarks/revisions.py --base /path/to/old/checkout/.venv/bin/python \
        [--rounds 3] [--markdown docs/performance.md]

The other revision is the interpreter running this script.  Each round runs every case once in
the base, then once here (fresh processes: nothing is shared between the two).  The cases use
only public names that both revisions have: the wingtip model of chapter 10 analysed with
``method="reduced"`` and with the default, the thesis's fixed grid (ΔV = 1 m/s, 1–350 m/s,
``numpy.linalg.eig`` with vectors at every speed) on its state matrix, the design model
of 25 elements and 4 propellers, and ``examples/x57_like_folded.toml`` (both revisions must
have it) with the default.
"""
from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
from pathlib import Path

MARK_BEGIN = "<!-- revisions: begin -->"
MARK_END = "<!-- revisions: end -->"

CASE = r'''
import json, sys, time
import numpy as np
from threadpoolctl import threadpool_limits
from propwhirl.analysis import analyse
from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing

def cpu(f):
    t = time.process_time(); out = f(); return time.process_time() - t, out

case, REPEATS = sys.argv[1], 3
with threadpool_limits(limits=1):
    if case == "fixed-grid":
        m = wingtip_propeller_wing()
        fn = m.assembly().state_matrix if hasattr(m, "assembly") else m.state_matrix
        V = np.arange(1.0, 351.0, 1.0)
        def grid():
            for v in V:
                np.linalg.eig(fn(np.array([v]))[0])
        t, _ = cpu(grid)
        out = {}
    else:
        if case == "design-25-4":
            sys.path.insert(0, "benchmarks")
            from design_size import design
            build = lambda: design(25, 4)
            method = "auto"
        elif case == "x57-folded":                # six equal propellers stopped (issue 25)
            from propwhirl.io import load_model
            build = lambda: load_model("examples/x57_like_folded.toml")
            method = "auto"
        else:
            build, method = wingtip_propeller_wing, case.split("-")[1]
        runs = []
        for _ in range(REPEATS):                  # fresh models: nothing kept between runs
            m = build()
            runs.append(cpu(lambda: analyse(m, method=method)))
        t, a = min(runs, key=lambda r: r[0])
        out = {"events": [[e.kind, e.event, float(e.V)] for e in a.events]}
print(json.dumps({"cpu": t, **out}))
'''

CASES = ("wingtip-reduced", "wingtip-auto", "fixed-grid", "design-25-4", "x57-folded")


def run_case(python: str, cwd: Path, case: str) -> dict:
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1")
    res = subprocess.run([python, "-c", CASE, case], cwd=cwd, env=env, capture_output=True,
                         text=True, check=True)
    return json.loads(res.stdout.strip().splitlines()[-1])


def _same(a: list, b: list) -> str:
    """The events of both revisions: the same kinds in order, and the largest |ΔV| [m/s]."""
    if [e[:2] for e in a] != [e[:2] for e in b]:
        return "different events"
    return f"same; largest ΔV {max((abs(x[2] - y[2]) for x, y in zip(a, b)), default=0.0):.1e} m/s"


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--base", required=True, help="the base revision's python (its checkout: "
                   "two folders up, or --base-dir)")
    p.add_argument("--base-dir", help="the base checkout (default: the python's ../..)")
    p.add_argument("--base-name", default="base")
    p.add_argument("--rounds", type=int, default=3)
    p.add_argument("--markdown", help="write the table between the revisions markers of this file")
    args = p.parse_args(argv)
    here = Path(__file__).resolve().parent.parent
    base_dir = Path(args.base_dir) if args.base_dir else Path(args.base).absolute().parents[2]
    best: dict[tuple[str, str], float] = {}
    events: dict[tuple[str, str], list] = {}
    for r in range(args.rounds):
        for case in CASES:
            for name, python, cwd in ((args.base_name, args.base, base_dir), ("HEAD", sys.executable, here)):
                out = run_case(python, cwd, case)
                key = (name, case)
                best[key] = min(best.get(key, float("inf")), out["cpu"])
                events[key] = out.get("events")
                print(f"round {r + 1} {name:10s} {case:16s} {out['cpu']:.3f} s", file=sys.stderr)
    load = os.getloadavg()
    lines = [f"Measured {__import__('datetime').date.today()} on {os.cpu_count()} cores, load "
             f"average {load[0]:.1f} / {load[1]:.1f} / {load[2]:.1f} (1 / 5 / 15 min) at the end; "
             f"CPU time, one BLAS thread, best of {args.rounds} alternating rounds of 3 fresh models each (the fixed grid: one sweep per round).", "",
             f"| case | {args.base_name} CPU [s] | HEAD CPU [s] | HEAD / {args.base_name} | "
             "fixed grid / case (HEAD) | events |", "|---|---|---|---|---|---|"]
    for case in CASES:
        b, h = best[(args.base_name, case)], best[("HEAD", case)]
        grid = best[("HEAD", "fixed-grid")] / h if case != "fixed-grid" else 1.0
        same = "" if case == "fixed-grid" else _same(events[(args.base_name, case)], events[("HEAD", case)])
        lines.append(f"| {case} | {b:.3f} | {h:.3f} | {h / b:.2f} | {grid:.1f}× | {same} |")
    table = "\n".join(lines)
    print(table)
    if args.markdown:
        path = Path(args.markdown)
        text = path.read_text()
        block = f"{MARK_BEGIN}\n{table}\n{MARK_END}"
        if MARK_BEGIN in text:
            pre, rest = text.split(MARK_BEGIN, 1)
            text = pre + block + rest.split(MARK_END, 1)[1]
        else:
            text = text.rstrip("\n") + "\n\n## Two revisions side by side\n\n" \
                   "`python benchmarks/revisions.py --base OLD/.venv/bin/python --markdown " \
                   "docs/performance.md`: the same analyses in each revision's interpreter, " \
                   "alternately.\n\n" + block + "\n"
        path.write_text(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
