"""Model files with mesh settings (stations_m, max_element_length_m): the issue-10 design wing
analysed from a file without n_elements; files without the keys read as before."""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from propwhirl import io
from propwhirl.app import cli
from propwhirl.cases import registry
from propwhirl.validate import InputError

ROOT = Path(__file__).resolve().parents[2]

#: The done-when case of issue 10, as a user writes it: five propellers at the layout's
#: stations on a 4.8 m wing, a maximum element length, no n_elements.
DESIGN = """\
format = "propwhirl-model"
format_version = 1
type = "propeller-wing"
name = "distributed propulsion, five propellers"
installations = [
    { propeller = "p1", y_m = 0.95 },
    { propeller = "p1", y_m = 1.5 },
    { propeller = "p1", y_m = 2.05 },
    { propeller = "p1", y_m = 3.1 },
    { propeller = "p1", y_m = 4.8 },
]

[wing]
semi_span_m = 4.8
mass_per_length_kg_per_m = 25.0
EI_N_m2 = 700000.0
GJ_N_m2 = 200000.0
root_chord_m = 1.25
tip_chord_m = 0.8
radius_of_gyration_chord = 0.25
elastic_axis_chord = 0.5
centre_of_gravity_chord = 0.5
max_element_length_m = 0.2

[flight]
density_kg_per_m3 = 0.96287
speed_of_sound_m_per_s = 330.8

[propellers.p1]
radius_m = 0.762
masses = [{ mass_kg = 35.0, x_m = -0.86 }]
rotor = { mass_kg = 8.0, x_m = -1.16 }
pivot_pitch_m = 0.0
pivot_yaw_m = 0.0
f_theta_hz = 7.0
f_psi_hz = 7.0
damping_theta = 0.005
damping_psi = 0.005
n_blades = 3
hub_radius_m = 0.125
blade_chord_m = 0.094
beta_075_deg = 35.0
zero_lift_angle_deg = -3.0
rotation = 1
"""
Y = (0.95, 1.5, 2.05, 3.1, 4.8)


def _error(text: str) -> str:
    with pytest.raises(InputError) as exc:
        io.loads(text, "model.toml")
    msg = str(exc.value)
    assert msg.startswith("model.toml: ") and "\n" not in msg
    return msg


def test_the_design_wing_is_read_with_every_propeller_on_a_node():
    assert "n_elements" not in DESIGN and "stations" not in DESIGN
    m = io.loads(DESIGN)
    assert m.wing.max_element_length == 0.2 and m.wing.element_length.max() <= 0.2
    np.testing.assert_array_equal(m.wing.node_y[list(m.nodes)], Y)
    assert m.wing.element_count == 26


def test_the_design_wing_is_analysed_from_its_file(tmp_path, capsys):
    path = tmp_path / "design.toml"
    path.write_text(DESIGN, encoding="utf-8")
    assert cli.main(["analyse", str(path), "--json", str(tmp_path / "a.json")]) == 0
    out = capsys.readouterr().out
    assert "critical" in out
    from propwhirl.analysis.stability import load

    saved = load(tmp_path / "a.json")
    assert saved.dof_map.node_y == tuple(io.loads(DESIGN).wing.node_y)
    assert [p.y for p in saved.dof_map.propellers] == list(Y)


def test_mesh_settings_round_trip():
    m = io.loads(DESIGN)
    text = io.dumps(m)
    assert "stations_m = [" in text and "max_element_length_m = 0.2" in text
    back = io.loads(text)
    assert back.wing == m.wing and back.wing.stations == Y
    np.testing.assert_array_equal(back.wing.node_y, m.wing.node_y)
    V = np.array([50.0, 180.0])
    np.testing.assert_array_equal(back.state_matrix(V), m.state_matrix(V))


def test_a_file_without_the_mesh_keys_reads_exactly_as_before():
    text = (ROOT / "examples" / "wingtip.toml").read_text(encoding="utf-8")
    assert "stations_m" not in text and "max_element_length_m" not in text
    m = io.loads(text)
    assert m.wing.stations is None and m.wing.max_element_length is None and m.wing.uniform
    assert np.array_equal(m.wing.node_y, np.linspace(0.0, m.wing.semi_span, m.wing.n_elements + 1))
    V = np.array([10.0, 200.0])
    np.testing.assert_array_equal(m.state_matrix(V), registry.case_model("wingtip").state_matrix(V))
    assert "stations_m" not in io.dumps(m) and "max_element_length_m" not in io.dumps(m)


@pytest.mark.parametrize("line, words", [
    ("stations_m = [1.0, 6.0]", "[wing] stations_m[1] = 6.0 is outside the wing: must be in (0, 4.8] m"),
    ("stations_m = []", "[wing] stations_m = [] is invalid: must be a list of one or more numbers"),
    ("stations_m = [1.0, 1.0]", "[wing] stations_m[1] = 1.0 is invalid: a duplicate of stations_m[0]"),
    ("stations_m = [2.0, 2.001]", "[wing] stations_m[1] = 2.001 is invalid: it makes an element of 0.001 m"),
    ("stations_m = 1.0", "[wing] stations_m = 1.0 is invalid: must be a list of one or more numbers"),
])
def test_bad_stations_in_a_file_name_the_key(line, words):
    msg = _error(DESIGN.replace("max_element_length_m = 0.2", line))
    assert words in msg


@pytest.mark.parametrize("value, words", [
    ("0.0", "[wing] max_element_length_m = 0.0 is outside the valid range [1e-4, 1000] m"),
    ("-0.2", "[wing] max_element_length_m = -0.2 is outside the valid range"),
    ("0.001", "max_element_length_m = 0.001 m gives 4,800 elements"),
])
def test_a_bad_maximum_length_in_a_file_is_one_line(value, words):
    msg = _error(DESIGN.replace("max_element_length_m = 0.2", f"max_element_length_m = {value}"))
    assert words in msg


def test_an_installation_outside_the_wing_names_it_in_the_file():
    msg = _error(DESIGN.replace("y_m = 3.1", "y_m = 5.1"))
    assert "[installations[3]] y_m = 5.1 is outside the wing" in msg
    msg = _error(DESIGN.replace("y_m = 3.1", "y_m = 0.0"))
    assert "[installations[3]] y_m = 0.0 is the clamped root" in msg
