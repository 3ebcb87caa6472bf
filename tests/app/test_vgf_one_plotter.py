"""One V-g-f plotter (issue 38, item 2): an analysis's V-g-f (``vgf_plot.vgf``) and a campaign
point's (``campaign_plot.point_vgf``, the certification report's) are both drawn by
``vgf_plot.vgf_figure`` — family colours, the emphasised modes named, the instabilities marked
and labelled — the campaign's with its requirements."""
from __future__ import annotations

import dataclasses
from pathlib import Path

import pytest

pytest.importorskip("matplotlib")

from matplotlib.colors import to_rgba  # noqa: E402

from propwhirl import io  # noqa: E402
from propwhirl.analysis.stability import analyse  # noqa: E402
from propwhirl.app import plots  # noqa: E402
from propwhirl.app.plots import campaign_plot, layout, vgf_plot  # noqa: E402
from propwhirl.io.campaign_files import load_campaign  # noqa: E402
from propwhirl.studies import campaign as C  # noqa: E402

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


@pytest.fixture(scope="module")
def point():
    """examples/wingtip_campaign.toml: the nominal case at its first altitude."""
    camp = C.from_spec(load_campaign(EXAMPLES / "wingtip_campaign.toml"))
    camp = dataclasses.replace(camp, cases=camp.cases[:1], points=camp.points[:1])
    return C.run_campaign(camp).rows[0]


#: a damping requirement g = 2ζ ≥ G_MIN drawn on the campaign point's V-g-f
G_MIN = 0.02


def _recording(monkeypatch) -> list:
    calls = []
    real = vgf_plot.vgf_figure
    monkeypatch.setattr(vgf_plot, "vgf_figure",
                        lambda *a, **k: calls.append((a, k)) or real(*a, **k))
    return calls


def test_an_analysis_and_a_campaign_point_have_one_vgf_plotter(point, monkeypatch):
    calls = _recording(monkeypatch)
    plots.vgf(analyse(io.load_model(EXAMPLES / "wingtip.toml")))
    row, g = point, G_MIN
    campaign_plot.point_vgf(row, g)
    assert len(calls) == 2
    (_, first), (curves, second) = calls[0], calls[1]
    assert first.get("requirements") is None
    req = second["requirements"]
    assert (req.V_D, req.V_required, req.min_damping_g) == (row.V_D, row.V_required, g)
    assert curves[0].labels == tuple(row.plot.modes)


def test_a_campaign_point_is_drawn_in_family_colours_with_its_requirements(point):
    """The report's V-g-f (before: a colour per mode from a cycle, backward 1 orange): the
    whirl modes in their family's colour, the critical speed in the legend, every event of
    its modes labelled."""
    row, g = point, G_MIN
    fig = campaign_plot.point_vgf(row, g)
    ax_z = fig.axes[0]
    curves = {ln.get_label(): ln for ln in ax_z.get_lines() if ln.get_label() in row.plot.modes}
    for name, family in (("backward 1", "backward whirl"), ("forward 1", "forward whirl")):
        assert to_rgba(curves[name].get_color()) == to_rgba(layout.FAMILY_COLOURS[family])
    legend = [t.get_text() for t in fig.legends[0].get_texts()]
    assert f"V_crit {row.critical_speed:.1f} m/s ({row.kind})" in legend
    assert f"required g ≥ {g:g} (ζ ≥ {0.5 * g:g})" in legend
    labels = [t.get_text() for t in ax_z.texts if t.get_gid() == vgf_plot.LABEL_GID]
    lo, hi = row.plot.V[0], row.plot.V[-1]
    for V, _f, kind, _event, _mode in row.plot.events:
        if lo <= V <= hi:
            assert any(f"{V:.1f} m/s" in t for t in labels), (V, kind, labels)
