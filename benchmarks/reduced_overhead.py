"""The overhead of the reduced wingtip analysis, in eigen-solutions of its own matrix (issue 26,
item 2): CPU time of one ``analyse(model, method="reduced")`` of ``examples/wingtip.toml``
divided by the CPU time of one ``numpy.linalg.eig`` (with vectors) of its reduced state matrix
(the same size, 50 states), where the time goes (exclusive CPU time per part) and the work
(eigen-solutions, nodes, links, cluster trials).

    python benchmarks/reduced_overhead.py [--base OLD/.venv/bin/python] [--rounds 5] \
        [--markdown docs/performance.md]

Each case runs in a fresh process of each revision's interpreter, alternately (the base first
in each round), in two environments: ``one thread`` (``OPENBLAS_NUM_THREADS=1``, as the test
suite and the other benchmarks) and ``default`` (no BLAS variable: what a user gets).  The
eig reference is always timed at one BLAS thread.  Best of the rounds; the parts are those of
the best round of this revision (wrappers on the parts' functions, each function's time
exclusive of the wrapped functions it calls; a wrapper costs ≈ 1 µs).
"""
from __future__ import annotations

import argparse
import datetime
import json
import os
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from markdown_section import replace_section  # noqa: E402

MARK_BEGIN = "<!-- reduced_overhead: begin -->"
MARK_END = "<!-- reduced_overhead: end -->"
TITLE = "## The reduced analysis's overhead (issue 26, item 2)"

CASE = r'''
import functools, importlib, json, sys, time
import numpy as np
from threadpoolctl import threadpool_limits
import propwhirl
from propwhirl.io import load_model
from propwhirl.model.reduction import reduce

PARTS = [  # (module, function, part): the part of each wrapped function's exclusive time
    ("propwhirl.analysis.stability", "analyse", "analysis glue: events, warnings, summary"),
    ("propwhirl.model.reduction", "reduce", "reduced model: the basis"),
    ("propwhirl.model.reduction", "ReducedModel.state_matrix", "reduced model: A(V)"),
    ("propwhirl.model.reduction", "ReducedModel.pencil", "full-order pencil (corrections)"),
    ("propwhirl.engine.tracker", "_sweep", "engine: tracking core, ordering"),
    ("propwhirl.engine.tracker", "_assemble", "engine: tracking core, ordering"),
    ("propwhirl.engine.nodes", "evaluate_nodes", "engine: nodes (eig, dλ/dV)"),
    ("propwhirl.engine.tracker", "link_nodes", "engine: linking"),
    ("propwhirl.engine.linking", "_cluster_continuations", "engine: cluster continuations"),
    ("propwhirl.engine.tracker", "branch_point_speeds", "engine: branch-point bracketing"),
    ("propwhirl.engine.tracker", "refine_crossings", "engine: crossings"),
    ("propwhirl.analysis.reduced", "correct_crossing", "full-order corrections"),
    ("propwhirl.analysis.stability", "named_modes", "naming (in-vacuo modes, Ω-follow, MAC)"),
    ("propwhirl.analysis.stability", "mode_content", "content (kinetic-energy shares)"),
    ("propwhirl.analysis.stability", "frequency_zero_points", "frequency-zero events"),
    ("propwhirl.analysis.stability", "branch_point_shape", "participation, event shapes"),
    ("propwhirl.analysis.stability", "with_participation", "participation, event shapes"),
]
acc, stack, counts = {}, [], {}

def wrap(mod, name, part):
    obj = importlib.import_module(mod)
    attr = name
    if "." in name:
        cls, attr = name.split(".")
        obj = getattr(obj, cls)
    f = getattr(obj, attr, None)
    if f is None:
        return
    @functools.wraps(f)
    def timed(*a, **k):
        t = time.process_time()
        if stack:
            acc[stack[-1][0]] = acc.get(stack[-1][0], 0.0) + t - stack[-1][1]
        stack.append([part, t])
        counts[name] = counts.get(name, 0) + 1
        try:
            return f(*a, **k)
        finally:
            t1 = time.process_time()
            p, t0 = stack.pop()
            acc[p] = acc.get(p, 0.0) + t1 - t0
            if stack:
                stack[-1][1] = t1
    setattr(obj, attr, timed)
    for m in list(sys.modules.values()):      # and where it was imported by name
        if getattr(m, "__name__", "").startswith("propwhirl") and getattr(m, attr, None) is f:
            setattr(m, attr, timed)

def cpu(f, n=1):
    t = time.process_time()
    for _ in range(n):
        f()
    return (time.process_time() - t) / n

model = load_model("examples/wingtip.toml")
R = reduce(model, model.flight.speeds())
A = R.state_matrix(np.array([150.0]))[0]
with threadpool_limits(limits=1):
    eig = min(cpu(lambda: np.linalg.eig(A), 100) for _ in range(5))
a = propwhirl.analyse(model, method="reduced")
REPEATS = 3
t = min(cpu(lambda: propwhirl.analyse(model, method="reduced")) for _ in range(REPEATS))
import propwhirl.engine.clusters as clusters
trials = [0]
try_cluster = clusters._try_cluster
def counted(*a, **k):
    trials[0] += 1
    return try_cluster(*a, **k)
clusters._try_cluster = counted
for mod, name, part in PARTS:
    wrap(mod, name, part)
for _ in range(REPEATS):
    propwhirl.analyse(model, method="reduced")
print(json.dumps({
    "eig": eig, "cpu": t, "states": int(A.shape[0]),
    "nodes": a.sweep.stats["nodes"], "eig_calls": a.sweep.stats["eig"],
    "links": counts.get("link_nodes", 0) // REPEATS, "cluster_trials": trials[0] // REPEATS,
    "parts": {p: s / REPEATS for p, s in acc.items()},
    "events": [[e.kind, e.event, e.label, float(e.V)] for e in a.events]}))
'''

ENVS = ("one thread", "default")


def run_case(python: str, cwd: Path, env_name: str) -> dict:
    env = {k: v for k, v in os.environ.items()
           if k not in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")}
    if env_name == "one thread":
        env.update(OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1")
    res = subprocess.run([python, "-c", CASE], cwd=cwd, env=env, capture_output=True, text=True,
                         check=True)
    return json.loads(res.stdout.strip().splitlines()[-1])


def _same(a: list, b: list) -> str:
    if [e[:3] for e in a] != [e[:3] for e in b]:
        return "different events"
    return f"same; largest ΔV {max((abs(x[3] - y[3]) for x, y in zip(a, b)), default=0.0):.1e} m/s"


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--base", help="another revision's python (its checkout: two folders up)")
    p.add_argument("--base-name", default="base")
    p.add_argument("--rounds", type=int, default=5)
    p.add_argument("--markdown", help="write the tables between this script's markers")
    args = p.parse_args(argv)
    here = Path(__file__).resolve().parent.parent
    revs = [("HEAD", sys.executable, here)]
    if args.base:
        revs.insert(0, (args.base_name, args.base, Path(args.base).absolute().parents[2]))
    best: dict[tuple[str, str], dict] = {}
    for r in range(args.rounds):
        for env_name in ENVS:
            for name, python, cwd in revs:
                out = run_case(python, cwd, env_name)
                key = (name, env_name)
                old = best.get(key)
                if old is None or out["cpu"] < old["cpu"]:
                    best[key] = out
                for k in ("eig",):          # the reference: its own best over the rounds
                    best[key][k] = min(best[key][k], out[k])
                print(f"round {r + 1} {name:6s} {env_name:10s} {out['cpu'] * 1e3:6.1f} ms, "
                      f"eig {out['eig'] * 1e3:.3f} ms", file=sys.stderr)
    load = os.getloadavg()
    lines = [f"Measured {datetime.date.today()} with `benchmarks/reduced_overhead.py` on "
             f"{os.cpu_count()} cores, load average {load[0]:.1f} / {load[1]:.1f} / "
             f"{load[2]:.1f} (1 / 5 / 15 min) at the end; CPU time, best of {args.rounds} "
             "alternating rounds of 3 analyses each (fresh processes); the eig reference at "
             "one BLAS thread.", "",
             "| revision | BLAS | analysis [ms] | eig [ms] | eigen-solution equivalents | "
             "nodes | eig calls | links | cluster trials | events |",
             "|---|---|---:|---:|---:|---:|---:|---:|---:|---|"]
    for env_name in ENVS:
        for name, _, _ in revs:
            o = best[(name, env_name)]
            same = _same(best[(revs[0][0], env_name)]["events"], o["events"]) \
                if name != revs[0][0] else ", ".join(f"{e[1]} {e[3]:.2f}" for e in o["events"])
            lines.append(f"| {name} | {env_name} | {o['cpu'] * 1e3:.1f} | {o['eig'] * 1e3:.3f} "
                         f"| {o['cpu'] / o['eig']:.0f} | {o['nodes']} | {o['eig_calls']} | "
                         f"{o['links']} | {o['cluster_trials']} | {same} |")
    for name, _, _ in revs:
        o = best[(name, "one thread")]
        total = sum(o["parts"].values())
        lines += ["", f"Where the time goes ({name}, one BLAS thread; exclusive CPU per part, "
                  f"instrumented: {total * 1e3:.1f} ms in all):", "",
                  "| part | CPU [ms] | share | eigen-solution equivalents |", "|---|---:|---:|---:|"]
        for part, s in sorted(o["parts"].items(), key=lambda x: -x[1]):
            lines.append(f"| {part} | {s * 1e3:.1f} | {100 * s / total:.0f} % | "
                         f"{s / o['eig']:.0f} |")
    table = "\n".join(lines)
    print(table)
    if args.markdown:
        replace_section(Path(args.markdown), table, MARK_BEGIN, MARK_END, TITLE)
    return 0


if __name__ == "__main__":
    sys.exit(main())
