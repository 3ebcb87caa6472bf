"""`propwhirl map` with the default options (warm-started, method auto: reduced on a wing): the
same map as the brute-force reference (`--reference`: dense, every point over its whole range)
to the crossing accuracy, and no partial-results file left behind (issue 26.1)."""
from __future__ import annotations

import numpy as np

from propwhirl.app import cli
from propwhirl.studies.sweeps import CriticalMap


def test_the_default_map_equals_the_brute_force_reference(small_file, tmp_path, capsys):
    base = ["map", str(small_file), "--param", "propellers[0].propeller.f_theta", "4", "12", "6",
            "--param", "propellers[0].propeller.f_psi", "4", "12", "6",
            "--speeds", "10", "350", "20", "--quiet"]
    warm, cold = tmp_path / "warm.json", tmp_path / "cold.json"
    assert cli.main(base + ["--json", str(warm)]) == 0
    assert cli.main(base + ["--reference", "--json", str(cold)]) == 0
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


def test_the_reference_refuses_what_contradicts_it(small_file, capsys):
    base = ["map", str(small_file), "--param", "wing.EI*", "1", "2", "2",
            "--param", "wing.GJ*", "1", "2", "2", "--reference"]
    assert cli.main(base + ["--method", "reduced"]) == 2
    assert "--reference is the dense brute-force reference" in capsys.readouterr().err
    assert cli.main(base + ["--warm-start"]) == 2
    assert "--warm-start contradicts it" in capsys.readouterr().err


def test_the_study_options_resolve_to_the_defaults_and_the_reference():
    import argparse

    from propwhirl.app import cli_studies

    def ns(**kw):
        return argparse.Namespace(**{"method": "auto", "warm_start": None, "reference": False,
                                     "thesis_convention": False, **kw})

    assert cli_studies._warm_start(ns()) is True
    assert cli_studies._method(ns()) == "auto"
    assert cli_studies._warm_start(ns(reference=True)) is False
    assert cli_studies._method(ns(reference=True)) == "dense"
    assert cli_studies._warm_start(ns(warm_start=False)) is False
    assert cli_studies._warm_start(ns(thesis_convention=True)) is False
