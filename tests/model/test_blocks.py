"""model.blocks: the block form of the second-order system against the dense one."""
import numpy as np
import pytest
import scipy.linalg as sla

from propwhirl.cases.ch10_other_wings import two_propeller_wing
from propwhirl.model.statespace import state_matrix

V = np.array([60.0, 180.0, 300.0])


@pytest.fixture(scope="module")
def model():
    return two_propeller_wing()


def test_dense_form_is_the_models_second_order(model):
    """second_order is assembled from the blocks: bit-identical matrices."""
    s, b = model.second_order(V), model.second_order_blocks(V).dense()
    for name in ("S1", "S2", "S3", "S4", "Ww", "Wv", "Wq"):
        np.testing.assert_array_equal(getattr(s, name), getattr(b, name))
    assert s.q_labels == b.q_labels and s.w_labels == b.w_labels


def test_sparse_pencil_has_the_eigenvalues_of_the_state_matrix(model):
    b = model.second_order_blocks(V)
    A = model.state_matrix(V)
    for t in range(V.size):
        F, E = b.pencil(t)
        assert F.shape == E.shape == A.shape[1:]
        np.testing.assert_allclose(sla.solve(E.toarray(), F.toarray()), A[t], rtol=1e-10,
                                   atol=1e-8 * np.abs(A[t]).max())


def test_projection_on_the_identity_is_the_dense_system(model):
    """Φ = the kept DOFs, Q = the kept lag states: the projection reproduces the dense system."""
    b = model.second_order_blocks(V)
    Phi = np.eye(b.n_q)[:, b.keep_q]
    Q = np.eye(b.n_w)[:, b.keep_w]
    got = b.project(Phi, Q)
    want = b.dense()
    for x, name in zip(got, ("S1", "S2", "S3", "S4", "Ww", "Wv", "Wq")):
        np.testing.assert_allclose(x, getattr(want, name), rtol=1e-12,
                                   atol=1e-12 * np.abs(getattr(want, name)).max())
    sys = type(want)(*got, want.q_labels, want.w_labels)
    np.testing.assert_allclose(state_matrix(sys), model.state_matrix(V), rtol=1e-9, atol=1e-6)


def test_projection_is_linear_in_the_basis(model):
    """Φᵀ S Φ of a random basis equals the dense product (the block sums are exact)."""
    b = model.second_order_blocks(V[:1])
    rng = np.random.default_rng(3)
    Phi = np.zeros((b.n_q, 5))
    Phi[b.keep_q] = rng.standard_normal((b.keep_q.size, 5))
    Q = np.zeros((b.n_w, 4))
    Q[b.keep_w] = np.linalg.qr(rng.standard_normal((b.keep_w.size, 4)))[0]
    S1, S2, S3, S4, Ww, Wv, Wq = b.project(Phi, Q)
    d = b.dense()
    P, G = Phi[b.keep_q], Q[b.keep_w]
    np.testing.assert_allclose(S3[0], P.T @ d.S3[0] @ P, rtol=1e-10)
    np.testing.assert_allclose(S4[0], P.T @ d.S4[0] @ G, rtol=1e-10, atol=1e-12)
    np.testing.assert_allclose(Wv[0], G.T @ d.Wv[0] @ P, rtol=1e-10, atol=1e-12)
    np.testing.assert_allclose(Ww[0], G.T @ d.Ww[0] @ G, rtol=1e-10, atol=1e-12)


def test_one_matrix_alone_is_the_dense_one(model):
    b = model.second_order_blocks(V)
    d = b.dense()
    for name in ("S1", "S2", "S3"):
        np.testing.assert_array_equal(b.matrix(name), getattr(d, name))
