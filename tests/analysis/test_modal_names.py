"""Names and shares on modal models (issue 34 item 4): a six-propeller wing written with
``write_modes`` both ways — mounts in the modes ("on-grid", the docs' way) and own mounts — names
its events and their propellers as the beam model does.  Before: "mode 7" (on-grid, propeller
column empty, wing share 1.0 for a pure whirl mode) and two different events both named
"mode 1" / "propeller 1 psi" (own mounts), named after the largest coordinate."""
from __future__ import annotations

import numpy as np
import pytest

from propwhirl.analysis import analyse
from propwhirl.analysis.participation import events_table
from propwhirl.analysis.stability import ModelAnalysis
from propwhirl.cases.ch09_baseline import baseline_wing, propeller_wing
from propwhirl.io import load_modal_model, write_modes

SPEEDS = np.arange(10.0, 301.0, 10.0)


@pytest.fixture(scope="module")
def six(tmp_path_factory):
    """(beam analysis, on-grid modal analysis, own-mount modal analysis, on-grid model, the
    folder of the modal files)."""
    d = tmp_path_factory.mktemp("six")
    w = baseline_wing(25)
    beam = propeller_wing(tuple(float(w.node_y[i]) for i in (5, 9, 13, 17, 21, 25)), name="six")
    out = [analyse(beam, speeds=SPEEDS)]
    models = []
    for mount in ("on-grid", "own"):
        write_modes(beam, d / f"{mount}.toml", mount=mount)
        models.append(load_modal_model(d / f"{mount}.toml"))
        out.append(analyse(models[-1], speeds=SPEEDS))
    return (*out, models[0], d)


def _leading(e):
    return e.participation.leading.propeller


def test_on_grid_hubs_are_in_the_dof_map(six):
    *_, on_grid, _ = six
    dm = on_grid.dof_map()
    assert dm.propellers == () and [h.number for h in dm.hubs] == list(range(6))
    assert [p.number for p in dm.whirling()] == list(range(6)) and dm.has_structure


def test_on_grid_events_are_named_as_the_beam_models(six):
    beam, grid, *_ = six
    whirls = [e for e in beam.events if e.kind == "flutter"]
    assert len(whirls) >= 3
    assert [e.label for e in grid.events] == [e.label for e in beam.events]
    assert [_leading(e) for e in grid.events] == [_leading(e) for e in beam.events]
    for eb, eg in zip(beam.events, grid.events):
        assert eg.whirl == eb.whirl
        p = eg.participation
        assert p.wing + p.other + sum(s.share for s in p.propellers) == pytest.approx(1.0)
    # a pure whirl mode is the propellers' (was wing share 1.0, no propeller), as much as on
    # the beam model: the hub's pitch and yaw and their coupling with the wing under it
    # (before the coupling was taken out: wing 0.089-0.342 against the beam's 0.004-0.083)
    for eb, eg in zip(beam.events, grid.events):
        if eg.kind != "flutter":
            continue
        assert eg.participation.wing == pytest.approx(eb.participation.wing, abs=2e-3)
        assert [s.share for s in eg.participation.propellers] == pytest.approx(
            [s.share for s in eb.participation.propellers], abs=2e-3)
        assert eg.participation.leading.share > 0.15


def test_own_mounts_give_the_beam_models_names_and_shares(six):
    beam, _, own, *_ = six
    assert [e.label for e in own.events] == [e.label for e in beam.events]
    for eb, eo in zip(beam.events, own.events):
        assert _leading(eo) == _leading(eb)
        assert [s.share for s in eo.participation.propellers] == pytest.approx(
            [s.share for s in eb.participation.propellers], abs=1e-4)


@pytest.mark.parametrize("which", [1, 2])
def test_no_two_different_events_share_a_name(six, which):
    a = six[which]
    onsets = [e for e in a.events if e.event == "onset"]
    assert len({e.label for e in onsets}) == len({e.mode for e in onsets}) == len(onsets)
    assert not any(e.label.startswith(("mode ", "propeller ")) for e in a.events)


def test_the_events_table_names_each_propeller(six):
    _, grid, *_ = six
    t = events_table(grid.events)
    flutter = t["kind"] == "flutter"
    assert set(t["propeller"][flutter]) == set(range(1, 7))
    assert np.all(t["wing_share"][flutter] < 0.5)
    crit = [ln for ln in grid.summary().splitlines() if "flutter onset of backward whirl" in ln]
    assert crit and "propeller" in grid.summary().split("propellers at each event")[1]


def test_hubs_survive_a_saved_analysis(six):
    _, grid, *_ = six
    again = ModelAnalysis.from_dict(grid.to_dict())
    assert again.dof_map == grid.dof_map
    assert [e.participation for e in again.events] == [e.participation for e in grid.events]


def test_certify_on_the_modal_wing_names_the_whirling_propellers(six, capsys):
    """The issue's 'done when': `propwhirl certify` on the six-propeller write_modes wing
    (mounts in the modes): its critical event (the thesis convention: the whirl flutter) is
    named by its propellers and carries each one's share (on main: 'mode 7', no shares)."""
    import json

    from propwhirl.app import cli

    d = six[-1]
    (d / "c.toml").write_text('format = "propwhirl-campaign"\nformat_version = 1\n'
                              'model = "on-grid.toml"\nconvention = "thesis"\n'
                              '[regulation]\nname = "cs25"\n[envelope]\nairspeed = "EAS"\n'
                              'V_D_m_per_s = 150.0\naltitudes_m = [0.0]\n'
                              '[[cases]]\nname = "nominal"\n')
    assert cli.main(["certify", str(d / "c.toml"), "--out", str(d / "out"), "--no-report",
                     "--quiet"]) in (0, 1)
    capsys.readouterr()
    (row,) = json.loads((d / "out" / "campaign.json").read_text())["rows"]
    assert row["kind"] == "flutter" and row["mode"].startswith("backward whirl, propellers 1–6")
    shares = {n: s for n, s, _ in row["propeller_shares"]}
    assert set(shares) == set(range(1, 7)) and max(shares.values()) > 0.15
