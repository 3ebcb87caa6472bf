"""Model files (TOML) and V-g-f tables (CSV): round trips, the example file, bad input."""
from __future__ import annotations

import dataclasses
import os
import subprocess
import sys
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from propwhirl import io
from propwhirl.io import schema
from propwhirl.model.propellers.propeller_aero import AeroSettings, Distribution, HouboltReedSource, PropellerGeometry
from propwhirl.analysis.stability import analyse
from propwhirl.cases.ch06_isolated import bennett_bland_propeller
from propwhirl.cases.ch07_patil import patil_model
from propwhirl.cases.ch09_baseline import (
    baseline_flight,
    baseline_propeller,
    baseline_wing,
    isolated_baseline_propeller,
)
from propwhirl.cases.ch10_other_wings import two_propeller_wing, wingtip_propeller_wing
from propwhirl.model.systems import FlightCondition, Installation, IsolatedPropeller, PropellerWing
from propwhirl.model.propellers.propeller import MeasuredDerivatives, PointMass
from propwhirl.validate import InputError
from propwhirl.model.fields import spec
from propwhirl.model.structure.wing import Wing

ROOT = Path(__file__).resolve().parents[2]
SPEEDS = np.array([5.0, 120.0, 300.0])


def _round_trip(model):
    return io.loads(io.dumps(model))


def _same_state_matrices(a, b, speeds=SPEEDS) -> None:
    A, B = a.state_matrix(speeds), b.state_matrix(speeds)
    assert A.shape == B.shape
    assert np.array_equal(A, B)  # floats are written with repr: the round trip is exact
    assert a.state_labels() == b.state_labels()


def _small_wing(**changes) -> Wing:
    base = dict(name="small wing", semi_span=4.0, root_chord=1.0, tip_chord=0.7,
                mass_per_length=np.linspace(20.0, 12.0, 4), radius_of_gyration=0.25,
                elastic_axis=np.array([0.40, 0.42, 0.44, 0.46]), centre_of_gravity=0.45,
                EI=np.linspace(9e5, 3e5, 4), GJ=2e5, aerodynamic_centre=0.25, n_elements=4,
                aero_model="wagner", rayleigh=(0.05, 1e-4))
    base.update(changes)
    return Wing(**base)


MEASURED = MeasuredDerivatives({"CZ_theta": -0.42, "Cm_psi": 0.138, "CY_psi": 0.42,
                                "Cn_theta": -0.138, "Cm_q": -0.14})


def _models():
    """Models exercising every kind of field the writer knows."""
    tab_chord = Distribution.tabulated([0.1, 0.5, 1.0], [0.12, 0.10, 0.06], "chord")
    p_tab = baseline_propeller(blade_chord=tab_chord, hub_radius=0.0762, spin_inertia=1.3,
                               K_theta=9000.0, f_theta=None, damping="zeta",
                               aero_settings=AeroSettings(wake=False, cnq_sign="rodden_rose"))
    p_meas = baseline_propeller(derivatives=MEASURED, operation="constant-speed", rpm=2250.0,
                                inertia={"I_theta_P": 40.0, "I_psi_P": 41.0}, rotation=-1)
    geo = PropellerGeometry(4, 0.8, 0.2, tab_chord,
                            lift_slope=Distribution.tabulated([0.0, 1.0], [6.0, 5.0], "lift_slope"),
                            reference_chord=0.1, aspect_ratio=3.5)
    p_geo = baseline_propeller(derivatives=HouboltReedSource(geo, AeroSettings(method="bennett_bland")))
    return {
        "wingtip": wingtip_propeller_wing(),
        "two rigid non-rotating": two_propeller_wing("rigid", rotating=False, propeller_aero=False),
        "patil elliptic": patil_model(6, "elliptic"),
        "isolated constant speed": isolated_baseline_propeller(operation="constant-speed", rpm=2250.0),
        "bennett-bland": bennett_bland_propeller(3),
        "per-element wing, three propellers": PropellerWing(
            _small_wing(), FlightCondition(1.1, 335.0, (2.0, 250.0, 7.5)),
            (Installation(p_tab, 1.0), Installation(p_meas, 2.0, "flexible", aero=False),
             Installation(p_geo, 4.0, "rigid")), wing_aero=True, propeller_aero=True,
            rotating=True, name="three propellers"),
        "polar inertia, no wing aero": PropellerWing(
            _small_wing(polar_inertia=0.9, radius_of_gyration=None, tip_chord=None),
            FlightCondition(0.5), (Installation(p_meas, 3.0),), wing_aero=False),
    }


MODELS = _models()


@pytest.mark.parametrize("name", list(MODELS))
def test_round_trip_gives_identical_state_matrices(name):
    model = MODELS[name]
    back = _round_trip(model)
    assert type(back) is type(model)
    _same_state_matrices(model, back)
    assert back.name == model.name
    if isinstance(model, PropellerWing):
        assert (back.wing_aero, back.propeller_aero, back.rotating) == (
            model.wing_aero, model.propeller_aero, model.rotating)
        assert [(i.y, i.mount, i.aero) for i in back.propellers] == [
            (i.y, i.mount, i.aero) for i in model.propellers]
    assert back.flight == model.flight


def test_text_is_stable_under_a_second_round_trip():
    for model in MODELS.values():
        text = io.dumps(model)
        assert io.dumps(io.loads(text)) == text


def test_propellers_round_trip_field_by_field():
    for model in MODELS.values():
        props = ([i.propeller for i in model.propellers] if isinstance(model, PropellerWing)
                 else [model.propeller])
        for p in props:
            back = io.loads(io.dumps(p))
            assert back == p  # every compared dataclass field
            assert back.derivatives == p.derivatives  # excluded from ==, checked here


def test_identical_propellers_share_one_table_and_one_object():
    text = io.dumps(two_propeller_wing())
    data = tomllib.loads(text)
    assert list(data["propellers"]) == ["p1"]
    assert [i["propeller"] for i in data["installations"]] == ["p1", "p1"]
    back = io.loads(text)
    assert back.propellers[0].propeller is back.propellers[1].propeller


def test_file_states_units_and_is_valid_toml():
    text = io.dumps(wingtip_propeller_wing())
    data = tomllib.loads(text)
    assert data["format"] == "propwhirl-model" and data["type"] == "propeller-wing"
    assert data["wing"]["semi_span_m"] == 5.7 and data["wing"]["EI_N_m2"] == 7.0e5
    assert data["flight"]["density_kg_per_m3"] == 0.96287
    p = data["propellers"]["p1"]
    assert p["rotor"] == {"mass_kg": 8.0, "x_m": -1.16} and p["f_theta_hz"] == 7.0
    for suffix, unit in schema.UNIT_SUFFIXES:
        assert f"{suffix}" in text and unit in text  # the unit table is in the header comment


def test_measured_derivatives_are_a_table():
    data = tomllib.loads(io.dumps(baseline_propeller(derivatives=MEASURED)))
    d = data["propellers"]["p1"]["derivatives"]
    assert d["source"] == "measured"
    assert d["values"] == dict(MEASURED.values)


def test_example_file_is_the_case_library_wingtip_model():
    model = io.load_model(ROOT / "examples" / "wingtip.toml")
    _same_state_matrices(model, wingtip_propeller_wing(), np.array([1.0, 143.0, 163.0, 350.0]))


def test_save_and_load_files(tmp_path):
    path = io.save_model(MODELS["bennett-bland"], tmp_path / "bb.toml")
    _same_state_matrices(io.load_model(path), MODELS["bennett-bland"])


def test_every_model_field_is_known_to_the_writer():
    """A new field in a model class must be added to io (and here) — else it would be lost."""
    known = {
        "Wing": {"semi_span", "mass_per_length", "EI", "GJ", "root_chord", "tip_chord", "chord",
                 "polar_inertia", "radius_of_gyration", "elastic_axis", "centre_of_gravity",
                 "lift_slope", "aerodynamic_centre", "n_elements", "stations", "max_element_length",
                 "aero_model", "rayleigh", "EI_chordwise", "aero", "dlm_chordwise_panels",
                 "dlm_mach", "dlm_spanwise_panels", "compressibility", "strip_mach", "name",
                 "_mesh"},
        "Propeller": {"radius", "rotor", "masses", "pivot_pitch", "pivot_yaw", "f_theta", "f_psi",
                      "K_theta", "K_psi", "damping_theta", "damping_psi", "damping",
                      "spin_inertia", "n_blades", "hub_radius", "blade_chord", "operation",
                      "beta_075_deg", "zero_lift_angle_deg", "advance_rule", "inertia", "rpm",
                      "derivatives", "aero_settings", "rotation", "name"},
        "PropellerWing": {"wing", "flight", "propellers", "wing_aero", "propeller_aero",
                          "rotating", "name", "groups", "_nodes"},
        "IsolatedPropeller": {"propeller", "flight", "propeller_aero", "rotating", "name"},
        "Installation": {"propeller", "y", "mount", "aero", "state", "rotation"},
        "FlightCondition": {"density", "speed_of_sound", "speed_range"},
        "AeroSettings": {"wake", "compressibility", "aspect_ratio_correction", "cnq_sign",
                         "method", "cutoff_lift_slope", "quadrature_order"},
        "PointMass": {"mass", "x"},
        "PropellerGeometry": {"n_blades", "radius", "hub_ratio", "chord", "lift_slope",
                              "reference_chord", "aspect_ratio"},
        "MeasuredDerivatives": {"values"},
        "HouboltReedSource": {"geometry", "settings"},
    }
    assert {k: set(v) for k, v in io.model_fields().items()} == known


# ----------------------------------------------------------------------------- the schema
def test_schema_declares_every_field_and_the_docs_are_current():
    schema.check()  # every field of every saved class carries a consistent spec
    doc = (ROOT / "docs" / "model-file.md").read_text(encoding="utf-8")
    assert doc == schema.markdown(), (
        "docs/model-file.md is stale: regenerate it with `python -m propwhirl.io > docs/model-file.md`")


def test_docs_list_every_key_with_its_unit_and_default():
    text = schema.markdown()
    for cls in schema.SCHEMA_CLASSES:
        for f in schema.fields_of(cls):
            for key in f.keys():
                assert f"| `{key}` |" in text, (cls.__name__, key)
    rows = {s.title: {r[0]: r for r in s.rows} for s in schema.sections()}
    assert rows["[wing]"]["EI_N_m2"][2:4] == ("N m^2", "required")
    assert rows["[wing]"]["EI_N_m2"][4] == "[1e-3, 1e12] N m^2"  # the valid range
    assert rows["[wing]"]["elastic_axis_chord"][3] == "required"  # issue 9: no silent 0.5
    assert rows["[wing]"]["aerodynamic_centre_chord"][3] == "`0.25` (physical)"
    assert rows["[wing]"]["root_chord_m"][3] == "required"  # a file must give it (Python: 1.0)
    assert rows["[propellers.KEY]"]["beta_075_deg"][3] == "required for fixed-pitch"
    assert rows["[propellers.KEY]"]["blade_chord_m"][3] == "required without [derivatives]"
    assert rows["[flight]"]["speed_range_m_per_s"][3] == "`[1.0, 350.0, 10.0]` (setting)"
    hr = rows['[propellers.KEY.derivatives] with source = "houbolt-reed"']
    assert hr["hub_ratio"][3] == "required"  # issue 9: no longer a silent 0 in files


def test_omitted_keys_take_the_dataclass_defaults():
    """The reader has no defaults of its own: every omitted key gives the class's default."""
    text = """
type = "propeller-wing"
installations = [{ propeller = "x", y_m = 2.0 }]
[wing]
semi_span_m = 4.0
root_chord_m = 1.0
mass_per_length_kg_per_m = 20.0
EI_N_m2 = 1e6
GJ_N_m2 = 1e5
radius_of_gyration_chord = 0.25
elastic_axis_chord = 0.4
centre_of_gravity_chord = 0.45
n_elements = 4
[flight]
density_kg_per_m3 = 1.225
speed_of_sound_m_per_s = 340.0
[propellers.x]
radius_m = 1.0
rotor = { mass_kg = 10.0, x_m = -0.5 }
f_theta_hz = 5.0
f_psi_hz = 5.0
pivot_pitch_m = 0.0
pivot_yaw_m = 0.0
rotation = 1
n_blades = 3
hub_radius_m = 0.1
blade_chord_m = 0.1
beta_075_deg = 30.0
zero_lift_angle_deg = -3.0
"""
    m = io.loads(text)
    given = {"semi_span", "root_chord", "mass_per_length", "EI", "GJ", "radius_of_gyration",
             "n_elements", "density", "radius", "rotor", "f_theta", "f_psi", "propeller", "y",
             "wing", "flight", "propellers", "_nodes", "_mesh", "elastic_axis", "centre_of_gravity",
             "speed_of_sound", "pivot_pitch", "pivot_yaw", "rotation", "n_blades", "hub_radius",
             "blade_chord", "beta_075_deg", "zero_lift_angle_deg"}
    objects = [m, m.wing, m.flight, m.propellers[0], m.propellers[0].propeller]
    checked = 0
    for obj in objects:
        for f in schema.fields_of(type(obj)):
            if f.name not in given:
                assert f.default is not dataclasses.MISSING, (type(obj).__name__, f.name)
                assert getattr(obj, f.name) == f.default, (type(obj).__name__, f.name)
                checked += 1
    assert checked >= 24


def test_houbolt_reed_geometry_requires_hub_ratio():
    p = baseline_propeller(derivatives=HouboltReedSource(PropellerGeometry(4, 0.8, 0.0, 0.1)))
    text = io.dumps(p)
    assert "hub_ratio = 0.0\n" in text
    assert io.loads(text).derivatives == p.derivatives
    with pytest.raises(InputError, match=r"missing key 'hub_ratio' in \[propellers.p1.derivatives\]"):
        io.loads(text.replace("hub_ratio = 0.0\n", ""))  # PropellerGeometry requires it


def test_incomplete_declarations_are_caught():
    @dataclass(frozen=True)
    class NoSpec:
        x: float

    @dataclass(frozen=True)
    class WrongUnit:
        x: float = field(metadata=spec("x_m", "kg", "a position"))

    @dataclass(frozen=True)
    class DefaultKindMissing:
        x: float = field(default=1.0, metadata=spec("x_m", "m", "a position"))

    @dataclass(frozen=True)
    class DefaultKindForRequired:
        x: float = field(metadata=spec("x_m", "m", "a position", default="physical"))

    for cls, message in ((NoSpec, "has no model-file spec"), (WrongUnit, "does not end with"),
                         (DefaultKindMissing, "exactly when the field has a default"),
                         (DefaultKindForRequired, "exactly when the field has a default")):
        with pytest.raises(TypeError, match=message):
            schema.fields_of(cls)


def test_file_starts_with_the_header():
    text = io.dumps(MODELS["bennett-bland"])
    assert text.startswith(schema.header())
    assert "docs/model-file.md" in schema.header() and "format version 2" in schema.header()


def test_saving_without_tomli_w_names_the_extra(monkeypatch, tmp_path):
    monkeypatch.setitem(sys.modules, "tomli_w", None)  # `import tomli_w` now fails
    for call in (lambda: io.dumps(MODELS["wingtip"]),
                 lambda: io.save_model(MODELS["wingtip"], tmp_path / "m.toml")):
        with pytest.raises(InputError, match=r"pip install propwhirl\[toml\]") as exc:
            call()
        assert "\n" not in str(exc.value)
    assert not (tmp_path / "m.toml").exists()
    assert io.load_model(ROOT / "examples" / "wingtip.toml").name == MODELS["wingtip"].name


def test_text_is_byte_identical_across_processes():
    code = ("import sys; from propwhirl import io; "
            "from propwhirl.cases.ch10_other_wings import two_propeller_wing; "
            "from propwhirl.cases.ch06_isolated import bennett_bland_propeller; "
            "sys.stdout.buffer.write((io.dumps(two_propeller_wing()) + "
            "io.dumps(bennett_bland_propeller(3))).encode())")
    outs = [subprocess.run([sys.executable, "-c", code], capture_output=True, check=True,
                           env={**os.environ, "PYTHONHASHSEED": seed}).stdout
            for seed in ("1", "2")]
    here = (io.dumps(two_propeller_wing()) + io.dumps(bennett_bland_propeller(3))).encode()
    assert outs[0] == outs[1] == here


# ----------------------------------------------------------------------------- cannot be saved
@pytest.mark.parametrize("model, field", [
    (PropellerWing(dataclasses.replace(baseline_wing(4), mass_per_length=lambda y: 25.0 + 0 * y),
                   baseline_flight()), "wing.mass_per_length"),
    (PropellerWing(dataclasses.replace(baseline_wing(4), chord=lambda y: 1.0 + 0 * y),
                   baseline_flight()), "wing.chord"),
    (PropellerWing(dataclasses.replace(baseline_wing(4), lift_slope=lambda y: 6.0 + 0 * y),
                   baseline_flight()), "wing.lift_slope"),
    (baseline_propeller(blade_chord=lambda eta: 0.1 + 0 * eta), "blade_chord"),
    (baseline_propeller(derivatives=lambda V, Om, a: {}), "derivatives"),
])
def test_functions_cannot_be_saved_and_the_error_names_the_field(model, field):
    with pytest.raises(InputError, match=field.replace(".", r"\.")):
        io.dumps(model)


def test_unsupported_object_is_an_input_error(tmp_path):
    with pytest.raises(InputError, match="cannot save a str"):
        io.dumps("wing")
    with pytest.raises(InputError, match="cannot write"):
        io.save_model(MODELS["wingtip"], tmp_path / "missing" / "m.toml")


# ----------------------------------------------------------------------------- bad files
EXAMPLE = (ROOT / "examples" / "wingtip.toml").read_text()


@pytest.mark.parametrize("old, new, message", [
    ("semi_span_m = 5.7", "semispan_m = 5.7", "unknown key 'semispan_m' in [wing]"),
    ("format_version = 2", "format_version = 2\ncolour = \"red\"", "unknown key 'colour' in the top level"),
    ("rotation = 1", "rotation = 1\nspin = 2", "unknown key 'spin' in [propellers.p1]"),
    ("wake = true", "wake = true\nwakes = 1", "unknown key 'wakes' in [propellers.p1.aero_settings]"),
    ("[propellers.p1.rotor]\nmass_kg = 8.0", "[propellers.p1.rotor]\nmass = 8.0",
     "unknown key 'mass' in [propellers.p1.rotor]"),
    ("semi_span_m = 5.7", "", "missing key 'semi_span_m' in [wing] (root-to-tip length; m; valid range [0.01, 1000] m)"),
    ("[flight]", "[flite]", "unknown key 'flite' in the top level"),
    ("EI_N_m2 = 700000.0", "EI_N_m2 = \"stiff\"", "[wing] EI_N_m2 = 'stiff' is invalid: must be a number"),
    ("n_elements = 25", "n_elements = 25.0", "[wing] n_elements = 25.0 is invalid: must be an integer"),
    ("wing_aero = true", "wing_aero = 1", "[switches] wing_aero = 1 is invalid: must be true or false"),
    ("EI_N_m2 = 700000.0", "EI_N_m2 = -1.0", "[wing] EI_N_m2 = -1.0 is outside the valid range [1e-3, 1e12] N m^2"),
    ("EI_N_m2 = 700000.0", "EI_N_m2 = [1.0, 2.0]", "EI_N_m2 has 2 values but the wing has n_elements = 25"),
    ("density_kg_per_m3 = 0.96287", "density_kg_per_m3 = 0.0", "[flight] density_kg_per_m3 = 0.0 is outside the valid range [1e-4, 10] kg/m^3 (air density)"),
    ("mount = \"flexible\"", "mount = \"glued\"", "mount = 'glued' is invalid"),
    ("y_m = 5.7", "y_m = 7.0", "outside the wing"),
    ("propeller = \"p1\"", "propeller = \"p9\"", "[installations[0]] propeller = 'p9' is invalid"),
    ("type = \"propeller-wing\"", "type = \"glider\"", "type = 'glider' is invalid"),
    ("format_version = 2", "format_version = 3", "format_version = 3 is newer than this propwhirl reads"),
    ("f_theta_hz = 7.0", "f_theta_hz = 7.0\nK_theta_N_m_per_rad = 1.0", "exactly one of f_theta"),
    ("aero_model = \"leishman-nguyen\"", "aero_model = \"doublet-lattice\"", "[wing] aero_model = 'doublet-lattice' is invalid"),
    ("cnq_sign = \"thesis\"", "cnq_sign = \"other\"", "cnq_sign = 'other' is invalid"),
    ("[wing]", "[wing", "not valid TOML"),
    ("    350.0,\n    10.0,\n]", "    350.0,\n]", "[flight] speed_range_m_per_s = [1.0, 350.0] is invalid"),
    ("    1.0,\n    350.0,", "    0.0,\n    350.0,",
     "[flight] speed_range_m_per_s[0] = 0.0 is outside the valid range (0, 10000] m/s"),
    ("aero = true, ", "aero = \"yes\", ", "[installations[0]] aero = 'yes' is invalid"),
    ("semi_span_m = 5.7", "semi_span_m = 5.7\nsemi_span_m = 6.0",
     "column 18): 'semi_span_m = 6.0'"),
    ("blade_chord_m = 0.094", "blade_chord_m = 0.094\nblade_chord = { eta = [0.0, 1.0], chord_m = [0.1, 0.1] }",
     "[propellers.p1]: give exactly one of blade_chord_m (a number) or [propellers.p1.blade_chord]"),
    ("[propellers.p1.rotor]\nmass_kg = 8.0\n", "[propellers.p1.rotor]\n",
     "missing key 'mass_kg' in [propellers.p1.rotor] (mass; kg; valid range [1e-4, 1e5] kg)"),
    ("[flight]\ndensity_kg_per_m3 = 0.96287", "[flight]",
     "missing key 'density_kg_per_m3' in [flight] (air density; kg/m^3"),
    ("root_chord_m = 1.25\n", "", "missing key 'root_chord_m' in [wing]"),
    ("radius_m = 0.762", "radius_m = true", "[propellers.p1] radius_m = True is invalid: must be a number"),
    ("damping = \"g\"", "damping = \"G\"", "[propellers.p1] damping = 'G' is invalid: must be one of g, zeta"),
    ("semi_span_m = 5.7", "semispan_m = 5.7", "(did you mean semi_span_m?)"),
    ("EI_N_m2 = 700000.0", "EI_N_m2 = -1.0", "(bending rigidity)"),
])
def test_bad_model_files_raise_input_errors_naming_the_field(old, new, message):
    assert old in EXAMPLE
    with pytest.raises(InputError) as exc:
        io.loads(EXAMPLE.replace(old, new, 1), "model.toml")
    assert str(exc.value).startswith("model.toml: ")
    assert message in str(exc.value)


def test_missing_file(tmp_path):
    with pytest.raises(InputError, match="not found"):
        io.load_model(tmp_path / "nope.toml")


def test_minimal_hand_written_file_uses_the_documented_defaults():
    text = """
type = "isolated-propeller"
propeller = "x"
[flight]
density_kg_per_m3 = 1.225
speed_of_sound_m_per_s = 340.0
[propellers.x]
radius_m = 1.0
rotor = { mass_kg = 10.0, x_m = -0.5 }
f_theta_hz = 5.0
f_psi_hz = 5.0
pivot_pitch_m = 0.0
pivot_yaw_m = 0.0
rotation = 1
beta_075_deg = 35.0
zero_lift_angle_deg = -3.0
[propellers.x.derivatives]
source = "measured"
[propellers.x.derivatives.values]
CZ_theta = -0.5
"""
    m = io.loads(text)
    assert isinstance(m, IsolatedPropeller)
    p = m.propeller
    assert p.pivot_pitch == 0.0 and p.operation == "fixed-pitch" and p.damping == "g"
    assert p.derivatives == MeasuredDerivatives({"CZ_theta": -0.5})
    assert m.propeller_aero and m.rotating
    assert np.isfinite(m.state_matrix(np.array([50.0]))).all()


# ----------------------------------------------------------------------------- hypothesis
names = st.text(min_size=0, max_size=20)  # any unicode: exercises the TOML string escapes
pos = st.floats(min_value=1e-3, max_value=1e6, allow_nan=False, allow_infinity=False)
frac = st.floats(min_value=0.05, max_value=0.95)


@settings(max_examples=30, deadline=None)
@given(name=names, wname=names, pname=names, span=st.floats(0.5, 20.0), chord=st.floats(0.1, 3.0),
       taper=st.floats(0.3, 1.0), m=st.lists(st.floats(1.0, 100.0), min_size=3, max_size=3),
       ea=frac, cg=frac, EI=pos, GJ=pos, rho=st.floats(0.05, 1.5),
       beta=st.floats(10.0, 60.0), f=st.floats(1.0, 30.0), g=st.floats(0.0, 0.1),
       x_rotor=st.floats(-2.0, -0.5), x_motor=st.floats(-1.5, -0.2), pivot=st.floats(-0.1, 0.1),
       node=st.integers(1, 3), mount=st.sampled_from(["flexible", "rigid"]),
       switches=st.tuples(st.booleans(), st.booleans(), st.booleans()))
def test_random_models_round_trip_exactly(name, wname, pname, span, chord, taper, m, ea, cg, EI,
                                          GJ, rho, beta, f, g, x_rotor, x_motor, pivot, node,
                                          mount, switches):
    wing = Wing(name=wname, semi_span=span, root_chord=chord, tip_chord=chord * taper,
                mass_per_length=np.array(m), radius_of_gyration=0.25, elastic_axis=ea,
                centre_of_gravity=cg, EI=EI, GJ=GJ, n_elements=3)
    prop = baseline_propeller(name=pname, rotor=PointMass(8.0, x_rotor),
                              masses=(PointMass(35.0, x_motor),), pivot_pitch=pivot,
                              pivot_yaw=pivot, beta_075_deg=beta, f_theta=f, f_psi=f * 0.9,
                              damping_theta=g, damping_psi=g)
    model = PropellerWing(wing, FlightCondition(rho), (Installation(prop, wing.node_y[node], mount),),
                          *switches, name=name)
    back = _round_trip(model)
    assert back.name == name and back.wing.name == wname and back.propellers[0].propeller.name == pname
    assert back.propellers[0].propeller == prop
    _same_state_matrices(model, back, np.array([30.0]))


# ----------------------------------------------------------------------------- V-g-f CSV
@pytest.fixture(scope="module")
def small_analysis():
    return analyse(isolated_baseline_propeller(), np.arange(1.0, 351.0, 50.0))


def test_vgf_csv_round_trip(tmp_path, small_analysis):
    path = io.write_vgf_csv(small_analysis, tmp_path / "vgf.csv")
    table = small_analysis.sweep.table()
    back = io.read_vgf_csv(path)
    assert list(back) == list(table)
    for key, col in table.items():
        if key == "label":
            assert list(back[key]) == list(col)
        else:
            assert np.array_equal(back[key], col)  # repr floats: exact
    count, header = path.read_text().splitlines()[:2]
    assert count == f"# propwhirl V-g-f table: {len(table['V'])} rows"
    assert header == "V_m_per_s,mode,label,frequency_hz,damping_ratio,real_per_s,imag_per_s"
    from_sweep = io.read_vgf_csv(io.write_vgf_csv(small_analysis.sweep, tmp_path / "s.csv"))
    assert np.array_equal(from_sweep["V"], table["V"])


def test_vgf_csv_bad_input(tmp_path):
    bad = tmp_path / "bad.csv"
    bad.write_text("a,b\n1,2\n")
    with pytest.raises(InputError, match="not a V-g-f table"):
        io.read_vgf_csv(bad)
    bad.write_text("V_m_per_s,mode,label,frequency_hz,damping_ratio,real_per_s,imag_per_s\n"
                   "1.0,0,wing 1,x,0.1,-1.0,2.0\n")
    with pytest.raises(InputError, match="frequency_hz"):
        io.read_vgf_csv(bad)
    with pytest.raises(InputError, match="not found"):
        io.read_vgf_csv(tmp_path / "none.csv")
