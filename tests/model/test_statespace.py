"""One state-matrix builder with one singularity rule (issue 8, item 2)."""
import numpy as np
import pytest

from propwhirl.cases.ch09_baseline import isolated_baseline_propeller
from propwhirl.model.statespace import (SINGULAR_CONDITION, SecondOrder, state_matrix,
                                        state_matrix_from_mck)
from propwhirl.validate import InputError


def test_mck_form_is_the_lag_free_state_space():
    s = isolated_baseline_propeller().second_order(np.array([50.0, 150.0]))
    np.testing.assert_array_equal(state_matrix_from_mck(s.S1, s.S2, s.S3), state_matrix(s))


@pytest.mark.parametrize("cond", [1e13, 0.5 * SINGULAR_CONDITION])
def test_both_forms_accept_the_same_conditioning(cond):
    M = np.diag([1.0, 1.0 / cond])
    A = state_matrix_from_mck(M, np.zeros((2, 2)), np.eye(2))
    assert np.isfinite(A).all()


@pytest.mark.parametrize("cond", [10.0 * SINGULAR_CONDITION, np.inf])
def test_both_forms_refuse_the_same_singular_mass(cond):
    M = np.diag([1.0, 1.0 / cond])
    with pytest.raises(InputError, match=r"singular at V = 7.0 m/s"):
        state_matrix_from_mck(M, np.zeros((2, 2)), np.eye(2), V=[7.0])
    z = np.zeros((1, 2, 0))
    sys = SecondOrder(M[None], np.zeros((1, 2, 2)), np.eye(2)[None], z, np.zeros((1, 0, 0)),
                      np.zeros((1, 0, 2)), np.zeros((1, 0, 2)), ("a", "b"), ())
    with pytest.raises(InputError, match=r"singular at V = 7.0 m/s"):
        state_matrix(sys, np.array([7.0]))
