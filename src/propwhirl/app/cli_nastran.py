"""The NASTRAN commands of the command line (:mod:`propwhirl.app.cli`): a beam model from a
BDF and a beam model as a BDF (docs/modal-structures.md, "NASTRAN bulk data").

    propwhirl import MODEL.bdf --out MODEL.toml --units si|mm-t-s|in-lbf-s --base BASE.toml
                    [--hubs GRID [GRID ...]]
    propwhirl import MODES.op2 --out MODAL.toml --units ... --base BASE.toml --hubs GRID ...
                    --wing-grids GRID GRID ... [--mount on-grid|own] [--modes N]
                    [--damping rayleigh|ZETA] [--subcase N] [--free [--keep-rigid] [--rigid-below HZ]]
                    [--mass-normalised]
    propwhirl export MODEL --out MODEL.bdf [--units si|mm-t-s|in-lbf-s]

``import`` reads the stick and its propellers' masses and mounts from the BDF
(:func:`propwhirl.io.nastran_read.read_bdf`; needs the ``nastran`` extra, which needs numpy < 2:
install it in an environment of its own) and what a BDF cannot say — the flight condition, the
chords and aerodynamics, the propellers' rotors and aerodynamics — from BASE, a model file;
``--hubs`` names the hub grid of each of BASE's installations, in order.  It writes MODEL.toml
only when the whole deck was read (atomically; any problem is one line naming the file, the
card and its id, exit code 2).  ``import`` of an OP2 (a file ending in .op2) reads a
SOL 103's eigenvectors and grids into a modal model (:func:`propwhirl.io.nastran_op2.read_op2`;
the same extra) and writes it as a modal model file (MODAL.toml and MODAL.modes.npz).
A swept stick is read as a modal model (its straight beam's modes on its swept grids) and
written as a modal model file, as an OP2's.  ``export`` writes a model (a file or a case name) as a SOL 103
deck (:func:`propwhirl.io.nastran_write.write_bdf`; no extra needed) and prints the hub grids
to give ``import``.
"""
from __future__ import annotations

import argparse
import os

from propwhirl.app.cli_common import (check_outputs, echo, lazy, load_model, model_or_case, plain,
                                       print_notes)
from propwhirl.validate import InputError


def units_help() -> str:
    """The help text of ``--units``: every unit system with its description."""
    from propwhirl.io.nastran import UNIT_SYSTEMS  # lazy: io loads the model files

    return "the deck's units: " + "; ".join(f"{u.name} ({u.description})"
                                            for u in UNIT_SYSTEMS.values())


def _import(args: argparse.Namespace) -> int:
    from propwhirl import io  # lazy: model files, only when the command runs
    from propwhirl.io import nastran_read  # lazy: model files, only when the command runs
    from propwhirl.model.systems import PropellerWing  # lazy: the models

    nastran_read.require_pynastran()
    check_outputs(out=args.out)
    _not_an_input(args.out, {"MODEL.bdf": args.bdf, "--base": args.base})
    if args.bdf.lower().endswith(".op2"):
        return _import_op2(args)
    for flag, value in (("--wing-grids", args.wing_grids), ("--modes", args.modes),
                        ("--subcase", args.subcase), ("--rigid-below", args.rigid_below),
                        ("--free", args.free or None),
                        ("--keep-rigid", args.keep_rigid or None),
                        ("--mass-normalised", args.mass_normalised or None)):
        if value is not None:
            raise InputError(f"{flag} is for an OP2's modes: {args.bdf} is read as a BDF")
    if args.base is None:
        raise InputError(f"{args.bdf}: a BDF holds the structure only: give --base MODEL.toml "
                         "for the flight condition, the chords and aerodynamics, and the "
                         "propellers' rotors and aerodynamics")
    base = load_model(args.base)
    if not isinstance(base, PropellerWing):
        raise InputError(f"--base {args.base} holds a {type(base).__name__}: it must be a wing "
                         "with propellers (type \"propeller-wing\")")
    notes: list[str] = []
    model = nastran_read.read_bdf(args.bdf, units=args.units, base=base, hubs=args.hubs or (),
                                  notes=notes, base_name=f"--base {args.base}")
    if not isinstance(model, PropellerWing):        # a swept stick: its modes, a modal model
        from propwhirl.io import modal_files  # lazy: only when the command runs

        npz = args.out.removesuffix(".toml") + ".modes.npz"
        _not_an_input(npz, {"MODEL.bdf": args.bdf, "--base": args.base})
        toml, npz_path = modal_files.save_modal_model(model, args.out)
        print_notes(notes)
        s = model.structure
        echo(f"wrote {toml} and {npz_path.name} (modal model of the swept stick: "
             f"{s.n_modes} modes, {s.frequencies_hz[0]:.4g}-{s.frequencies_hz[-1]:.4g} Hz, "
             f"{s.grid_ids.size} grids; read in {args.units} units)")
        return 0
    io.save_model(model, args.out)
    print_notes(notes)
    hubs = f"; propellers at hub GRID {', '.join(map(str, args.hubs))}" if args.hubs else ""
    echo(f"wrote {args.out} (wing: {model.wing.element_count} elements, semi-span "
         f"{model.wing.semi_span:g} m{hubs}; read in {args.units} units)")
    return 0


def _damping(text: str):
    """--damping: "rayleigh" or a ratio (the reader checks its range)."""
    if text == "rayleigh":
        return text
    try:
        return float(text)
    except ValueError:
        raise InputError(f"--damping {text} is invalid: must be 'rayleigh' or a modal damping "
                         "ratio in [0, 1)") from None


def _import_op2(args: argparse.Namespace) -> int:
    from propwhirl.io import modal_files, nastran_op2  # lazy: only when the command runs
    from propwhirl.model.systems import PropellerWing  # lazy: the models

    if args.base is None:
        raise InputError(f"{args.bdf}: an OP2 holds the modes only: give --base MODEL.toml for "
                         "the strips, the flight condition and the propellers")
    npz = args.out.removesuffix(".toml") + ".modes.npz"
    _not_an_input(npz, {"MODES.op2": args.bdf, "--base": args.base})
    base = load_model(args.base)
    if not isinstance(base, PropellerWing):
        raise InputError(f"--base {args.base} holds a {type(base).__name__}: it must be a wing "
                         "with propellers (type \"propeller-wing\")")
    notes: list[str] = []
    free = {} if args.rigid_below is None else {"rigid_body_hz": args.rigid_below}
    if args.keep_rigid and not args.free:
        raise InputError("--keep-rigid keeps a free structure's plunge and roll rigid-body "
                         "modes: give --free too")
    if args.rigid_below is not None and not args.free:
        raise InputError("--rigid-below is the threshold of a free structure's rigid-body "
                         "modes: give --free too")
    model = nastran_op2.read_op2(
        args.bdf, units=args.units, base=base, hubs=args.hubs or (),
        wing_grids=args.wing_grids or (), mount=args.mount, n_modes=args.modes,
        damping=_damping(args.damping), subcase=args.subcase, free=args.free,
        mass_normalised=args.mass_normalised, notes=notes, keep_rigid=args.keep_rigid, **free)
    toml, npz_path = modal_files.save_modal_model(model, args.out)
    print_notes(notes)
    s = model.structure
    echo(f"wrote {toml} and {npz_path.name} (modal model: {s.n_modes} modes, "
         f"{s.frequencies_hz[0]:.4g}-{s.frequencies_hz[-1]:.4g} Hz, {s.grid_ids.size} grids; "
         f"propellers {args.mount} at hub GRID {', '.join(map(str, args.hubs or ()))}; read "
         f"in {args.units} units)")
    return 0


def _export(args: argparse.Namespace) -> int:
    from propwhirl.io import nastran_write  # lazy: model files, only when the command runs

    check_outputs(out=args.out, model=args.model)
    model = model_or_case(args.model, "export")
    deck = nastran_write.write_bdf(model, args.out, args.units)
    hubs = f" --hubs {' '.join(map(str, deck.hubs))}" if deck.hubs else ""
    echo(f"wrote {args.out} (NASTRAN SOL 103 deck, {deck.units} units); read it back with: "
         f"propwhirl import {args.out} --out MODEL.toml --units {deck.units} --base "
         f"{args.model if args.model.endswith('.toml') else 'BASE.toml'}{hubs}")
    return 0


def _not_an_input(out: str, inputs: dict[str, str | None]) -> None:
    """--out must be none of the files read (it would be replaced before being read)."""
    def key(path: str) -> str:
        return os.path.normcase(os.path.realpath(os.path.abspath(path)))

    for label, path in inputs.items():
        if path is not None and key(path) == key(out):
            raise InputError(f"--out {out} is {label} {path}: give another path")


def add_commands(sub) -> None:
    """Register ``import`` and ``export`` on the CLI's subparsers."""
    p = sub.add_parser("import", help="a beam model from a NASTRAN BDF (a straight stick, its "
                       "propellers' masses and mounts), or a modal model from an OP2's modes, "
                       "completed by a base model file",
                       description=plain(__doc__.split("\n\n")[2]))
    p.add_argument("bdf", metavar="MODEL.bdf", help="the NASTRAN bulk data file, or an OP2 "
                   "(MODES.op2: a SOL 103's eigenvectors and grids)")
    p.add_argument("--out", required=True, metavar="MODEL.toml", help="the model file to write")
    p.add_argument("--units", metavar="UNITS", help=lazy(__name__, "units_help")
                   + " (required: NASTRAN has none)")
    p.add_argument("--base", metavar="BASE.toml", help="model file giving what a BDF cannot: "
                   "flight condition, chords and aerodynamics, the propellers' rotors and "
                   "aerodynamics (its structure is replaced by the BDF's)")
    p.add_argument("--hubs", nargs="+", type=int, metavar="GRID", help="the hub grid of each of "
                   "BASE's installations, in their order (the grid with the rotor's CONM2)")
    p.add_argument("--wing-grids", nargs="+", type=int, metavar="GRID", help="an OP2: the "
                   "wing's reference-axis grids, root to tip, the strips are splined to")
    p.add_argument("--mount", choices=("on-grid", "own"), default="on-grid", help="an OP2: "
                   "the propellers rigid on their hub grids, mass and mount in the modes "
                   "(on-grid, default), or on BASE's own mounts (own: the bare wing's modes)")
    p.add_argument("--modes", type=int, metavar="N", help="an OP2: keep the lowest N elastic "
                   "modes (default all)")
    p.add_argument("--damping", default="rayleigh", metavar="rayleigh|ZETA", help="an OP2: "
                   "modal damping, BASE's Rayleigh damping (default) or one ratio")
    p.add_argument("--subcase", type=int, metavar="N", help="an OP2: the subcase (default "
                   "the only one)")
    p.add_argument("--free", action="store_true", help="an OP2: the structure is free; its "
                   "rigid-body modes are left out (docs/modal-structures.md)")
    p.add_argument("--keep-rigid", action="store_true", help="with --free: keep the "
                   "rigid-body modes, each a plunge or a roll (a rigid pitch needs a tail, "
                   "which the command line does not give: read_op2(..., surfaces=...) or a "
                   "modal model file's [[surfaces]]; a yaw is refused: no fin)")
    p.add_argument("--rigid-below", type=float, metavar="HZ", help="with --free: the modes "
                   "below HZ are rigid-body modes (default 0.1)")
    p.add_argument("--mass-normalised", action="store_true", help="an OP2 without an "
                   "eigenvalue table (LAMA): its eigenvectors are mass-normalised")
    p.set_defaults(func=_import)
    p = sub.add_parser("export", help="a beam model as a NASTRAN SOL 103 deck (BDF)",
                       description=plain(__doc__.split("\n\n")[2]))
    p.add_argument("model", metavar="MODEL", help="a model file (.toml) or a case name")
    p.add_argument("--out", required=True, metavar="MODEL.bdf", help="the BDF to write")
    p.add_argument("--units", default="si", metavar="UNITS", help=lazy(__name__, "units_help")
                   + " (default si)")
    p.set_defaults(func=_export)
