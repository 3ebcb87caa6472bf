"""The gradient and sensitivity-check studies pass one DlmTables to all their analyses, as the
sweeps, maps and campaigns do (issue 37 item 2): the variants of one doublet-lattice planform
then compute their AICs once (on a strip wing the tables are never read)."""
import numpy as np

from propwhirl.analysis import analyse, critical_sensitivities
from propwhirl.cases.ch09_baseline import baseline_propeller, baseline_wing
from propwhirl.model import FlightCondition, Installation, PropellerWing
from propwhirl.model.aerodynamics.dlm import DlmTables
from propwhirl.studies import gradients, sensitivity_check


def small():
    return PropellerWing(baseline_wing(n_elements=4),
                         FlightCondition(0.96287, speed_range=(100.0, 200.0, 20.0)),
                         (Installation(baseline_propeller(), 5.7),))


def recorder(monkeypatch, module):
    seen = []
    real = module.analyse
    monkeypatch.setattr(module, "analyse",
                        lambda *a, **kw: seen.append(kw.get("dlm_tables")) or real(*a, **kw))
    return seen


def test_verify_sensitivities_shares_one_tables(monkeypatch):
    model = small()
    a = analyse(model)
    paths = ["propellers[0].propeller.f_theta", "propellers[0].propeller.f_psi"]
    cs = critical_sensitivities(model, a, params=paths)
    seen = recorder(monkeypatch, sensitivity_check)
    check = sensitivity_check.verify_sensitivities(model, a, cs, params=paths)
    assert check.analyses == 4 and len(seen) == 4
    assert isinstance(seen[0], DlmTables) and all(t is seen[0] for t in seen)


def test_critical_speed_shares_one_tables(monkeypatch):
    seen = recorder(monkeypatch, gradients)
    f = gradients.CriticalSpeed(small(), ("propellers[0].propeller.K_theta",))
    f.value(f.x0)
    f.value(f.x0 * np.array([0.9]))
    assert f.analyses == 2 and len(seen) == 2
    assert seen[0] is f.tables and seen[1] is f.tables
