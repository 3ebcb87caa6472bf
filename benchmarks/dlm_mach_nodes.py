"""How far apart may the doublet-lattice tables' Mach nodes be (issue 37, item 2)?  A
measurement, not a test.

Run from the repository root (needs the ``dlm`` extra, PanelAero; about a minute)::

    .venv/bin/python benchmarks/dlm_mach_nodes.py

On ``examples/x57_like.toml`` with ``aero = "dlm"`` (8 x 37 panels): Q(k, M) on the free wing
DOFs at the modal state space's reduced frequencies (``dlm_rfa.tracking_ks``) computed at Mach
0, 0.1, ..., 0.8; printed: the Roger fit's own error at each Mach (what the state space's fits
already carry), and the error of Q interpolated linearly in Mach, or in 1/beta, between two
nodes 0.2 or 0.3 apart at their midpoint, against the AICs computed there (max |dQ| / max |Q|),
beside the Prandtl-Glauert estimate (h^2/8)(1 + 2M^2)/(1 - M^2)^2 of the linear-in-Mach error.
The error falls as the step squared: a step half as long has a quarter of it.
"""
import dataclasses
from pathlib import Path

import numpy as np
from threadpoolctl import threadpool_limits

from propwhirl.io.model_files import load_model
from propwhirl.model.aerodynamics import dlm_rfa
from propwhirl.model.aerodynamics.dlm import DlmTables
from propwhirl.model.structure.assembly import free_dofs

ROOT = Path(__file__).resolve().parents[1]


def pg_estimate(mach: float, step: float) -> float:
    m2 = mach * mach
    return step ** 2 / 8.0 * (1.0 + 2.0 * m2) / (1.0 - m2) ** 2


def main() -> None:
    threadpool_limits(1)
    m = load_model(ROOT / "examples" / "x57_like.toml")
    m = m.with_(wing=dataclasses.replace(m.wing, aero="dlm", dlm_chordwise_panels=8))
    tables = DlmTables(processes=1)
    aero = tables.aero(m.wing)
    ks = dlm_rfa.tracking_ks()
    keep = free_dofs(aero.n_nodes)
    machs = [0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.75, 0.8]
    Q = {}
    for mm in machs:
        fit = dlm_rfa.column_fit(aero, mm, ks)
        Q[mm] = np.stack([aero.column_node(mm, i)[np.ix_(keep, keep)]
                          for i in dlm_rfa.TRACKING_K_NODES])
        print(f"Roger fit error at Mach {mm:g}: {fit.error:.2e}")

    def between(a, b, x, inverse_beta):
        f = (lambda z: 1 / np.sqrt(1 - z * z)) if inverse_beta else (lambda z: z)
        t = (f(x) - f(a)) / (f(b) - f(a))
        return (1 - t) * Q[a] + t * Q[b]

    print("| nodes | midpoint | linear in Mach | linear in 1/beta | PG estimate (Mach) |")
    print("|---|---:|---:|---:|---:|")
    for a, b, x in [(0.0, 0.2, 0.1), (0.0, 0.3, 0.1), (0.0, 0.3, 0.2), (0.2, 0.4, 0.3),
                    (0.3, 0.5, 0.4), (0.4, 0.6, 0.5), (0.5, 0.7, 0.6), (0.6, 0.8, 0.7),
                    (0.7, 0.8, 0.75)]:
        ref = np.abs(Q[x]).max()
        e = [np.abs(between(a, b, x, inv) - Q[x]).max() / ref for inv in (False, True)]
        print(f"| {a:g}-{b:g} | {x:g} | {e[0]:.2e} | {e[1]:.2e} | {pg_estimate(b, b - a):.2e} |")


if __name__ == "__main__":
    main()
