"""The cheap paths of PropellerWing's block evaluation give what the general ones give."""
import numpy as np
from hypothesis import given, settings, strategies as st

from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
from propwhirl.model.propeller_blocks import _stack_blocks


@settings(max_examples=30, deadline=None)
@given(st.integers(1, 4), st.integers(1, 3), st.integers(1, 3), st.integers(1, 3),
       st.integers(1, 3), st.integers(0, 2**31 - 1))
def test_stack_blocks_is_np_block(nV, r1, r2, c1, c2, seed):
    rng = np.random.default_rng(seed)
    a, b = rng.normal(size=(nV, r1, c1)), rng.normal(size=(nV, r1, c2))
    c, d = rng.normal(size=(nV, r2, c1)), rng.normal(size=(nV, r2, c2))
    assert np.array_equal(_stack_blocks([[a, b], [c, d]]), np.block([[a, b], [c, d]]))


def test_propeller_constants_are_computed_once_and_do_not_leak_into_values():
    m = wingtip_propeller_wing()
    V = np.array([100.0, 200.0])
    v1 = m._propeller_values(0, V)
    const = m._memo["installations"][0]
    assert "V" not in const and "Omega" not in const and "CZ_theta" not in const
    v1["K_theta"] = -1.0                                 # the caller's dict, not the memo
    v2 = m._propeller_values(0, V)
    assert v2["K_theta"] == const["K_theta"] > 0
    assert m._propeller_constants(0) is const
