"""engine.correction: a reduced crossing within xtol/10 of the full one costs one evaluation
(Newton's step with the reduced slope is then below xtol/10); farther, the secant goes on."""
import numpy as np
import scipy.sparse as sp

from propwhirl.engine.correction import correct_crossing


def divergence(V):
    """λ = (V − 30)/10 in real arithmetic (a spectator at −5): d Re λ/dV = 0.1 /m."""
    return sp.csc_matrix([[(V - 30.0) / 10.0, 0.0], [0.0, -5.0]]), sp.identity(2, format="csc")


def test_a_crossing_within_a_tenth_of_xtol_takes_one_evaluation():
    c = correct_crossing(divergence, 30.0008, 0.0 + 0j, np.array([1.0, 0.0]), xtol=0.01,
                         slope=0.1)
    assert c.evaluations == 1 and c.iterations == 0
    assert abs(c.V - 30.0) < 1e-9           # the Newton step of a linear Re λ(V) is exact
    assert abs(c.eigenvalue - 0.00008) < 1e-12    # λ of the last evaluation, at V0


def test_a_farther_crossing_is_iterated():
    c = correct_crossing(divergence, 30.02, 0.0 + 0j, np.array([1.0, 0.0]), xtol=0.01,
                         slope=0.05)        # a slope off by a factor 2: Newton overshoots
    assert c.evaluations >= 2 and abs(c.V - 30.0) < 1e-3


def test_a_wrong_slope_near_the_crossing_stays_within_xtol():
    """Even with a slope twice the true one, the accepted step's error is below the step."""
    c = correct_crossing(divergence, 30.0009, 0.0 + 0j, np.array([1.0, 0.0]), xtol=0.01,
                         slope=0.2)
    assert c.evaluations == 1 and abs(c.V - 30.0) <= 0.0009
