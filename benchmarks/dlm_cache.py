"""The cost of the AIC cache's integrity checks (issue 33, item 4): the checksum beside each
entry and the spot check (the first entry read of a geometry computed again).

Run from the repository root (needs the ``dlm`` extra; one BLAS thread)::

    .venv/bin/python benchmarks/dlm_cache.py                 # 4 x 12 and 8 x 29 panels
    .venv/bin/python benchmarks/dlm_cache.py --quick         # 4 x 12 only
    PYTHONPATH=OLD/src .venv/bin/python benchmarks/dlm_cache.py --quick   # a revision before
    ... --rerun DIR --panels 8x29      # only reruns on the cache DIR (filled by the first)

``--rerun`` times reruns of the analysis on a cache directory kept between runs (filled by
the first call): alternate it between two revisions' interpreters (``PYTHONPATH``) to compare
them side by side on the same files (an older revision reads the same ``.npy`` files and
ignores the checksums).

For the thesis's wingtip model (§10.1) on 6 elements with doublet-lattice panels (4 x 12, and
the default 8 x 29), CPU seconds of: one AIC computed (PanelAero, Mach 0.5, k = 0.3); one
entry read back (``dlm_cache.load``: the ``.npy`` and, where the revision has it, the checksum
verified); the checksum alone; one entry written; then ``analyse(model)`` over 120–240 m/s
every 20 (the Roger state space: its AIC tables at every Mach node spanned) the first time
(every AIC computed), the second time (a new session of the same panels: the entries read,
one AIC computed again by the spot check) and the second time with the spot check skipped
(its count started at one: what the rerun costs without it).  Each timing is the median of
``--rounds`` runs (the analyses: one first run, then ``--rounds`` reruns).
"""
from __future__ import annotations

import argparse
import dataclasses
import os
import statistics
import tempfile
import time

import numpy as np
from threadpoolctl import threadpool_limits

from propwhirl.analysis import analyse
from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
from propwhirl.model.aerodynamics import dlm, dlm_cache

SPEEDS = np.arange(120.0, 241.0, 20.0)


def model(nc: int, ns: int):
    m = wingtip_propeller_wing()
    return m.with_(wing=dataclasses.replace(m.wing, n_elements=6, aero="dlm",
                                            dlm_chordwise_panels=nc, dlm_spanwise_panels=ns))


def cpu(f, rounds: int) -> float:
    out = []
    for _ in range(rounds):
        t = time.process_time()
        f()
        out.append(time.process_time() - t)
    return statistics.median(out)


def analysis(m, *, spot_check: bool = True) -> tuple[float, int, int]:
    """CPU [s] of analyse(m) in a new session of its panels, its AICs computed and read."""
    tables = dlm.DlmTables()                 # a new session's tables
    aero = tables.aero(m.wing)
    if not spot_check:
        aero.cache_hits = 1                  # the first entry read then counts as trusted
    t = time.process_time()
    analyse(m, speeds=SPEEDS, dlm_tables=tables)
    return time.process_time() - t, aero.evaluations, aero.cache_hits - (not spot_check)


def run(nc: int, ns: int, rounds: int) -> list[str]:
    m = model(nc, ns)
    with tempfile.TemporaryDirectory(prefix="aic-bench-") as tmp:
        os.environ[dlm_cache.CACHE_ENV] = tmp
        a = dlm.DlmAerodynamics(m.wing)
        kbar = 0.3 / a.b_ref
        t_aic = cpu(lambda: _compute(a, 0.5, 0.3), rounds)
        Q = _compute(a, 0.5, 0.3)
        dlm_cache.store(a.cache, a._geometry, 0.5, kbar, Q)
        t_store = cpu(lambda: dlm_cache.store(a.cache, a._geometry, 0.5, kbar, Q), rounds)
        t_load = cpu(lambda: dlm_cache.load(a.cache, a._geometry, 0.5, kbar, a.mesh.n),
                     5 * rounds)
        path = dlm_cache._path(a.cache, a._geometry, 0.5, kbar)
        has_sum = hasattr(dlm_cache, "checksum")
        t_sum = cpu(lambda: dlm_cache.checksum(path, Q), 5 * rounds) if has_sum else float("nan")
        first, computed, _ = analysis(m)
        again = [analysis(m) for _ in range(rounds)]
        bare = [analysis(m, spot_check=False) for _ in range(rounds)] if has_sum else []
        files = len(list(a.cache.glob("aic-*.npy")))
        size = sum(p.stat().st_size for p in a.cache.glob("aic-*.npy"))
    med = statistics.median
    rerun = med(r[0] for r in again)
    no_spot = med(r[0] for r in bare) if bare else float("nan")
    return [
        f"panels {nc} x {ns} ({a.mesh.n} per half-wing, {a.mesh.n ** 2 * 16 / 2**20:.2f} MiB "
        f"per entry): one AIC computed {t_aic * 1e3:.1f} ms, read back {t_load * 1e3:.2f} ms "
        f"(checksum alone {t_sum * 1e3:.2f} ms), written {t_store * 1e3:.2f} ms",
        f"  analyse: first {first:.2f} s ({computed} AICs computed, {files} files, "
        f"{size / 2**20:.1f} MiB); again {rerun:.2f} s (AICs computed "
        f"{again[0][1]}, read {again[0][2]}); again without the spot check {no_spot:.2f} s "
        f"(spot check {rerun - no_spot:+.2f} s, {100 * (rerun - no_spot) / no_spot:+.1f} %)"]


def rerun(nc: int, ns: int, rounds: int, directory: str) -> str:
    os.environ[dlm_cache.CACHE_ENV] = directory
    m = model(nc, ns)
    runs = [analysis(m) for _ in range(rounds + 1)]
    times = [r[0] for r in runs[1:]]
    return (f"panels {nc} x {ns}: first here {runs[0][0]:.2f} s (AICs computed {runs[0][1]}, "
            f"read {runs[0][2]}); reruns {', '.join(f'{t:.3f}' for t in times)} s, median "
            f"{statistics.median(times):.3f} s (AICs computed {runs[1][1]}, read {runs[1][2]})")


def _compute(a, mach, k):
    """One AIC computed (the cache bypassed)."""
    saved, a.cache = a.cache, None
    try:
        return a.aic(mach, k)
    finally:
        a.cache = saved


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="the 4 x 12 panels only")
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--rerun", metavar="DIR", help="only reruns, on the cache DIR")
    ap.add_argument("--panels", help="e.g. 8x29 (default 4x12 and 8x29)")
    args = ap.parse_args()
    panels = [(4, 12)] if args.quick else [(4, 12), (8, 29)]
    if args.panels:
        panels = [tuple(int(x) for x in args.panels.lower().split("x"))]
    print(f"propwhirl from {dlm.__file__}; CPU seconds, one BLAS thread, median of "
          f"{args.rounds}")
    with threadpool_limits(1):
        for nc, ns in panels:
            if args.rerun:
                print(rerun(nc, ns, args.rounds, args.rerun), flush=True)
                continue
            for line in run(nc, ns, args.rounds):
                print(line, flush=True)


if __name__ == "__main__":
    main()
