"""Command-line interface: `propwhirl <command> ...` (also `python -m propwhirl`).

Commands
  run          the main analysis (wingtip-mounted propeller wing), plots to --out
  reproduce    recompute the thesis's numbers and compare (ids from thesis_values.toml)
  derivatives  Houbolt–Reed propeller aerodynamic derivatives for one operating point
  analyse      stability analysis of a TOML model file (instabilities, V-g-f plot/JSON/CSV)
  modes        in-vacuo modes of a model file, with the thesis's names
  campbell     frequencies against propeller RPM (Campbell diagram) of a model file
  sweep        critical speed of a model (file or case) against one parameter path
  map          critical speed of a model over two parameter paths (contour map)
  case         export a model of the thesis's case library as a TOML model file
  upgrade-model  rewrite a model file of an older format version in the current one
  import       a beam model from a NASTRAN bulk data file (BDF), or a modal model from an OP2's
               modes, completed by a base model file
  export       a beam model as a NASTRAN SOL 103 deck (BDF)
  boundary     stability boundary in a plane of two parameters (continuation)
  clearance    clearance to factor x V_D (exit code 0 cleared, 1 not cleared)
  sensitivity  sensitivities of the critical speed to the model's parameters, ranked
  docs         the installed documentation (validation, errata, model-file reference, ...)

Bad input (a missing or unreadable file, bad TOML, an unknown field, an invalid value, an
option that cannot be honoured, two outputs on one file) is reported as one line
``propwhirl: error: ...`` on stderr with exit code 2, before any analysis starts.  A study
(``sweep``, ``map``) whose every point failed exits with code 2 too (one line: the count and
the first message; --json/--csv are still written with each point's error); one with some
failed points exits with code 0 (a warning on stderr lists them, column error holds them).
Output piped into a reader that stops early (``| head``) ends quietly with exit code 141
(128 + SIGPIPE).
``propwhirl --version`` prints the version.
"""
from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path

from propwhirl import documents
from propwhirl import limits
from propwhirl import fileio
from propwhirl import progress
from propwhirl import validate as v
from propwhirl.app import cli_certify, cli_design, cli_nastran, cli_studies, execution_options
from propwhirl.app.cli_common import (LazyHelpFormatter, check_outputs, echo, lazy, load_model,
                                      print_notes, speed_grid)
from propwhirl.cases import registry
from propwhirl.certification import FACTOR_CFR23, FACTOR_CS25, FACTOR_RANGE, required_speed
from propwhirl.validate import InputError


def _reproduce(args: argparse.Namespace) -> int:
    from propwhirl.reproduce import harness as reproduce  # lazy: the reproduction

    check_outputs(json=args.json)
    if args.only:                   # a prefix that selects nothing: refused, not an empty table
        ids = [r.id for r in reproduce.load_references()]
        unknown = [o for o in args.only if not any(i.startswith(o) for i in ids)]
        if unknown:
            tables = sorted({i.split("/")[0] for i in ids})
            raise InputError(f"--only {' '.join(unknown)}: no id of the thesis's values starts "
                             f"with {'it' if len(unknown) == 1 else 'them'} (the ids start with "
                             f"{', '.join(tables)})")
    cp = execution_options.checkpoint(args, args.json)
    records = reproduce.run(args.only, **execution_options.run_options(args), checkpoint=cp)
    print(reproduce.format_table(records))
    if args.json:
        reproduce.Records(tuple(records)).save(args.json)
        print(f"wrote {args.json}")
    execution_options.finish(cp)
    return 0


def _add_reproduce(sub) -> None:
    p = sub.add_parser("reproduce", help="recompute the thesis's numbers and compare")
    p.add_argument("--only", nargs="*", metavar="PREFIX", help="id prefixes, e.g. t7.2 t9")
    p.add_argument("--json", metavar="FILE", help="also write the records as JSON (the finished "
                   f"cases are kept in FILE{execution_options.PARTIAL_SUFFIX} while it runs)")
    execution_options.add(p)
    p.set_defaults(func=_reproduce)


def _run(args: argparse.Namespace) -> int:
    from propwhirl.app import run as mainjob  # lazy: the main job

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

    from propwhirl.model.propellers import propeller_aero as aero  # lazy: models

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
    sound = None if args.mach is not None else _speed_of_sound(args)
    if args.blade_angle is not None:
        d = aero.windmilling(geo, args.speed, math.radians(args.blade_angle), sound, args.mach,
                             math.radians(args.zero_lift_angle), args.advance_rule, settings)
    else:
        omega = args.omega if args.omega is not None else args.rpm * math.pi / 30.0
        d = aero.constant_speed(geo, args.speed, omega, sound, args.mach, settings)
    points = [d.at(i) for i in range(np.size(d.airspeed))]
    for note in aero.validity_warnings(d):
        print(f"propwhirl: warning: {note}", file=sys.stderr)
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


def _speed_of_sound(args: argparse.Namespace) -> float:
    """--speed-of-sound, or the ISA value at --altitude-m / --altitude-ft, or the one default."""
    from propwhirl.model import atmosphere  # lazy: models
    from propwhirl.model.flight import DEFAULT_SPEED_OF_SOUND  # lazy: models

    if args.altitude_m is not None:
        v.in_range("--altitude-m", args.altitude_m, atmosphere.MIN_ALTITUDE,
                   atmosphere.MAX_ALTITUDE, "m")
        return atmosphere.speed_of_sound(args.altitude_m)
    if args.altitude_ft is not None:
        v.in_range("--altitude-ft", args.altitude_ft, atmosphere.MIN_ALTITUDE_FT,
                   atmosphere.MAX_ALTITUDE_FT, "ft")
        return atmosphere.isa(altitude_ft=args.altitude_ft).speed_of_sound
    return DEFAULT_SPEED_OF_SOUND if args.speed_of_sound is None else args.speed_of_sound


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
    air = o.add_mutually_exclusive_group()
    air.add_argument("--speed-of-sound", type=float, help="[m/s] (default "
                     + lazy("propwhirl.model.flight", "DEFAULT_SPEED_OF_SOUND", ".2f")
                     + ", ISA at 8000 ft: propwhirl's one default)")
    air.add_argument("--altitude-m", type=float, metavar="M",
                     help="ISA altitude [m]: the standard atmosphere's speed of sound")
    air.add_argument("--altitude-ft", type=float, metavar="FT", help="ISA altitude [ft]")
    air.add_argument("--mach", type=float, help="flight Mach number instead of a speed of sound")
    s = p.add_argument_group("model")
    s.add_argument("--no-wake", action="store_true", help="F = 1, G = 0")
    s.add_argument("--no-compressibility", action="store_true", help="M_r = 0")
    s.add_argument("--no-aspect-ratio-correction", action="store_true", help="A'/(A'+2) = 1")
    s.add_argument("--cnq-sign", choices=("thesis", "rodden_rose"), default="thesis")
    s.add_argument("--method", choices=("houbolt_reed", "bennett_bland"), default="houbolt_reed")
    s.add_argument("--quadrature-order", type=int, default=32)
    p.add_argument("--json", action="store_true", help="print JSON instead of a table")
    p.set_defaults(func=_derivatives)


# ----------------------------------------------------------------------------- model files
def _analyse(args: argparse.Namespace) -> int:
    from propwhirl import io  # lazy: model files
    from propwhirl.analysis.reduced import choose_method  # lazy: analyses
    from propwhirl.analysis.stability import analyse  # lazy: analyses

    check_outputs(json=args.json, csv=args.csv, plot=args.plot, summary_csv=args.summary_csv,
                  events_csv=args.events_csv, animate=args.animate, plot_shape=args.plot_shape,
                  model=args.model)
    if args.plot_modes is not None:          # before the analysis, not when plotting

        v.integer_at_least("--plot-modes", args.plot_modes, 1)
        if not (args.plot or args.summary):
            raise InputError(f"--plot-modes {args.plot_modes} needs --plot or --summary (the "
                             "number of modes they show)")
    V_req = _analyse_required_speed(args)
    model = load_model(args.model, "analyse")
    speeds = speed_grid(*args.speeds) if args.speeds else None
    if V_req is not None:                  # the grid reaches beyond factor x V_D, as clearance's
        from propwhirl.studies.clearance import clearance_speeds  # lazy: studies

        speeds = clearance_speeds(model, V_req, speeds)
    notice = None if args.quiet else limits.analysis_notice(model,
                                                            choose_method(model, args.method))
    if notice:                             # a long one is announced before the work (issue 20.9)
        print(f"propwhirl: estimate: {notice}", file=sys.stderr)
    with progress.spinner(f"analysing {limits.printable(model.name)}", quiet=args.quiet) as spin:
        a = analyse(model, speeds, vgf=True, method=args.method,
                    progress=spin.stage("doublet-lattice AICs"))
    echo(a.summary())
    st = a.sweep.stats
    if "reduced_L" in st:                 # a strip wing's reduced model (analysis/reduced)
        echo(f"  method: reduced ({st['reduced_states']} of {model.dof_map().n_states} states:"
              f" {st['reduced_r']} Ritz vectors, {st['reduced_L']} lag states); "
              f"{a.criticals.stats.get('corrected', 0)} of {len(a.criticals.points)} crossings "
              "converged on the full-order model")
    elif "reduced_states" in st:           # a DLM wing's modal Roger state space (modal_dlm)
        echo(f"  method: reduced (the Roger state space on {st['reduced_r']} in-vacuo modes, "
             f"{st['reduced_states']} states); its crossings converged by the p-k method on Q(k)")
    if V_req is not None:                  # the summary's last line (issue 25.5)
        from propwhirl.analysis.margin import speed_margin  # lazy: analyses

        echo("  " + speed_margin(a, args.vd, args.factor, describe=a.describe).format())
    for note in a.warnings:
        print(f"propwhirl: warning: {limits.printable(note)}", file=sys.stderr)
    if args.json:
        a.save(args.json)
        print(f"wrote {args.json}")
    if args.csv:
        io.write_vgf_csv(a, args.csv)
        print(f"wrote {args.csv}")
    if args.summary:
        echo("\n" + a.flutter_summary().format(a.modes_of_interest(8 if args.plot_modes is None else args.plot_modes)))
    for path, write in ((args.summary_csv, a.flutter_summary().to_csv),
                        (args.events_csv, a.events_csv)):
        if path:
            write(path)
            print(f"wrote {path}")
    if args.plot:
        from propwhirl.app import plots  # lazy: figures

        req = None if V_req is None else plots.VgfRequirements(args.vd, V_req)
        # the analysis's own speeds (analysed with vgf=True), Hermite curves between them: no
        # second sweep (issue 35 item 5: it tripled the run time)
        plots.vgf(a, None, n_modes=args.plot_modes, path=args.plot, requirements=req,
                  hermite=True)
        print(f"wrote {args.plot}")
    if args.plot_shape and a.critical is not None:    # the critical mode's shape
        from propwhirl.app import plots  # lazy: figures

        plots.event_mode_shape(a, a.critical, path=args.plot_shape)
        print(f"wrote {args.plot_shape}")
    elif args.plot_shape:
        print(f"propwhirl: warning: no instability in the speed range: --plot-shape "
              f"{args.plot_shape} not written", file=sys.stderr)
    if args.animate and a.critical is not None:
        from propwhirl.app import plots  # lazy: figures

        print(f"wrote {plots.animate_event(a, a.critical, args.animate)}")
    elif args.animate:
        print(f"propwhirl: warning: no instability in the speed range: --animate {args.animate} "
              "not written", file=sys.stderr)
    return 0


def _analyse_required_speed(args: argparse.Namespace) -> float | None:
    """factor x V_D [m/s] of ``analyse --vd V [--factor F]`` (None without --vd), checked
    before the work: --factor needs --vd."""

    if args.vd is None:
        if args.factor is not None:
            raise InputError(f"--factor {args.factor:g} needs --vd (the design dive speed V_D "
                             "[m/s] it multiplies)")
        return None
    if args.factor is None:
        args.factor = FACTOR_CS25
    return required_speed(args.vd, args.factor, vd_name="--vd", factor_name="--factor")[0]


def _add_analyse(sub) -> None:
    p = sub.add_parser("analyse", help="stability analysis of a TOML model file")
    p.add_argument("model", metavar="MODEL.toml", help="model file (see `propwhirl case`)")
    p.add_argument("--speeds", nargs=3, type=float, metavar=("START", "STOP", "STEP"),
                   help="initial airspeed grid [m/s] (default: the model file's "
                   "flight.speed_range_m_per_s; refined automatically)")
    p.add_argument("--json", metavar="OUT", help="write the analysis as JSON")
    p.add_argument("--csv", metavar="OUT", help="write the V-g-f table as CSV")
    p.add_argument("--summary", action="store_true", help="print the flutter summary (V, k, "
                   "zeta, g, f, density, Mach) of the modes with an event and the lowest N")
    p.add_argument("--summary-csv", metavar="OUT", help="write the flutter summary of every mode")
    p.add_argument("--events-csv", metavar="OUT", help="write the events with each propeller's "
                   "participation as CSV")
    p.add_argument("--plot", metavar="PNG", help="write the V-g-f plot: the analysis's own "
                   "speeds (dots) and cubic Hermite curves between them from the exact slopes, "
                   "no second sweep; with --vd, V_D and factor x V_D drawn")
    p.add_argument("--plot-modes", type=int, default=None, metavar="N",
                   help="at most N >= 1 modes in the plot (default: the modes that matter) and "
                        "the lowest N in --summary (default 8); only with --plot or --summary "
                        "(a count: the critical mode's shape is --plot-shape)")
    p.add_argument("--plot-shape", metavar="PNG", help="write the critical mode's shape: the "
                   "wing's h and alpha along the span and each propeller's theta-psi orbit "
                   "(plots.event_mode_shape; --plot-modes is a count of V-g-f curves, not shapes)")
    p.add_argument("--animate", metavar="GIF", help="write a GIF of the critical mode")
    p.add_argument("--method", choices=("auto", "dense", "reduced", "pk"), default="auto",
                   help="dense: every root of the full-order model (the reference); reduced: "
                        "a reduced-order model, crossings converged on the full order; pk: the "
                        "p-k method with the exact Theodorsen function (frequency domain); "
                        "auto (default): reduced for a wing, kept where every crossing converged "
                        "on the full order, else dense; its V-g-f table holds the modes below "
                        "the reduction's cut-off (dense: every mode)")
    p.add_argument("--quiet", action="store_true", help="no progress on stderr (by default a "
                   f"spinner on a terminal, else a line every {progress.INTERVAL:g} s; nothing in "
                   f"the first {progress.DELAY:g} s)")
    p.add_argument("--vd", type=float, default=None, metavar="V", help="design dive speed V_D "
                   "[m/s]: the summary ends with the margin of the critical instability to "
                   "factor x V_D [m/s and %%] and the least damping g = 2 zeta below it (the "
                   "speeds reach beyond factor x V_D); the exit code stays 0: `propwhirl "
                   "clearance` and `propwhirl certify` give the pass/fail exit code")
    p.add_argument("--factor", type=float, default=None, metavar="F", help="the required "
                   f"speed's factor on --vd, in [{FACTOR_RANGE[0]:g}, {FACTOR_RANGE[1]:g}]: "
                   f"{FACTOR_CS25:g} (CS/FAR 25.629, default) or {FACTOR_CFR23:g} (14 CFR "
                   "23.629); only with --vd")
    p.set_defaults(func=_analyse)


def _modes(args: argparse.Namespace) -> int:
    import numpy as np

    from propwhirl.analysis.naming import kinetic_energy_shares  # lazy: analyses
    from propwhirl.analysis.vibration import label_modes, model_modes  # lazy: analyses

    model = load_model(args.model, "modes")
    count = v.integer_at_least("--count", args.count, 1)
    modes, M = model_modes(model)
    dm = model.dof_map()
    modal = "modal" in (found := dm.groups())          # a modal structure's coordinates
    names = label_modes(model) if dm.has_wing or modal else None
    wing = ("modal",) if modal else ("bending", "torsion")
    groups = wing + (("chordwise",) if "chordwise" in found else ()) + (
        "pitch", "yaw")                  # chordwise: in-plane bending (wing.EI_chordwise)
    share = kinetic_energy_shares(modes.shapes, M, {g: found.get(g, []) for g in groups})
    many = len(dm.propellers) >= 2
    if many:                         # each propeller's share (its θ, ψ; participation.py)
        from propwhirl.analysis.participation import participation  # lazy: analyses
        part = participation(dm, modes.shapes, M, 1j * modes.omega, 0.0)
    echo(f"{model.name}: in-vacuo modes (V = 0, not rotating; kinetic-energy shares"
         + ("; propellers: the three largest propeller shares, numbered from 1)" if many
            else ")"))
    print(f"  {'mode':12s} {'f [Hz]':>10s} " + " ".join(f"{g:>8s}" for g in groups)
          + ("  propellers" if many else ""))
    order = np.argsort(modes.omega, kind="stable")
    for r, i in enumerate(order[:count]):
        if names is not None:
            label, f = names[r]
        else:  # no wing (isolated propeller): named by its dominant motion
            label, f = max(groups, key=lambda g: share[g][i]), float(modes.frequency_hz[i])
        who = f"  {_leading_shares(part, int(i))}" if many else ""
        echo(f"  {label:12s} {f:10.4f} " + " ".join(f"{share[g][i]:8.3f}" for g in groups)
             + who)
    return 0


def _leading_shares(part, k: int, count: int = 3) -> str:
    """'3 27 %, 4 21 %, 2 20 %': the (at most ``count``) propellers of mode ``k`` of a
    :class:`~propwhirl.analysis.participation.Participation` with the largest shares of its
    kinetic energy (their θ, ψ), numbered from 1; those under 0.5 % left out ('-' if all)."""
    order = sorted(range(part.number.size), key=lambda j: -part.share[j, k])[:count]
    out = [f"{int(part.number[j])} {100 * part.share[j, k]:.0f} %" for j in order
           if part.share[j, k] >= 0.005]
    return ", ".join(out) or "-"


def _add_modes(sub) -> None:
    p = sub.add_parser("modes", help="in-vacuo modes of a TOML model file")
    p.add_argument("model", metavar="MODEL.toml")
    p.add_argument("--count", type=int, default=10, help="number of modes (default 10)")
    p.set_defaults(func=_modes)


def _campbell(args: argparse.Namespace) -> int:
    import numpy as np

    from propwhirl.analysis.vibration import campbell  # lazy: analyses

    check_outputs(plot=args.plot, model=args.model)
    model = load_model(args.model, "campbell")   # the model says when it has no whirl
    lo, hi, n = args.rpm
    v.in_range("--rpm START", lo, 0.0, limits.MAX_RPM, "rev/min")
    v.in_range("--rpm STOP", hi, 0.0, limits.MAX_RPM, "rev/min")
    n_pts = v.integer_at_least("--rpm N", int(n) if float(n).is_integer() else n, 1)
    if n_pts > 10_000:
        raise InputError(f"--rpm N = {n_pts} is invalid: must be <= 10000")
    if n_pts > 1 and not hi > lo:
        raise InputError(f"--rpm STOP = {hi!r} rev/min is invalid: must be > START = {lo!r} "
                         "rev/min (or N = 1)")
    count = v.integer_at_least("--count", args.count, 1)
    result = campbell(model, np.linspace(lo, hi, n_pts))
    count = min(count, result.n_modes)
    echo(f"{model.name}: natural frequencies [Hz] against propeller speed (no aerodynamics), "
          "each mode followed from RPM 0")
    if len(set(result.rpm_ratio)) > 1:        # the propellers turn at different speeds
        ratio = result.rpm_ratio
        ref = next((j for j, r in enumerate(ratio) if r > 0), 0)    # the first that turns
        still = [str(j + 1) for j, r in enumerate(ratio) if r == 0]
        echo(f"  RPM of propeller {ref + 1}; " + ", ".join(
            [f"propeller {j + 1} at {r:.4g} x RPM" for j, r in enumerate(ratio)
             if j != ref and r > 0]
            + ([f"propeller{'s' * (len(still) > 1)} {', '.join(still)} not turning "
                "(stopped or feathered)"] if still else [])))
    echo(f"  {'RPM':>8s} " + " ".join(f"{lab:>11s}" for lab in result.labels[:count]))
    for r, row in zip(result.rpm, result.frequency_hz):
        print(f"  {r:8.1f} " + " ".join(f"{x:11.3f}" for x in row[:count]))
    if not result.resolved.all():
        print(f"  note: mode identity left ambiguous between (RPM) {list(result.unresolved)}")
    if args.plot:
        from propwhirl.app import plots  # lazy: figures

        # the result itself: its families (colours) and each propeller's speed (1P/2P lines)
        plots.campbell_diagram(result, n_modes=count,
                               title=f"{limits.printable(model.name)}: Campbell diagram",
                               path=args.plot)
        print(f"wrote {args.plot}")
    return 0


def _add_campbell(sub) -> None:
    p = sub.add_parser("campbell", help="Campbell diagram of a model file (a propeller wing or "
                       "an isolated propeller)")
    p.add_argument("model", metavar="MODEL.toml")
    p.add_argument("--rpm", nargs=3, type=float, required=True, metavar=("START", "STOP", "N"),
                   help="N propeller speeds from START to STOP [rev/min]")
    p.add_argument("--count", type=int, default=8, help="number of modes (default 8)")
    p.add_argument("--plot", metavar="PNG", help="write the Campbell diagram")
    p.set_defaults(func=_campbell)


def _case(args: argparse.Namespace) -> int:
    from propwhirl import io  # lazy: model files

    case = registry.get(args.name)  # an unknown name: one line listing the valid names
    check_outputs(save=args.save)
    model = case.model()
    if args.save:
        io.save_model(model, args.save)
        print(f"wrote {args.save} ({case.summary})")
    else:
        sys.stdout.write(io.dumps(model))
    return 0


def _add_case(sub) -> None:
    p = sub.add_parser("case", help="export a case-library model as a TOML model file",
                       description="Models: " + "; ".join(f"{c.name}: {c.summary}"
                                                           for c in registry.CASES.values()))
    p.add_argument("name", metavar="NAME", help="one of " + ", ".join(registry.CASES))
    p.add_argument("--save", metavar="MODEL.toml", help="write the model file (default: print it)")
    p.set_defaults(func=_case)


def _upgrade_model(args: argparse.Namespace) -> int:
    from propwhirl import io  # lazy: model files

    old, new = Path(args.old), Path(args.new)
    if not args.force and fileio.same_file(old, new):    # resolved, links followed
        raise InputError(f"upgrade-model: NEW {args.new} is the file OLD: give another name "
                         "(or --force to replace OLD)")
    fileio.check_writable(new, what="upgrade-model NEW")   # a regular file or a new path
    from propwhirl.io.modal_files import is_modal_file  # lazy: model files

    if is_modal_file(old):                 # the model says why it has nothing to upgrade
        load_model(str(old), "upgrade-model")
    notes: list[str] = []
    text = io.dumps(io.load_model(old, notes=notes))  # read and checked whole before writing
    fileio.write_text(new, text, what="model file")
    print_notes(notes)
    echo(f"wrote {args.new} (format version {io.schema.FORMAT_VERSION}"
         f"{'' if notes else '; no value assumed'})")
    return 0


def _add_upgrade_model(sub) -> None:
    p = sub.add_parser("upgrade-model", help="rewrite a model file of an older format version "
                       "in the current one, the values it assumed written out",
                       description="Reads OLD (any format version this propwhirl reads) and "
                       "writes the same model to NEW in the current version; the values assumed "
                       "for keys OLD omits are printed (docs/model-file.md, Format versions).")
    p.add_argument("old", metavar="OLD.toml", help="the model file to upgrade")
    p.add_argument("new", metavar="NEW.toml", help="the file to write (atomically)")
    p.add_argument("--force", action="store_true", help="allow NEW to be OLD (replaced)")
    p.set_defaults(func=_upgrade_model)


def _docs(args: argparse.Namespace) -> int:
    if args.name is None:
        print(f"propwhirl documentation, installed in {documents.folder()}:")
        for name in documents.names():
            print(f"  {name:14s} {documents.path(name)}")
        print("`propwhirl docs NAME` prints a page (Markdown); --path prints its file name")
    elif args.path:
        print(documents.path(args.name))
    else:
        sys.stdout.write(documents.text(args.name))
    return 0


def _add_docs(sub) -> None:
    p = sub.add_parser("docs", help="the installed documentation: list the pages, print one")
    p.add_argument("name", nargs="?", metavar="NAME", help="page, e.g. validation, errata, "
                   "model-file (default: list the pages and where they are installed)")
    p.add_argument("--path", action="store_true", help="print the page's file name only")
    p.set_defaults(func=_docs)


def version() -> str:
    """The version of propwhirl: the installed distribution's, else that of the source
    checkout's pyproject.toml, else "unknown"."""
    from importlib import metadata

    try:
        return metadata.version("propwhirl")
    except metadata.PackageNotFoundError:
        pass
    import tomllib

    try:
        pyproject = Path(__file__).resolve().parents[3] / "pyproject.toml"
        return str(tomllib.loads(pyproject.read_text())["project"]["version"]) + " (source)"
    except (OSError, KeyError, tomllib.TOMLDecodeError):
        return "unknown"


class _Parser(argparse.ArgumentParser):
    """argparse with the project's error style: a usage error is one line naming the command
    and pointing to its --help (exit code 2, through :func:`main`), not the usage text."""

    def __init__(self, *args, **kwargs):
        kwargs.setdefault("formatter_class", LazyHelpFormatter)   # the subcommands' too
        super().__init__(*args, **kwargs)

    def error(self, message: str):  # noqa: D102 (argparse's hook)
        raise InputError(f"{self.prog}: {message} (see `{self.prog} --help`)")


#: The exit codes, as `propwhirl --help` lists them.
EXIT_CODES = ("Exit codes: 0 done; 1 clearance or certify not cleared; 2 bad input (one line on stderr, "
              "before any analysis starts) or a sweep/map whose every point failed (some failed "
              "points: 0 and a warning); 130 interrupted (Ctrl-C); 141 the output's reader "
              "stopped early.")


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(
        prog="propwhirl",
        description="Wing flutter, propeller whirl flutter and divergence of flexible wings "
        "with flexibly mounted propellers (SI units).",
        epilog=EXIT_CODES,
    )
    parser.add_argument("--version", action="version", version=f"propwhirl {version()}")
    sub = parser.add_subparsers(dest="command", required=True)
    _add_run(sub)
    _add_reproduce(sub)
    _add_derivatives(sub)
    _add_analyse(sub)
    _add_modes(sub)
    _add_campbell(sub)

    cli_studies.add_commands(sub)
    _add_case(sub)
    _add_upgrade_model(sub)
    cli_nastran.add_commands(sub)
    cli_design.add_commands(sub)
    cli_certify.add_commands(sub)
    _add_docs(sub)
    return parser


#: Exit code after Ctrl-C (128 + SIGINT, the shell's convention).
EXIT_INTERRUPTED = 130
#: Exit code when the reader of the output went away (128 + SIGPIPE, the shell's convention).
EXIT_BROKEN_PIPE = 141


def main(argv: list[str] | None = None) -> int:
    """Run one command; returns the exit code: 0, 1 when `clearance` does not clear, 2 for bad
    input, a file that cannot be read or written (one line on stderr naming it) or a study
    whose every point failed (some failed points: 0 and a warning), 130 after Ctrl-C (one
    line, and no partial output file: every file is written atomically,
    :mod:`propwhirl.fileio`), 141 when the reader of the output stops early
    (``propwhirl reproduce | head -1``: quietly)."""
    try:
        parser = build_parser()
        args = parser.parse_args(argv)
        code = args.func(args)
        sys.stdout.flush()  # a closed pipe shows here, not at the interpreter's exit
        return code
    except BrokenPipeError:
        _silence_stdout()
        return EXIT_BROKEN_PIPE
    except KeyboardInterrupt as exc:  # a study's Interrupted says what was kept, and where
        detail = f": {limits.printable(_one_line(str(exc)))}" if str(exc) else ""
        print(f"propwhirl: interrupted{detail}", file=sys.stderr, flush=True)
        return EXIT_INTERRUPTED
    except InputError as exc:
        for line in getattr(exc, "errors", None) or [str(exc)]:   # a file's every error
            print(f"propwhirl: error: {limits.printable(_one_line(line))}", file=sys.stderr)
        return 2
    except OSError as exc:  # a file error not raised through propwhirl.fileio
        name = getattr(exc, "filename", None)
        where = f"cannot access {str(name)!r}: " if name else ""
        print(f"propwhirl: error: {limits.printable(where + _one_line(fileio.reason(exc)))}",
              file=sys.stderr)
        return 2


def _silence_stdout() -> None:
    """Point stdout at /dev/null: the interpreter's final flush must not meet the closed pipe
    again (Python's documented remedy, see the `signal` module's notes on SIGPIPE)."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        os.close(devnull)
    except (OSError, ValueError, AttributeError):  # stdout without a file descriptor
        pass


def _one_line(text: str) -> str:
    """Error messages on one line (tomllib's and numpy's may span several)."""
    return " ".join(text.split())
