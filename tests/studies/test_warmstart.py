"""Warm-started maps (propwhirl.studies.warmstart): the same rows as a full-range map to the
crossing accuracy, fewer speeds analysed, the full-range fallback, conventions, back ends."""
from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from propwhirl.cases.ch09_baseline import (baseline_flight, baseline_propeller, baseline_wing,
                                           isolated_baseline_propeller)
from propwhirl.model.systems import Installation, PropellerWing
from propwhirl.studies import paths as P
from propwhirl.studies.sweeps import critical_map, run_points
from propwhirl.studies.warmstart import (_corners, clipped_grid, coarse_indices,
                                        warm_started_rows)
from propwhirl.validate import InputError

SPEEDS = np.arange(10.0, 351.0, 20.0)
XTOL = 0.01


def small_wing():
    """5-element baseline wing, the baseline propeller flexibly mounted at the tip (fast)."""
    return PropellerWing(baseline_wing(5), baseline_flight(),
                         (Installation(baseline_propeller(), 5.7),), name="small wingtip")


AXES = [("propellers[0].propeller.f_theta", np.linspace(4.0, 12.0, 5)),
        ("propellers[0].propeller.f_psi", np.linspace(4.0, 12.0, 5))]


def assert_same_rows(a, b, xtol=XTOL):
    for col in ("kind", "event", "critical_mode", "content", "whirl", "propeller", "error"):
        assert np.array_equal(a.columns[col], b.columns[col]), col
    for col in ("critical_speed", "static_divergence_speed"):
        x, y = a.columns[col], b.columns[col]
        assert np.array_equal(np.isnan(x), np.isnan(y)), col
        d = np.abs(x - y)
        assert np.all(d[np.isfinite(d)] <= xtol), col
    f, g = a.columns["critical_frequency"], b.columns["critical_frequency"]
    d = np.abs(f - g) / np.maximum(np.abs(g), 1.0)
    assert np.all(d[np.isfinite(d)] <= 1e-3)


def test_coarse_indices_and_corners():
    assert coarse_indices(11, 5).tolist() == [0, 5, 10]
    assert coarse_indices(12, 5).tolist() == [0, 5, 10, 11]
    assert coarse_indices(1, 5).tolist() == [0]
    c = [coarse_indices(11, 5), coarse_indices(12, 5)]
    assert sorted(_corners((2, 7), c)) == [(0, 5), (0, 10), (5, 5), (5, 10)]
    assert sorted(_corners((5, 11), c)) == [(5, 11)]
    assert sorted(_corners((5, 3), c)) == [(5, 0), (5, 5)]


def test_clipped_grid():
    g = np.arange(10.0, 351.0, 20.0)
    assert clipped_grid(g, 100.0).tolist() == [10.0, 30.0, 50.0, 70.0, 90.0, 100.0]
    assert clipped_grid(g, 90.0).tolist() == [10.0, 30.0, 50.0, 70.0, 90.0]
    assert clipped_grid(g, 400.0) is None and clipped_grid(g, 5.0) is None


@pytest.fixture(scope="module")
def cold_and_warm():
    model = small_wing()
    stats = {}
    # the brute-force reference: every point dense over its whole range
    cold = critical_map(model, AXES, speeds=SPEEDS, method="dense", warm_start=False)
    warm_map = critical_map(model, AXES, speeds=SPEEDS, stats=stats)      # the defaults
    return cold, warm_map, stats


def test_the_default_map_is_the_brute_force_reference_to_the_crossing_accuracy(cold_and_warm):
    """issue 26.1: a map with the default options (warm-started, method "auto": reduced on a
    wing) gives the rows of the brute-force reference to the crossing accuracy."""
    cold, warm, stats = cold_and_warm
    assert stats["coarse"] + stats["fine"] == 25           # warm-started by default
    assert_same_rows(warm, cold)
    assert set(warm.columns["kind"].ravel()) <= {"flutter", "divergence"}


def test_warm_start_clips_the_fine_points(cold_and_warm):
    _, _, stats = cold_and_warm
    # 5 × 5 with stride 5: the coarse points are rows/columns 0 and 4
    assert stats["coarse"] == 4 and stats["fine"] == 21
    assert stats["clipped"] == 21 and stats["again"] == 0


def test_a_point_above_its_clipped_range_is_analysed_again():
    """The isolated propeller's flutter speed is 243 and 229 m/s at f_psi = 4 and 5 Hz, 257
    and 298 m/s at 8 and 9 Hz: with the coarse points at 4 and 5 Hz (the ends) and the range
    of the others cut right at their speed, the interior points find nothing below it and are
    analysed again over the whole range — and still equal the full-range sweep."""
    model = isolated_baseline_propeller()
    values = np.array([4.0, 9.0, 8.0, 5.0])
    cold = critical_map(model, [("propeller.f_psi", values)], speeds=SPEEDS, warm_start=False)
    variants = [P.set_values(model, {"propeller.f_psi": x}) for x in values]
    stats = {}
    rows = warm_started_rows(variants, [str(x) for x in values], (4,), [SPEEDS] * 4,
                             lambda ms, **kw: run_points(ms, **kw), margin=1.0 + 1e-9,
                             stats=stats)
    v = cold.columns["critical_speed"]
    assert min(v[1], v[2]) > max(v[0], v[3])
    assert stats == {"coarse": 2, "fine": 2, "clipped": 2, "again": 2}
    speeds = np.array([r["critical_speed"] for r in rows])
    assert np.max(np.abs(speeds - cold.columns["critical_speed"])) <= XTOL
    assert [r["kind"] for r in rows] == list(cold.columns["kind"])


def test_thesis_low_speed_convention_is_not_warm_started():
    stats = {}
    critical_map(small_wing(), [AXES[0]], speeds=SPEEDS, warm_start=True, low_speed=False,
                 static_divergence=False, stats=stats)
    assert stats == {"analyses": 5}


def test_serial_and_processes_give_identical_warm_maps(cold_and_warm):
    _, warm, _ = cold_and_warm
    par = critical_map(small_wing(), AXES, speeds=SPEEDS, processes=2)
    for col, x in warm.columns.items():
        y = par.columns[col]
        if x.dtype.kind == "f":
            assert np.array_equal(x, y, equal_nan=True), col
        else:
            assert np.array_equal(x, y), col


def test_bad_options_are_refused():
    with pytest.raises(InputError, match="warm_start"):
        critical_map(small_wing(), [AXES[0]], warm_start="yes")
    with pytest.raises(InputError, match="method"):
        critical_map(small_wing(), [AXES[0]], method="fast")


def test_an_interrupted_warm_map_resumes_to_the_same_result(tmp_path, cold_and_warm):
    """Interrupted in its fine pass, a warm-started map keeps the coarse pass and the fine
    points done (one partial-results file per pass) and resumes to the same result."""
    from propwhirl.studies.execution import Checkpoint, Interrupted
    from propwhirl.studies.warmstart import pass_checkpoints

    _, warm, _ = cold_and_warm
    cp = Checkpoint(tmp_path / "map.json.partial", interval=0.0)
    calls = []

    def stop_in_fine_pass(done, total):      # one count over the passes (issue 35 item 8)
        calls.append((done, total))
        if total == 25 and done == 4 + 5:
            raise KeyboardInterrupt

    with pytest.raises(Interrupted):
        critical_map(small_wing(), AXES, speeds=SPEEDS, checkpoint=cp,
                     progress=stop_in_fine_pass)
    coarse, fine, again = (c.path for c in pass_checkpoints(cp))
    assert coarse.exists() and fine.exists() and not again.exists()
    seen = []
    resumed = critical_map(small_wing(), AXES, speeds=SPEEDS,
                           checkpoint=Checkpoint(cp.path, resume=True),
                           progress=lambda done, total: seen.append((done, total)))
    assert seen[0] == (4, 25)           # the coarse pass was not redone
    assert min(d for d, _ in seen[1:]) == 4 + 5     # nor the 5 fine points done
    for col, x in warm.columns.items():
        assert np.array_equal(x, resumed.columns[col], equal_nan=x.dtype.kind == "f"), col


def test_cells_whose_corners_have_no_wing_divergence_are_not_clipped():
    """A stiff wing (GJ × 100) does not diverge below 350 m/s: its fine points would find no
    divergence below a clipped top and be analysed twice, so they are analysed once, over the
    whole range — the map is the full-range one and costs no more than it."""
    stiff = small_wing()
    stiff = stiff.with_(wing=replace(stiff.wing, GJ=100.0 * stiff.wing.GJ))
    axes = [("propellers[0].propeller.f_theta", np.linspace(6.0, 12.0, 5)),
            ("propellers[0].propeller.f_psi", np.linspace(4.0, 12.0, 3))]
    cold = critical_map(stiff, axes, speeds=SPEEDS, method="reduced", warm_start=False)
    assert np.all(np.isnan(cold.columns["static_divergence_speed"]))
    assert np.sum(cold.columns["kind"] != "none") >= 5     # criticals without wing divergence
    stats = {}
    warm = critical_map(stiff, axes, speeds=SPEEDS, method="reduced", warm_start=True,
                        stats=stats)
    assert stats["clipped"] == 0 and stats["again"] == 0
    assert stats["coarse"] + stats["fine"] == 15
    assert_same_rows(warm, cold)


def test_a_progress_callback_sees_one_count_over_the_passes():
    """Issue 35 item 8: a callable saw (4, 4) for the coarse pass, then (0, 21): the total
    jumped mid-run. Now one count over the passes against every point from the start."""
    seen = []
    stats = {}
    critical_map(small_wing(), AXES, speeds=SPEEDS, stats=stats,
                 progress=lambda done, total: seen.append((done, total)))
    assert stats["coarse"] < 25 and seen
    totals = [t for _, t in seen]
    assert totals[0] == 25 and totals == sorted(totals)                 # never falls back
    dones = [d for d, _ in seen]
    assert dones == sorted(dones) and seen[-1] == (25 + stats["again"], 25 + stats["again"])
