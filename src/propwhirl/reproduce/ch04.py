"""Chapter 4: Table 4.1 (Rodden & Rose's propeller derivatives) and the sensitivity of the
inferred, unprinted data behind it (docs/validation.md, "Chapter 4").

The propeller, its operating points and the inferred assumptions are the case of
:mod:`propwhirl.cases.ch04_propeller_aero`.
"""
from __future__ import annotations

import math

from propwhirl.cases.ch04_propeller_aero import TABLE_4_1_BETAS, Table41Assumptions, table_4_1_derivatives
from propwhirl.model.propellers import propeller_aero as aero
from propwhirl.reproduce.harness import load_references, register


#: Table 4.1 rows and the id suffix each one is stored under.
TABLE_4_1_ROWS = {
    "CZ_theta": "CZ_theta", "Cm_theta": "Cm_theta", "Cmq": "Cm_q",
    "CZ_psi": "CZ_psi", "Cm_psi": "Cm_psi",
}


def table_4_1_values(a: Table41Assumptions = Table41Assumptions()) -> dict[str, float]:
    """{"t4.1/beta25/CZ_theta": value, ...} for the 25 entries of Table 4.1."""
    d = table_4_1_derivatives(a)
    out = {}
    for i, beta in enumerate(TABLE_4_1_BETAS):
        for row, name in TABLE_4_1_ROWS.items():
            out[f"t4.1/beta{beta}/{row}"] = float(getattr(d, name)[i])
    return out


@register("t4.1")
def table_4_1() -> dict[str, float]:
    """Table 4.1 with the inferred planform and advance-ratio relation."""
    return table_4_1_values()


#: Variations of the inferred data for the sensitivity table of docs/validation.md.
SENSITIVITY_CASES: dict[str, Table41Assumptions] = {
    "inferred (baseline)": Table41Assumptions(),
    "hub ratio 0.20": Table41Assumptions(hub_ratio=0.20),
    "hub ratio 0.24": Table41Assumptions(hub_ratio=0.24),
    "alpha_0L = -2 deg": Table41Assumptions(zero_lift_deg=-2.0),
    "alpha_0L = -4 deg": Table41Assumptions(zero_lift_deg=-4.0),
    "mu = tan(beta - 3 deg) (eq. 9.1)": Table41Assumptions(advance_rule="thesis_eq_9_1"),
    "mu = 0.75 tan(beta - 3 deg)": Table41Assumptions(zero_lift_deg=3.0),
    "A from eq. 4.21 with doubled chord": Table41Assumptions(aspect_ratio_rule="eq_4_21"),
    "linear taper c_tip/c_root = 0.7": Table41Assumptions(taper=0.7),
    "no compressibility": Table41Assumptions(
        settings=aero.AeroSettings(compressibility=False)),
    "no wake (F=1, G=0)": Table41Assumptions(settings=aero.AeroSettings(wake=False)),
}


def table_4_1_sensitivity() -> dict[str, dict[str, float]]:
    """Per variation: max |relative difference| to the thesis values per row, and rms."""
    refs = {r.id: r.thesis for r in load_references() if r.id.startswith("t4.1/")}
    out = {}
    for label, a in SENSITIVITY_CASES.items():
        vals = table_4_1_values(a)
        rel = {k: vals[k] / refs[k] - 1.0 for k in refs}
        row = {r: max(abs(e) for k, e in rel.items() if k.endswith("/" + r))
               for r in TABLE_4_1_ROWS}
        row["rms"] = math.sqrt(sum(e * e for e in rel.values()) / len(rel))
        out[label] = row
    return out
