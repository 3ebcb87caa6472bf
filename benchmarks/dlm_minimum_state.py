"""Does Karpel's minimum-state approximation pay? (issue 23, item 3b; docs/validation.md,
"Karpel's minimum-state approximation").

Run from the repository root (needs the ``dlm`` extra; about 2 min, one BLAS thread)::

    .venv/bin/python benchmarks/dlm_minimum_state.py [--markdown docs/validation.md]

The wingtip model (§10.1, 25 elements) with ``aero = "dlm"``, 4 × 12 panels and a fixed
``dlm_mach = 0.5`` (one Mach: the minimum-state fit is at one Mach number, and so is the
comparison): the critical speeds of the engine on Roger's state space (the runtime's, lags
0.2, 0.5, 1, 2 per free wing DOF) and on minimum-state state spaces of m = 4, 6, 8, 12 lag
states in all (``benchmarks/minimum_state.py``), against the p-k method on the same
tables; the states, the fit's error and the CPU of one eigen-solution of A(V) and of the fit.
"""
from __future__ import annotations

import argparse
import dataclasses
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "benchmarks"))

from markdown_section import replace_section  # noqa: E402

from propwhirl.analysis.pk import pk_sweep  # noqa: E402
from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing  # noqa: E402
from propwhirl.engine import analyse as engine_analyse  # noqa: E402
from propwhirl.engine import single_thread_blas  # noqa: E402
import minimum_state as ms  # noqa: E402
from propwhirl.model.aerodynamics import dlm_rfa  # noqa: E402
from propwhirl.model.aerodynamics.dlm import DlmTables, dlm_aerodynamics  # noqa: E402

SPEEDS = np.arange(100.0, 291.0, 10.0)
MACH = 0.5
LAG_SETS = {4: (0.2, 0.5, 1.0, 2.0), 6: tuple(np.geomspace(0.1, 2.0, 6)),
            8: tuple(np.geomspace(0.1, 2.0, 8)), 12: tuple(np.geomspace(0.05, 3.0, 12))}
BEGIN = "<!-- dlm_minimum_state: begin (benchmarks/dlm_minimum_state.py writes this block) -->"
END = "<!-- dlm_minimum_state: end -->"
TITLE = "### Karpel's minimum-state approximation (item 3(b): does it pay?)"


def model():
    m = wingtip_propeller_wing()
    return m.with_(wing=dataclasses.replace(m.wing, aero="dlm", dlm_chordwise_panels=4,
                                            dlm_spanwise_panels=12, dlm_mach=MACH))


def onsets(matrix_fn, n: int, size: int):
    """(kind, V, f_hz) of every onset of the engine on the state matrices, and the CPU [s] of
    one eigen-solution of a matrix of this size."""
    disp = np.zeros(size, bool)
    disp[:n] = True
    an = engine_analyse(matrix_fn, SPEEDS, displacement=disp)
    A = matrix_fn(np.array([200.0]))[0]
    t = time.process_time()
    for _ in range(3):
        np.linalg.eig(A)
    eig = (time.process_time() - t) / 3
    return [(p.kind, float(p.V), float(p.frequency_hz)) for p in an.criticals.points
            if p.direction == "onset"], eig


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--markdown", type=Path, help="write the table into this file")
    args = p.parse_args()
    rows = ["| aerodynamic states | lag states | states of A(V) | fit error (% of max abs Q) "
            "| divergence V [m/s] | flutter V [m/s], f [Hz] | CPU of one eig(A) [ms] "
            "| CPU of the fit [s] |", "|---|---:|---:|---:|---:|---:|---:|---:|"]
    with single_thread_blas():
        m = model()
        n = m.dof_map().n_dof
        tables = DlmTables()
        aero = dlm_aerodynamics(m.wing, tables)
        pk = pk_sweep(m, SPEEDS, tables=tables).flutter
        pk_on = [(e.kind, e.V, e.frequency_hz) for e in pk if e.event == "onset"]
        t = time.process_time()
        roger = dlm_rfa.column_fit(aero, MACH)
        t_roger = time.process_time() - t
        size = 2 * n + roger.lags.size * roger.A.shape[-1]
        r_on, r_eig = onsets(lambda V: dlm_rfa.state_matrix(m, roger, V), n, size)

        def row(name, lag, size, err, on, eig, cpu):
            div = [x for x in on if x[0] == "divergence"]
            fl = [x for x in on if x[0] == "flutter"]
            d = f"{div[0][1]:.2f}" if div else "–"
            f = "; ".join(f"{x[1]:.2f}, {x[2]:.3f}" for x in fl) or "–"
            rows.append(f"| {name} | {lag} | {size} | {err} | {d} | {f} | "
                        f"{eig} | {cpu} |")
            print(rows[-1], flush=True)

        row("p-k on Q(k) (reference)", "–", 2 * n, "–", pk_on, "–", "–")
        row("Roger, 4 lags per DOF", roger.lags.size * roger.A.shape[-1], size,
            f"{100 * roger.error:.2f}", r_on, f"{1e3 * r_eig:.1f}", f"{t_roger:.2f}")
        for mm, lags in LAG_SETS.items():
            t = time.process_time()
            f = ms.fit_model(m, lags, tables=tables)
            cpu = time.process_time() - t
            on, eig = onsets(lambda V: ms.state_matrix(m, f, V), n, 2 * n + mm)
            row(f"minimum state, m = {mm} ({f.sweeps} sweeps)", mm, 2 * n + mm,
                f"{100 * f.error:.2f}", on, f"{1e3 * eig:.1f}", f"{cpu:.1f}")
    if args.markdown:
        body = "\n".join([
            f"Wingtip model, 25 elements, `aero = \"dlm\"`, 4 × 12 panels, `dlm_mach = {MACH}` "
            f"(every fit at that Mach), engine on {SPEEDS[0]:.0f}–{SPEEDS[-1]:.0f} m/s; CPU one "
            "BLAS thread, shared machine:", "", *rows])
        replace_section(args.markdown, body, BEGIN, END, TITLE)


if __name__ == "__main__":
    main()
