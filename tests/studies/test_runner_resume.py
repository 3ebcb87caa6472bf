"""A study (issue 12, item 5): a model invalid at one parameter value is a row with its error,
the others go on; an interrupted study keeps its finished points and resumes to the same table."""
from __future__ import annotations

import json
from dataclasses import replace

import numpy as np
import pytest

from propwhirl.cases.ch09_baseline import baseline_propeller
from propwhirl.studies import parametric as S
from propwhirl.studies import runner
from propwhirl.studies.execution import Checkpoint, Interrupted


def propellers():
    base = baseline_propeller()
    return [replace(base, f_psi=f, K_psi=None) for f in (3.0, 5.0, 7.0, 9.0)]


def study(**kw):
    props = propellers()
    props[2] = replace(props[2], n_blades=8, blade_chord=1.5)     # blades overfill the disc
    return runner.propeller_study("yaw stiffness", "f_psi", "Hz", {"f_psi": [3.0, 5.0, 7.0, 9.0]},
                                  props, models=("isolated",), **kw)


def test_an_invalid_point_is_recorded_and_the_others_go_on():
    t = study()
    err = t.columns["error"]
    assert t.columns["kind"][2] == "error" and "error" not in t.columns["kind"][[0, 1, 3]]
    assert err[2].startswith("InputError: propeller solidity") and "n_blades = 8" in err[2]
    assert list(err[[0, 1, 3]]) == ["", "", ""]
    assert np.isnan(t.columns["critical_speed"][2]) and np.all(np.isfinite(t.columns["critical_speed"][[0, 1, 3]]))
    assert t.units["error"] == ""
    assert "error" in t.to_csv().splitlines()[0]


def test_the_chapter_studies_carry_the_error_column():
    t = S.nacelle_stiffness("yaw", [4.0, 6.0], models=("isolated",))
    assert list(t.columns["error"]) == ["", ""]


@pytest.mark.parametrize("processes", [1, 2])
def test_an_interrupted_study_resumes_to_the_same_table(tmp_path, processes):
    path = tmp_path / "study.json.partial"
    full = study().to_dict()

    def stop_after_two(done, total):
        if done == 2:
            raise KeyboardInterrupt

    with pytest.raises(Interrupted) as info:
        study(processes=processes, checkpoint=Checkpoint(path), progress=stop_after_two)
    assert info.value.done == 2
    data = json.loads(path.read_text())
    fp = data["fingerprint"]
    assert (fp["study"], fp["parameter"], fp["models"]) == ("yaw stiffness", "f_psi", ["isolated"])
    assert fp["variants"].startswith("sha256:") and fp["points"] == "study row"
    assert all(p["key"].startswith("isolated f_psi=") for p in data["points"])

    counts = []
    resumed = study(processes=processes, checkpoint=Checkpoint(path, resume=True),
                    progress=lambda d, t: counts.append(d))
    assert resumed.to_dict() == full
    assert counts[0] == 2 and counts[-1] == 4


def test_a_partial_file_of_another_study_is_refused(tmp_path):
    from propwhirl.validate import InputError

    path = tmp_path / "p.partial"
    study(checkpoint=Checkpoint(path))
    with pytest.raises(InputError, match="was written for another study"):
        S.nacelle_stiffness("yaw", [3.0, 5.0, 7.0, 9.0], models=("isolated",),
                            checkpoint=Checkpoint(path, resume=True))
