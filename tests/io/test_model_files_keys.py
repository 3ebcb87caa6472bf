"""Model-file errors name the file, the table and the key as the user wrote it (issue 9,
items 1, 4 and 9): constructor errors restated with the file's keys, missing keys with their
meaning, unit and range, the installation by its index, no silent blade chord."""
from __future__ import annotations

from pathlib import Path

import pytest

from propwhirl import io
from propwhirl.cases.ch10_other_wings import two_propeller_wing
from propwhirl.validate import InputError

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = (ROOT / "examples" / "wingtip.toml").read_text()


def _error(text: str, source: str = "model.toml") -> str:
    with pytest.raises(InputError) as exc:
        io.loads(text, source)
    msg = str(exc.value)
    assert msg.startswith(f"{source}: ") and "\n" not in msg
    return msg


@pytest.mark.parametrize("old, new, message", [
    # item 1: huge values refused on reading, with the key and the range
    ("EI_N_m2 = 700000.0", "EI_N_m2 = 1e300",
     "model.toml: [wing] EI_N_m2 = 1e+300 is outside the valid range [1e-3, 1e12] N m^2 "
     "(bending rigidity)"),
    ("GJ_N_m2 = 200000.0", "GJ_N_m2 = 1e300",
     "[wing] GJ_N_m2 = 1e+300 is outside the valid range [1e-3, 1e12] N m^2"),
    ("rayleigh_mu_per_s = 0.0", "rayleigh_mu_per_s = 1e300",
     "[wing] rayleigh_mu_per_s = 1e+300 is outside the valid range [0, 1000] 1/s"),
    ("damping_theta = 0.005", "damping_theta = 1e300",
     "[propellers.p1] damping_theta = 1e+300 is outside the valid range [0, 2]"),
    ("damping_psi = 0.005", "damping_psi = 1e300",
     "[propellers.p1] damping_psi = 1e+300 is outside the valid range [0, 2]"),
    ("hub_radius_m = 0.125", "hub_radius_m = 0.125\nspin_inertia_kg_m2 = 1e300",
     "[propellers.p1] spin_inertia_kg_m2 = 1e+300 is outside the valid range [0, 1e6] kg m^2"),
    ("f_theta_hz = 7.0", "f_theta_hz = 1e300",
     "[propellers.p1] f_theta_hz = 1e+300 is outside the valid range [1e-3, 1000] Hz"),
    ("f_psi_hz = 7.0", "f_psi_hz = 1e300",
     "[propellers.p1] f_psi_hz = 1e+300 is outside the valid range [1e-3, 1000] Hz"),
    ("radius_m = 0.762", "radius_m = 1e300",
     "[propellers.p1] radius_m = 1e+300 is outside the valid range [0.01, 20] m"),
    ("mass_kg = 8.0", "mass_kg = 1e300",
     "[propellers.p1.rotor] mass_kg = 1e+300 is outside the valid range [1e-4, 1e5] kg"),
    ("density_kg_per_m3 = 0.96287", "density_kg_per_m3 = 1e300",
     "[flight] density_kg_per_m3 = 1e+300 is outside the valid range [1e-4, 10] kg/m^3"),
    ("n_blades = 3", "n_blades = 100", "[propellers.p1] n_blades = 100 is outside the valid range"),
    ("EI_N_m2 = 700000.0", "EI_N_m2 = " + str([7e5] * 24 + [1e300]),
     "[wing] EI_N_m2[24] = 1e+300 is outside the valid range [1e-3, 1e12] N m^2"),
    # item 9: semi_span refused by its range before any propeller-position check
    ("semi_span_m = 5.7", "semi_span_m = 1e300",
     "model.toml: [wing] semi_span_m = 1e+300 is outside the valid range [0.01, 1000] m"),
    # item 9: a negative blade chord at load time, naming file and table
    ("blade_chord_m = 0.094", "blade_chord_m = -1.0",
     "model.toml: [propellers.p1] blade_chord_m = -1.0 is outside the valid range [1e-3, 5] m"),
    # item 9: the key as written, not the Python name
    ("beta_075_deg = 35.0", "beta_075_deg = 2.0",
     "[propellers.p1] beta_075_deg = 2.0 is invalid: the inflow angle"),
    ("hub_radius_m = 0.125", "hub_radius_m = 0.9",
     "[propellers.p1] hub_radius_m = 0.9 is invalid: must be < radius_m = 0.762 m"),
    ("f_theta_hz = 7.0", "f_theta_hz = 7.0\nK_theta_N_m_per_rad = 1.0",
     "[propellers.p1]: give exactly one of f_theta_hz [Hz] or K_theta_N_m_per_rad [N m/rad]"),
    ("rotation = 1\n", "rotation = 1\ninertia = { I_theta_P_kg_m2 = -1.0 }\n",
     "[propellers.p1.inertia] I_theta_P_kg_m2 = -1.0 is outside the valid range [1e-8, 1e9]"),
    ("cutoff_lift_slope_per_rad = 12.566370614359172", "cutoff_lift_slope_per_rad = 6.0",
     "[propellers.p1.aero_settings] cutoff_lift_slope_per_rad = 6.0 is outside the valid range "
     "(6.28319, 1000] 1/rad"),
    ("    1.0,\n    350.0,", "    1.0,\n    1e300,",
     "[flight] speed_range_m_per_s[1] = 1e+300 is outside the valid range (0, 10000] m/s"),
])
def test_constructor_errors_name_the_table_and_the_key(old, new, message):
    assert old in EXAMPLE
    assert message in _error(EXAMPLE.replace(old, new, 1))


def test_missing_type_names_the_choices():
    msg = _error(EXAMPLE.replace('type = "propeller-wing"\n', ""))
    assert msg == ('model.toml: missing key \'type\' at the top level (one of "propeller-wing", '
                   '"isolated-propeller", "propeller")')
    assert "None" not in msg


@pytest.mark.parametrize("key", ["blade_chord_m", "n_blades", "hub_radius_m", "beta_075_deg",
                                 "zero_lift_angle_deg", "pivot_pitch_m", "pivot_yaw_m",
                                 "rotation"])
def test_aircraft_values_without_a_physical_default_are_required(key):
    lines = [ln for ln in EXAMPLE.splitlines(keepends=True) if not ln.startswith(f"{key} = ")]
    assert len(lines) == len(EXAMPLE.splitlines()) - 1
    msg = _error("".join(lines))
    assert f"missing key {key!r} in [propellers.p1] (" in msg


def test_missing_blade_chord_is_an_error_with_its_meaning_unit_and_range():
    """Issue 9, item 4: it silently became 0.1 m (critical speed 142.87 instead of 143.15)."""
    msg = _error(EXAMPLE.replace("blade_chord_m = 0.094\n", ""))
    assert msg.startswith("model.toml: missing key 'blade_chord_m' in [propellers.p1] (blade chord")
    assert "; m; valid range [1e-3, 5] m" in msg and "[propellers.p1.blade_chord]" in msg


@pytest.mark.parametrize("old, new, key", [
    ("elastic_axis_chord = 0.5\n", "", "elastic_axis_chord"),
    ("centre_of_gravity_chord = 0.5\n", "", "centre_of_gravity_chord"),
])
def test_wing_positions_are_required(old, new, key):
    msg = _error(EXAMPLE.replace(old, new, 1))
    assert f"missing key {key!r} in [wing] (" in msg and "valid range [0, 1]" in msg


def test_speed_of_sound_is_required():
    text = EXAMPLE.replace("speed_of_sound_m_per_s = 330.8027446243564\n", "")
    msg = _error(text)
    assert "missing key 'speed_of_sound_m_per_s' in [flight] (speed of sound" in msg
    assert "valid range [100, 1000] m/s" in msg


def test_blade_geometry_is_not_required_with_given_derivatives():
    text = (EXAMPLE.replace("blade_chord_m = 0.094\n", "").replace("n_blades = 3\n", "")
            .replace("hub_radius_m = 0.125\n", "")
            + '\n[propellers.p1.derivatives]\nsource = "measured"\nvalues = { CZ_theta = -0.5 }\n')
    model = io.loads(text)
    assert model.propellers[0].propeller.blade_chord is None


def test_blade_angles_are_not_required_at_constant_speed():
    text = (EXAMPLE.replace("beta_075_deg = 35.0\n", "").replace("zero_lift_angle_deg = -3.0\n", "")
            .replace('operation = "fixed-pitch"', 'operation = "constant-speed"\nrpm = 2250.0'))
    assert io.loads(text).propellers[0].propeller.rpm == 2250.0


def _two_propeller_text() -> str:
    return io.dumps(two_propeller_wing())


def test_an_installation_error_names_the_installation():
    text = _two_propeller_text()
    tip = text.split("installations = [")[1].split("]")[0]
    assert tip.count("y_m =") == 2
    second_y = tip.split("y_m = ")[2].split(",")[0]
    msg = _error(text.replace(f"y_m = {second_y}", "y_m = 6.0", 1))
    assert "model.toml: [installations[1]] y_m = 6.0 is outside the wing" in msg
    first_y = tip.split("y_m = ")[1].split(",")[0]
    msg = _error(text.replace(f"y_m = {second_y}", f"y_m = {first_y}", 1))
    assert f"[installations[1]] y_m = {first_y} is invalid: two propellers at node" in msg
    msg = _error(text.replace(f"y_m = {second_y}", "y_m = 0.0", 1))
    assert "[installations[1]] y_m = 0.0 is the clamped root" in msg


def test_the_file_name_leads_every_message(tmp_path):
    path = tmp_path / "bad.toml"
    path.write_text(EXAMPLE.replace("blade_chord_m = 0.094", "blade_chord_m = -1.0"),
                    encoding="utf-8")
    with pytest.raises(InputError) as exc:
        io.load_model(path)
    assert str(exc.value).startswith(f"{path}: [propellers.p1] blade_chord_m = -1.0 is outside")


def test_a_tabulated_chord_value_is_named_in_its_table():
    text = EXAMPLE.replace("blade_chord_m = 0.094",
                           "blade_chord = { eta = [0.0, 1.0], chord_m = [0.1, 50.0] }")
    msg = _error(text)
    assert "[propellers.p1.blade_chord] chord_m[1] = 50.0 is outside the valid range [1e-3, 5] m" in msg
