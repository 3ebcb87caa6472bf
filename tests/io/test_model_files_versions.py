"""Model-file format versions (issue 20, item 11): files of format version 1 keep loading.

Version 2 made keys required that version 1 let a file omit (issue 9: no silent default for a
value of the aircraft).  A version-1 file omitting them is read with the values version 1 gave
them, and one note naming those values; a file newer than this propwhirl is a one-line error.
The fixtures in tests/io/data are real format-1 files from git history: the example of the
first release (ad70631, hand-commented), the example as the format-1 writer wrote it
(874de5b^1) and the documented example of `propwhirl.io.loads` of that time (874de5b^1).
"""
from __future__ import annotations

from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from propwhirl import io
from propwhirl.io import schema, versions
from propwhirl.model.propellers.propeller import PointMass, Propeller
from propwhirl.validate import InputError

DATA = Path(__file__).resolve().parent / "data"
ROOT = Path(__file__).resolve().parents[2]
RELEASE = (DATA / "format1_wingtip_0.1.0.toml").read_text()      # first release's example
WRITTEN = (DATA / "format1_wingtip.toml").read_text()             # format-1 writer's output
DOCUMENTED = (DATA / "format1_propeller.toml").read_text()        # loads's docstring example

#: (key, its line in RELEASE): the keys of the example version 2 requires and version 1 did
#: not, with the values version 1 gave them when omitted (the example states those values).
V1_KEYS = {"elastic_axis_chord": "0.5", "centre_of_gravity_chord": "0.5",
           "speed_of_sound_m_per_s": "330.8027446243564", "pivot_pitch_m": "0.0",
           "pivot_yaw_m": "0.0", "n_blades": "3", "beta_075_deg": "35.0",
           "zero_lift_angle_deg": "-3.0", "rotation": "1"}


def _without(text: str, keys) -> str:
    """`text` without the lines setting `keys` (comments after a value allowed)."""
    lines = text.splitlines(keepends=True)
    out = [ln for ln in lines if not any(ln.startswith(f"{k} = ") for k in keys)]
    assert len(out) == len(lines) - len(set(keys)), "each key is set on one line"
    return "".join(out)


def _read(text: str, source: str = "old.toml"):
    notes: list[str] = []
    model = io.loads(text, source, notes=notes)
    return model, notes


def test_the_documented_format_1_example_loads_as_documented():
    """It failed with "missing key 'pivot_pitch_m' in [propellers.p]" after the ranges merge."""
    p, notes = _read(DOCUMENTED, "propeller.toml")
    assert (p.radius, p.beta_075_deg) == (1.0, 35.0)  # the result that version documented
    # every value as version 1's reader gave it (its Propeller's defaults, printed by that code)
    assert p == Propeller(radius=1.0, rotor=PointMass(10.0, -0.5), f_theta=5.0, f_psi=5.0,
                          pivot_pitch=0.0, pivot_yaw=0.0, n_blades=3, hub_radius=0.0,
                          blade_chord=0.1, beta_075_deg=35.0, zero_lift_angle_deg=-3.0,
                          rotation=1)
    assert len(notes) == 1 and "\n" not in notes[0]
    assert notes[0].startswith("propeller.toml: no format_version: read as format version 1")
    for text in ("[propellers.p] pivot_pitch_m = 0.0", "pivot_yaw_m = 0.0", "rotation = 1",
                 "n_blades = 3", "hub_radius_m = 0.0", "blade_chord_m = 0.1",
                 "beta_075_deg = 35.0", "zero_lift_angle_deg = -3.0", "propwhirl upgrade-model"):
        assert text in notes[0]


def test_the_format_1_examples_load_to_one_model_without_notes():
    """The examples give every value: the same model as today's example, no note."""
    (a, na), (b, nb) = _read(RELEASE), _read(WRITTEN)
    assert a == b and na == nb == []
    assert a == io.load_model(ROOT / "examples" / "wingtip.toml")


def test_a_format_1_file_relying_on_the_old_defaults_gives_the_same_model_and_analysis():
    """The first release's example without the keys whose values were version 1's defaults:
    the model and the analysis of the explicit file, and a note naming each assumed value."""
    from propwhirl.analysis import analyse

    full, _ = _read(RELEASE)
    model, notes = _read(_without(RELEASE, V1_KEYS), "wingtip.toml")
    assert model == full
    assert len(notes) == 1 and "\n" not in notes[0]
    assert notes[0].startswith("wingtip.toml: format version 1: assumed the values version 1 "
                               "gave omitted keys: [wing] elastic_axis_chord = 0.5, "
                               "centre_of_gravity_chord = 0.5; [flight] speed_of_sound_m_per_s = "
                               "330.8027446243564; [propellers.p1] ")
    for key, value in V1_KEYS.items():
        assert f"{key} = {value}" in notes[0]
    # upgraded: the current format with the assumed values written out, read without notes
    text = io.dumps(model)
    assert f"format_version = {schema.FORMAT_VERSION}\n" in text and schema.FORMAT_VERSION == 2
    upgraded, upgraded_notes = _read(text, "new.toml")
    assert upgraded == model and upgraded_notes == []
    a, b = analyse(model), analyse(upgraded)
    assert [(e.kind, e.V, e.frequency_hz) for e in a.events] == \
           [(e.kind, e.V, e.frequency_hz) for e in b.events]
    assert a.events  # the wingtip model has instabilities in 1-350 m/s


@settings(max_examples=40, deadline=None, derandomize=True)
@given(keys=st.sets(st.sampled_from(sorted(V1_KEYS)), min_size=1))
def test_any_omitted_version_1_defaults_are_assumed_and_named(keys):
    full, _ = _read(WRITTEN)
    model, notes = _read(_without(WRITTEN, keys))
    assert model == full
    assert len(notes) == 1 and "\n" not in notes[0]
    assert sorted(k for k in V1_KEYS if f" {k} = " in notes[0]) == sorted(keys)


def test_only_the_keys_that_are_used_are_assumed():
    """The blade geometry at given derivatives, the blade angles at constant speed: not used,
    so not assumed (and not named)."""
    text = (_without(WRITTEN, ["beta_075_deg", "zero_lift_angle_deg"])
            .replace('operation = "fixed-pitch"', 'operation = "constant-speed"\nrpm = 2250.0'))
    model, notes = _read(text)
    assert model.propellers[0].propeller.rpm == 2250.0 and notes == []
    text = (_without(WRITTEN, ["n_blades", "hub_radius_m", "blade_chord_m"])
            + '\n[propellers.p1.derivatives]\nsource = "measured"\nvalues = { CZ_theta = -0.5 }\n')
    model, notes = _read(text)
    assert model.propellers[0].propeller.blade_chord is None and notes == []


def test_format_version_2_still_requires_the_keys():
    text = _without(io.dumps(_read(WRITTEN)[0]), ["pivot_pitch_m"])
    with pytest.raises(InputError, match=r"^model.toml: missing key 'pivot_pitch_m' in "
                                         r"\[propellers.p1\]"):
        io.loads(text, "model.toml", notes=[])


def test_a_houbolt_reed_table_of_version_1_takes_hub_ratio_0():
    text = WRITTEN + ('\n[propellers.p1.derivatives]\nsource = "houbolt-reed"\nn_blades = 4\n'
                      'radius_m = 0.762\nchord_m = 0.1\n')
    model, notes = _read(text)
    assert model.propellers[0].propeller.derivatives.geometry.hub_ratio == 0.0
    assert "[propellers.p1.derivatives] hub_ratio = 0.0" in notes[0]


@pytest.mark.parametrize("value, message", [
    ("3", "model.toml: format_version = 3 is newer than this propwhirl reads (versions 1, 2): "
          "update propwhirl to read it"),
    ("99", "format_version = 99 is newer than this propwhirl reads"),
    ("0", "model.toml: format_version = 0 is invalid: must be one of 1, 2"),
    ("-1", "format_version = -1 is invalid: must be one of 1, 2"),
    ('"1"', "format_version = '1' is invalid: must be an integer"),
    ("true", "format_version = True is invalid: must be an integer"),
    ("1.0", "format_version = 1.0 is invalid: must be an integer"),
])
def test_unknown_format_versions_are_one_line_errors(value, message):
    text = WRITTEN.replace("format_version = 1\n", f"format_version = {value}\n")
    with pytest.raises(InputError) as exc:
        io.loads(text, "model.toml")
    assert message in str(exc.value) and "\n" not in str(exc.value)


def test_the_writer_and_the_header_state_version_2():
    text = io.dumps(_read(WRITTEN)[0])
    assert text.startswith("# propwhirl model file (propwhirl-model, format version 2)")
    assert "\nformat_version = 2\n" in text


def test_load_model_passes_the_notes(tmp_path):
    path = tmp_path / "old.toml"
    path.write_text(_without(WRITTEN, ["rotation"]))
    notes: list[str] = []
    assert io.load_model(path, notes=notes) == _read(WRITTEN)[0]
    assert len(notes) == 1 and notes[0].startswith(f"{path}: format version 1: ")
    assert io.load_model(path) == _read(WRITTEN)[0]  # without a list: the same model


def test_the_version_1_defaults_are_declared_on_fields_version_2_requires():
    """Each entry names a field of its class that a version-2 file must give (always or under
    its condition), and the values are those version 1's reader gave (git 874de5b^1)."""
    schema.check()  # the same check, as the schema runs it
    for (cls, name), value in versions.VERSION_1_DEFAULTS.items():
        f = next(f for f in schema.fields_of(cls) if f.name == name)
        assert f.required or f.required_when, (cls.__name__, name)
    keys = {f"{cls.__name__}.{name}": value
            for (cls, name), value in versions.VERSION_1_DEFAULTS.items()}
    assert keys == {"Wing.elastic_axis": 0.5, "Wing.centre_of_gravity": 0.5,
                    "FlightCondition.speed_of_sound": 330.8027446243564,
                    "Propeller.pivot_pitch": 0.0, "Propeller.pivot_yaw": 0.0,
                    "Propeller.rotation": 1, "Propeller.n_blades": 3,
                    "Propeller.hub_radius": 0.0, "Propeller.blade_chord": 0.1,
                    "Propeller.beta_075_deg": 35.0, "Propeller.zero_lift_angle_deg": -3.0,
                    "PropellerGeometry.hub_ratio": 0.0}


def test_the_documentation_lists_the_versions_and_the_version_1_values():
    doc = (ROOT / "docs" / "model-file.md").read_text()
    assert doc == schema.markdown()
    section = doc.split("## Format versions")[1].split("\n## ")[0]
    assert "propwhirl upgrade-model OLD.toml NEW.toml" in section
    for key, value in V1_KEYS.items():
        assert f"| `{key}` |" in section and f"`{value}`" in section


def test_an_old_default_on_a_field_that_is_not_required_is_caught(monkeypatch):
    from propwhirl.model.structure.wing import Wing

    monkeypatch.setattr(versions, "OLD_DEFAULTS", {1: {(Wing, "n_elements"): 20}})
    with pytest.raises(TypeError, match=r"OLD_DEFAULTS\[1\]: Wing.n_elements is not a field"):
        schema.check()
