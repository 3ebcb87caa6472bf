"""Issue 33, item 9: a wrong type given to the Python API is the one-line InputError of the
file readers, naming the argument and what it must be — not a TypeError or AttributeError
from deep inside; a Case with a malformed mass or value is refused when it is made."""
from __future__ import annotations

import pytest

from propwhirl.validate import InputError

EXAMPLE = "examples/wingtip_campaign.toml"


def _calls():
    from propwhirl.app.report import report_html, write_report
    from propwhirl.io.campaign_files import load_campaign, loads
    from propwhirl.io.modal_files import load_modal_model, load_modes
    from propwhirl.studies.campaign import Campaign, Case, from_spec, run_campaign
    from propwhirl.studies.campaign_result import CampaignResult

    return [
        ("load_modal_model(None)", lambda: load_modal_model(None), "path = None"),
        ("load_modal_model(123)", lambda: load_modal_model(123), "path = 123"),
        ("load_modal_model(b'..')", lambda: load_modal_model(b"m.toml"), "path = b'm.toml'"),
        ("load_modal_model('')", lambda: load_modal_model(""), "got an empty string"),
        ("load_modes(None, ..)", lambda: load_modes(None, 3, 3), "path = None"),
        ("load_campaign(None)", lambda: load_campaign(None), "path = None"),
        ("loads(123)", lambda: loads(123), "text = 123"),
        ("loads(b'..')", lambda: loads(b"format = 1"), "text = b'format = 1'"),
        ("from_spec(None)", lambda: from_spec(None), "spec = None"),
        ("from_spec({'cases': []})", lambda: from_spec({"cases": []}), "spec = {'cases': []}"),
        ("run_campaign(None)", lambda: run_campaign(None), "c = None"),
        ("CampaignResult.load(None)", lambda: CampaignResult.load(None), "path = None"),
        ("CampaignResult.load(7)", lambda: CampaignResult.load(7), "path = 7"),
        ("report_html(None)", lambda: report_html(None), "result = None"),
        ("write_report(None, ..)", lambda: write_report(None, "out"), "result = None"),
        ("Case(added_masses=[(1.0,)])", lambda: Case("a", added_masses=[(1.0,)]),
         "added_masses[0] = (1.0,)"),
        ("Case(added_masses=[('1', 2)])", lambda: Case("a", added_masses=[("1", 2.0)]),
         "added_masses[0]"),
        ("Case(values={'x': 1})", lambda: Case("a", values={"x": 1}), "values = {'x': 1}"),
        ("Case(values=[('x',)])", lambda: Case("a", values=[("x",)]), "values[0]"),
        ("Case(values=[(1, 2)])", lambda: Case("a", values=[(1, 2.0)]), "values[0]"),
        ("Case(propellers=1)", lambda: Case("a", propellers=1), "propellers = 1"),
        ("Case(reverse_rotation='yes')", lambda: Case("a", reverse_rotation="yes"),
         "reverse_rotation = 'yes'"),
        ("Campaign(cases=None)", lambda: Campaign("c", None, None, ()), "cases = None"),
    ]


@pytest.mark.parametrize("i", range(len(_calls())), ids=[c[0] for c in _calls()])
def test_a_wrong_type_is_one_line_naming_the_argument(i):
    _, call, words = _calls()[i]
    with pytest.raises(InputError) as e:
        call()
    msg = str(e.value)
    assert "\n" not in msg and words in msg and "invalid" in msg, msg


def test_every_result_kind_loads_and_saves_only_a_path(tmp_path):
    """Result.load / save (and the kinds that override them) take a path, nothing else."""
    from test_result_protocol import _all_subclasses

    import propwhirl.analysis  # noqa: F401
    import propwhirl.studies.campaign  # noqa: F401
    import propwhirl.studies.sweeps  # noqa: F401
    from propwhirl.results import Result

    for cls in sorted(_all_subclasses(Result), key=lambda c: c.__qualname__):
        for bad in (None, 3, b"a.json", ["a.json"]):
            with pytest.raises(InputError, match=r"^path = .* is invalid: must be the path of"):
                cls.load(bad)


def test_a_list_is_taken_for_a_tuple_and_the_case_stays_hashable():
    from propwhirl.studies.campaign import Case

    c = Case("a", propellers=[1], added_masses=[[20, -0.5]], values=[["wing.EI*", 0.9]])
    assert c.propellers == (1,) and c.added_masses == ((20.0, -0.5),)
    assert c.values == (("wing.EI*", 0.9),) and hash(c) == hash(Case(
        "a", propellers=(1,), added_masses=((20.0, -0.5),), values=(("wing.EI*", 0.9),)))
