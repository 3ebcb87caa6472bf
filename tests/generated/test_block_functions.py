"""The one form of propwhirl.generated: block functions (several matrices from one function,
one common-subexpression elimination, used by the assembly), and per matrix a thin view of its
block function (the documented API the oracle tests check against the thesis) or, for a matrix
in no block, the matrix's own code."""
import ast
import importlib
import inspect
import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from propwhirl.generated import MODULES

GENERATED = {name: importlib.import_module(f"propwhirl.generated.{name}") for name in MODULES}
GROUPS = [(name, group) for name, mod in GENERATED.items() for group in getattr(mod, "BLOCKS", {})]
VIEWS = [(name, view) for name, mod in GENERATED.items() for view in getattr(mod, "VIEWS", {})]


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


def entry_writers(mod) -> set[str]:
    """Names of the module's functions that compute matrix entries (``x[..., i, j] = ...``)."""
    tree = ast.parse(inspect.getsource(mod))
    return {
        f.name for f in tree.body if isinstance(f, ast.FunctionDef)
        and any(isinstance(n, ast.Assign) and isinstance(n.targets[0], ast.Subscript)
                for n in ast.walk(f))
    }


@pytest.mark.parametrize("name", MODULES)
def test_every_matrix_is_computed_by_one_piece_of_code(name):
    """One generated form: a matrix in a block is computed by its block function only — its
    own function is a view (a single call of the block function) — and a matrix in no block
    by its own function; beside these only the derivative functions compute entries."""
    mod = GENERATED[name]
    owner = {m: group for group, (_, members) in mod.BLOCKS.items() for m in members}
    assert sum(len(members) for _, members in mod.BLOCKS.values()) == len(owner)  # one block each
    assert mod.VIEWS == owner
    singles = set(mod.OUTPUTS) - set(owner)
    assert entry_writers(mod) == set(mod.BLOCKS) | singles | set(mod.PARTIALS)
    tree = {f.name: f for f in ast.parse(inspect.getsource(mod)).body
            if isinstance(f, ast.FunctionDef)}
    for view, group in mod.VIEWS.items():
        body = tree[view].body
        assert len(body) == 2 and isinstance(body[1], ast.Return), view  # docstring, return
        call = body[1].value
        assert isinstance(call, ast.Call) and call.func.id == "_view", view
        assert [a.id if isinstance(a, ast.Name) else a.value for a in call.args] == [group, view]
        assert [k.arg for k in call.keywords] == list(mod.OUTPUTS[view][0])
        assert list(inspect.signature(getattr(mod, view)).parameters) == list(mod.OUTPUTS[view][0])


positive = st.floats(0.1, 10.0, allow_nan=False)


def draw(data, argnames, n):
    """Random positive values, some of them arrays of length n (the rest scalars)."""
    return {a: (np.array(data.draw(st.lists(positive, min_size=n, max_size=n)))
                if data.draw(st.booleans()) else data.draw(positive))
            for a in argnames}


@pytest.mark.parametrize("name, view", VIEWS)
@settings(max_examples=15, deadline=None)
@given(data=st.data(), n=st.integers(1, 4), m=st.integers(1, 3))
def test_view_is_its_block_functions_matrix_whatever_the_other_arguments(name, view, data, n, m):
    """A view returns, bit for bit, the matrix its block function computes at the view's
    arguments, whatever values the block's other arguments take (they feed only the other
    matrices; the view fills them with NaN, without a warning), with the broadcast shape of
    its own arguments."""
    mod = GENERATED[name]
    group = mod.VIEWS[view]
    own = mod.OUTPUTS[view][0]
    values = draw(data, own, n)
    others = {a: np.array(data.draw(st.lists(positive, min_size=m, max_size=m)))[:, None]
              for a in mod.BLOCKS[group][0] if a not in own}
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        got = getattr(mod, view)(*(values[a] for a in own))
    block = getattr(mod, group)(**values, **others)[view]
    shape = np.broadcast_shapes(*(np.shape(v) for v in values.values()))
    assert got.shape == shape + block.shape[-2:]
    assert np.array_equal(np.broadcast_to(got, block.shape), block)


def test_the_generator_refuses_a_matrix_in_two_blocks():
    """A view must name one block function: the generator stops on a matrix in two blocks."""
    pytest.importorskip("sympy", reason="the generator needs the codegen extra")
    from derivations.generate import block_of
    from derivations.typical_section import derive

    d = derive()
    d.blocks = {"blocks": ("mass", "stiffness"), "again": ("mass",)}
    with pytest.raises(ValueError, match="'mass' is in blocks 'blocks' and 'again'"):
        block_of(d)
