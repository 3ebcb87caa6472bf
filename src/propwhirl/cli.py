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


def _pairs(name: str, flat: list[float]) -> tuple[list[float], list[float]]:
    if len(flat) < 4 or len(flat) % 2:
        raise InputError(f"{name} = {flat!r} is invalid: must be pairs ETA VALUE (at least two)")
    return flat[0::2], flat[1::2]


def _derivatives(args: argparse.Namespace) -> int:
    import json
    import math

    import numpy as np

    from propwhirl import aero

    if args.chord_table:
        chord = aero.Distribution.tabulated(*_pairs("--chord-table", args.chord_table), "chord")
    elif args.chord_tip is not None:
        chord = aero.Distribution.linear(args.chord, args.chord_tip, args.hub_ratio, "chord")
    elif args.chord is not None:
        chord = args.chord
    else:
        raise InputError("blade chord missing: give --chord, --chord with --chord-tip, "
                         "or --chord-table")
    slope = (aero.Distribution.tabulated(*_pairs("--lift-slope-table", args.lift_slope_table),
                                         "lift_slope") if args.lift_slope_table else None)
    geo = aero.PropellerGeometry(args.blades, args.radius, args.hub_ratio, chord,
                                 lift_slope=slope, reference_chord=args.reference_chord,
                                 aspect_ratio=args.aspect_ratio)
    settings = aero.AeroSettings(
        wake=not args.no_wake, compressibility=not args.no_compressibility,
        aspect_ratio_correction=not args.no_aspect_ratio_correction,
        cnq_sign=args.cnq_sign, method=args.method, quadrature_order=args.quadrature_order)
    sound = None if args.mach is not None else args.speed_of_sound
    if args.blade_angle is not None:
        d = aero.windmilling(geo, args.speed, math.radians(args.blade_angle), sound, args.mach,
                             math.radians(args.zero_lift_angle), args.advance_rule, settings)
    else:
        omega = args.omega if args.omega is not None else args.rpm * math.pi / 30.0
        d = aero.constant_speed(geo, args.speed, omega, sound, args.mach, settings)
    points = [d.at(i) for i in range(np.size(d.airspeed))]
    if args.json:
        print(json.dumps({"aspect_ratio": d.aspect_ratio, "reference_chord": d.reference_chord,
                          "points": points}, indent=2))
        return 0
    rows = [("V [m/s]", "airspeed"), ("Omega [RPM]", "omega"), ("mu = V/(Omega R)",
            "advance_ratio"), ("Mach", "mach"), ("cut-off applied", "cutoff_applied")]
    rows += [(n, n) for n in aero.DERIVATIVE_NAMES]
    print(f"Houbolt-Reed derivatives (method {args.method}, wake {settings.wake}, "
          f"compressibility {settings.compressibility}, aspect ratio A = {d.aspect_ratio:.4g} "
          f"{'on' if settings.aspect_ratio_correction else 'off'}, C_nq sign {args.cnq_sign})")
    for label, key in rows:
        vals = []
        for p in points:
            x = p[key]
            if isinstance(x, bool):
                vals.append(f"{'yes' if x else 'no':>12s}")
            else:
                vals.append(f"{x * (30.0 / math.pi if key == 'omega' else 1.0):12.6g}")
        print(f"{label:18s}" + "".join(vals))
    return 0


def _add_derivatives(sub) -> None:
    p = sub.add_parser("derivatives", help="Houbolt-Reed propeller aerodynamic derivatives "
                       "(chapter 4) for one propeller and operating point (SI units)")
    g = p.add_argument_group("propeller")
    g.add_argument("--blades", type=int, required=True, help="number of blades (>= 3)")
    g.add_argument("--radius", type=float, required=True, help="tip radius R [m]")
    g.add_argument("--hub-ratio", type=float, default=0.0, help="r0/R in [0, 1) (default 0)")
    g.add_argument("--chord", type=float, help="constant chord [m] (root chord with --chord-tip)")
    g.add_argument("--chord-tip", type=float, help="tip chord [m]: linear taper from the hub")
    g.add_argument("--chord-table", type=float, nargs="+", metavar="ETA_C",
                   help="tabulated chord: pairs eta c[m], eta increasing")
    g.add_argument("--lift-slope-table", type=float, nargs="+", metavar="ETA_A",
                   help="tabulated lift-curve slope: pairs eta a[1/rad] (default 2 pi)")
    g.add_argument("--reference-chord", type=float, help="c0 [m] (default c at 0.75R)")
    g.add_argument("--aspect-ratio", type=float, help="blade aspect ratio A (default eq. 4.21)")
    o = p.add_argument_group("operating point")
    o.add_argument("--speed", type=float, nargs="+", required=True, help="airspeed(s) V [m/s]")
    w = o.add_mutually_exclusive_group(required=True)
    w.add_argument("--rpm", type=float, help="constant rotational speed [rev/min]")
    w.add_argument("--omega", type=float, help="constant rotational speed [rad/s]")
    w.add_argument("--blade-angle", type=float, metavar="DEG",
                   help="fixed-pitch windmilling at beta_0.75R [deg]: Omega from the advance ratio")
    o.add_argument("--zero-lift-angle", type=float, default=-3.0, metavar="DEG",
                   help="alpha_0L for --blade-angle [deg] (default -3)")
    o.add_argument("--advance-rule", choices=("thesis_eq_9_1", "blade_element"),
                   default="thesis_eq_9_1", help="beta -> advance ratio relation (default: eq. 9.1 "
                   "mu = tan(beta + alpha_0L); blade_element: mu = 0.75 tan(beta - alpha_0L))")
    o.add_argument("--speed-of-sound", type=float, default=340.294,
                   help="[m/s] (default 340.294, ISA sea level)")
    o.add_argument("--mach", type=float, help="flight Mach number instead of --speed-of-sound")
    s = p.add_argument_group("model")
    s.add_argument("--no-wake", action="store_true", help="F = 1, G = 0")
    s.add_argument("--no-compressibility", action="store_true", help="M_r = 0")
    s.add_argument("--no-aspect-ratio-correction", action="store_true", help="A'/(A'+2) = 1")
    s.add_argument("--cnq-sign", choices=("thesis", "rodden_rose"), default="thesis")
    s.add_argument("--method", choices=("houbolt_reed", "bennett_bland"), default="houbolt_reed")
    s.add_argument("--quadrature-order", type=int, default=32)
    p.add_argument("--json", action="store_true", help="print JSON instead of a table")
    p.set_defaults(func=_derivatives)


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="propwhirl",
        description="Wing flutter, propeller whirl flutter and divergence of flexible wings "
        "with flexibly mounted propellers (SI units).",
    )
    sub = parser.add_subparsers(dest="command", required=True)
    _add_run(sub)
    _add_reproduce(sub)
    _add_derivatives(sub)
    return parser


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return args.func(args)
    except InputError as exc:
        print(f"propwhirl: error: {exc}", file=sys.stderr)
        return 2
