"""Mode families (issue 38, item 2): one classifier (``analysis.naming.mode_family``) behind the
Campbell result, the Campbell diagram and the V-g-f, and one table of family colours
(``app.plots.layout.FAMILY_COLOURS``) for every figure."""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("matplotlib")

from matplotlib.colors import to_rgba  # noqa: E402

from propwhirl import io  # noqa: E402
from propwhirl.analysis import campbell as campbell_module  # noqa: E402
from propwhirl.analysis.stability import analyse  # noqa: E402
from propwhirl.app import plots  # noqa: E402
from propwhirl.app.plots import campbell_plot, layout  # noqa: E402

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def test_one_table_of_family_colours_for_every_family():
    """Every family the classifier gives has its colour and hue, in the legends' order, in one
    table the Campbell diagram shares (before: its own, with a family "mode" of its own)."""
    assert tuple(layout.FAMILY_COLOURS) == tuple(layout.FAMILY_MAPS) == campbell_module.FAMILIES
    assert campbell_plot.FAMILY_COLOURS is layout.FAMILY_COLOURS


def test_campbell_diagram_of_arrays_names_its_families_as_the_result_does():
    """Arrays without families: each curve's family from its name by the one classifier — a
    mode neither of the wing nor a whirl is "other" (before: "mode", a family of the diagram
    alone); the legend lists families of :data:`FAMILIES` only."""
    rpm = np.linspace(0.0, 3000.0, 4)
    f = np.column_stack([np.full(4, 2.0), np.full(4, 5.0), 5.0 + rpm / 1000.0])
    fig = plots.campbell_diagram(rpm, f, names=["wing 1", "pitch", "forward 1"])
    legend = [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
    families = [t for t in legend if "P (" not in t and "P of" not in t]
    assert families == ["wing bending", "forward whirl", "other"]
    assert set(families) <= set(campbell_module.FAMILIES)


def test_a_campbell_result_with_any_family_is_read_back(tmp_path):
    """The result file takes every family of the one classifier (before: four of them)."""
    c = campbell_module.CampbellResult(
        rpm=np.array([0.0, 100.0]), frequency_hz=np.array([[1.0, 2.0], [1.0, 2.1]]),
        labels=("wing 1", "mode 2"), slope_hz_per_rpm=np.zeros((2, 2)),
        resolved=np.array([True, True]), families=("wing bending", "other"))
    back = campbell_module.CampbellResult.load(c.save(tmp_path / "c.json"))
    assert back.families == ("wing bending", "other")


def test_vgf_draws_lag_roots_grey_not_as_in_plane_modes():
    """The wingtip model's V-g-f with its lag roots (``include_lag``): a lag root is no mode of
    a family — grey, as "other" — where the V-g-f's own classifier made it "in-plane" (orange:
    "lag" read as the in-plane lead-lag)."""
    a = analyse(io.load_model(EXAMPLES / "wingtip.toml"))
    fig = plots.vgf(a, margin=None, include_lag=True)
    drawn = [ln for ln in fig.axes[0].get_lines() if ln.get_label().startswith("lag ")]
    assert drawn
    for ln in drawn:
        r, g, b, _ = to_rgba(ln.get_color())
        assert r == g == b, (ln.get_label(), ln.get_color())       # a grey: no hue
