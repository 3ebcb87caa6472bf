"""`propwhirl map --method reduced --warm-start`: the same map as the full-range one to the
crossing accuracy, and no partial-results file left behind."""
from __future__ import annotations

import numpy as np

from propwhirl.app import cli
from propwhirl.studies.sweeps import CriticalMap


def test_warm_started_reduced_map_equals_the_full_range_map(small_file, tmp_path, capsys):
    base = ["map", str(small_file), "--param", "propellers[0].propeller.f_theta", "4", "12", "6",
            "--param", "propellers[0].propeller.f_psi", "4", "12", "6",
            "--speeds", "10", "350", "20", "--quiet"]
    warm, cold = tmp_path / "warm.json", tmp_path / "cold.json"
    assert cli.main(base + ["--method", "reduced", "--warm-start", "--json", str(warm)]) == 0
    assert cli.main(base + ["--json", str(cold)]) == 0
    capsys.readouterr()
    a, b = CriticalMap.load(warm), CriticalMap.load(cold)
    assert np.array_equal(a.columns["kind"], b.columns["kind"])
    assert np.array_equal(a.columns["critical_mode"], b.columns["critical_mode"])
    assert np.nanmax(np.abs(a.critical_speed - b.critical_speed)) <= 0.01
    assert sorted(p.name for p in tmp_path.iterdir()) == ["cold.json", "warm.json"]


def test_method_choices_are_checked(small_file, capsys):
    assert cli.main(["map", str(small_file), "--param", "wing.EI*", "1", "2", "2",
                     "--param", "wing.GJ*", "1", "2", "2", "--method", "fast"]) == 2
    assert "argument --method: invalid choice: 'fast'" in capsys.readouterr().err
