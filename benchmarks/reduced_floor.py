"""The floor of the reduced wingtip analysis (issue 26, item 2): the work any analysis of
``examples/wingtip.toml`` with ``method="reduced"`` does whatever its tracker, in
eigen-solutions of its own reduced matrix (one ``numpy.linalg.eig`` with vectors, 50 states).

    python benchmarks/reduced_floor.py [--model examples/wingtip.toml] [--repeats 20] \
        [--markdown docs/performance.md]

The parts of the floor, each timed alone (CPU, one BLAS thread, median of ``--repeats``), by
calling the package's own functions on the model's own analysis:

* the basis: :func:`propwhirl.model.reduction.reduce` (in-vacuo modes of the full structure,
  static-correction vectors, lag basis) — a reduced analysis needs it;
* the first nodes: the eigen-solutions (eig with vectors and dλ/dV, A(V) at V and V + h) at
  the speeds the tracker starts from (``ANALYSE_INITIAL_STEP`` apart) — no tracker can know
  the roots without them;
* the full-order guarantee (item 1): each crossing converged on the full-order sparse pencil
  (:func:`propwhirl.engine.correction.correct_crossing`, from the analysis's own reduced
  crossing) and each frequency-zero event checked there
  (:func:`propwhirl.analysis.reduced.frequency_zero_on_full_order`);
* the names the result reports: :func:`propwhirl.analysis.naming.named_modes`.

Everything else — refinement nodes, linking, clusters, locating the crossings on the reduced
model, participation, content, the result — is what a tracker and the reporting add.  Each
part's time is a measurement of today's code, not of an ideal implementation; the floor says
how much of the ≤ 50 target those parts alone take.
"""
from __future__ import annotations

import argparse
import datetime
import os
import sys
import time
from pathlib import Path

import numpy as np
from threadpoolctl import threadpool_limits

sys.path.insert(0, str(Path(__file__).resolve().parent))
from markdown_section import replace_section  # noqa: E402

import propwhirl  # noqa: E402
from propwhirl.analysis.naming import named_modes  # noqa: E402
from propwhirl.analysis.reduced import (_reduced_slopes, frequency_zero_on_full_order,  # noqa: E402
                                        reduced_engine_analysis)
from propwhirl.analysis.stability import _frequency_zero_events  # noqa: E402
from propwhirl.engine import analyse as engine_analyse  # noqa: E402
from propwhirl.engine.correction import correct_crossing  # noqa: E402
from propwhirl.engine.nodes import evaluate_nodes  # noqa: E402
from propwhirl.engine.options import TrackingOptions  # noqa: E402
from propwhirl.engine.tracker import ANALYSE_INITIAL_STEP, _initial_subset  # noqa: E402
from propwhirl.engine.crossings import XTOL  # noqa: E402
from propwhirl.io import load_model  # noqa: E402
from propwhirl.model.reduction import reduce  # noqa: E402

MARK_BEGIN = "<!-- reduced_floor: begin -->"
MARK_END = "<!-- reduced_floor: end -->"
TITLE = "## The reduced analysis's floor (issue 26, item 2)"


def cpu(f, repeats: int) -> float:
    """Median CPU time [s] of ``f()`` over ``repeats`` calls."""
    out = []
    for _ in range(repeats):
        t = time.process_time()
        f()
        out.append(time.process_time() - t)
    return float(np.median(out))


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--model", default="examples/wingtip.toml")
    p.add_argument("--repeats", type=int, default=20)
    p.add_argument("--markdown", help="write the table between this script's markers")
    args = p.parse_args(argv)
    model = load_model(args.model)
    grid = model.flight.speeds()
    dm = model.dof_map()
    opts = TrackingOptions()
    with threadpool_limits(limits=1):
        R = reduce(model, grid)
        A = R.state_matrix(np.array([150.0]))[0]
        eig = min(cpu(lambda: np.linalg.eig(A), 100) for _ in range(5))
        for _ in range(3):
            a = propwhirl.analyse(model, method="reduced")
        total = cpu(lambda: propwhirl.analyse(model, method="reduced"), args.repeats)
        first = _initial_subset(grid, ANALYSE_INITIAL_STEP)
        an = engine_analyse(R.state_matrix, grid, displacement=R.displacement,
                            state_labels=R.labels(), xtol=0.1 * XTOL)
        lift = R.lift
        slopes = _reduced_slopes(an.sweep, an.criticals.points)
        crossings = [(pt.V, pt.eigenvalue, lift @ pt.eigenvector, s)
                     for pt, s in zip(an.criticals.points, slopes)]
        run = reduced_engine_analysis(model, grid, displacement=dm.displacement,
                                      state_labels=dm.state_labels, xtol=XTOL)
        fzero, shapes = _frequency_zero_events(model, run.analysis.sweep, R.state_matrix, XTOL,
                                               lift)

        def fresh():        # a reduced model without evaluations kept from another part
            return reduce(model, grid)

        def nodes(Rm):
            evaluate_nodes(Rm.state_matrix, first, Rm.n_states, None, opts, {})

        def corrections(Rm):
            for V, lam, x, s in crossings:
                correct_crossing(Rm.pencil, V, lam, x, xtol=XTOL, slope=s)

        rows = [
            ("the basis (`reduce`)", cpu(fresh, args.repeats)),
            (f"the first nodes ({first.size} speeds {ANALYSE_INITIAL_STEP:g} m/s apart: "
             "A(V) at V and V + h, eig with vectors, dλ/dV)",
             cpu(lambda: nodes(fresh()), args.repeats) - cpu(fresh, args.repeats)),
            (f"the full-order guarantee: {len(crossings)} crossings corrected on the full-order "
             "pencil (`correct_crossing`)",
             cpu(lambda: corrections(fresh()), args.repeats) - cpu(fresh, args.repeats)),
            ("the names (`named_modes`: in-vacuo modes, Ω-follow, MAC)",
             cpu(lambda: named_modes(model, a.sweep, R.dof_basis,
                                     R.assembly.without_aerodynamics()), args.repeats)),
        ]
        check = (cpu(lambda: frequency_zero_on_full_order(fzero, shapes, fresh()), args.repeats)
                 - cpu(fresh, args.repeats))
        auto = cpu(lambda: propwhirl.analyse(model), args.repeats)
    floor = sum(t for _, t in rows)
    load = os.getloadavg()
    lines = [f"Measured {datetime.date.today()} with `benchmarks/reduced_floor.py` on "
             f"{os.cpu_count()} cores, load average {load[0]:.1f} / {load[1]:.1f} / "
             f"{load[2]:.1f} (1 / 5 / 15 min) at the end; CPU time at one BLAS thread, median "
             f"of {args.repeats}; `{args.model}`, {R.n_states} reduced states, one eig with "
             f"vectors {eig * 1e3:.3f} ms; events "
             + ", ".join(f"{e.event} {e.V:.2f}" for e in a.events) + ".", "",
             "| part | CPU [ms] | eigen-solution equivalents |", "|---|---:|---:|"]
    for name, t in rows:
        lines.append(f"| {name} | {t * 1e3:.1f} | {t / eig:.0f} |")
    lines += [f"| **the floor** (sum) | **{floor * 1e3:.1f}** | **{floor / eig:.0f}** |",
              f"| the whole analysis (`analyse(model, method=\"reduced\")`) | {total * 1e3:.1f} "
              f"| {total / eig:.0f} |",
              f"| left to the tracker (refinement nodes, linking, clusters, crossings on the "
              f"reduced model) and the reporting | {(total - floor) * 1e3:.1f} | "
              f"{(total - floor) / eig:.0f} |",
              f"| the default (`method=\"auto\"`) adds: {len(fzero)} frequency-zero event(s) "
              f"checked on the full-order pencil (`frequency_zero_on_full_order`) | "
              f"{check * 1e3:.1f} | {check / eig:.0f} |",
              f"| the default analysis (`analyse(model)`) | {auto * 1e3:.1f} | {auto / eig:.0f} |"]
    table = "\n".join(lines)
    print(table)
    if args.markdown:
        replace_section(Path(args.markdown), table, MARK_BEGIN, MARK_END, TITLE)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
