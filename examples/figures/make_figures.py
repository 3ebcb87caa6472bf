"""Render the figures of the four-propeller distributed-propulsion wing into this folder.

    python examples/figures/make_figures.py [OUT]

The baseline wing of Table 9.1 (25 elements) with four baseline propellers (Tables 9.3–9.4)
at y = 1.5, 3.0, 4.5 and 5.7 m: the V-g-f diagram (fine grid), the Campbell diagram, the mode
shape of the first flutter (the critical instability is the wing's static divergence, a real
root) and its animation (GIF, written only when OUT is given).
"""
from __future__ import annotations

import sys
import time
from pathlib import Path

from propwhirl.analysis import analyse
from propwhirl.app import plots
from propwhirl.cases.ch09_baseline import propeller_wing

#: resolution of the committed PNGs [dots per inch]
DPI = 100
#: spanwise positions of the four propellers [m]
POSITIONS = (1.5, 3.0, 4.5, 5.7)


def four_propeller_wing():
    return propeller_wing(POSITIONS, name="four-propeller wing")


def main(out: Path, gif: bool) -> None:
    model = four_propeller_wing()
    t0 = time.perf_counter()
    a = analyse(model)
    print(a.summary())
    print(f"analyse: {time.perf_counter() - t0:.1f} s")
    t0 = time.perf_counter()
    plots.save(plots.vgf(a, model), out / "four_propeller_vgf.png", dpi=DPI)
    print(f"vgf (fine grid): {time.perf_counter() - t0:.1f} s")
    plots.save(plots.campbell(model), out / "four_propeller_campbell.png", dpi=DPI)
    flutter = a.critical_excluding("divergence")
    plots.save(plots.event_mode_shape(a, flutter), out / "four_propeller_mode_flutter.png", dpi=DPI)
    if gif:
        plots.animate_event(a, flutter, out / "four_propeller_mode_flutter.gif")


if __name__ == "__main__":
    target = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent
    main(target, gif=len(sys.argv) > 1)
