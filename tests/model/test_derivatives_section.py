"""propwhirl.model.derivatives_section: the chain rule from chord, taper, centre of gravity,
elastic axis, aerodynamic centre and section inertia to the element, node and propeller blocks,
against central finite differences of ``second_order`` of the model with the field changed."""
import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from helpers.derivative_checks import assert_matches_central_differences
from propwhirl.cases.registry import case_model
from propwhirl.model import derivatives as D
from propwhirl.model import derivatives_section as S
from propwhirl.model.propellers.propeller import MeasuredDerivatives, PointMass, Propeller
from propwhirl.model.propellers.propeller_aero import DERIVATIVE_NAMES
from propwhirl.model.systems import FlightCondition, Installation, PropellerWing
from propwhirl.model.structure.wing import Wing

V = np.array([40.0, 95.0])


def random_model(data) -> PropellerWing:
    """A small wing (3–5 elements; tapered or not; centre of gravity, elastic axis and
    aerodynamic centre uniform or one value per element; radius of gyration or polar inertia;
    either strip-aerodynamics model, or none) with one or two propellers (measured
    derivatives; flexible or rigid) at nodes."""
    u = lambda lo, hi: data.draw(st.floats(lo, hi))  # noqa: E731
    n = data.draw(st.integers(3, 5))
    per_element = lambda lo, hi: (np.array([u(lo, hi) for _ in range(n)])  # noqa: E731
                                  if data.draw(st.booleans()) else u(lo, hi))
    inertia = (dict(radius_of_gyration=per_element(0.2, 0.3)) if data.draw(st.booleans())
               else dict(polar_inertia=per_element(1.0, 3.0)))
    wing = Wing(semi_span=u(3.0, 6.0), root_chord=u(0.8, 1.4),
                tip_chord=data.draw(st.sampled_from([None, 0.6])),
                mass_per_length=per_element(15.0, 35.0), EI=per_element(3e5, 9e5),
                GJ=per_element(1e5, 3e5), elastic_axis=per_element(0.35, 0.5),
                centre_of_gravity=per_element(0.4, 0.55), lift_slope=u(4.0, 7.0),
                aerodynamic_centre=per_element(0.2, 0.3), n_elements=n,
                aero_model=data.draw(st.sampled_from(["leishman-nguyen", "wagner"])),
                rayleigh=(u(0.0, 0.5), u(0.0, 1e-3)), **inertia)
    installs = []
    for node in data.draw(st.lists(st.integers(1, n), min_size=1, max_size=2, unique=True)):
        prop = Propeller(
            radius=u(0.6, 0.9), rotor=PointMass(u(5.0, 10.0), u(-1.3, -1.0)),
            masses=(PointMass(u(20.0, 40.0), u(-0.9, -0.6)),), pivot_pitch=u(-0.2, 0.2),
            pivot_yaw=u(-0.2, 0.2), f_theta=u(4.0, 9.0), K_psi=u(5e4, 2e5),
            damping_theta=0.02, damping_psi=0.02, operation="constant-speed",
            rpm=u(1500.0, 2500.0), rotation=1,
            derivatives=MeasuredDerivatives({k: u(-1.0, 1.0) for k in DERIVATIVE_NAMES}))
        installs.append(Installation(prop, float(wing.node_y[node]),
                                     mount=data.draw(st.sampled_from(["flexible", "rigid"]))))
    return PropellerWing(wing, FlightCondition(density=u(0.8, 1.2)), tuple(installs),
                         wing_aero=data.draw(st.booleans()))


@settings(max_examples=10, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(data=st.data())
def test_section_derivatives_equal_central_differences_on_random_models(data):
    model = random_model(data)
    pars = [p for p in D.parameters(model) if p.kind == "section"]
    names = {p.name for p in pars}
    assert {"root_chord", "tip_chord", "chord", "centre_of_gravity", "elastic_axis",
            "aerodynamic_centre"} <= names
    assert ("radius_of_gyration" in names) == (model.wing.radius_of_gyration is not None)
    assert ("polar_inertia" in names) == (model.wing.polar_inertia is not None)
    chosen = [p for p in pars if p.index == -1]
    for name in sorted(names - {"root_chord", "tip_chord"}):
        chosen += data.draw(st.lists(st.sampled_from([p for p in pars if p.name == name]),
                                     min_size=1, max_size=2, unique_by=lambda p: p.path))
    derivs = D.second_order_derivatives(model, V, chosen)
    for par in chosen:
        assert_matches_central_differences(model, par, derivs[par.path], V)


def test_wingtip_model_every_section_parameter():
    """The thesis's headline case (tapered baseline wing, radius of gyration, a wingtip
    propeller): every section field, elements, nodes and the propeller's elastic axis."""
    model = case_model("wingtip")
    pars = [p for p in D.parameters(model) if p.kind == "section"]
    n = model.wing.element_count
    assert len(pars) == 2 + (n + 1) + 4 * n          # root, tip, node chords, 4 fields × n
    derivs = D.second_order_derivatives(model, V, pars)
    for par in pars:
        assert_matches_central_differences(model, par, derivs[par.path], V)


def test_taper_is_the_sum_of_the_node_chords():
    """c(y) = c_r (1 − y/L) + c_t y/L: a root-chord change is the node chords moved by
    1 − y/L, a tip-chord change by y/L (the same derivative blocks, summed)."""
    model = case_model("wingtip")
    wing = model.wing
    nodes = [p.path for p in D.parameters(model) if p.name == "chord"]
    assert len(nodes) == wing.n_nodes
    d = D.second_order_derivatives(model, V, ["wing.root_chord", "wing.tip_chord"] + nodes)
    x = wing.node_y / wing.semi_span
    for path, weight in (("wing.root_chord", 1.0 - x), ("wing.tip_chord", x)):
        for name in ("S1", "S2", "S3", "S4", "Wv"):
            total = sum(w * getattr(d[p], name) for w, p in zip(weight, nodes))
            np.testing.assert_allclose(getattr(d[path], name), total, rtol=1e-9,
                                       atol=1e-12 * np.abs(total).max())


def test_chain_of_one_element_field():
    """The chain itself: a centre of gravity moves x_α b by c and ρI_p by 2 m x_α b c (radius
    of gyration) at its element only; an elastic axis also moves a at the two nodes about its
    element's mid-point (interpolation weights ½ each there on a uniform mesh)."""
    wing = case_model("wingtip").wing
    p = wing.element_properties()
    c = wing.chord_at(wing.element_y)
    e = 7
    ch = S.chain(wing, "centre_of_gravity", e)
    expect = np.zeros(wing.element_count)
    expect[e] = c[e]
    np.testing.assert_allclose(ch.element["x_alpha_b"], expect, rtol=1e-15)
    np.testing.assert_allclose(ch.element["rho_Ip"], 2 * p["m"] * p["x_alpha_b"] * expect,
                               atol=1e-15)
    assert not any(np.any(x) for x in ch.node.values())
    ch = S.chain(wing, "elastic_axis", e)
    assert np.flatnonzero(ch.node["a"]).tolist() == [e, e + 1]
    np.testing.assert_allclose(ch.node["a"][[e, e + 1]], [1.0, 1.0], rtol=1e-12)
    assert S.chain(wing, "aerodynamic_centre", e).node["ac"].sum() == pytest.approx(2.0)


def test_fields_without_per_element_values_are_not_offered():
    """A chord function leaves out the chord paths; an elastic axis given as a function of y
    (evaluated at the nodes) leaves out its per-element paths; the centre of gravity (an
    element property) is still offered."""
    wing = Wing(semi_span=4.0, mass_per_length=20.0, EI=5e5, GJ=2e5, polar_inertia=2.0,
                chord=lambda y: 1.0 - 0.05 * y, elastic_axis=lambda y: 0.4 + 0.01 * y,
                n_elements=4)
    model = PropellerWing(wing, FlightCondition(density=1.0))
    names = {p.name for p in D.parameters(model) if p.kind == "section"}
    assert names == {"centre_of_gravity", "aerodynamic_centre", "polar_inertia"}
    par = next(p for p in D.parameters(model) if p.path == "wing.centre_of_gravity[2]")
    assert_matches_central_differences(model, par,
                                       D.second_order_derivatives(model, V, [par])[par.path], V)


def test_with_value_changes_that_field_alone():
    model = case_model("wingtip")
    base = {p.path: p.value for p in D.parameters(model)}
    for path, x in (("wing.chord[10]", 1.01), ("wing.elastic_axis[3]", 0.45),
                    ("wing.radius_of_gyration[20]", 0.27), ("wing.aerodynamic_centre[0]", 0.3)):
        changed = {p.path: p.value for p in D.parameters(D.with_value(model, path, x))}
        assert changed[path] == pytest.approx(x, rel=1e-15)
        others = {k for k in base if k != path and k in changed
                  and changed[k] != pytest.approx(base[k], rel=1e-13)}
        assert not others, (path, others)
    tip = D.with_value(model, "wing.tip_chord", 0.7).wing
    assert tip.chord_at(np.array([tip.semi_span]))[0] == pytest.approx(0.7)
