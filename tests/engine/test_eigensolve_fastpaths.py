"""The fast paths of engine/eigensolve.py against the library calls they replace, bit for bit.

:func:`_lu_factor` / :func:`_lu_solve` call LAPACK getrf/getrs directly instead of
``scipy.linalg.lu_factor`` / ``lu_solve``, and :func:`_norm` forms the 2-norm without
``numpy.linalg.norm``'s argument handling; each claims the very same floats.
"""
from __future__ import annotations

import warnings

import numpy as np
import pytest
import scipy.linalg as sla
from hypothesis import given, settings
from hypothesis import strategies as st

from propwhirl.engine import eigensolve as es

SETTINGS = settings(max_examples=150, deadline=None, derandomize=True)


def same_bits(x, y) -> bool:
    x, y = np.asarray(x), np.asarray(y)
    return x.dtype == y.dtype and x.shape == y.shape and x.tobytes() == y.tobytes()


def random_array(seed: int, shape: tuple[int, ...], complex_: bool, order: str = "C"):
    rng = np.random.default_rng(seed)
    a = rng.standard_normal(shape) * 10.0 ** rng.integers(-3, 4, size=shape)
    if complex_:
        a = a + 1j * rng.standard_normal(shape)
    return np.asarray(a, order=order)


@SETTINGS
@given(seed=st.integers(0, 2**32 - 1), n=st.integers(1, 60), cplx=st.booleans(),
       order=st.sampled_from("CF"))
def test_lu_factor_is_scipys(seed, n, cplx, order):
    M = random_array(seed, (n, n), cplx, order)
    M0 = M.copy()
    lu, piv = es._lu_factor(M)
    lu_ref, piv_ref = sla.lu_factor(M, check_finite=False)
    assert same_bits(lu, lu_ref) and same_bits(piv, piv_ref)
    assert lu.flags.f_contiguous == lu_ref.flags.f_contiguous
    assert same_bits(M, M0)                      # the input is not overwritten


@SETTINGS
@given(seed=st.integers(0, 2**32 - 1), n=st.integers(1, 60), k=st.integers(0, 3),
       cplx_a=st.booleans(), cplx_b=st.booleans(), trans=st.sampled_from([0, 1, 2]))
def test_lu_solve_is_scipys(seed, n, k, cplx_a, cplx_b, trans):
    M = random_array(seed, (n, n), cplx_a) + 5.0 * np.eye(n)
    b = random_array(seed + 1, (n,) if k == 0 else (n, k), cplx_b)
    b0 = b.copy()
    lu = sla.lu_factor(M, check_finite=False)
    x = es._lu_solve(lu, b, trans=trans)
    x_ref = sla.lu_solve(lu, b, trans=trans, check_finite=False)
    assert same_bits(x, x_ref)
    assert same_bits(b, b0)


def test_singular_and_other_types_go_through_scipy():
    M = np.array([[1.0, 2.0], [2.0, 4.0]])           # exactly singular: scipy's warning
    with pytest.warns(sla.LinAlgWarning):
        lu, piv = es._lu_factor(M)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ref = sla.lu_factor(M, check_finite=False)
    assert same_bits(lu, ref[0]) and same_bits(piv, ref[1])
    M32 = np.eye(3, dtype=np.float32) * 2
    lu32 = es._lu_factor(M32)
    assert same_bits(lu32[0], sla.lu_factor(M32, check_finite=False)[0])
    b32 = np.ones(3, dtype=np.float32)
    assert same_bits(es._lu_solve(lu32, b32), sla.lu_solve(lu32, b32, check_finite=False))
    with pytest.raises(ValueError):
        es._lu_solve(lu32, np.ones(4))


@SETTINGS
@given(seed=st.integers(0, 2**32 - 1), shape=st.sampled_from([(1,), (7,), (50,), (129,),
                                                                (50, 2), (3, 50), (0,)]),
       cplx=st.booleans(), order=st.sampled_from("CF"), step=st.sampled_from([1, 2]))
def test_norm_is_numpys(seed, shape, cplx, order, step):
    x = random_array(seed, tuple(s * step for s in shape[:1]) + shape[1:], cplx, order)
    x = x[::step]
    got = es._norm(x)
    ref = np.linalg.norm(x)
    assert type(got) is type(ref) and same_bits(got, ref)
