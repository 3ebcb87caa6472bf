"""Result types: save / load round trips, a sweep saved without eigenvectors."""
from __future__ import annotations

import json

import numpy as np
import pytest

from propwhirl.engine import Analysis, Sweep, analyse, critical_points
from propwhirl.validate import InputError

from helpers.engine_systems import section


def test_save_load_round_trip(section_analysis):
    an = section_analysis[3]
    text = json.dumps(an.to_dict())
    back = Analysis.from_dict(json.loads(text))
    for name in ("V", "eigenvalues", "eigenvectors", "dlam_dV", "physical", "displacement",
                 "partner", "grid", "floor"):
        np.testing.assert_array_equal(getattr(back.sweep, name), getattr(an.sweep, name))
    assert back.sweep.state_labels == an.sweep.state_labels
    assert back.sweep.mode_labels == an.sweep.mode_labels
    for p, q in zip(back.criticals.points, an.criticals.points):
        assert (p.V, p.kind, p.eigenvalue, p.benignity) == (q.V, q.kind, q.eigenvalue, q.benignity)
        np.testing.assert_array_equal(p.eigenvector, q.eigenvector)
    assert back.criticals.first_onset.V == an.criticals.first_onset.V
    tab = back.sweep.table()
    assert set(tab) == {"V", "mode", "label", "frequency_hz", "damping_ratio", "real", "imag"}
    assert np.all(np.diff(tab["V"]) >= 0) and tab["V"].size == an.sweep.physical.sum()


def test_saved_without_eigenvectors_and_unstable_at_start():
    fn = section()[0]
    an = analyse(fn, np.arange(25.0, 61.0, 5.0), n_dof=2)      # flutter began at 19.66
    unstable = an.criticals.unstable_at_start
    assert len(unstable) == 1 and an.sweep.eigenvalues[0, unstable[0]].imag > 0
    lean = Sweep.from_dict(json.loads(json.dumps(an.sweep.to_dict(include_eigenvectors=False))))
    assert lean.eigenvectors is None
    np.testing.assert_array_equal(lean.eigenvalues, an.sweep.eigenvalues)
    with pytest.raises(InputError, match="without eigenvectors"):
        lean.mode_shape(0, 0)
    with pytest.raises(InputError, match="without them"):
        critical_points(lean, fn)
