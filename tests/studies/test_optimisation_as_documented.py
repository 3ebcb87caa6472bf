"""studies.gradients (issue 25.7): the stiffness optimisation runs the method asked for, says
plainly whether it cleared (no 3e-6 m/s short reported as a success), stops at once when the
mount cannot move the critical speed, and prints a readable summary; the OpenMDAO names are
the documented rule's.  Work is counted in analyses, never timed."""
import math
import re
from pathlib import Path

import numpy as np
import pytest

from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
from propwhirl.studies import gradients as G
from propwhirl.validate import InputError

DOCS = Path(__file__).resolve().parents[2] / "docs" / "gradients.md"


class Smooth:
    """A stand-in for CriticalSpeed: V(x) smooth, rising with both stiffnesses, counted."""

    paths = ("a", "b")

    def __init__(self, V0: float, gain: float):
        self.x0 = np.array([2.0e4, 5.0e4])
        self.V0, self.gain, self.analyses, self.seen = V0, gain, 0, set()

    def _n(self, x):
        key = tuple(np.round(np.asarray(x, float), 9))
        if key not in self.seen:
            self.seen.add(key)
            self.analyses += 1
        return np.asarray(x, float) / self.x0

    def value(self, x):
        n = self._n(x)
        return self.V0 + self.gain * (np.sqrt(n[0]) - 1.0) + 0.3 * self.gain * (n[1] ** 0.25 - 1.0)

    def gradient(self, x):
        n = self._n(x)
        return self.gain * np.array([0.5 / np.sqrt(n[0]), 0.075 * n[1] ** -0.75]) / self.x0


@pytest.mark.parametrize("target", [120.0, 140.0, 149.5, 150.0, 158.0])
@pytest.mark.parametrize("method", ["exact", "fd"])
def test_cleared_is_what_the_message_says_and_holds_without_tolerance(target, method):
    f = Smooth(150.0, 30.0)
    x, V, msg = G._optimise(f, method, target, G.LOWER_BOUND, G.UPPER_BOUND)
    assert V == pytest.approx(f.value(x * f.x0))
    assert V >= target                        # SLSQP's tolerated violation is not "cleared"
    assert msg.startswith("cleared: ") and f"{V:.3f}" in msg
    assert np.all(x >= G.LOWER_BOUND) and np.all(x <= G.UPPER_BOUND)


def test_a_shortfall_is_said_plainly():
    f = Smooth(100.0, 15.0)                   # even 9 K0 on both gives 133.3 < 149.5 m/s
    x, V, msg = G._optimise(f, "exact", 149.5, G.LOWER_BOUND, G.UPPER_BOUND)
    assert V < 149.5 and msg.startswith("not cleared: ")
    assert f"{149.5 - V:.3g} m/s short" in msg
    assert np.all(x <= G.UPPER_BOUND)         # bounded: never past the model's valid range


@pytest.mark.parametrize("method, analyses", [("exact", 1), ("fd", 3)])
def test_a_critical_speed_the_mount_does_not_move_stops_at_once(method, analyses):
    """The X-57-like model's propeller 7 (issue 25.7: 56 analyses, then a traceback): its
    mount does not move the high-lift propellers' whirl flutter. Here a stand-in of that."""
    f = Smooth(80.0, 1e-3)
    x, V, msg = G._optimise(f, method, 149.5, G.LOWER_BOUND, G.UPPER_BOUND)
    assert f.analyses == analyses
    assert V == 80.0 and np.all(x == 1.0)
    assert msg.startswith("not cleared: V_crit = 80.000 m/s is 69.5 m/s short")
    assert msg.endswith("this mount cannot clear it")
    assert "does not move with these stiffnesses" in msg


@pytest.fixture(scope="module")
def wingtip():
    return wingtip_propeller_wing()


def test_only_the_asked_method_runs_and_the_summary_reads(wingtip):
    """The wing's own static divergence (143.2 m/s) governs with static_divergence=True: no
    mount up to 1.5 K0 clears 149.5 m/s (the gradient says so after one analysis); the exact
    run alone, its analyses counted, its summary plain."""
    r = G.minimum_mount_stiffness(wingtip, 130.0, static_divergence=True, upper=1.5)
    assert r.x_fd is None and r.analyses_fd is None and r.method == "exact"
    assert not r.cleared and r.V < 149.5 and r.message.startswith("not cleared")
    assert r.analyses == 1 and "does not move with these stiffnesses" in r.message
    text = str(r)
    assert text.splitlines()[0] == "stiffness optimisation (exact gradients): NOT cleared"
    assert f"V_crit = {r.V:.3f} m/s, required 149.500 m/s" in text
    assert "  1 analysis\n" in text
    assert "propellers[0].propeller.K_theta = " in text and "× design" in text


@pytest.mark.parametrize("kw, match", [
    (dict(propeller=1), r"propeller = 1 is invalid: must be an index of model.propellers, "
                        r"0 to 0"),
    (dict(gradients="both"), r"gradients = 'both' is invalid"),
    (dict(upper=0.5), r"upper"),
])
def test_bad_options_are_one_line_errors_before_any_analysis(wingtip, kw, match):
    with pytest.raises(InputError, match=match):
        G.minimum_mount_stiffness(wingtip, 130.0, **kw)


def test_a_version_1_file_still_loads(tmp_path):
    p = tmp_path / "o.json"
    p.write_text('{"format": "propwhirl.stiffness-optimisation/1", "paths": ["a.K_theta", '
                 '"a.K_psi"], "x": [1.0, 2.0], "V_m_per_s": 150.0, "objective": 0.9, '
                 '"cleared": true, "message": "ok", "analyses": 6, "x_fd": [1.0, 2.0], '
                 '"analyses_fd": 18}')
    r = G.OptimisationResult.load(p)
    assert r.analyses_fd == 18 and r.target is None and "150.000 m/s" in str(r)
    r2 = G.OptimisationResult.load(r.save(tmp_path / "o2.json"))
    assert r2.analyses_fd == 18 and math.isfinite(r2.V)


def test_openmdao_names_are_the_documented_rule(wingtip):
    """Every `path` → `name` pair of the OpenMDAO section is openmdao_name's, and a component
    over those paths has exactly those inputs (no analysis: setup only)."""
    text = DOCS.read_text(encoding="utf-8")
    section = text[text.index("## OpenMDAO"):]
    pairs = re.findall(r"`([\w.\[\]]+)` →\s*`(\w+)`", section)
    assert len(pairs) >= 3 and ("propellers[6].propeller.f_theta",
                                "propellers_6_propeller_f_theta") in pairs
    for path, name in pairs:
        assert G.openmdao_name(path) == name
    om = pytest.importorskip("openmdao.api")
    paths = ["propellers[0].propeller.f_theta", "wing.EI[3]"]
    comp = G.openmdao_component(wingtip, paths, vd=130.0)
    prob = om.Problem(reports=False)
    prob.model.add_subsystem("whirl", comp)
    prob.setup()
    prob.final_setup()
    inputs = {m["prom_name"] for _, m in comp.list_inputs(out_stream=None, prom_name=True)}
    assert inputs == {"propellers_0_propeller_f_theta", "wing_EI_3"}
    assert comp.input_names == dict(zip(paths, ["propellers_0_propeller_f_theta", "wing_EI_3"]))
