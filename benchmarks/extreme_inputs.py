"""Valid inputs at the edges of their ranges (issue 20, item 9): time and memory of each.

Run from the repository root (each case in a subprocess of its own, one BLAS thread; CPU time
and peak RSS of that process from ``os.wait4``)::

    .venv/bin/python benchmarks/extreme_inputs.py                      # this checkout
    .venv/bin/python benchmarks/extreme_inputs.py --reference ../main  # and another, side by side
    .venv/bin/python benchmarks/extreme_inputs.py --quick              # small versions only
    .venv/bin/python benchmarks/extreme_inputs.py --markdown docs/performance.md

The cases (the wingtip model of examples/wingtip.toml, 1–350 m/s, ``analyse(model)``):

* ``rayleigh_lambda_s = 1.0`` (its range maximum);
* ``EI_chordwise_N_m2 = 1e14`` (its range maximum);
* 64 equal propellers (the limit) evenly spaced to the tip;
* a 500 × 500 map of ``wing.EI`` × ``wing.GJ``: only whether it starts (the first variant
  stops it) or is refused before the work with its estimate — never run.

Full size, a reference checkout of the code before issue 20.9 takes > 10 minutes (the Rayleigh
case alone 690 s); ``--timeout`` (default 300 s) stops a case and records it as not finished.
``--quick`` runs 12-element versions and 16 propellers.
"""
from __future__ import annotations

import argparse
import json
import os
import re
import subprocess
import sys
import tempfile
import threading
import time
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "examples" / "wingtip.toml"
BEGIN = "<!-- extreme_inputs:begin -->"
END = "<!-- extreme_inputs:end -->"
TITLE = "## Valid inputs at the edges of their ranges (issue 20.9)"

ANALYSE = """
import json, sys
import propwhirl
from propwhirl.io import load_model
from propwhirl.analysis import analyse
a = analyse(load_model(sys.argv[1]))
print(json.dumps({"nodes": a.sweep.stats.get("nodes"),
                  "events": [[e.kind, e.event, e.label, round(e.V, 3)] for e in a.events],
                  "critical": a.summary().splitlines()[-1].strip()}))
"""

MAP = """
import json, sys
import numpy as np
from propwhirl.io import load_model
from propwhirl.studies import paths as P, sweeps
from propwhirl.validate import InputError
class Started(Exception):
    pass
def guard(model, point):
    raise Started
P.set_values = guard
m = load_model(sys.argv[1])
try:
    sweeps.map2d(m, ("wing.EI", np.linspace(5e5, 9e5, 500)), ("wing.GJ", np.linspace(1.5e5, 2.5e5, 500)),
                 progress=True)
    out = "finished?"
except Started:
    out = "started: 250,000 variants and analyses, no estimate"
except InputError as exc:
    out = "refused before the work: " + str(exc)
print(json.dumps({"nodes": None, "events": [], "critical": out}))
"""


@dataclass
class Run:
    case: str
    code: str
    cpu: float | None
    rss_mb: float | None
    result: dict | None
    note: str = ""


def model_file(directory: Path, *, n_elements: int = 25, lam: float = 0.0,
               ei_chordwise: float | None = None, propellers: int = 1) -> Path:
    """examples/wingtip.toml with the given changes, written into ``directory``."""
    text = EXAMPLE.read_text().replace("n_elements = 25", f"n_elements = {n_elements}")
    text = text.replace("rayleigh_lambda_s = 0.0", f"rayleigh_lambda_s = {lam!r}")
    if ei_chordwise is not None:
        text = text.replace("EI_N_m2 = 700000.0",
                            f"EI_N_m2 = 700000.0\nEI_chordwise_N_m2 = {ei_chordwise!r}")
    if propellers > 1:
        rows = "".join(f'    {{ propeller = "p1", y_m = {5.7 * (i + 1) / propellers!r}, '
                       'mount = "flexible", aero = true },\n' for i in range(propellers))
        text = re.sub(r"installations = \[\n.*?\n\]\n", f"installations = [\n{rows}]\n", text,
                      flags=re.S)
    path = directory / f"w{n_elements}_l{lam}_e{ei_chordwise}_p{propellers}.toml"
    path.write_text(text)
    return path


def run_case(script: str, path: Path, src: Path | None, timeout: float) -> tuple:
    """(CPU [s], peak RSS [MB], parsed output or None, note) of ``script path`` in a child."""
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1", MKL_NUM_THREADS="1")
    if src is not None:
        env["PYTHONPATH"] = os.pathsep.join([str(src / "src"), str(src)])
    with tempfile.TemporaryFile("w+") as out:
        p = subprocess.Popen([sys.executable, "-c", script, str(path)], stdout=out,
                             stderr=subprocess.DEVNULL, env=env)
        killed = threading.Event()

        def stop():
            killed.set()
            p.kill()

        timer = threading.Timer(timeout, stop)
        timer.start()
        _, status, ru = os.wait4(p.pid, 0)
        timer.cancel()
        p.returncode = status
        out.seek(0)
        text = out.read().strip().splitlines()
    cpu = ru.ru_utime + ru.ru_stime
    rss = ru.ru_maxrss / 1024.0
    if killed.is_set():
        return cpu, rss, None, f"not finished in {timeout:.0f} s"
    try:
        return cpu, rss, json.loads(text[-1]), ""
    except (IndexError, ValueError):
        return cpu, rss, None, "failed"


def cases(directory: Path, quick: bool) -> list[tuple[str, str, Path]]:
    ne = 12 if quick else 25
    return [
        (f"rayleigh_lambda_s = 1.0 ({ne} el.)", ANALYSE, model_file(directory, n_elements=ne,
                                                                     lam=1.0)),
        (f"EI_chordwise_N_m2 = 1e14 ({ne} el.)", ANALYSE,
         model_file(directory, n_elements=ne, ei_chordwise=1e14)),
        (f"{16 if quick else 64} propellers ({ne} el.)", ANALYSE,
         model_file(directory, n_elements=ne, propellers=16 if quick else 64)),
        ("500 x 500 map (wing.EI x wing.GJ)", MAP, model_file(directory)),
    ]


def run(reference: Path | None, quick: bool, timeout: float) -> list[Run]:
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for name, script, path in cases(Path(tmp), quick):
            for code, src in (("this", None), ("reference", reference)):
                if code == "reference" and reference is None:
                    continue
                cpu, rss, res, note = run_case(script, path, src, timeout)
                rows.append(Run(name, code, cpu, rss, res, note))
                print(f"{name:40s} {code:9s} CPU {cpu:7.1f} s  RSS {rss:7.0f} MB  "
                      f"{note or (res or {}).get('critical', '')}", flush=True)
    return rows


def table(rows: list[Run], reference: Path | None, quick: bool) -> str:
    L = [f"Measured {time.strftime('%Y-%m-%d')} with `benchmarks/extreme_inputs.py"
         f"{' --quick' if quick else ''}` (each case a process of its own, one BLAS thread, CPU "
         "time and peak RSS from `os.wait4`; the machine: "
         f"{os.cpu_count()} cores, shared)." + (f" Reference: the checkout `{reference}`."
                                                if reference else ""),
         "",
         "| case | code | CPU [s] | peak RSS [MB] | nodes | result |",
         "|---|---|---:|---:|---:|---|"]
    for r in rows:
        res = r.result or {}
        what = r.note or str(res.get("critical", "")).replace("|", "/")
        L.append(f"| {r.case} | {r.code} | {r.cpu:.1f} | {r.rss_mb:.0f} | "
                 f"{res.get('nodes') if res.get('nodes') is not None else '-'} | {what} |")
    return "\n".join(L)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="benchmarks/extreme_inputs.py", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--reference", type=Path, help="another checkout to run side by side")
    ap.add_argument("--quick", action="store_true", help="12 elements, 16 propellers")
    ap.add_argument("--timeout", type=float, default=300.0, help="seconds per case")
    ap.add_argument("--markdown", type=Path, help="write the table into this file")
    args = ap.parse_args(argv)
    rows = run(args.reference, args.quick, args.timeout)
    text = table(rows, args.reference, args.quick)
    print(text)
    if args.markdown:
        sys.path.insert(0, str(Path(__file__).resolve().parent))
        from markdown_section import replace_section

        replace_section(args.markdown, text, BEGIN, END, TITLE)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
