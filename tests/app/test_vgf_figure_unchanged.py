"""The V-g-f figure, artist by artist, is what it was before ``vgf_figure`` was split into
small functions (issue 38 item 7: no change of behaviour).

Four figures — an analysis's V-g-f from its own sweep (the wingtip example), one on a fine
grid with the aerodynamic lag roots drawn (the isolated baseline propeller), and a campaign
point's with its requirements and the analysed speeds as dots, with and without the damping
requirement — are reduced to their artists' data (every line's points, colour, width, alpha,
marker, z-order and label; the shaded spans; every text and label with its position; the
legend's entries; the axes' limits and labels) and compared with the fingerprint recorded by
the code before the split (``data/vgf_fingerprint.json``).  Only what the code decides is
compared, in data coordinates: computed numbers (a line's points come from eigenvalues) within
a relative 1e-6 of their array's largest magnitude — LAPACK's rounding differs between builds
and machines — and nothing laid out by the font's metrics (text extents, the axes' place on
the page), which changes with matplotlib's release and the fonts installed, not with the code.
``PROPWHIRL_RECORD_VGF=1`` rewrites it (only when the drawing is meant to change).
"""
from __future__ import annotations

import dataclasses
import json
import os
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("matplotlib")

from matplotlib.colors import to_rgba  # noqa: E402

from propwhirl import io  # noqa: E402
from propwhirl.analysis.stability import analyse  # noqa: E402
from propwhirl.app import plots  # noqa: E402
from propwhirl.app.plots import campaign_plot  # noqa: E402
from propwhirl.cases.ch09_baseline import isolated_baseline_propeller  # noqa: E402
from propwhirl.io.campaign_files import load_campaign  # noqa: E402
from propwhirl.studies import campaign as C  # noqa: E402

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
RECORD = Path(__file__).resolve().parent / "data" / "vgf_fingerprint.json"


def _num(x) -> object:
    a = np.asarray(x, dtype=float).ravel()
    return [None if not np.isfinite(t) else float(f"{t:.10g}") for t in a]


def _patch_xy(p) -> np.ndarray:
    """A patch's vertices in its own (data or axes-blended) coordinates, not on the page."""
    if hasattr(p, "get_xy"):
        return np.asarray(p.get_xy(), dtype=float)
    return np.asarray(p.get_path().vertices, dtype=float)


def _same(now, was, where) -> None:
    """`now` equals the recorded `was`: numbers of one list within 1e-6 of the list's largest
    magnitude (1e-9 absolute for a list of zeros), everything else exactly."""
    if isinstance(was, dict):
        assert isinstance(now, dict) and set(now) == set(was), where
        for k in was:
            _same(now[k], was[k], f"{where}.{k}")
    elif isinstance(was, list) and was and all(isinstance(t, (int, float)) or t is None
                                              for t in was) and any(
            isinstance(t, float) for t in was):
        assert isinstance(now, list) and len(now) == len(was), where
        a = np.array([np.nan if t is None else t for t in now], dtype=float)
        b = np.array([np.nan if t is None else t for t in was], dtype=float)
        scale = max(float(np.nanmax(np.abs(b), initial=0.0)), 1e-3)
        assert np.allclose(a, b, rtol=0.0, atol=1e-6 * scale, equal_nan=True), where
    elif isinstance(was, list):
        assert isinstance(now, list) and len(now) == len(was), where
        for i, (u, w) in enumerate(zip(now, was)):
            _same(u, w, f"{where}[{i}]")
    elif isinstance(was, float):
        assert isinstance(now, (int, float)) and abs(now - was) <= 1e-6 * max(abs(was), 1e-3), \
            where
    else:
        assert now == was, where


def _points(x) -> list:
    """A line's coordinates (10 significant digits; compared within a tolerance)."""
    return _num(x)


def _colour(c) -> list:
    return _num(to_rgba(c)) if c is not None and not (isinstance(c, str) and c == "none") \
        else ["none"]


def fingerprint(fig) -> dict:
    """Every artist of `fig` that a reader sees, as plain data."""
    fig.canvas.draw()
    axes = []
    for ax in fig.axes:
        lines = [{"x": _points(ln.get_xdata()), "y": _points(ln.get_ydata()),
                  "colour": _colour(ln.get_color()), "lw": ln.get_linewidth(),
                  "ls": ln.get_linestyle(), "alpha": ln.get_alpha(),
                  "marker": str(ln.get_marker()), "ms": ln.get_markersize(),
                  "mfc": _colour(ln.get_markerfacecolor()),
                  "mec": _colour(ln.get_markeredgecolor()), "zorder": ln.get_zorder(),
                  "label": ln.get_label(), "clip": ln.get_clip_on()}
                 for ln in ax.get_lines()]
        patches = [{"type": type(p).__name__, "xy": _num(_patch_xy(p)),
                    "colour": _colour(p.get_facecolor()), "label": p.get_label()}
                   for p in ax.patches]
        texts = [{"text": t.get_text(), "xy": _num(t.get_position()), "gid": t.get_gid(),
                  "colour": _colour(t.get_color()), "ha": t.get_ha()}
                 for t in ax.texts]
        axes.append({"xlim": _num(ax.get_xlim()), "ylim": _num(ax.get_ylim()),
                     "xlabel": ax.get_xlabel(), "ylabel": ax.get_ylabel(),
                     "title": ax.get_title(),
                     "lines": lines, "patches": patches, "texts": texts})
    legends = [[t.get_text() for t in leg.get_texts()] for leg in fig.legends]
    handles = [[{"type": type(h).__name__,
                 "colour": _colour(h.get_color() if hasattr(h, "get_color")
                                   else h.get_facecolor())}
                for h in leg.legend_handles] for leg in fig.legends]
    return {"axes": axes, "legends": legends, "legend_handles": handles}


@pytest.fixture(scope="module")
def figures() -> dict:
    out = {}
    wingtip = io.load_model(EXAMPLES / "wingtip.toml")
    out["wingtip analysis"] = plots.vgf(analyse(wingtip))
    model = isolated_baseline_propeller()
    a = analyse(model, speeds=[100.0, 200.0, 250.0])
    out["baseline fine with lags"] = plots.vgf(a, model, n_speeds=21, include_lag=True,
                                               margin=None)
    camp = C.from_spec(load_campaign(EXAMPLES / "wingtip_campaign.toml"))
    camp = dataclasses.replace(camp, cases=camp.cases[:1], points=camp.points[:1])
    row = C.run_campaign(camp).rows[0]
    out["campaign point"] = campaign_plot.point_vgf(row, 0.02)
    out["campaign point without requirement"] = campaign_plot.point_vgf(row)
    return {k: fingerprint(f) for k, f in out.items()}


def test_the_vgf_figures_are_drawn_as_before(figures):
    if os.environ.get("PROPWHIRL_RECORD_VGF") == "1":
        RECORD.parent.mkdir(exist_ok=True)
        RECORD.write_text(json.dumps(figures, indent=0, sort_keys=True, ensure_ascii=False)
                          + "\n")
    recorded = json.loads(RECORD.read_text())
    assert set(recorded) == set(figures)
    for name, fp in figures.items():
        _same(json.loads(json.dumps(fp)), recorded[name], name)


def test_the_fingerprint_sees_a_change(figures):
    """The comparison can fail: one line's colour changed is seen."""
    was = json.loads(RECORD.read_text())["campaign point"]
    fp = json.loads(json.dumps(figures["campaign point"]))
    fp["axes"][0]["lines"][0]["colour"] = [0.0, 0.0, 0.0, 1.0]
    with pytest.raises(AssertionError):
        _same(fp, was, "campaign point")
    fp = json.loads(json.dumps(figures["campaign point"]))     # a point moved by 1e-4 of the line
    y = fp["axes"][0]["lines"][0]["y"]
    i = max(j for j, t in enumerate(y) if t is not None)
    y[i] += 1e-4 * max(abs(t) for t in y if t is not None)
    with pytest.raises(AssertionError):
        _same(fp, was, "campaign point")
    assert len(fp["axes"][0]["lines"]) > 10 and fp["axes"][0]["texts"]
