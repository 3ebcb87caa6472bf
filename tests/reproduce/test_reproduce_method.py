"""The reproduction's analyses are the dense reference (issue 26.1): the default method "auto"
reduces a wing since issue 26, the reproduction names its method (harness.ANALYSIS_METHOD)."""
from __future__ import annotations

from propwhirl.analysis import stability
from propwhirl.reproduce import harness


def test_every_analysis_of_a_reproduced_case_is_dense(monkeypatch):
    seen = []

    def recorder(model, *args, **kwargs):
        seen.append(kwargs.get("method"))
        return real(model, *args, **kwargs)

    real = stability.analyse
    monkeypatch.setattr(stability, "analyse", recorder)
    out = harness.registered_cases()["t10.2"]()
    assert harness.ANALYSIS_METHOD == "dense"
    assert seen == ["dense"]
    assert set(out) == {"t10.2/flutter_speed", "t10.2/flutter_frequency"}
    assert harness.analyse.__doc__ and "ANALYSIS_METHOD" in harness.analyse.__doc__
