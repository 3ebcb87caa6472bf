"""The traced whirl-flutter boundary of the isolated propeller (chapter 6 model, §9.2) against
grid maps of the same (f_θ, f_ψ) plane: agreement within the grid's resolution, and the
accuracy of a 50 x 50 map with at least 10 times fewer eigen-solutions."""
from __future__ import annotations

import numpy as np
import pytest

from propwhirl.cases.registry import case_model
from propwhirl.studies.boundary import (grid_agreement, grid_map, level_of, neutral_curve,
                                        path_variant, speed_contour)

PATHS = ("propeller.f_theta", "propeller.f_psi")
LO, HI, V = (3.0, 3.0), (12.0, 12.0), 220.0


@pytest.fixture(scope="module")
def model():
    return case_model("isolated-propeller")


@pytest.fixture(scope="module")
def traced(model):
    return neutral_curve(model, PATHS, LO, HI, V)


def _distance(g, p, h=1e-4):
    """First-order distance [Hz] of p to the curve g = 0: |g| / |grad g|."""
    f0 = g(p)
    grad = np.array([(g(p + e) - f0) / h for e in (np.array([h, 0.0]), np.array([0.0, h]))])
    return abs(f0) / np.hypot(*grad)


def test_the_curve_crosses_the_plane_and_its_points_are_neutral(model, traced):
    assert len(traced.curves) == 1 and traced.stops[0] == ("bounds", "bounds")
    c = traced.curves[0]
    assert np.all(c >= np.array(LO) - 1e-12) and np.all(c <= np.array(HI) + 1e-12)
    g = level_of(traced, model)
    assert max(_distance(g, p) for p in c) < 5e-3     # tol 1e-4 of 9 Hz
    # stable for stiffer mounts: at (12, 12) the least stable mode is damped, at the curve not
    assert g(np.array([12.0, 12.0])) < 0 < g(np.array([4.0, 4.0]))
    # the symmetry of equal pitch and yaw inertias: (a, b) on the curve <=> (b, a)
    assert max(_distance(g, p[::-1]) for p in c) < 5e-3


def test_agrees_with_a_coarse_grid_within_its_resolution(model, traced):
    grid = grid_map(level_of(traced, model), LO, HI, 13)
    d_traced, d_grid = grid_agreement(traced, grid)
    assert d_traced <= 1.0 and d_grid <= 1.0          # cells (a half-diagonal is 0.71)


def _grid_contour_points(grid):
    """The 50 x 50 map's boundary: linear interpolation of g along every cell edge it crosses."""
    out = []
    z = grid.values
    for i in range(len(grid.x)):
        for j in range(len(grid.y)):
            for di, dj in ((1, 0), (0, 1)):
                k, m = i + di, j + dj
                if k < len(grid.x) and m < len(grid.y) and z[i, j] * z[k, m] < 0:
                    t = z[i, j] / (z[i, j] - z[k, m])
                    out.append([grid.x[i] + t * (grid.x[k] - grid.x[i]),
                                grid.y[j] + t * (grid.y[m] - grid.y[j])])
    return np.array(out)


@pytest.mark.long
def test_ten_times_fewer_evaluations_than_a_50x50_map_at_equal_accuracy(model, traced):
    g = level_of(traced, model)
    grid = grid_map(g, LO, HI, 50)
    assert grid.evaluations == 2500 and 10 * traced.evaluations <= grid.evaluations
    grid_error = max(_distance(g, p) for p in _grid_contour_points(grid))
    traced_error = max(_distance(g, p) for p in traced.curves[0])
    assert traced_error <= grid_error


def test_the_critical_speed_contour_runs_along_the_neutral_curve(model, traced):
    """V_crit(f_θ, f_ψ) = 220 m/s traced with analyses lies on the neutral curve at 220 m/s
    (the crossing of the whirl mode there) — two level functions, one boundary."""
    c = speed_contour(model, PATHS, LO, HI, V)
    assert len(c.curves) == 1 and c.evaluations < 250
    g = level_of(traced, model)
    assert max(_distance(g, p) for p in c.curves[0]) < 0.02
    assert {d["kind"] for d in c.info[0]} == {"flutter"}


def test_a_variant_callable_instead_of_paths(model, traced):
    variant, _ = path_variant(model, PATHS)
    b = neutral_curve(model, ("a", "b"), LO, HI, V, variant=variant)
    np.testing.assert_allclose(b.curves[0], traced.curves[0])
