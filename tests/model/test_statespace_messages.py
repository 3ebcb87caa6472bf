"""State-matrix errors name the model parameter and the states behind them (issue 9, item 9).

The field ranges refuse such values when a model is built; these tests set them behind the
ranges (``object.__setattr__`` on the frozen dataclasses) to hold the diagnosis of the last
line of defence, the state-matrix builder.
"""
import copy
import warnings
from dataclasses import replace

import numpy as np
import pytest

from propwhirl.cases.ch09_baseline import isolated_baseline_propeller
from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
from propwhirl.model.propellers.propeller import PointMass
from propwhirl.model.statespace import SecondOrder, StateMatrixError, state_matrix
from propwhirl.validate import InputError

V = np.array([1.0])


def _forced(obj, **changes):
    out = copy.copy(obj)
    for k, val in changes.items():
        object.__setattr__(out, k, val)
    return out


def _wing_model(**wing):
    m = wingtip_propeller_wing()
    return m.with_(wing=_forced(m.wing, **wing))


def _prop_model(**prop):
    m = wingtip_propeller_wing()
    inst = m.propellers[0]
    return m.with_(propellers=(replace(inst, propeller=_forced(inst.propeller, **prop)),))


def _message(model) -> str:
    with warnings.catch_warnings():
        warnings.simplefilter("error")        # no numpy RuntimeWarning on the way
        with pytest.raises(InputError) as exc:
            model.state_matrix(V)
    return str(exc.value)


def test_a_huge_mount_stiffness_is_named_with_its_value():
    msg = _message(_prop_model(f_theta=None, K_theta=3.2e305))
    assert msg.startswith("propeller 1: K_theta = 3.2e+305 N m/rad makes its stiffness block")
    assert "V = 1.0 m/s" in msg and "check the model parameters" not in msg


@pytest.mark.parametrize("field, unit", [("EI", "N m^2"), ("GJ", "N m^2"),
                                         ("mass_per_length", "kg/m")])
def test_a_huge_wing_property_is_named_with_its_station(field, unit):
    """Set behind the construction-time ranges, the value is refused by the wing's own
    evaluation of its properties along the span, naming the property, the station, the value
    and the range (before the state matrix is reached)."""
    msg = _message(_wing_model(**{field: 1e300}))
    assert msg.startswith(f"{field}(y = ") and f"= 1e+300 {unit} is outside the valid range" in msg, msg


def test_huge_mount_damping_is_named():
    msg = _message(_prop_model(damping_theta=1e300))
    assert msg.startswith("propeller 1: zeta_theta = 5e+299 makes its damping block")


def test_a_huge_mass_is_badly_scaled_not_zero_mass():
    p = wingtip_propeller_wing().propellers[0].propeller
    msg = _message(_prop_model(rotor=_forced(PointMass(1.0, p.rotor.x), mass=1e300)))
    assert "badly scaled" in msg and "zero mass" not in msg
    assert "propeller 1:" in msg and "node 25" in msg


def test_a_dof_without_inertia_is_singular_and_named():
    z = np.zeros((1, 2, 0))
    sys = SecondOrder(np.array([[[1.0, 0.0], [0.0, 0.0]]]), np.zeros((1, 2, 2)),
                      np.eye(2)[None], z, np.zeros((1, 0, 0)), np.zeros((1, 0, 2)),
                      np.zeros((1, 0, 2)), ("node 1 h", "propeller 1 theta"), ())
    with pytest.raises(StateMatrixError, match=r"singular .*: propeller 1 theta has no independent "
                                               r"inertia \(a zero mass or inertia\?\)"):
        state_matrix(sys, V)


def test_a_non_finite_entry_names_matrix_role_and_states():
    z = np.zeros((1, 2, 0))
    K = np.eye(2)[None].copy()
    K[0, 1, 0] = np.inf
    sys = SecondOrder(np.eye(2)[None], np.zeros((1, 2, 2)), K, z, np.zeros((1, 0, 0)),
                      np.zeros((1, 0, 2)), np.zeros((1, 0, 2)), ("a", "b"), ())
    with pytest.raises(StateMatrixError, match=r"the stiffness matrix S3 is not finite at "
                                               r"V = 1.0 m/s \(row b, column a\)"):
        state_matrix(sys, V)


def test_the_isolated_propeller_names_its_parameter_too():
    m = isolated_baseline_propeller()
    m = m.with_(propeller=_forced(m.propeller, f_psi=None, K_psi=1e305))
    assert _message(m).startswith("propeller 1: K_psi = 1e+305 N m/rad")


def test_second_order_alone_reports_a_non_finite_entry():
    m = _prop_model(f_theta=None, K_theta=np.inf)
    # the mount damping c = 2 zeta sqrt(K I) is the first matrix it spoils
    with pytest.raises(InputError, match=r"propeller 1: K_theta = inf N m/rad makes its damping "
                                         r"block non-finite \(the damping matrix S2"):
        m.second_order(V)
