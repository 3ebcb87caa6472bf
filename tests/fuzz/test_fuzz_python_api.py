"""Fuzz: the Python constructors (one field of a valid object replaced by a value of any type
and size) and the analysis arguments (speed grids of any shape and value)."""
from __future__ import annotations

import dataclasses
import math

import numpy as np
from hypothesis import given
from hypothesis import strategies as st

from fuzz.conftest import FUZZ, held_to_the_rule
from propwhirl.analysis import analyse
from propwhirl.cases.ch09_baseline import baseline_propeller, isolated_baseline_propeller
from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing

ANY = st.one_of(
    st.none(), st.booleans(), st.text(max_size=8),
    st.floats(allow_nan=True, allow_infinity=True),
    st.sampled_from([0.0, -1.0, 1e-300, 1e300, -1e300, 1e12, 2**63]),
    st.integers(min_value=-10**6, max_value=10**6), st.complex_numbers(max_magnitude=1e3),
    st.lists(st.floats(allow_nan=False, allow_infinity=False, width=32), max_size=3),
    st.tuples(st.floats(-2, 2), st.floats(-2, 2)),
)


def _wing_model(n=4):
    m = wingtip_propeller_wing()
    return m.with_(wing=dataclasses.replace(m.wing, n_elements=n))


def _targets():
    m = _wing_model()
    p = m.propellers[0]
    return {"Wing": m.wing, "Propeller": baseline_propeller(), "Installation": p,
            "FlightCondition": m.flight, "PropellerWing": m,
            "IsolatedPropeller": isolated_baseline_propeller()}


TARGETS = _targets()


@FUZZ
@given(name=st.sampled_from(sorted(TARGETS)), data=st.data())
def test_constructors(name, data):
    obj = TARGETS[name]
    fields = [f.name for f in dataclasses.fields(obj) if f.init and not f.name.startswith("_")]
    field = data.draw(st.sampled_from(fields), label="field")
    old = getattr(obj, field)
    if isinstance(old, (int, float)) and not isinstance(old, bool) and data.draw(st.booleans()):
        value = type(old)(old * 10.0 ** data.draw(st.floats(-2.0, 2.0), label="log10 factor"))
    else:
        value = data.draw(ANY, label="value")
    with held_to_the_rule(f"python: {name}(...)"):
        new = dataclasses.replace(obj, **{field: value})
        if name in ("PropellerWing", "IsolatedPropeller"):
            A = new.state_matrix(np.array([10.0, 100.0]))
            assert np.isfinite(A).all()


SPEEDS = st.one_of(
    st.lists(st.floats(min_value=1.0, max_value=600.0), min_size=2, max_size=6, unique=True)
    .map(sorted),
    st.lists(st.floats(min_value=1.0, max_value=600.0), min_size=2, max_size=6, unique=True)
    .map(sorted),
    st.lists(st.floats(allow_nan=True, allow_infinity=True), max_size=6),
    st.lists(st.floats(min_value=-10.0, max_value=400.0), max_size=6),
    st.floats(allow_nan=True, allow_infinity=True), st.text(max_size=4), st.none(),
    st.lists(st.lists(st.floats(1.0, 300.0), min_size=2, max_size=2), min_size=1, max_size=3),
)


@FUZZ
@given(speeds=SPEEDS)
def test_analysis_arguments(speeds):
    model = isolated_baseline_propeller()
    with held_to_the_rule("python: analyse(model, speeds)"):
        if speeds is None:
            return                                       # None is the documented default
        a = analyse(model, speeds)
        assert all(math.isfinite(e.V) for e in a.events)


# ----------------------------------------------------------------------------- issue 33, item 9
def _entries():
    from propwhirl.app.report import report_html
    from propwhirl.io.campaign_files import load_campaign, loads
    from propwhirl.io.modal_files import load_modal_model, load_modes
    from propwhirl.studies.campaign import from_spec, run_campaign
    from propwhirl.studies.campaign_result import CampaignResult

    return {"load_modal_model(x)": load_modal_model, "load_modes(x, 3, 3)":
            lambda x: load_modes(x, 3, 3), "load_campaign(x)": load_campaign, "loads(x)": loads,
            "from_spec(x)": from_spec, "run_campaign(x)": run_campaign,
            "CampaignResult.load(x)": CampaignResult.load, "report_html(x)": report_html}


ENTRIES = _entries()
WRONG = st.one_of(ANY, st.binary(max_size=6), st.dictionaries(st.text(max_size=3), ANY, max_size=2),
                  st.sampled_from(["", "\0", ".", "/", "a\0b.toml", "nonexistent.toml"]))


@FUZZ
@given(name=st.sampled_from(sorted(ENTRIES)), value=WRONG)
def test_api_entry_points_given_any_value(name, value, tmp_path_factory):
    """A value of any type to the campaign and modal-model entry points: a one-line InputError
    (none of these values is a file, a spec, a campaign or a result)."""
    import os

    here = os.getcwd()
    os.chdir(tmp_path_factory.mktemp("api"))           # relative names find nothing
    try:
        with held_to_the_rule(f"python: {name}"):
            ENTRIES[name](value)
            raise AssertionError(f"{name} accepted {value!r}")
    finally:
        os.chdir(here)


CASE_FIELDS = ("propellers", "mount_stiffness", "mount_damping", "wing_damping", "operation",
               "rpm_factor", "reverse_rotation", "added_masses", "values", "state", "failure")
CASE_VALUES = st.one_of(
    ANY, st.lists(ANY, max_size=2), st.lists(st.tuples(ANY, ANY), max_size=2),
    st.lists(st.tuples(st.sampled_from(["wing.EI*", "wing.GJ", "x", ""]), ANY), max_size=2),
    st.dictionaries(st.sampled_from(["wing.EI*", "x"]), ANY, max_size=2))


@FUZZ
@given(field=st.sampled_from(CASE_FIELDS), value=CASE_VALUES)
def test_campaign_case_fields(field, value):
    """A Case with one field of any type and value: refused when it is made (one line), or
    made, described and applied to the wingtip model (or refused there, one line)."""
    from propwhirl.studies.campaign import Case

    with held_to_the_rule("python: Case(...)"):
        case = Case("fuzz", **{field: value})
        hash(case)
        assert isinstance(case.describe(), str)
        case.apply(_wing_model())
