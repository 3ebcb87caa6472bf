"""Bad wing input raises InputError naming parameter, value and valid range."""
import numpy as np
import pytest

from propwhirl.cases.ch09_baseline import baseline_wing
from propwhirl.validate import InputError
from propwhirl.model.structure.wing import Wing

BASE = dict(semi_span=5.0, mass_per_length=10.0, EI=1e5, GJ=1e5, polar_inertia=1.0, n_elements=4)


@pytest.mark.parametrize(
    "change, words",
    [
        ({"semi_span": 0.0}, ["semi_span", "0.0", "[0.01, 1000] m"]),
        ({"semi_span": -2.0}, ["semi_span", "-2.0"]),
        ({"mass_per_length": -1.0}, ["mass_per_length", "-1.0", "[1e-4, 1e5] kg/m"]),
        ({"EI": 0.0}, ["EI = 0.0 N m^2 is outside the valid range [1e-3, 1e12] N m^2"]),
        ({"GJ": np.nan}, ["GJ", "finite"]),
        ({"root_chord": 0.0}, ["root_chord", "[1e-3, 100] m"]),
        ({"n_elements": 0}, ["n_elements", ">= 1"]),
        ({"n_elements": 2.5}, ["n_elements", "integer"]),
        ({"elastic_axis": 1.2}, ["elastic_axis", "1.2", "[0, 1]"]),
        ({"centre_of_gravity": -0.1}, ["centre_of_gravity", "-0.1"]),
        ({"mass_per_length": [1.0, 2.0]}, ["mass_per_length", "2 values", "n_elements = 4"]),
        ({"aero_model": "doublet"}, ["aero_model", "doublet"]),
        ({"lift_slope": "flat"}, ["lift_slope", "flat"]),
        ({"rayleigh": (-1.0, 0.0)}, ["rayleigh[0] = -1.0 1/s", "[0, 1000] 1/s"]),
    ],
)
def test_bad_input_names_parameter_value_and_range(change, words):
    with pytest.raises(InputError) as exc:
        Wing(**{**BASE, **change})
    for w in words:
        assert w in str(exc.value)


def test_exactly_one_inertia_definition():
    with pytest.raises(InputError, match="exactly one"):
        Wing(**{**BASE, "radius_of_gyration": 0.25})


def test_per_element_and_callable_properties():
    w = Wing(**{**BASE, "mass_per_length": [1.0, 2.0, 3.0, 4.0], "EI": lambda y: 1e5 * (1 - 0.1 * y)})
    p = w.element_properties()
    np.testing.assert_array_equal(p["m"], [1.0, 2.0, 3.0, 4.0])
    np.testing.assert_allclose(p["EI"], 1e5 * (1 - 0.1 * w.element_y))


def test_baseline_wing_properties():
    w = baseline_wing()
    p = w.element_properties()
    c = 1.25 + (0.8 - 1.25) * w.element_y / 5.7
    np.testing.assert_allclose(p["rho_Ip"], 25.0 * (0.25 * c) ** 2)
    nodes = w.node_properties()
    assert np.isclose(nodes["width"].sum(), 5.7)
    np.testing.assert_allclose(nodes["ac"], -0.5)
    np.testing.assert_allclose(nodes["a"], 0.0)
