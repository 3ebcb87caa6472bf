"""The boundary and clearance figures: axes, labels, line counts."""
from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("matplotlib")

from propwhirl.app import plots  # noqa: E402
from propwhirl.studies.boundary import Boundary, GridMap  # noqa: E402
from propwhirl.studies.clearance import Clearance, Margin  # noqa: E402


def _boundary():
    t = np.linspace(0, np.pi / 2, 9)
    pts = np.column_stack([3 + 4 * np.cos(t), 3 + 4 * np.sin(t)])
    return Boundary("neutral-stability", ("a.f", "b.f"), ("Hz", "Hz"), 150.0, (3.0, 3.0),
                    (12.0, 12.0), (pts,), (False,), (("bounds", "bounds"),),
                    (tuple({"frequency_hz": 1.0} for _ in pts),), 40, pts[4:5], "m")


def test_boundary_plot_has_the_curve_the_grid_and_the_design_point(tmp_path):
    x = y = np.linspace(3, 12, 7)
    X, Y = np.meshgrid(x, y, indexing="ij")
    grid = GridMap(x, y, 4.0 - np.hypot(X - 3, Y - 3))
    fig = plots.boundary_plot(_boundary(), grid, design=(7.0, 7.0), path=tmp_path / "b.png")
    ax = fig.axes[0]
    assert ax.get_xlabel() == "a.f [Hz]" and ax.get_ylabel() == "b.f [Hz]"
    labels = [l.get_label() for l in ax.get_lines()]
    assert any(l.startswith("neutral stability at V = 150 m/s") for l in labels)
    assert "design point" in labels and "start (bracketing search)" in labels
    assert ("max Re λ = 0 read off the grid (linear interpolation: within a cell of the traced "
            "curve)") in labels
    note = " ".join(fig.get_supxlabel().split())       # the grey band explained (issue 35.6)
    assert "the pale band is where it is near zero" in note and "grid" in note
    assert [t.get_text() for t in ax.texts] == ["unstable", "stable"]
    assert len(fig.axes) == 2                      # the colour bar
    assert (tmp_path / "b.png").stat().st_size > 1000


def test_clearance_plot_has_one_bar_per_instability():
    ms = (Margin("divergence", "onset", "wing 1", 143.0, 0.0, 143 / 149.5 - 1, False),
          Margin("flutter", "onset", "forward 1", 159.0, 11.2, 159 / 149.5 - 1, True))
    r = Clearance("m", 130.0, 1.15, 149.5, True, ms[1], ms, (), "x", (1.0, 350.0), 1)
    fig = plots.clearance_plot(r)
    ax = fig.axes[0]
    assert len(ax.patches) == 2 and "cleared to 1.15 V_D" in ax.get_title()
    assert [t.get_text() for t in ax.get_yticklabels()][0].startswith("divergence onset of wing 1")
