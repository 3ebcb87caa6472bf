"""The engine's result types re-read from corrupt dicts (Sweep, CriticalPoint, Criticals,
FrequencyZero, Analysis .from_dict): an InputError naming the key, never a KeyError,
TypeError or a silently accepted NaN or shape mismatch (issue 9, item 6)."""
from __future__ import annotations

import copy
import json
import math

import pytest

from propwhirl.engine import Analysis, CriticalPoint, Criticals, FrequencyZero, Sweep
from propwhirl.validate import InputError


@pytest.fixture(scope="module")
def doc(section_analysis) -> dict:
    an = section_analysis[3]
    assert an.criticals.points, "the section must have a crossing to corrupt"
    return json.loads(json.dumps(an.to_dict()))


def test_round_trip_is_exact(doc):
    assert Analysis.from_dict(doc).to_dict() == doc


def at(d, where):
    for k in where:
        d = d[k]
    return d


@pytest.mark.parametrize("where, value, match", [
    (("sweep", "V"), "fast", r"sweep\.V: must be a list"),
    (("sweep", "V"), [1.0, math.nan], r"sweep\.V: holds non-finite numbers"),
    (("sweep", "V"), [1.0, 2.0, 3.0], r"sweep\.eigenvalues\.re: shape \(12, 4\): axis 0 must have 3"),
    (("sweep", "V"), [5.0, 1.0] + [float(x) for x in range(10, 20)], r"sweep\.V: speeds must increase"),
    (("sweep", "floor"), [1.0], r"sweep\.floor: shape \(1,\): axis 0 must have 12"),
    (("sweep", "eigenvectors", "im"), [[[0.0]]], r"sweep\.eigenvectors\.im: shape \(1, 1, 1\)"),
    (("sweep", "dlam_dV", "re"), None, r"sweep\.dlam_dV\.re: must be a list, got null"),
    (("criticals", "points", 0, "V"), math.inf, r"criticals\.points\[0\]\.V: must be a finite"),
    (("criticals", "points", 0, "kind"), "buzz", r"criticals\.points\[0\]\.kind: = 'buzz'"),
    (("criticals", "points", 0, "mode"), 17, r"criticals\.points: mode id 17 is outside"),
    (("criticals", "points", 0, "bracket"), [2.0, 1.0], r"bracket: = \[2\.0, 1\.0\] is invalid"),
    (("criticals", "points", 0, "eigenvalue"), 1.0, r"eigenvalue: must be an object"),
    (("criticals", "humps"), {}, r"criticals\.humps: must be a list"),
    (("criticals", "unstable_at_start"), [-1], r"unstable_at_start: mode ids must be >= 0"),
    (("criticals", "stats"), [], r"criticals\.stats: must be an object of integer counters"),
])
def test_corrupt_analysis(doc, where, value, match):
    d = copy.deepcopy(doc)
    at(d, where[:-1])[where[-1]] = value
    with pytest.raises(InputError, match=match):
        Analysis.from_dict(d)


@pytest.mark.parametrize("cls", [Sweep, CriticalPoint, Criticals, FrequencyZero, Analysis])
@pytest.mark.parametrize("bad", [None, [], "x", {}, {"unknown": 1}])
def test_not_a_dict_or_missing_keys(cls, bad):
    with pytest.raises(InputError, match="must be an object|missing key"):
        cls.from_dict(bad)


def test_frequency_zero(doc):
    fz = {"mode": 1, "label": "m", "V": 10.0, "bracket": [9.99, 10.01]}
    assert FrequencyZero.from_dict(fz).bracket == (9.99, 10.01)
    with pytest.raises(InputError, match=r"frequency_zero\.V: must be a finite number"):
        FrequencyZero.from_dict(dict(fz, V="10"))
    with pytest.raises(InputError, match=r"frequency_zero: unknown key 'extra'"):
        FrequencyZero.from_dict(dict(fz, extra=0))
