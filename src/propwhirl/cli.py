"""Command-line interface: `propwhirl <command> ...` (also `python -m propwhirl`).

Commands
  run          the main analysis (wingtip-mounted propeller wing), plots to --out
  reproduce    recompute the thesis's numbers and compare (ids from thesis_values.toml)
  derivatives  Houbolt–Reed propeller aerodynamic derivatives for one operating point
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

from propwhirl.validate import InputError


def _reproduce(args: argparse.Namespace) -> int:
    from propwhirl import reproduce

    records = reproduce.run(args.only, processes=args.processes)
    print(reproduce.format_table(records))
    if args.json:
        Path(args.json).write_text(reproduce.to_json(records))
        print(f"wrote {args.json}")
    return 0


def _add_reproduce(sub) -> None:
    p = sub.add_parser("reproduce", help="recompute the thesis's numbers and compare")
    p.add_argument("--only", nargs="*", metavar="PREFIX", help="id prefixes, e.g. t7.2 t9")
    p.add_argument("--json", metavar="FILE", help="also write the records as JSON")
    p.add_argument("--processes", type=int, default=1, help="worker processes (default 1)")
    p.set_defaults(func=_reproduce)


def _run(args: argparse.Namespace) -> int:
    from propwhirl import mainjob

    return mainjob.main(Path(args.out))


def _add_run(sub) -> None:
    p = sub.add_parser("run", help="main analysis of the thesis's headline configuration")
    p.add_argument("--out", default="out", help="output folder for plots and tables")
    p.set_defaults(func=_run)


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="propwhirl",
        description="Wing flutter, propeller whirl flutter and divergence of flexible wings "
        "with flexibly mounted propellers (SI units).",
    )
    sub = parser.add_subparsers(dest="command", required=True)
    _add_run(sub)
    _add_reproduce(sub)
    return parser


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return args.func(args)
    except InputError as exc:
        print(f"propwhirl: error: {exc}", file=sys.stderr)
        return 2
