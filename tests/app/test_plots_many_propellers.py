"""Figures with many propellers (issue 25, item 2): the seven-propeller X-57-like wing's V-g-f
and Campbell diagrams with labels that never collide, families by colour, axes around the
region that matters; the boundary plot's sides and closed curves; clearance bars by pass/fail
with the propeller named."""
from __future__ import annotations

import re
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("matplotlib")

from matplotlib.colors import to_rgba  # noqa: E402

from propwhirl import io  # noqa: E402
from propwhirl.analysis.naming import mode_family  # noqa: E402
from propwhirl.analysis.stability import analyse  # noqa: E402
from propwhirl.analysis.vibration import campbell  # noqa: E402
from propwhirl.app import plots  # noqa: E402
from propwhirl.app.plots import layout, vgf_plot  # noqa: E402
from propwhirl.studies.boundary import Boundary, GridMap  # noqa: E402
from propwhirl.studies.clearance import Clearance, Margin  # noqa: E402

X57 = Path(__file__).resolve().parents[2] / "examples" / "x57_like.toml"
#: speeds of the test's analysis [m/s]: the range of the example file, coarser (cheap; with
#: the reduced method the same seven events as the example's dense analysis, a third of the cost)
SPEEDS = np.linspace(1.0, 250.0, 13)


@pytest.fixture(scope="module")
def x57():
    return io.load_model(X57)


@pytest.fixture(scope="module")
def x57_analysis(x57):
    return analyse(x57, SPEEDS, method="reduced")


def _labels(fig) -> list:
    return [t for ax in fig.axes for t in ax.texts if t.get_gid() == "label"]


def _boxes(fig, texts) -> list:
    """Each label's text box in display pixels, measured here (not by the layout code)."""
    from matplotlib.text import Text

    r = fig.canvas.get_renderer()
    out = []
    for t in texts:
        t.update_positions(r)
        out.append(Text.get_window_extent(t, r))
    return out


def _collisions(boxes) -> list[tuple[int, int]]:
    return [(i, j) for i, a in enumerate(boxes) for j, b in enumerate(boxes) if i < j
            and min(a.x1, b.x1) > max(a.x0, b.x0) and min(a.y1, b.y1) > max(a.y0, b.y0)]


def _check_vgf(fig, analysis):
    ax_z, ax_f = fig.axes[:2]
    texts = _labels(fig)
    boxes = _boxes(fig, texts)
    assert _collisions(boxes) == []
    frame = ax_z.get_window_extent()
    assert all(frame.x0 <= b.x0 and b.x1 <= frame.x1 and frame.y0 <= b.y0 and b.y1 <= frame.y1
               for b in boxes)                       # inside the ζ axes, off the tick labels
    V0, V1 = ax_z.get_xlim()
    flat = [" ".join(t.get_text().split()) for t in texts]
    for e in analysis.events:      # every event in range labelled: its mode, then its speed
        if V0 <= e.V <= V1:
            name, V = analysis.describe(e.label), f"{e.V:.1f} m/s"
            base, _, detail = name.partition(" (")          # rows under a family heading
            assert any(f"of {name} {V}" in t or f"{name}: {V}" in t
                       or (f"{base}:" in t and f" {detail[:-1]}: {V}" in t) for t in flat), e
    return ax_z, ax_f, texts


def test_x57_vgf_labels_never_collide_and_name_every_event(x57_analysis):
    a = x57_analysis
    onsets = [e for e in a.events if e.event == "onset" and e.kind == "flutter"]
    assert len(onsets) >= 5                           # the crowd near 80 m/s of the issue
    fig = plots.vgf(a)
    ax_z, ax_f, texts = _check_vgf(fig, a)
    assert 2 <= len(texts) < len(a.events)            # the crowd near 80 m/s in one table
    # the ζ axis around the crossings (not stretched to ζ ≈ 1 by a mode nearing divergence)
    lo, hi = ax_z.get_ylim()
    assert lo <= -0.05 and 0.0 < hi <= 1.15 * vgf_plot.ZETA_TOP
    # the frequency axis to the emphasised (whirl) modes' range, not to the highest mode's
    assert ax_f.get_ylim()[1] < 1.2 * max(e.frequency_hz for e in onsets) * 2.0
    # emphasised modes bold, coloured by family (backward whirl red), the others thin
    lines = {ln.get_label(): ln for ln in ax_z.get_lines() if not ln.get_label().startswith("_")}
    for e in onsets:
        ln = lines[a.describe(e.label)]
        assert ln.get_linewidth() >= 2.0
        r, g, b, _ = to_rgba(ln.get_color())
        assert r > g and r > b
    assert any(ln.get_linewidth() < 1.0 for ln in lines.values())


def test_vgf_with_long_mode_names_wraps_and_does_not_overprint(x57_analysis):
    """Names that carry the propellers (another change of issue 25) are long: wrapped in the
    labels, still no collision."""
    a = x57_analysis
    sw = a.sweep
    long = {lab: (f"{lab.split()[0]} whirl, propellers 1–6 (collective, mode "
                  f"{lab.split()[-1]})" if lab.startswith(("backward", "forward")) else lab)
            for lab in sw.mode_labels}
    b = replace(a, sweep=sw.relabel([long[lab] for lab in sw.mode_labels]),
                events=tuple(replace(e, label=long[e.label]) for e in a.events),
                content={long.get(k, k): c for k, c in a.content.items()})
    fig = plots.vgf(b)
    _, _, texts = _check_vgf(fig, b)
    assert max(len(line) for t in texts for line in t.get_text().split("\n")) <= vgf_plot.WRAP_ROW


def test_x57_campbell_end_labels_rpm_axes_and_the_aerodynamics_note(x57):
    c = campbell(x57, np.linspace(0.0, 6000.0, 5), mac_min=0.5, min_step=100.0)   # cheap tracking
    assert len(set(c.rpm_ratio)) == 2                 # high-lift and cruise propellers differ
    fig = plots.campbell_diagram(c, title="x57")
    ax = fig.axes[0]
    texts = _labels(fig)
    n = len(texts)
    assert [t.get_text() for t in texts] == [layout.wrap(x) for x in c.labels[:n]]
    assert _collisions(_boxes(fig, texts)) == []
    assert "propellers 1–6" in ax.get_xlabel()
    tops = [child for child in ax.child_axes if child.get_xlabel()]
    assert len(tops) == 1 and "propeller 7" in tops[0].get_xlabel()
    q = c.rpm_ratio[6]                                # its scale: propeller 7's own rpm
    assert tops[0]._functions[0](np.array(6000.0)) == pytest.approx(6000.0 * q)
    assert "aerodynamics off" in ax.get_title()


def test_long_campbell_names_are_wrapped_and_stacked():
    f = np.column_stack([np.linspace(6.0, 7.0, 5) + 0.001 * i for i in range(8)])
    names = [f"backward whirl, propeller {i + 1} and its neighbours (differential)"
             for i in range(8)]
    fig = plots.campbell_diagram(np.linspace(0.0, 4000.0, 5), f, names=names)
    texts = _labels(fig)
    assert len(texts) == 8 and _collisions(_boxes(fig, texts)) == []
    assert all(len(line) <= layout.WRAP for t in texts for line in t.get_text().split("\n"))


def test_mode_family_from_old_and_new_names():
    assert mode_family("backward 3") == "backward whirl"
    assert mode_family("forward whirl, propeller 7") == "forward whirl"
    assert mode_family("wing 2", {"torsion": 0.8, "bending": 0.1}) == "wing torsion"
    assert mode_family("wing 1", {"bending": 0.9}) == "wing bending"
    assert mode_family("in-plane whirl, propeller 2") == "in-plane"
    assert mode_family("plunge") == "other"


def test_place_labels_keeps_crowded_labels_apart():
    from propwhirl.app.plots.canvas import new_figure

    fig = new_figure(figsize=(6.0, 4.0), layout="constrained")
    ax = fig.subplots()
    ax.set_xlim(0.0, 10.0)
    ax.set_ylim(-1.0, 1.0)
    layout.freeze_layout(fig)
    anns = layout.place_labels(ax, [(5.0 + 0.01 * i, 0.0) for i in range(12)],
                               [f"flutter of backward {i}\n80.{i} m/s" for i in range(12)],
                               ["red"] * 12)
    assert len(anns) == 12 and _collisions(_boxes(fig, anns)) == []


# ----------------------------------------------------------------------------- boundary
def _closed_boundary():
    t = np.linspace(0.0, 2.0 * np.pi, 25)[:-1]          # a closed curve, not repeating its start
    pts = np.column_stack([7.0 + 3.0 * np.cos(t), 7.0 + 3.0 * np.sin(t)])
    return Boundary("neutral-stability", ("a.f", "b.f"), ("Hz", "Hz"), 150.0, (3.0, 3.0),
                    (12.0, 12.0), (pts,), (True,), (("closed", "closed"),),
                    (tuple({"frequency_hz": 1.0} for _ in pts),), 40, pts[:1], "m")


def test_boundary_plot_draws_a_closed_curve_closed():
    b = _closed_boundary()
    fig = plots.boundary_plot(b)
    curve = next(ln for ln in fig.axes[0].get_lines()
                 if ln.get_label().startswith("neutral stability"))
    x, y = (np.asarray(d, float) for d in curve.get_data())
    assert (x[0], y[0]) == (x[-1], y[-1]) and x.size == len(b.curves[0]) + 1


@pytest.mark.parametrize("kind", ["neutral-stability", "critical-speed"])
def test_boundary_plot_hatches_and_names_the_unstable_side(kind):
    x = y = np.linspace(3, 12, 7)
    X, Y = np.meshgrid(x, y, indexing="ij")
    inside = 3.0 - np.hypot(X - 7, Y - 7)             # > 0 inside the circle
    # unstable inside: max Re λ > 0 there; or V_crit below the speed there (level V_crit - V)
    grid = GridMap(x, y, inside if kind == "neutral-stability" else -inside)
    fig = plots.boundary_plot(replace(_closed_boundary(), kind=kind), grid)
    ax = fig.axes[0]
    named = {t.get_text(): (t.get_position()) for t in ax.texts}
    assert set(named) == {"stable", "unstable"}
    assert np.hypot(named["unstable"][0] - 7, named["unstable"][1] - 7) < 3.0
    assert np.hypot(named["stable"][0] - 7, named["stable"][1] - 7) > 3.0
    legend = [t.get_text() for t in ax.get_legend().get_texts()]
    assert any(t.startswith("unstable side") for t in legend)


# ----------------------------------------------------------------------------- clearance
def test_clearance_bars_by_pass_or_fail_with_the_propeller_named(x57_analysis):
    a = x57_analysis
    ms = tuple(Margin(e.kind, e.event, e.label, e.V, e.frequency_hz, e.V / 100.0 - 1.0, True)
               for e in a.events)
    r = Clearance("m", 87.0, 1.15, 100.0, False, ms[0], ms, (), "x", (1.0, 250.0), 1)
    fig = plots.clearance_plot(r, analysis=a)
    ax = fig.axes[0]
    for bar, m in zip(ax.patches, ms):
        expect = plots.FAIL_COLOUR if m.margin < 0 else plots.PASS_COLOUR
        assert to_rgba(bar.get_facecolor())[:3] == to_rgba(expect)[:3]
    names = [t.get_text() for t in ax.get_yticklabels()]
    for name, e in zip(names, a.events):
        if e.kind == "flutter":
            top = max(e.participation.propellers, key=lambda p: p.share).propeller
            who = re.search(r"\npropellers? ([\d, ]+) leading$", name)
            assert who and top in [int(x) for x in who.group(1).split(",")], name
    legend = [t.get_text() for t in ax.get_legend().get_texts()]
    assert legend[:2] == ["margin met", "margin not met"]
