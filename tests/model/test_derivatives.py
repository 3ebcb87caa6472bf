"""propwhirl.model.derivatives: the chain rule from the generated ∂(block)/∂p to model fields,
against central finite differences of ``second_order`` of the model with the field changed."""
import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from helpers.derivative_checks import assert_matches_central_differences
from propwhirl.cases.registry import case_model
from propwhirl.model import derivatives as D
from propwhirl.model.propellers.propeller import MeasuredDerivatives, PointMass, Propeller
from propwhirl.model.propellers.propeller_aero import DERIVATIVE_NAMES
from propwhirl.model.systems import FlightCondition, Installation, PropellerWing
from propwhirl.model.structure.wing import Wing
from propwhirl.validate import InputError

V = np.array([40.0, 95.0])


def random_model(data) -> PropellerWing:
    """A small wing (3–5 elements; spanwise or uniform properties; radius of gyration or
    polar inertia; Rayleigh damping; either strip-aerodynamics model) with one or two
    propellers at nodes (measured derivatives; stiffness or frequency; g or ζ; flexible or
    rigid; aerodynamics on or off per propeller; spinning or not)."""
    u = lambda lo, hi: data.draw(st.floats(lo, hi))  # noqa: E731
    n = data.draw(st.integers(3, 5))
    per_element = lambda lo, hi: (np.array([u(lo, hi) for _ in range(n)])  # noqa: E731
                                  if data.draw(st.booleans()) else u(lo, hi))
    inertia = (dict(radius_of_gyration=u(0.2, 0.3)) if data.draw(st.booleans())
               else dict(polar_inertia=per_element(1.0, 3.0)))
    wing = Wing(semi_span=u(3.0, 6.0), root_chord=u(0.8, 1.4), tip_chord=u(0.5, 0.8),
                mass_per_length=per_element(15.0, 35.0), EI=per_element(3e5, 9e5),
                GJ=per_element(1e5, 3e5), elastic_axis=u(0.35, 0.5),
                centre_of_gravity=u(0.4, 0.55), lift_slope=u(4.0, 7.0),
                aerodynamic_centre=u(0.2, 0.3), n_elements=n,
                aero_model=data.draw(st.sampled_from(["leishman-nguyen", "wagner"])),
                rayleigh=(u(0.0, 0.5), u(0.0, 1e-3)), **inertia)
    installs = []
    nodes = data.draw(st.lists(st.integers(1, n), min_size=1, max_size=2, unique=True))
    for node in nodes:
        stiff = (dict(f_theta=u(4.0, 9.0)) if data.draw(st.booleans())
                 else dict(K_theta=u(5e4, 2e5)))
        stiff.update(dict(f_psi=u(4.0, 9.0)) if data.draw(st.booleans())
                     else dict(K_psi=u(5e4, 2e5)))
        prop = Propeller(
            radius=u(0.6, 0.9), rotor=PointMass(u(5.0, 10.0), u(-1.3, -1.0)),
            masses=(PointMass(u(20.0, 40.0), u(-0.9, -0.6)),), pivot_pitch=u(-0.2, 0.2),
            pivot_yaw=u(-0.2, 0.2), damping_theta=u(0.005, 0.05), damping_psi=u(0.005, 0.05),
            damping=data.draw(st.sampled_from(["g", "zeta"])),
            spin_inertia=data.draw(st.sampled_from([None, 1.5])),
            operation="constant-speed", rpm=u(1500.0, 2500.0),
            derivatives=MeasuredDerivatives({k: u(-1.0, 1.0) for k in DERIVATIVE_NAMES}),
            rotation=data.draw(st.sampled_from([1, -1])), **stiff)
        y = wing.node_y[node]
        installs.append(Installation(prop, float(y),
                                     mount=data.draw(st.sampled_from(["flexible", "rigid"])),
                                     aero=data.draw(st.booleans())))
    return PropellerWing(wing, FlightCondition(density=u(0.8, 1.2)), tuple(installs),
                         rotating=data.draw(st.booleans()))


@settings(max_examples=12, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(data=st.data())
def test_derivatives_equal_central_differences_on_random_models(data):
    model = random_model(data)
    pars = D.parameters(model)
    # a sample of every kind of parameter (all of them for the propellers)
    chosen = [p for p in pars if p.kind == "propeller"]
    for kind in ("element", "node"):
        of_kind = [p for p in pars if p.kind == kind]
        if of_kind:
            chosen += data.draw(st.lists(st.sampled_from(of_kind), min_size=1, max_size=4,
                                         unique_by=lambda p: p.path))
    derivs = D.second_order_derivatives(model, V, chosen)
    assert list(derivs) == [p.path for p in chosen]
    for par in chosen:
        assert_matches_central_differences(model, par, derivs[par.path], V)


def test_wingtip_model_every_parameter():
    """The thesis's headline case (25 elements, a wingtip propeller given by its mount
    frequencies, g damping, Houbolt–Reed derivatives): every covered parameter."""
    model = case_model("wingtip")
    pars = D.parameters(model)
    paths = {p.path for p in pars}
    assert {"wing.EI[24]", "wing.GJ[0]", "wing.lift_slope[25]", "propellers[0].propeller.f_theta",
            "propellers[0].propeller.K_psi"} <= paths
    assert not any("derivatives.values" in s for s in paths)  # Houbolt–Reed: not a field
    derivs = D.second_order_derivatives(model, V)
    for par in pars:
        assert_matches_central_differences(model, par, derivs[par.path], V)


def test_frequency_chain_rule_is_two_k_over_f():
    model = case_model("wingtip")
    pre = "propellers[0].propeller."
    d = D.second_order_derivatives(model, V, [pre + "f_theta", pre + "K_theta"])
    K = model.propellers[0].propeller.stiffness()[0]
    f = model.propellers[0].propeller.f_theta
    for name in ("S2", "S3"):
        np.testing.assert_allclose(getattr(d[pre + "f_theta"], name),
                                   2 * K / f * getattr(d[pre + "K_theta"], name), rtol=1e-14)


def test_with_value_changes_that_parameter_alone():
    model = case_model("wingtip")
    base = {p.path: p.value for p in D.parameters(model)}
    for path, x in (("wing.EI[3]", 1.234e6), ("wing.lift_slope[7]", 5.5),
                    ("wing.mass_per_length[10]", 31.0),
                    ("propellers[0].propeller.f_psi", 6.1),
                    ("propellers[0].propeller.K_theta", 2.2e5)):
        changed = {p.path: p.value for p in D.parameters(D.with_value(model, path, x))}
        assert changed[path] == pytest.approx(x, rel=1e-15)
        others = {k for k in base if k != path and changed.get(k) != pytest.approx(base[k], rel=1e-15)}
        if path.endswith("K_theta"):  # the frequency field gives way to the stiffness
            others -= {"propellers[0].propeller.f_theta"}
        if path.endswith("f_psi"):  # the stiffness follows: K = I (2π f)²
            I = model.propellers[0].propeller.pivot_inertia()["I_psi_P"]
            assert changed["propellers[0].propeller.K_psi"] == pytest.approx(
                I * (2 * np.pi * x) ** 2, rel=1e-14)
            others -= {"propellers[0].propeller.K_psi"}
        assert not others, (path, others)


def test_pencil_and_projection_of_the_derivative_blocks():
    """pencil_derivative and project() of a derivative BlockSystem agree with its dense form
    (the same assembly as the system's)."""
    model = case_model("wingtip")
    pre = "propellers[0].propeller."
    paths = ["wing.EI[5]", "wing.lift_slope[12]", pre + "K_psi"]
    blocks = D.derivative_blocks(model, V, paths)
    rng = np.random.default_rng(0)
    for path in paths:
        b = blocks[path]
        dense = b.dense()
        n = dense.n_dof
        for t in range(V.size):
            dF, dE = D.pencil_derivative(b, t)
            dF, dE = dF.toarray(), dE.toarray()
            np.testing.assert_array_equal(dE[n:2 * n, n:2 * n], dense.S1[t])
            np.testing.assert_array_equal(dF[n:2 * n, :n], -dense.S3[t])
            np.testing.assert_array_equal(dF[n:2 * n, n:2 * n], -dense.S2[t])
            np.testing.assert_array_equal(dF[n:2 * n, 2 * n:], dense.S4[t])
            np.testing.assert_array_equal(dF[2 * n:, :n], dense.Wq[t])
            np.testing.assert_array_equal(dF[2 * n:, n:2 * n], dense.Wv[t])
            np.testing.assert_array_equal(dF[2 * n:, 2 * n:], dense.Ww[t])
            assert not dF[:n].any() and not dE[:n].any() and not dE[2 * n:].any()
        Phi = np.zeros((b.n_q, 4))
        Phi[b.keep_q] = rng.standard_normal((b.keep_q.size, 4))
        Q = np.zeros((b.n_w, 3))
        Q[b.keep_w] = np.linalg.qr(rng.standard_normal((b.keep_w.size, 3)))[0]
        P, G = Phi[b.keep_q], Q[b.keep_w]
        S1, S2, S3, S4, Ww, Wv, Wq = b.project(Phi, Q)
        for got, full, left, right in ((S1, dense.S1, P, P), (S3, dense.S3, P, P),
                                       (S4, dense.S4, P, G), (Wv, dense.Wv, G, P)):
            np.testing.assert_allclose(got, left.T @ full @ right, atol=1e-9 * max(
                np.abs(full).max(), 1e-300))


def test_unknown_parameter_and_other_models_are_errors():
    model = case_model("wingtip")
    with pytest.raises(InputError, match="wing.EI\\[99\\]"):
        D.second_order_derivatives(model, V, ["wing.EI[99]"])
    with pytest.raises(InputError, match="PropellerWing"):
        D.parameters(case_model("isolated-propeller"))
