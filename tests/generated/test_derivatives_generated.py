"""The generated derivative functions (``<block>_d``) of propwhirl.generated: against SymPy's
evaluated derivative of the derivation's matrix, and against central finite differences of
the generated matrix function itself."""
import functools
import importlib

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from propwhirl.generated import MODULES

GENERATED = {name: importlib.import_module(f"propwhirl.generated.{name}") for name in MODULES}
FUNCTIONS = [(name, f) for name, mod in GENERATED.items() for f in mod.PARTIALS]

value = st.floats(0.5, 2.0, allow_nan=False)


def draw_values(data, argnames, n=None):
    """Random parameter values in [0.5, 2] (in SI units, all the matrices are smooth there);
    with `n`, some of them arrays of length n (the rest scalars: broadcasting)."""
    out = {}
    for a in argnames:
        if n is not None and data.draw(st.booleans()):
            out[a] = np.array(data.draw(st.lists(value, min_size=n, max_size=n)))
        else:
            out[a] = data.draw(value)
    return out


def original(mod, fname):
    """The generated function the derivative function differentiates, as name -> matrix."""
    of = fname[: -len("_d")]
    if of in getattr(mod, "BLOCKS", {}):
        return getattr(mod, of)
    return lambda **kw: {of: getattr(mod, of)(**kw)}


def test_every_block_function_and_every_matrix_has_derivatives():
    for name, mod in GENERATED.items():
        covered = {m for _, nonzero in mod.PARTIALS.values() for m in nonzero}
        assert covered == set(mod.OUTPUTS), name
        for block in mod.BLOCKS:
            assert f"{block}_d" in mod.PARTIALS
            assert mod.PARTIALS[f"{block}_d"][0] == mod.BLOCKS[block][0]  # same signature


@pytest.mark.parametrize("name, fname", FUNCTIONS)
@settings(max_examples=10, deadline=None)
@given(data=st.data(), n=st.integers(1, 3))
def test_derivatives_equal_central_differences_of_the_generated_matrices(name, fname, data, n):
    """∂M/∂p of every matrix for every argument p (zero where PARTIALS leaves p out) against
    (M(p + h) − M(p − h))/2h with h = 1e-5 p: truncation ~ (h/p)² = 1e-10 and rounding
    ~ 1e-16 |terms of M|/h ≈ 1e-11 |terms of M|/p, so 1e-6 of max(|∂M/∂p|, |terms of M|/p)
    separates a wrong derivative from the difference's error.  |terms of M| is |M|, or, where
    M's terms cancel (an entry exactly 0 from terms of size 1: the rounding of M(p ± h) is
    then that of its terms, not of |M|), the largest |q ∂M/∂q| over the arguments q: the size
    of the terms M is a sum of (a wrong ∂M/∂q fails its own check, scaled by itself)."""
    mod = GENERATED[name]
    argnames, nonzero = mod.PARTIALS[fname]
    values = draw_values(data, argnames, n)
    got = getattr(mod, fname)(**values)
    f = original(mod, fname)
    base = f(**values)
    assert list(got) == list(nonzero) == list(base)
    shape = np.broadcast_shapes(*(np.shape(x) for x in values.values()))
    for p in argnames:
        h = 1e-5 * np.asarray(values[p])
        up, down = dict(values), dict(values)
        up[p], down[p] = values[p] + h, values[p] - h
        fu, fd = f(**up), f(**down)
        hh = np.reshape(h, np.shape(h) + (1, 1))
        for m in nonzero:
            terms = max([float(np.max(np.abs(base[m])))]
                        + [float(np.max(np.abs(np.reshape(values[q], np.shape(values[q]) + (1, 1))
                                               * got[m][q]))) for q in got[m]])
            diff = (np.broadcast_to(fu[m], shape + base[m].shape[-2:])
                    - np.broadcast_to(fd[m], shape + base[m].shape[-2:])) / (2 * hh)
            exact = got[m].get(p)
            assert (exact is None) == (p not in nonzero[m]), (m, p)
            if exact is None:
                exact = np.zeros_like(diff)
            assert exact.shape == shape + base[m].shape[-2:], (m, p)
            scale = max(np.max(np.abs(exact)), terms / np.min(np.abs(values[p])))
            assert np.max(np.abs(exact - diff)) <= 1e-6 * scale, (m, p)


@functools.lru_cache(maxsize=None)
def derivation(name):
    pytest.importorskip("sympy", reason="the SymPy oracle needs the codegen extra")
    mod = importlib.import_module(f"derivations.{name}")
    return mod.derive()


@functools.lru_cache(maxsize=None)
def sympy_derivatives(name, fname):
    """{(matrix, parameter): numpy function of the arguments} from SymPy's own diff of the
    derivation's matrix, lambdified (nothing from the generator)."""
    import sympy as sp

    d = derivation(name)
    mod = GENERATED[name]
    argnames, nonzero = mod.PARTIALS[fname]
    symbols = {p.symbol.name: p.symbol for p in d.params}
    args = [symbols[a] for a in argnames]
    by_name = {o.name: o for o in d.outputs}
    out = {}
    for m in nonzero:
        for a in args:
            dm = sp.Matrix(by_name[m].matrix).diff(a).applyfunc(sp.expand)
            # Σ|term| of each entry: the scale of its rounding error (terms may cancel)
            size = dm.applyfunc(lambda e: sp.Add(*(sp.Abs(t) for t in sp.Add.make_args(e))))
            out[m, a.name] = (dm == sp.zeros(*dm.shape), sp.lambdify(args, dm, "numpy"),
                              sp.lambdify(args, size, "numpy"))
    return out


@pytest.mark.parametrize("name, fname", FUNCTIONS)
@settings(max_examples=10, deadline=None)
@given(data=st.data())
def test_derivatives_equal_sympys_evaluated_derivative(name, fname, data):
    """The generated ∂M/∂p equals SymPy's diff of the derivation's matrix, lambdified and
    evaluated at the same random values, to 1e-12 of the largest Σ|term| of its entries (the
    two differ in operation order only, and terms may cancel exactly); the zero derivatives
    are exactly the ones left out."""
    mod = GENERATED[name]
    argnames, nonzero = mod.PARTIALS[fname]
    values = draw_values(data, argnames)
    got = getattr(mod, fname)(**values)
    oracle = sympy_derivatives(name, fname)
    for m in nonzero:
        for p in argnames:
            is_zero, fn, size = oracle[m, p]
            assert is_zero == (p not in nonzero[m]), (m, p)
            args = [values[a] for a in argnames]
            expected = np.array(fn(*args), dtype=float)
            exact = got[m].get(p, np.zeros(expected.shape))
            scale = max(float(np.max(np.array(size(*args), dtype=float))), 1e-300)
            assert np.max(np.abs(exact - expected)) <= 1e-12 * scale, (m, p)
