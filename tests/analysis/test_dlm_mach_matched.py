"""A Mach-matched doublet-lattice onset is the onset at its own Mach (issue 37, item 5).

Between the tables' Mach nodes (0.05 apart) Q is linear in Mach, ~5e-4 of max |Q| from the AICs
at that Mach (Mach 0.6-0.66); on a near-neutral whirl hump that moved the wingtip wing's
forward-whirl onset by metres per second. Every matched crossing is now converged with Q at its
own Mach (``pk.matched_crossing``: the fine columns 0.001 apart around it, within 2e-7 of max
|Q| of that Mach's AICs at Mach 0.6), so the same wing with ``dlm_mach`` fixed at the onset's
V/a has its onset at the same speed.

Tolerance, 2 xtol (0.02 m/s): the fixed-Mach onset is Brent's, within xtol of its root; the
matched one within xtol / 10 of its own (the secant's last step), and a fixed-Mach analysis at
V/a moves by (dV/dM)/a times that error — ~9 on the forward-whirl hump (5.2 m/s per 0.0016 of
Mach), so at most 0.9 xtol; the fine columns' 2e-7 of Q, ~0.002 m/s on that hump. Measured: <= 0.0015 m/s (before: -0.027 m/s for the divergence,
-5.2 m/s for the forward whirl, p-k)."""
import dataclasses

import numpy as np
import pytest

pytest.importorskip("panelaero")

from propwhirl.analysis import analyse  # noqa: E402
from propwhirl.analysis.pk import XTOL, matched_crossing, pk_root  # noqa: E402
from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing  # noqa: E402
from propwhirl.model.aerodynamics.dlm import DlmTables  # noqa: E402

SPEEDS = np.arange(140.0, 231.0, 10.0)


@pytest.fixture(scope="module")
def wing():
    """The thesis's wingtip model on 6 elements and 3 x 8 panels, Mach V/a."""
    m = wingtip_propeller_wing()
    return m.with_(wing=dataclasses.replace(m.wing, n_elements=6, aero="dlm",
                                            dlm_chordwise_panels=3, dlm_spanwise_panels=8))


def onsets(a):
    return {(e.kind, e.label): e.V for e in a.events if e.event == "onset"}


@pytest.mark.parametrize("method, want", [
    ("pk", {("divergence", "wing 1"), ("flutter", "backward 1"), ("flutter", "forward 1")}),
    # the default's modal state space does not cross on the fixed-Mach forward-whirl hump
    # (g within 5e-4 of zero over 40 m/s): the two events it reports at both Machs
    ("auto", {("divergence", "wing 1"), ("flutter", "backward 1")}),
])
def test_matched_onset_is_the_onset_at_its_own_fixed_mach(wing, method, want):
    a_sound = wing.flight.speed_of_sound
    matched = onsets(analyse(wing, SPEEDS, method=method))
    assert want <= set(matched)
    for key in sorted(want):
        V = matched[key]
        fixed = wing.with_(wing=dataclasses.replace(wing.wing, dlm_mach=V / a_sound))
        assert onsets(analyse(fixed, SPEEDS, method=method))[key] == \
            pytest.approx(V, abs=2 * XTOL), key


def test_matched_crossing_is_a_root_at_the_exact_mach(wing):
    """From the interpolated tables' crossing, the secant on the exact-Mach AICs ends where the
    exact-Mach p-k root has Re p within a tenth of xtol's worth of slope; the interpolated
    crossing itself is not such a root (the forward whirl, 5.2 m/s away there)."""
    tables = DlmTables()
    a = analyse(wing, SPEEDS, method="pk", dlm_tables=tables)
    (e,) = [x for x in a.events if x.label == "forward 1" and x.event == "onset"]
    p0 = complex(0.0, 2 * np.pi * e.frequency_hz)
    p_lo, _ = pk_root(wing, e.V - 1.0, p0, tables=tables, own_mach=True)
    p_hi, _ = pk_root(wing, e.V + 1.0, p0, tables=tables, own_mach=True)
    assert p_lo.real < 0 < p_hi.real                       # a crossing within 1 m/s of e.V
    slope = (p_hi.real - p_lo.real) / 2.0
    V, p, _ = matched_crossing(wing, e.V + 0.5, p0, slope, lo=SPEEDS[0], hi=SPEEDS[-1],
                               tables=tables)
    assert abs(V - e.V) <= XTOL / 10 + XTOL / 10          # both within xtol/10 of the root
    assert abs(p.real) <= abs(slope) * XTOL
    p_interp, _ = pk_root(wing, V, p, tables=tables)       # the Mach-interpolated tables
    assert abs(p_interp.real) > 10 * abs(p.real)
