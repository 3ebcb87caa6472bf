"""Free structures with their plunge and roll kept (issue 36, item 4): the table, measured.

The wingtip model's wing (tests/helpers/op2_files.free_modal_model) on a root body free in
plunge and roll (pitch held: a wing alone has no tail), the body's mass and roll and pitch
inertia κ times the wing's own, every mode kept (``ModalStructure(free=True)``: the two
rigid-body modes at 0 Hz with the strips' aerodynamics on them), against the clamped wing:
each clamped instability's match among the free structure's (the nearest onset within 30 % of
the same kind; for a divergence also a flutter below half the clamped wing's first
frequency: a free structure's divergence root meets the plunge's aerodynamic root and the
pair crosses as a low-frequency flutter) and the free structure's other events.  Runs in
the main environment (no pyNastran), from the repository root::

    .venv/bin/python benchmarks/free_structures.py --markdown docs/validation.md
"""
from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "benchmarks"))
sys.path.insert(0, str(ROOT / "tests"))

from markdown_section import replace_section  # noqa: E402

from helpers.op2_files import free_modal_model  # noqa: E402
from propwhirl.analysis.stability import analyse  # noqa: E402
from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing  # noqa: E402
from propwhirl.engine import single_thread_blas  # noqa: E402
from propwhirl.model.modal import ModalStructure  # noqa: E402

KAPPAS = (1e6, 1e4, 1e2, 10.0, 1.0)
BEGIN, END = "<!-- free-structures:begin -->", "<!-- free-structures:end -->"


def nearest(e, got, used, low_hz):
    """Index of the event of ``got`` (not in ``used``) nearest ``e`` in onset speed, within
    30 % (else None), of the same kind — or, for a divergence, a flutter below ``low_hz``
    [Hz] (the divergence root met by the plunge's aerodynamic root)."""
    def like(g):
        return g.kind == e.kind or (e.kind == "divergence" and g.frequency_hz < low_hz)
    best = min((j for j in range(len(got)) if j not in used and like(got[j])),
               key=lambda j: abs(got[j].V - e.V), default=None)
    return best if best is not None and abs(got[best].V - e.V) <= 0.3 * e.V else None


def cell(g, e) -> str:
    kind = g.kind if g.kind == "divergence" else f"{g.kind} {g.frequency_hz:.3g} Hz"
    return f"{100 * (g.V - e.V) / e.V:+.2f} ({kind})"


def table() -> str:
    full = wingtip_propeller_wing()
    ref = analyse(full).events
    clamped_f = ModalStructure.from_wing(full.wing, n_modes=1).frequencies_hz[0]
    head = ("| root | κ (body / wing) | rigid-body modes kept | first elastic mode [Hz] | "
            + " | ".join(f"ΔV/V [%] {e.kind} {e.V:.2f}" for e in ref)
            + " | other events (m/s) |")
    lines = [head, "|" + "---|" * (5 + len(ref)),
             "| clamped | — | — | " + f"{clamped_f:.3f} | " + " | ".join("0" for _ in ref)
             + " | |"]
    for kappa in KAPPAS:
        model, n_rigid = free_modal_model(full, kappa, "plunge-roll")
        got = analyse(model).events
        used: set[int] = set()
        cells = []
        for e in ref:
            j = nearest(e, got, used, 0.5 * clamped_f)
            if j is None:
                cells.append("—")
            else:
                used.add(j)
                cells.append(cell(got[j], e))
        other = ", ".join(f"{g.kind} {g.V:.1f}" + ("" if g.kind == "divergence" else
                                                   f" ({g.frequency_hz:.3g} Hz)")
                          for j, g in enumerate(got) if j not in used)
        f1 = model.structure.frequencies_hz[n_rigid]
        lines.append(f"| plunge and roll | {kappa:g} | {n_rigid} | {f1:.3f} | "
                     + " | ".join(cells) + f" | {other} |")
    return "\n".join(lines)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--markdown", type=Path, help="write the table into this file")
    args = ap.parse_args()
    t0 = time.perf_counter()
    with single_thread_blas():
        body = table()
    print(body)
    print(f"({time.perf_counter() - t0:.1f} s)")
    if args.markdown:
        replace_section(args.markdown, body, BEGIN, END)


if __name__ == "__main__":
    main()
