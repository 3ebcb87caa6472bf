"""The refinement's node budget is bounded absolutely and by memory; what it leaves is
reported in Sweep.unresolved, never grown without limit."""
from __future__ import annotations

import numpy as np

from propwhirl import limits
from propwhirl.engine import analyse, sweep


def never_resolved(V):
    """Two close oscillators whose mode shapes rotate 40 rad per m/s: every step stays
    ambiguous down to min_step (MAC < 0.8 at 0.01 m/s), so refinement wants every 0.01 m/s."""
    V = np.atleast_1d(V)
    th = 40.0 * V
    c, s = np.cos(th), np.sin(th)
    R = np.stack([np.stack([c, -s], -1), np.stack([s, c], -1)], -2)      # (T, 2, 2)
    D = np.zeros((V.size, 2, 2))
    D[:, 0, 0] = 100.0
    D[:, 1, 1] = 100.0 * (1 + 1e-3 * np.sin(V))
    K = R @ D @ np.swapaxes(R, -1, -2)
    A = np.zeros((V.size, 4, 4))
    A[:, :2, 2:] = np.eye(2)
    A[:, 2:, :2] = -K
    A[:, 2:, 2:] = -0.1 * np.eye(2)
    return A


def test_refinement_is_bounded_absolutely():
    """The old budget, 20·len(grid) + 200, let this 1,000-speed grid grow to 20,200 nodes."""
    grid = np.linspace(1.0, 1000.0, 1000)
    an = analyse(never_resolved, grid, n_dof=2)
    first = 21                                   # the grid speeds ≈ 50 m/s apart
    assert an.sweep.stats["nodes"] <= first + limits.MAX_REFINED_NODES
    assert an.sweep.stats["nodes"] < 20 * grid.size + 200
    assert len(an.sweep.unresolved) > 100        # what is left is reported
    assert all(a < b for a, b in an.sweep.unresolved)


def test_refinement_is_bounded_by_memory(monkeypatch):
    monkeypatch.setenv(limits.MEMORY_ENV, "16MiB")
    grid = np.linspace(1.0, 100.0, 100)
    budget = limits.node_budget(grid.size, grid.size, 4)
    assert budget < grid.size + limits.MAX_REFINED_NODES          # memory is what binds
    sw = sweep(never_resolved, grid, n_dof=2)
    assert grid.size < sw.V.size <= budget
    assert limits.sweep_bytes(sw.V.size, 4) <= 16 * 2 ** 20
    assert sw.unresolved


def test_an_extreme_stiffness_does_not_grow_the_grid():
    """A light wing with the stiffest allowed EI (1e12 N m^2): the sweep stays small."""
    from propwhirl.analysis.stability import analyse as model_analyse
    from propwhirl.model import FlightCondition, PropellerWing, Wing

    wing = Wing(semi_span=6.096, root_chord=1.8288, mass_per_length=0.1, polar_inertia=0.025,
                EI=1e12, GJ=0.987e6, elastic_axis=0.33, centre_of_gravity=0.43, n_elements=4)
    a = model_analyse(PropellerWing(wing, FlightCondition(1.225)), vgf=True)
    grid = a.sweep.grid.size
    assert a.sweep.V.size <= min(20 * grid + 200, grid + limits.MAX_REFINED_NODES)
    assert np.all(np.isfinite(a.sweep.eigenvalues))
