"""Render the figures of the four-propeller wing and of the seven-propeller X-57-like wing.

    python examples/figures/make_figures.py [OUT [NAME ...]]

NAME: ``four_propeller`` and/or ``x57_like`` (default both); OUT defaults to this folder.

* four_propeller: the baseline wing of Table 9.1 (25 elements) with four baseline propellers
  (Tables 9.3–9.4) at y = 1.5, 3.0, 4.5 and 5.7 m: the V-g-f diagram (fine grid), the Campbell
  diagram, the mode shape of the first flutter (the critical instability is the wing's static
  divergence, a real root) and its animation (GIF, written only when OUT is given).
* x57_like: ``examples/x57_like.toml`` (six high-lift propellers and a wingtip cruise
  propeller, issue 25): the V-g-f diagram on the fine grid and the Campbell diagram
  (``x57_like_vgf.png``, ``x57_like_campbell.png``).
"""
from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

from propwhirl.analysis import analyse
from propwhirl.app import plots
from propwhirl.cases.ch09_baseline import propeller_wing

#: resolution of the committed PNGs [dots per inch]
DPI = 100
#: resolution of the X-57-like figures [dots per inch]: their labels legible at full width
X57_DPI = 130
#: spanwise positions of the four propellers [m]
POSITIONS = (1.5, 3.0, 4.5, 5.7)


def four_propeller_wing():
    return propeller_wing(POSITIONS, name="four-propeller wing")


#: the seven-propeller example model
X57_FILE = Path(__file__).resolve().parents[1] / "x57_like.toml"


def x57_like(out: Path) -> None:
    """The V-g-f (fine grid) and Campbell diagrams of examples/x57_like.toml."""
    from propwhirl import io

    model = io.load_model(X57_FILE)
    t0 = time.perf_counter()
    a = analyse(model)
    print(a.summary())
    plots.save(plots.vgf(a, model), out / "x57_like_vgf.png", dpi=X57_DPI)
    plots.save(plots.campbell(model, np.linspace(0.0, 6000.0, 61)), out / "x57_like_campbell.png",
               dpi=X57_DPI)
    print(f"x57_like: {time.perf_counter() - t0:.1f} s")


def main(out: Path, gif: bool, names: tuple[str, ...] = ("four_propeller", "x57_like")) -> None:
    unknown = sorted(set(names) - {"four_propeller", "x57_like"})
    if unknown:
        raise SystemExit(f"unknown figure set(s) {unknown}: four_propeller, x57_like")
    if "x57_like" in names:
        x57_like(out)
    if "four_propeller" in names:
        four_propeller(out, gif)


def four_propeller(out: Path, gif: bool) -> None:
    """The four-propeller wing's V-g-f, Campbell and flutter mode shape (and GIF)."""
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
    main(target, gif=len(sys.argv) > 1, names=tuple(sys.argv[2:]) or ("four_propeller", "x57_like"))
