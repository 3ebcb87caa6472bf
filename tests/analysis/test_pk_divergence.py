"""Divergence in the p-k method (analysis/pk_divergence.py): the sign changes of the p-k
equation's matrix at p = 0.

Before: the p-k sweep followed one root per oscillatory mode, and where a mode's complex pair
split on the real axis it kept the real root moving left, so ``analyse(model, method="pk")``
reported no divergence on ``examples/x57_like.toml`` (default: 226.17 m/s) nor on
``examples/four_propeller.toml`` (default: 334.54 m/s)."""
import numpy as np
import pytest

from propwhirl.analysis import analyse
from propwhirl.analysis.pk import XTOL, pk_sweep
from propwhirl.analysis.pk_divergence import (_scaled_det, divergence_crossings,
                                              static_stiffness)
from propwhirl.io import load_model
from propwhirl.model import FlightCondition

HIGH = np.arange(200.0, 351.0, 10.0)


def _example(name: str, speeds: tuple[float, float, float] | None = None):
    m = load_model(f"examples/{name}.toml")
    if speeds is not None:
        f = m.flight
        m = m.with_(flight=FlightCondition(f.density, f.speed_of_sound, speed_range=speeds))
    return m


@pytest.mark.parametrize("name", ["x57_like", "four_propeller"])
def test_the_static_crossing_is_the_defaults_divergence(name):
    """Divergence is static (k = 0, where the finite-state and exact Theodorsen loads are the
    same): the p-k equation's singular speed is the default's divergence onset."""
    m = _example(name, (200.0, 350.0, 10.0))
    default = [e for e in analyse(m).events if e.kind == "divergence" and e.event == "onset"]
    found = divergence_crossings(m, HIGH, xtol=XTOL)
    assert len(default) == 1 and [c.direction for c in found] == ["onset"]
    assert found[0].V == pytest.approx(default[0].V, abs=2 * XTOL)
    # the matrix at p = 0 is singular there: its scaled determinant changes sign across it
    lo, hi = (_scaled_det(static_stiffness(m, found[0].V + s)) for s in (-XTOL, XTOL))
    assert lo * hi < 0


def test_the_sweep_reports_the_divergence_its_followed_root_misses():
    """x57_like's first followed mode: its pair meets the real axis near 230 m/s and the root
    it keeps moves left (stable); the divergence the other real root makes is reported."""
    m = _example("x57_like")
    V = np.arange(200.0, 251.0, 10.0)
    sw = pk_sweep(m, V, n_modes=1)
    div = [e for e in sw.flutter if e.kind == "divergence"]
    assert [(e.event, e.frequency) for e in div] == [("onset", 0.0)]
    assert div[0].V == pytest.approx(226.17, abs=0.02)
    assert abs(div[0].root) < 1e-2            # the real root through zero


def test_a_divergence_the_sweep_follows_is_reported_once():
    """The wingtip model's divergence at 143.15 m/s is a followed root's own crossing: the
    static check finds the same speed and adds no second event."""
    m = _example("wingtip")
    V = np.arange(120.0, 171.0, 10.0)
    sw = pk_sweep(m, V, n_modes=2)
    div = [e for e in sw.flutter if e.kind == "divergence"]
    static = divergence_crossings(m, V, xtol=XTOL)
    assert len(div) == 1 and len(static) == 1
    assert div[0].V == pytest.approx(static[0].V, abs=2 * XTOL)
    assert div[0].V == pytest.approx(143.152, abs=0.02)


def test_no_static_crossing_where_the_wing_does_not_diverge():
    m = _example("wingtip")
    assert divergence_crossings(m, HIGH, xtol=XTOL) == ()
