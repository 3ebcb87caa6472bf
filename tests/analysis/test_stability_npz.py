"""Eigenvectors saved as .npz beside a lean analysis JSON (issue 11, item 5): the JSON is
readable on its own; the npz is checked against it."""
from __future__ import annotations

import json

import numpy as np
import pytest

from propwhirl.analysis import analyse, load
from propwhirl.analysis.stability import eigenvectors_path
from propwhirl.cases.ch09_baseline import isolated_baseline_propeller
from propwhirl.validate import InputError


@pytest.fixture(scope="module")
def a():
    return analyse(isolated_baseline_propeller(), np.arange(1.0, 351.0, 10.0), vgf=True)


def test_eigenvectors_round_trip(a, tmp_path):
    path = tmp_path / "a.json"
    a.save(path, include_eigenvectors=True)
    npz = tmp_path / "a.eigenvectors.npz"
    assert eigenvectors_path(path) == npz and npz.is_file()
    doc = json.loads(path.read_text())
    assert doc["eigenvectors_file"] == npz.name and "eigenvectors" not in doc["sweep"]
    back = load(path)
    np.testing.assert_array_equal(back.sweep.eigenvectors, a.sweep.eigenvectors)
    assert back.events == a.events


def test_the_json_is_loadable_without_the_npz(a, tmp_path):
    path = tmp_path / "a.json"
    a.save(path, include_eigenvectors=True)
    eigenvectors_path(path).unlink()
    back = load(path)
    assert back.sweep.eigenvectors is None and back.events == a.events


def test_a_foreign_or_broken_npz_is_refused(a, tmp_path):
    other = analyse(isolated_baseline_propeller(), np.arange(1.0, 351.0, 20.0), vgf=True)
    path = tmp_path / "a.json"
    a.save(path, include_eigenvectors=True)
    other.save(tmp_path / "b.json", include_eigenvectors=True)
    eigenvectors_path(path).write_bytes((tmp_path / "b.eigenvectors.npz").read_bytes())
    with pytest.raises(InputError, match="does not belong to this analysis file"):
        load(path)
    eigenvectors_path(path).write_bytes(b"PK\x03\x04 not a zip")
    with pytest.raises(InputError, match="cannot read the eigenvector file"):
        load(path)


def test_the_npz_name_must_be_beside_the_json(a, tmp_path):
    doc = json.loads(json.dumps(a.to_dict()))
    doc["eigenvectors_file"] = "../elsewhere.npz"
    path = tmp_path / "a.json"
    path.write_text(json.dumps(doc))
    with pytest.raises(InputError, match="eigenvectors_file = '../elsewhere.npz' is invalid"):
        load(path)


def test_without_eigenvectors_nothing_to_save(a, tmp_path):
    from dataclasses import replace

    lean = replace(a, sweep=replace(a.sweep, eigenvectors=None))
    with pytest.raises(InputError, match="no eigenvectors"):
        lean.save(tmp_path / "a.json", include_eigenvectors=True)
    assert not list(tmp_path.iterdir())
