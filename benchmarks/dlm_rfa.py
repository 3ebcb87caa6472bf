"""The doublet-lattice wing in the time domain (issue 23, item 3b): Roger's state space
(``analyse(model)``, method "auto") against the p-k on the same Q(k) (method "pk"), on the
thesis's wingtip model (examples/wingtip.toml) with ``aero = "dlm"``.

Run from the repository root (needs the ``dlm`` extra, PanelAero)::

    .venv/bin/python benchmarks/dlm_rfa.py                     # coarse 4 x 12 panels, prints
    .venv/bin/python benchmarks/dlm_rfa.py --markdown docs/validation.md   # and writes its table
    ... --panels 8 29                                         # the default panels (slow: AICs)

Prints (and with ``--markdown`` writes between the ``dlm-rfa`` markers of the page):

* the fit's error per term: for each pair of DOF kinds (h, φ, α of the free wing nodes: rows
  the loaded DOF, columns the moving one) the largest |Q_fit − Q| over the fitted k and every
  Mach node the speeds use, relative to the largest |Q| of that block; and the error of each
  node's fit relative to max |Q| (:attr:`propwhirl.model.aerodynamics.dlm_rfa.RogerFit.error`);
* the effect on each critical speed: every onset of the state space against the p-k's (V, f,
  differences), the CPU time of each analysis (one BLAS thread) and the AICs each computed.
"""
from __future__ import annotations

import argparse
import dataclasses
import sys
import time
from pathlib import Path

import numpy as np
from threadpoolctl import threadpool_limits

sys.path.insert(0, str(Path(__file__).resolve().parent))
from markdown_section import replace_section  # noqa: E402

from propwhirl.analysis import analyse  # noqa: E402
from propwhirl.io import load_model  # noqa: E402
from propwhirl.model.aerodynamics import dlm_rfa  # noqa: E402
from propwhirl.model.structure.assembly import free_dofs  # noqa: E402
from propwhirl.model.aerodynamics.dlm import MACH_STEP, DlmTables, dlm_aerodynamics  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
MODEL = ROOT / "examples" / "wingtip.toml"
#: the speeds of benchmarks/dlm_thesis_models.py: the tables stop at Mach 0.9 = 297.7 m/s
SPEEDS = np.r_[np.arange(100.0, 295.0, 10.0), 296.0]
KINDS = ("h", "phi", "alpha")
BEGIN, END = "<!-- dlm-rfa:begin -->", "<!-- dlm-rfa:end -->"


def dlm_model(panels: tuple[int, int]):
    """examples/wingtip.toml with ``aero = "dlm"`` on ``panels`` (chordwise, spanwise)."""
    m = load_model(MODEL)
    return m.with_(wing=dataclasses.replace(m.wing, aero="dlm", dlm_chordwise_panels=panels[0],
                                            dlm_spanwise_panels=panels[1]))


def block_errors(model, fits, tables) -> np.ndarray:
    """(3, 3) worst |Q_fit − Q| / max |Q| of each DOF-kind block over the fits' k and nodes."""
    aero = dlm_aerodynamics(model.wing, tables)
    keep = free_dofs(model.wing.n_nodes)
    kind = np.array([KINDS.index(["h", "phi", "alpha"][i % 3]) for i in keep])
    out = np.zeros((3, 3))
    for fit in fits:
        im = int(round(fit.mach / MACH_STEP))
        Q = np.stack([aero.gaf(im * MACH_STEP, k)[np.ix_(keep, keep)] for k in fit.ks])
        dev = np.abs(np.stack([fit(k) for k in fit.ks]) - Q).max(axis=0)
        big = np.abs(Q).max(axis=0)
        for r in range(3):
            for c in range(3):
                blk = np.ix_(kind == r, kind == c)
                out[r, c] = max(out[r, c], dev[blk].max() / big[blk].max())
    return out


def onsets(a) -> list:
    return [e for e in a.events if e.event == "onset"]


def run(panels: tuple[int, int]) -> str:
    model = dlm_model(panels)
    tables = DlmTables()                      # both analyses' tables: the p-k reuses the AICs
    aero = dlm_aerodynamics(model.wing, tables)
    a_sound = model.flight.speed_of_sound
    n0 = aero.evaluations
    t = time.process_time()
    rfa = analyse(model, speeds=SPEEDS, dlm_tables=tables)
    cpu_rfa, aic_rfa = time.process_time() - t, aero.evaluations - n0
    n0 = aero.evaluations
    t = time.process_time()
    pk = analyse(model, speeds=SPEEDS, method="pk", dlm_tables=tables)
    cpu_pk, aic_pk = time.process_time() - t, aero.evaluations - n0
    fits = dlm_rfa.fits_used(model, SPEEDS, tables=tables)
    errs = block_errors(model, fits, tables)
    lines = [f"Wingtip model (`examples/wingtip.toml`, {model.wing.n_nodes - 1} elements) with "
             f"`aero = \"dlm\"`, {panels[0]} × {panels[1]} panels, speeds {SPEEDS[0]:g}–"
             f"{SPEEDS[-1]:g} m/s; {model.dof_map().n_states} states "
             f"({len(model.dof_map().w_labels)} of them lag states). Fits: lags "
             f"{', '.join(f'{x:g}' for x in fits[0].lags)}, k = 0 and {fits[0].ks.size - 1} "
             f"table values from {fits[0].ks[1]:g} to {fits[0].ks[-1]:.3g}, at the "
             f"{len(fits)} Mach nodes {fits[0].mach:.2f}–{fits[-1].mach:.2f}.", "",
             "Fit error per term (largest \\|Q_fit − Q\\| over the fitted k and the Mach nodes, "
             "relative to the largest \\|Q\\| of the block; rows: the loaded DOF, columns: the "
             "moving one):", "",
             "| Q block | h | φ | α |", "|---|---:|---:|---:|"]
    for r, name in enumerate(("h", "φ", "α")):
        lines.append(f"| {name} | " + " | ".join(f"{100 * errs[r, c]:.2f} %" for c in range(3))
                     + " |")
    per_node = ", ".join(f"{f.mach:.2f}: {100 * f.error:.2f} %" for f in fits)
    lines += ["", f"Whole-Q error of each node's fit (of max \\|Q\\|), by Mach: {per_node}.", "",
              "Effect on each critical speed (onsets; the p-k on the same Q(k) is the reference):",
              "", "| event (mode by p-k) | whirl | p-k V [m/s] / f [Hz] | state space V / f | ΔV | Δf |",
              "|---|---|---:|---:|---:|---:|"]
    got = {(e.kind, e.whirl): e for e in onsets(rfa)}
    for p in onsets(pk):
        e = got.pop((p.kind, p.whirl), None)
        if e is None:
            lines.append(f"| {p.kind} ({p.label}) | {p.whirl or '–'} | {p.V:.2f} / "
                         f"{p.frequency_hz:.3f} | not found | – | – |")
            continue
        df = (f"{100 * (e.frequency_hz / p.frequency_hz - 1):+.2f} %"
              if p.frequency_hz > 0 else "–")
        lines.append(f"| {p.kind} ({p.label}) | {p.whirl or '–'} | {p.V:.2f} / "
                     f"{p.frequency_hz:.3f} | {e.V:.2f} / {e.frequency_hz:.3f} | "
                     f"{100 * (e.V / p.V - 1):+.2f} % | {df} |")
    for e in got.values():
        lines.append(f"| {e.kind} ({e.label}) | {e.whirl or '–'} | not found | "
                     f"{e.V:.2f} / {e.frequency_hz:.3f} | – | – |")
    lines += ["", f"CPU (one BLAS thread, shared machine): state space {cpu_rfa:.1f} s "
              f"({aic_rfa} AICs: {len(fits)} Mach nodes × {fits[0].ks.size} k), then p-k "
              f"{cpu_pk:.1f} s ({aic_pk} more AICs: the p-k reads the same tables). Mach of the "
              f"events: " + ", ".join(f"{e.V / a_sound:.2f}" for e in onsets(pk)) + "."]
    return "\n".join(lines)


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--panels", type=int, nargs=2, default=(4, 12), metavar=("NC", "NS"))
    p.add_argument("--markdown", type=Path, help="write the table into this page's dlm-rfa "
                   "section")
    args = p.parse_args()
    with threadpool_limits(1):
        text = run(tuple(args.panels))
    print(text)
    if args.markdown is not None:
        replace_section(args.markdown, text, BEGIN, END)


if __name__ == "__main__":
    main()
