"""Fuzz: campaign files (propwhirl.io.campaign_files, issue 24) mutated as a hostile user
would — values of any type and size, keys removed or unknown, truncated or corrupted text,
deep nesting: a campaign whose every case and envelope point is built (and every number
finite), or a one-line InputError naming the file.  No analysis is run (the reader and the
task builder check everything before the first)."""
from __future__ import annotations

import math
import tomllib

import tomli_w
from hypothesis import given
from hypothesis import strategies as st

from fuzz.conftest import FUZZ, ROOT, held_to_the_rule
from fuzz.test_fuzz_model_files import VALUES, mutate
from propwhirl.io.campaign_files import loads
from propwhirl.studies.campaign import from_spec, tasks

SOURCE = "fuzz-campaign.toml"
EXAMPLE = ROOT / "examples" / "wingtip_campaign.toml"
BASE = EXAMPLE.read_text()


def _check(text: str) -> None:
    c = from_spec(loads(text, SOURCE, EXAMPLE.parent))
    todo, keys = tasks(c)
    assert len(todo) == len(c.cases) * len(c.points) == len(set(keys))
    for t in todo:
        assert math.isfinite(t.V_D) and t.V_D > 0 and t.V_required >= t.V_D
        assert t.speeds[-1] > t.V_required


@FUZZ
@given(data=st.data())
def test_mutated_values(data):
    doc = tomllib.loads(BASE)
    mutate(doc, data, ("scaled", "scaled", "value", "delete", "unknown"))
    with held_to_the_rule("campaign: mutated values/keys", SOURCE):
        _check(tomli_w.dumps(doc))


CASE_KEYS = st.fixed_dictionaries({}, optional={
    "mount_stiffness": VALUES, "mount_damping": VALUES, "wing_damping": VALUES,
    "rpm_factor": VALUES, "operation": st.sampled_from(["windmilling", "feathered", ""]),
    "state": st.sampled_from(["feathered", "stopped", "operating", "windmilling", "", 1]),
    "reverse_rotation": VALUES, "propellers": st.lists(st.integers(-2, 3), max_size=3),
    "each_propeller": st.booleans(), "group": st.sampled_from(["a", "b"]),
    "added_masses": st.lists(st.fixed_dictionaries({"mass_kg": VALUES, "x_m": VALUES}),
                             max_size=2),
    "values": st.dictionaries(st.sampled_from(["wing.EI*", "wing.GJ", "flight.density",
                                               "propellers[0].propeller.f_theta", "nope",
                                               "wing.mass_per_length*"]),
                              VALUES | st.sampled_from([1e308, -1e308, 1e300]), max_size=2)})


@FUZZ
@given(cases=st.lists(CASE_KEYS, min_size=1, max_size=4),
       combine=st.sampled_from(["list", "product"]))
def test_generated_cases(cases, combine):
    doc = tomllib.loads(BASE)
    doc["combine"] = combine
    doc["cases"] = [{"name": f"case {i}", **c} for i, c in enumerate(cases)]
    try:
        text = tomli_w.dumps(doc)
    except (TypeError, ValueError):           # a value TOML cannot hold (e.g. nan in a key)
        return
    with held_to_the_rule("campaign: generated cases", SOURCE):
        _check(text)


@FUZZ
@given(cut=st.integers(min_value=0, max_value=3000), junk=st.binary(max_size=8))
def test_truncated_and_corrupted_text(cut, junk):
    raw = BASE.encode()
    cut = min(cut, len(raw))
    text = (raw[:cut] + junk + raw[cut:]).decode("utf-8", errors="replace")
    with held_to_the_rule("campaign: truncated/corrupted text", SOURCE):
        _check(text)


@FUZZ
@given(depth=st.integers(min_value=1, max_value=20000))
def test_deep_nesting(depth):
    with held_to_the_rule("campaign: deep nesting", SOURCE):
        loads('format = "propwhirl-campaign"\nx = ' + "[" * depth + "]" * depth + "\n", SOURCE)
