"""The model contract: every model implements Model, and its DOF map describes its states."""
import numpy as np
import pytest

from propwhirl.cases.ch07_patil import patil_model
from propwhirl.cases.ch09_baseline import isolated_baseline_propeller
from propwhirl.cases.ch10_other_wings import two_propeller_wing, wingtip_propeller_wing
from propwhirl.model import FlightCondition, TypicalSection
from propwhirl.model.protocol import DOF_KINDS, DofMap, Model
from propwhirl.validate import InputError


def _models():
    fl = FlightCondition(density=1.0)
    return {
        "wingtip": wingtip_propeller_wing(),
        "two-propeller rigid": two_propeller_wing("rigid"),
        "two-propeller": two_propeller_wing(),
        "wingtip no wing aero": wingtip_propeller_wing(wing_aero=False),
        "patil": patil_model(),
        "isolated": isolated_baseline_propeller(),
        "section": TypicalSection(b=1.0, a=-0.2, x_alpha=0.1, r_alpha=0.5, m=10.0, omega_h=5.0,
                                  omega_alpha=12.0, flight=fl),
        "section wagner": TypicalSection(b=1.0, a=-0.2, x_alpha=0.1, r_alpha=0.5, m=10.0,
                                         omega_h=5.0, omega_alpha=12.0, flight=fl,
                                         aero_model="wagner"),
    }


@pytest.mark.parametrize("name", list(_models()))
def test_every_model_implements_the_contract(name):
    model = _models()[name]
    assert isinstance(model, Model)
    dm = model.dof_map()
    s = model.second_order(np.array([50.0]))
    # the map describes exactly the states the model produces, in order
    assert dm.state_labels == s.labels
    assert dm.n_dof == s.n_dof and dm.n_lag == s.n_lag
    A = model.state_matrix(np.array([50.0]))
    assert A.shape == (1, dm.n_states, dm.n_states)
    assert dm.displacement.sum() == dm.n_dof
    # every DOF kind is a known one; wing DOFs carry their node, propeller DOFs their propeller
    for kind, node, prop in zip(dm.q_kinds, dm.q_node, dm.q_propeller):
        assert kind in DOF_KINDS
        assert (node >= 1) == (kind in ("h", "phi", "alpha"))
        assert (prop >= 0) == (kind in ("theta", "psi"))
    for p in dm.propellers:
        assert dm.q_kinds[p.theta] == "theta" and dm.q_kinds[p.psi] == "psi"
        assert dm.q_propeller[p.theta] == dm.q_propeller[p.psi] == p.number
        assert p.rotation in (1, -1)
    # the quiet model has the same DOFs and no aerodynamic lag states
    quiet = model.without_aerodynamics()
    assert quiet.dof_map().q_labels == dm.q_labels and quiet.dof_map().n_lag == 0


def test_propeller_positions_in_the_map():
    dm = two_propeller_wing().dof_map()
    ys = [p.y for p in dm.propellers]
    assert len(ys) == 2 and ys[0] < ys[1]
    wing = two_propeller_wing().wing
    for p in dm.propellers:
        assert p.y == pytest.approx(wing.node_y[p.node])
    assert dm.propeller(1).number == 1
    with pytest.raises(InputError, match="propeller 7 has no pitch/yaw"):
        dm.propeller(7)
    assert two_propeller_wing("rigid").dof_map().propellers == ()


def test_lag_states_belong_to_nodes_1_and_up():
    m = wingtip_propeller_wing()
    dm = m.dof_map()
    assert min(dm.w_node) == 1 and max(dm.w_node) == m.wing.n_nodes - 1


def test_groups_are_the_content_groups():
    dm = wingtip_propeller_wing().dof_map()
    g = dm.groups()
    assert set(g) == {"bending", "torsion", "pitch", "yaw"}
    assert sum(len(ix) for ix in g.values()) == dm.n_dof
    assert set(TypicalSection(b=1.0, a=-0.2, x_alpha=0.1, r_alpha=0.5, m=10.0, omega_h=5.0,
                              omega_alpha=12.0, flight=FlightCondition(density=1.0)
                              ).dof_map().groups()) == {"plunge", "pitch"}


def test_bad_maps_are_refused():
    with pytest.raises(InputError, match="q_kinds has 1 entries"):
        DofMap(("a", "b"), ("h",), (1, 1), (-1, -1))
    with pytest.raises(InputError, match="unknown kind"):
        DofMap(("a",), ("twist",), (1,), (-1,))
