"""The stability engine on the real model: the wingtip propeller-wing of §10.1 (25 elements,
Leishman–Nguyen, baseline propeller, 1–350 m/s, 204 states), against brute force.

* Every onset/recovery the engine reports coincides (±0.5 m/s) with a change of the number of
  eigenvalues with Re λ > 0 on a dense 0.5 m/s grid of full eigendecompositions, with the right
  sign and size (2 for a complex pair, 1 for a real root), and vice versa; the critical speed
  is the first sign change of max Re λ; frequency-zero events coincide with an unstable pair
  turning into two unstable real roots.
* Each crossing is within 0.01 m/s of its converged value (bisection with full ``eigvals`` to
  1e-4 m/s, :func:`helpers.brute_force.converge_crossing`).
* No mode swaps identity: a thesis-style MAC tracking (§5.2.3) on the dense grid follows the
  seven lowest modes through the same eigenvalues as the engine at its nodes, and every step
  over which a mode's shape changes by more than the engine's MAC threshold (accepted on
  decisive eigenvalue evidence) is confirmed by that dense tracking.
* The names at V = 1 m/s are the thesis's (Table 10.3) with its frequencies, and the whirl
  modes whirl in their named sense.
"""
from __future__ import annotations

import numpy as np
import pytest
from scipy.optimize import linear_sum_assignment
from threadpoolctl import threadpool_limits

from helpers.brute_force import (
    Crossing,
    converge_crossing,
    detect_crossings,
    engine_crossings,
    fixed_grid_sweep,
    match_crossings,
)
from propwhirl.analysis.stability import analyse
from propwhirl.analysis.whirl import whirl_sense
from propwhirl.engine import TrackingOptions, mac
from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
from propwhirl.reproduce.harness import load_references
from propwhirl.analysis.response import rotation_sign

LOW_MODES = ("wing 1", "backward 1", "forward 1", "wing 2", "wing 3", "wing 4", "wing 5")
DENSE_STEP = 0.5        # [m/s]


@pytest.fixture(scope="module")
def model():
    return wingtip_propeller_wing()


@pytest.fixture(scope="module")
def engine(model):
    """The engine on the full-order model (method "dense"), as the dense tracking sees it."""
    with threadpool_limits(limits=1):
        return analyse(model, method="dense")


@pytest.fixture(scope="module")
def dense(model):
    """Full eigendecomposition every 0.5 m/s: all eigenvalues, and the displacement part of
    the eigenvectors of the oscillatory roots below 70 Hz (for the MAC tracking)."""
    V = np.arange(1.0, 350.0 + 1e-9, DENSE_STEP)
    n_dof = model.second_order(np.array([1.0])).n_dof
    lam, cands = [], []
    with threadpool_limits(limits=1):
        for i in range(0, V.size, 25):
            w, X = np.linalg.eig(model.state_matrix(V[i:i + 25]))
            for t in range(w.shape[0]):
                lam.append(w[t])
                sel = np.nonzero((w[t].imag > 0) & (w[t].imag < 2 * np.pi * 70.0))[0]
                cands.append((w[t][sel], X[t][:n_dof][:, sel]))
    return V, np.array(lam), cands


def changes(V, counts):
    """(midpoint [m/s], change) of every interval where an integer count changes."""
    i = np.nonzero(np.diff(counts))[0]
    return [(0.5 * (V[j] + V[j + 1]), int(counts[j + 1] - counts[j])) for j in i]


# ----------------------------------------------------------------------------------------------
# labels (fast)
# ----------------------------------------------------------------------------------------------
def test_names_at_first_speed_are_the_thesis_modes(engine, model):
    sw = engine.sweep
    assert sw.V[0] == 1.0
    lam0 = sw.eigenvalues[0]
    osc = [k for k in range(sw.n_modes) if sw.physical[0, k] and lam0[k].imag > 0]
    osc.sort(key=lambda k: lam0[k].imag)
    assert tuple(sw.mode_labels[k] for k in osc[:7]) == LOW_MODES
    refs = {r.id: r for r in load_references()}
    ids = {"wing 1": "wing1", "backward 1": "backward", "forward 1": "forward", "wing 2": "wing2",
           "wing 3": "wing3", "wing 4": "wing4", "wing 5": "wing5"}
    for k in osc[:7]:
        ref = refs[f"t10.3/{ids[sw.mode_labels[k]]}"]
        assert abs(lam0[k]) / (2 * np.pi) == pytest.approx(ref.thesis, rel=ref.tol)
    # the whirl modes whirl in their named sense (θ–ψ orbit against the rotor's spin)
    th = sw.state_labels.index("propeller 1 theta")
    ps = sw.state_labels.index("propeller 1 psi")
    rot = rotation_sign(model)
    for name in ("backward 1", "forward 1"):
        k = sw.mode_labels.index(name)
        x = sw.eigenvectors[0, :, k]
        assert whirl_sense(x[th], x[ps], rot, lam0[k]) == name.split()[0]


# ----------------------------------------------------------------------------------------------
# crossings against brute force (long: ~10 s of full eigendecompositions)
# ----------------------------------------------------------------------------------------------
@pytest.mark.long
def test_every_crossing_against_the_dense_unstable_count(engine, dense):
    V, lam, _ = dense
    n_plus = (lam.real > 0).sum(axis=1)                 # all roots, conjugates counted apart
    dense_changes = changes(V, n_plus)
    pts = [p for p in engine.criticals.points if p.V <= V[-1]]
    assert pts, "the wingtip model has instabilities in 0-350 m/s (Table 10.4)"
    for p in pts:                                       # engine -> dense
        size = 2 if p.kind == "flutter" else 1
        sign = 1 if p.direction == "onset" else -1
        near = [d for m, d in dense_changes if abs(m - p.V) <= DENSE_STEP]
        assert sign * size in near, (p.label, p.kind, p.direction, p.V, dense_changes)
    for m, d in dense_changes:                          # dense -> engine
        near = [p for p in pts if abs(p.V - m) <= DENSE_STEP]
        assert near, (m, d)
        assert d == sum((2 if p.kind == "flutter" else 1) * (1 if p.direction == "onset" else -1)
                        for p in near)
    # the critical speed: first sign change of max Re λ
    first = np.nonzero(lam.real.max(axis=1) > 0)[0][0]
    crit = engine.critical
    assert crit is not None and abs(crit.V - 0.5 * (V[first - 1] + V[first])) <= DENSE_STEP
    # frequency-zero: an unstable pair turns into two unstable real roots
    cplx = ((lam.real > 0) & (lam.imag != 0)).sum(axis=1)
    real = ((lam.real > 0) & (lam.imag == 0)).sum(axis=1)
    fz_dense = [0.5 * (V[j] + V[j + 1]) for j in range(V.size - 1)
                if cplx[j + 1] == cplx[j] - 2 and real[j + 1] == real[j] + 2]
    fz_engine = [e.V for e in engine.events if e.event == "frequency-zero"]
    assert len(fz_dense) == len(fz_engine)
    for a, b in zip(sorted(fz_engine), sorted(fz_dense)):
        assert abs(a - b) <= DENSE_STEP


@pytest.mark.long
def test_crossings_match_the_thesis_style_detection(engine, dense):
    """The thesis-style fixed-grid detection (sign changes of Re λ between consecutive
    speeds, kind and frequency) finds the same events as the engine, one to one."""
    V, lam, _ = dense
    pairs, e_only, d_only = match_crossings(engine_crossings(engine), detect_crossings(V, lam),
                                            dV=DENSE_STEP)
    assert not e_only and not d_only, (e_only, d_only)
    assert pairs


@pytest.mark.long
def test_onsets_within_a_hundredth_of_the_converged_speed(engine, model):
    for p in engine.criticals.points:
        lo, hi = np.floor(p.V) - 1.0, np.floor(p.V) + 2.0
        Vc, hw = converge_crossing(model.state_matrix, lo, hi)
        assert abs(p.V - Vc) <= 0.01 + hw, (p.label, p.kind, p.V, Vc)
        assert p.bracket[0] - hw <= Vc <= p.bracket[1] + hw


@pytest.mark.long
def test_frequency_zero_within_a_hundredth_of_the_converged_speed(engine, model):
    for e in engine.events:
        if e.event != "frequency-zero":
            continue
        lo, hi = np.floor(e.V) - 1.0, np.floor(e.V) + 2.0
        Vc, hw = converge_crossing(model.state_matrix, lo, hi, complex_only=True)
        assert abs(e.V - Vc) <= 0.01 + hw, (e.label, e.V, Vc)


# ----------------------------------------------------------------------------------------------
# identity
# ----------------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def dense_tracks(engine, dense):
    """§5.2.3 on the dense grid: each of the seven lowest modes followed by an optimal MAC
    assignment among the oscillatory roots below 70 Hz (lost when its pair turns real)."""
    V, _, cands = dense
    sw = engine.sweep
    lam0, X0 = cands[0]
    cur, track = {}, {}
    for lab in LOW_MODES:
        j = int(np.argmin(np.abs(lam0 - sw.eigenvalues[0, sw.mode_labels.index(lab)])))
        cur[lab] = X0[:, j]
        track[lab] = [lam0[j]]
    for t in range(1, V.size):
        lam_c, Xc = cands[t]
        live = [lab for lab in LOW_MODES if len(track[lab]) == t]
        M = mac(np.stack([cur[lab] for lab in live], axis=1), Xc)
        for i, j in zip(*linear_sum_assignment(-M)):
            if M[i, j] >= 0.5:
                cur[live[i]] = Xc[:, j]
                track[live[i]].append(lam_c[j])
    return track


def _agrees(engine, track, lab, ti) -> bool | None:
    """Does the engine's mode `lab` at node ti carry the dense track's eigenvalue?  None when
    not comparable (node off the dense grid, mode not oscillatory, track lost)."""
    sw = engine.sweep
    i = int(round((sw.V[ti] - 1.0) / DENSE_STEP))
    if abs(1.0 + i * DENSE_STEP - sw.V[ti]) > 1e-9:
        return None
    le = sw.eigenvalues[ti, sw.mode_labels.index(lab)]
    if le.imag <= 0 or i >= len(track[lab]):
        return None
    return bool(abs(le - track[lab][i]) <= 1e-6 * abs(le))


@pytest.mark.long
def test_dense_mac_tracking_follows_the_same_branches(engine, dense_tracks):
    """At every engine node on the dense grid, each of the seven lowest modes (where
    oscillatory) carries the eigenvalue the thesis-style dense MAC tracking reaches there."""
    sw = engine.sweep
    compared = 0
    on_grid = 0
    for ti in range(sw.V.size):
        res = [_agrees(engine, dense_tracks, lab, ti) for lab in LOW_MODES]
        if any(r is not None for r in res):
            on_grid += 1
        for lab, r in zip(LOW_MODES, res):
            assert r is not False, (lab, sw.V[ti])
            compared += r is True
    assert on_grid >= 8 and compared >= 5 * on_grid


@pytest.mark.long
def test_shape_changes_between_nodes_are_confirmed_by_dense_tracking(engine, dense_tracks):
    """No mode swaps identity where the shape test cannot tell: every step over which the
    displacement shape of an oscillatory mode changes (consecutive MAC < the engine's
    mac_min — accepted because the eigenvalue evidence alone was decisive, e.g. the whirl
    modes at low speed, whose orbits change with the propeller aerodynamics) is one of the
    lowest modes, and the dense MAC tracking (§5.2.3, 0.5 m/s steps) reaches the engine's
    eigenvalues at both of its nodes."""
    sw = engine.sweep
    lam = sw.eigenvalues
    P = sw.eigenvectors[:, sw.displacement, :]
    num = np.abs(np.einsum("tik,tik->tk", P[:-1].conj(), P[1:])) ** 2
    den = np.sum(np.abs(P[:-1]) ** 2, axis=1) * np.sum(np.abs(P[1:]) ** 2, axis=1)
    mac = num / den
    osc = (lam[:-1].imag > 0) & (lam[1:].imag > 0)
    unresolved = np.zeros(sw.V.size - 1, dtype=bool)
    for a, b in sw.unresolved:
        unresolved |= (sw.V[:-1] >= a) & (sw.V[1:] <= b)
    low = osc & (mac < TrackingOptions().mac_min) & ~unresolved[:, None]
    for t, k in zip(*np.nonzero(low)):
        lab = sw.mode_labels[k]
        assert lab in LOW_MODES, (sw.V[t], lab, mac[t, k])
        ok = _agrees(engine, dense_tracks, lab, t) and _agrees(engine, dense_tracks, lab, t + 1)
        assert ok, (sw.V[t], sw.V[t + 1], lab, mac[t, k])


# ----------------------------------------------------------------------------------------------
# the brute-force helpers themselves, on a family with known events
# ----------------------------------------------------------------------------------------------
def toy(V):
    """Block-diagonal A(V): a pair (V − 10) ± 5i (flutter onset at 10 m/s), a real root
    V − 20 (divergence onset at 20 m/s), a pair 1 ± √(V − 30) (unstable; real beyond 30 m/s —
    a frequency-zero event — and its smaller root recovers through zero at 31 m/s)."""
    V = np.atleast_1d(np.asarray(V, dtype=float))
    A = np.zeros((V.size, 5, 5))
    A[:, 0, 0] = A[:, 1, 1] = V - 10.0
    A[:, 0, 1], A[:, 1, 0] = -5.0, 5.0
    A[:, 2, 2] = V - 20.0
    A[:, 3, 3] = A[:, 4, 4] = 1.0
    A[:, 3, 4], A[:, 4, 3] = 1.0, V - 30.0
    return A


def test_brute_force_helpers_on_known_events():
    from propwhirl.validate import InputError

    res = fixed_grid_sweep(toy, np.arange(1.0, 41.0, 1.0), chunk=7)
    found = {(c.event, c.kind): c for c in res.crossings}
    exact = {("onset", "flutter"): 10.0, ("onset", "divergence"): 20.0,
             ("frequency-zero", "divergence"): 30.0, ("recovery", "divergence"): 31.0}
    assert set(found) == set(exact) and len(res.crossings) == 4
    assert found["onset", "flutter"].V == pytest.approx(10.0)
    assert found["onset", "flutter"].frequency_hz == pytest.approx(5.0 / (2 * np.pi))
    assert found["onset", "divergence"].bracket == (19.0, 20.0) or \
        found["onset", "divergence"].bracket == (20.0, 21.0)
    for key, c in found.items():
        lo, hi = c.bracket[0] - 0.5, c.bracket[1] + 0.5
        Vc, hw = converge_crossing(toy, lo, hi, complex_only=key[0] == "frequency-zero")
        assert abs(Vc - exact[key]) <= hw + 1e-12, key
    eng = [Crossing("flutter", "onset", 10.004, 0.796, (10.0, 10.01)),
           Crossing("divergence", "onset", 19.9, 0.0, (19.8, 20.0))]
    pairs, e_only, r_only = match_crossings(eng, res.crossings)
    assert len(pairs) == 2 and not e_only
    assert sorted(c.event for c in r_only) == ["frequency-zero", "recovery"]
    wrong_f = [Crossing("flutter", "onset", 10.0, 1.5, (10.0, 10.0))]
    assert match_crossings(wrong_f, res.crossings)[1] == wrong_f
    with pytest.raises(InputError, match="not a single crossing"):
        converge_crossing(toy, 11.0, 12.0)
    with pytest.raises(InputError, match="hi > lo"):
        converge_crossing(toy, 12.0, 11.0)
