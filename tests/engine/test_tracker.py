"""The sweep loop: branch points bracketed, subset of the grid, bad input."""
from __future__ import annotations

import numpy as np
import pytest

from propwhirl.engine import TrackingOptions, analyse, sweep, time_response
from propwhirl.model.statespace import second_order_labels, state_matrix_from_mck
from propwhirl.validate import InputError

from helpers.engine_systems import section, toy_fz


def test_unstable_pair_turning_real_is_bracketed_by_two_nodes():
    """The branch point of an unstable pair turning real (the thesis's whirl divergence) is
    located from the discriminant of the pair's 2 × 2 Ritz matrix and bracketed by two sweep
    nodes 0.9·min_step apart: complex at the lower, real at the upper."""
    opts = TrackingOptions()
    sw = sweep(toy_fz, np.arange(1.0, 52.0, 10.0), options=opts)
    V = sw.V
    i = int(np.searchsorted(V, 30.0))
    assert V[i - 1] < 30.0 < V[i] and V[i] - V[i - 1] <= 0.9 * opts.min_step + 1e-12
    k = int(np.argmax(sw.eigenvalues[0].real))               # the unstable mode
    assert sw.eigenvalues[i - 1, k].imag != 0 and sw.eigenvalues[i, k].imag == 0
    assert sw.eigenvalues[i, k].real > 1.0                    # it keeps the larger root
    assert sw.stats["branch_point_nodes"] == 2


def test_analyse_evaluates_a_subset_of_the_grid_and_all_on_request():
    fn, _, _ = section()
    grid = np.arange(1.0, 202.0, 5.0)
    coarse = analyse(fn, grid, n_dof=2, xtol=1e-3)
    full = analyse(fn, grid, n_dof=2, initial_step=None, xtol=1e-3)
    assert np.all(np.isin(grid, full.sweep.V))
    assert coarse.sweep.V.size < 0.5 * grid.size
    assert np.all(np.isin(coarse.sweep.grid, grid)) and coarse.sweep.V[0] == grid[0]
    assert coarse.sweep.V[-1] == grid[-1]
    for p, q in zip(coarse.criticals.points, full.criticals.points):
        assert (p.kind, p.direction) == (q.kind, q.direction) and abs(p.V - q.V) < 1e-3
    with pytest.raises(InputError, match="initial_step"):
        analyse(fn, grid, n_dof=2, initial_step=0.0)


def test_bad_speeds():
    fn = section()[0]
    with pytest.raises(InputError, match=r"speeds\[0\] = 0.0 m/s.*> 0"):
        sweep(fn, [0.0, 10.0])
    with pytest.raises(InputError, match="> 0"):
        analyse(fn, [-5.0, 10.0])
    with pytest.raises(InputError, match="strictly increasing"):
        sweep(fn, [10.0, 10.0, 20.0])
    with pytest.raises(InputError, match="at least 2"):
        sweep(fn, [])
    with pytest.raises(InputError, match="finite"):
        sweep(fn, [1.0, np.nan])


def test_bad_state_matrices_name_the_speed():
    base = section()[0]

    def nan_at_30(V):
        A = base(V)
        A[np.isclose(V, 30.0), 3, 1] = np.nan
        return A

    with pytest.raises(InputError, match=r"V = 30.0 m/s, row 3 \(d/dt alpha\), column 1 "
                                         r"\(alpha\)"):
        sweep(nan_at_30, [10.0, 20.0, 30.0], state_labels=second_order_labels(["h", "alpha"]))
    with pytest.raises(InputError, match="shape"):
        sweep(lambda V: np.zeros((V.size, 3, 2)), [1.0, 2.0])
    with pytest.raises(InputError, match="complex"):
        sweep(lambda V: base(V) * (1 + 1j), [1.0, 2.0])
    with pytest.raises(InputError, match="n_dof"):
        sweep(base, [1.0, 2.0], n_dof=7)
    with pytest.raises(InputError, match="either n_dof or displacement"):
        sweep(base, [1.0, 2.0], n_dof=2, displacement=np.ones(4, bool))
    with pytest.raises(InputError, match=r"mass matrix .* is singular at V = 2.0 m/s"):
        state_matrix_from_mck(np.stack([np.eye(2), np.diag([1.0, 0.0])]), np.zeros((2, 2)),
                                 np.eye(2), V=[1.0, 2.0])
    with pytest.raises(InputError, match="min_step"):
        TrackingOptions(min_step=0.0)
    with pytest.raises(InputError, match="method"):
        time_response(np.eye(2), [1.0, 0.0], [0.0, 1.0], method="euler")
    with pytest.raises(InputError, match="x0"):
        time_response(np.eye(2), [1.0, 0.0, 0.0], [0.0, 1.0])
