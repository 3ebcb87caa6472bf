"""critical_sensitivities refuses, in one line and before building any matrix, what it cannot
differentiate (issue 20.5): an isolated propeller (no full-order pencil), an analysis of another
model — of another size (was a NumPy matmul traceback), of another name, or of a variant of
the same size and name (was a silently wrong result) — and an object that is no analysis."""
from __future__ import annotations

import pytest

from propwhirl.analysis import analyse, critical_sensitivities
from propwhirl.analysis import sensitivity as S
from propwhirl.cases.registry import case_model
from propwhirl.studies import paths as P
from propwhirl.validate import InputError


@pytest.fixture(scope="module")
def wingtip():
    m = case_model("wingtip")
    return m, analyse(m)


@pytest.fixture(scope="module")
def baseline():
    m = case_model("baseline-wing")
    return m, analyse(m)


def _one_line(exc) -> str:
    msg = str(exc.value)
    assert "\n" not in msg and len(msg) < 300, msg
    return msg


@pytest.fixture
def no_pencil(monkeypatch):
    """Counts the pencils built for the differentiation (0 for a refused input)."""
    count = [0]
    real = S.full_order_root

    def counted(*args, **kwargs):
        count[0] += 1
        return real(*args, **kwargs)

    monkeypatch.setattr(S, "full_order_root", counted)
    return count


def test_an_isolated_propeller_is_refused(no_pencil):
    iso = case_model("isolated-propeller")
    with pytest.raises(InputError, match="IsolatedPropeller has none") as exc:
        critical_sensitivities(iso, analyse(iso))
    _one_line(exc)
    assert no_pencil[0] == 0


def test_another_models_analysis_is_refused(wingtip, baseline, no_pencil):
    (w, aw), (b, ab) = wingtip, baseline
    for model, analysis in ((w, ab), (b, aw)):
        with pytest.raises(InputError, match="the analysis is of") as exc:
            critical_sensitivities(model, analysis)
        _one_line(exc)
    # the same name, another size
    renamed = b.with_(name=w.name)
    with pytest.raises(InputError, match="its eigenvectors have 204 states, the model 160"):
        critical_sensitivities(renamed, aw)
    assert no_pencil[0] == 0
    with pytest.raises(InputError, match="must be the ModelAnalysis"):
        critical_sensitivities(w, {"critical": None})


def test_a_variants_analysis_is_refused_not_differentiated(wingtip):
    w, aw = wingtip
    variant = P.set_value(w, "propellers[0].propeller.f_theta", 6.9)   # same size, same name
    with pytest.raises(InputError, match="the analysis is not of this model") as exc:
        critical_sensitivities(variant, aw)
    _one_line(exc)
    # the model's own analysis is still differentiated
    cs = critical_sensitivities(w, aw, params=["propellers[0].propeller.f_theta"])
    assert cs.V == pytest.approx(aw.critical.V)
