"""The block functions of propwhirl.generated (several matrices from one function, used by the
assembly) against the per-matrix functions the oracle tests check against the thesis."""
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from propwhirl.generated import MODULES
import importlib

GENERATED = {name: importlib.import_module(f"propwhirl.generated.{name}") for name in MODULES}
GROUPS = [(name, group) for name, mod in GENERATED.items() for group in getattr(mod, "BLOCKS", {})]


def test_every_module_has_block_functions_for_the_assembly():
    assert {name for name, _ in GROUPS} == set(MODULES)
    assert ("prop_flexwing", "aero_blocks") in GROUPS and ("strip_aero", "ln_blocks") in GROUPS


@pytest.mark.parametrize("name, group", GROUPS)
def test_block_arguments_are_the_union_of_the_members_arguments(name, group):
    mod = GENERATED[name]
    argnames, members = mod.BLOCKS[group]
    union = set().union(*(mod.OUTPUTS[m][0] for m in members))
    assert set(argnames) == union and len(argnames) == len(union)
    assert list(argnames) == [p for p in mod.PARAMETERS if p in union]  # parameter order


positive = st.floats(0.1, 10.0, allow_nan=False)


@pytest.mark.parametrize("name, group", GROUPS)
@settings(max_examples=25, deadline=None)
@given(data=st.data(), n=st.integers(1, 4))
def test_block_function_equals_the_per_matrix_functions(name, group, data, n):
    """Same matrices as the per-matrix functions on random parameters (some broadcast over a
    leading axis of length n, some scalar): to 1e-12 of each matrix's largest entry, and in
    fact bit for bit — the block functions reuse each matrix's own common subexpressions
    (`derivations/generate.py`, block_cse="merged"), which is why the reproduced values do
    not move when the assembly switched to them."""
    mod = GENERATED[name]
    argnames, members = mod.BLOCKS[group]
    values = {
        a: (np.array(data.draw(st.lists(positive, min_size=n, max_size=n)))
            if data.draw(st.booleans()) else data.draw(positive))
        for a in argnames
    }
    got = getattr(mod, group)(**values)
    assert list(got) == list(members)
    for m in members:
        expected = getattr(mod, m)(**{a: values[a] for a in mod.OUTPUTS[m][0]})
        shape = np.broadcast_shapes(*(np.shape(v) for v in values.values()))
        assert got[m].shape == shape + expected.shape[-2:]
        expected = np.broadcast_to(expected, got[m].shape)
        scale = max(float(np.max(np.abs(expected))), 1e-300)
        assert np.max(np.abs(got[m] - expected)) <= 1e-12 * scale, m
        assert np.array_equal(got[m], expected), m
