"""Propeller model: inertia, stiffness, damping readings, operation, bad input."""
import numpy as np
import pytest

from propwhirl.cases.ch09_baseline import baseline_propeller
from propwhirl.model.propellers.propeller import MeasuredDerivatives, PointMass
from propwhirl.validate import InputError


def test_stiffness_from_frequency_and_damping_readings():
    p = baseline_propeller()
    Kt, Kp = p.stiffness()
    assert Kt == pytest.approx((8 * 1.16**2 + 35 * 0.86**2) * (2 * np.pi * 7) ** 2)
    assert p.viscous_damping_ratios() == (0.0025, 0.0025)          # g = 2ζ (6.4)
    assert baseline_propeller(damping="zeta").viscous_damping_ratios() == (0.005, 0.005)
    assert baseline_propeller(K_theta=1e4, f_theta=None).stiffness()[0] == 1e4


def test_advance_ratio_rules():
    # eq. 9.1 as the thesis uses it: J = π tan(β − 3°) = 1.96 at 35° (Table 9.3)
    assert np.pi * baseline_propeller().advance_ratio == pytest.approx(1.963, abs=1e-3)
    # Table 9.5: 221 m/s at 4433 RPM
    rpm = baseline_propeller().rotational_speed(np.array([221.0]))[0] * 60 / (2 * np.pi)
    assert rpm == pytest.approx(4433, rel=2e-3)
    be = baseline_propeller(advance_rule="blade_element").advance_ratio
    assert be == pytest.approx(0.75 * np.tan(np.radians(38.0)))


def test_constant_speed_rotation():
    p = baseline_propeller(operation="constant-speed", rpm=2250.0)
    np.testing.assert_allclose(p.rotational_speed(np.array([50.0, 300.0])), 2250 * 2 * np.pi / 60)


def test_inertia_override_and_spin_inertia():
    p = baseline_propeller(inertia={"I_theta_P": 2.0, "I_psi_P": 3.0}, spin_inertia=0.5)
    i = p.pivot_inertia()
    assert (i["I_theta_P"], i["I_psi_P"], p.I_Omega) == (2.0, 3.0, 0.5)
    assert i["S_theta_P"] == pytest.approx(-39.38)  # not overridden: from the point masses
    assert baseline_propeller().I_Omega == pytest.approx(8 * 0.762**2 / 3)


def test_measured_derivatives_subset_rest_zero():
    d = MeasuredDerivatives({"CZ_theta": -0.3, "Cm_q": -0.1})(np.array([10.0, 20.0]), None, 340.0)
    assert len(d) == 16 and np.all(d["CZ_theta"] == -0.3) and np.all(d["CY_psi"] == 0.0)
    with pytest.raises(InputError, match="CZ_thta"):
        MeasuredDerivatives({"CZ_thta": 1.0})


@pytest.mark.parametrize(
    "change, words",
    [
        ({"n_blades": 2}, ["n_blades = 2 ", "[3, 20]"]),
        ({"radius": 0.0}, ["radius = 0.0 m", "valid range [0.01, 20] m"]),
        ({"hub_radius": 0.9}, ["hub_radius", "0.9"]),
        ({"f_theta": -1.0}, ["f_theta", "-1.0", "[1e-3, 1000] Hz"]),
        ({"K_theta": 1e4}, ["exactly one of f_theta"]),
        ({"damping_psi": -0.1}, ["damping_psi", "[0, 2]"]),
        ({"damping": "hysteretic"}, ["damping", "hysteretic"]),
        ({"operation": "constant-speed"}, ["rpm is required"]),
        ({"operation": "constant-speed", "rpm": -5.0}, ["rpm", "-5.0"]),
        ({"operation": "windmill"}, ["operation", "windmill"]),
        ({"beta_075_deg": 2.0}, ["beta_075_deg = 2.0 deg", "inflow angle"]),
        ({"rotation": 0}, ["rotation", "+1 or -1"]),
        ({"inertia": {"I_x": 1.0}}, ["inertia", "unknown entry", "I_x"]),
        ({"inertia": {"I_theta_P": -1.0}}, ["I_theta_P", "-1.0 kg m^2", "[1e-8, 1e9]"]),
        ({"pivot_pitch": np.inf}, ["pivot_pitch", "finite"]),
        ({"blade_chord": None}, ["missing blade_chord", "Houbolt-Reed"]),
    ],
)
def test_bad_propeller_input(change, words):
    with pytest.raises(InputError) as exc:
        baseline_propeller(**change)
    for w in words:
        assert w in str(exc.value)


def test_point_mass_validation():
    with pytest.raises(InputError, match=r"mass = 0.0 kg is outside the valid range \[1e-4, 1e5\]"):
        PointMass(0.0, 1.0)
