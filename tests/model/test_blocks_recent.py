"""RecentBlocks: an explicit store of one assembly's evaluations, held by the reduced model of
one analysis: speeds asked for again are answered with the values of a fresh evaluation; the
store is bounded and read-only; an overriding rotational speed is never answered from it."""
import numpy as np
import pytest

from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
from propwhirl.model.blocks import RecentBlocks
from propwhirl.model.reduction import reduce


def _arrays(b):
    return [b.V, b.M, b.C, b.K] + b.speed_arrays()[1:]


def _equal(b1, b2):
    return all(np.array_equal(x, y) for x, y in zip(_arrays(b1), _arrays(b2)))


def test_a_speed_of_a_kept_evaluation_has_the_fresh_values():
    a = wingtip_propeller_wing().assembly()
    store = RecentBlocks()
    V = np.array([120.0, 143.15, 201.5, 320.9])
    batch = store.add(a.blocks(V))
    again = store.get(V[[2, 0]])                       # from the kept batch
    fresh = wingtip_propeller_wing().assembly().blocks(V[[2, 0]])
    assert again.V.tolist() == [201.5, 120.0]
    assert _equal(again, fresh)
    assert store.get(V) is batch                        # the same request: the same object
    assert store.get(np.array([100.0, 120.0])) is None  # one speed not kept


def test_kept_arrays_are_read_only():
    a = wingtip_propeller_wing().assembly()
    b = RecentBlocks().add(a.blocks(np.array([100.0, 200.0])))
    with pytest.raises(ValueError):
        b.blocks[0].S1[...] = 0.0


def test_the_reduced_model_answers_an_overriding_rotational_speed_afresh():
    R = reduce(wingtip_propeller_wing(), np.arange(10.0, 351.0, 20.0))
    V = np.array([150.0])
    own = R.second_order(V)
    spun = R.second_order(V, omega=np.array([10.0]))
    assert not np.array_equal(own.S2, spun.S2)
    assert np.array_equal(R.second_order(V).S2, own.S2)
    fresh = reduce(wingtip_propeller_wing(), np.arange(10.0, 351.0, 20.0))
    assert np.array_equal(fresh.second_order(V, omega=np.array([10.0])).S2, spun.S2)


def test_the_store_is_bounded():
    a = wingtip_propeller_wing().assembly()
    store = RecentBlocks(max_batches=2, max_speeds=5)
    for V in ([1.0, 2.0], [3.0, 4.0], [5.0]):
        store.add(a.blocks(np.array(V)))
    assert store.get(np.array([5.0])) is not None
    assert store.get(np.array([3.0, 4.0])) is not None
    assert store.get(np.array([1.0])) is None           # dropped: more than two batches
    store = RecentBlocks(max_batches=8, max_speeds=3)
    store.add(a.blocks(np.array([1.0, 2.0])))
    store.add(a.blocks(np.array([3.0, 4.0])))
    assert store.get(np.array([1.0])) is None           # dropped: more than three speeds
    big = a.blocks(np.arange(1.0, 5.0))
    assert store.add(big) is big and store.get(big.V) is None    # too big to keep
