"""The critical-point refinement module: one default tolerance, frequency-zero events."""
from __future__ import annotations

import inspect
import json

import numpy as np

from propwhirl.analysis.stability import analyse as analyse_model
from propwhirl.engine import (XTOL, FrequencyZero, analyse, critical_points,
                              frequency_zero_points, sweep)


def pair_turning_real(V):
    """A stable oscillator (−0.2 ± 5i) and an unstable pair 1 ± √(V − 30): it turns into two
    real roots at V = 30 m/s (frequency zero) and its smaller root recovers at 31 m/s."""
    V = np.atleast_1d(np.asarray(V, dtype=float))
    A = np.zeros((V.size, 4, 4))
    A[:, 0, 0] = A[:, 1, 1] = -0.2
    A[:, 0, 1], A[:, 1, 0] = 5.0, -5.0
    A[:, 2, 2] = A[:, 3, 3] = 1.0
    A[:, 2, 3], A[:, 3, 2] = 1.0, V - 30.0
    return A


def test_one_default_tolerance():
    assert XTOL == 0.01
    for fn in (critical_points, frequency_zero_points, analyse, analyse_model):
        assert inspect.signature(fn).parameters["xtol"].default == XTOL, fn


def test_frequency_zero_bracketed_by_exact_eigenvalue_counts():
    grid = np.arange(1.0, 52.0, 10.0)
    sw = sweep(pair_turning_real, grid)
    for xtol in (XTOL, 1e-4):
        (p,) = frequency_zero_points(sw, pair_turning_real, xtol=xtol)
        lo, hi = p.bracket
        assert lo < 30.0 < hi and hi - lo <= xtol and p.V == 0.5 * (lo + hi)
        lam = np.linalg.eigvals(pair_turning_real(np.array([lo, hi])))
        assert np.any((lam[0].real > 0) & (lam[0].imag > 0))        # a pair at lo
        assert not np.any((lam[1].real > 0) & (lam[1].imag > 0))    # real roots at hi
        assert sw.eigenvalues[0, p.mode].real > 0 and p.label == sw.mode_labels[p.mode]
    assert FrequencyZero.from_dict(json.loads(json.dumps(p.to_dict()))) == p


def test_no_frequency_zero_without_an_unstable_pair_turning_real():
    sw = sweep(pair_turning_real, np.arange(1.0, 30.0, 7.0))       # ends before 30 m/s
    assert frequency_zero_points(sw, pair_turning_real) == ()
