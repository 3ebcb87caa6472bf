"""Fuzz: partial-results files (--resume; issue 20, items 1–3).  A valid file of a study's
rows, then one entry replaced by a value of any type and depth, a key deleted or added, a
fingerprint entry changed, a pickle planted, the text cut or a byte changed: every file gives
checked rows or a one-line InputError naming the file — never a traceback, a forged row taken
or a line of the file run (a planted pickle would create a file: it never exists)."""
from __future__ import annotations

import base64
import copy
import json
import math
import pickle
from pathlib import Path

import pytest
from hypothesis import example, given
from hypothesis import strategies as st

from fuzz.conftest import FUZZ, held_to_the_rule
from propwhirl.studies import execution as X
from propwhirl.studies.execution import Checkpoint, TaskError
from propwhirl.studies.sweeps import STUDY_ROW

KEYS = [f"propeller.f_psi={x!r}" for x in (4.0, 6.0, 8.0, 10.0)]
ROWS = {
    0: {"critical_speed": 412.5, "critical_frequency": 5.25, "critical_mode": "backward",
        "content": "yaw", "kind": "flutter", "event": "onset", "whirl": "backward",
        "propeller": 1, "propeller_share": 0.93, "static_divergence_speed": float("nan")},
    1: {"critical_speed": float("nan"), "critical_frequency": float("nan"), "critical_mode": "",
        "content": "", "kind": "none", "event": "", "whirl": "", "propeller": 0,
        "propeller_share": float("nan"), "static_divergence_speed": float("nan")},
    2: TaskError("InputError", "propeller solidity 1.2 is invalid: must be < 1"),
}


def checkpoint(path: Path, resume: bool = False) -> Checkpoint:
    return Checkpoint(path, resume=resume).with_entries(
        STUDY_ROW, study="critical map", model="sha256:" + "ab" * 32, method="auto", xtol=0.01,
        axes=[{"path": "propeller.f_psi", "values": [4.0, 6.0, 8.0, 10.0]}])


def valid_document(tmp: Path) -> dict:
    path = tmp / "valid.partial"
    checkpoint(path).write(KEYS, ROWS)
    return json.loads(path.read_text())


class Touch:
    def __init__(self, marker: Path):
        self.marker = marker

    def __reduce__(self):
        return (Path.touch, (self.marker,))


JSON = st.recursive(
    st.one_of(st.none(), st.booleans(), st.integers(-2**70, 2**70), st.text(max_size=6),
              st.floats(allow_nan=True, allow_infinity=True),
              st.sampled_from(["flutter", "none", "error", "", "sha256:00", "pickle", 0.0, -1.0])),
    lambda inner: st.one_of(st.lists(inner, max_size=3),
                            st.dictionaries(st.sampled_from(["index", "key", "value", "error",
                                                             "error_type", "pickle", "kind", "x"]),
                                            inner, max_size=3)),
    max_leaves=8)


def _paths(doc, at=()):
    """Every (path, value) of the document: the places a mutation may go."""
    yield at, doc
    if isinstance(doc, dict):
        for k, x in doc.items():
            yield from _paths(x, at + (k,))
    elif isinstance(doc, list):
        for i, x in enumerate(doc):
            yield from _paths(x, at + (i,))


def _nested(depth: int) -> object:
    x: object = 1.0
    for _ in range(depth):
        x = [x]
    return x


def _check(rows: dict) -> None:
    """Rows read back: each a TaskError or a row the schema holds (numbers finite or NaN)."""
    for i, r in rows.items():
        assert 0 <= i < len(KEYS)
        if isinstance(r, TaskError):
            assert "\n" not in r.message
            continue
        assert STUDY_ROW.decode(STUDY_ROW.encode(r), "row", KEYS[i]) is not None
        for k in ("critical_speed", "critical_frequency", "propeller_share",
                  "static_divergence_speed"):
            assert isinstance(r[k], float) and (math.isnan(r[k]) or math.isfinite(r[k]))


MUTATIONS = ["replace", "delete", "add", "fingerprint", "pickle", "nest", "cut", "byte"]


@FUZZ
@given(kind=st.sampled_from(MUTATIONS), data=st.data())
@example(kind="nest", data=None)
def test_partial_files(tmp_path, kind, data):
    doc = valid_document(tmp_path)
    path, marker = tmp_path / "r.json.partial", tmp_path / "pwned"
    marker.unlink(missing_ok=True)
    draw = (lambda s, label: data.draw(s, label=label)) if data is not None else \
        (lambda s, label: 100_000)
    places = list(_paths(doc))
    text = None
    if kind in ("replace", "delete", "add"):
        at, _ = places[draw(st.integers(1, len(places) - 1), "place")] if len(places) > 1 else places[0]
        parent = doc
        for k in at[:-1]:
            parent = parent[k]
        if kind == "replace":
            parent[at[-1]] = draw(JSON, "value")
        elif kind == "delete":
            del parent[at[-1]]
        elif isinstance(parent[at[-1]], dict):
            parent[at[-1]][draw(st.text(max_size=5), "new key")] = draw(JSON, "value")
        else:
            parent[at[-1]] = [parent[at[-1]], draw(JSON, "value")]
    elif kind == "fingerprint":
        name = draw(st.sampled_from(sorted(doc["fingerprint"]) + ["extra"]), "entry")
        doc["fingerprint"][name] = draw(JSON, "value")
    elif kind == "pickle":
        payload = base64.b64encode(pickle.dumps(Touch(marker))).decode("ascii")
        j = draw(st.integers(0, len(doc["points"]) - 1), "point")
        if draw(st.booleans(), "old layout"):
            doc = {"format": X.OLD_PARTIAL_FORMAT, "version": 1, "fingerprint": "",
                   "total": len(KEYS), "done": 1,
                   "points": [{"index": j, "key": KEYS[j], "pickle": payload}]}
        else:
            doc["points"][j] = {"index": j, "key": KEYS[j], "pickle": payload}
    elif kind == "nest":
        depth = draw(st.sampled_from([20, 1000, 100_000]), "depth")
        text = json.dumps(doc).replace('"value": {', '"value": ' + "[" * depth + "{", 1)
        text = text.replace("}}", "}" + "]" * depth + "}", 1)
    else:
        text = json.dumps(doc)
        cut = draw(st.integers(0, len(text) - 1), "position")
        if kind == "cut":
            text = text[:cut]
        else:
            text = text[:cut] + draw(st.sampled_from(list('{}[]",:0-eE\\\x00é')), "char") + text[cut + 1:]
    path.write_text(json.dumps(copy.deepcopy(doc)) if text is None else text, encoding="utf-8")
    with held_to_the_rule(f"partial file: {kind}", source=str(path)):
        _check(checkpoint(path, resume=True).load(KEYS))
    assert not marker.exists(), "a pickle of the partial file was run"


def test_the_unmutated_file_reads_back(tmp_path):
    valid_document(tmp_path)
    rows = checkpoint(tmp_path / "valid.partial", resume=True).load(KEYS)
    assert rows[2] == ROWS[2]

    def same(a, b):
        return a == b or (isinstance(a, float) and math.isnan(a) and math.isnan(b))

    for i in (0, 1):
        assert rows[i].keys() == ROWS[i].keys()
        assert all(same(rows[i][k], ROWS[i][k]) for k in ROWS[i]), (rows[i], ROWS[i])


@pytest.mark.parametrize("entry, value", [("model", "sha256:" + "cd" * 32), ("xtol", 0.1),
                                          ("method", "dense"), ("total", 5), ("propwhirl", "0.0")])
def test_a_forged_fingerprint_is_refused_naming_the_entry(tmp_path, entry, value):
    doc = valid_document(tmp_path)
    doc["fingerprint"][entry] = value
    path = tmp_path / "forged.partial"
    path.write_text(json.dumps(doc))
    with pytest.raises(X.v.InputError, match=rf"was written for another study: {entry} \("):
        checkpoint(path, resume=True).load(KEYS)
