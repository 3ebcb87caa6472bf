"""RecentBlocks: speeds asked for again are answered from a kept evaluation, with the values
of a fresh one; the store is bounded and read-only; variants of a model share what they can."""
from dataclasses import replace

import numpy as np
import pytest

from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
from propwhirl.model.blocks import RecentBlocks


def _arrays(b):
    return [b.V, b.M, b.C, b.K] + b.speed_arrays()[1:]


def _equal(b1, b2):
    return all(np.array_equal(x, y) for x, y in zip(_arrays(b1), _arrays(b2)))


def test_a_speed_of_a_kept_evaluation_has_the_fresh_values():
    m = wingtip_propeller_wing()
    V = np.array([120.0, 143.15, 201.5, 320.9])
    batch = m.second_order_blocks(V)
    again = m.second_order_blocks(V[[2, 0]])           # from the kept batch
    fresh = wingtip_propeller_wing().second_order_blocks(V[[2, 0]])
    assert again.V.tolist() == [201.5, 120.0]
    assert _equal(again, fresh)
    assert m.second_order_blocks(V) is batch            # the same request: the same object


def test_kept_arrays_are_read_only_and_new_speeds_are_evaluated():
    m = wingtip_propeller_wing()
    b = m.second_order_blocks(np.array([100.0, 200.0]))
    with pytest.raises(ValueError):
        b.blocks[0].S1[...] = 0.0
    mixed = m.second_order_blocks(np.array([100.0, 250.0]))      # one speed not kept
    assert _equal(mixed, wingtip_propeller_wing().second_order_blocks(np.array([100.0, 250.0])))


def test_an_overriding_rotational_speed_is_never_answered_from_the_store():
    m = wingtip_propeller_wing()
    V = np.array([150.0])
    m.second_order_blocks(V)
    spun = m.second_order_blocks(V, omega=np.array([10.0]))
    own = m.second_order_blocks(V)
    assert not _equal(spun, own)


def test_the_store_is_bounded():
    m = wingtip_propeller_wing()
    store = RecentBlocks(max_batches=2, max_speeds=5)
    for V in ([1.0, 2.0], [3.0, 4.0], [5.0]):
        store.add(m.second_order_blocks(np.array(V)))
    assert store.get(np.array([5.0])) is not None
    assert store.get(np.array([3.0, 4.0])) is not None
    assert store.get(np.array([1.0])) is None           # dropped: more than two batches
    store = RecentBlocks(max_batches=8, max_speeds=3)
    store.add(m.second_order_blocks(np.array([1.0, 2.0])))
    store.add(m.second_order_blocks(np.array([3.0, 4.0])))
    assert store.get(np.array([1.0])) is None           # dropped: more than three speeds
    big = m.second_order_blocks(np.arange(1.0, 5.0))
    assert store.add(big) is big and store.get(big.V) is None    # too big to keep


def test_variants_share_the_structure_and_the_quiet_model_is_made_once():
    m = wingtip_propeller_wing()
    m.second_order_blocks(np.array([10.0]))
    q = m.without_aerodynamics()
    assert q is m.without_aerodynamics()
    assert q._memo["wing"]["structure"] is m._memo["wing"]["structure"]
    assert not q.wing_aero and not q.propeller_aero
    stiff = m.with_(wing=replace(m.wing, rayleigh=(0.1, 1e-4)))      # a new wing
    stiff.second_order_blocks(np.array([10.0]))
    assert stiff._memo["wing"]["structure"] is not m._memo["wing"]["structure"]
    assert not np.array_equal(stiff._memo["wing"]["structure"][1], m._memo["wing"]["structure"][1])
    thin = m.with_(flight=replace(m.flight, density=0.5))             # the same wing
    assert thin._memo["wing"]["structure"] is m._memo["wing"]["structure"]
    thin.second_order_blocks(np.array([10.0]))
    assert thin._memo["installations"] is not m._memo["installations"]   # ρ is one of them


def test_a_variant_made_before_any_evaluation_shares_what_it_computes():
    m = wingtip_propeller_wing()
    q = m.with_(rotating=False).without_aerodynamics()       # as the reduced basis makes it
    q.second_order_blocks(np.array([1.0]))
    m.second_order_blocks(np.array([1.0]))
    assert m._memo["wing"]["structure"] is q._memo["wing"]["structure"]
    assert m._memo["installations"][0] is q._memo["installations"][0]
