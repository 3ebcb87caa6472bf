"""The continuation itself on level functions with known curves (a circle, a parabola, none)."""
from __future__ import annotations

import numpy as np
import pytest

from propwhirl.studies.continuation import ContinuationOptions, Counted, trace
from propwhirl.validate import InputError


def circle(p):
    return float(np.hypot(p[0] - 5.0, p[1] - 5.0) - 3.0)


def test_a_circle_closes_once_on_the_curve():
    tr = trace(circle, [0, 0], [10, 10])
    assert len(tr.branches) == 1           # the diagonal meets it twice: traced once
    b = tr.branches[0]
    assert b.closed and b.stops == ("closed",)
    r = np.hypot(b.points[:, 0] - 5, b.points[:, 1] - 5)
    assert np.max(np.abs(r - 3.0)) < 10 * 1e-4 * 10   # tol 1e-4 of the side (10)
    angles = np.unwrap(np.arctan2(b.points[:, 1] - 5, b.points[:, 0] - 5))
    assert abs(abs(angles[-1] - angles[0]) - 2 * np.pi) < 1e-6   # once around
    assert tr.evaluations < 120


def test_an_open_curve_runs_from_edge_to_edge():
    g = lambda p: p[1] - 0.3 * p[0] ** 2 - 1.0  # noqa: E731
    tr = trace(g, [0, 0], [4, 4])
    (b,) = tr.branches
    assert not b.closed and b.stops == ("bounds", "bounds")
    ends = b.points[[0, -1]]
    np.testing.assert_allclose(sorted(ends[:, 0]), [0.0, np.sqrt(3 / 0.3)], atol=2e-3)
    assert np.max(np.abs([g(p) for p in b.points])) < 2e-3


def test_no_sign_change_no_curve_and_the_count():
    c = Counted(lambda p: 1.0 + p[0] ** 2)
    tr = trace(c, [0, 0], [1, 1], options=ContinuationOptions(n_search=5))
    # 4 search lines x 5 samples, the centre shared by all four (memoised): 20 - 3
    assert tr.branches == () and tr.evaluations == c.calls == 17


def test_bad_bounds_and_nan():
    with pytest.raises(InputError, match="upper > lower"):
        trace(circle, [0, 0], [0, 1])
    with pytest.raises(InputError, match="NaN"):
        trace(lambda p: float("nan"), [0, 0], [1, 1])
