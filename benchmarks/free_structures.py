"""Free structures with their rigid-body modes kept (issue 36, item 4): the tables, measured.

The wingtip model's wing (tests/helpers/op2_files.free_modal_model) on a root body free in
plunge and roll (pitch held: a wing alone has no tail), the body's mass and roll and pitch
inertia κ times the wing's own, every mode kept (``ModalStructure(free=True)``: the two
rigid-body modes at 0 Hz with the strips' aerodynamics on them), against the clamped wing:
each clamped instability's match among the free structure's (the nearest onset within 30 % of
the same kind; for a divergence also a flutter below half the clamped wing's first
frequency: a free structure's divergence root meets the plunge's aerodynamic root and the
pair crosses as a low-frequency flutter) and the free structure's other events.

The second table: the same wing on a root body free in plunge, roll **and pitch** with a
horizontal tail on a rigid arm (tests/helpers/op2_files.tailed_modal_model: the body's
centre of gravity at the mean chord's quarter point, pitch inertia κ m_wing r_y², the tail's
strips a second lifting surface on grids that move with the body): the centre of gravity and
the strips' neutral point (:func:`propwhirl.model.modal_surface.neutral_point`), the rigid
roots' highest real part below the first clamped instability (stable: < 0) and the
short-period root at 100 m/s, the same ΔV/V against the clamped wing, and the tail put as far
ahead of the centre of gravity (statically unstable): its first event.  Runs in the main
environment (no pyNastran), from the repository root::

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

import numpy as np  # noqa: E402

from helpers.op2_files import (TAIL, centre_of_gravity_x, free_modal_model,  # noqa: E402
                               tailed_modal_model)
from propwhirl.model.modal_surface import neutral_point  # noqa: E402
from propwhirl.analysis.stability import analyse  # noqa: E402
from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing  # noqa: E402
from propwhirl.engine import single_thread_blas  # noqa: E402
from propwhirl.model.modal import ModalStructure  # noqa: E402

KAPPAS = (1e6, 1e4, 1e2, 10.0, 1.0)
TAIL_KAPPAS = (1e6, 1e4, 1e2, 10.0, 1.0)
BEGIN, END = "<!-- free-structures:begin -->", "<!-- free-structures:end -->"
TAIL_BEGIN, TAIL_END = "<!-- free-tail:begin -->", "<!-- free-tail:end -->"


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


def _matched(ref, got, low_hz):
    """The ΔV/V cells of ``ref``'s events among ``got`` (:func:`nearest`), each with the mode
    it is of, and the others."""
    used: set[int] = set()
    cells = []
    for e in ref:
        j = nearest(e, got, used, low_hz)
        if j is None:
            cells.append("—")
        else:
            used.add(j)
            cells.append(cell(got[j], e) + f" [{got[j].label}]")
    other = ", ".join(f"{g.kind} {g.V:.1f}" + ("" if g.kind == "divergence" else
                                               f" ({g.frequency_hz:.3g} Hz)")
                      + f" [{g.label}]" for j, g in enumerate(got) if j not in used)
    return cells, other


def rigid_roots(analysis) -> tuple[str, complex]:
    """(the first instability of a rigid-body mode — an event of a mode named "rigid k" or
    "static k" — as "V (kind)", or "none"; the short period: the rigid modes' oscillatory
    root with the largest |λ| at the sweep's speed nearest 100 m/s)."""
    sw = analysis.sweep
    first = min((g for g in analysis.events if g.event != "recovery"
                 and g.label.split()[0] in ("rigid", "static")), key=lambda g: g.V,
                default=None)
    rigid = [k for k, lab in enumerate(sw.mode_labels) if lab.startswith("rigid")]
    i = int(np.argmin(np.abs(sw.V - 100.0)))
    lam = sw.eigenvalues[i, rigid]
    osc = lam[lam.imag > 0]
    where = "none" if first is None else (
        f"{first.V:.1f} ({first.kind}" + ("" if first.kind == "divergence" else
                                          f" {first.frequency_hz:.3g} Hz") + ")")
    return where, complex(osc[np.argmax(np.abs(osc))]) if osc.size else complex("nan")


def tail_table() -> str:
    full = wingtip_propeller_wing()
    ref = analyse(full).events
    clamped_f = ModalStructure.from_wing(full.wing, n_modes=1).frequencies_hz[0]
    head = ("| κ (body / wing) | x_cg [m] | x_np [m] | static margin [% c̄] | short period at "
            "100 m/s [Hz, ζ] | rigid modes first unstable [m/s] | "
            + " | ".join(f"ΔV/V [%] {e.kind} {e.V:.2f}" for e in ref)
            + " | other events (m/s) [mode] | tail ahead (arm −"
            f"{TAIL['arm']:g} m): first event |")
    lines = [head, "|" + "---|" * (8 + len(ref))]
    for kappa in TAIL_KAPPAS:
        model, n_rigid = tailed_modal_model(full, kappa)
        a = analyse(model)
        got = a.events
        x_cg = centre_of_gravity_x(model)
        x_np = neutral_point([model.planform, *(s.planform for s in model.surfaces)])
        p = model.planform
        c_mean = float(np.sum(p.chord * p.width) / np.sum(p.width))
        where, sp = rigid_roots(a)
        cells, other = _matched(ref, got, 0.5 * clamped_f)
        ahead, _ = tailed_modal_model(full, kappa, arm=-TAIL["arm"])
        first = min(analyse(ahead).events, key=lambda g: g.V)
        lines.append(
            f"| {kappa:g} | {x_cg:.3f} | {x_np:.3f} | {100 * (x_np - x_cg) / c_mean:.1f} | "
            f"{abs(sp.imag) / (2 * np.pi):.3g}, {-sp.real / abs(sp):.2g} | {where} | "
            + " | ".join(cells) + f" | {other} | {first.kind} ({first.event}) at "
            f"{first.V:.1f} m/s [{first.label}] |")
    return "\n".join(lines)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--markdown", type=Path, help="write the table into this file")
    args = ap.parse_args()
    t0 = time.perf_counter()
    with single_thread_blas():
        body = table()
        tail = tail_table()
    print(body)
    print(tail)
    print(f"({time.perf_counter() - t0:.1f} s)")
    if args.markdown:
        replace_section(args.markdown, body, BEGIN, END)
        replace_section(args.markdown, tail, TAIL_BEGIN, TAIL_END)


if __name__ == "__main__":
    main()
