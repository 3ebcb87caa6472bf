"""The figures answer the question: V-g-f of the modes that matter on a fine grid, Campbell by
families with 1P/2P lines per propeller speed, mode shapes in a grid, the GIF, inline display."""
from __future__ import annotations

import io

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st_
from matplotlib.colors import to_rgba
from PIL import Image

from propwhirl.analysis.modes import GyroscopicSystem
from propwhirl.analysis.stability import analyse
from propwhirl.analysis.vibration import campbell
from propwhirl.app import cli, plots
from propwhirl.app.plots import campbell_plot, vgf_plot
from propwhirl.cases.ch09_baseline import (baseline_flight, baseline_propeller, baseline_wing,
                                           propeller_wing,
                                           isolated_baseline_propeller)
from propwhirl.model.protocol import DofMap, PropellerDofs
from propwhirl.model.systems import Installation, PropellerWing
from propwhirl.validate import InputError

PNG = b"\x89PNG\r\n\x1a\n"


def small_wing(positions=(2.28, 5.7), **props) -> PropellerWing:
    """Baseline wing, 5 elements, baseline propellers at `positions` (fast)."""
    return PropellerWing(baseline_wing(5), baseline_flight(),
                         tuple(Installation(baseline_propeller(**props), y) for y in positions),
                         name="small two-propeller wing")


@pytest.fixture(scope="module")
def model():
    return small_wing()


@pytest.fixture(scope="module")
def analysis(model):
    return analyse(model)


@pytest.fixture(scope="module")
def fine(analysis, model):
    return plots.fine_sweep(analysis, model, n_speeds=41)


# ----------------------------------------------------------------------------- display
def test_figures_display_inline_in_jupyter(analysis):
    """IPython renders an object by its _repr_png_ when no formatter for its type is
    registered (the case without pyplot / %matplotlib inline): it must be a real PNG."""
    fig = plots.vgf(analysis)
    png = fig._repr_png_()
    assert png.startswith(PNG)
    w, h = Image.open(io.BytesIO(png)).size
    assert (w, h) == (round(fig.get_figwidth() * 100), round(fig.get_figheight() * 100))
    from matplotlib.figure import Figure
    assert isinstance(fig, Figure)


def test_ipython_formatter_shows_the_image(analysis):
    formatters = pytest.importorskip("IPython.core.formatters")
    fmt = formatters.PNGFormatter()
    assert fmt(plots.mode_shape(*plots.event_eigenvector(analysis, analysis.critical)[:2],
                                analysis.dof_map)).startswith(PNG)


# ----------------------------------------------------------------------------- V-g-f
def _mode_lines(ax, analysis, sweep):
    """{mode label: its ζ line}; a line is labelled analysis.describe(label) (names may hold
    parentheses of their own: 'backward whirl, propellers 1–2 (1 of 2, collective; pitch)')."""
    by_text = {analysis.describe(lab): lab for lab in sweep.mode_labels}
    return {by_text[ln.get_label()]: ln for ln in ax.get_lines()
            if ln.get_label() in by_text}


def test_vgf_on_a_fine_grid_with_the_modes_that_matter(analysis, model, fine, monkeypatch):
    monkeypatch.setattr(vgf_plot, "fine_sweep", lambda *a, **k: fine)
    fig = plots.vgf(analysis, model)
    ax_z, ax_f = fig.axes[:2]
    lines = _mode_lines(ax_z, analysis, fine)
    # every mode with an instability is drawn, and no mode far above them
    assert {e.label for e in analysis.events} <= set(lines)
    ids = plots.select_modes(analysis, sweep=fine)
    assert set(lines) == {fine.mode_labels[k] for k in ids}
    top = max(fine.frequency_hz[:, fine.mode_labels.index(e.label)].max() for e in analysis.events)
    f0 = {fine.mode_labels[k]: fine.frequency_hz[0, k] for k in ids}
    assert max(f0.values()) <= vgf_plot.CUTOFF_FACTOR * top
    assert len(lines) < len(plots.select_modes(analysis, sweep=fine, margin=None))
    # the fine grid, not the engine's nodes
    flutter = next(e.label for e in analysis.events if e.kind == "flutter")
    x = np.asarray(lines[flutter].get_xdata(), float)
    np.testing.assert_array_equal(x, fine.V)
    assert x.size > 2 * analysis.sweep.V.size or x.size >= 41
    # the convention on the axis, the shaded unstable half, limits from the data
    assert "ζ < 0: unstable" in ax_z.get_ylabel()
    lo, hi = ax_z.get_ylim()
    shade = [p for p in ax_z.patches if p.get_label() == "unstable (ζ < 0)"]
    assert len(shade) == 1
    y0, y1 = shade[0].get_y(), shade[0].get_y() + shade[0].get_height()   # data units
    assert min(y0, y1) == pytest.approx(lo) and max(y0, y1) == pytest.approx(0.0)
    assert to_rgba(shade[0].get_facecolor())[:3] == to_rgba("red")[:3]
    drawn = np.concatenate([np.asarray(ln.get_ydata(), float) for ln in lines.values()])
    drawn = drawn[np.isfinite(drawn)]
    # the ζ window: around zero, not stretched to ±1; where a curve leaves it, a triangle
    assert lo <= vgf_plot.ZETA_BOTTOM and 0.0 < hi <= 1.15 * vgf_plot.ZETA_TOP and lo > -1.0
    marks = [ln for ln in ax_z.get_lines() if ln.get_marker() in ("^", "v")]
    for ln in lines.values():
        y = np.asarray(ln.get_ydata(), float)
        if ((y > hi) | (y < lo))[np.isfinite(y)].any():
            assert any(to_rgba(m.get_color()) == to_rgba(ln.get_color()) for m in marks)
    # instabilities annotated with V and f
    texts = [" ".join(t.get_text().split()) for t in ax_z.texts]      # labels wrap
    for e in analysis.events:
        if e.event == "onset":
            assert any(f"{e.V:.1f} m/s" in t and analysis.describe(e.label) in t for t in texts)
            if e.kind == "flutter":
                assert any(f"{e.frequency_hz:.2f} Hz" in t for t in texts)
    assert any(getattr(c, "get_ylabel", lambda: "")() == "g = 2ζ" for c in ax_z.child_axes)


def test_fine_sweep_is_the_analysed_model(analysis, fine, model):
    """The fine sweep is dense: every mode of the analysis (the default: reduced, the modes below
    the cut-off) is one of its modes, and with a dense analysis it has exactly its modes."""
    assert fine.V.size >= 41 and fine.V[0] == analysis.sweep.V[0]
    assert "reduced_states" in analysis.sweep.stats
    assert set(analysis.sweep.mode_labels) < set(fine.mode_labels)
    dense = analyse(model, method="dense")
    assert set(plots.fine_sweep(dense, model, n_speeds=5).mode_labels) == set(dense.sweep.mode_labels)
    with pytest.raises(InputError, match="pass the analysed model"):
        plots.fine_sweep(analysis, small_wing((5.7,)), n_speeds=5)


def test_margin_takes_in_a_mode_whose_damping_falls_back():
    """damping_fall: the peak ζ and the lowest ζ after it."""
    from types import SimpleNamespace

    lam = np.array([[-0.05 + 1j, -0.001 + 2j], [-0.3 + 1j, -0.002 + 2j], [-0.01 + 1j, -0.003 + 2j]])
    zeta = -lam.real / np.abs(lam)
    sw = SimpleNamespace(eigenvalues=lam, physical=np.ones((3, 2), bool), damping_ratio=zeta,
                         n_modes=2)
    fall = vgf_plot.damping_fall(sw)
    np.testing.assert_allclose(fall[0], [zeta[1, 0], zeta[2, 0]])
    np.testing.assert_allclose(fall[1], [zeta[2, 1], zeta[2, 1]])   # rising: no fall


# ----------------------------------------------------------------------------- Campbell
def _boxes_overlap(a, b) -> bool:
    return not (a.x1 <= b.x0 or b.x1 <= a.x0 or a.y1 <= b.y0 or b.y1 <= a.y0)


def test_campbell_families_labels_and_excitation_lines(model):
    c = campbell(model, np.linspace(0.0, 6000.0, 13))
    assert set(c.families) <= set(campbell_plot.FAMILY_COLOURS)
    assert {"backward whirl", "forward whirl", "wing bending"} <= set(c.families)
    fig = plots.campbell_diagram(c)
    ax = fig.axes[0]
    curves = [ln for ln in ax.get_lines() if ln.get_label().startswith("_")]
    n = campbell_plot.default_count(c.families, c.frequency_hz)
    assert len(curves) == n
    for i, ln in enumerate(curves):                   # tracked columns, family colours
        np.testing.assert_array_equal(ln.get_ydata(), c.frequency_hz[:, i])
        assert to_rgba(ln.get_color()) == to_rgba(campbell_plot.FAMILY_COLOURS[c.families[i]])
    labelled = {ln.get_label(): ln for ln in ax.get_lines() if not ln.get_label().startswith("_")}
    np.testing.assert_allclose(labelled["1P (f = n/60)"].get_ydata(), c.rpm / 60.0)
    np.testing.assert_allclose(labelled["2P (f = 2n/60)"].get_ydata(), 2.0 * c.rpm / 60.0)
    names = [t.get_text() for t in ax.texts]
    assert names == list(c.labels[:n])
    fig.canvas.draw()
    boxes = [t.get_window_extent() for t in ax.texts]
    assert not any(_boxes_overlap(a, b) for i, a in enumerate(boxes) for b in boxes[i + 1:])
    legend = [t.get_text() for t in ax.get_legend().get_texts()]
    assert "backward whirl" in legend and "forward whirl" in legend


def test_campbell_end_labels_of_six_propellers_do_not_overlap():
    """Issue 35 item 8: six propellers' close backward and forward whirl ends (the baseline
    wing with propellers at nodes 5-25): 6 overlapping pairs of end labels before, when the
    label stacking oscillated between two groupings and stopped; none now."""
    from propwhirl.app.plots.layout import label_boxes
    w = baseline_wing(25)
    six = propeller_wing(tuple(float(w.node_y[i]) for i in (5, 9, 13, 17, 21, 25)), name="six")
    fig = plots.campbell_diagram(campbell(six, np.linspace(0.0, 6000.0, 25)))
    fig.canvas.draw()
    boxes = label_boxes(fig)
    assert len(boxes) >= 12
    assert not any(_boxes_overlap(a, b) for i, a in enumerate(boxes) for b in boxes[i + 1:])


@given(st_.lists(st_.floats(0.0, 100.0), min_size=1, max_size=30), st_.floats(0.1, 10.0))
@settings(max_examples=200, deadline=None)
def test_spread_labels_keeps_every_gap_and_the_order(y, gap):
    """Any curve ends: positions at least `gap` apart in the order of the ends (the stacking
    the Campbell diagram and the V-g-f use), and each pool of labels centred on its ends."""
    from propwhirl.app.plots.canvas import spread_labels
    p = spread_labels(y, gap, lo=-1e9, hi=1e9)
    order = np.argsort(y, kind="stable")
    ps = np.asarray(p)[order]
    assert np.all(np.diff(ps) >= gap - 1e-9 * max(1.0, gap))
    assert abs(np.mean(p) - np.mean(y)) <= 1e-9 * max(1.0, float(np.max(np.abs(y))))


def test_campbell_per_propeller_rpm(model):
    """Propellers at different speeds: one 1P/2P pair per speed, labelled; ratios (1, 1) by
    the per-propeller route give the same matrices as the common-speed route."""
    c = campbell(model, np.linspace(0.0, 4000.0, 9), rpm_ratio=(1.0, 0.5))
    assert c.rpm_ratio == (1.0, 0.5)
    np.testing.assert_allclose(c.propeller_rpm()[:, 1], 0.5 * c.rpm)
    same = campbell(model, np.linspace(0.0, 4000.0, 9))
    assert not np.allclose(c.frequency_hz, same.frequency_hz)
    np.testing.assert_allclose(c.frequency_hz[0], same.frequency_hz[0])   # at rest: equal
    fig = plots.campbell_diagram(c)
    labels = [ln.get_label() for ln in fig.axes[0].get_lines()]
    assert "1P of propeller 1 (at 1 n)" in labels and "1P of propeller 2 (at 0.5 n)" in labels
    assert "2P of propeller 2 (at 0.5 n)" in labels
    assert "propeller 1" in fig.axes[0].get_xlabel()
    Om = np.array([0.0, 37.0, 420.0])
    a = GyroscopicSystem.of(model).matrices(Om)
    b = GyroscopicSystem._per_propeller(model, (1.0, 1.0)).matrices(Om)
    for x, y in zip(a, b):
        np.testing.assert_allclose(x, y, rtol=1e-12, atol=1e-12 * np.abs(x).max())
    with pytest.raises(InputError, match="rpm_ratio"):
        campbell(model, [0.0, 100.0], rpm_ratio=(1.0,))


def test_campbell_default_ratio_follows_the_operation():
    m = PropellerWing(baseline_wing(5), baseline_flight(), (
        Installation(baseline_propeller(operation="constant-speed", rpm=2000.0), 2.28),
        Installation(baseline_propeller(operation="constant-speed", rpm=1500.0), 5.7)))
    assert campbell(m, [0.0, 1000.0]).rpm_ratio == pytest.approx((1.0, 0.75), rel=1e-14)


def test_campbell_of_an_isolated_propeller():
    iso = isolated_baseline_propeller()
    c = campbell(iso, np.linspace(0.0, 4000.0, 9))
    assert c.labels == ("backward 1", "forward 1")
    assert c.families == ("backward whirl", "forward whirl")
    b, f = c.frequency_hz[:, 0], c.frequency_hz[:, 1]
    assert np.all(np.diff(b) < 0) and np.all(np.diff(f) > 0)
    fig = plots.campbell(iso, np.linspace(0.0, 4000.0, 9))
    assert [t.get_text() for t in fig.axes[0].texts] == ["backward 1", "forward 1"]


# ----------------------------------------------------------------------------- mode shapes
def _map(n_props: int) -> DofMap:
    """Two wing nodes and `n_props` propellers (synthetic)."""
    labels = ["node 1 h", "node 1 phi", "node 1 alpha", "node 2 h", "node 2 phi", "node 2 alpha"]
    kinds = ["h", "phi", "alpha"] * 2
    props = []
    for j in range(n_props):
        props.append(PropellerDofs(j, len(labels), len(labels) + 1, 1, True, 0.5 + 0.25 * j, 2))
        labels += [f"propeller {j + 1} theta", f"propeller {j + 1} psi"]
        kinds += ["theta", "psi"]
    return DofMap(tuple(labels), tuple(kinds), (1, 1, 1, 2, 2, 2) + (-1,) * (2 * n_props),
                  (-1,) * 6 + tuple(j for j in range(n_props) for _ in range(2)),
                  propellers=tuple(props), node_y=(0.0, 1.0, 3.0))


@pytest.mark.parametrize("n_props", [1, 4, 8])
def test_mode_shape_grid_scales_with_the_propellers(n_props):
    dm = _map(n_props)
    rng = np.random.default_rng(n_props)
    x = rng.normal(size=dm.n_dof) + 1j * rng.normal(size=dm.n_dof)
    fig = plots.mode_shape(x, -0.1 + 20j, dm)
    orbits = [ax for ax in fig.axes if ax.get_title().startswith("propeller")]
    assert len(orbits) == n_props
    assert [ax.get_title().splitlines()[0] for ax in orbits] == \
        [f"propeller {j + 1} (y = {0.5 + 0.25 * j:.3g} m)" for j in range(n_props)]
    assert fig.get_figwidth() <= 13.0 and fig.get_figheight() <= 12.0   # a grid, not a row
    rows = {round(ax.get_position().y0, 3) for ax in orbits}
    assert len(rows) == -(-n_props // 4)
    wing = [ax for ax in fig.axes if ax.get_title(loc="left") == "wing"]
    assert len(wing) == 1
    assert [t.get_text() for t in wing[0].texts] == [f"P{j + 1}" for j in range(n_props)]
    if n_props > 1:
        amps = [float(ax.get_title().rsplit("amplitude ", 1)[1]) for ax in orbits]
        assert max(amps) == 1.0 and min(amps) > 0


def test_event_mode_shape_of_the_two_propeller_wing(analysis):
    e = next(e for e in analysis.events if e.kind == "flutter")
    fig = plots.event_mode_shape(analysis, e)
    titles = [ax.get_title() for ax in fig.axes if ax.get_title().startswith("propeller")]
    # each propeller's kinetic-energy share of the event's mode (issue 11.1), as in the summary
    want = [f"propeller {q.propeller} (y = {q.y:.3g} m): {100 * q.share:.0f} %"
            for q in e.participation.propellers]
    assert [t.splitlines()[0] for t in titles] == want
    assert [w.split(":")[0] for w in want] == ["propeller 1 (y = 2.28 m)",
                                               "propeller 2 (y = 5.7 m)"]
    assert all(("forward whirl" in t) or ("backward whirl" in t) for t in titles)


# ----------------------------------------------------------------------------- animation
def test_animation_gif(analysis, tmp_path):
    path = plots.animate_event(analysis, analysis.critical_excluding("divergence"),
                               tmp_path / "m.gif", frames=6, fps=10)
    with Image.open(path) as im:
        assert im.format == "GIF" and im.n_frames == 6
        first = np.asarray(im.convert("RGB"))
        im.seek(3)
        assert not np.array_equal(first, np.asarray(im.convert("RGB")))   # it moves
    with pytest.raises(InputError, match="gif"):
        plots.animate_event(analysis, analysis.critical, tmp_path / "m.png")


def test_cli_animates_the_critical_mode(tmp_path):
    from propwhirl import io as pio

    model_file = tmp_path / "m.toml"
    pio.save_model(small_wing(), model_file)
    gif = tmp_path / "crit.gif"
    assert cli.main(["analyse", str(model_file), "--speeds", "1", "350", "50",
                     "--animate", str(gif)]) == 0
    with Image.open(gif) as im:
        assert im.n_frames > 1


def test_time_history_numbers_propellers_from_one():
    from propwhirl.engine import time_response

    iso = isolated_baseline_propeller()
    t = np.linspace(0.0, 0.2, 21)
    r = time_response(iso.state_matrix(100.0)[0], np.array([0.01, 0, 0, 0]), t, iso.state_labels())
    assert plots.time_history(r).get_suptitle() == "propeller 1: time response"
