"""pk_crossing's Brent bracket keeps its mode (issue 37 item 2, found on x57_like with
aero = "dlm": "ValueError: f(a) and f(b) must have different signs" from inside brentq).

The bracket [a, b] is found with each end's root continued outward; Brent's method then
re-solved every speed from the left end's root, and at the right end a mode whose frequency
moved far (here 2 Hz-ish over the bracket) was re-found as another, nearer root of the other
sign. Each speed now starts from the root interpolated between the two ends'."""
from types import SimpleNamespace

import pytest

from propwhirl.analysis import pk_crossings as pk   # where the crossings are refined


def two_modes(model, V, p0, **_):
    """Roots of two modes at V [m/s]: A crosses Re p = 0 at 100 m/s while its frequency
    moves 1 rad/s per m/s; B is stable at 5.2 rad/s. The root nearest ``p0`` is returned, as
    the p-k iteration converges to the root nearest its start."""
    A = complex(0.01 * (V - 100.0), 5.0 + (V - 99.0))
    B = complex(-1.0, 5.2)
    p = A if abs(A - p0) <= abs(B - p0) else B
    return p, abs(p.imag) * 0.5 / V


def test_the_bracket_ends_keep_their_mode(monkeypatch):
    monkeypatch.setattr(pk, "pk_root", two_modes)
    c = pk.pk_crossing(SimpleNamespace(), 100.0, complex(0.0, 6.0), lo=90.0, hi=110.0,
                       xtol=1e-9)
    assert c.direction == "onset"
    assert c.V == pytest.approx(100.0, abs=1e-8)
    assert c.p == pytest.approx(complex(0.0, 6.0), abs=1e-8)        # mode A, not B
