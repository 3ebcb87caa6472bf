"""NASTRAN in and out (issue 36, items 4 and 6): the evidence tables, measured.

Needs pyNastran, so it runs in the NASTRAN environment (``make test`` builds it), from the
repository root (writes the tables into docs/validation.md, "NASTRAN in and out")::

    .venv-nastran/bin/python benchmarks/nastran_evidence.py --markdown docs/validation.md

(6a) **BDF out and in**: the wingtip and two-propeller models written as SOL 103 decks
     (``write_bdf``) in each unit system and read back (``read_bdf``): every instability's
     speed against the original's.
(6b) **Modes through an OP2**: the whole structure's modes (mounts in the modes, way b) of
     each model written as an OP2 by pyNastran (mm-t-s units, single precision as NASTRAN
     writes them; tests/helpers/op2_files.py) and read by ``read_op2`` with the lowest n
     modes, the modal damping of the structure's modes given per mode: ΔV/V of each
     instability of the beam model, and the fewest modes from which all stay within 0.5 %;
     and the same with the OP2 route's default damping (the base wing's Rayleigh damping
     alone: the mount dampers are not in it).
(6c) **A mount as a beam element**: each model written as a deck (SI) and each flexible
     mount's two CELAS2 hinges replaced by one massless mount beam of length L forward of its
     wing grid (E I / L = the springs' K; ``tests/helpers/bdf_decks.with_mount_beams``), read
     back: every instability against the spring model with its pivots at the beams'
     mid-points (the same model: the difference is rounding) and against the model itself
     (pivots at the wing grid: the beam's mid-point moves them forward by L/2).
(6d) **Propellers on pylons** (tests/data/nastran/pylons.bdf, by hand): its modes by the
     independent frame solver of tests/helpers/frame_fe.py through an OP2 (``mount =
     "on-grid"``); the same deck with the propellers rigid on the wing against the BDF route's
     beam model (the rotors' I11 out, and in).
(4)  **Free structures**: the wingtip model's wing on a body (a fuselage) instead of a clamp —
     free in heave, roll and pitch, or a half aircraft's symmetric (heave, pitch) or
     antisymmetric (roll) freedoms — its free structure's modes written as an OP2 and read with
     ``free=True`` (rigid-body modes left out): the first elastic frequency and every
     instability against the clamped wing's, the body's mass and inertias κ times the wing's.
"""
from __future__ import annotations

import argparse
import sys
import tempfile
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "benchmarks"))
sys.path.insert(0, str(ROOT / "tests"))

from markdown_section import replace_section  # noqa: E402
from modal_convergence import match, name  # noqa: E402

from helpers import frame_fe  # noqa: E402
from helpers.bdf_decks import with_mount_beams  # noqa: E402
from helpers.op2_files import free_free_modes, write_op2, write_op2_arrays  # noqa: E402
from propwhirl.analysis.stability import analyse  # noqa: E402
from propwhirl.cases.ch10_other_wings import (two_propeller_wing,  # noqa: E402
                                              wingtip_propeller_wing)
from propwhirl.engine import single_thread_blas  # noqa: E402
from propwhirl.io.nastran_op2 import read_op2  # noqa: E402
from propwhirl.io.nastran_read import read_bdf  # noqa: E402
from propwhirl.io.nastran_write import write_bdf  # noqa: E402
from propwhirl.model.modal import ModalStructure  # noqa: E402
from propwhirl.model.structure.assembly import wing_structure  # noqa: E402

BEGIN, END = "<!-- nastran-evidence:begin -->", "<!-- nastran-evidence:end -->"
BEAM_LENGTHS = (0.2, 0.1, 0.05, 0.02)
MODES = (4, 5, 6, 8, 10, 12, 16, 20, 30, None)
MODELS = (("wingtip (§10.1)", wingtip_propeller_wing), ("two-propeller (§10.2)",
                                                        two_propeller_wing))


def _cells(ds) -> list[str]:
    return ["—" if d is None else f"{d:+.4f}" for d in ds]


def bdf_table(folder: Path) -> str:
    lines = ["| model | units | " + "instabilities of the model [m/s] | ΔV of the model "
             "read back [m/s] |", "|---|---|---|---|"]
    for label, build in MODELS:
        full = build()
        ref = analyse(full).events
        for units in ("si", "mm-t-s", "in-lbf-s"):
            path = folder / f"m-{units}.bdf"
            deck = write_bdf(full, path, units)
            back = read_bdf(path, units=units, base=full, hubs=deck.hubs)
            got = analyse(back).events
            dv = [None if d is None else d * e.V / 100 for d, e in zip(match(ref, got), ref)]
            lines.append(f"| {label} | {units} | "
                         + ", ".join(f"{name(e)}" for e in ref) + " | "
                         + ", ".join("—" if d is None else f"{d:+.4f}" for d in dv) + " |")
    return "\n".join(lines)


def op2_convergence(folder: Path, full, rayleigh: bool) -> tuple[list, list, str]:
    s, hubs, _ = ModalStructure.with_mounts(full)
    path = write_op2(s, folder / "modes.op2", "mm-t-s")
    wing_grids = [int(g) for g in s.grid_ids[:full.wing.n_nodes]]
    ref = analyse(full).events
    rows = []
    for n in MODES:
        k = s.n_modes if n is None else n
        damping = "rayleigh" if rayleigh else s.damping_ratio[:k]
        model = read_op2(path, units="mm-t-s", base=full, hubs=hubs, wing_grids=wing_grids,
                         n_modes=n, damping=damping, mass_normalised=True)
        rows.append((f"{k}" + (" (all)" if n is None else ""),
                     match(ref, analyse(model).events)))
    need = "—"
    for i in range(len(rows)):
        if all(d is not None and abs(d) <= 0.5 for _, ds in rows[i:] for d in ds):
            need = rows[i][0]
            break
    return ref, rows, need


def op2_table(folder: Path) -> str:
    parts = []
    for label, build in MODELS:
        full = build()
        ref, rows, need = op2_convergence(folder, full, rayleigh=False)
        _, rows_r, need_r = op2_convergence(folder, full, rayleigh=True)
        head = ("| modes kept | " + " | ".join(name(e) for e in ref)
                + " | (Rayleigh damping only) " + " | ".join(name(e) for e in ref) + " |")
        lines = [f"**{label}, its modes through an OP2 (way b)** — ΔV/V [%] of each "
                 f"instability of the beam model; all within 0.5 % from **{need}** modes on "
                 f"with the modes' own damping, from **{need_r}** with the base wing's "
                 "Rayleigh damping alone.", "", head, "|" + "---|" * (2 * len(ref) + 1)]
        for (n, ds), (_, dr) in zip(rows, rows_r):
            lines.append(f"| {n} | " + " | ".join(_cells(ds)) + " | "
                         + " | ".join(_cells(dr)) + " |")
        parts.append("\n".join(lines))
    return "\n\n".join(parts)


def wing_inertia(wing) -> list[float]:
    """The beam wing's rigid-body mass [kg], roll and pitch inertia about the root [kg m²]."""
    M = wing_structure(wing)[0]
    shapes = np.zeros((3, M.shape[0]))
    shapes[0, 0::3] = 1.0
    shapes[1, 0::3], shapes[1, 1::3] = wing.node_y, 1.0
    shapes[2, 2::3] = 1.0
    return [float(r @ M @ r) for r in shapes]


def free_table(folder: Path) -> str:
    full = wingtip_propeller_wing()
    ref = analyse(full).events
    clamped_f = ModalStructure.from_wing(full.wing, n_modes=1).frequencies_hz[0]
    mass, roll, pitch = wing_inertia(full.wing)
    lines = ["| root | κ (body / wing) | rigid-body modes left out | first elastic mode [Hz] | "
             + " | ".join(f"ΔV/V [%] {name(e)}" for e in ref) + " | other instabilities "
             "(m/s) |", "|" + "---|" * (5 + len(ref))]
    lines.append("| clamped | — | — | " + f"{clamped_f:.3f} | " + " | ".join(
        "0" for _ in ref) + " | |")
    for root in ("free", "symmetric", "antisymmetric"):
        for kappa in (1e4, 1e2, 10.0, 1.0):
            ids, xyz, w2, shapes = free_free_modes(full.wing, kappa * mass, kappa * roll,
                                                   kappa * pitch, root)
            path = write_op2_arrays(folder / "free.op2", ids, xyz, w2, shapes, "si")
            notes: list[str] = []
            model = read_op2(path, units="si", base=full, hubs=[1 + full.nodes[0]],
                             wing_grids=list(ids), mount="own", mass_normalised=True,
                             free=True, notes=notes)
            got = analyse(model).events
            ds = match(ref, got)
            matched = {min(range(len(got)), key=lambda j: abs(got[j].V - e.V * (1 + d / 100)))
                       for d, e in zip(ds, ref) if d is not None}
            other = ", ".join(f"{g.kind} {g.V:.1f}" for j, g in enumerate(got)
                              if j not in matched)
            n_rigid = int(np.sum(np.sqrt(np.abs(w2)) / (2 * np.pi) < 0.1))
            lines.append(f"| {root} | {kappa:g} | {n_rigid} | "
                         f"{model.structure.frequencies_hz[0]:.3f} | "
                         + " | ".join("—" if d is None else f"{d:+.2f}" for d in ds)
                         + f" | {other} |")
    return "\n".join(lines)


def springs_at(model, shifts):
    """``model`` with its mounts' stiffness as K (not a frequency) and both pivots of each
    moved by its shift [m] (tests/nastran/test_mount_beam.py has the same)."""
    out = []
    for inst, shift in zip(model.propellers, shifts):
        p = inst.propeller
        K_theta, K_psi = p.stiffness()
        out.append(replace(inst, propeller=replace(
            p, pivot_pitch=p.pivot_pitch + shift, pivot_yaw=p.pivot_yaw + shift,
            K_theta=K_theta, K_psi=K_psi, f_theta=None, f_psi=None)))
    return model.with_(propellers=tuple(out))


def mount_beam_table(folder: Path) -> str:
    lines = ["| model | mount beam L [m] | instabilities of the spring model, pivots at the "
             "beams' mid-points [m/s] | ΔV of the beam deck read back [m/s] | ΔV/V against "
             "the model itself (its pivots at the wing grid, L/2 aft of the mid-point) [%] |", "|---|---|---|---|---|"]
    for label, build in MODELS:
        full = build()
        ref_own = analyse(full).events
        deck = write_bdf(full, folder / "springs.bdf", "si")
        for length in BEAM_LENGTHS:
            text, shifts = with_mount_beams(deck, length)
            path = folder / "beams.bdf"
            path.write_text(text)
            beams = read_bdf(path, units="si", base=full, hubs=deck.hubs)
            got = analyse(beams).events
            ref = analyse(springs_at(full, shifts)).events
            dv = [None if d is None else d * e.V / 100 for d, e in zip(match(ref, got), ref)]
            lines.append(f"| {label} | {length:g} | " + ", ".join(name(e) for e in ref) + " | "
                         + ", ".join("—" if d is None else f"{d:+.1e}" for d in dv) + " | "
                         + ", ".join(f"{name(e)}: " + ("—" if d is None else f"{d:+.2f}")
                                     for d, e in zip(match(ref_own, got), ref_own)) + " |")
    return "\n".join(lines)


PYLON_DECK = ROOT / "tests" / "data" / "nastran" / "pylons.bdf"
PYLON_HUBS = (1001, 1011)


def _on_the_wing(text: str, spin_out: bool) -> str:
    """The pylon deck with each propeller rigid on its wing grid (tests/nastran/test_pylons.py
    has the same), the rotors' I11 out or kept."""
    for k, (wing, y) in enumerate(((5, 1.596), (14, 5.7))):
        text = (text.replace(f"CBAR,{101 + k},2,{wing},{201 + k},1.,0.,0.\n", "")
                .replace(f"GRID,{201 + k},,0.,{y!r},-0.35\n", "")
                .replace(f"RBE2,{301 + k},{201 + k},", f"RBE2,{301 + k},{wing},"))
    text = text.replace(",-0.35\n", ",0.\n")
    return text.replace(",1.548,0.,", ",0.,0.,") if spin_out else text


def _fe_events(folder: Path, deck: Path, base, n_modes: int):
    ids, xyz, w2, shapes = frame_fe.modes(deck, n_modes)
    op2 = write_op2_arrays(folder / "fe.op2", ids, xyz, w2, shapes, "si")
    model = read_op2(op2, units="si", base=base, hubs=list(PYLON_HUBS),
                     wing_grids=list(range(1, 15)), mount="on-grid", mass_normalised=True)
    return analyse(model).events


def pylon_table(folder: Path) -> str:
    base = two_propeller_wing()
    lines = ["| structure | route | instabilities [m/s] | ΔV/V against the beam model [%] |",
             "|---|---|---|---|"]
    for spin_out, label in ((True, "on the wing, rotors' I11 out"),
                            (False, "on the wing, rotors' I11 in")):
        path = folder / "on_wing.bdf"
        path.write_text(_on_the_wing(PYLON_DECK.read_text(), spin_out))
        ref = analyse(read_bdf(path, units="si", base=base, hubs=PYLON_HUBS)).events
        got = _fe_events(folder, path, base, 40)
        lines.append(f"| {label} | BDF → beam model | " + ", ".join(name(e) for e in ref)
                     + " | 0 |")
        lines.append(f"| {label} | FE modes (40) → OP2 | " + ", ".join(name(e) for e in got)
                     + " | " + ", ".join(_cells(match(ref, got))) + " |")
    for n in (10, 20, 30, 40, 60):
        got = _fe_events(folder, PYLON_DECK, base, n)
        lines.append(f"| pylons 0.35 m (the deck) | FE modes ({n}) → OP2 | "
                     + ", ".join(name(e) for e in got) + " | (the BDF route refuses it) |")
    return "\n".join(lines)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--markdown", type=Path, help="write the tables into this page")
    args = parser.parse_args(argv)
    t0 = time.perf_counter()
    with single_thread_blas(), tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        parts = [
            "**(6a) BDF out and in** — every instability of the model, and the change of its "
            "speed after `write_bdf` then `read_bdf` (the engine's crossing tolerance is "
            "0.01 m/s):\n\n" + bdf_table(folder),
            "**(6b) Modes through an OP2**\n\n" + op2_table(folder),
            "**(6c) A mount as a beam element** — each flexible mount's two hinges (CELAS2) "
            "replaced by one massless mount beam of length L forward of its wing grid "
            "(E I / L = K), read back, against the spring model with its pivots at the beams' "
            "mid-points (the crossing tolerance is 0.01 m/s) and against the model itself:"
            "\n\n" + mount_beam_table(folder),
            "**(6d) Propellers on pylons** — tests/data/nastran/pylons.bdf (by hand), its "
            "modes by the frame solver of tests/helpers/frame_fe.py written as an OP2 and read "
            "with `mount = \"on-grid\"`; the same deck with the propellers rigid on the wing "
            "also through the BDF route (the beam model):\n\n" + pylon_table(folder),
            "**(4) Free structures** — the wingtip model's wing on a body instead of a clamp "
            "(κ: the body's mass, roll and pitch inertia over the wing's own), its elastic "
            "modes through an OP2 (`free=True`), against the clamped wing:\n\n"
            + free_table(folder),
        ]
    body = "\n\n".join(parts)
    print(body)
    print(f"\n({time.perf_counter() - t0:.0f} s)", file=sys.stderr)
    if args.markdown:
        replace_section(args.markdown, body, BEGIN, END)
    return 0


if __name__ == "__main__":
    sys.exit(main())
