"""derivative_arrays: the sixteen derivatives of derivatives(), with its checks."""
import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from propwhirl.model import propeller_aero as aero
from propwhirl.model.propeller_aero import AeroSettings, PropellerGeometry
from propwhirl.validate import InputError

GEO = PropellerGeometry(n_blades=3, radius=1.2, hub_ratio=0.2, chord=0.15)


@settings(max_examples=25, deadline=None)
@given(st.lists(st.floats(5.0, 250.0), min_size=1, max_size=5), st.floats(50.0, 400.0),
       st.sampled_from(["houbolt_reed", "bennett_bland"]), st.booleans())
def test_the_same_numbers_as_derivatives(V, omega, method, wake):
    s = AeroSettings(method=method, wake=wake)
    V = np.array(V)
    full = aero.derivatives(GEO, V, omega, speed_of_sound=320.0, settings=s).derivatives()
    arrays = aero.derivative_arrays(GEO, V, omega, 320.0, s)
    assert list(arrays) == list(full)
    for name in full:
        assert arrays[name].shape == V.shape
        assert np.array_equal(arrays[name], full[name]), name


def test_the_same_refusals():
    with pytest.raises(InputError, match="airspeed"):
        aero.derivative_arrays(GEO, np.array([-1.0]), 100.0, 320.0)
    with pytest.raises(InputError, match="speed_of_sound"):
        aero.derivative_arrays(GEO, np.array([100.0]), 100.0, None)
    with pytest.raises(InputError, match="Mach"):
        aero.derivative_arrays(GEO, np.array([2000.0]), 100.0, 320.0)
