"""Analyses of a model with in-plane wing bending (issue 14): the reduced-order path gives
the dense path's critical speeds (its crossings are converged on the full-order model); the
generated parameter derivatives refuse such a model (their assembly has no in-plane DOFs), so
its sensitivities are central differences of its state matrix."""
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


def test_sensitivities_of_an_inplane_model_are_central_differences(model):
    """Issue 34 item 2: no generated in-plane derivatives, so central differences of the state
    matrix (the crossing is a full-order root), said so, and checked against re-analyses."""
    from propwhirl.analysis.sensitivity import critical_sensitivities
    from propwhirl.model.parameter_paths import parameter_paths
    from propwhirl.model.protocol import capabilities
    from propwhirl.studies.sensitivity_check import verify_sensitivities

    c = capabilities(model)
    assert c.supports("sensitivity") and c.derivatives == "central difference"
    assert "EI_chordwise" in c.refusal("exact-sensitivity")
    paths = parameter_paths(model)
    assert {p.derivative for p in paths} == {"central difference"}
    assert [p.path for p in paths] == [p.path for p in parameter_paths(
        model.with_(wing=replace(model.wing, EI_chordwise=None)))]     # the strip wing's paths
    a = analyse(model, speeds=np.arange(10.0, 351.0, 20.0), method="dense")
    flutter = next(e for e in a.events if e.kind == "flutter" and e.event == "onset")
    cs = critical_sensitivities(model, a, flutter, params=["flight.density", "wing.GJ*",
                                                            "propellers[0].propeller.f_theta"])
    assert {s.derivative for s in cs.sensitivities} == {"central difference"}
    check = verify_sensitivities(model, a, cs, method="dense")
    assert check.passed, check.format()
    # 3.6e-3 at most, the dense analyses' crossings moving slightly differently with the
    # parameter, as on the strip wing's exact route (docs/gradients.md); on a 6-element
    # in-plane wing 4e-5
    assert max(abs(x.rel_diff) for x in check.checks) < 5e-3, check.format()
