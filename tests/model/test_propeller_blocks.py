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


def test_propeller_values_are_new_dicts_over_the_assembly_constants():
    a = wingtip_propeller_wing().assembly()
    p = a.propellers[0]
    V = np.array([100.0, 200.0])
    v1 = a.propeller_values(p, V)
    assert "V" not in p.constants and "Omega" not in p.constants and "CZ_theta" not in p.constants
    v1["K_theta"] = -1.0                                 # the caller's dict, not the assembly's
    v2 = a.propeller_values(p, V)
    assert v2["K_theta"] == p.constants["K_theta"] > 0
