"""The p-k events of ``analyse(model, speeds, method="pk")`` on a fixed set of models, written
to JSON (``--out``), and two such files compared (``--compare before.json after.json``): for
each case the events (kind, onset/end, mode name, frequency) matched in order, the largest
|ΔV| [m/s], |Δf| [Hz] and relative change of the benignity, and whether the analysis's notes
(its warnings) are the same (issue 37: the modal p-k sweep must leave every event unchanged).

Run from the repository root (one BLAS thread)::

    OPENBLAS_NUM_THREADS=1 .venv/bin/python benchmarks/pk_events_compare.py --out /tmp/after.json
    .venv/bin/python benchmarks/pk_events_compare.py --compare /tmp/before.json /tmp/after.json

Cases: the seven rows of ``benchmarks/nastran95_side_by_side.py``; the examples (four
propellers, wingtip, x57_like, x57_like folded) on strips over their own speeds; the thesis
models the p-k tests run (Patil's wing on strips and on 4 × 32 panels, the wingtip model on
strips and on 4 × 12 panels, the wingtip model on 6 elements and 3 × 8 panels Mach-matched
and at a fixed Mach, x57_like over 60-100 and 10-120 m/s).
"""
from __future__ import annotations

import argparse
import dataclasses
import json
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "benchmarks"))


def cases():
    """name -> () -> (model, speeds)."""
    from propwhirl import io
    from propwhirl.cases.ch07_patil import patil_model
    from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
    import nastran95_side_by_side as bench

    ex = ROOT / "examples"

    def example(name):
        def make():
            m = io.load_model(ex / f"{name}.toml")
            return m, m.flight.speeds()
        return make

    def dlm(m, **kw):
        return m.with_(wing=dataclasses.replace(m.wing, aero="dlm", **kw))

    def small_wingtip(mach):
        m = wingtip_propeller_wing()
        return m.with_(wing=dataclasses.replace(m.wing, n_elements=6, aero="dlm", dlm_mach=mach,
                                                dlm_chordwise_panels=3, dlm_spanwise_panels=8))

    out = {c: (lambda c=c: bench.build(c)[:2]) for c in bench.CASES}
    out.update({f"example_{n}": example(n)
                for n in ("four_propeller", "wingtip", "x57_like", "x57_like_folded")})
    out.update({
        "patil_strips": lambda: (patil_model(), np.linspace(5.0, 200.0, 40)),
        "patil_dlm_4x32": lambda: (dlm(patil_model(10), dlm_chordwise_panels=4,
                                       dlm_spanwise_panels=32), np.arange(20.0, 42.0, 4.0)),
        "wingtip_strips": lambda: (wingtip_propeller_wing(), np.linspace(100.0, 200.0, 11)),
        "wingtip_dlm_4x12": lambda: (dlm(wingtip_propeller_wing(), dlm_chordwise_panels=4,
                                         dlm_spanwise_panels=12), np.arange(140.0, 201.0, 10.0)),
        "wingtip6_dlm_matched": lambda: (small_wingtip("speed"), np.arange(140.0, 231.0, 10.0)),
        "wingtip6_dlm_m06": lambda: (small_wingtip(0.6), np.arange(140.0, 231.0, 10.0)),
        "x57_like_60_100": lambda: (io.load_model(ex / "x57_like.toml"),
                                    np.arange(60.0, 100.1, 5.0)),
        "x57_like_10_120": lambda: (io.load_model(ex / "x57_like.toml"),
                                    np.linspace(10, 120, 23)),
    })
    return out


def run(names, out: Path) -> None:
    from propwhirl.analysis import analyse
    got = json.loads(out.read_text()) if out.exists() else {}
    for name, make in cases().items():
        if names and name not in names:
            continue
        model, speeds = make()
        t0 = time.process_time()
        a = analyse(model, speeds, method="pk")
        cpu = time.process_time() - t0
        got[name] = {"cpu_s": cpu, "events": [[e.kind, e.event, e.label, float(e.V),
                                               float(e.frequency_hz), e.benignity]
                                              for e in a.events],
                     "notes": list(a.warnings)}
        print(f"{name}: {cpu:.1f} s, {len(a.events)} events", flush=True)
        out.write_text(json.dumps(got, indent=1))


def compare(before: Path, after: Path) -> None:
    b, a = json.loads(before.read_text()), json.loads(after.read_text())
    print("| case | events | same kind/direction/name | max abs dV [m/s] | max abs df [Hz] "
          "| max rel. d benignity | same notes | CPU before [s] | CPU after [s] |")
    print("|---|---:|---|---:|---:|---:|---|---:|---:|")
    for name in b:
        if name not in a:
            continue
        eb, ea = b[name]["events"], a[name]["events"]
        same = len(eb) == len(ea) and all(x[:3] == y[:3] for x, y in zip(eb, ea))
        dv = max((abs(x[3] - y[3]) for x, y in zip(eb, ea)), default=0.0)
        df = max((abs(x[4] - y[4]) for x, y in zip(eb, ea)), default=0.0)
        # benignity and notes: in files written since they were recorded (else "-")
        pairs = [(x[5], y[5]) for x, y in zip(eb, ea) if len(x) > 5 and len(y) > 5]
        db = max((abs(y / x - 1) if x and y else float(x != y) for x, y in pairs
                  if x is not None or y is not None), default=0.0)
        nb, na = b[name].get("notes"), a[name].get("notes")
        notes = "-" if nb is None or na is None else "yes" if nb == na else "NO"
        print(f"| {name} | {len(eb)} / {len(ea)} | {'yes' if same else 'NO'} | {dv:.4f} | "
              f"{df:.5f} | {db:.1e} | {notes} | {b[name]['cpu_s']:.1f} | "
              f"{a[name]['cpu_s']:.1f} |")
        if notes == "NO":
            for x in sorted(set(nb) ^ set(na)):
                print("   " + ("before " if x in nb else "after  ") + x)
        if not same:
            for x in eb:
                print("   before", x)
            for y in ea:
                print("   after ", y)


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--out", type=Path)
    p.add_argument("--only", default="", help="comma-separated cases")
    p.add_argument("--compare", nargs=2, type=Path)
    args = p.parse_args()
    if args.compare:
        compare(*args.compare)
    else:
        run([c for c in args.only.split(",") if c], args.out)


if __name__ == "__main__":
    main()
