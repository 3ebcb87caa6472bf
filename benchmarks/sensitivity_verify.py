"""`propwhirl sensitivity wingtip --verify --top 5` on 1 and 2 processes (issue 26, item 3):
the whole command (the analysis, the sensitivities and the 10 verification analyses in one
batch), each run a fresh process, alternated over ``--rounds`` rounds; wall time and CPU time of
the command and its worker processes (``resource.getrusage(RUSAGE_CHILDREN)``), BLAS at one
thread; the load average before and after.  And the verification batch alone
(``verify_sensitivities(..., processes=P)`` in this process, the model, analysis and
sensitivities made once): wall, and CPU of this process plus its workers.

    .venv/bin/python benchmarks/sensitivity_verify.py --rounds 5
"""
from __future__ import annotations

import argparse
import os
import resource
import statistics
import subprocess
import sys
import time


def run(processes: int) -> tuple[float, float]:
    """(wall [s], CPU [s]) of one command."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t = time.perf_counter()
    subprocess.run([sys.executable, "-m", "propwhirl", "sensitivity", "wingtip", "--verify",
                    "--top", "5", "--quiet", "--processes", str(processes)], check=True,
                   stdout=subprocess.DEVNULL, env={**os.environ, "OPENBLAS_NUM_THREADS": "1"})
    wall = time.perf_counter() - t
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu


def batch(processes: int, model, analysis, cs) -> tuple[float, float]:
    """(wall [s], CPU [s]) of the verification batch alone (this process and its workers)."""
    from propwhirl.studies.sensitivity_check import verify_sensitivities

    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    c0, t = time.process_time(), time.perf_counter()
    r = verify_sensitivities(model, analysis, cs, top=5, processes=processes)
    wall = time.perf_counter() - t
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = time.process_time() - c0 + (after.ru_utime - before.ru_utime) + (
        after.ru_stime - before.ru_stime)
    assert r.passed and r.analyses == 10
    return wall, cpu


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rounds", type=int, default=5)
    args = ap.parse_args()
    os.environ["OPENBLAS_NUM_THREADS"] = "1"
    from threadpoolctl import threadpool_limits

    threadpool_limits(limits=1)
    from propwhirl.analysis import analyse, critical_sensitivities
    from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing

    model = wingtip_propeller_wing()
    analysis = analyse(model)
    cs = critical_sensitivities(model, analysis)
    load0 = os.getloadavg()
    times: dict[int, list[tuple[float, float]]] = {1: [], 2: []}
    alone: dict[int, list[tuple[float, float]]] = {1: [], 2: []}
    for _ in range(args.rounds):
        for p in (1, 2):
            times[p].append(run(p))
            alone[p].append(batch(p, model, analysis, cs))
    load1 = os.getloadavg()
    print(f"machine: {os.cpu_count()} cores; load average (1, 5, 15 min) before "
          f"{load0[0]:.2f} {load0[1]:.2f} {load0[2]:.2f}, after {load1[0]:.2f} {load1[1]:.2f} "
          f"{load1[2]:.2f}; {args.rounds} rounds, alternated")
    print("| run | processes | median wall [s] | best wall [s] | median CPU [s] | best CPU [s] |")
    print("|---|---:|---:|---:|---:|---:|")
    for what, table in (("the command", times), ("the batch of 10 analyses", alone)):
        for p, ts in table.items():
            w, c = [x[0] for x in ts], [x[1] for x in ts]
            print(f"| {what} | {p} | {statistics.median(w):.2f} | {min(w):.2f} | "
                  f"{statistics.median(c):.2f} | {min(c):.2f} |")


if __name__ == "__main__":
    main()
