"""The failure-case keys of a campaign file (issue 24: CS/14 CFR 25.629(b)(2)): [envelope]
V_C_m_per_s and M_C, [[cases]] failure; the keys read, and every bad one is one line naming the
file, the key, the value and what is valid."""
from __future__ import annotations

import math
import tomllib
from pathlib import Path

import pytest
import tomli_w
from hypothesis import given, settings
from hypothesis import strategies as st

from propwhirl.io.campaign_files import loads
from propwhirl.studies.campaign import from_spec
from propwhirl.validate import InputError

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "examples" / "wingtip_campaign.toml"


def _doc(**envelope) -> dict:
    doc = tomllib.loads(EXAMPLE.read_text())
    doc["cases"] = doc["cases"][:3]        # nominal, the 50 % mount, the failed damper
    doc["envelope"].update(envelope)
    return doc


def _load(doc: dict):
    return from_spec(loads(tomli_w.dumps(doc), "c.toml", EXAMPLE.parent))


def test_the_failure_keys_read():
    doc = _doc(V_C_m_per_s=80.0, M_C=0.3)
    doc["cases"][0]["failure"] = True
    doc["cases"][2]["failure"] = False
    c = _load(doc)
    assert [x.is_failure for x in c.cases] == [True, True, False]
    assert [p.line_part for p in c.points] == ["1.15 V_C", "V_C-M_C line", "M_C + 0.05"]
    assert all(p.V_line is not None for p in c.points)
    c = _load(_doc(V_C_m_per_s=[80.0, 81.0, 82.0]))
    assert [p.line_part for p in c.points] == ["1.15 V_C"] * 3
    assert all(p.V_line is None for p in _load(_doc()).points)       # no V_C: no line


BAD = [
    (dict(V_C_m_per_s=0.5), ["[envelope] V_C_m_per_s", "0.5", "[1, 1000]"]),
    (dict(V_C_m_per_s="fast"), ["[envelope] V_C_m_per_s", "'fast'", "a number"]),
    (dict(V_C_m_per_s=[80.0, 81.0]), ["[envelope] V_C_m_per_s", "[80.0, 81.0]",
                                      "one per altitude (3)"]),
    (dict(V_C_m_per_s=80.0, M_C=1.2), ["[envelope] M_C", "1.2", "[0.01, 0.95]"]),
    (dict(M_C=0.3), ["missing key 'V_C_m_per_s'", "[envelope]", "M_C needs V_C"]),
    (dict(V_C_m_per_s=200.0, M_C=0.2), ["[envelope]", "M_C = 0.2 is invalid", "below 1.15 V_C",
                                        "-5000 m"]),
]


@pytest.mark.parametrize("envelope, words", BAD, ids=[repr(e) for e, _ in BAD])
def test_every_bad_failure_key_is_one_line(envelope, words):
    with pytest.raises(InputError) as e:
        _load(_doc(**envelope))
    msg = str(e.value)
    assert "\n" not in msg and msg.startswith("c.toml: "), msg
    assert all(w in msg for w in words), msg


@pytest.mark.parametrize("name, factor", [("far23", None), ("explicit", 1.25)])
def test_V_C_is_refused_where_25_629_b_2_does_not_apply(name, factor):
    """Part 23 (and explicit factors) hold every case, failure or not, to the factor times V_D:
    a V_C there is an error saying so, not silently ignored."""
    doc = _doc(V_C_m_per_s=80.0)
    doc["regulation"] = {"name": name} | ({} if factor is None else {"factor": factor})
    with pytest.raises(InputError) as e:
        _load(doc)
    msg = str(e.value)
    assert "\n" not in msg and msg.startswith("c.toml: [envelope] V_C_m_per_s = 80.0 is invalid")
    assert f"name = '{name}'" in msg and "25.629(b)(2)" in msg and " V_D" in msg


def test_failure_must_be_a_boolean():
    doc = _doc()
    doc["cases"][0]["failure"] = "yes"
    with pytest.raises(InputError, match=r"^c\.toml: \[cases\[0\]\] failure = 'yes' is invalid: "
                                         "must be true or false"):
        _load(doc)


@settings(max_examples=60, deadline=None)
@given(V_C=st.one_of(st.floats(allow_nan=True, allow_infinity=True),
                     st.lists(st.floats(0.0, 2000.0), min_size=1, max_size=3)),
       M_C=st.one_of(st.none(), st.floats(allow_nan=True, allow_infinity=True)),
       alts=st.lists(st.floats(-6000.0, 33000.0), min_size=1, max_size=3))
def test_any_failure_envelope_is_finite_or_one_line(V_C, M_C, alts):
    """Whatever V_C, M_C and altitudes: finite envelope points or a one-line InputError."""
    from propwhirl.studies.campaign import envelope

    try:
        pts = envelope(150.0, alts, V_C=V_C, M_C=M_C)
    except InputError as exc:
        assert "\n" not in str(exc)
        return
    assert all(math.isfinite(p.V_line) and p.V_line > 0 and p.line_part for p in pts)


@pytest.mark.parametrize("path, value", [("wing.mass_per_length*", 1e308), ("wing.EI*", 1e308),
                                         ("propellers[0].propeller.f_theta*", 1e308)])
def test_a_scale_beyond_the_floats_is_the_error_alone(path, value):
    """Issue 33, item 10: a campaign value "wing.mass_per_length*" = 1e308 printed numpy's
    RuntimeWarning (overflow) before the one-line error; now the error alone, naming the file,
    the case, the path and what is wrong."""
    import warnings

    doc = _doc()
    doc["cases"].append({"name": "heavy", "values": {path: value}})
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(InputError) as e:
            _load(doc)
    msg = str(e.value)
    assert "\n" not in msg and msg.startswith("c.toml: [cases[3]] case 'heavy': ") and path in msg
    assert "must be finite" in msg or "outside the valid range" in msg, msg
