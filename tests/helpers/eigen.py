"""Comparing the eigenvalues of two state matrices of one system built two ways (a beam model
and its modal model, a model and the one read back from a file).

The two are the same system in other coordinates, so their eigenvalues agree to rounding — but
to the rounding of each eigenvalue as LAPACK computes it, which differs between platforms
(numpy 1.26 / 2.x, OpenBLAS builds): an error of about eps·‖A‖·κ (κ the eigenvalue's
condition number) in absolute terms.  ‖A‖ is set by the stiffest modes (≈ 2e11 for the
thesis's wings: eps‖A‖ ≈ 4e-5 rad/s), so a root near zero — the divergence root just past
the divergence speed, |λ| ≈ 1 rad/s — is accurate in absolute, not relative terms: measured
6e-7 rad/s on numpy 2.4 (4.9e-7 relative to max(1, |λ|)), and 1.89e-6 relative to
max(1, |λ|) was seen on numpy 1.26
(issue 36, item 2).  So each distance is relative to max(|λ|, :data:`EIGEN_FLOOR`).
"""
from __future__ import annotations

import numpy as np
from scipy.optimize import linear_sum_assignment

#: [rad/s] Below this an eigenvalue's distance counts absolutely: 1e-6 of it is 1e-5 rad/s,
#: 5e-5 m/s on the divergence root's crossing (dλ/dV ≈ 0.2 1/s per m/s near 143 m/s), far
#: below the engine's crossing tolerance (0.01 m/s).
EIGEN_FLOOR = 10.0


def matched_gap(a: np.ndarray, b: np.ndarray, floor: float = EIGEN_FLOOR) -> float:
    """The largest distance between the eigenvalues of square matrices ``a`` and ``b``,
    optimally paired (not sorted: sorting complex numbers pairs near-equal real parts by
    rounding), each relative to max(|λ|, ``floor``)."""
    ea, eb = np.linalg.eigvals(a), np.linalg.eigvals(b)
    d = np.abs(ea[:, None] - eb[None, :]) / np.maximum(floor, np.abs(ea))[:, None]
    r, c = linear_sum_assignment(d)
    return float(d[r, c].max())
