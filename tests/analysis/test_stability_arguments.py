"""analyse() and campbell() arguments: every bad one is a one-line InputError naming it."""
from __future__ import annotations

import warnings

import numpy as np
import pytest

from propwhirl.analysis.stability import analyse
from propwhirl.analysis.vibration import campbell
from propwhirl.cases.ch09_baseline import isolated_baseline_propeller
from propwhirl.engine import analyse as engine_analyse, sweep
from propwhirl.validate import InputError


@pytest.fixture(scope="module")
def prop():
    return isolated_baseline_propeller()


BAD_SPEEDS = {
    "empty": ([], "at least 2 values, got shape .0,."),
    "scalar": (5.0, "at least 2 values, got shape ..:"),
    "2-D": (np.ones((2, 3)) * [[1, 2, 3]], r"got shape .2, 3."),
    "nan": ([1.0, np.nan], "speeds = nan m/s is invalid: must be finite"),
    "inf": ([1.0, np.inf], "speeds = inf m/s is invalid: must be finite"),
    "decreasing": ([10.0, 5.0], r"strictly increasing, but speeds\[1\] = 5.0"),
    "repeated": ([10.0, 10.0], "strictly increasing"),
    "zero": ([0.0, 10.0], r"speeds\[0\] = 0.0 m/s is invalid: must be > 0"),
    "negative": ([-1.0, 5.0], r"speeds\[0\] = -1.0 m/s"),
    "strings": (["a", "b"], "speeds = .'a', 'b'. is invalid: must be an increasing 1-D array"),
    "string": ("1 2", "speeds = '1 2' is invalid"),
    "complex": ([1 + 2j, 3.0], "speeds = .* is invalid: must be an increasing"),
    "complex-array": (np.array([1 + 2j, 3.0]), "speeds = .* is invalid"),
    "bools": ([True, False], "speeds = .True, False. is invalid"),
    "ragged": ([[1, 2], [3]], "speeds = .* is invalid"),
    "dict": ({1: 2}, "speeds = .1: 2. is invalid"),
    "none-inside": ([1.0, None], "speeds = .* is invalid"),
    "too-many": (np.arange(1.0, 200_002.0), "speeds gives 200,001 speeds: must be at most "
                                            "100,000"),
}


@pytest.mark.parametrize("speeds, match", BAD_SPEEDS.values(), ids=BAD_SPEEDS.keys())
def test_bad_speeds_are_one_line_input_errors(prop, speeds, match):
    with warnings.catch_warnings():
        warnings.simplefilter("error")           # no ComplexWarning, no RuntimeWarning
        for call in (lambda: analyse(prop, speeds), lambda: sweep(prop.state_matrix, speeds),
                     lambda: engine_analyse(prop.state_matrix, speeds)):
            with pytest.raises(InputError, match=match) as exc:
                call()
            msg = str(exc.value)
            assert "\n" not in msg and "speeds" in msg
            assert "increasing 1-D array" in msg or "> 0" in msg or "at most" in msg


def test_other_analyse_arguments(prop):
    with pytest.raises(InputError, match="model = 'wing' is invalid: must be a model"):
        analyse("wing", [1.0, 2.0])
    with pytest.raises(InputError, match="vgf = 'yes' is invalid"):
        analyse(prop, [100.0, 200.0], vgf="yes")
    with pytest.raises(InputError, match="options = .* is invalid: must be a TrackingOptions"):
        analyse(prop, [100.0, 200.0], options={"mac_min": 0.5})
    with pytest.raises(InputError, match="xtol"):
        analyse(prop, [100.0, 200.0], xtol=float("nan"))
    a = analyse(prop, (100, 200, 250))                   # integers and tuples are fine
    assert a.critical is not None


@pytest.fixture(scope="module")
def tip_model():
    from propwhirl.cases.ch09_baseline import baseline_flight, baseline_propeller, baseline_wing
    from propwhirl.model.systems import Installation, PropellerWing

    return PropellerWing(baseline_wing(5), baseline_flight(),
                         (Installation(baseline_propeller(), 5.7),))


@pytest.mark.parametrize("rpm, match", [
    ([0.0, 1e300], r"rpm = 1e\+300 rev/min is outside the valid range \[0, 1e5\] rev/min"),
    ([0.0, np.inf], "rpm = inf rev/min is invalid: must be finite"),
    ([0.0, np.nan], "must be finite"),
    ([-1.0, 10.0], "rpm = -1.0 rev/min"),
    ([10.0, 5.0], "strictly increasing"),
    ([], "at least 1 value"),
    (np.ones((2, 2)), r"1-D array .* got shape \(2, 2\)"),
    ("fast", "rpm = 'fast' is invalid: must be an increasing 1-D array"),
    ([1 + 1j], "rpm = .* is invalid"),
    (True, "rpm = True is invalid"),
])
def test_bad_campbell_rpm(tip_model, rpm, match):
    with pytest.raises(InputError, match=match):
        campbell(tip_model, rpm)


def test_campbell_at_the_rpm_bound_is_finite_and_not_zero(tip_model):
    c = campbell(tip_model, [0.0, 50_000.0, 100_000.0], max_frequency_hz=20.0)
    assert np.isfinite(c.frequency_hz).all() and (c.frequency_hz > 0).all()
