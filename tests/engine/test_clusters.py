"""Clusters of roots followed as a set through a split and a merge inside one step."""
from __future__ import annotations

import numpy as np

from propwhirl.engine import analyse

from helpers.engine_systems import cubic_cluster


def test_cluster_followed_through_split_and_merge():
    """A pair turning real and its lower root merging with a real root 0.14 m/s later, inside
    one 49 m/s step: followed as a cluster (coefficients of its characteristic polynomial),
    with the module's conventions — the oscillatory mode keeps the larger root and owns the
    divergence, the merged pair's Im > 0 member goes to the smaller id (the real root's) —
    and no refinement down to the events."""
    an = analyse(cubic_cluster, np.array([91.0, 161.0]), initial_step=None, xtol=0.001)
    sw = an.sweep
    assert sw.unresolved == () and sw.stats["eig"] <= 6
    np.testing.assert_allclose(np.sort_complex(sw.eigenvalues),
                               np.sort_complex(np.linalg.eigvals(cubic_cluster(sw.V))),
                               atol=1e-9)
    assert sw.eigenvalues[0, 0].imag > 0 and sw.eigenvalues[0, 1].imag == 0
    after = np.nonzero((sw.V > 132.2) & (sw.V < 144.3))[0]
    assert after.size
    for t in after:
        assert sw.eigenvalues[t, 0].imag == 0                 # mode 0 owns the real root
        assert sw.eigenvalues[t, 1].imag > 0 and sw.physical[t, 1]   # smaller id: Im > 0
        assert not sw.physical[t, 2]
    (p,) = an.criticals.points
    Vd = np.arange(143.0, 146.0, 1e-4)
    det = np.linalg.det(cubic_cluster(Vd))
    V_exact = Vd[np.nonzero(np.diff(np.sign(det)))[0][0]]
    assert (p.kind, p.direction, p.mode) == ("divergence", "onset", 0)
    assert abs(p.V - V_exact) <= 1e-3 and p.frequency_hz == 0
