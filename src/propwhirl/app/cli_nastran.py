"""The NASTRAN commands of the command line (:mod:`propwhirl.app.cli`): a beam model from a
BDF and a beam model as a BDF (docs/modal-structures.md, "NASTRAN bulk data").

    propwhirl import MODEL.bdf --out MODEL.toml --units si|mm-t-s|in-lbf-s --base BASE.toml
                    [--hubs GRID [GRID ...]]
    propwhirl export MODEL --out MODEL.bdf [--units si|mm-t-s|in-lbf-s]

``import`` reads the stick and its propellers' masses and mounts from the BDF
(:func:`propwhirl.io.nastran_read.read_bdf`; needs the ``nastran`` extra, which needs numpy < 2:
install it in an environment of its own) and what a BDF cannot say — the flight condition, the
chords and aerodynamics, the propellers' rotors and aerodynamics — from BASE, a model file;
``--hubs`` names the hub grid of each of BASE's installations, in order.  It writes MODEL.toml
only when the whole deck was read (atomically; any problem is one line naming the file, the
card and its id, exit code 2).  ``export`` writes a model (a file or a case name) as a SOL 103
deck (:func:`propwhirl.io.nastran_write.write_bdf`; no extra needed) and prints the hub grids
to give ``import``.
"""
from __future__ import annotations

import argparse
import os

from propwhirl.app.cli_common import (check_outputs, echo, load_model, model_or_case,
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
    io.save_model(model, args.out)
    print_notes(notes)
    hubs = f"; propellers at hub GRID {', '.join(map(str, args.hubs))}" if args.hubs else ""
    echo(f"wrote {args.out} (wing: {model.wing.element_count} elements, semi-span "
         f"{model.wing.semi_span:g} m{hubs}; read in {args.units} units)")
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
                       "propellers' masses and mounts), completed by a base model file",
                       description=__doc__.split("\n\n")[2])
    p.add_argument("bdf", metavar="MODEL.bdf", help="the NASTRAN bulk data file")
    p.add_argument("--out", required=True, metavar="MODEL.toml", help="the model file to write")
    p.add_argument("--units", metavar="UNITS", help=units_help() + " (required: NASTRAN has none)")
    p.add_argument("--base", metavar="BASE.toml", help="model file giving what a BDF cannot: "
                   "flight condition, chords and aerodynamics, the propellers' rotors and "
                   "aerodynamics (its structure is replaced by the BDF's)")
    p.add_argument("--hubs", nargs="+", type=int, metavar="GRID", help="the hub grid of each of "
                   "BASE's installations, in their order (the grid with the rotor's CONM2)")
    p.set_defaults(func=_import)
    p = sub.add_parser("export", help="a beam model as a NASTRAN SOL 103 deck (BDF)",
                       description=__doc__.split("\n\n")[2])
    p.add_argument("model", metavar="MODEL", help="a model file (.toml) or a case name")
    p.add_argument("--out", required=True, metavar="MODEL.bdf", help="the BDF to write")
    p.add_argument("--units", default="si", metavar="UNITS", help=units_help() + " (default si)")
    p.set_defaults(func=_export)
