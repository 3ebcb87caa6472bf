"""Expanding a campaign before its first analysis (issue 33, item 11): ``from_spec`` and
``run_campaign`` up to the first analysis, for 10,000 tasks, side by side with another checkout.

Run from the repository root::

    .venv/bin/python benchmarks/campaign_expansion.py                          # this checkout
    .venv/bin/python benchmarks/campaign_expansion.py --reference /tmp/main     # and another
    .venv/bin/python benchmarks/campaign_expansion.py --markdown docs/performance.md

``--reference DIR``: a checkout whose ``DIR/src`` is put first on ``PYTHONPATH`` (its
``propwhirl.generated`` must import from there).  The campaigns, on ``examples/wingtip.toml``
(25 elements, one propeller), V_D = 100 m/s EAS, CS 25:

* ``100 cases x 100 altitudes``: a list of 100 mount-stiffness cases, 100 ISA altitudes;
* ``product 100 x 100``: two groups of 100 (mount stiffness; a nacelle mass), one altitude;
* ``1000 cases x 10 altitudes``: a list of 1000 cases, 10 altitudes.

Each (campaign, checkout) runs in a process of its own, one BLAS thread, after a small
campaign has warmed the imports: ``from_spec`` timed (wall and CPU), then again under
tracemalloc (its peak), then ``run_campaign`` with a partial-results file (as ``propwhirl
certify`` runs it) up to its call of ``map_analyses`` (the work before the first analysis:
the estimate, the tasks, the fingerprint).  ``--rounds`` alternates the checkouts; the
fastest round of each is kept.  Nothing is analysed.
"""
from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
BEGIN = "<!-- campaign_expansion:begin -->"
END = "<!-- campaign_expansion:end -->"
TITLE = "## Expanding a campaign before its first analysis (issue 33, item 11)"
SHAPES = {"100 cases x 100 altitudes": (100, 100, False),
          "product 100 x 100 (1 altitude)": (100, 1, True),
          "1000 cases x 10 altitudes": (1000, 10, False)}

CHILD = r'''
import json, sys, tempfile, time, tracemalloc
from pathlib import Path
from propwhirl.io.campaign_files import loads
from propwhirl.studies import campaign as C, execution

n, na, product, examples = int(sys.argv[1]), int(sys.argv[2]), sys.argv[3] == "1", sys.argv[4]

def text(n, na, product):
    alts = ", ".join(f"{100.0 * i:.1f}" for i in range(na))
    head = ('format = "propwhirl-campaign"\nformat_version = 1\nmodel = "wingtip.toml"\n'
            f'combine = "{"product" if product else "list"}"\n[regulation]\nname = "cs25"\n'
            f'[envelope]\nairspeed = "EAS"\nV_D_m_per_s = 100.0\naltitudes_m = [{alts}]\n')
    if product:
        return head + "".join(f'[[cases]]\nname = "k{i}"\ngroup = "mount"\nmount_stiffness = '
                              f'{0.5 + i / n}\n' for i in range(n)) + "".join(
            f'[[cases]]\nname = "m{i}"\ngroup = "mass"\nadded_masses = [{{ mass_kg = '
            f'{1.0 + i}, x_m = -0.5 }}]\n' for i in range(n))
    return head + "".join(f'[[cases]]\nname = "c{i}"\nmount_stiffness = {0.5 + i / n}\n'
                          for i in range(n))

spec = lambda: loads(text(n, na, product), "bench.toml", examples)
C.from_spec(loads(text(2, 2, product), "warm.toml", examples))       # imports, caches
s = spec()
w, c = time.perf_counter(), time.process_time()
camp = C.from_spec(s)
wall, cpu = time.perf_counter() - w, time.process_time() - c
tracemalloc.start()
C.from_spec(spec())
peak = tracemalloc.get_traced_memory()[1]
tracemalloc.stop()

class Reached(Exception):
    pass

def stop(*a, **k):
    raise Reached
execution.map_analyses = stop
import os
os.environ.setdefault("PROPWHIRL_STUDY_TIME_LIMIT", "none")
with tempfile.TemporaryDirectory() as tmp:
    camp = C.from_spec(spec())
    w, c = time.perf_counter(), time.process_time()
    try:
        C.run_campaign(camp, checkpoint=execution.Checkpoint(Path(tmp) / "c.partial"))
    except Reached:
        pass
    pre_wall, pre_cpu = time.perf_counter() - w, time.process_time() - c
print(json.dumps({"tasks": len(camp.cases) * len(camp.points), "wall": wall, "cpu": cpu,
                  "peak": peak, "pre_wall": pre_wall, "pre_cpu": pre_cpu}))
'''


def run_child(shape: tuple, src: Path | None, timeout: float) -> dict | None:
    n, na, product = shape
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1", MKL_NUM_THREADS="1")
    if src is not None:
        env["PYTHONPATH"] = str(src / "src")
    try:
        out = subprocess.run([sys.executable, "-c", CHILD, str(n), str(na), str(int(product)),
                              str(ROOT / "examples")], env=env, capture_output=True, text=True,
                             timeout=timeout, cwd=ROOT)
    except subprocess.TimeoutExpired:
        return None
    try:
        return json.loads(out.stdout.strip().splitlines()[-1])
    except (IndexError, ValueError):
        print(out.stderr[-2000:], file=sys.stderr)
        return None


def run(reference: Path | None, rounds: int, timeout: float) -> dict:
    best: dict = {}
    codes = [("this", None)] + ([("reference", reference)] if reference else [])
    for r in range(rounds):
        for name, shape in SHAPES.items():
            for code, src in codes:
                res = run_child(shape, src, timeout)
                print(f"round {r + 1} {name:32s} {code:9s} {res}", flush=True)
                key = (name, code)
                if res is not None and (key not in best or res["cpu"] < best[key]["cpu"]):
                    best[key] = res
                best.setdefault(key, None)
    return best


def table(best: dict, reference: Path | None, rounds: int) -> str:
    load = " / ".join(f"{x:.1f}" for x in os.getloadavg())
    L = [f"Measured {time.strftime('%Y-%m-%d')} with `benchmarks/campaign_expansion.py"
         f" --rounds {rounds}` on {os.cpu_count()} cores (shared; load average {load} at the "
         "end), one BLAS thread, each campaign a process of its own, the fastest round (by CPU)"
         " of each; `from_spec`'s peak from tracemalloc; before the first analysis: "
         "`run_campaign` with a partial-results file up to `map_analyses`."
         + (f" Reference: the checkout `{reference}`." if reference else ""),
         "",
         "| campaign (tasks) | code | from_spec wall [s] | CPU [s] | peak [MB] | "
         "run_campaign before the first analysis, CPU [s] |",
         "|---|---|---:|---:|---:|---:|"]
    for (name, code), res in best.items():
        if res is None:
            L.append(f"| {name} | {code} | - | - | - | - |")
            continue
        L.append(f"| {name} ({res['tasks']:,}) | {code} | {res['wall']:.2f} | {res['cpu']:.2f} | "
                 f"{res['peak'] / 1e6:.1f} | {res['pre_cpu']:.2f} |")
    return "\n".join(L)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="benchmarks/campaign_expansion.py", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--reference", type=Path, help="another checkout to run side by side")
    ap.add_argument("--rounds", type=int, default=2, help="alternating rounds (default 2)")
    ap.add_argument("--timeout", type=float, default=900.0, help="seconds per campaign")
    ap.add_argument("--markdown", type=Path, help="write the table into this file")
    args = ap.parse_args(argv)
    best = run(args.reference, args.rounds, args.timeout)
    text = table(best, args.reference, args.rounds)
    print(text)
    if args.markdown:
        sys.path.insert(0, str(Path(__file__).resolve().parent))
        from markdown_section import replace_section

        replace_section(args.markdown, text, BEGIN, END, TITLE)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
