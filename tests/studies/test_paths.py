"""Parameter paths (propwhirl.studies.paths): listing, resolution, setting through the models'
own validation, the scale form, every error message."""
from __future__ import annotations

import pickle
from dataclasses import replace

import numpy as np
import pytest

from propwhirl.cases.ch09_baseline import baseline_propeller, isolated_baseline_propeller
from propwhirl.cases.registry import case_model
from propwhirl.model.propellers.propeller_aero import Distribution
from propwhirl.studies import paths as P
from propwhirl.validate import InputError


@pytest.fixture(scope="module")
def two():
    return case_model("two-propeller")


def test_valid_paths_cover_nested_fields_by_index(two):
    ps = P.valid_paths(two)
    for p in ("flight.density", "wing.GJ", "wing.EI*", "wing.rayleigh[0]",
              "propellers[1].propeller.f_theta", "propellers[0].propeller.masses[0].mass",
              "propellers[0].propeller.inertia.I_theta_P", "propellers[*].propeller.f_psi",
              "propellers[1].y", "propellers[0].propeller.aero_settings.cutoff_lift_slope"):
        assert p in ps, p
    # no strings, switches, functions or derived fields
    for p in ("name", "wing.aero_model", "rotating", "propellers[0].mount",
              "propellers[0].propeller.operation", "wing._mesh", "wing.chord"):
        assert p not in ps, p
    assert not any(p.startswith("propellers[2]") for p in ps)


def test_metadata_gives_unit_range_and_description(two):
    p = P.resolve(two, "propellers[1].propeller.f_theta")
    assert p.unit == "Hz" and (p.range.low, p.range.high) == (1e-3, 1e3)
    assert "pitch frequency" in p.doc and p.label == "propellers[1].propeller.f_theta [Hz]"
    assert p.value(two) == 7.0
    r = P.resolve(two, "wing.rayleigh[1]")
    assert r.unit == "s" and r.range.high == 1.0
    e = P.resolve(two, " wing.EI * ")
    assert e.path == "wing.EI*" and e.scale and e.unit == "" and e.value(two) == 1.0


def test_setting_changes_only_the_addressed_field(two):
    m = P.set_value(two, "propellers[1].propeller.f_theta", 5.0)
    assert m.propellers[1].propeller.f_theta == 5.0
    assert m.propellers[0].propeller.f_theta == 7.0 and two.propellers[1].propeller.f_theta == 7.0
    assert m.wing == two.wing and m.flight == two.flight
    both = P.set_value(two, "propellers[*].propeller.f_psi", 4.0)
    assert [i.propeller.f_psi for i in both.propellers] == [4.0, 4.0]
    d = P.set_value(two, "flight.density", 1.1)
    assert d.flight.density == 1.1 and d.flight.speed_of_sound == two.flight.speed_of_sound
    mass = P.set_value(two, "propellers[0].propeller.masses[0].mass", 20.0)
    assert mass.propellers[0].propeller.masses[0].mass == 20.0
    assert mass.propellers[0].propeller.masses[0].x == two.propellers[0].propeller.masses[0].x
    inertia = P.set_value(two, "propellers[0].propeller.inertia.I_theta_P", 4.0)
    assert inertia.propellers[0].propeller.inertia == {"I_theta_P": 4.0}
    n = P.set_value(two, "wing.n_elements", 30.0)
    assert n.wing.n_elements == 30 and isinstance(n.wing.n_elements, int)


def test_alternative_field_is_cleared():
    p = baseline_propeller(f_theta=None, K_theta=5000.0)
    out = P.set_value(p, "f_theta", 6.0)
    assert out.f_theta == 6.0 and out.K_theta is None
    back = P.set_value(out, "K_theta", 5000.0)
    assert back.K_theta == 5000.0 and back.f_theta is None
    assert P.resolve(p, "f_theta").value(p) is None     # not given: no design value


def test_scale_form_of_distributed_properties(two):
    m = P.set_value(two, "wing.EI*", 0.5)
    assert m.wing.EI == pytest.approx(0.5 * two.wing.EI)
    np.testing.assert_allclose(m.wing.element_properties()["EI"],
                               0.5 * two.wing.element_properties()["EI"])
    # one value per element
    w = P.set_value(two, "wing.GJ", 1.0e5)
    arr = P.set_value(w, "wing.GJ*", 1.0)   # a number stays a number
    assert arr.wing.GJ == 1.0e5
    per = replace(two.wing, GJ=np.linspace(1e5, 2e5, two.wing.element_count))
    model = two.with_(wing=per)
    sc = P.set_value(model, "wing.GJ*", 2.0)
    np.testing.assert_allclose(sc.wing.GJ, 2.0 * model.wing.GJ)
    one = P.set_value(model, "wing.GJ[3]", 9.0e4)
    assert one.wing.GJ[3] == 9.0e4 and one.wing.GJ[4] == model.wing.GJ[4]
    # a function of y: scaled and still picklable
    fn = model.with_(wing=replace(per, GJ=_gj))
    f2 = P.set_value(fn, "wing.GJ*", 2.0)
    assert isinstance(f2.wing.GJ, P.Scaled)
    np.testing.assert_allclose(f2.wing.element_properties()["GJ"],
                               2.0 * fn.wing.element_properties()["GJ"])
    assert pickle.loads(pickle.dumps(f2)).wing.GJ.factor == 2.0
    f4 = P.set_value(f2, "wing.GJ*", 2.0)       # factors compose on the original function
    assert f4.wing.GJ.factor == 4.0 and f4.wing.GJ.function is _gj
    # a radial distribution of the blade chord
    p = baseline_propeller(blade_chord=Distribution.linear(0.1, 0.05, 0.2, "chord"))
    q = P.set_value(p, "blade_chord*", 2.0)
    assert q.blade_chord.values == pytest.approx((0.2, 0.1))


def _gj(y):
    return 1.0e5 * (1.0 - 0.5 * y / 5.7)


def test_variants_and_grid():
    iso = isolated_baseline_propeller()
    vs = P.variants(iso, {"propeller.f_theta": [3.0, 4.0], "propeller.f_psi": [5.0, 6.0]})
    assert [(m.propeller.f_theta, m.propeller.f_psi) for m in vs] == [(3.0, 5.0), (4.0, 6.0)]
    g = P.grid_variants(iso, [("propeller.f_theta", [3.0, 4.0]), ("propeller.f_psi", [5.0, 6.0, 7.0])])
    assert [(m.propeller.f_theta, m.propeller.f_psi) for m in g][:4] == [
        (3.0, 5.0), (3.0, 6.0), (3.0, 7.0), (4.0, 5.0)]
    with pytest.raises(InputError, match="2 values, expected 1"):
        P.variants(iso, {"propeller.f_theta": [3.0], "propeller.f_psi": [5.0, 6.0]})
    with pytest.raises(InputError, match="appears twice"):
        P.grid_variants(iso, [("propeller.f_theta", [3.0]), ("propeller.f_theta", [4.0])])


# ----------------------------------------------------------------------------- errors
@pytest.mark.parametrize("path, match", [
    ("wing.gj", r"parameter path 'wing.gj' is invalid: wing has no field 'gj'; nearest valid paths: wing.GJ"),
    ("GJ", r"PropellerWing has no field 'GJ'; nearest valid paths: wing.GJ"),
    ("flight.densty", r"flight has no field 'densty'; nearest valid paths: flight.density"),
    ("propellers[2].propeller.f_theta", r"propellers has 2 entries \(indices 0 to 1, from 0: propellers\[0\] is "
                                        r"propeller 1 of the reports\); nearest valid "
                                        r"paths: propellers\[1\].propeller.f_theta"),
    ("propellers.propeller.f_theta", r"propellers is a list of tables: give an index"),
    ("wing.rayleigh", r"wing.rayleigh is a list of numbers: address one entry; nearest valid paths: "
                      r"wing.rayleigh\[1\], wing.rayleigh\[0\]"),
    ("wing.rayleigh[5]", r"wing.rayleigh has 2 values: give an index from 0 to 1"),
    ("wing.GJ[0]", r"wing.GJ is not a list: it takes no index"),
    ("propellers[0].propeller", r"is a table, not a number: address one of its fields"),
    ("wing..GJ", r"'' is not a field name"),
    ("flight.density.x", r"flight.density has no fields"),
])
def test_unknown_paths_list_the_nearest(two, path, match):
    with pytest.raises(InputError, match=match) as exc:
        P.resolve(two, path)
    assert "\n" not in str(exc.value)


@pytest.mark.parametrize("path, what", [
    ("wing.aero_model", "a string"), ("propellers[0].propeller.operation", "a string"),
    ("rotating", "a switch"), ("propellers[0].aero", "a switch"), ("name", "a string"),
])
def test_non_numeric_fields_are_refused(two, path, what):
    with pytest.raises(InputError, match=rf"parameter path '{path.replace('[', '.').replace(']', '.')}' "
                       rf"is invalid: {what} .*not a number: only numeric fields can be varied"):
        P.resolve(two, path)


def test_scale_form_needs_a_value(two):
    with pytest.raises(InputError, match=r"the scale form needs a number to scale, the field is None"):
        P.resolve(two, "wing.max_element_length*")
    with pytest.raises(InputError, match="scale form needs a number"):
        P.resolve(two, "wing.n_elements*")        # an integer is not scaled
    ell = two.with_(wing=replace(two.wing, lift_slope="elliptic"))
    with pytest.raises(InputError, match=r"a named rule 'elliptic'"):
        P.resolve(ell, "wing.lift_slope*")
    assert P.set_value(ell, "wing.lift_slope", 6.0).wing.lift_slope == 6.0


@pytest.mark.parametrize("path, value, match", [
    ("flight.density", -1.0, r"^flight.density = -1.0 kg/m\^3 is outside the valid range \[1e-4, 10\] kg/m\^3$"),
    ("propellers[1].propeller.f_theta", 2000.0,
     r"^propellers\[1\].propeller.f_theta = 2000.0 Hz is outside the valid range \[1e-3, 1000\] Hz$"),
    ("wing.rayleigh[1]", 3.0, r"wing.rayleigh\[1\] = 3.0 s is outside the valid range \[0, 1\] s"),
    ("wing.n_elements", 2.5, r"wing.n_elements = 2.5 is invalid: must be a whole number"),
    ("flight.density", float("nan"), r"flight.density = nan kg/m\^3 is invalid: must be finite"),
    ("flight.density", [1.0, 2.0], r"must be one number"),
    ("wing.EI*", -1.0, r"wing.EI\* = -1.0 is invalid: must be > 0"),
    # the model's own checks, restated with the path
    ("propellers[0].propeller.hub_radius", 5.0,
     r"^propellers\[0\].propeller.hub_radius = 5 m: hub_radius = 5.0 m is invalid: must be < radius"),
    ("propellers[0].y", 100.0, r"^propellers\[0\].y = 100 m: propellers\[0\].y = 100.0 m is outside the wing"),
    ("wing.EI*", 1e7, r"^wing.EI\* = 1e\+07: EI = 7000000000000.0 N m\^2 is outside the valid range \[1e-3, 1e12\] N m\^2$"),
])
def test_invalid_values_name_the_path_and_range(two, path, value, match):
    with pytest.raises(InputError, match=match):
        P.set_value(two, path, value)


def test_not_a_model():
    with pytest.raises(InputError, match="parameter paths address the fields of a model dataclass"):
        P.resolve(3.0, "x")
    with pytest.raises(InputError, match="non-empty string"):
        P.resolve(isolated_baseline_propeller(), "")
