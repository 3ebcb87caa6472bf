"""engine.correction: crossings converged on a sparse pencil."""
import numpy as np
import scipy.sparse as sp

from propwhirl.engine.correction import correct_crossing, full_order_pair, full_order_root


def oscillator(V):
    """ẍ + (0.5 − 0.01 V) ẋ + 100 x = 0 with a stable spectator: flutter at V = 50 m/s."""
    F = sp.csc_matrix(np.array([[0.0, 1.0, 0.0], [-100.0, -(0.5 - 0.01 * V), 0.0],
                                [0.0, 0.0, -3.0]]))
    E = sp.csc_matrix(np.diag([1.0, 2.0, 1.0])) @ sp.csc_matrix(np.diag([1.0, 0.5, 1.0]))
    return F, E


def test_flutter_crossing_is_converged_from_a_perturbed_start():
    lam0 = 0.01 + 10j                      # a reduced model's estimate near V = 49 m/s
    x0 = np.array([1.0, lam0, 0.0])
    c = correct_crossing(oscillator, 49.0, lam0, x0, xtol=0.01)
    assert c is not None
    assert abs(c.V - 50.0) < 1e-3
    assert abs(c.eigenvalue.real) < 1e-6 and abs(abs(c.eigenvalue.imag) - 10.0) < 1e-3


def test_divergence_root_in_real_arithmetic():
    pencil = lambda V: (sp.csc_matrix([[V - 30.0, 0.0], [0.0, -5.0]]), sp.identity(2, format="csc"))  # noqa: E731
    c = correct_crossing(pencil, 29.5, -0.5 + 0j, np.array([1.0, 0.0]), xtol=0.01)
    assert c is not None and abs(c.V - 30.0) < 1e-3 and c.eigenvalue.imag == 0


def test_inverse_iteration_finds_the_root_nearest_the_shift():
    F, E = oscillator(40.0)
    lam, x = full_order_root(F, E, 0.0 + 9.9j, np.array([1.0, 10j, 0.0]))
    # converged to the residual rule (1e-10 of the pencil norm): λ to ~1e-8
    assert abs(lam - (-0.05 + 1j * np.sqrt(100 - 0.05 ** 2))) < 1e-7


def test_a_branch_jump_or_no_crossing_returns_none():
    """The spectator root (−3) never crosses: no secant root inside the bounds."""
    assert correct_crossing(oscillator, 49.0, -3.0 + 0j, np.array([0.0, 0.0, 1.0]),
                            xtol=0.01) is None


def test_a_real_root_given_with_a_quarter_turn_phase_is_still_found():
    """The eigenvector of a real root may come with any complex phase (sweep alignment): its
    direction, not its (vanishing) real part, starts the real iteration."""
    from propwhirl.engine.correction import real_direction

    pencil = lambda V: (sp.csc_matrix([[V - 30.0, 0.0], [0.0, -5.0]]), sp.identity(2, format="csc"))  # noqa: E731
    x0 = 1j * np.array([1.0, 1e-3])                      # phase π/2: Re x0 = 0
    np.testing.assert_allclose(real_direction(x0), [1.0, 1e-3])
    c = correct_crossing(pencil, 29.5, -0.5 + 0j, x0, xtol=0.01)
    assert c is not None and abs(c.V - 30.0) < 1e-3


def _pair_pencil(d: float, n_far: int = 30):
    """A real pencil F x = λ E x (E symmetric positive definite, not I) with the pair
    2 ± √d (complex for d < 0, two real roots for d > 0) and n_far roots between 8 and 40,
    in a random basis."""
    rng = np.random.default_rng(3)
    n = 2 + n_far
    D = np.zeros((n, n))
    D[:2, :2] = [[2.0, 1.0], [d, 2.0]]
    D[2:, 2:] = np.diag(np.linspace(8.0, 40.0, n_far))
    T = np.eye(n) + 0.3 * rng.standard_normal((n, n))
    E = rng.standard_normal((n, n))
    E = E @ E.T + n * np.eye(n)
    F = E @ T @ D @ np.linalg.inv(T)           # E⁻¹F = T D T⁻¹
    return sp.csc_matrix(F), sp.csc_matrix(E), rng.standard_normal((n, 2))


def test_pair_is_complex_before_and_real_after_the_branch_point():
    """full_order_pair: the two roots nearest σ, a conjugate pair or exactly real, from a
    random start subspace, on either side of a branch point as close as 1e-6."""
    for d in (-1.0, -1e-6, 1e-6, 1.0):
        F, E, X0 = _pair_pencil(d)
        lam = full_order_pair(F, E, 2.0, X0)
        expected = 2.0 + np.sqrt(complex(d)) * np.array([1.0, -1.0])
        np.testing.assert_allclose(np.sort_complex(lam), np.sort_complex(expected),
                                   rtol=0, atol=1e-7)
        if d > 0:
            assert np.all(lam.imag == 0)
        else:
            assert np.all(lam.imag != 0)


def test_pair_not_converged_returns_none():
    """One iteration from a random start does not reach the invariant subspace: None."""
    F, E, X0 = _pair_pencil(-1.0)
    assert full_order_pair(F, E, 2.0, X0, max_iter=1) is None


def test_norm1_is_scipys_one_norm_to_the_last_bit():
    """engine.correction.norm1: the same sums as scipy.sparse.linalg.norm(A, 1), in the same
    order (columns of 1 to 50 entries, magnitudes over 16 decades), without its temporaries."""
    import scipy.sparse.linalg as spla

    from propwhirl.engine.correction import norm1

    rng = np.random.default_rng(7)
    for k in range(100):
        A = sp.random(50, 40, density=rng.uniform(0.02, 1.0), format="csc", random_state=k)
        A.data = rng.standard_normal(A.data.size) * 10.0 ** rng.uniform(-8, 8, A.data.size)
        assert norm1(A) == spla.norm(A, 1)
    assert norm1(sp.csr_matrix(A)) == spla.norm(A, 1)          # another format: scipy's own
    assert norm1(sp.csc_matrix((3, 3))) == 0.0
