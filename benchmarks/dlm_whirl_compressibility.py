"""Why the doublet lattice lowers the wingtip model's 6 Hz whirl flutter: compressibility, not
tip loss (issue 37, item 5).  A numerical experiment, not a test.

Run from the repository root (needs the ``dlm`` extra, PanelAero)::

    PROPWHIRL_DLM_CACHE=/tmp/dlmcache .venv/bin/python benchmarks/dlm_whirl_compressibility.py
    ... --panels 4 12                # coarse panels (default: the wing's default, 8 x 29)
    ... --markdown docs/validation.md

The wingtip model of §10.1 (``propwhirl.cases.ch10_other_wings.wingtip_propeller_wing``, the
model of ``examples/wingtip.toml`` and of docs/validation.md's "The thesis's wingtip and
two-propeller models"), analysed by the p-k (:func:`propwhirl.analysis.pk.pk_sweep`) with

* the doublet lattice at a fixed Mach (``dlm_mach`` = 0, 0.3, 0.45, 0.55, 0.6) at every speed
  (non-matched: the Mach of the loads held while the speed changes), and Mach matched
  (``dlm_mach = "speed"``, V/a at each speed, the tables stop at Mach 0.9);
* the strips (C_lα = 2π, exact Theodorsen, incompressible) and the strips with the
  Prandtl–Glauert lift slope 2π/β (``compressibility = "prandtl-glauert"``) at the same fixed
  Mach numbers and matched.

For each: NASTRAN's damping g = 2 Re p / Im p of the ~6 Hz whirl mode (the strips' 6.5 Hz
whirl-flutter mode, the same tracked column in every run: every run starts from the same
strip finite-state roots) along the speeds, its largest value (the hump's peak, refined by a
bounded scalar search on the p-k root) and the speed of its onset (g = 0), with the CPU time
of each run (one BLAS thread).
"""
from __future__ import annotations

import argparse
import dataclasses
import os
import time
from pathlib import Path

import numpy as np
from scipy.optimize import minimize_scalar
from threadpoolctl import threadpool_limits

from propwhirl.analysis.pk import pk_root, pk_sweep
from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing

FIXED_MACHS = (0.0, 0.3, 0.45, 0.55, 0.6)
#: speeds [m/s]: every 10 from 100 to 350 (fixed Mach); matched up to Mach 0.9 (297.7 m/s)
SPEEDS = np.arange(100.0, 351.0, 10.0)
#: the whirl mode: the column with a crossing between these frequencies [Hz] on the strips
WHIRL_BAND = (5.5, 7.5)
BEGIN, END = "<!-- dlm-whirl-mach:begin -->", "<!-- dlm-whirl-mach:end -->"


def variant(model, aero: str, mach, panels=None):
    """The model with its wing's aerodynamics ``aero`` ("dlm", "strip", "strip-pg") at ``mach``
    (a number: fixed; "speed": matched; ignored by "strip")."""
    w = model.wing
    if aero == "dlm":
        nc, ns = panels if panels is not None else (w.dlm_chordwise_panels, None)
        w = dataclasses.replace(w, aero="dlm", dlm_mach=mach, dlm_chordwise_panels=nc,
                                dlm_spanwise_panels=ns)
    elif aero == "strip-pg":
        w = dataclasses.replace(w, compressibility="prandtl-glauert", strip_mach=mach)
    return model.with_(wing=w)


def whirl_column(sweep) -> int:
    """The tracked column of the ~6 Hz whirl mode: the one whose onset frequency lies in
    :data:`WHIRL_BAND` (the strips' 6.54 Hz whirl flutter)."""
    for e in sweep.flutter:
        if e.event == "onset" and e.kind == "flutter" \
                and WHIRL_BAND[0] <= e.frequency_hz <= WHIRL_BAND[1]:
            return e.mode
    raise RuntimeError("no whirl-flutter onset in the band on the strips")


def hump(model, sweep, j: int) -> dict:
    """The damping curve of column ``j``: g at each speed, the peak (V, g, f) refined between
    the grid neighbours of the largest grid value, and the first onset (V, f)."""
    g = sweep.damping[:, j]
    V = sweep.speeds
    ok = np.isfinite(g)
    i = int(np.nanargmax(np.where(ok, g, -np.inf)))
    peak_V, peak_g = float(V[i]), float(g[i])
    f = float(abs(sweep.roots[i, j].imag) / (2 * np.pi))
    if 0 < i < V.size - 1:                     # an interior maximum: the hump's peak
        p0 = sweep.roots[i, j]

        def minus_g(x: float) -> float:
            p, _ = pk_root(model, x, p0)
            return -2 * p.real / abs(p.imag)

        r = minimize_scalar(minus_g, bounds=(float(V[i - 1]), float(V[i + 1])),
                            method="bounded", options={"xatol": 0.05})
        p, _ = pk_root(model, float(r.x), p0)
        peak_V, peak_g, f = float(r.x), float(-r.fun), float(abs(p.imag) / (2 * np.pi))
    onsets = [e for e in sweep.flutter if e.mode == j and e.event == "onset"]
    ends = [e for e in sweep.flutter if e.mode == j and e.event == "end"]
    onset = (onsets[0].V, onsets[0].frequency_hz) if onsets else None
    return {"g": g, "V": V, "peak": (peak_V, peak_g, f), "interior": 0 < i < V.size - 1,
            "onset": onset, "end": ends[0].V if ends else None}


def run(model, speeds, j: int | None = None):
    """(sweep, column, hump, CPU [s]) of one variant."""
    t = time.process_time()
    sweep = pk_sweep(model, speeds)
    j = whirl_column(sweep) if j is None else j
    h = hump(model, sweep, j)
    return sweep, j, h, time.process_time() - t


def table(rows, a: float, title: str) -> str:
    """The markdown table of the runs."""
    out = [title, "",
           "| wing aerodynamics | Mach of the loads | peak g of the whirl mode | at V [m/s] (V/a) "
           "| f [Hz] | onset V [m/s] (V/a) | f [Hz] | stable again from V [m/s] | CPU [s] |",
           "|---|---|---:|---:|---:|---:|---:|---:|---:|"]
    for label, mach, h, cpu in rows:
        pV, pg, pf = h["peak"]
        last = h["V"][np.isfinite(h["g"])][-1]
        if not h["interior"]:
            peak = f"– (rising to {last:.0f})"
            at, fp = "–", "–"
        else:
            peak = f"{pg:+.4f}"
            at, fp = f"{pV:.1f} ({pV / a:.2f})", f"{pf:.3f}"
        on = ("none up to " + f"{last:.0f}" if h["onset"] is None
              else f"{h['onset'][0]:.2f} ({h['onset'][0] / a:.3f})")
        fo = "–" if h["onset"] is None else f"{h['onset'][1]:.3f}"
        end = "–" if h["end"] is None else f"{h['end']:.2f}"
        out.append(f"| {label} | {mach} | {peak} | {at} | {fp} | {on} | {fo} | {end} "
                   f"| {cpu:.1f} |")
    return "\n".join(out)


def curves(rows, speeds) -> str:
    """g of the whirl mode at every speed, one column per run (a markdown table)."""
    head = "| V [m/s] | " + " | ".join(f"{lab} {m}" for lab, m, _, _ in rows) + " |"
    out = [head, "|---:|" + "---:|" * len(rows)]
    for i, Vi in enumerate(speeds):
        cells = []
        for _, _, h, _ in rows:
            k = np.flatnonzero(np.isclose(h["V"], Vi))
            cells.append(f"{h['g'][k[0]]:+.4f}" if k.size and np.isfinite(h["g"][k[0]]) else "")
        out.append(f"| {Vi:.0f} | " + " | ".join(cells) + " |")
    return "\n".join(out)


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--panels", type=int, nargs=2, default=None, metavar=("CHORD", "SPAN"))
    p.add_argument("--no-pg", action="store_true", help="without the Prandtl-Glauert strips")
    p.add_argument("--markdown", type=Path, default=None)
    args = p.parse_args()
    base = wingtip_propeller_wing()
    a = base.flight.speed_of_sound
    matched = SPEEDS[SPEEDS <= 0.9 * a]
    rows_dlm, rows_strip = [], []
    with threadpool_limits(1):
        sweep, j, h, cpu = run(base, SPEEDS)
        print(f"whirl column {j}: {sweep.labels[j]}")
        rows_strip.append(("strips 2π", "– (incompressible)", h, cpu))
        print(rows_strip[-1][:2], h["peak"], h["onset"], f"CPU {cpu:.1f} s", flush=True)
        runs = [("dlm", m) for m in FIXED_MACHS] + [("dlm", "speed")]
        if not args.no_pg:
            runs += [("strip-pg", m) for m in FIXED_MACHS] + [("strip-pg", "speed")]
        for aero, m in runs:
            model = variant(base, aero, m, args.panels)
            speeds = matched if m == "speed" else SPEEDS
            _, _, h, cpu = run(model, speeds, j)
            label = "DLM" if aero == "dlm" else "strips 2π/β (Prandtl–Glauert)"
            mach = "V/a (matched)" if m == "speed" else f"{m:g}"
            (rows_dlm if aero == "dlm" else rows_strip).append((label, mach, h, cpu))
            print(label, mach, h["peak"], h["onset"], f"CPU {cpu:.1f} s", flush=True)
    panels = "default 8 × 29" if args.panels is None else f"{args.panels[0]} × {args.panels[1]}"
    cache = ("AICs read from PROPWHIRL_DLM_CACHE" if os.environ.get("PROPWHIRL_DLM_CACHE")
             else "AICs computed")
    body = "\n\n".join([
        table(rows_dlm + rows_strip, a,
              f"Wingtip model (§10.1, 25 elements, flexible mount, full propeller aerodynamics), "
              f"p-k, DLM panels {panels}; a = {a:.2f} m/s; CPU of each run (one BLAS "
              f"thread, {cache}, load average {os.getloadavg()[0]:.1f}); the whirl mode is the p-k's "
              f"{sweep.labels[j]}; peak: the largest g between the speeds' ends "
              "(refined to 0.05 m/s)."),
        "g = 2 Re p / Im p of the whirl mode along the speeds:",
        curves(rows_dlm + rows_strip, SPEEDS)])
    print(body)
    if args.markdown is not None:
        from markdown_section import replace_section  # noqa: E402  (benchmarks/ on sys.path)
        replace_section(args.markdown, body, BEGIN, END)


if __name__ == "__main__":
    main()
