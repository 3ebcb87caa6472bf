"""BlockSystem.pencil with the constant part computed once (pencil_constant) equals the
pencil assembled from scratch, at every speed; the constant lists are not changed by use."""
import numpy as np

from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing


def test_pencil_from_a_cached_constant_part_equals_the_fresh_one():
    m = wingtip_propeller_wing()
    b = m.second_order_blocks(np.array([60.0, 150.0, 300.0]))
    const = m.second_order_blocks(np.array([1.0])).pencil_constant()
    sizes = [len(t.v) for t in const]
    for t in range(3):
        F0, E0 = b.pencil(t)
        F1, E1 = b.pencil(t, const)
        assert (F0 != F1).nnz == 0 and (E0 != E1).nnz == 0
        assert abs(F0).sum() > 0
    assert [len(t.v) for t in const] == sizes
