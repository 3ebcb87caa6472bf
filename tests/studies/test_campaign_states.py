"""Campaign cases of feathered, stopped and reversed propellers (issue 24 item 1, with the
installation states of issue 25 item 3): the case kinds in Python and in the campaign file,
the four-propeller example, and one small run."""
from __future__ import annotations

import dataclasses
import math
import tomllib
from pathlib import Path

import numpy as np
import pytest
import tomli_w

from propwhirl.io import load_model
from propwhirl.io.campaign_files import load_campaign, loads
from propwhirl.model.propellers.propeller import MeasuredDerivatives
from propwhirl.studies import campaign as C
from propwhirl.studies.campaign import from_spec
from propwhirl.validate import InputError

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "examples" / "four_propeller_campaign.toml"


@pytest.fixture(scope="module")
def four():
    """The four-propeller wing of the example on a 6-element mesh (its stations keep the
    propellers on nodes)."""
    m = load_model(ROOT / "examples" / "four_propeller.toml")
    return m.with_(wing=dataclasses.replace(m.wing, n_elements=6))


def test_example_reads_with_its_cases():
    c = from_spec(load_campaign(EXAMPLE))
    assert [x.name for x in c.cases] == [
        "nominal", *(f"mount stiffness at 50 % (propeller {i})" for i in range(1, 5)),
        "failed mount dampers", "wingtip propeller feathered", "wingtip propeller reversed"]
    assert [p.altitude_m for p in c.points] == [0.0, 2438.4, 5000.0]
    assert c.factor == 1.15 and c.regulation == "cs25"
    feathered = c.cases[6].apply(c.model)
    assert [i.state for i in feathered.propellers] == ["operating"] * 3 + ["feathered"]
    rev = c.cases[7].apply(c.model)
    assert [i.sense for i in rev.propellers] == [1, 1, 1, -1]
    # one shared propeller table: the case reverses the installation, not the table
    assert len({id(i.propeller) for i in rev.propellers}) == 1
    assert rev.propellers[3].propeller.rotation == 1


def test_state_cases_in_python(four):
    stopped = C.Case("folded", state="stopped").apply(four)
    assert {i.state for i in stopped.propellers} == {"stopped"}
    one = C.Case("f2", propellers=(2,), state="feathered").apply(four)
    assert [i.state for i in one.propellers] == ["operating", "feathered", "operating", "operating"]
    assert C.Case("f2", propellers=(2,), state="feathered").describe() == "feathered on propeller 2"
    both = C.Case("f", propellers=(4,), state="feathered").combine(
        C.Case("r", propellers=(4,), reverse_rotation=True))
    m = both.apply(four)
    assert (m.propellers[3].state, m.propellers[3].sense) == ("feathered", -1)
    twice = C.Case("r", reverse_rotation=True).combine(C.Case("r2", reverse_rotation=True))
    assert [i.sense for i in twice.apply(four).propellers] == [1, 1, 1, 1]
    back = C.Case("on", state="operating").apply(stopped)
    assert back.propellers == four.propellers


@pytest.mark.parametrize("kw,match", [
    (dict(state="folded"), r"^case 'x': state = 'folded' is invalid: must be one of operating, "
                           r"feathered, stopped$"),
    (dict(state="windmilling"), r"state = 'windmilling' is invalid"),
    (dict(operation="feathered"), r"operation = 'feathered' is invalid: .*state"),
])
def test_bad_case_kinds(kw, match):
    with pytest.raises(InputError, match=match):
        C.Case("x", **kw)


def test_feathered_case_without_blades_names_the_case(four):
    inst = four.propellers[0]
    measured = dataclasses.replace(inst.propeller, blade_chord=None,
                                   derivatives=MeasuredDerivatives({"CY_psi": 0.2}))
    m = four.with_(propellers=(dataclasses.replace(inst, propeller=measured),)
                   + four.propellers[1:])
    with pytest.raises(InputError, match=r"^case 'fe': state = 'feathered' is invalid.*blade_chord"):
        C.Case("fe", propellers=(1,), state="feathered").apply(m)


@pytest.mark.parametrize("value,reason", [
    ("folded", "one of operating, feathered, stopped"), (True, "a string"), ("", "one of")])
def test_campaign_file_state_key(value, reason):
    doc = tomllib.loads(EXAMPLE.read_text())
    doc["cases"][3]["state"] = value
    with pytest.raises(InputError, match=rf"^c\.toml: \[cases\[3\]\] state = .*{reason}"):
        loads(tomli_w.dumps(doc), "c.toml", EXAMPLE.parent)


def test_small_run_of_the_new_kinds():
    """The wingtip model (6 elements): nominal, the rotor stopped, feathered and reversed, at
    one altitude: every number finite; stopping or feathering changes V_crit (the blades'
    loads gone, or fins ahead of the pivots), each case's model is what it says."""
    m = load_model(ROOT / "examples" / "wingtip.toml")
    m = m.with_(wing=dataclasses.replace(m.wing, n_elements=6))
    cases = (C.Case("nominal"), C.Case("stopped", state="stopped"),
             C.Case("feathered", propellers=(1,), state="feathered"),
             C.Case("reversed", propellers=(1,), reverse_rotation=True))
    camp = C.Campaign("states", m, cases, C.envelope(90.0, [2438.4], airspeed="TAS"))
    r = C.run_campaign(camp)
    assert [row.case for row in r.rows] == [c.name for c in cases]
    for row in r.rows:
        assert math.isfinite(row.critical_speed) and math.isfinite(row.margin_m_per_s)
    v = {row.case: row.critical_speed for row in r.rows}
    assert v["stopped"] != pytest.approx(v["nominal"], abs=0.1)
    assert v["feathered"] != pytest.approx(v["nominal"], abs=0.1)
    assert [(i.state, i.sense) for c in cases for i in c.apply(m).propellers] == [
        ("operating", 1), ("stopped", 1), ("feathered", 1), ("operating", -1)]
