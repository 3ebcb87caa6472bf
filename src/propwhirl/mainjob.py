"""`make run` / `propwhirl run`: the main analysis.

Until the propeller–wing aeroelastic model lands this runs the most complete analysis that
exists: the in-vacuo modes of the baseline wing (Table 9.1) with their bending/torsion
classification, compared with Table 9.2, and the reproduction of every thesis number the
package can compute so far.
"""
from __future__ import annotations

from pathlib import Path

from propwhirl import reproduce
from propwhirl.cases.ch09_baseline import baseline_wing
from propwhirl.vibration import classify_wing_modes


def main(out: Path) -> int:
    out.mkdir(parents=True, exist_ok=True)
    wing = baseline_wing()
    print(f"{wing.name}: {wing.n_elements} elements, semi-span {wing.semi_span} m")
    print("In-vacuo modes (V = 0):")
    rows = classify_wing_modes(wing, count=5)
    for label, omega in rows:
        print(f"  {label:12s} {omega / 6.283185307179586:8.3f} Hz")
    records = reproduce.run()
    table = reproduce.format_table([r for r in records if r.computed is not None])
    print("\nReproduction of the thesis's numbers computed so far:")
    print(table)
    (out / "reproduction.json").write_text(reproduce.to_json(records))
    print(f"\nwrote {out / 'reproduction.json'}")
    return 0
