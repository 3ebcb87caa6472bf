"""The wing on a non-uniform mesh: equivalence with the uniform mesh, element lengths and
properties at the right y, strip widths, and convergence of the Patil wing's divergence."""
from dataclasses import replace

import numpy as np
import pytest
import scipy.linalg as sl

from propwhirl.cases.ch07_patil import PATIL_DENSITY, patil_model
from propwhirl.cases.ch09_baseline import baseline_flight, baseline_propeller, baseline_wing
from propwhirl.model.structure.assembly import wing_aero, wing_structure
from propwhirl.model.systems import Installation, PropellerWing
from propwhirl.model.structure.wing import Wing
from propwhirl.validate import InputError


def dyadic_wing(**mesh) -> Wing:
    """A 4 m wing: a uniform 16-element mesh has nodes at multiples of 0.25 m, exact in binary."""
    return replace(baseline_wing(16), semi_span=4.0, **mesh)


# ----------------------------------------------------------------------------- equivalence
def test_uniform_mesh_through_stations_equals_the_n_elements_mesh_exactly():
    uniform = dyadic_wing()
    through = dyadic_wing(stations=(1.0, 2.5, 3.75))  # on the 0.25 m grid; h = 4/16 = 0.25 m
    assert not through.uniform and through.element_count == 16
    assert np.array_equal(through.node_y, uniform.node_y)
    for a, b in zip(wing_structure(through), wing_structure(uniform)):
        assert np.array_equal(a, b)
    V = np.array([30.0, 120.0])
    fa, fb = wing_aero(through, 1.2, V), wing_aero(uniform, 1.2, V)
    for key in ("Ma", "Ca", "Ka", "W0", "Ww", "Wv", "Wq"):
        assert np.array_equal(fa[key], fb[key]), key
    props = lambda w: PropellerWing(w, baseline_flight(), (  # noqa: E731
        Installation(baseline_propeller(), 1.0), Installation(baseline_propeller(), 4.0)))
    assert np.array_equal(props(through).state_matrix(V), props(uniform).state_matrix(V))


def test_a_maximum_length_of_semi_span_over_n_is_the_uniform_mesh_exactly():
    w = baseline_wing(25)  # 5.7 m
    by_length = replace(w, max_element_length=5.7 / 25)
    assert np.array_equal(by_length.node_y, w.node_y)
    V = np.array([50.0, 200.0])
    m = lambda wing: PropellerWing(wing, baseline_flight(), (  # noqa: E731
        Installation(baseline_propeller(), 5.7),))
    assert np.array_equal(m(by_length).state_matrix(V), m(w).state_matrix(V))


# ----------------------------------------------------------------------------- lengths, properties
def graded_wing() -> Wing:
    return replace(baseline_wing(), stations=(0.3, 0.45, 1.2, 2.0), max_element_length=0.4)


def test_element_lengths_and_positions_follow_the_nodes():
    w = graded_wing()
    y = w.node_y
    assert w.element_count == 16 and np.ptp(w.element_length) > 0.2  # 0.15 ... 0.4 m
    np.testing.assert_array_equal(w.element_length, np.diff(y))
    np.testing.assert_array_equal(w.element_y, 0.5 * (y[:-1] + y[1:]))
    np.testing.assert_array_equal(w.element_properties()["length"], np.diff(y))


def test_the_strip_widths_are_half_of_each_adjacent_element_and_sum_to_the_semi_span():
    w = graded_wing()
    width = w.node_properties()["width"]
    le = w.element_length
    np.testing.assert_allclose(width, np.r_[le / 2, 0] + np.r_[0, le / 2], rtol=0, atol=0)
    assert width.sum() == pytest.approx(w.semi_span, rel=1e-14)


def test_node_and_element_properties_are_evaluated_at_their_own_y():
    w = replace(graded_wing(), tip_chord=0.5)
    node = w.node_properties()
    np.testing.assert_allclose(node["y"], w.node_y)
    np.testing.assert_allclose(2 * node["b"], 1.25 + (0.5 - 1.25) * w.node_y / 5.7, rtol=1e-14)
    el = replace(w, EI=lambda y: 7e5 * (1 + y)).element_properties()
    np.testing.assert_allclose(el["EI"], 7e5 * (1 + w.element_y), rtol=1e-14)


def test_a_property_step_at_a_station_is_integrated_exactly():
    """With the step at a station every element lies on one side: the wing's mass is exact."""
    step = lambda y: np.where(y < 1.2, 40.0, 25.0)  # noqa: E731
    at_station = replace(graded_wing(), mass_per_length=step)
    el = at_station.element_properties()
    assert np.sum(el["m"] * el["length"]) == pytest.approx(40.0 * 1.2 + 25.0 * 4.5, rel=1e-13)
    off = replace(baseline_wing(8), mass_per_length=step)  # nodes every 0.7125 m: 1.2 inside
    el = off.element_properties()
    assert abs(np.sum(el["m"] * el["length"]) - (40.0 * 1.2 + 25.0 * 4.5)) > 1.0


def test_a_per_element_array_has_one_value_per_element_of_the_mesh():
    w = graded_wing()
    ok = replace(w, EI=np.full(16, 7e5))
    assert ok.element_properties()["EI"].shape == (16,)
    with pytest.raises(InputError, match="EI has 20 values but the wing has 16 elements"):
        replace(w, EI=np.full(20, 7e5))


def test_an_empty_station_list_is_no_stations():
    w = replace(baseline_wing(25), stations=[])
    assert w.stations is None and w.uniform
    assert np.array_equal(w.node_y, baseline_wing(25).node_y)


# ----------------------------------------------------------------------------- errors
@pytest.mark.parametrize("changes, words", [
    (dict(stations=(6.0,)), "stations[0] = 6.0 m is outside the wing: must be in (0, 5.7] m"),
    (dict(stations=(0.0,)), "stations[0] = 0.0 m is outside the valid range (0, 1000] m"),
    (dict(stations=(1.0, 1.0)), "stations[1] = 1.0 m is invalid: a duplicate of stations[0]"),
    (dict(stations=(1.0, 1.003)), "shorter than the minimum 0.0057 m (0.001 x semi_span)"),
    (dict(max_element_length=-0.2), "max_element_length = -0.2 m is outside the valid range [1e-4, 1000] m"),
    (dict(max_element_length=0.0), "max_element_length = 0.0 m is outside the valid range"),
    (dict(max_element_length=0.001), "max_element_length = 0.001 m gives 5,700 elements"),
    (dict(stations=[1.0, "2"]), "stations[1]"),
])
def test_bad_mesh_settings_are_one_line_errors(changes, words):
    with pytest.raises(InputError) as exc:
        replace(baseline_wing(), **changes)
    assert words in str(exc.value) and "\n" not in str(exc.value)


# ----------------------------------------------------------------------------- Patil divergence
def static_divergence_speed(model: PropellerWing) -> float:
    """The static divergence speed [m/s] of a wing model from its steady limit.

    At rest (q̇ = 0, ẇ = 0) the lag states are w = −Ww⁻¹ Wq q and the stiffness is
    K(V) = S3 + S4 Ww⁻¹ Wq = K_s − V² A (steady strip theory, checked at a second speed);
    divergence is the lowest V with K(V) singular: V² the least positive eigenvalue of
    K_s x = V² A x."""
    def stiffness(V: float) -> np.ndarray:
        s = model.second_order(np.array([V]))
        return s.S3[0] + s.S4[0] @ np.linalg.solve(s.Ww[0], s.Wq[0])

    Ks = model.without_aerodynamics().second_order(np.array([1.0])).S3[0]
    A = Ks - stiffness(1.0)
    np.testing.assert_allclose(stiffness(3.0), Ks - 9.0 * A, rtol=0, atol=1e-9 * np.abs(Ks).max())
    lam = sl.eigvals(Ks, A)
    lam = lam[np.isfinite(lam) & (np.abs(lam.imag) <= 1e-9 * np.abs(lam)) & (lam.real > 0)]
    return float(np.sqrt(lam.real.min()))


def test_non_uniform_patil_divergence_converges_to_the_closed_form():
    """q_D = (π/2L)² GJ / (e c C_lα) (37.15 m/s, as tests/model/test_systems.py).  Nodal strips
    integrate the torsion load by the trapezoidal rule: the error falls as h² (measured on
    stations 1.1, 2.7, 7.3 m: −2.35e-4, −6.5e-5, −2.1e-5 at h = 1, 0.5, 0.25 m; the uniform
    20- and 40-element meshes: −2.6e-4, −6.4e-5)."""
    e, c, GJ, L = 0.25, 1.0, 1e4, 16.0
    VD = np.sqrt(2 * (np.pi / (2 * L)) ** 2 * GJ / (e * c * 2 * np.pi) / PATIL_DENSITY)
    base = patil_model()
    errors = []
    for h in (1.0, 0.5, 0.25):
        wing = replace(base.wing, stations=(1.1, 2.7, 7.3), max_element_length=h)
        assert np.ptp(wing.element_length) > 0.05 * h  # non-uniform
        errors.append(abs(static_divergence_speed(replace(base, wing=wing)) - VD) / VD)
    assert errors[0] / errors[1] > 2.5 and errors[1] / errors[2] > 2.5  # second order
    assert errors[2] < 5e-5


def test_the_static_divergence_of_the_uniform_mesh_is_the_dynamic_one():
    """The static computation above agrees with the analysed divergence bracket of the
    20-element Patil wing (a check of the helper itself)."""
    model = patil_model()
    VD = static_divergence_speed(model)
    lam = np.linalg.eigvals(model.state_matrix(np.array([0.999 * VD, 1.001 * VD])))
    real = lambda row: row[np.abs(row.imag) < 1e-9].real  # noqa: E731
    assert real(lam[0]).max() < 0 < real(lam[1]).max()
