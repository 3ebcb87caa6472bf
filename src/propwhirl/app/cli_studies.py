"""`propwhirl sweep` and `propwhirl map`: the critical speed of a model (a model file or a case
of the library) against one or over two parameter paths (:mod:`propwhirl.studies.sweeps`),
with --json, --csv and --plot.  Part of the command line of :mod:`propwhirl.app.cli`."""
from __future__ import annotations

import argparse

import numpy as np

from propwhirl import validate as v
from propwhirl.app import execution_options
from propwhirl.app.cli_common import check_outputs, echo, model_or_case, speed_grid
from propwhirl.results import Result
from propwhirl.cases import registry
from propwhirl.validate import InputError


#: Most values of one --param axis (a map of two: their product is analysed).
MAX_PARAM_VALUES = 1000
#: Most points of a map (each one analysis).
MAX_MAP_POINTS = 250_000


def _param_axis(values: list[str]) -> tuple[str, "object"]:
    """--param PATH START STOP N: the path and N values from START to STOP."""
    import numpy as np

    path, start, stop, n = values
    try:
        lo, hi = float(start), float(stop)
        count = float(n)
    except ValueError:
        raise InputError(f"--param {' '.join(values)} is invalid: START, STOP and N must be "
                         "numbers") from None
    v.finite(f"--param {path} START", lo)
    v.finite(f"--param {path} STOP", hi)
    if not count.is_integer() or not 1 <= count <= MAX_PARAM_VALUES:
        raise InputError(f"--param {path} N = {n} is invalid: must be an integer in "
                         f"[1, {MAX_PARAM_VALUES}]")
    if count > 1 and not hi != lo:
        raise InputError(f"--param {path} STOP = {stop} is invalid: must differ from START "
                         "(or N = 1)")
    return path, np.linspace(lo, hi, int(count))


def _study_options(args: argparse.Namespace) -> dict:
    """The study function's options: the convention, the speeds and the execution options
    (processes, a Dask scheduler, a progress bar unless --quiet, the partial-results file
    beside --json, resumed with --resume)."""
    opts = {**execution_options.run_options(args),
            "checkpoint": execution_options.checkpoint(args, args.json),
            "static_divergence": not args.thesis_convention,
            "low_speed": not args.thesis_convention,
            "method": _method(args), "warm_start": _warm_start(args)}
    if args.speeds:
        opts["speeds"] = speed_grid(*args.speeds)
    return opts


def _method(args: argparse.Namespace) -> str:
    """--method, "dense" with --reference (which refuses another method)."""
    if args.reference and args.method not in ("auto", "dense"):
        raise InputError(f"--reference is the dense brute-force reference: --method "
                         f"{args.method} contradicts it (leave one out)")
    return "dense" if args.reference else args.method


def _warm_start(args: argparse.Namespace) -> bool:
    """Whether the study is warm-started: by default, unless --no-warm-start, --reference or
    --thesis-convention (whose recovering low-speed instabilities a clipped range cannot
    tell)."""
    if args.reference and args.warm_start:
        raise InputError("--reference analyses every point over its whole speed range: "
                         "--warm-start contradicts it (leave one out)")
    if args.warm_start is None:
        return not (args.reference or args.thesis_convention)
    return bool(args.warm_start)


def _write_study(result, args: argparse.Namespace, plot, checkpoint=None) -> None:
    """Print the result, report the failing points on stderr, write the outputs (then the
    partial-results file is removed).

    A study whose every point failed has no result: its --json and --csv are still written
    (each point's message in column error; no plot: nothing to draw), then an InputError
    (exit code 2) names the count and the first message.  Some failed points: a warning on
    stderr, exit code 0 (:data:`FAILED_POINTS_HELP`)."""
    echo(result.format())
    errors = [str(e) for e in np.ravel(result.columns["error"])]
    every_point_failed = bool(errors) and all(errors)
    if not every_point_failed:
        execution_options.report_failures(errors)
    if args.json:
        Result.save(result, args.json)        # JSON even for a name ending in .csv
        print(f"wrote {args.json}")
        execution_options.finish(checkpoint)
    if args.csv:
        result.to_csv(args.csv)
        print(f"wrote {args.csv}")
    if every_point_failed:
        kept = (": the outputs hold each point's error (column error)" if args.json or args.csv
                else "")
        raise InputError(f"{args.command}: every one of the {len(errors)} points failed (first: "
                         f"{errors[0]}){kept}" + (f"; --plot {args.plot} not written" if args.plot
                                                 else ""))
    if args.plot:
        plot(result, path=args.plot)
        print(f"wrote {args.plot}")


#: What the help of `sweep` and `map` says of failing points (their exit codes).
FAILED_POINTS_HELP = ("A point whose model cannot be built or whose analysis fails is "
                      "recorded (kind error, its message in column error) and the others go on. "
                      "Exit code 0 when every point was analysed, also 0 when some failed (a "
                      "warning on stderr lists them); exit code 2 when every point failed (one "
                      "line on stderr; --json and --csv are still written, with each point's "
                      "error), as for bad input.")


#: The index and link syntax of parameter paths (--list-params; docs/studies.md).
PATH_SYNTAX = (
    "indices of installations are from 0 (propellers[0] is propeller 1 of the reports); "
    "select several with",
    "  propellers[*]                  every installation",
    "  propellers[0:6]                a Python slice: 0 to 5 (STOP excluded; 0:6:2 every other)",
    "  propellers[0,2,4]              a list",
    "  propellers[NAME]               a named group: the model file's [groups] table, "
    "NAME = [indices from 0]",
    "link paths with commas to set one value on each (quote the whole in the shell):",
    '  --param "propellers[0].propeller.f_theta,propellers[0].propeller.f_psi" 6 14 5',
)


def _list_parameters(model) -> int:
    from propwhirl.studies import paths  # lazy: studies

    echo(f"{model.name}: parameter paths (PATH* scales a distribution by a factor)")
    for p in paths.parameters(model):
        echo(f"  {p.describe()}")
    for line in PATH_SYNTAX:
        echo(line)
    groups = paths.groups_of(model)
    if groups:
        echo("groups of this model (indices into propellers, from 0):")
        for name, members in groups.items():
            echo(f"  propellers[{name}] = propellers[{','.join(map(str, members))}] "
                 f"(propellers {', '.join(str(i + 1) for i in members)} of the reports)")
    return 0


def _sweep(args: argparse.Namespace) -> int:
    from propwhirl.studies import sweeps  # lazy: studies

    model = model_or_case(args.model, "sweep")
    if args.list_params:
        given = [f"--{o}" for o in ("param", "json", "csv", "plot") if getattr(args, o)]
        if given:
            raise InputError(f"sweep --list-params only lists the parameter paths: "
                             f"{', '.join(given)} would be ignored (leave out --list-params)")
        return _list_parameters(model)
    if args.param is None:
        raise InputError("sweep: give --param PATH START STOP N (see --list-params)")
    _check_study_outputs(args)
    path, values = _param_axis(args.param)
    opts = _study_options(args)
    result = sweeps.sweep(model, path, values, **opts)

    def plot(r, path):
        from propwhirl.app import plots  # lazy: figures

        plots.critical_sweep(r, path=path)

    _write_study(result, args, plot, opts["checkpoint"])
    return 0


def _map(args: argparse.Namespace) -> int:
    from propwhirl.studies import sweeps  # lazy: studies

    model = model_or_case(args.model, "map")
    if not args.param or len(args.param) != 2:
        raise InputError(f"map: give --param PATH START STOP N twice (got "
                         f"{len(args.param or [])})")
    _check_study_outputs(args)
    first, second = (_param_axis(p) for p in args.param)
    n = len(first[1]) * len(second[1])
    if n > MAX_MAP_POINTS:
        raise InputError(f"map: N1 x N2 = {n} points is invalid: must be <= {MAX_MAP_POINTS}")
    for path, values in (first, second):
        if args.plot and len(values) < 2:      # a contour map needs a plane
            raise InputError(f"map --plot needs at least 2 values of each parameter: --param "
                             f"{path} has N = {len(values)}")
    opts = _study_options(args)
    result = sweeps.map2d(model, first, second, **opts)

    def plot(r, path):
        from propwhirl.app import plots  # lazy: figures

        plots.critical_map(r, path=path)       # both axes have 2 values or more (checked)

    _write_study(result, args, plot, opts["checkpoint"])
    return 0


def _check_study_outputs(args: argparse.Namespace) -> None:
    """The outputs of `sweep`/`map` (:func:`check_outputs`): none on another, on the model
    file, or on the partial-results files kept beside --json while the study runs."""
    check_outputs(json=args.json, csv=args.csv, plot=args.plot, model=args.model,
                  partial_of="json", warm_start=_warm_start(args))


def _add_study_options(p) -> None:
    p.add_argument("model", metavar="MODEL", help="a model file (.toml) or a case name ("
                   + ", ".join(registry.CASES) + ")")
    p.add_argument("--speeds", nargs=3, type=float, metavar=("START", "STOP", "STEP"),
                   help="initial airspeed grid [m/s] (default: the model's speed range)")
    p.add_argument("--thesis-convention", action="store_true", help="leave out the wing's "
                   "static divergence and low-speed instabilities that recover (chapter 11)")
    p.add_argument("--method", choices=("auto", "dense", "reduced"), default="auto",
                   help="each point's analysis (default auto: for a wing the reduced-order "
                   "model, kept where every crossing converged on the full order, else dense; "
                   "dense: every root of the full-order model, the reference)")
    p.add_argument("--warm-start", action=argparse.BooleanOptionalAction, default=None,
                   help="analyse most points only up to the speeds found at their coarse "
                   "neighbours (every 5th point of each axis, analysed first); a point that "
                   "finds nothing there is analysed over the whole range: the same results to "
                   "the crossing accuracy (default on; off with --thesis-convention, whose "
                   "recovering instabilities a clipped range cannot tell)")
    p.add_argument("--reference", action="store_true", help="the brute-force reference: "
                   "every point dense over its whole speed range (= --method dense "
                   "--no-warm-start; the defaults give the same map to the crossing accuracy)")
    p.add_argument("--json", metavar="OUT", help="write the result as JSON")
    p.add_argument("--csv", metavar="OUT", help="write one row per point as CSV")
    p.add_argument("--plot", metavar="PNG", help="write the plot")
    execution_options.add(p)


def _add_sweep(sub) -> None:
    p = sub.add_parser("sweep", help="critical speed of a model against one parameter path",
                       description="Critical speed (kind, mode, dominant propeller) of MODEL "
                       "at N values of one parameter, e.g. --param "
                       "propellers[0].propeller.f_psi 3 12 10, or --param wing.EI* 0.5 2 7 "
                       "(a factor on the distribution).  Installations are indexed from 0 "
                       "(propellers[0] is propeller 1 of the reports); several at once: "
                       "propellers[0:6] (a slice), propellers[0,2,4], propellers[NAME] (a "
                       "group of the model file's [groups] table); linked paths take one "
                       "value: --param \"propellers[0].propeller.f_theta,"
                       "propellers[0].propeller.f_psi\" 6 14 5 (quote paths with brackets).  "
                       "--list-params lists the paths.  "
                       + FAILED_POINTS_HELP)
    _add_study_options(p)
    p.add_argument("--param", nargs=4, metavar=("PATH", "START", "STOP", "N"),
                   help="the parameter path (or linked paths PATH1,PATH2: one value set on "
                   "each) and N values from START to STOP")
    p.add_argument("--list-params", action="store_true", help="list the model's parameter paths")
    p.set_defaults(func=_sweep)


def _add_map(sub) -> None:
    p = sub.add_parser("map", help="critical speed of a model over two parameter paths",
                       description="Critical speed of MODEL over the N1 x N2 grid of two "
                       "parameters: --param PATH START STOP N twice (`propwhirl sweep MODEL "
                       "--list-params` lists the paths, the selections propellers[0:6], "
                       "propellers[0,2,4], propellers[NAME] and linked paths PATH1,PATH2).  "
                       + FAILED_POINTS_HELP)
    _add_study_options(p)
    p.add_argument("--param", nargs=4, action="append", metavar=("PATH", "START", "STOP", "N"),
                   help="a parameter path and N values from START to STOP (give it twice)")
    p.set_defaults(func=_map)




def add_commands(sub) -> None:
    """Register `sweep` and `map` on the CLI's subparsers."""
    _add_sweep(sub)
    _add_map(sub)
