"""Modal structures (issue 22, 4(b), 4(c)): the thesis's wingtip and two-propeller models given
as modal structures, against the beam models, as modes are added; and the error of the strips'
spline from coarser grids.

Run from the repository root (writes the tables into docs/validation.md, "Modal structures")::

    .venv/bin/python benchmarks/modal_convergence.py --markdown docs/validation.md

(a) "own mounts" (way a): the wing's own in-vacuo modes (the lowest n), the propellers with
    their own pitch and yaw DOFs, springs and masses added by the modal model;
(b) "mounts in the modes" (way b): the modes of the whole structure — wing, propeller masses,
    mount springs (the thesis's, its damping made modal) — the propellers rigid on hub grids.
Every instability of the beam model (:func:`propwhirl.analysis.analyse`, 0.01 m/s) is matched
to the modal model's of the same kind (one to one, nearest speed, at most 30 % away); the
table gives ΔV/V [%] per number of modes kept, and the fewest modes from which every
instability stays within 0.5 %.  The spline table: the wingtip wing's first six modes from
grids at n evenly spaced nodes, interpolated to every node (the strips), the largest error of
heave and twist over the modes (relative to each mode's largest value), and the critical
speeds of the modal model (all modes, way a) splined from those grids.
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np
from scipy.optimize import linear_sum_assignment

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "benchmarks"))

from markdown_section import replace_section  # noqa: E402

from propwhirl.analysis.stability import analyse  # noqa: E402
from propwhirl.cases.ch10_other_wings import two_propeller_wing, wingtip_propeller_wing  # noqa: E402
from propwhirl.engine import single_thread_blas  # noqa: E402
from propwhirl.model.modal import (ModalInstallation, ModalPropellerWing,  # noqa: E402
                                   ModalStructure, StripPlanform, strip_interpolation)

MODES = (2, 3, 4, 5, 6, 8, 10, 12, 16, 20, 30, 40, None)
BEGIN, END = "<!-- modal-convergence:begin -->", "<!-- modal-convergence:end -->"


def own_mounts(full, n=None, wing_grids=None):
    """Way (a): the wing's modes, the propellers with their own mounts at the nodes' grids."""
    s = ModalStructure.from_wing(full.wing, n)
    inst = tuple(ModalInstallation(i.propeller, 1 + node, i.mount, i.aero)
                 for i, node in zip(full.propellers, full.nodes))
    grids = tuple(int(g) for g in s.grid_ids) if wing_grids is None else wing_grids
    return ModalPropellerWing(s, grids, StripPlanform.from_wing(full.wing), full.flight, inst)


def mounts_in_modes(full, n=None):
    """Way (b): the whole structure's modes, the propellers rigid on hub grids."""
    s, hubs, _ = ModalStructure.with_mounts(full, n)
    inst = tuple(ModalInstallation(i.propeller, h, "on-grid", i.aero)
                 for i, h in zip(full.propellers, hubs))
    return ModalPropellerWing(s, tuple(int(g) for g in s.grid_ids[:full.wing.n_nodes]),
                              StripPlanform.from_wing(full.wing), full.flight, inst)


def name(e) -> str:
    """An instability of the beam model as a column head."""
    what = "frequency zero" if e.event == "frequency-zero" else e.kind
    props = e.participation.propellers if e.participation else ()
    share = sum(p.share for p in props)
    if e.kind == "flutter":
        what = "whirl flutter" if share > 0.5 else "wing flutter"
    return f"{what} {e.V:.2f}"


def match(ref, got) -> list[float | None]:
    """ΔV/V [%] of each reference event from its match among ``got`` (same kind and event),
    one to one by nearest speed, None beyond 30 %."""
    cost = np.full((len(ref), max(1, len(got))), 1e9)
    for i, a in enumerate(ref):
        for j, b in enumerate(got):
            if (a.kind, a.event) == (b.kind, b.event):
                cost[i, j] = abs(b.V - a.V) / a.V
    out: list[float | None] = [None] * len(ref)
    for i, j in zip(*linear_sum_assignment(cost)):
        if cost[i, j] <= 0.3:
            out[i] = 100 * (got[j].V - ref[i].V) / ref[i].V
    return out


def convergence(full, build) -> tuple[list, list[tuple[str, list]], str]:
    ref = analyse(full).events
    rows = []
    for n in MODES:
        model = build(full, n)
        rows.append((str(model.structure.n_modes) + (" (all)" if n is None else ""),
                     match(ref, analyse(model).events)))
    need = "—"
    for k in range(len(rows)):
        if all(d is not None and abs(d) <= 0.5 for _, ds in rows[k:] for d in ds):
            need = rows[k][0]
            break
    return ref, rows, need


def convergence_table(title: str, full, build) -> str:
    ref, rows, need = convergence(full, build)
    head = "| modes kept | " + " | ".join(name(e) for e in ref) + " |"
    lines = [f"**{title}** — ΔV/V [%] of each instability of the beam model (m/s); "
             f"every one within 0.5 % from **{need}** modes on.", "", head,
             "|" + "---|" * (len(ref) + 1)]
    for n, ds in rows:
        cells = ["—" if d is None else f"{d:+.2f}" for d in ds]
        lines.append(f"| {n} | " + " | ".join(cells) + " |")
    return "\n".join(lines)


def spline_table() -> str:
    full = wingtip_propeller_wing()
    wing = full.wing
    s = ModalStructure.from_wing(wing, 6)
    planform = StripPlanform.from_wing(wing)
    want_h, want_a = -s.shapes[:, 1:, 2], s.shapes[:, 1:, 4]
    ref = analyse(full).events
    lines = ["| grids | largest heave error | largest twist error (cubic twist) | "
             + " | ".join(f"ΔV/V [%] {name(e)}" for e in ref) + " |",
             "|" + "---|" * (3 + len(ref))]
    for n in (3, 4, 6, 9, 13, 26):
        nodes = np.unique(np.round(np.linspace(0, wing.n_nodes - 1, n)).astype(int))
        grids = tuple(int(g) for g in s.grid_ids[nodes])
        T = strip_interpolation(s, grids, planform)
        got = np.einsum("scgk,mgk->msc", T, s.shapes)
        eh = np.max(np.abs(got[..., 0] - want_h) / np.abs(want_h).max(axis=1, keepdims=True))
        ea = np.max(np.abs(got[..., 1] - want_a) / np.abs(want_a).max(axis=1, keepdims=True))
        cubic = np.einsum("scgk,mgk->msc", strip_interpolation(s, grids, planform, "cubic"),
                          s.shapes)
        ec = np.max(np.abs(cubic[..., 1] - want_a) / np.abs(want_a).max(axis=1, keepdims=True))
        d = match(ref, analyse(own_mounts(full, wing_grids=grids)).events)
        cells = ["—" if x is None else f"{x:+.3f}" for x in d]
        lines.append(f"| {len(nodes)} | {100 * eh:.3g} % | {100 * ea:.3g} % "
                     f"({100 * ec:.3g} %) | "
                     + " | ".join(cells) + " |")
    return "\n".join(lines)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--markdown", type=Path, help="write the tables into this page")
    args = parser.parse_args(argv)
    with single_thread_blas():
        parts = [
            convergence_table("Wingtip model (§10.1), own mounts (way a)",
                              wingtip_propeller_wing(), own_mounts),
            convergence_table("Wingtip model (§10.1), mounts in the modes (way b)",
                              wingtip_propeller_wing(), mounts_in_modes),
            convergence_table("Two-propeller model (§10.2), own mounts (way a)",
                              two_propeller_wing(), own_mounts),
            convergence_table("Two-propeller model (§10.2), mounts in the modes (way b)",
                              two_propeller_wing(), mounts_in_modes),
            "**The strips' spline** — the wingtip wing's first six modes from grids at evenly "
            "spaced nodes to every node (the strips), and the critical speeds of the modal "
            "model (all 75 wing modes, own mounts) splined from those grids:\n\n"
            + spline_table(),
        ]
    body = "\n\n".join(parts)
    print(body)
    if args.markdown:
        replace_section(args.markdown, body, BEGIN, END)
    return 0


if __name__ == "__main__":
    sys.exit(main())
