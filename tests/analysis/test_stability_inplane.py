"""Analyses of a model with in-plane wing bending (issue 14): the reduced-order path gives
the dense path's critical speeds (its crossings are converged on the full-order model), and
the parameter derivatives refuse such a model (their assembly has no in-plane DOFs)."""
from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from propwhirl.analysis.stability import analyse
from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
from propwhirl.model import derivatives
from propwhirl.validate import InputError


@pytest.fixture(scope="module")
def model():
    m = wingtip_propeller_wing()
    return m.with_(wing=replace(m.wing, EI_chordwise=20 * m.wing.EI))


def test_reduced_equals_dense(model):
    dense = analyse(model, method="dense")
    reduced = analyse(model, method="reduced")
    assert [(e.kind, e.event) for e in reduced.events] == [(e.kind, e.event) for e in dense.events]
    for a, b in zip(reduced.events, dense.events):
        assert a.V == pytest.approx(b.V, abs=0.05)
        assert a.frequency_hz == pytest.approx(b.frequency_hz, abs=1e-3)
    # the chordwise mode takes part: some event's mode is mostly in-plane bending
    assert any(dense.content[e.label].get("chordwise", 0) > 0.5 for e in dense.events)


def test_derivatives_refuse_inplane_models(model):
    with pytest.raises(InputError, match="EI_chordwise"):
        derivatives.derivative_blocks(model, np.array([100.0]))


def test_sensitivities_of_an_inplane_model_are_refused_by_name(model):
    from propwhirl.analysis.sensitivity import critical_sensitivities

    a = analyse(model, speeds=np.arange(10.0, 351.0, 20.0), method="dense")
    with pytest.raises(InputError, match=r"wing.EI_chordwise = .* N m\^2 \(in-plane bending\)"):
        critical_sensitivities(model, a)
