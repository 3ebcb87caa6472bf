"""Following small clusters of roots as a set through branch points on the real axis.

Where roots meet on the real axis — a pair turning real at its square-root branch point, two
real roots merging, a split and a merge in one step — single-root predictions fail.  Small
*clusters* (2–4 roots) are then followed as a set: the coefficients of their characteristic
polynomial are analytic through the branch points, are predicted like single roots, and the
roots of their Hermite interpolant, followed on sub-steps, fix who is who and show that no real
part changes sign inside (:func:`cluster_continuations`, step 3 of the linking of
:mod:`propwhirl.engine.linking`).  Inside a cluster followed as a set, the conventions of
:mod:`propwhirl.engine.ordering` are applied along the followed roots of its interpolated
characteristic polynomial (a pair formed inside a step by roots that were not partners gives
its Im > 0 member to the smaller id, like two real roots merging).  Accepted clusters also
report the unstable pairs that turn real inside them (the tracker brackets those branch
points, :func:`propwhirl.engine.crossings.branch_point_speeds`).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import linear_sum_assignment

from propwhirl.engine.cluster_tables import ClusterTables, frozen as _frozen, cluster_tables as _tables
from propwhirl.engine.hermite import hermite_coeffs, hermite_eval
from propwhirl.engine.nodes import Node
from propwhirl.engine.options import TrackingOptions


def _poly_and_derivative(lam: np.ndarray, dlam: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Coefficients c of Π(z − λ_i) (leading 1 dropped) and their derivatives along V.

    The coefficients of a cluster's characteristic polynomial are analytic in V through the
    branch points where its roots split or merge (single roots have square-root
    singularities there); their derivatives follow from the λ'_i by the product rule.
    ``lam``, ``dlam``: (..., k), a batch of clusters along the leading axes (each one gets
    the same elementwise operations as alone, so the same coefficients bit for bit).
    """
    k = lam.shape[-1]
    z = np.zeros((2,) + lam.shape[:-1] + (k + 1,), dtype=complex)   # z[0]: c, z[1]: dc
    c, dc = z[0], z[1]
    c[..., 0] = 1.0
    for j in range(k):
        # dc ← dc − r·dc⁻ − d·c⁻ and c ← c − r·c⁻ (⁻: shifted by one), as three operations
        r, d = lam[..., j, None], dlam[..., j, None]
        u = d * c[..., :-1]
        z[..., 1:] -= r * z[..., :-1]
        dc[..., 1:] -= u
    return c[..., 1:], dc[..., 1:]


def _cluster_mismatch(ca, dca, cb, dcb, h, scale):
    """Relative mismatch of the trapezoidal prediction of polynomial coefficients (last axis:
    the coefficients; each relative to scale^order and not larger than the change itself)."""
    sc = scale ** _tables(ca.shape[-1]).orders
    change = cb - ca
    mis = np.abs(change - 0.5 * (dca + dcb) * h)
    return (np.minimum(mis, np.abs(change)) / sc).max(axis=-1), mis


def _alternative_mismatches(lam, dlam, cand, dcand, ca, dca, cb, dcb, h, scale):
    """Mismatch of the cluster with one member replaced by another eigenvalue, for every
    member and candidate at both ends at once (:func:`_cluster_mismatch`).

    ``lam``, ``dlam``: (2, k), the cluster's roots at a and at b; ``cand``, ``dcand``:
    (2, n_cand), the other eigenvalues at a and at b; ``ca`` … ``dcb``: the cluster's
    coefficients at both ends.  Returns (2, k, n_cand): at end e, the mismatch with member m
    replaced by candidate j (the other end kept).
    """
    k = lam.shape[-1]
    others = _tables(k).others
    p, dp = _poly_and_derivative(lam[:, others], dlam[:, others])          # (2, k, k − 1)
    # (z − x) Π_others: coefficients [p, 0] − x·[1, p] (leading 1 dropped)
    pe, ps, dpe, dps = np.zeros((4, 2, k, 1, k), dtype=complex)
    pe[..., 0, :-1] = p
    ps[..., 0, 0] = 1.0
    ps[..., 0, 1:] = p
    dpe[..., 0, :-1] = dp
    dps[..., 0, 1:] = dp
    x, dx = cand[:, None, :, None], dcand[:, None, :, None]                 # (2, 1, n, 1)
    c = pe - x * ps
    dc = dpe - x * dps - dx * ps                                            # (2, k, n, k)
    return np.array([_cluster_mismatch(c[0], dc[0], cb, dcb, h, scale)[0],
                     _cluster_mismatch(ca, dca, c[1], dc[1], h, scale)[0]])


def _subspace_mac(Xa: np.ndarray, Xb: np.ndarray, disp: np.ndarray) -> float:
    """Smallest squared cosine of the principal angles between two shape subspaces."""
    Pa, Pb = Xa[disp], Xb[disp]
    if Pa.shape[0] < Pa.shape[1] or np.linalg.norm(Pa) < 1e-5 or np.linalg.norm(Pb) < 1e-5:
        Pa, Pb = Xa, Xb
    Qa, Qb = np.linalg.qr(np.array([Pa, Pb]))[0]      # both in one call (each as alone)
    s = np.linalg.svd(Qa.conj().T @ Qb, compute_uv=False)
    return float(s.min() ** 2)


#: sub-steps on which the interpolated characteristic polynomial of a cluster is followed
_CLUSTER_SUBSTEPS = 32
#: their ends s ∈ [0, 1], and the envelope 16 s²(1 − s)² of the coefficients' uncertainty
_S = _frozen(np.linspace(0.0, 1.0, _CLUSTER_SUBSTEPS + 1))
_S_COL = _frozen(_S[:, None])
_ENV = _frozen(16 * _S ** 2 * (1 - _S) ** 2)


def _interpolated_roots(coeffs, s: float) -> np.ndarray:
    """Roots of the cluster polynomial with Hermite-interpolated (real) coefficients at s."""
    c = hermite_eval(coeffs, s).real
    k = c.size
    comp = np.zeros((k, k))
    comp[0, :] = -c
    if k > 1:
        comp[_tables(k).sub] = 1.0
    return np.linalg.eigvals(comp).astype(complex)


def _n_real_roots(c: np.ndarray) -> int:
    """The number of roots with imaginary part 0 that ``np.roots([1, *c])`` returns (c: real
    coefficients below the leading 1), from the same companion matrix and eigenvalues —
    np.roots drops trailing zero coefficients as zero roots — without its overhead."""
    p = np.concatenate([[1.0], c])
    nz = p.nonzero()[0]
    trailing = p.size - 1 - int(nz[-1])
    p = p[:int(nz[-1]) + 1]
    if p.size == 1:
        return trailing
    A = np.zeros((p.size - 1, p.size - 1))
    A[0, :] = -p[1:] / p[0]
    A[_tables(p.size - 1).sub] = 1.0
    return int(np.count_nonzero(np.linalg.eigvals(A).imag == 0)) + trailing


def _partners(r: np.ndarray) -> np.ndarray:
    """Index of each root's conjugate partner (−1 for a real root)."""
    out = np.full(r.size, -1)
    for i in (r.imag != 0).nonzero()[0]:
        d = np.abs(r - r[i].conjugate())
        d[i] = np.inf
        out[i] = int(d.argmin())
    return out


def _type_kept(im0: np.ndarray, im1: np.ndarray):
    """Whether no root changes type between two orderings (last axis): real stays real and
    complex stays complex with the sign of Im kept.  As one comparison of the signs of Im —
    equal signs imply the same real/complex type, and roots all real at both ends have
    equal (zero) signs — which is exactly (real₀ == real₁).all() and (real₀.all() or
    (sign₀ == sign₁).all()), NaN included (never equal)."""
    return (np.sign(im0) == np.sign(im1)).all(axis=-1)


def _follow_substep(cur, r, s0, s1, coeffs, perms, depth):
    """Continue the roots ``cur`` (at s0) to the roots ``r`` (at s1) by nearest distance, the
    Im > 0 member of a pair turning real taking the larger root; a sub-step in which the
    pairing changes by more than one split or one merge is halved (up to 2⁵ times)."""
    k = cur.size
    nxt = r[perms[int(np.abs(cur[None, :] - r[perms]).sum(axis=1).argmin())]]
    for i in range(k):              # a pair turning real: Im > 0 takes the larger root
        if cur[i].imag > 0 and nxt[i].imag == 0:
            j = int(np.argmin(np.abs(cur - cur[i].conjugate()) + np.where(
                np.arange(k) == i, np.inf, 0.0)))
            if nxt[j].imag == 0 and nxt[j].real > nxt[i].real:
                nxt[i], nxt[j] = nxt[j], nxt[i]
    if _type_kept(cur.imag, nxt.imag) and (cur.imag == 0).sum() >= k - 2:
        return nxt                  # no root changed type: at most one pair, kept
    pc, pn = _partners(cur), _partners(nxt)
    changed = (pc != pn).nonzero()[0]
    clean = changed.size == 0 or (changed.size == 2 and (
        (pc[changed[0]] == changed[1] and (pn[changed] == -1).all())        # one split
        or (pn[changed[0]] == changed[1] and (pc[changed] == -1).all())))   # one merge
    if clean or depth >= 5:
        return nxt
    sm = 0.5 * (s0 + s1)
    mid = _follow_substep(cur, _interpolated_roots(coeffs, sm), s0, sm, coeffs, perms,
                          depth + 1)
    return _follow_substep(mid, r, sm, s1, coeffs, perms, depth + 1)


def _plain_steps(roots: np.ndarray, tab: ClusterTables) -> tuple[np.ndarray, np.ndarray]:
    """Per sub-step m − 1 → m: the nearest assignment of the roots at m − 1 (LAPACK order) to
    those at m (index into ``tab.perms``), and whether the step is *plain* — its nearest
    assignment is unambiguous (the best sum of distances below the second best by far more
    than rounding) and no root changes type (real stays real, Im keeps its sign, at most one
    pair).  For a plain step :func:`_follow_substep` from the roots at m − 1 in *any* order σ
    returns the roots at m in the order σ composed with that assignment (the same sums of
    the same distances, a unique minimum, no pair turning real, the same test of type), so a
    run of plain steps is followed by composing permutations (the assignments found for all
    sub-steps in one vectorised pass).  Row 0 may be the exact roots at the start (the first
    sub-step is then judged from them)."""
    m, k = roots.shape[0] - 1, roots.shape[1]
    perms = tab.perms
    D = np.abs(roots[:-1, :, None] - roots[1:, None, :])                 # (m, k, k)
    cost = D.reshape(m, k * k)[:, tab.gather].sum(axis=2)               # (m, n_perm)
    order = cost.argsort(axis=1)
    best = order[:, 0]
    steps = np.arange(m)
    c0 = cost[steps, best]
    c1 = cost[steps, order[:, 1]] if perms.shape[0] > 1 else np.full(c0.shape, np.inf)
    clear = c1 - c0 > 1e-9 * (c0 + c1 + np.abs(roots[1:]).max(axis=1))
    nxt = roots[1:][steps[:, None], perms[best]]                         # (m, k)
    same = _type_kept(roots[:-1].imag, nxt.imag)
    return best, clear & same & ((roots[:-1].imag == 0).sum(axis=1) >= k - 2)


def _order_of(x: np.ndarray, r: np.ndarray) -> np.ndarray | None:
    """σ with x = r[σ] (x a reordering of the exact values r), or None."""
    eq = x[:, None] == r[None, :]
    if not ((eq.sum(axis=0) == 1).all() and (eq.sum(axis=1) == 1).all()):
        return None
    return eq.argmax(axis=1)


def _follow_substeps(track: np.ndarray, roots: np.ndarray, S: np.ndarray, coeffs,
                     tab: ClusterTables) -> None:
    """Fill ``track[1:]`` (track[0]: the exact roots at the start) by :func:`_follow_substep`
    on every sub-step — runs of plain sub-steps (:func:`_plain_steps`) by composing their
    assignments, which gives the same roots in the same order without a call per sub-step
    (σ kept as its row in ``tab.perms``, composed by table; the plain rows of track written
    at the end in one indexing, the one a call starts from before it).  The first sub-step
    starts from the exact roots track[0] in their own order (σ = the identity, perms[0]):
    plain from them, it is composed like the others."""
    perms, compose = tab.perms, tab.compose
    best, plain = _plain_steps(np.concatenate([track[:1], roots[1:]]), tab)
    best, plain = best.tolist(), plain.tolist()
    sigma = 0                   # track[m - 1] = rows[m - 1][perms[sigma]], when known (rows:
    #                             track[0], then the roots)
    ms: list[int] = []          # plain sub-steps (written into track at the end), their σ
    sigmas: list[int] = []
    for m in range(1, S.size):
        if sigma is not None and plain[m - 1]:
            sigma = compose[best[m - 1]][sigma]
            ms.append(m)
            sigmas.append(sigma)
            continue
        if ms and ms[-1] == m - 1:          # the start of this sub-step, from a plain one
            track[m - 1] = roots[m - 1][perms[sigma]]
        track[m] = _follow_substep(track[m - 1], roots[m], S[m - 1], S[m], coeffs, perms, 0)
        order = _order_of(track[m], roots[m])
        sigma = None if order is None else tab.index[tuple(order.tolist())]
    if ms:
        at = np.array(ms)
        track[at] = roots[at[:, None], perms[np.array(sigmas)]]


def _sign_change_without_branch_point(la: np.ndarray, roots: np.ndarray) -> bool:
    """Whether following the roots from ``la`` over the sub-steps' ``roots`` (rows 1:) must
    find a real part changing sign with no branch point inside — without following them.

    Each row of the followed track is an ordering of that sub-step's roots (row 0: la, no
    real part 0), so a row with another number of roots of Re > 0 than la, or a real part 0,
    has a root whose real part changed sign whatever the order; and a number of real roots
    constant along the rows means no branch point to split at.  :func:`_follow_cluster`
    refuses such a cluster without a split speed either way.
    """
    rows = np.concatenate([la[None], roots[1:]])
    nreal = (rows.imag == 0).sum(axis=1)
    return bool((nreal == nreal[0]).all() and (
        ((rows.real > 0).sum(axis=1) != (la.real > 0).sum()).any() or (rows.real == 0).any()))


def _follow_cluster(ca, dca, cb, dcb, la, lb, h, margin):
    """Follow the roots of a cluster's characteristic polynomial, interpolated in V.

    Each coefficient is the cubic Hermite interpolant of its exact values and derivatives at
    the step's ends; its roots are followed on ``_CLUSTER_SUBSTEPS`` sub-steps by nearest
    continuation (:func:`_follow_substep`: finer where a split and a merge fall into one
    sub-step), a pair turning real giving the larger root to its Im > 0 member (the module's
    convention; merging roots are fixed by branch id later).  Returns (q, events)
    with lb[q[i]] the continuation of la[i] and the unstable pairs of ``la`` that turn real
    inside (s, member, partner, the double root's real part); or (None, s) when the
    interpolated roots change the sign of their real part, come closer to zero than
    ``margin`` × their uncertainty (the coefficients' trapezoidal mismatch δp, spread as
    16 s²(1 − s)²: min(|δp|/|p'|, √(2|δp|/|p''|)) at the root), or end away from the exact
    roots — s ∈ (0, 1) is where to split the step: between a sign change and the nearest
    change of the number of real roots (a branch point), so that the two parts separate them;
    None for the middle.
    """
    k = la.size
    ca, dca, cb, dcb = ca.real, dca.real, cb.real, dcb.real       # conjugation-closed: real
    coeffs = hermite_coeffs(ca, cb, dca, dcb, h)
    tab = _tables(k)
    mis = np.abs(cb - ca - 0.5 * (dca + dcb) * h)     # trapezoidal mismatch of each coefficient
    S = _S
    C = hermite_eval(coeffs, _S_COL)                                    # (m, k)
    comp = np.zeros((S.size, k, k))
    comp[:, 0, :] = -C
    if k > 1:
        comp[(slice(None),) + tab.sub] = 1.0
    roots = np.linalg.eigvals(comp).astype(complex, copy=False)   # real roots exactly real
    sign0 = np.sign(la.real)
    if (sign0 == 0).any() or (np.sign(lb.real) == 0).any():
        return None, None
    if _sign_change_without_branch_point(la, roots):
        return None, None       # as after following the roots (below), without following
    track = np.empty((S.size, k), dtype=complex)
    track[0] = la
    _follow_substeps(track, roots, S, coeffs, tab)
    cur = track[-1]
    flip = (np.sign(track.real) != sign0).any(axis=1)
    if flip.any():     # a real part changes sign: split between it and the nearest branch point
        mc = int(flip.argmax())
        nreal = (track.imag == 0).sum(axis=1)
        ev = (np.diff(nreal) != 0).nonzero()[0] + 0.5          # branch points, in sub-steps
        if ev.size == 0:
            return None, None
        e = ev[np.abs(ev - mc).argmin()]
        return None, float(np.clip(0.5 * (e + mc) / _CLUSTER_SUBSTEPS, 0.05, 0.95))
    # real parts: sign kept, with margin over the uncertainty of the roots: first order
    # |δp(λ)|/|p'(λ)|, or √(2|δp(λ)|/|p''(λ)|) near a double root (where p' → 0)
    full = np.concatenate([np.ones((S.size, 1)), C], axis=1)             # (m, k+1)
    powers = track[:, None, :] ** tab.e1          # λ^(k−1) … λ^0; those of p'' are its rows 1:
    d1 = (full[:, :-1, None] * (tab.w1 * powers)).sum(axis=1)
    d2 = (full[:, :-2, None] * (tab.w2 * powers[:, 1:])).sum(axis=1) \
        if k >= 2 else np.zeros_like(track)
    err = np.abs(sum(mis[q] * track ** (k - 1 - q) for q in range(k)))
    env = _ENV
    with np.errstate(all="ignore"):
        lin = err / np.abs(d1)
        quad = np.sqrt(2 * err / np.abs(d2))
    # p' = p'' = 0 at a root of multiplicity ≥ 3 (e.g. lag roots shared by several nodes):
    # the estimates are unbounded (inf, or 0/0); but the envelope is 0 at the ends, where the
    # roots are the exact ones, so the uncertainty there is 0 — not 0·inf
    # (lin and quad are ≥ 0, +inf or NaN: NaN → inf, as np.nan_to_num(…, nan=inf) would)
    est = np.minimum(lin, quad)
    est = np.where(np.isnan(est), np.inf, est)
    unc = np.multiply(env[:, None], est, out=np.zeros(est.shape), where=env[:, None] > 0)
    if (np.abs(track.real) < margin * unc).any():
        return None, None
    scale = max(float(np.abs(la).max()), float(np.abs(lb).max()), 1e-300)
    cost = np.abs(cur[:, None] - lb[None, :])
    rows, cols = linear_sum_assignment(cost)
    q = cols[rows.argsort()]
    if cost[np.arange(k), q].max() > 1e-6 * scale:
        return None, None
    # unstable pairs of the first sample turning real: (s, member, partner, double root)
    events = []
    for i in ((la.imag > 0) & (la.real > 0)).nonzero()[0]:
        real = (track[:, i].imag == 0).nonzero()[0]
        if real.size:
            m = int(real[0])
            ic = int(np.abs(la - np.conj(la[i])).argmin())
            n_real = int(np.count_nonzero(roots[m - 1].imag == 0))
            lo, hi = S[m - 1], S[m]
            for _ in range(12):        # the interpolated branch point, inside the sub-step
                mid = 0.5 * (lo + hi)
                cm = np.real(hermite_eval(coeffs, mid))
                if _n_real_roots(cm) == n_real:
                    lo = mid
                else:
                    hi = mid
            events.append((0.5 * (lo + hi), int(i), ic,
                           float(0.5 * (track[m - 1, i] + track[m - 1, ic]).real)))
    return q, events


def _closure(seed: set[int], perm: list[int], inv: list[int], conj_a: list[int],
             conj_b: list[int]) -> set[int]:
    """Smallest row set containing ``seed`` closed under conjugation at both ends and perm
    (the index arrays as lists of ints: the assignment, its inverse, the conjugates at a, b)."""
    S = set(seed)
    while True:
        S2 = S | {conj_a[i] for i in S}
        T = {perm[i] for i in S2}
        T |= {conj_b[j] for j in T}
        S2 |= {inv[j] for j in T}
        if S2 == S:
            return S
        S = S2


@dataclass(frozen=True)
class ClusterLinks:
    """What :func:`cluster_continuations` returns: the assignment ``perm`` (b[perm[i]]
    continues a[i]) and the ambiguity flags ``amb`` with the accepted clusters' assignment and
    flags applied (new arrays: the caller's are not changed); the ``clusters`` (raw row indices
    at a); ``split_at``, where to split the step [m/s] or None; and the ``events``, unstable
    pairs turning real inside accepted clusters (speed [m/s], raw rows of the pair at a,
    estimated double root [1/s])."""

    perm: np.ndarray
    amb: np.ndarray
    clusters: tuple[tuple[int, ...], ...]
    split_at: float | None
    events: tuple[tuple[float, int, int, float], ...]


def _first_trials(a: Node, seed: int, base: set[int], bl: np.ndarray, ra: np.ndarray,
                  rb_perm: np.ndarray, mis: np.ndarray, rel_err: np.ndarray,
                  opts: TrackingOptions) -> list[set[int]]:
    """The row sets first tried from one seed's closure ``base`` (rows ``bl``): the closure
    itself when it has a real root (at either end) or a pair near the real axis; complex
    pairs away from the axis only when their prediction fails (with one of the three real
    roots nearest them: a real root may have joined them through branch points); a lone root
    with one of its three nearest others."""
    if not (ra[bl].any() or rb_perm[bl].any() or (np.abs(a.lam[bl].imag) <= mis[bl]).any()):
        if not (rel_err[bl] > opts.dist_max).any():
            return []                                   # a veering, resolved by refinement
        d = np.abs(a.lam[:, None] - a.lam[bl][None, :]).min(axis=1)
        d[~ra] = np.inf
        d[bl] = np.inf
        near = [int(x) for x in d.argsort()[:3] if np.isfinite(d[x])]
        return [base | {x} for x in near]
    if len(base) > 1:
        return [base]
    d = np.abs(a.lam - a.lam[seed])
    d[seed] = np.inf
    return [base | {int(x)} for x in d.argsort()[:3]]


def cluster_continuations(a: Node, b: Node, perm: np.ndarray, amb: np.ndarray,
                          rel_err: np.ndarray, disp: np.ndarray,
                          opts: TrackingOptions) -> ClusterLinks:
    """Follow small clusters of roots as a set where single roots cannot be followed.

    Where roots meet — a pair turning real at its square-root branch point, two real roots
    merging into a pair, a split and a merge in the same step — single-root predictions fail
    although nothing is ambiguous about the set.  The coefficients of the cluster's
    characteristic polynomial Π(z − λ_i) stay analytic there.  Seeds: the ambiguous rows and
    the real roots whose own prediction misses by more than ``dist_max`` (not ambiguous, but
    their Hermite models are useless).  Each seed grows to the smallest row set closed under
    conjugation and under the assignment (then, if needed, by the nearest other roots) up to
    four roots.  Only clusters with a real root at either end, or a pair so close to the real
    axis that its own prediction misses by more than its imaginary part, qualify (complex
    pairs meeting away from the axis are a veering or crossing, resolved by refinement).  A
    cluster is accepted when

    * its coefficients follow their trapezoidal prediction within ``dist_max`` (relative to
      |λ|^order), clearly better (``cost_ratio``) than with any one member replaced by any
      other eigenvalue at either end (a real member not by the other real roots of its sign:
      like single real roots, those are interchangeable — e.g. the aerodynamic lag roots);
    * its shape subspaces at both ends agree (principal angles: MAC ≥ ``mac_min``);
    * the roots of the Hermite-interpolated polynomial, followed on sub-steps
      (:func:`_follow_cluster`), keep the sign of their real parts with ``margin`` to spare
      (a crossing inside is resolved with single roots, by refinement) and end on the exact
      roots — which also fixes who is who inside the cluster.

    Accepted clusters get that assignment and lose their ambiguity flags (in the returned
    copies of ``perm`` and ``amb``); their members are then checked as a cluster, not by the
    per-root Hermite check.  Returns a :class:`ClusterLinks`: those, the clusters (raw row
    indices at a); when a cluster was refused because a root crosses the imaginary axis
    inside the step, a speed where to split the step (between the crossing and the nearest
    branch point) [m/s]; and the unstable pairs that turn real inside accepted clusters
    (estimated speed [m/s], raw rows of the pair at a, estimated double root [1/s]).
    """
    perm, amb = np.array(perm), np.array(amb)
    n = a.lam.size
    h = b.V - a.V
    inv = np.empty(n, dtype=int)
    inv[perm] = np.arange(n)
    ra, rb = a.lam.imag == 0, b.lam.imag == 0
    # real roots badly predicted (not ambiguous) matter only where their Hermite model could
    # come near zero: |Re λ| not clearly above the mismatch at both ends
    mis = rel_err * np.maximum(np.abs(a.lam), a.floor)
    near_zero = np.minimum(np.abs(a.lam.real), np.abs(b.lam[perm].real)) <= 4 * max(
        opts.margin, 1.0) * mis
    bad = ra & rb[perm] & (rel_err > opts.dist_max) & near_zero & ~amb
    seeds = list(amb.nonzero()[0]) + list(bad.nonzero()[0])
    done: set[int] = set()
    lists = [perm.tolist(), inv.tolist(), a.conj.tolist(), b.conj.tolist()]   # for _closure
    out = []
    splits: list[float] = []
    events: list[tuple[float, int, int, float]] = []
    # trials refused in this step, by their rows and columns (a row set can come again from
    # another seed): the same trial gives the same answer
    refused: dict[tuple[tuple[int, ...], tuple[int, ...]], float | None] = {}
    for seed in seeds:
        if int(seed) in done:
            continue
        base = _closure({int(seed)}, *lists)
        done.update(base)
        bl = np.array(sorted(base))
        trials = _first_trials(a, int(seed), base, bl, ra, rb[perm], mis, rel_err, opts)
        tried: set[frozenset[int]] = set()
        # trials: row sets closed when their turn comes (the lists change only when a
        # cluster is accepted, and then the remaining trials are dropped)
        while trials:
            S = _closure(trials.pop(0), *lists)
            if len(S) > 4 or frozenset(S) in tried:
                continue
            tried.add(frozenset(S))
            rows = np.array(sorted(S))
            key = (tuple(rows.tolist()), tuple(perm[rows].tolist()))
            if key in refused:
                q, info = None, refused[key]
            else:
                q, info = _try_cluster(a, b, rows, perm[rows], rel_err[rows], disp, opts, h)
            if q is not None:
                perm[rows] = perm[rows][q]
                inv[perm] = np.arange(n)
                lists[:2] = perm.tolist(), inv.tolist()
                amb[rows] = False
                done.update(S)
                out.append(tuple(int(i) for i in rows))
                for s_ev, i, ic, sig in info:
                    events.append((a.V + s_ev * h, int(rows[i]), int(rows[ic]), sig))
                break
            refused[key] = info
            if info is not None:
                splits.append(a.V + info * h)
            if len(tried) < 4:       # grow by one of the nearest other roots (at a)
                d = np.abs(a.lam[:, None] - a.lam[rows][None, :]).min(axis=1)
                d[rows] = np.inf
                for x in d.argsort()[:3]:
                    trials.append(S | {int(x)})
    return ClusterLinks(perm, amb, tuple(out), min(splits) if splits else None, tuple(events))


def _try_cluster(a: Node, b: Node, rows: np.ndarray, cols: np.ndarray, rel_err: np.ndarray,
                 disp: np.ndarray, opts: TrackingOptions, h: float):
    """The assignment inside an acceptable cluster (see :func:`cluster_continuations`):
    (q, events of :func:`_follow_cluster`) with b[cols[q[i]]] the continuation of a[rows[i]];
    (None, where to split the step or None) if not acceptable."""
    la, da, lb, db = a.lam[rows], a.dlam[rows], b.lam[cols], b.dlam[cols]
    near_axis = np.abs(la.imag) <= rel_err * np.abs(la)
    if not ((la.imag == 0).any() or (lb.imag == 0).any() or near_axis.any()):
        return None, None     # complex pairs only: a veering, resolved by refinement
    scale = max(float(np.abs(la).max()), a.floor)
    k = rows.size
    lam, dlam = np.array([la, lb]), np.array([da, db])                     # (2, k): a, b
    cc, dcc = _poly_and_derivative(lam, dlam)
    ca, cb, dca, dcb = cc[0], cc[1], dcc[0], dcc[1]
    e = float(_cluster_mismatch(ca, dca, cb, dcb, h, scale)[0])
    if not e <= opts.dist_max:
        return None, None
    q, events = _follow_cluster(ca, dca, cb, dcb, la, lb, h, opts.margin)
    if q is None:
        return None, events
    if _subspace_mac(a.X[:, rows], b.X[:, cols], disp) < opts.mac_min:
        return None, None
    n = a.lam.size
    alt = np.inf
    if n > k:
        keep_a, keep_b = np.ones(n, dtype=bool), np.ones(n, dtype=bool)
        keep_a[rows] = keep_b[cols] = False
        cand = np.array([a.lam[keep_a], b.lam[keep_b]])
        dcand = np.array([a.dlam[keep_a], b.dlam[keep_b]])
        mis = _alternative_mismatches(lam, dlam, cand, dcand, ca, dca, cb, dcb, h,
                                      scale)                                 # (2, k, n − k)
        # a real member is interchangeable with the other real roots of its sign (no shape
        # identity is kept between them): they are no competitors
        same_kind = ((lam.imag == 0)[:, :, None] & (cand.imag == 0)[:, None, :]
                     & (np.sign(lam.real)[:, :, None] == np.sign(cand.real)[:, None, :]))
        at_a, at_b = np.where(same_kind, np.inf, mis).min(axis=-1).tolist()
        for ma, mb in zip(at_a, at_b):    # folded member by member, a before b (NaN as before)
            alt = min(alt, ma)
            alt = min(alt, mb)
    if e > opts.cost_ratio * alt:
        return None, None
    return q, events
