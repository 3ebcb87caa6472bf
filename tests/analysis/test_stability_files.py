"""Analysis files (ModelAnalysis.save / load): format and version, and corrupt files — empty,
truncated, non-JSON, wrong types, missing keys, NaN, inconsistent shapes — each an InputError
of one line naming the file and what is wrong (issue 9, item 6)."""
from __future__ import annotations

import copy
import json
import math
import re
from pathlib import Path

import numpy as np
import pytest

from propwhirl.analysis.stability import FORMAT, FORMAT_VERSION, ModelAnalysis, analyse, load
from propwhirl.cases.ch09_baseline import isolated_baseline_propeller
from propwhirl.validate import InputError


@pytest.fixture(scope="module")
def analysis() -> ModelAnalysis:
    return analyse(isolated_baseline_propeller(), np.arange(1.0, 351.0, 10.0), vgf=True)


@pytest.fixture(scope="module")
def doc(analysis) -> dict:
    return json.loads(json.dumps(analysis.to_dict()))


def refused(path: Path, match: str) -> str:
    """load(path) raises one line starting with the path and matching `match`."""
    with pytest.raises(InputError) as err:
        load(path)
    text = str(err.value)
    assert "\n" not in text
    assert str(path) in text, text
    assert re.search(match, text.replace(str(path), "FILE")), text
    return text


def write_doc(tmp_path: Path, d) -> Path:
    path = tmp_path / "a.json"
    path.write_text(json.dumps(d))
    return path


def test_the_file_names_its_format_and_version(analysis, tmp_path):
    path = tmp_path / "a.json"
    analysis.save(path)
    d = json.loads(path.read_text())
    assert d["format"] == FORMAT == "propwhirl.analysis/3" and FORMAT_VERSION == 3
    assert "format_version" not in d     # the version is in the tag (issue 21.4)
    back = load(path)
    assert back.events == analysis.events and back.content == analysis.content
    assert back.dof_map == analysis.dof_map
    assert np.array_equal(back.sweep.eigenvalues, analysis.sweep.eigenvalues)


def test_a_file_without_format_keys_is_read_as_version_1(doc, tmp_path):
    """Files written before the format keys existed have the same layout otherwise."""
    old = {k: x for k, x in doc.items() if k not in ("format", "format_version")}
    assert load(write_doc(tmp_path, old)).events == ModelAnalysis.from_dict(doc).events


@pytest.mark.parametrize("text, match", [
    ("", "empty"),
    ("   \n", "empty"),
    ("hello", r"not valid JSON: Expecting value \(line 1, column 1\)"),
    ("{'model_name': 1}", "not valid JSON"),
    ("[1, 2, 3]", "must be an object, got a list"),
    ('"analysis"', "must be an object, got a string"),
    ("3", "must be an object, got a number"),
    ("null", "must be an object, got null"),
    ("[" * 100_000, "nested too deeply|not valid JSON"),
    ('{"V": NaN}', "NaN"),
    ('{"V": Infinity}', "Infinity"),
    ('{"V": ' + "9" * 5000 + "}", "not an analysis file"),
])
def test_not_an_analysis_file(tmp_path, text, match):
    path = tmp_path / "a.json"
    path.write_text(text)
    refused(path, match)


def test_binary_and_non_utf8_files(tmp_path):
    path = tmp_path / "a.json"
    path.write_bytes(b"\x89PNG\r\n\x1a\n\x00\x00")
    refused(path, "not UTF-8")
    path.write_bytes('{"model_name": "é"}'.encode("latin-1"))
    refused(path, "not UTF-8")


def test_missing_file_and_folder(tmp_path):
    refused(tmp_path / "none.json", "not found")
    refused(tmp_path, "cannot read analysis file")


def test_truncated_file(analysis, tmp_path):
    """Issue 9.6: a truncated file raised JSONDecodeError."""
    path = tmp_path / "a.json"
    analysis.save(path)
    text = path.read_text()
    for cut in (1, len(text) // 3, len(text) - 1):
        path.write_text(text[:cut])
        refused(path, r"not valid JSON: .* \(the file ends early: truncated\?\)")


@pytest.mark.parametrize("key", ["model_name", "events", "critical", "dof_map", "content",
                                 "sweep"])
def test_missing_top_level_key(doc, tmp_path, key):
    d = {k: x for k, x in doc.items() if k != key}
    refused(write_doc(tmp_path, d), f"missing key '{key}'")


@pytest.mark.parametrize("key", ["V", "eigenvalues", "dlam_dV", "physical", "state_labels",
                                 "displacement", "mode_labels", "partner", "grid", "floor",
                                 "unresolved", "stats"])
def test_missing_sweep_key(doc, tmp_path, key):
    d = copy.deepcopy(doc)
    del d["sweep"][key]
    refused(write_doc(tmp_path, d), f"sweep: missing key '{key}'")


def test_unknown_key(doc, tmp_path):
    d = dict(doc, extra=1)
    refused(write_doc(tmp_path, d), "unknown key 'extra'")


def mutate(doc, where: str, value):
    """A copy of doc with doc[k1][k2]... = value (where "sweep.V")."""
    d = copy.deepcopy(doc)
    *head, last = where.split(".")
    node = d
    for k in head:
        node = node[int(k)] if isinstance(node, list) else node[k]
    if isinstance(node, list):
        node[int(last)] = value
    else:
        node[last] = value
    return d


def test_three_speeds_against_35_eigenvalue_rows(doc, tmp_path):
    """Issue 9.6: 3 speeds against 35 eigenvalue rows were accepted."""
    T = len(doc["sweep"]["V"])
    assert T == 35
    d = mutate(doc, "sweep.V", doc["sweep"]["V"][:3])
    refused(write_doc(tmp_path, d), rf"sweep\.eigenvalues\.re: shape \({T}, 4\): axis 0 must "
            "have 3 entries")


def test_nan_and_infinite_speeds(doc, tmp_path):
    """Issue 9.6: NaN speeds were accepted (Python's json writes and reads NaN)."""
    V = list(doc["sweep"]["V"])
    V[1] = math.nan
    path = tmp_path / "a.json"
    path.write_text(json.dumps(mutate(doc, "sweep.V", V)))       # allow_nan: writes NaN
    refused(path, "holds NaN")
    path.write_text(json.dumps(doc).replace(f"{doc['sweep']['V'][1]!r}", "1e400", 1))
    refused(path, r"sweep\.V: holds non-finite numbers")


@pytest.mark.parametrize("where, value, match", [
    ("model_name", 3, "model_name: must be a string"),
    ("events", {}, "events: must be a list"),
    ("sweep", [], "sweep: must be an object, got a list"),
    ("sweep.V", "1, 2", r"sweep\.V: must be a list, got a string"),
    ("sweep.V", [[1.0], [2.0, 3.0]], r"sweep\.V: must be a rectangular list"),
    ("sweep.V", [True, False], r"sweep\.V: must hold numbers only"),
    ("sweep.V", [], r"sweep\.V: no speeds"),
    ("sweep.physical", [[1, 0]], r"sweep\.physical: must hold booleans"),
    ("sweep.eigenvalues", [1, 2], r"sweep\.eigenvalues: must be an object"),
    ("sweep.eigenvalues.im", [[1.0, "x"]], r"sweep\.eigenvalues\.im: must hold numbers only"),
    ("sweep.mode_labels", ["a"], r"sweep\.mode_labels: has 1 entries, need 4"),
    ("sweep.partner", [0, 1, 2, 9], r"sweep\.partner: mode id 9 is outside \[-1, 3\]"),
    ("sweep.stats", {"eig": 1.5}, r"sweep\.stats: must be an object of integer counters"),
    ("sweep.unresolved", [[1.0]], r"sweep\.unresolved: shape \(1, 1\)"),
    ("events.0.mode", 1.5, r"events\[0\]\.mode: must be an integer"),
    ("events.0.mode", 99, r"events\[0\]\.mode: = 99 is outside \[0, 3\]"),
    ("events.0.kind", "wobble", r"events\[0\]\.kind: = 'wobble' is invalid"),
    ("events.0.label", "wing 7", r"events\[0\]\.label = 'wing 7' is not the name of mode"),
    ("events.0.V", None, r"events\[0\]\.V: must be a finite number, got None"),
    ("events.0.V", "fast", r"events\[0\]\.V: must be a finite number"),
    ("events.0.whirl", "sideways", r"events\[0\]\.whirl: = 'sideways' is invalid"),
    ("events.0.V", 1.0, r"critical: does not match"),
    ("content", [], r"content: must be an object"),
    ("content.forward", {"pitch": "half"}, r"content\.forward\.pitch: must be a finite number"),
    ("dof_map.q_kinds", ["theta"], r"dof_map: DofMap\.q_kinds has 1 entries"),
    ("dof_map.q_labels", ["a", "b"], r"dof_map: its 4 states do not match"),
    ("dof_map.propellers", [{"number": 0}], r"dof_map\.propellers\[0\]: missing keys"),
    ("dof_map.propellers.0.theta", 7, r"dof_map\.propellers\[0\]\.theta: = 7 is outside"),
    ("format", "propwhirl-model", r"format 'propwhirl-model' is a model file, not an analysis "
                                  r"file \(format 'propwhirl.analysis/3'\)"),
    ("format", "propwhirl.analysis/4", r"version 4 is not supported \(written by a newer"),
    ("format", "propwhirl.clearance/1", r"is a clearance file, not an analysis file"),
    ("format", 3, r"not an analysis file \(format 'propwhirl.analysis/3'\): format = 3 is "
                  r"invalid"),
])
def test_wrong_value(doc, tmp_path, where, value, match):
    refused(write_doc(tmp_path, mutate(doc, where, value)), match)


@pytest.mark.parametrize("version, match", [
    (3, r"format_version = 3 is not supported: this propwhirl reads 'propwhirl-analysis' "
        r"versions 1, 2"),
    ("1", r"format_version = '1' is not supported"),
    (True, r"format_version = True is not supported"),
    (None, r"missing key 'format_version'"),
])
def test_wrong_old_version(doc, tmp_path, version, match):
    """Files of the earlier format name keep their version key, checked as before."""
    old = dict(doc, format="propwhirl-analysis")
    if version is not None:
        old["format_version"] = version
    refused(write_doc(tmp_path, old), match)


def test_from_dict_errors_are_input_errors(doc):
    """The same checks without a file (ModelAnalysis.from_dict): no KeyError or TypeError."""
    for bad in (None, [], {}, {"sweep": {}}, mutate(doc, "sweep.V", doc["sweep"]["V"][:3])):
        with pytest.raises(InputError):
            ModelAnalysis.from_dict(bad)


def test_saved_json_never_holds_nan(analysis, tmp_path):
    """A non-finite number where the schema allows none is refused (naming the key) and
    nothing is written; a non-finite benignity is saved as null."""
    from dataclasses import replace

    lam = analysis.sweep.eigenvalues.copy()
    lam[2, 1] = complex(math.nan, 1.0)
    bad = replace(analysis, sweep=replace(analysis.sweep, eigenvalues=lam))
    path = tmp_path / "a.json"
    with pytest.raises(InputError, match=r"cannot save the analysis to '.*a\.json': "
                       r"sweep\.eigenvalues\.re\[2\]\[1\] is not a finite number"):
        bad.save(path)
    assert not path.exists()
    assert list(tmp_path.iterdir()) == []
    e = replace(analysis.events[0], benignity=math.inf)
    inf_ben = replace(analysis, events=(e,) + analysis.events[1:])
    inf_ben.save(path)
    text = path.read_text()
    assert "Infinity" not in text and "NaN" not in text
    assert load(path).events[0].benignity is None
