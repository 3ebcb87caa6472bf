"""engine/nodes.py: the nodes keep NumPy's eig output without copying it when it is already
complex; the same nodes, bit for bit, as the former code that always copied."""
from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from propwhirl.engine.eigensolve import call_state_matrix, conj_index, eig_derivative
from propwhirl.engine.nodes import evaluate_nodes
from propwhirl.engine.options import TrackingOptions


def former_nodes(fn, V, opts):
    V = np.asarray(V, dtype=float)
    h = opts.fd_rel * np.maximum(V, 1.0)
    A_all = call_state_matrix(fn, np.concatenate([V, V + h]), None, None)
    A, Ah = A_all[: V.size], A_all[V.size:]
    w, X = np.linalg.eig(A)
    w, X = w.astype(complex), X.astype(complex)
    conj = conj_index(w)
    dlam = eig_derivative(w, X, conj, (Ah - A) / h[:, None, None])
    floor = np.maximum(1e-3 * np.median(np.abs(w), axis=1), 1e-12)
    return w, X, dlam, conj, floor


@settings(max_examples=60, deadline=None, derandomize=True)
@given(seed=st.integers(0, 2**32 - 1), n=st.integers(1, 12), T=st.integers(1, 4),
       symmetric=st.booleans())
def test_nodes_as_with_copies(seed, n, T, symmetric):
    rng = np.random.default_rng(seed)
    A0, A1 = rng.standard_normal((2, n, n))
    if symmetric:                                   # real eigenvalues: eig returns floats
        A0, A1 = A0 + A0.T, A1 + A1.T

    def fn(V):
        return A0[None] + V[:, None, None] * A1[None]

    V = np.sort(rng.random(T)) * 100
    opts = TrackingOptions()
    nodes = evaluate_nodes(fn, V, None, None, opts, {})
    w, X, dlam, conj, floor = former_nodes(fn, V, opts)
    for t, nd in enumerate(nodes):
        for got, ref in ((nd.lam, w[t]), (nd.X, X[t]), (nd.dlam, dlam[t]), (nd.conj, conj[t])):
            assert got.dtype == ref.dtype and got.tobytes() == ref.tobytes()
            assert got.strides == ref.strides
        assert nd.floor == float(floor[t]) and nd.V == float(V[t])
