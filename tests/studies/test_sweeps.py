"""Sweeps and maps of the critical speed (propwhirl.studies.sweeps): each point equals a direct
analysis of the variant, the dominant propeller, files, parallel == serial."""
from __future__ import annotations

import json
import math

import numpy as np
import pytest

from propwhirl.analysis.stability import analyse
from propwhirl.cases.ch09_baseline import (baseline_flight, baseline_propeller, baseline_wing,
                                           isolated_baseline_propeller)
from propwhirl.model.systems import Installation, PropellerWing
from propwhirl.studies import paths as P
from propwhirl.studies.critical import critical_instability, wing_divergence_predicate
from propwhirl.studies.sweeps import CriticalMap, map2d, sweep
from propwhirl.validate import InputError

SPEEDS = np.arange(10.0, 351.0, 20.0)


def small_two_propeller_model():
    """5-element baseline wing with propellers at 2.28 m and the tip (fast)."""
    p = baseline_propeller()
    return PropellerWing(baseline_wing(5), baseline_flight(),
                         (Installation(p, 2.28), Installation(p, 5.7)), name="small two-propeller")


@pytest.fixture(scope="module")
def small_map():
    m = small_two_propeller_model()
    return m, map2d(m, ("propellers[1].propeller.f_theta", [4.0, 9.0]),
                    ("wing.GJ*", [0.7, 1.4]), speeds=SPEEDS)


def test_each_point_equals_a_direct_analysis_of_the_variant(small_map):
    m, r = small_map
    assert r.shape == (2, 2) and len(r) == 4
    for i, ft in enumerate([4.0, 9.0]):
        for j, f in enumerate([0.7, 1.4]):
            variant = P.set_values(m, {"propellers[1].propeller.f_theta": ft, "wing.GJ*": f})
            assert variant.propellers[1].propeller.f_theta == ft
            assert variant.wing.GJ == pytest.approx(f * m.wing.GJ)
            c = analyse(variant, SPEEDS).critical
            assert r.critical_speed[i, j] == c.V
            assert r.columns["critical_frequency"][i, j] == c.frequency_hz
            assert r.kind[i, j] == c.kind and r.columns["critical_mode"][i, j] == c.label
            lead = max(c.participation.propellers, key=lambda p: p.share)
            assert r.columns["propeller"][i, j] == lead.propeller
            assert r.columns["propeller_share"][i, j] == lead.share
    # the parameters change the answer (the map is not one number repeated)
    assert len(set(np.round(r.critical_speed.ravel(), 6))) > 1


def test_axes_carry_units_and_the_design_point(small_map):
    m, r = small_map
    a, b = r.axes
    assert (a.path, a.unit, a.design) == ("propellers[1].propeller.f_theta", "Hz", 7.0)
    assert (b.path, b.unit, b.design) == ("wing.GJ*", "", 1.0)
    assert a.label == "propellers[1].propeller.f_theta [Hz]" and b.label == "wing.GJ* (factor)"
    X, Y = r.grids()
    assert X[1, 0] == 9.0 and Y[0, 1] == 1.4


def test_thesis_convention_goes_through_studies_critical():
    m = small_two_propeller_model()
    r = sweep(m, "propellers[0].propeller.f_psi", [3.0, 7.0], speeds=SPEEDS,
              static_divergence=False, low_speed=False)
    assert "thesis convention" in r.convention
    for k, f in enumerate([3.0, 7.0]):
        variant = P.set_value(m, "propellers[0].propeller.f_psi", f)
        a = analyse(variant, SPEEDS)
        e = critical_instability(a, static_divergence=False, low_speed=False,
                                 is_wing_divergence=wing_divergence_predicate(variant, a))
        assert r.critical_speed[k] == e.V and r.kind[k] == e.kind


def test_isolated_sweep_and_no_instability_points():
    iso = isolated_baseline_propeller()
    r = sweep(iso, "propeller.f_psi", [7.0, 12.0], speeds=[50.0, 150.0, 250.0])
    assert r.columns["kind"].tolist() == ["flutter", "none"]
    assert math.isnan(r.critical_speed[1]) and r.columns["propeller"][1] == 0
    assert r.columns["propeller"][0] == 1 and r.columns["propeller_share"][0] == pytest.approx(1.0)
    text = r.format()
    assert "1 of 2 points: no instability" in text and "design point: propeller.f_psi = 7 Hz" in text


def test_files_round_trip(small_map, tmp_path):
    _, r = small_map
    r.save(tmp_path / "m.json")
    back = CriticalMap.load(tmp_path / "m.json")
    assert back.model_name == r.model_name and back.axes[0].design == 7.0
    for k in r.columns:
        np.testing.assert_array_equal(np.asarray(back.columns[k]), np.asarray(r.columns[k]))
    d = json.loads((tmp_path / "m.json").read_text())
    assert d["format"] == "propwhirl.critical-map/1" and len(d["columns"]["critical_speed"]) == 4
    r.save(tmp_path / "m.csv")
    lines = (tmp_path / "m.csv").read_text().splitlines()
    assert lines[0] == "# propwhirl critical map: 4 rows"
    assert lines[1].startswith("propellers[1].propeller.f_theta [Hz],wing.GJ*,critical_speed [m/s]")
    assert len(lines) == 6
    csv_back = CriticalMap.load(tmp_path / "m.csv")
    np.testing.assert_array_equal(csv_back.critical_speed, r.critical_speed)   # exact text
    np.testing.assert_array_equal(csv_back.axes[1].values, [0.7, 1.4])
    with pytest.raises(InputError, match="not a critical map"):
        CriticalMap.from_dict({"format": "x"})
    (tmp_path / "bad.csv").write_text("a,b\n1,2\n")
    with pytest.raises(InputError, match="not a critical-map table"):
        CriticalMap.load(tmp_path / "bad.csv")


def test_to_dataframe(small_map):
    pd = pytest.importorskip("pandas")
    _, r = small_map
    df = r.to_dataframe()
    assert isinstance(df, pd.DataFrame) and len(df) == 4
    assert df.attrs["units"]["critical_speed"] == "m/s"
    assert df.attrs["units"]["propellers[1].propeller.f_theta"] == "Hz"


def test_parallel_equals_serial():
    iso = isolated_baseline_propeller()
    kw = dict(speeds=np.arange(10.0, 500.0, 25.0))
    a = map2d(iso, ("propeller.f_theta", [4.0, 8.0]), ("propeller.f_psi", [4.0, 8.0]), **kw)
    b = map2d(iso, ("propeller.f_theta", [4.0, 8.0]), ("propeller.f_psi", [4.0, 8.0]), processes=2, **kw)
    assert a.to_dict() == b.to_dict()


def test_bad_input():
    iso = isolated_baseline_propeller()
    with pytest.raises(InputError, match="nearest valid paths: propeller.f_psi"):
        sweep(iso, "propeller.f_ps", [1.0])
    # a value outside the path's declared range stops the study before any analysis (issue 20.6)
    with pytest.raises(InputError, match=r"propeller.f_psi: values = -1 Hz is outside the valid "
                                         r"range \[1e-3, 1000\] Hz"):
        sweep(iso, "propeller.f_psi", [3.0, -1.0], speeds=[100.0, 200.0, 300.0])
    # a value the model refuses is a failing point (issue 12.5): recorded with its message, the
    # others are analysed — never silently dropped
    r = sweep(iso, "propeller.hub_radius", [0.125, 5.0], speeds=[100.0, 200.0, 300.0])
    assert r.kind[0] in ("flutter", "divergence") and r.kind[1] == "error"
    assert r.columns["error"][0] == ""
    assert "hub_radius = 5.0 m is invalid: must be < radius" in r.columns["error"][1]
    assert np.isnan(r.critical_speed[1]) and np.isfinite(r.critical_speed[0])
    back = type(r).from_dict(r.to_dict())
    assert list(back.columns["error"]) == list(r.columns["error"])
    with pytest.raises(InputError, match="non-empty"):
        sweep(iso, "propeller.f_psi", [])
    with pytest.raises(InputError, match="xtol"):
        sweep(iso, "propeller.f_psi", [3.0], xtol=0.0)
