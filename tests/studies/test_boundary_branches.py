"""Boundaries with branches (issue 35, item 6): an L-shaped stability boundary whose corner
stops the corrector has two branches; the start search lines meet one, the grid map's zero set
seeds the other (`add_branches`, `continuation.trace(seeds=...)`), and the text says how many
branches there are and where each ends."""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from propwhirl.io import load_model
from propwhirl.studies import boundary as B
from propwhirl.studies.continuation import trace

ROOT = Path(__file__).resolve().parents[2]


def _l_shape(p):
    """Negative (unstable) where x < 0.3 or y < 0.4: the boundary is an L, two straight arms
    meeting at a right-angled corner (0.3, 0.4) — where two modes exchange the lead."""
    return min(p[0] - 0.3, p[1] - 0.4)


def test_the_corner_stops_the_line_search_and_the_seeds_find_the_other_arm():
    only_lines = trace(_l_shape, [0.0, 0.0], [1.0, 1.0])
    assert len(only_lines.branches) == 1                       # the failure
    assert "corrector failed" in only_lines.branches[0].stops
    x = np.linspace(0.0, 1.0, 12)
    grid = B.GridMap(x, x, np.array([[_l_shape((a, b)) for b in x] for a in x]))
    t = trace(_l_shape, [0.0, 0.0], [1.0, 1.0], seeds=B.grid_seeds(grid),
              seed_spacing=float(np.hypot(1 / 11, 1 / 11)))
    assert len(t.branches) == 2 and len(t.starts) == 2
    horizontal = [b for b in t.branches if np.ptp(b.points[:, 1]) < 1e-3]
    vertical = [b for b in t.branches if np.ptp(b.points[:, 0]) < 1e-3]
    assert len(horizontal) == len(vertical) == 1
    assert np.allclose(horizontal[0].points[:, 1], 0.4, atol=1e-3)
    assert np.allclose(vertical[0].points[:, 0], 0.3, atol=1e-3)
    # each arm from the plane's edge to the corner
    assert vertical[0].points[:, 1].max() == pytest.approx(1.0)
    assert vertical[0].points[:, 1].min() == pytest.approx(0.4, abs=0.02)
    assert horizontal[0].points[:, 0].max() == pytest.approx(1.0)
    assert horizontal[0].points[:, 0].min() == pytest.approx(0.3, abs=0.02)


def test_a_seed_on_a_traced_curve_is_not_traced_again():
    x = np.linspace(0.0, 1.0, 9)
    g = (lambda p: (p[0] - 0.5) ** 2 + (p[1] - 0.45) ** 2 - 0.09)     # one closed curve
    grid = B.GridMap(x, x, np.array([[g((a, b)) for b in x] for a in x]))
    t = trace(g, [0.0, 0.0], [1.0, 1.0], seeds=B.grid_seeds(grid),
              seed_spacing=float(np.hypot(1 / 8, 1 / 8)))
    assert len(B.grid_seeds(grid)) >= 8
    assert len(t.branches) == 1 and t.branches[0].closed and len(t.starts) >= 1


@pytest.fixture(scope="module")
def l_shaped():
    """The four-propeller wing at 103.5 m/s in the plane of the inboard propeller's pitch
    and the outboard one's yaw mount frequency: unstable where either is below ~1.17 Hz."""
    model = load_model(ROOT / "examples" / "four_propeller.toml")
    params = ("propellers[0].propeller.f_theta", "propellers[3].propeller.f_psi")
    b = B.neutral_curve(model, params, (0.5, 0.5), (8.0, 8.0), V=103.5)
    grid = B.grid_map(B.level_of(b, model), (0.5, 0.5), (8.0, 8.0), 8)
    return model, b, grid, B.add_branches(b, model, grid)


def test_the_l_shaped_boundary_of_a_wing_has_both_branches(l_shaped):
    model, b, grid, every = l_shaped
    assert len(b.curves) == 1 and "corrector failed" in b.stops[0]
    assert len(every.curves) == 2
    ends = {why for stops in every.stops for why in stops}
    assert ends == {"bounds", "corrector failed"}               # each from an edge to the corner
    g = B.level_of(every, model)
    for c in every.curves:     # every point neutral: |g| / |grad g| (a distance [Hz]) small
        for p in c[1:-1:max(1, len(c) // 4)]:
            f0, h = g(p), 1e-4
            grad = np.hypot(*[(g(p + e) - f0) / h for e in np.eye(2) * h])
            assert abs(f0) / grad < 5e-3, (p, f0, grad)     # tol 1e-4 of the 7.5 Hz plane
    arms = sorted(every.curves, key=lambda c: float(np.ptp(c[:, 0])))
    assert np.ptp(arms[0][:, 0]) < 0.05 and arms[0][:, 1].max() == pytest.approx(8.0)
    assert np.ptp(arms[1][:, 1]) < 0.05 and arms[1][:, 0].max() == pytest.approx(8.0)
    d1, d2 = B.grid_agreement(every, grid)
    assert d1 < 1.5 and d2 < 1.5                                # within the grid's resolution
    assert every.evaluations > b.evaluations and every.settings["seeded_from_grid"] == "8 x 8"


def test_the_text_says_how_many_branches_and_where_each_ends(l_shaped):
    _, b, _, every = l_shaped
    text = every.format()
    assert "2 branches, every sign change of a 8 x 8 grid map on one of them" in text
    assert "the plane's edge propellers[3].propeller.f_psi = upper" in text
    assert "the plane's edge propellers[0].propeller.f_theta = upper" in text
    assert text.count("corrector failed") == 2
    assert "from the start search lines only" in b.format()
    again = B.Boundary.from_dict(every.to_dict()) if hasattr(B.Boundary, "from_dict") else None
    if again is not None:
        assert again.format() == text
