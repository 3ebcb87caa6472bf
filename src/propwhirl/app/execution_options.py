"""The command line's execution options of every study command (`propwhirl reproduce`, the
sweeps and maps, `clearance`, `certify`, `boundary`): ``--processes``, ``--scheduler``,
``--resume``, ``--quiet``, and what they become for
:func:`propwhirl.studies.execution.map_analyses` (a scheduler address, a progress bar, the
partial-results file beside the output).

    p = sub.add_parser("sweep", ...)
    execution_options.add(p)
    ...
    cp = execution_options.checkpoint(args, args.json)      # None without an output file
    table = study(..., **execution_options.run_options(args), checkpoint=cp)
    write the outputs ...
    execution_options.finish(cp)                            # the partial file is removed
    execution_options.report_failures(table.columns["error"], "points")
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any, Iterable

from propwhirl import limits
from propwhirl import progress
from propwhirl import validate as v
from propwhirl.studies.execution import check_scheduler
from propwhirl.studies.partial import Checkpoint
from propwhirl.studies.warmstart import pass_checkpoints
from propwhirl.validate import InputError

#: Suffix of the partial-results file kept beside a study's output while it runs.
PARTIAL_SUFFIX = ".partial"


def add(parser: argparse.ArgumentParser, *, processes_default: int = 1,
        resume: bool = True) -> None:
    """Add ``--processes``, ``--scheduler``, ``--resume`` (unless ``resume=False``: a command
    that keeps no partial results, e.g. `boundary`) and ``--quiet`` to a study command."""
    g = parser.add_argument_group("execution")
    g.add_argument("--processes", type=int, default=processes_default,
                   help=f"local worker processes (default {processes_default}; at most one per CPU)")
    g.add_argument("--scheduler", metavar="ADDRESS", help="run on a Dask cluster, e.g. "
                   "tcp://host:8786 (needs pip install propwhirl[distributed])")
    if resume:
        g.add_argument("--resume", action="store_true", help="continue an interrupted run: keep "
                       "the finished points of the partial-results file beside the output "
                       f"(OUT{PARTIAL_SUFFIX}) and compute only the others (a file written for "
                       "another model, parameters, speeds, method or convention is refused)")
    g.add_argument("--quiet", action="store_true", help="no progress on stderr (by default a "
                   f"bar on a terminal, else a line every {progress.INTERVAL:g} s; nothing in "
                   f"the first {progress.DELAY:g} s)")


def run_options(args: argparse.Namespace) -> dict[str, Any]:
    """``processes``, ``client`` (the scheduler address or None) and ``progress`` (a bar unless
    --quiet) for a study function; the address is checked here, before any work."""
    v.integer_at_least("--processes", args.processes, 1)
    if args.scheduler is not None:
        check_scheduler(args.scheduler)
    return {"processes": args.processes, "client": args.scheduler, "progress": not args.quiet}


def partial_path(output: str | Path) -> Path:
    """The partial-results file kept beside `output` while a study runs."""
    return Path(str(output) + PARTIAL_SUFFIX)


def checkpoint(args: argparse.Namespace, output: str | Path | None) -> Checkpoint | None:
    """The partial-results file beside `output` (resumed with --resume); None without an
    output file (--resume then is an error: there is nowhere the points were kept)."""
    if output is None:
        if args.resume:
            raise InputError("--resume needs the output file of the interrupted run (e.g. --json "
                             "FILE): the finished points are kept beside it")
        return None
    # the study functions add the fingerprint (model content, paths and values, speeds,
    # method, convention, tolerance, version): a file of another study is refused
    return Checkpoint(partial_path(output), resume=bool(args.resume))


def finish(cp: Checkpoint | None) -> None:
    """Remove the partial-results file (and those of a warm-started study's passes) once the
    final output is written."""
    if cp is not None:
        for c in [cp, *pass_checkpoints(cp)]:
            c.discard()


def report_failures(errors: Iterable[str], what: str = "points") -> int:
    """Print how many `what` failed (and the first messages) on stderr; returns the count."""
    failed = [str(e) for e in errors if str(e)]
    if failed:
        print(f"propwhirl: warning: {len(failed)} {what} failed (column error):", file=sys.stderr)
        for message in failed[:5]:
            print(f"  {limits.printable(message)}", file=sys.stderr)
        if len(failed) > 5:
            print(f"  ... and {len(failed) - 5} more", file=sys.stderr)
    return len(failed)
