"""The fast paths of engine/linking.py against the straightforward code they replaced, bit for bit.

The free columns of the assignment by a mask instead of ``np.setdiff1d``, the pairs i < k of
the approach check without forming ``np.triu``, and the degenerate-neighbour test by the
array's own ``any``.
"""
from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from propwhirl.engine import linking as lk

SETTINGS = settings(max_examples=200, deadline=None, derandomize=True)


def same_bits(x, y) -> bool:
    x, y = np.asarray(x), np.asarray(y)
    return x.dtype == y.dtype and x.shape == y.shape and x.tobytes() == y.tobytes()


@SETTINGS
@given(seed=st.integers(0, 2**32 - 1), n=st.integers(1, 80), k=st.integers(0, 100))
def test_free_columns_is_setdiff1d(seed, n, k):
    rng = np.random.default_rng(seed)
    taken = rng.integers(0, n, size=min(k, 3 * n))      # repeats allowed, like j1[easy]
    assert same_bits(lk._free_columns(n, taken), np.setdiff1d(np.arange(n), taken))


@SETTINGS
@given(seed=st.integers(0, 2**32 - 1), p=st.integers(0, 40), density=st.floats(0, 1))
def test_upper_pairs_is_nonzero_of_triu(seed, p, density):
    rng = np.random.default_rng(seed)
    cand = rng.random((p, p)) < density
    ref = cand.copy()
    np.fill_diagonal(ref, False)
    i_ref, k_ref = np.nonzero(np.triu(ref))
    i, k = lk._upper_pairs(cand)
    assert same_bits(i, i_ref) and same_bits(k, k_ref)


def near_reference(lam, conj, scale, tol, rows):
    d = np.abs(lam[rows, None] - lam[None, :])
    r = np.arange(rows.size)
    d[r, rows] = np.inf
    d[r, conj[rows]] = np.inf
    return np.any(d <= tol * scale[rows, None], axis=1)


@SETTINGS
@given(seed=st.integers(0, 2**32 - 1), pairs=st.integers(0, 12), reals=st.integers(0, 12),
       tol=st.sampled_from([0.0, 1e-6, 1e-2, 0.5]))
def test_near_is_the_plain_any(seed, pairs, reals, tol):
    rng = np.random.default_rng(seed)
    z = rng.standard_normal(pairs) + 1j * rng.random(pairs)
    z[: pairs // 3] = z[0] if pairs else z[: pairs // 3]     # some degenerate pairs
    lam = np.concatenate([np.ravel(np.column_stack([z, z.conj()])), rng.standard_normal(reals)])
    n = lam.size
    if n == 0:
        return
    conj = np.arange(n)
    conj[: 2 * pairs: 2] += 1
    conj[1: 2 * pairs: 2] -= 1
    scale = np.maximum(np.abs(lam), 1e-3)
    rows = np.unique(rng.integers(0, n, size=n))
    assert same_bits(lk._near(lam, conj, scale, tol, rows), near_reference(lam, conj, scale, tol, rows))
