"""The clearance's minimum-frequency searches (issue 24.2): a non-monotone V_crit(f) is
reported as what it is (a mode switch, status "not monotone"), not as a minimum; the searches
can be limited to chosen propellers; they run on local processes with the same result, and
resume from their partial-results files without an analysis."""
from __future__ import annotations

from pathlib import Path

import pytest

from propwhirl.io import load_model
from propwhirl.studies import clearance as C
from propwhirl.studies import sweeps
from propwhirl.studies.execution import Checkpoint
from propwhirl.validate import InputError

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def model():
    return load_model(ROOT / "examples" / "wingtip.toml")


def test_a_mode_switch_is_not_reported_as_a_minimum(model):
    """Thesis convention, V_required = 145 m/s: f_theta = 1.36 Hz clears (the critical mode is
    wing 2 at 145.1 m/s), 1.86-3.44 Hz do not (forward 1 at 143-145 m/s), 4.69 Hz and above
    clear: no single minimum frequency."""
    V_req = 145.0
    speeds = C.clearance_speeds(model, V_req)
    q = C.minimum_frequency(model, 0, "f_theta", V_req, speeds, frequency_range=(1.0, 30.0),
                            n_scan=12, frequency_tol=0.01, static_divergence=False,
                            low_speed=False)
    assert q.status == "not monotone"
    assert 3.44 < q.frequency < 4.69 and q.critical_speed > V_req
    assert "not monotone" in q.note and "wing 2 -> forward 1" in q.note and "not a margin" in q.note
    r = C.Clearance("m", V_req / 1.15, 1.15, V_req, True, None, (), (q,), "thesis",
                    (1.0, 351.0), q.analyses + 1)
    text = r.format()
    assert "NOT MONOTONE" in text and "no single minimum" in text
    assert C.Clearance.from_dict(r.to_dict()) == r


def test_propellers_limits_the_searches(model):
    r = C.clearance(model, 100.0, speeds=None, propellers=[1], frequency_range=(5.0, 9.0),
                    n_scan=2, frequency_tol=0.1)
    assert [(q.propeller, q.parameter) for q in r.minimum] == [(1, "f_theta"), (1, "f_psi")]
    with pytest.raises(InputError, match=r"propellers = 2 is invalid: .* are 1"):
        C.clearance(model, 100.0, propellers=[2])


def test_processes_give_the_same_result_and_resume_needs_no_analysis(model, tmp_path,
                                                                     monkeypatch):
    opts = dict(frequency_range=(5.0, 9.0), n_scan=3, frequency_tol=0.05,
                static_divergence=False, low_speed=False)
    one = C.clearance(model, 120.0, **opts)
    cp = Checkpoint(tmp_path / "c.json.partial")
    two = C.clearance(model, 120.0, **opts, processes=2, checkpoint=cp)
    assert two == one
    assert all(c.path.exists() for c in C.phase_checkpoints(cp)[:2])

    def no_analysis(task):
        raise AssertionError("an analysis of a finished point ran again")

    monkeypatch.setattr(sweeps, "_evaluate", no_analysis)
    monkeypatch.setattr(C, "_refine", lambda t: pytest.fail("a refinement ran again"))
    assert C.clearance(model, 120.0, **opts, checkpoint=Checkpoint(cp.path, resume=True)) == one
