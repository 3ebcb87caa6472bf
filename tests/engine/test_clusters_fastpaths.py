"""The fast paths of engine/clusters.py against their straightforward references, bit for bit.

The batched and vectorised helpers of the cluster follow (one pass over several clusters, every
member's alternatives at once, permutations composed by table, a stacked QR, the real-root
count without np.roots) claim the very same floats as the plain per-item code they replaced;
the references below are that plain code.
"""
from __future__ import annotations

import itertools

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from propwhirl.engine import clusters as cl
from propwhirl.engine.cluster_tables import cluster_tables

SETTINGS = settings(max_examples=150, deadline=None, derandomize=True)


def same_bits(x, y) -> bool:
    x, y = np.asarray(x), np.asarray(y)
    return x.dtype == y.dtype and x.shape == y.shape and x.tobytes() == y.tobytes()


def roots_of(seed: int, k: int, lead: tuple[int, ...] = ()) -> tuple[np.ndarray, np.ndarray]:
    """Eigenvalue-like values (some real, some exact conjugate pairs, some zeros in the
    imaginary part) and derivatives, of shape lead + (k,)."""
    rng = np.random.default_rng(seed)
    shape = lead + (k,)
    mag = 10.0 ** rng.integers(-3, 4, shape)
    lam = (rng.standard_normal(shape) + 1j * rng.standard_normal(shape)
           * (rng.random(shape) < 0.6)) * mag
    dlam = (rng.standard_normal(shape) + 1j * rng.standard_normal(shape)) * 10.0 ** (
        rng.integers(-6, 1, shape))
    return lam, dlam


def poly_reference(lam, dlam):
    """The per-cluster product rule loop."""
    k = lam.size
    c = np.zeros(k + 1, dtype=complex)
    dc = np.zeros(k + 1, dtype=complex)
    c[0] = 1.0
    for r, d in zip(lam, dlam):
        dc[1:] = dc[1:] - r * dc[:-1] - d * c[:-1]
        c[1:] = c[1:] - r * c[:-1]
    return c[1:], dc[1:]


@SETTINGS
@given(seed=st.integers(0, 2**32 - 1), k=st.integers(1, 4), batch=st.integers(1, 5))
def test_batched_polynomial_is_the_per_cluster_loop(seed, k, batch):
    lam, dlam = roots_of(seed, k, (2, batch))
    c, dc = cl._poly_and_derivative(lam, dlam)
    for i, j in itertools.product(range(2), range(batch)):
        c0, dc0 = poly_reference(lam[i, j], dlam[i, j])
        assert same_bits(c[i, j], c0) and same_bits(dc[i, j], dc0)
    c1, dc1 = cl._poly_and_derivative(lam[0, 0], dlam[0, 0])          # unbatched
    assert same_bits(c1, c[0, 0]) and same_bits(dc1, dc[0, 0])


def alternative_reference(lam_o, dl_o, cand, dcand, c_fix, dc_fix, other_at_a, h, scale):
    """One member replaced by each candidate, for one member (the former per-member code)."""
    p, dp = poly_reference(lam_o, dl_o)
    p1 = np.concatenate([[1.0], p])
    dp1 = np.concatenate([[0.0], dp])
    c = (np.concatenate([p1, [0.0]])[None, :]
         - cand[:, None] * np.concatenate([[0.0], p1])[None, :])[:, 1:]
    dc = (np.concatenate([dp1, [0.0]])[None, :]
          - cand[:, None] * np.concatenate([[0.0], dp1])[None, :]
          - dcand[:, None] * np.concatenate([[0.0], p1])[None, :])[:, 1:]
    if other_at_a:
        return cl._cluster_mismatch(c, dc, c_fix[None, :], dc_fix[None, :], h, scale)[0]
    return cl._cluster_mismatch(c_fix[None, :], dc_fix[None, :], c, dc, h, scale)[0]


@SETTINGS
@given(seed=st.integers(0, 2**32 - 1), k=st.integers(2, 4), n_cand=st.integers(1, 7))
def test_vectorised_alternatives_are_the_per_member_loop(seed, k, n_cand):
    lam, dlam = roots_of(seed, k, (2,))
    cand, dcand = roots_of(seed + 1, n_cand, (2,))
    rng = np.random.default_rng(seed)
    h, scale = float(rng.uniform(0.01, 5.0)), float(np.abs(lam[0]).max())
    (ca, cb), (dca, dcb) = cl._poly_and_derivative(lam, dlam)
    mis = cl._alternative_mismatches(lam, dlam, cand, dcand, ca, dca, cb, dcb, h, scale)
    assert mis.shape == (2, k, n_cand)
    for m in range(k):
        keep = np.delete(np.arange(k), m)
        ref_a = alternative_reference(lam[0, keep], dlam[0, keep], cand[0], dcand[0], cb, dcb,
                                      True, h, scale)
        ref_b = alternative_reference(lam[1, keep], dlam[1, keep], cand[1], dcand[1], ca, dca,
                                      False, h, scale)
        assert same_bits(mis[0, m], ref_a) and same_bits(mis[1, m], ref_b)


@SETTINGS
@given(seed=st.integers(0, 2**32 - 1), k=st.integers(1, 4), zeros=st.integers(0, 4))
def test_real_root_count_is_that_of_np_roots(seed, k, zeros):
    rng = np.random.default_rng(seed)
    c = rng.standard_normal(k) * 10.0 ** rng.integers(-2, 3, k)
    c[k - min(zeros, k):] = 0.0                     # trailing zeros: zero roots in np.roots
    if rng.random() < 0.3:
        c = np.round(c)                             # double roots, exactly real ones
    expected = int(np.count_nonzero(np.roots(np.concatenate([[1.0], c])).imag == 0))
    assert cl._n_real_roots(c) == expected


@pytest.mark.parametrize("k", [1, 2, 3, 4, 5])
def test_tables(k):
    tab = cluster_tables(k)
    perms = [tuple(p) for p in itertools.permutations(range(k))]
    assert [tuple(p) for p in tab.perms.tolist()] == perms
    for i, p in enumerate(perms):
        assert tab.index[p] == i
        for j, r in enumerate(perms):
            assert tuple(tab.perms[tab.compose[i][j]]) == tuple(np.array(p)[list(r)])
    assert [sorted(set(range(k)) - set(row)) for row in tab.others.tolist()] == [
        [m] for m in range(k)]
    assert not tab.perms.flags.writeable and not tab.e1.flags.writeable
    D = np.arange(k * k).reshape(k, k)
    assert tab.gather.tolist() == [[D[i, p[i]] for i in range(k)] for p in perms]
    assert cluster_tables(k) is cluster_tables(k) or k > 4     # built once for the sizes that occur


IMAG = st.sampled_from([0.0, -0.0, 1e-300, -1e-300, 2.5, -2.5, np.nan])


@settings(max_examples=400, deadline=None, derandomize=True)
@given(pairs=st.lists(st.tuples(IMAG, IMAG), min_size=1, max_size=5))
def test_type_kept_is_the_former_test(pairs):
    im0, im1 = (np.array(x) for x in zip(*pairs))
    real0, real1 = im0 == 0, im1 == 0
    former = bool(np.array_equal(real0, real1) and (real0.all() or np.array_equal(
        np.sign(im0), np.sign(im1))))
    assert bool(cl._type_kept(im0, im1)) is former
    both = cl._type_kept(np.array([im0, im1]), np.array([im1, im1]))     # along the last axis
    assert both.tolist() == [former, bool(cl._type_kept(im1, im1))]


def plain_reference(roots, perms):
    """The former formulation of _plain_steps (type kept: real ↔ real and Im sign kept)."""
    k = roots.shape[1]
    D = np.abs(roots[:-1, :, None] - roots[1:, None, :])
    cost = D[:, np.arange(k)[None, :], perms].sum(axis=2)
    order = np.argsort(cost, axis=1)
    best = order[:, 0]
    c0 = np.take_along_axis(cost, order[:, :1], axis=1)[:, 0]
    c1 = (np.take_along_axis(cost, order[:, 1:2], axis=1)[:, 0] if perms.shape[0] > 1
          else np.full(c0.shape, np.inf))
    clear = c1 - c0 > 1e-9 * (c0 + c1 + np.abs(roots).max(axis=1)[1:])
    nxt = np.take_along_axis(roots[1:], perms[best], axis=1)
    real_c, real_n = roots[:-1].imag == 0, nxt.imag == 0
    same = np.all(real_c == real_n, axis=1) & (
        np.all(real_c, axis=1) | np.all(np.sign(roots[:-1].imag) == np.sign(nxt.imag), axis=1))
    return best, clear & same & (real_c.sum(axis=1) >= k - 2)


def random_coeffs(seed: int, k: int):
    """Hermite coefficient tuples of a real monic polynomial of degree k whose roots move,
    split and merge over s ∈ [0, 1]."""
    rng = np.random.default_rng(seed)
    return tuple(rng.standard_normal(k) * s for s in (1.0, 1.5, 2.0, 1.0))


def interpolated(coeffs):
    C = cl.hermite_eval(tuple(c[None, :] for c in coeffs), cl._S[:, None])
    k = C.shape[1]
    comp = np.zeros((cl._S.size, k, k))
    comp[:, 0, :] = -C
    if k > 1:
        comp[:, np.arange(1, k), np.arange(k - 1)] = 1.0
    return np.linalg.eigvals(comp).astype(complex)


@SETTINGS
@given(seed=st.integers(0, 2**32 - 1), k=st.integers(1, 4))
def test_plain_steps_as_formulated_before(seed, k):
    roots = interpolated(random_coeffs(seed, k))
    tab = cluster_tables(k)
    best, plain = cl._plain_steps(roots, tab)
    best0, plain0 = plain_reference(roots, tab.perms)
    assert same_bits(plain, plain0)
    assert same_bits(best[plain], best0[plain0])


def follow_substep_reference(cur, r, s0, s1, coeffs, perms, depth):
    """The former _follow_substep (its test for a sub-step without a change of type)."""
    k = cur.size
    nxt = r[perms[int(np.argmin(np.abs(cur[None, :] - r[perms]).sum(axis=1)))]]
    for i in range(k):
        if cur[i].imag > 0 and nxt[i].imag == 0:
            j = int(np.argmin(np.abs(cur - cur[i].conjugate()) + np.where(
                np.arange(k) == i, np.inf, 0.0)))
            if nxt[j].imag == 0 and nxt[j].real > nxt[i].real:
                nxt[i], nxt[j] = nxt[j], nxt[i]
    real_c, real_n = cur.imag == 0, nxt.imag == 0
    if np.array_equal(real_c, real_n) and (real_c.all() or np.array_equal(
            np.sign(cur.imag), np.sign(nxt.imag))) and real_c.sum() >= k - 2:
        return nxt
    pc, pn = cl._partners(cur), cl._partners(nxt)
    changed = np.nonzero(pc != pn)[0]
    clean = changed.size == 0 or (changed.size == 2 and (
        (pc[changed[0]] == changed[1] and np.all(pn[changed] == -1))
        or (pn[changed[0]] == changed[1] and np.all(pc[changed] == -1))))
    if clean or depth >= 5:
        return nxt
    sm = 0.5 * (s0 + s1)
    mid = follow_substep_reference(cur, cl._interpolated_roots(coeffs, sm), s0, sm, coeffs,
                                   perms, depth + 1)
    return follow_substep_reference(mid, r, sm, s1, coeffs, perms, depth + 1)


def follow_substeps_reference(start, roots, coeffs, perms):
    """Every sub-step by the former _follow_substep, one after the other."""
    track = np.empty(roots.shape, dtype=complex)
    track[0] = start
    S = cl._S
    for m in range(1, S.size):
        track[m] = follow_substep_reference(track[m - 1], roots[m], S[m - 1], S[m], coeffs,
                                            perms, 0)
    return track


@SETTINGS
@given(seed=st.integers(0, 2**32 - 1), k=st.integers(1, 4), jitter=st.booleans())
def test_substeps_composed_by_table_are_the_step_by_step_follow(seed, k, jitter):
    coeffs = random_coeffs(seed, k)
    roots = interpolated(coeffs)
    start = roots[0][np.random.default_rng(seed).permutation(k)]
    if jitter:                 # the exact roots at the start are not the interpolated ones
        start = start * (1 + 1e-12) + 1e-13
    tab = cluster_tables(k)
    track = np.empty(roots.shape, dtype=complex)
    track[0] = start
    cl._follow_substeps(track, roots, cl._S, coeffs, tab)
    assert same_bits(track, follow_substeps_reference(start, roots, coeffs, tab.perms))


@SETTINGS
@given(seed=st.integers(0, 2**32 - 1), k=st.integers(1, 4), n=st.integers(2, 12),
       tiny=st.booleans())
def test_subspace_mac_with_a_stacked_qr(seed, k, n, tiny):
    rng = np.random.default_rng(seed)
    Xa = rng.standard_normal((n, k)) + 1j * rng.standard_normal((n, k))
    Xb = Xa + 0.1 * (rng.standard_normal((n, k)) + 1j * rng.standard_normal((n, k)))
    disp = rng.random(n) < 0.6
    if tiny:
        Xa[disp] *= 1e-7                    # displacement rows too small: the whole shapes
    Pa, Pb = Xa[disp], Xb[disp]
    if Pa.shape[0] < Pa.shape[1] or np.linalg.norm(Pa) < 1e-5 or np.linalg.norm(Pb) < 1e-5:
        Pa, Pb = Xa, Xb
    Qa, _ = np.linalg.qr(Pa)
    Qb, _ = np.linalg.qr(Pb)
    ref = float(np.min(np.linalg.svd(Qa.conj().T @ Qb, compute_uv=False)) ** 2)
    assert same_bits(cl._subspace_mac(Xa, Xb, disp), ref)


@pytest.mark.parametrize("k", [1, 2, 3, 4])
def test_sign_change_without_branch_point_is_what_the_followed_track_shows(k):
    """The early refusal of _follow_cluster (a real part changes sign, the number of real
    roots never changes) only where following the roots would refuse the same way — and it
    does fire (the test is not vacuous)."""
    fired = refused = 0
    for seed in range(300):
        coeffs = random_coeffs(seed, k)
        roots = interpolated(coeffs)
        start = roots[0][np.random.default_rng(seed).permutation(k)]
        if (start.real == 0).any():          # refused before, by _follow_cluster itself
            continue
        track = np.empty(roots.shape, dtype=complex)
        track[0] = start
        cl._follow_substeps(track, roots, cl._S, coeffs, cluster_tables(k))
        flip = bool((np.sign(track.real) != np.sign(start.real)).any())
        no_branch_point = bool((np.diff((track.imag == 0).sum(axis=1)) == 0).all())
        early = cl._sign_change_without_branch_point(start, roots)
        assert not early or (flip and no_branch_point)
        fired += early
        refused += flip and no_branch_point
    assert fired >= 0.8 * refused and fired > 0
