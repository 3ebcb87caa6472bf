"""propwhirl.model.propellers.derivatives_blade: the Houbolt–Reed derivatives' exact ∂/∂μ and the chain
rule from blade angle, zero-lift angle and rpm to the system, against central differences of
the runtime's own quadrature and of ``second_order``."""
import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from helpers.derivative_checks import assert_matches_central_differences
from propwhirl.cases.registry import case_model
from propwhirl.model import derivatives as D
from propwhirl.model.propellers import derivatives_blade as B
from propwhirl.model.propellers import propeller_aero as pa
from propwhirl.model.propellers.propeller import MeasuredDerivatives, PointMass, Propeller
from propwhirl.model.systems import FlightCondition, Installation, PropellerWing
from propwhirl.model.aerodynamics.theodorsen import theodorsen
from propwhirl.model.structure.wing import Wing

V = np.array([40.0, 95.0])


def test_theodorsen_derivative_against_central_differences():
    k = np.array([1e-3, 0.02, 0.1, 0.5, 1.0, 3.0, 30.0, 300.0])
    h = 1e-6 * k
    fd = (theodorsen(k + h) - theodorsen(k - h)) / (2 * h)
    np.testing.assert_allclose(B.theodorsen_derivative(k), fd, rtol=1e-7)
    # the expansions where theodorsen() uses them, differentiated term by term
    for k0 in (1e-10, 1e5):
        x = np.array([k0 * 0.99, k0 * 1.01])    # truncation ~1e-6, rounding ~1e-16 / 2e-12
        slope = (theodorsen(x[1:]) - theodorsen(x[:1])) / (x[1] - x[0])
        np.testing.assert_allclose(B.theodorsen_derivative(np.array([k0])), slope, rtol=1e-4)


GEOMETRIES = (
    pa.PropellerGeometry(3, 0.762, 0.125 / 0.762, 0.094),
    pa.PropellerGeometry(4, 1.2, 0.2, pa.Distribution.linear(0.15, 0.08, 0.0, "chord"),
                         lift_slope=pa.Distribution.tabulated([0.0, 0.6, 1.0], [6.0, 6.3, 5.5])),
    pa.PropellerGeometry(3, 0.9, 0.15, lambda eta: 0.12 - 0.05 * eta ** 2, aspect_ratio=7.0),
)


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(geo=st.sampled_from(GEOMETRIES), wake=st.booleans(), comp=st.booleans(),
       arc=st.booleans(), method=st.sampled_from(["houbolt_reed", "bennett_bland"]),
       sign=st.sampled_from(["thesis", "rodden_rose"]),
       mu=st.floats(0.2, 1.5), mach=st.floats(0.05, 0.7))
def test_advance_ratio_derivatives_against_the_quadrature(geo, wake, comp, arc, method, sign,
                                                          mu, mach):
    """∂C/∂μ at fixed M against central differences of propeller_aero.derivatives with Ω
    moved (h = 1e-5 μ); the values equal that function's.  The derivative is the exact one
    of the integral evaluated by the same rule, so it differs from the rule's own derivative
    by the rule's error (32 Gauss points per smooth panel: ~1e-12): tolerance 1e-7 relative
    (truncation (h/μ)² ~ 1e-10, rounding 1e-16/1e-5)."""
    s = pa.AeroSettings(wake=wake, compressibility=comp, aspect_ratio_correction=arc,
                        method=method, cnq_sign=sign)
    Vv = np.array([60.0, 150.0])
    M = np.array([mach, 0.8 * mach])
    om = Vv / (mu * geo.radius)
    values, d = B.derivatives_and_mu_derivatives(geo, s, Vv, om, M)
    ref = pa.derivatives(geo, Vv, om, mach=M, settings=s).derivatives()
    h = 1e-5 * mu
    up = pa.derivatives(geo, Vv, Vv / ((mu + h) * geo.radius), mach=M, settings=s).derivatives()
    dn = pa.derivatives(geo, Vv, Vv / ((mu - h) * geo.radius), mach=M, settings=s).derivatives()
    scale = max(np.abs(ref[n]).max() for n in ref) / mu
    for n in ref:
        np.testing.assert_allclose(values[n], ref[n], rtol=1e-13, atol=1e-15, err_msg=n)
        fd = (up[n] - dn[n]) / (2 * h)
        np.testing.assert_allclose(d[n], fd, rtol=1e-7, atol=1e-8 * scale, err_msg=n)


def test_the_cut_off_radius_moves_with_mu_without_a_jump():
    """High Mach (tip beyond the Rodden–Rose cut-off): ∂I/∂μ still equals the difference
    quotient — the integrand is continuous where the cut-off begins."""
    geo = GEOMETRIES[0]
    Vv, M = np.array([200.0]), np.array([0.6])
    for mu in (0.5, 0.9):
        om = Vv / (mu * geo.radius)
        assert pa.derivatives(geo, Vv, om, mach=M).cutoff_applied.all()
        _, d = B.derivatives_and_mu_derivatives(geo, pa.AeroSettings(), Vv, om, M)
        h = 1e-5 * mu
        f = lambda m: pa.derivatives(geo, Vv, Vv / (m * geo.radius), mach=M)  # noqa: E731
        fd = (f(mu + h).CY_psi - f(mu - h).CY_psi) / (2 * h)
        np.testing.assert_allclose(d["CY_psi"], fd, rtol=1e-7)


def random_model(data) -> PropellerWing:
    """A 3-element wing with one or two Houbolt–Reed propellers (the default source or a
    given HouboltReedSource or measured derivatives; fixed pitch by either advance rule, or
    constant speed; either sense of rotation; random Houbolt–Reed switches; flexible or rigid;
    spinning or not)."""
    u = lambda lo, hi: data.draw(st.floats(lo, hi))  # noqa: E731
    wing = Wing(semi_span=4.0, root_chord=1.2, tip_chord=0.8, mass_per_length=25.0,
                EI=6e5, GJ=2e5, radius_of_gyration=0.25, n_elements=3)
    installs = []
    for node in data.draw(st.lists(st.integers(1, 3), min_size=1, max_size=2, unique=True)):
        settings_ = pa.AeroSettings(wake=data.draw(st.booleans()),
                                    compressibility=data.draw(st.booleans()),
                                    method=data.draw(st.sampled_from(["houbolt_reed",
                                                                      "bennett_bland"])))
        op = data.draw(st.sampled_from(["fixed-pitch", "constant-speed"]))
        kw = (dict(rpm=u(1500.0, 2500.0)) if op == "constant-speed" else
              dict(beta_075_deg=u(25.0, 45.0), zero_lift_angle_deg=u(-4.0, -1.0),
                   advance_rule=data.draw(st.sampled_from(["thesis_eq_9_1",
                                                           "blade_element"]))))
        base = dict(radius=0.762, hub_radius=0.125, blade_chord=0.094, n_blades=3,
                    pivot_pitch=0.0, pivot_yaw=0.0, rotor=PointMass(8.0, -1.16), masses=(PointMass(35.0, -0.86),),
                    f_theta=u(5.0, 8.0), f_psi=u(5.0, 8.0), damping_theta=0.01,
                    damping_psi=0.01, operation=op, aero_settings=settings_,
                    rotation=data.draw(st.sampled_from([1, -1])), **kw)
        source = data.draw(st.sampled_from(["default", "given", "measured"]))
        prop = Propeller(**base)
        if source == "given":
            prop = Propeller(**base, derivatives=pa.houbolt_reed_source(prop, settings_))
        elif source == "measured":
            prop = Propeller(**base, derivatives=MeasuredDerivatives({"CZ_theta": 0.5}))
        installs.append(Installation(prop, float(wing.node_y[node]),
                                     mount=data.draw(st.sampled_from(["flexible", "rigid"]))))
    return PropellerWing(wing, FlightCondition(density=1.0, speed_of_sound=330.0),
                         tuple(installs), rotating=data.draw(st.booleans()),
                         propeller_aero=data.draw(st.booleans()))


@settings(max_examples=12, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(data=st.data())
def test_rotation_derivatives_equal_central_differences_on_random_models(data):
    model = random_model(data)
    pars = [p for p in D.parameters(model) if p.kind == "rotation"]
    for inst, j in zip(model.propellers, range(len(model.propellers))):
        names = {p.name for p in pars if p.index == j}
        want = ({"rpm"} if inst.propeller.operation == "constant-speed"
                else {"beta_075_deg", "zero_lift_angle_deg"})
        assert names == want
    derivs = D.second_order_derivatives(model, V, pars)
    for par in pars:
        assert_matches_central_differences(model, par, derivs[par.path], V)


def test_wingtip_blade_angle():
    """The headline case: β_0.75 and α_0L (eq. 9.1 as the thesis uses it, μ = tan(β + α_0L):
    the two derivatives are equal)."""
    model = case_model("wingtip")
    pre = "propellers[0].propeller."
    pars = [p for p in D.parameters(model) if p.kind == "rotation"]
    assert [p.path for p in pars] == [pre + "beta_075_deg", pre + "zero_lift_angle_deg"]
    d = D.second_order_derivatives(model, V, pars)
    for par in pars:
        assert_matches_central_differences(model, par, d[par.path], V)
    for name in ("S1", "S2", "S3"):
        np.testing.assert_array_equal(getattr(d[pre + "beta_075_deg"], name),
                                      getattr(d[pre + "zero_lift_angle_deg"], name))


def test_advance_ratio_rates():
    prop = case_model("wingtip").propellers[0].propeller
    mu = prop.advance_ratio
    assert mu == pytest.approx(math.tan(math.radians(32.0)))
    dmu, dom = B.advance_ratio_rates(prop, "beta_075_deg", V)
    np.testing.assert_allclose(dmu, (1 + mu ** 2) * math.pi / 180, rtol=1e-15)
    np.testing.assert_allclose(dom, -V / (mu ** 2 * prop.radius) * dmu, rtol=1e-14)
    cs = Propeller(**{**{f: getattr(prop, f) for f in ("radius", "rotor", "masses", "f_theta",
                                                        "f_psi", "blade_chord", "hub_radius",
                                                        "n_blades", "pivot_pitch", "pivot_yaw",
                                                        "rotation")},
                      "operation": "constant-speed", "rpm": 2000.0})
    dmu, dom = B.advance_ratio_rates(cs, "rpm", V)
    Om = 2000.0 * 2 * math.pi / 60
    np.testing.assert_allclose(dom, Om / 2000.0, rtol=1e-15)
    np.testing.assert_allclose(dmu, -V / (Om * cs.radius) / 2000.0, rtol=1e-14)


def test_an_unknown_derivative_source_has_no_rotation_parameters():
    model = case_model("wingtip")
    prop = model.propellers[0].propeller

    def source(V, Omega, a):
        return {k: np.zeros_like(V) for k in pa.DERIVATIVE_NAMES}

    assert B.parameters(prop, True) and not B.parameters(
        Propeller(**{f: getattr(prop, f) for f in ("radius", "rotor", "masses", "f_theta",
                                                   "f_psi", "pivot_pitch", "pivot_yaw",
                                                   "rotation", "beta_075_deg",
                                                   "zero_lift_angle_deg")},
                  derivatives=source), True)
