"""Groups of propellers in parameter paths (issue 25, item 4): slices, lists, named groups (the
model's ``groups``, a model file's [groups] table), linked paths (one value, several paths),
their errors, and the group sweep of the six high-lift mounts of examples/x57_like.toml."""
from __future__ import annotations

import dataclasses
import json
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from propwhirl import io
from propwhirl.app import cli
from propwhirl.studies import boundary
from propwhirl.studies import paths as P
from propwhirl.studies import sweeps
from propwhirl.validate import InputError

X57 = Path(__file__).parents[2] / "examples" / "x57_like.toml"
ISOTROPIC = "propellers[high_lift].propeller.f_theta,propellers[high_lift].propeller.f_psi"


@pytest.fixture(scope="module")
def x57():
    return io.load_model(X57)


def _mounts(model) -> list[tuple[float, float]]:
    return [(i.propeller.f_theta, i.propeller.f_psi) for i in model.propellers]


def _one_line(exc) -> str:
    msg = str(exc.value)
    assert "\n" not in msg and len(msg) < 600, msg
    return msg


# ----------------------------------------------------------------------------- selections
def test_the_model_file_defines_the_high_lift_group(x57):
    assert len(x57.propellers) == 7
    assert x57.groups == {"high_lift": (0, 1, 2, 3, 4, 5)}
    assert [i.y for i in x57.propellers[:6]] == [0.95, 1.55, 2.15, 2.75, 3.35, 3.95]


@pytest.mark.parametrize("path, chosen", [
    ("propellers[0:6].propeller.f_theta", range(6)),
    ("propellers[:6].propeller.f_theta", range(6)),
    ("propellers[4:].propeller.f_theta", range(4, 7)),
    ("propellers[0:6:2].propeller.f_theta", (0, 2, 4)),
    ("propellers[-2:].propeller.f_theta", (5, 6)),
    ("propellers[0,2,4].propeller.f_theta", (0, 2, 4)),
    ("propellers[6,0].propeller.f_theta", (6, 0)),
    ("propellers[high_lift].propeller.f_theta", range(6)),
    ("propellers[*].propeller.f_theta", range(7)),
])
def test_a_selection_sets_exactly_its_installations(x57, path, chosen):
    p = P.resolve(x57, path)
    assert p.path == path and p.unit == "Hz" and p.value(x57) == 12.0
    m = p.set(x57, 9.5)
    assert [f for f, _ in _mounts(m)] == [9.5 if j in chosen else 12.0 for j in range(7)]
    assert [f for _, f in _mounts(m)] == [f for _, f in _mounts(x57)]    # f_psi untouched
    assert _mounts(x57)[0] == (12.0, 12.0)                              # the model as it was


def test_setting_one_installation_of_a_shared_table_changes_that_one_only(x57):
    # the six high-lift installations share the file's one [propellers.high_lift] table
    shared = x57.propellers[0].propeller
    assert all(i.propeller is shared for i in x57.propellers[:6])
    m = P.set_value(x57, "propellers[2].propeller.f_theta", 7.0)
    assert [f for f, _ in _mounts(m)] == [12.0, 12.0, 7.0, 12.0, 12.0, 12.0, 12.0]
    assert all(m.propellers[j].propeller is shared for j in (0, 1, 3, 4, 5))
    assert shared.f_theta == 12.0


def test_the_value_of_a_selection_with_differing_values_is_none(x57):
    m = P.set_value(x57, "propellers[1].propeller.f_theta", 7.0)
    assert P.resolve(m, "propellers[0:3].propeller.f_theta").value(m) is None
    assert P.resolve(m, "propellers[2:6].propeller.f_theta").value(m) == 12.0


def test_groups_given_in_python(x57):
    m = dataclasses.replace(x57, groups={"inner": [0, 1], "tip": (6,)})
    assert m.groups == {"inner": (0, 1), "tip": (6,)}
    out = P.set_value(m, "propellers[tip].propeller.f_psi", 5.0)
    assert [f for _, f in _mounts(out)] == [12.0] * 6 + [5.0]
    assert P.groups_of(m) == m.groups and out.groups == m.groups


def test_disjoint_selections_vary_together_overlapping_ones_are_refused(x57):
    a, b = (P.resolve(x57, f"propellers[{s}].propeller.f_theta") for s in ("0:3", "3,4,5"))
    P.check_independent([a, b])
    m = P.set_values(x57, {a: 8.0, b: 10.0})
    assert [f for f, _ in _mounts(m)] == [8.0] * 3 + [10.0] * 3 + [12.0]
    for other in ("propellers[2].propeller.f_theta", "propellers[high_lift].propeller.f_theta",
                  "propellers[1].propeller.K_theta"):
        with pytest.raises(InputError, match="invalid together") as exc:
            P.check_independent([a, P.resolve(x57, other)])
        _one_line(exc)


# ----------------------------------------------------------------------------- linked paths
def test_linked_paths_set_one_value_on_every_path(x57):
    p = P.resolve(x57, ISOTROPIC)
    q = P.resolve(x57, tuple(ISOTROPIC.split(",")))
    assert p == q and p.path == ISOTROPIC and len(p.links) == 2
    assert p.unit == "Hz" and p.value(x57) == 12.0 and p.label == f"{ISOTROPIC} [Hz]"
    m = p.set(x57, 9.0)
    assert _mounts(m) == [(9.0, 9.0)] * 6 + [(12.0, 8.0)]
    assert p.value(m) == 9.0 and p.value(P.set_value(m, "propellers[0].propeller.f_psi", 8.0)) is None
    # variants, grids and the boundary's plane take linked parameters like any other
    v = P.variants(x57, {ISOTROPIC: [10.0, 11.0]})
    assert [_mounts(x)[3] for x in v] == [(10.0, 10.0), (11.0, 11.0)]
    variant, params = boundary.path_variant(
        x57, [ISOTROPIC, "propellers[6].propeller.f_theta,propellers[6].propeller.f_psi"])
    assert _mounts(variant(np.array([7.0, 6.0]))) == [(7.0, 7.0)] * 6 + [(6.0, 6.0)]


def test_a_linked_value_is_checked_against_every_path_before_anything_is_built(x57):
    p = P.resolve(x57, "propellers[0].y,propellers[0].propeller.pivot_pitch")     # both [m]
    with pytest.raises(InputError, match=r"propellers\[0\].propeller.pivot_pitch = 500 m is "
                                         r"outside the valid range \[-100, 100\]") as exc:
        p.check_values([1.0, 500.0])
    _one_line(exc)
    with pytest.raises(InputError, match=r"pivot_pitch = 500 m is outside"):
        p.set(x57, 500.0)
    with pytest.raises(InputError, match="must be one number"):
        P.resolve(x57, ISOTROPIC).set(x57, [1.0, 2.0])


@pytest.mark.parametrize("path, match", [
    ("propellers[0].propeller.f_theta,propellers[0].propeller.K_psi",
     r"invalid linked: one value for both, but one is \[Hz\] and the other \[N m/rad\]"),
    ("propellers[0].propeller.f_theta,wing.EI*", r"one is \[Hz\] and the other a factor"),
    ("propellers[0].propeller.f_theta,propellers[0].propeller.K_theta", "alternative"),
    ("propellers[0:3].propeller.f_theta,propellers[1].propeller.f_theta", "same value"),
    ("propellers[0].propeller.f_theta,propellers[0].propeller.f_theta", "appears twice"),
    ("propellers[0].propeller.f_theta,", "an empty path between commas"),
    (("propellers[0].propeller.f_theta", 3), "tuple of strings"),
    ((), "tuple of strings"),
])
def test_bad_links_are_one_line_errors(x57, path, match):
    with pytest.raises(InputError, match=match) as exc:
        P.resolve(x57, path)
    _one_line(exc)


# ----------------------------------------------------------------------------- errors
@pytest.mark.parametrize("path, match", [
    ("propellers[hl].propeller.f_theta", r"propellers\[hl\] names no group: the model's groups "
                                         "are high_lift"),
    ("propellers[3:3].propeller.f_theta", r"selects no entry .*propellers has 7 entries, from 0: "
                                          r"propellers\[0\] is propeller 1 of the reports: give an "
                                          r"index 0 to 6, \*, a slice such as 0:7, a list such as "
                                          r"0,1, or a group \(high_lift\)"),
    ("propellers[0:6:0].propeller.f_theta", "slice step of 0"),
    ("propellers[0,7].propeller.f_theta", "has 7, out of range"),
    ("propellers[1,1].propeller.f_theta", "lists 1 twice"),
    ("propellers[7].propeller.f_theta", r"propellers has 7 entries \(indices 0 to 6, from 0"),
    ("propellers[-1].propeller.f_theta", "is not an index"),
    ("propellers[0:2:x].propeller.f_theta", "is not an index"),
    ("propellers[].propeller.f_theta", "is not an index"),
    ("wing.rayleigh[0:1]", r"wing.rayleigh has 2 values: give one index from 0 to 1"),
    ("propellers[0].propeller.masses[high_lift].mass", "groups name installations"),
    ("propellers[0:2].propeller", "is a table, not a number"),
])
def test_bad_selections_are_one_line_errors_naming_what_is_valid(x57, path, match):
    with pytest.raises(InputError, match=match) as exc:
        P.resolve(x57, path)
    assert _one_line(exc).startswith("parameter path")


def test_a_group_of_a_model_without_groups(x57):
    m = dataclasses.replace(x57, groups={})
    with pytest.raises(InputError, match=r"the model defines no groups \(a \[groups\] table of "
                                         r"the model file, or PropellerWing\(groups=") as exc:
        P.resolve(m, "propellers[high_lift].propeller.f_theta")
    _one_line(exc)


@pytest.mark.parametrize("groups, match", [
    ({"high_lift": (0, 7)}, r"groups.high_lift = \[0, 7\] is invalid: index 7 is outside the 7 "
                            r"installations \(indices from 0 to 6"),
    ({"high_lift": ()}, "non-empty list of installation indices"),
    ({"high_lift": (0, 0)}, "lists installation 0 twice"),
    ({"high_lift": (0.0,)}, "non-empty list of installation indices"),
    ({"high_lift": 3}, "non-empty list of installation indices"),
    ({"9x": (0,)}, "a group name must be an identifier"),
    ([("a", (0,))], "must be a mapping"),
])
def test_bad_groups_of_a_python_model(x57, groups, match):
    with pytest.raises(InputError, match=match) as exc:
        dataclasses.replace(x57, groups=groups)
    _one_line(exc)


@pytest.mark.parametrize("table, match", [
    ("high_lift = [0, 9]", r"x57.toml: groups.high_lift = \[0, 9\] is invalid: index 9 is outside"),
    ("high_lift = []", r"x57.toml: \[groups\] high_lift = \[\] is invalid: must be a non-empty list"),
    ("high_lift = [0, true]", r"\[groups\] high_lift = \[0, True\] is invalid"),
])
def test_bad_groups_of_a_model_file(table, match):
    text = X57.read_text().replace("high_lift = [0, 1, 2, 3, 4, 5]", table)
    with pytest.raises(InputError, match=match) as exc:
        io.loads(text, "x57.toml")
    _one_line(exc)


def test_groups_are_saved_and_read_back(x57):
    again = io.loads(io.dumps(x57))
    assert again.groups == x57.groups and again == x57
    assert "[groups]" not in io.dumps(dataclasses.replace(x57, groups={}))


@settings(max_examples=150, deadline=None, derandomize=True)
@given(st.text(alphabet="0123456789:,-*_ahlgi ", max_size=8))
def test_any_index_text_is_a_parameter_or_a_one_line_error(x57, token):
    try:
        p = P.resolve(x57, f"propellers[{token}].propeller.f_psi")
    except InputError as exc:
        assert "\n" not in str(exc)
        return
    m = p.set(x57, 4.0)
    assert 1 <= sum(f == 4.0 for _, f in _mounts(m)) <= 7


# ----------------------------------------------------------------------------- the CLI
def test_list_params_shows_the_selection_syntax_and_the_groups(capsys):
    assert cli.main(["sweep", str(X57), "--list-params"]) == 0
    out = capsys.readouterr().out
    assert "propellers[0:6]                a Python slice" in out
    assert "propellers[NAME]               a named group" in out
    assert ("propellers[high_lift] = propellers[0,1,2,3,4,5] (propellers 1, 2, 3, 4, 5, 6 of "
            "the reports)") in out


def test_a_bad_group_on_the_command_line_is_one_line_exit_2(capsys):
    code = cli.main(["sweep", str(X57), "--param", "propellers[highlift].propeller.f_psi",
                     "8", "16", "3"])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(err) == 1
    assert "propellers[highlift] names no group: the model's groups are high_lift" in err[0]


def test_group_sweep_of_the_six_high_lift_mounts_of_x57(x57, tmp_path, capsys):
    """Issue 25's done-when: the isotropic mount (f_theta = f_psi) of the six high-lift
    propellers swept together, the tip propeller as it is."""
    out = tmp_path / "s.json"
    code = cli.main(["sweep", str(X57), "--param", ISOTROPIC, "8", "16", "3", "--method",
                     "reduced", "--json", str(out)])
    assert code == 0
    text = capsys.readouterr().out
    assert f"critical speed over {ISOTROPIC} (3 values)" in text
    r = sweeps.CriticalMap.load(out)
    assert r.axes[0].path == ISOTROPIC and r.axes[0].values.tolist() == [8.0, 12.0, 16.0]
    assert r.axes[0].design == 12.0 and r.axes[0].unit == "Hz"
    assert list(r.kind) == ["flutter"] * 3
    # stiffer high-lift mounts whirl later; the design point is the example's (80.0 m/s)
    assert r.critical_speed[0] < r.critical_speed[1] < r.critical_speed[2]
    assert r.critical_speed[1] == pytest.approx(80.0, abs=0.05)
    assert all(1 <= p <= 6 for p in r.columns["propeller"])   # a high-lift propeller whirls
    # the same point from Python, the linked paths given as a tuple
    one = sweeps.sweep(x57, tuple(ISOTROPIC.split(",")), [16.0], method="reduced")
    assert one.critical_speed[0] == r.critical_speed[2]
    assert json.loads(out.read_text())["format"]
