"""The V-g-f figure, artist by artist, is what it was before ``vgf_figure`` was split into
small functions (issue 38 item 7: no change of behaviour).

Four figures — an analysis's V-g-f from its own sweep (the wingtip example), one on a fine
grid with the aerodynamic lag roots drawn (the isolated baseline propeller), and a campaign
point's with its requirements and the analysed speeds as dots, with and without the damping
requirement — are reduced to their artists' data (every line's points, colour, width, alpha,
marker, z-order and label; the shaded spans; every text and label with its position; the
legend's entries; the axes' limits and labels) and compared with the fingerprint recorded by
the code before the split (``data/vgf_fingerprint.json``, numbers to 9 significant digits; a
line's points by their count and SHA-256).  ``PROPWHIRL_RECORD_VGF=1`` rewrites it (only when
the drawing is meant to change, or matplotlib's text metrics do).
"""
from __future__ import annotations

import dataclasses
import hashlib
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
    return [None if not np.isfinite(t) else float(f"{t:.9g}") for t in a]


def _points(x) -> dict:
    """A line's coordinates: their count and the SHA-256 of their 9-digit text."""
    values = _num(x)
    return {"n": len(values),
            "sha256": hashlib.sha256(json.dumps(values).encode()).hexdigest()}


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
        patches = [{"type": type(p).__name__, "extent": _num(p.get_extents().bounds),
                    "colour": _colour(p.get_facecolor()), "label": p.get_label()}
                   for p in ax.patches]
        texts = [{"text": t.get_text(), "xy": _num(t.get_position()),
                  "window": _num(t.get_window_extent().bounds), "gid": t.get_gid(),
                  "colour": _colour(t.get_color()), "ha": t.get_ha()}
                 for t in ax.texts]
        axes.append({"xlim": _num(ax.get_xlim()), "ylim": _num(ax.get_ylim()),
                     "xlabel": ax.get_xlabel(), "ylabel": ax.get_ylabel(),
                     "title": ax.get_title(), "position": _num(ax.get_position().bounds),
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
        RECORD.write_text(json.dumps(figures, indent=1, sort_keys=True, ensure_ascii=False)
                          + "\n")
    recorded = json.loads(RECORD.read_text())
    assert set(recorded) == set(figures)
    for name, fp in figures.items():
        was = recorded[name]
        assert len(fp["axes"]) == len(was["axes"]), name
        for i, (ax, ax_was) in enumerate(zip(fp["axes"], was["axes"])):
            for key in ax_was:
                assert json.loads(json.dumps(ax[key])) == ax_was[key], (name, i, key)
        assert fp["legends"] == was["legends"], name
        assert json.loads(json.dumps(fp["legend_handles"])) == was["legend_handles"], name


def test_the_fingerprint_sees_a_change(figures):
    """The comparison can fail: one line's colour changed is seen."""
    fp = json.loads(json.dumps(figures["campaign point"]))
    fp["axes"][0]["lines"][0]["colour"] = [0.0, 0.0, 0.0, 1.0]
    assert fp != json.loads(RECORD.read_text())["campaign point"]
    assert len(fp["axes"][0]["lines"]) > 10 and fp["axes"][0]["texts"]
