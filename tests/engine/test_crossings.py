"""The critical-point refinement: crossings on toy systems with independent answers — flutter
(Routh–Hurwitz), divergence (det K), hump modes and benignity (eq. 5.13), every crossing of
random families (dense sweep) — one default tolerance, frequency-zero events."""
from __future__ import annotations

import inspect
import json

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st_

from propwhirl.analysis.stability import analyse as analyse_model
from propwhirl.engine import (XTOL, FrequencyZero, TrackingOptions, analyse, critical_points,
                              frequency_zero_points, sweep)

from helpers.engine_systems import (HUMP, hump_system, random_family, routh_hurwitz_flutter,
                                    section, toy_fz)


def test_flutter_matches_routh_hurwitz(section_analysis):
    fn, mck, _, an = section_analysis
    V_rh, w_rh = routh_hurwitz_flutter(mck, 1.0, 30.0)
    flutter = [p for p in an.criticals.points if p.kind == "flutter"]
    assert len(flutter) == 1
    p = flutter[0]
    assert p.direction == "onset"
    assert abs(p.V - V_rh) < 1e-3
    assert p.bracket[1] - p.bracket[0] <= 1e-3
    assert abs(2 * np.pi * p.frequency_hz - w_rh) < 1e-5 * w_rh
    assert an.criticals.first_onset is p
    # benignity (5.13) against a brute-force central difference on full eigenvalue sets
    h = 0.01
    lam = np.linalg.eigvals(fn(np.array([p.V - h, p.V + h])))
    crit = lam[np.arange(2), np.argmax(np.where(lam.imag > 0, lam.real, -np.inf), axis=1)]
    dz = np.diff(-crit.real / np.abs(crit))[0] / (2 * h)
    assert p.dzeta_dV < 0 and abs(p.dzeta_dV - dz) < 1e-4 * abs(dz)
    assert p.benignity == pytest.approx(1 / p.dzeta_dV)


def test_divergence_matches_det_K(section_analysis):
    fn, mck, VD, an = section_analysis
    div = [p for p in an.criticals.points if p.kind == "divergence"]
    assert len(div) == 1
    p = div[0]
    assert p.direction == "onset" and abs(p.V - VD) < 1e-3
    assert p.frequency_hz == 0 and p.benignity is None and abs(p.eigenvalue) < 1e-6
    # det K(V) changes sign inside the reported bracket
    dets = [np.linalg.det(mck(v)[2][0]) for v in p.bracket]
    assert dets[0] * dets[1] < 0
    # the pair split into two real roots; the physical mode id kept the larger (crossing) root
    sw = an.sweep
    n_phys = int(sw.physical[0].sum())
    assert p.mode < n_phys and sw.eigenvalues[0, p.mode].imag > 0
    t = np.searchsorted(sw.V, p.V)
    partner = sw.partner[p.mode]
    assert sw.eigenvalues[t, p.mode].imag == 0 and sw.eigenvalues[t, partner].imag == 0
    assert sw.eigenvalues[t, p.mode].real > sw.eigenvalues[t, partner].real
    assert sw.physical[t, partner] and sw.mode_labels[partner] == f"mode {p.mode}'"


def test_divergence_alone_is_critical():
    fn, _, VD = section(x_alpha=-0.2, wa=6.0, zeta=0.05)
    an = analyse(fn, np.arange(1.0, 61.0, 5.0), n_dof=2, xtol=1e-3)
    c = an.criticals.first_onset
    assert c.kind == "divergence" and abs(c.V - VD) < 1e-3


def test_refinement_to_one_hundredth(section_analysis):
    fn, mck, VD, _ = section_analysis
    V_rh, _ = routh_hurwitz_flutter(mck, 1.0, 30.0)
    an = analyse(fn, np.arange(1.0, 61.0, 10.0), n_dof=2, xtol=0.01)
    got = sorted(p.V for p in an.criticals.points)
    assert np.allclose(got, sorted([V_rh, VD]), atol=0.01, rtol=0)
    for p in an.criticals.points:
        assert p.bracket[1] - p.bracket[0] <= 0.01 + 1e-12
        assert p.bracket[0] <= p.V <= p.bracket[1]
    # eigenvalue-only: no full eigendecomposition needed in the refinement, and few solves
    stats = an.criticals.stats
    assert stats.get("fallback_eig", 0) == 0
    assert stats["state_matrix_calls"] <= 12 * len(an.criticals.points)


def test_hump_mode_both_crossings_and_benignity():
    fn = hump_system(**HUMP)
    grid = np.arange(1.0, 102.0, 20.0)        # 41 and 61 bracket the hump at 47.3 … 53.3
    an = analyse(fn, grid, n_dof=2, xtol=1e-3)
    half = np.sqrt((HUMP["beta"] - HUMP["c0"]) / HUMP["gamma"])
    assert len(an.criticals.humps) == 1
    hump = an.criticals.humps[0]
    assert abs(hump.V_onset - (HUMP["Vc"] - half)) < 1e-3
    assert abs(hump.V_recovery - (HUMP["Vc"] + half)) < 1e-3
    assert hump.kind == "flutter"
    assert an.criticals.first_onset.V == pytest.approx(hump.V_onset)
    # ζ = c/(2√k) → dζ/dV = γ (V − Vc)/√k: benignity ∓ √k/(γ·half) = ∓300 m/s
    on, rec = (p for p in an.criticals.points if p.mode == hump.mode)
    expected = np.sqrt(100.0) / (HUMP["gamma"] * half)
    assert on.benignity == pytest.approx(-expected, rel=1e-5)
    assert rec.benignity == pytest.approx(expected, rel=1e-5)
    assert on.frequency_hz == pytest.approx(10 / (2 * np.pi), rel=1e-9)
    assert an.sweep.stats.get("hump_refined", 0) >= 1
    # without the Hermite check the coarse grid never sees the hump
    blind = analyse(fn, grid, n_dof=2, options=TrackingOptions(hump_check=False))
    assert blind.criticals.points == ()


@pytest.mark.parametrize("grid", [[20.0, 50.0, 80.0, 110.0, 140.0], [20.0, 50.0, 80.0, 110.0],
                                  [10.0, 50.0, 200.0]])
def test_hump_whose_crossings_fall_on_grid_speeds(grid):
    """A hump whose onset (and recovery) land exactly on grid speeds: Re λ is zero there, so
    those samples have no sign of their own (−, 0, 0, −).  The unstable band 50–80 m/s was
    reported as no instability at all; the hump check now takes the sign of a zero sample
    from its neighbours and sees the hump from the slopes."""
    def state_matrix(V):
        A = np.zeros((np.size(V), 2, 2))
        A[:, 0, 1] = 1.0
        A[:, 1, 0] = -100.0
        A[:, 1, 1] = 1e-3 * (np.asarray(V) - 50.0) * (80.0 - np.asarray(V))  # ζ < 0 on 50–80
        return A
    an = analyse(state_matrix, np.array(grid), n_dof=1, xtol=1e-3)
    (hump,) = an.criticals.humps
    assert hump.V_onset == pytest.approx(50.0, abs=1e-3)
    assert hump.V_recovery == pytest.approx(80.0, abs=1e-3)
    assert an.criticals.first_onset.V == pytest.approx(50.0, abs=1e-3)


def test_undamped_branch_is_not_refined():
    """A branch with Re λ = 0 at every speed (an undamped mode without aerodynamics) has no
    signed sample: the hump check leaves it alone (no samples added for it)."""
    def state_matrix(V):
        A = np.zeros((np.size(V), 2, 2))
        A[:, 0, 1] = 1.0
        A[:, 1, 0] = -100.0 - np.asarray(V)
        return A
    an = analyse(state_matrix, np.arange(10.0, 101.0, 10.0), n_dof=1)
    assert an.criticals.points == ()
    assert an.sweep.stats.get("hump_refined", 0) == 0


def test_benignity_by_central_difference_on_request(section_analysis):
    """With ``benignity_step`` the benignity is a central difference of ζ (as the thesis),
    agreeing with the default, from dλ/dV at the crossing."""
    fn, _, _, an = section_analysis
    p = [q for q in an.criticals.points if q.kind == "flutter"][0]
    cd = critical_points(an.sweep, fn, benignity_step=0.01, xtol=1e-3)
    q = [r for r in cd.points if r.kind == "flutter"][0]
    assert q.dzeta_dV == pytest.approx(p.dzeta_dV, rel=1e-4)


@settings(max_examples=12, deadline=None)
@given(seed=st_.integers(0, 10_000))
def test_every_crossing_found_against_dense_sweep(seed):
    fn = random_family(seed)
    grid = np.arange(1.0, 60.0, 7.0)
    an = analyse(fn, grid, n_dof=3, xtol=1e-3)
    Vd = np.arange(grid[0], grid[-1], 0.004)
    nun = (np.linalg.eigvals(fn(Vd)).real > 0).sum(axis=1)     # number of unstable roots
    i = np.nonzero(nun[1:] != nun[:-1])[0]
    dense = 0.5 * (Vd[i] + Vd[i + 1])
    found = np.array([p.V for p in an.criticals.points if p.V < Vd[-1]])
    assert found.size == dense.size
    if dense.size:
        assert np.abs(np.sort(found) - dense).max() < 0.01
    net = sum((2 if p.kind == "flutter" else 1) * (1 if p.direction == "onset" else -1)
              for p in an.criticals.points if p.V < Vd[-1])
    assert net == nun[-1] - nun[0]
    # tracked eigenvalues are the eigenvalues; conjugate bookkeeping is exact
    lam = an.sweep.eigenvalues
    ref = np.sort_complex(np.linalg.eigvals(fn(an.sweep.V)))
    np.testing.assert_allclose(np.sort_complex(lam), ref, atol=1e-9)
    assert np.all(an.sweep.physical.sum(axis=1) == (lam.imag >= 0).sum(axis=1))


def test_one_default_tolerance():
    assert XTOL == 0.01
    for fn in (critical_points, frequency_zero_points, analyse, analyse_model):
        assert inspect.signature(fn).parameters["xtol"].default == XTOL, fn


def test_frequency_zero_bracketed_by_exact_eigenvalue_counts():
    grid = np.arange(1.0, 52.0, 10.0)
    sw = sweep(toy_fz, grid)
    for xtol in (XTOL, 1e-4):
        (p,) = frequency_zero_points(sw, toy_fz, xtol=xtol)
        lo, hi = p.bracket
        assert lo < 30.0 < hi and hi - lo <= xtol and p.V == 0.5 * (lo + hi)
        lam = np.linalg.eigvals(toy_fz(np.array([lo, hi])))
        assert np.any((lam[0].real > 0) & (lam[0].imag > 0))        # a pair at lo
        assert not np.any((lam[1].real > 0) & (lam[1].imag > 0))    # real roots at hi
        assert sw.eigenvalues[0, p.mode].real > 0 and p.label == sw.mode_labels[p.mode]
    assert FrequencyZero.from_dict(json.loads(json.dumps(p.to_dict()))) == p


def test_no_frequency_zero_without_an_unstable_toy_fz():
    sw = sweep(toy_fz, np.arange(1.0, 30.0, 7.0))       # ends before 30 m/s
    assert frequency_zero_points(sw, toy_fz) == ()
