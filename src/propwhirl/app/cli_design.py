"""The design-study commands of the command line (:mod:`propwhirl.app.cli`):

  boundary     a stability boundary in a plane of two parameters, traced by continuation
               (:mod:`propwhirl.studies.boundary`)
  clearance    clearance to factor x V_D (:mod:`propwhirl.studies.clearance`); exit code 0
               when cleared, 1 when not
  sensitivity  the critical point, then the parameters ranked by normalised sensitivity
               (p/V) dV/dp (:mod:`propwhirl.analysis.sensitivity`); with --verify each
               checked against a central difference of the critical speed
               (:mod:`propwhirl.studies.sensitivity_check`), exit code 1 when one is flagged

MODEL is a TOML model file or the name of a case (``propwhirl case``).
"""
from __future__ import annotations

import argparse

from propwhirl.app import execution_options
from propwhirl.app.cli_common import check_outputs, echo, lazy, model_or_case
from propwhirl.certification import FACTOR_CFR23, FACTOR_CS25
from propwhirl.validate import InputError

#: Largest N of the --grid N x N map under a boundary plot (each point an eigen-solution, or
#: with --contour an analysis).
MAX_GRID = 60
#: N of the grid map with --plot when --grid is not given.
DEFAULT_GRID = 12


def _boundary(args: argparse.Namespace) -> int:
    from propwhirl.studies import boundary as B  # lazy: studies
    from propwhirl.studies import paths as P  # lazy: studies

    check_outputs(json=args.json, csv=args.csv, plot=args.plot, model=args.model)
    if args.grid is None:                  # a plot's map (and every branch) by default
        args.grid = DEFAULT_GRID if args.plot else 0
    if args.grid != 0 and not 2 <= args.grid <= MAX_GRID:       # before the tracing
        raise InputError(f"--grid = {args.grid} is invalid: must be 0 (none) or in "
                         f"[2, {MAX_GRID}]")
    if args.thesis and not args.contour:      # options that would be ignored: refused
        raise InputError("--thesis is for --contour, it has no effect on the "
                         "neutral-stability curve: add --contour or leave it out")
    if args.oscillatory and args.contour:
        raise InputError("--oscillatory is for the neutral-stability curve, it has no effect "
                         "with --contour: leave one out")

    run = execution_options.run_options(args)      # checked before the tracing
    model = model_or_case(args.model, "boundary")
    params = [P.resolve(model, p) for p in args.params]
    current = [p.value(model) for p in params]
    if args.bounds is not None:
        lower, upper = [args.bounds[0], args.bounds[2]], [args.bounds[1], args.bounds[3]]
    else:
        if any(x is None or x <= 0 for x in current):
            raise InputError("--bounds is needed: the model has no positive value at "
                             + ", ".join(p.path for p, x in zip(params, current) if x is None or x <= 0))
        lower, upper = [0.5 * x for x in current], [2.0 * x for x in current]
    if args.contour:
        b = B.speed_contour(model, args.params, lower, upper, args.speed,
                            static_divergence=not args.thesis, low_speed=not args.thesis, **run)
    else:
        b = B.neutral_curve(model, args.params, lower, upper, args.speed,
                            oscillatory=args.oscillatory, **run)
    grid = None
    if args.grid:                          # every branch: seeded from the grid's zero set
        grid = B.grid_map(B.level_of(b, model, **run), lower, upper, args.grid)
        b = B.add_branches(b, model, grid, **run)
    echo(b.format())
    if grid is not None:
        d1, d2 = B.grid_agreement(b, grid)
        print(f"grid map {args.grid} x {args.grid} ({grid.evaluations} {b.evaluation_name}): "
              f"traced points within {d1:.2f} cells of the grid's boundary, grid's boundary "
              f"within {d2:.2f} cells of the traced curves")
    if args.json:
        b.save(args.json)
        print(f"wrote {args.json}")
    if args.csv:
        b.to_csv(args.csv)
        print(f"wrote {args.csv}")
    if args.plot:
        from propwhirl.app import plots  # lazy: figures

        design = current if all(x is not None for x in current) else None
        plots.boundary_plot(b, grid, design=design, path=args.plot)
        print(f"wrote {args.plot}")
    return 0


def _add_boundary(sub) -> None:
    p = sub.add_parser("boundary", help="stability boundary in a plane of two parameters, "
                       "traced by continuation")
    p.add_argument("model", metavar="MODEL", help="model file (TOML) or case name")
    p.add_argument("--params", nargs=2, required=True, metavar=("PATH", "PATH"),
                   help="two parameter paths, e.g. propellers[0].propeller.f_theta "
                   "propellers[0].propeller.f_psi")
    p.add_argument("--speed", type=float, required=True, metavar="V",
                   help="airspeed of the neutral-stability curve, or the target critical "
                   "speed with --contour [m/s]")
    p.add_argument("--bounds", nargs=4, type=float, metavar=("LO1", "HI1", "LO2", "HI2"),
                   help="the plane (default: half to twice the model's values)")
    p.add_argument("--contour", action="store_true", help="trace V_crit = V (one analysis per "
                   "point) instead of the neutral-stability curve at V (one eigen-solution)")
    p.add_argument("--oscillatory", action="store_true", help="neutral curve of the flutter "
                   "modes only (complex eigenvalues; divergence roots left out)")
    p.add_argument("--thesis", action="store_true", help="with --contour: the thesis's "
                   "convention (wing static divergence and recovering low-speed instabilities "
                   "left out)")
    p.add_argument("--grid", type=int, default=None, metavar="N",
                   help=f"an N x N grid map of the plane (0: none, else 2 to {MAX_GRID}; "
                   f"default {DEFAULT_GRID} with --plot, none without): every branch its zero "
                   "set shows is traced (the start lines alone can miss one), and --plot "
                   "draws it under the curves")
    p.add_argument("--json", metavar="OUT", help="write the boundary as JSON")
    p.add_argument("--csv", metavar="OUT", help="write the boundary's points as CSV")
    p.add_argument("--plot", metavar="PNG", help="plot the boundary over the grid map")

    # the start search's samples and the grid map are batches of independent evaluations
    execution_options.add(p, resume=False)
    p.set_defaults(func=_boundary)


def _clearance(args: argparse.Namespace) -> int:
    from propwhirl.studies.clearance import clearance, phase_checkpoints  # lazy: studies

    check_outputs(json=args.json, csv=args.csv, plot=args.plot, model=args.model)
    options = execution_options.run_options(args)
    cp = execution_options.checkpoint(args, args.json)
    model = model_or_case(args.model, "clearance")
    r = clearance(model, args.vd, args.factor, static_divergence=not args.thesis,
                  low_speed=not args.thesis, minimum=not args.no_minimum,
                  frequency_range=tuple(args.frequency_range), propellers=args.propellers,
                  **options, checkpoint=cp)
    echo(r.format())
    if args.json:
        r.save(args.json)
        print(f"wrote {args.json}")
    if args.csv:
        r.to_csv(args.csv)
        print(f"wrote {args.csv}")
    if args.plot:
        from propwhirl.app import plots  # lazy: figures

        plots.clearance_plot(r, path=args.plot)
        print(f"wrote {args.plot}")
    for c in [cp, *phase_checkpoints(cp)]:
        if c is not None:
            c.discard()
    return 0 if r.cleared else 1


def _add_clearance(sub) -> None:
    p = sub.add_parser("clearance", help="clearance to factor x V_D (exit code 0 cleared, 1 not)")
    p.add_argument("model", metavar="MODEL", help="model file (TOML) or case name")
    p.add_argument("--vd", type=float, required=True, metavar="V", help="design dive speed V_D [m/s]")
    p.add_argument("--factor", type=float, default=FACTOR_CS25, help=f"{FACTOR_CS25:g} (CS/FAR "
                   f"25.629, default) or {FACTOR_CFR23:g} (14 CFR 23.629)")
    p.add_argument("--frequency-range", nargs=2, type=float, default=(1.0, 30.0),
                   metavar=("LO", "HI"), help="range of the minimum mount frequencies [Hz] "
                   "(default 1 30)")
    p.add_argument("--no-minimum", action="store_true", help="skip the minimum mount frequencies")
    p.add_argument("--propellers", type=int, nargs="+", metavar="N", help="search the minimum "
                   "mount frequencies of these propellers only (numbered from 1; default all)")
    p.add_argument("--thesis", action="store_true", help="the thesis's convention: the wing's "
                   "static divergence and recovering low-speed instabilities left out")
    p.add_argument("--json", metavar="OUT", help="write the result as JSON")
    p.add_argument("--csv", metavar="OUT", help="write the result as CSV")
    p.add_argument("--plot", metavar="PNG", help="plot the margins")
    execution_options.add(p)
    p.set_defaults(func=_clearance)



def _sensitivity(args: argparse.Namespace) -> int:
    from propwhirl.analysis.sensitivity import critical_sensitivities  # lazy: analyses
    from propwhirl.analysis.stability import analyse  # lazy: analyses
    from propwhirl.model.aerodynamics.dlm import DlmTables  # lazy: the model package
    from propwhirl.model.parameter_paths import parameter_paths  # lazy: the model package

    check_outputs(json=args.json, plot=args.plot, model=args.model)
    if args.top < 1:
        raise InputError(f"--top {args.top} is invalid: must be >= 1")
    run = execution_options.run_options(args)      # checked before the analysis
    if not args.verify and (args.processes != 1 or args.scheduler):
        given = "--scheduler" if args.scheduler else f"--processes {args.processes}"
        raise InputError(f"{given} is for --verify (the central-difference analyses); the "
                         "sensitivities themselves are one analysis: add --verify or leave "
                         f"{given.split()[0]} out")
    model = model_or_case(args.model, "sensitivity")      # the model says when it has none
    known = parameter_paths(model)                         # the model contract's paths
    spanwise = ("wing.EI[", "wing.GJ[", "wing.mass_per_length[")
    if args.plot and not any(p.path.startswith(spanwise) for p in known):
        raise InputError("--plot draws the per-element sensitivities of a beam wing's EI, GJ "
                         "and m: a modal model has none (its parameters are its modes'; "
                         "leave --plot out)")
    if args.list:
        echo("\n".join(f"{p.path}  [{p.unit or 'factor'}]  {p.doc}  ({p.derivative})"
                        for p in known))
        return 0
    params = None
    if args.param:
        paths = {p.path for p in known}
        bad = next((q for q in args.param if q not in paths), None)
        if bad is not None:
            raise InputError(f"--param {bad!r} is invalid: not a parameter with derivatives of "
                             f"this model (`propwhirl sensitivity {args.model} --list` lists "
                             f"the {len(paths)} valid paths)")
        params = list(dict.fromkeys(args.param))
        if args.plot and not any(q.startswith(spanwise) for q in params):
            raise InputError("--plot draws the per-element sensitivities of EI, GJ and m: "
                             "leave out --param, or add paths such as --param 'wing.GJ[0]'")
    tables = DlmTables()          # a doublet-lattice wing's AICs: once for every analysis
    a = analyse(model, dlm_tables=tables)
    event = a.critical
    if args.kind is not None:
        cands = [e for e in a.events if e.kind == args.kind and e.event == "onset"]
        if not cands:
            raise InputError(f"no {args.kind} onset in the analysed range")
        event = min(cands, key=lambda e: e.V)
    cs = critical_sensitivities(model, a, event, params=params, dlm_tables=tables)
    echo(cs.format(args.top))
    check = None
    if args.verify:
        from propwhirl.studies.sensitivity_check import verify_sensitivities  # lazy: studies

        check = verify_sensitivities(model, a, cs, top=args.top, dlm_tables=tables, **run)
        echo("")
        echo(check.format())
    if args.json:
        if check is not None:
            check.save(args.json)
        else:
            cs.save(args.json, args.top)
        print(f"wrote {args.json}")
    if args.plot:
        from propwhirl.app import plots  # lazy: figures

        plots.spanwise_sensitivity(cs, model, path=args.plot)
        print(f"wrote {args.plot}")
    return 0 if check is None or check.passed else 1


def _add_sensitivity(sub) -> None:
    check = "propwhirl.studies.sensitivity_check"   # its constants, read when printed
    REL_STEP, RTOL, NORMALISED_ATOL = (lazy(check, name, "g")
                                       for name in ("REL_STEP", "RTOL", "NORMALISED_ATOL"))
    p = sub.add_parser("sensitivity", help="sensitivities of the critical speed to the model's "
                       "parameters (exact derivatives, or central differences where the model "
                       "has none, said which; ranked; --verify: checked by central differences "
                       "of re-analyses, exit code 1 when one is flagged)")
    p.add_argument("model", metavar="MODEL", help="a model file (.toml) or a case name")
    p.add_argument("--top", type=int, default=10, metavar="N",
                   help="the N parameters of largest normalised sensitivity (default 10)")
    p.add_argument("--kind", choices=("flutter", "divergence"),
                   help="the first onset of this kind instead of the critical instability")
    p.add_argument("--json", metavar="FILE", help="write the critical point and the ranked "
                   "sensitivities as JSON (propwhirl.sensitivities/2; with --verify the "
                   "verification holding them, propwhirl.sensitivity-check/1)")
    p.add_argument("--plot", metavar="PNG", help="write the spanwise sensitivities of EI, GJ, m")
    p.add_argument("--param", action="append", metavar="PATH",
                   help="compute only this parameter's sensitivity (repeat for more; "
                   "--list shows the valid paths)")
    p.add_argument("--list", action="store_true",
                   help="list the model's parameter paths, each with how its derivative is "
                   "computed, and stop")
    p.add_argument("--verify", action="store_true",
                   help="check each sensitivity shown (the --top N, of the --param ones if "
                   "given) against the central difference of the critical speed: the model "
                   f"analysed at p(1 +- {REL_STEP}) with the same method and speeds, the same "
                   "event (kind and mode) found in both; 2 analyses per parameter, in one batch "
                   "(--processes, --scheduler, progress). A check is flagged when "
                   f"|exact - FD| > {RTOL} |FD| + {NORMALISED_ATOL} in normalised units, or "
                   "the critical mode changed, or a variant failed; the exit code is then 1 "
                   "(0 when all pass)")
    # the verification's analyses are one batch of independent analyses
    execution_options.add(p, resume=False)
    p.set_defaults(func=_sensitivity)


def add_commands(sub) -> None:
    """Register ``boundary``, ``clearance`` and ``sensitivity`` on the CLI's subparsers."""
    _add_boundary(sub)
    _add_clearance(sub)
    _add_sensitivity(sub)
