"""Following small clusters of roots as a set through branch points on the real axis.

Where roots meet on the real axis — a pair turning real at its square-root branch point, two
real roots merging, a split and a merge in one step — single-root predictions fail.  Small
*clusters* (2–4 roots) are then followed as a set: the coefficients of their characteristic
polynomial are analytic through the branch points, are predicted like single roots, and the
roots of their Hermite interpolant, followed on sub-steps, fix who is who and show that no real
part changes sign inside (:func:`_cluster_continuations`, step 3 of the linking of
:mod:`propwhirl.engine.linking`).  Inside a cluster followed as a set, the conventions of
:mod:`propwhirl.engine.ordering` are applied along the followed roots of its interpolated
characteristic polynomial (a pair formed inside a step by roots that were not partners gives
its Im > 0 member to the smaller id, like two real roots merging).  Accepted clusters also
report the unstable pairs that turn real inside them (the tracker brackets those branch
points, :func:`propwhirl.engine.crossings._branch_point_speeds`).
"""
from __future__ import annotations

import itertools

import numpy as np
from scipy.optimize import linear_sum_assignment

from propwhirl.engine.hermite import _hermite_coeffs, _hermite_eval
from propwhirl.engine.nodes import _Node
from propwhirl.engine.options import TrackingOptions


def _poly_and_derivative(lam: np.ndarray, dlam: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Coefficients c of Π(z − λ_i) (leading 1 dropped) and their derivatives along V.

    The coefficients of a cluster's characteristic polynomial are analytic in V through the
    branch points where its roots split or merge (single roots have square-root
    singularities there); their derivatives follow from the λ'_i by the product rule.
    """
    k = lam.size
    c = np.zeros(k + 1, dtype=complex)
    dc = np.zeros(k + 1, dtype=complex)
    c[0] = 1.0
    for r, d in zip(lam, dlam):
        dc[1:] = dc[1:] - r * dc[:-1] - d * c[:-1]
        c[1:] = c[1:] - r * c[:-1]
    return c[1:], dc[1:]


def _cluster_mismatch(ca, dca, cb, dcb, h, scale):
    """Relative mismatch of the trapezoidal prediction of polynomial coefficients (last axis:
    the coefficients; each relative to scale^order and not larger than the change itself)."""
    k = ca.shape[-1]
    sc = scale ** np.arange(1, k + 1)
    mis = np.abs(cb - ca - 0.5 * (dca + dcb) * h)
    return np.max(np.minimum(mis, np.abs(cb - ca)) / sc, axis=-1), mis


def _alternative_mismatch(lam_o, dl_o, cand, dcand, c_fix, dc_fix, other_at_a, h, scale):
    """Mismatch with one member replaced by each candidate (vectorised over candidates)."""
    p, dp = _poly_and_derivative(lam_o, dl_o)
    p1 = np.concatenate([[1.0], p])
    dp1 = np.concatenate([[0.0], dp])
    # (z − x) Π_others: coefficients [1, p1 − x·…]
    c = (np.concatenate([p1, [0.0]])[None, :]
         - cand[:, None] * np.concatenate([[0.0], p1])[None, :])[:, 1:]
    dc = (np.concatenate([dp1, [0.0]])[None, :]
          - cand[:, None] * np.concatenate([[0.0], dp1])[None, :]
          - dcand[:, None] * np.concatenate([[0.0], p1])[None, :])[:, 1:]
    if other_at_a:
        return _cluster_mismatch(c, dc, c_fix[None, :], dc_fix[None, :], h, scale)[0]
    return _cluster_mismatch(c_fix[None, :], dc_fix[None, :], c, dc, h, scale)[0]


def _subspace_mac(Xa: np.ndarray, Xb: np.ndarray, disp: np.ndarray) -> float:
    """Smallest squared cosine of the principal angles between two shape subspaces."""
    Pa, Pb = Xa[disp], Xb[disp]
    if Pa.shape[0] < Pa.shape[1] or np.linalg.norm(Pa) < 1e-5 or np.linalg.norm(Pb) < 1e-5:
        Pa, Pb = Xa, Xb
    Qa, _ = np.linalg.qr(Pa)
    Qb, _ = np.linalg.qr(Pb)
    s = np.linalg.svd(Qa.conj().T @ Qb, compute_uv=False)
    return float(np.min(s) ** 2)


#: sub-steps on which the interpolated characteristic polynomial of a cluster is followed
_CLUSTER_SUBSTEPS = 32


def _interpolated_roots(coeffs, s: float) -> np.ndarray:
    """Roots of the cluster polynomial with Hermite-interpolated (real) coefficients at s."""
    c = np.real(_hermite_eval(coeffs, s))
    k = c.size
    comp = np.zeros((k, k))
    comp[0, :] = -c
    if k > 1:
        comp[np.arange(1, k), np.arange(k - 1)] = 1.0
    return np.linalg.eigvals(comp).astype(complex)


def _partners(r: np.ndarray) -> np.ndarray:
    """Index of each root's conjugate partner (−1 for a real root)."""
    out = np.full(r.size, -1)
    for i in np.nonzero(r.imag != 0)[0]:
        d = np.abs(r - r[i].conjugate())
        d[i] = np.inf
        out[i] = int(np.argmin(d))
    return out


def _follow_substep(cur, r, s0, s1, coeffs, perms, depth):
    """Continue the roots ``cur`` (at s0) to the roots ``r`` (at s1) by nearest distance, the
    Im > 0 member of a pair turning real taking the larger root; a sub-step in which the
    pairing changes by more than one split or one merge is halved (up to 2⁵ times)."""
    k = cur.size
    nxt = r[perms[int(np.argmin(np.abs(cur[None, :] - r[perms]).sum(axis=1)))]]
    for i in range(k):              # a pair turning real: Im > 0 takes the larger root
        if cur[i].imag > 0 and nxt[i].imag == 0:
            j = int(np.argmin(np.abs(cur - cur[i].conjugate()) + np.where(
                np.arange(k) == i, np.inf, 0.0)))
            if nxt[j].imag == 0 and nxt[j].real > nxt[i].real:
                nxt[i], nxt[j] = nxt[j], nxt[i]
    real_c, real_n = cur.imag == 0, nxt.imag == 0
    if np.array_equal(real_c, real_n) and (real_c.all() or np.array_equal(
            np.sign(cur.imag), np.sign(nxt.imag))) and real_c.sum() >= k - 2:
        return nxt                  # no root changed type: at most one pair, kept
    pc, pn = _partners(cur), _partners(nxt)
    changed = np.nonzero(pc != pn)[0]
    clean = changed.size == 0 or (changed.size == 2 and (
        (pc[changed[0]] == changed[1] and np.all(pn[changed] == -1))        # one split
        or (pn[changed[0]] == changed[1] and np.all(pc[changed] == -1))))   # one merge
    if clean or depth >= 5:
        return nxt
    sm = 0.5 * (s0 + s1)
    mid = _follow_substep(cur, _interpolated_roots(coeffs, sm), s0, sm, coeffs, perms,
                          depth + 1)
    return _follow_substep(mid, r, sm, s1, coeffs, perms, depth + 1)


def _plain_steps(roots: np.ndarray, perms: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Per sub-step m − 1 → m: the nearest assignment of the roots at m − 1 (LAPACK order) to
    those at m (index into ``perms``), and whether the step is *plain* — its nearest
    assignment is unambiguous (the best sum of distances below the second best by far more
    than rounding) and no root changes type (real stays real, Im keeps its sign, at most one
    pair).  For a plain step :func:`_follow_substep` from the roots at m − 1 in *any* order σ
    returns the roots at m in the order σ composed with that assignment, so a run of plain
    steps is followed by composing permutations (the assignments found for all sub-steps in
    one vectorised pass)."""
    k = roots.shape[1]
    D = np.abs(roots[:-1, :, None] - roots[1:, None, :])                 # (m, k, k)
    cost = D[:, np.arange(k)[None, :], perms].sum(axis=2)               # (m, n_perm)
    order = np.argsort(cost, axis=1)
    best = order[:, 0]
    c0 = np.take_along_axis(cost, order[:, :1], axis=1)[:, 0]
    c1 = (np.take_along_axis(cost, order[:, 1:2], axis=1)[:, 0] if perms.shape[0] > 1
          else np.full(c0.shape, np.inf))
    clear = c1 - c0 > 1e-9 * (c0 + c1 + np.abs(roots).max(axis=1)[1:])
    nxt = np.take_along_axis(roots[1:], perms[best], axis=1)            # (m, k)
    real_c, real_n = roots[:-1].imag == 0, nxt.imag == 0
    same = np.all(real_c == real_n, axis=1) & (
        np.all(real_c, axis=1) | np.all(np.sign(roots[:-1].imag) == np.sign(nxt.imag), axis=1))
    return best, clear & same & (real_c.sum(axis=1) >= k - 2)


def _order_of(x: np.ndarray, r: np.ndarray) -> np.ndarray | None:
    """σ with x = r[σ] (x a reordering of the exact values r), or None."""
    eq = x[:, None] == r[None, :]
    if not (np.all(eq.sum(axis=0) == 1) and np.all(eq.sum(axis=1) == 1)):
        return None
    return np.argmax(eq, axis=1)


def _follow_substeps(track: np.ndarray, roots: np.ndarray, S: np.ndarray, coeffs,
                     perms: np.ndarray) -> None:
    """Fill ``track[1:]`` (track[0]: the exact roots at the start) by :func:`_follow_substep`
    on every sub-step — runs of plain sub-steps (:func:`_plain_steps`) by composing their
    assignments, which gives the same roots in the same order without a call per sub-step."""
    best, plain = _plain_steps(roots, perms)
    sigma = None                       # track[m - 1] = roots[m - 1][sigma], when known
    for m in range(1, S.size):
        if sigma is not None and plain[m - 1]:
            sigma = perms[best[m - 1]][sigma]
            track[m] = roots[m][sigma]
        else:
            track[m] = _follow_substep(track[m - 1], roots[m], S[m - 1], S[m], coeffs, perms, 0)
            sigma = _order_of(track[m], roots[m])


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
    ca, dca, cb, dcb = (np.real(x) for x in (ca, dca, cb, dcb))   # conjugation-closed: real
    coeffs = _hermite_coeffs(ca, cb, dca, dcb, h)
    _, mis = _cluster_mismatch(ca, dca, cb, dcb, h, 1.0)
    S = np.linspace(0.0, 1.0, _CLUSTER_SUBSTEPS + 1)
    C = _hermite_eval(tuple(c[None, :] for c in coeffs), S[:, None])      # (m, k)
    comp = np.zeros((S.size, k, k))
    comp[:, 0, :] = -C
    if k > 1:
        comp[:, np.arange(1, k), np.arange(k - 1)] = 1.0
    roots = np.linalg.eigvals(comp).astype(complex)   # real roots exactly real (LAPACK)
    sign0 = np.sign(la.real)
    if np.any(sign0 == 0) or np.any(np.sign(lb.real) == 0):
        return None, None
    scale = max(float(np.max(np.abs(la))), float(np.max(np.abs(lb))), 1e-300)
    track = np.empty((S.size, k), dtype=complex)
    track[0] = la
    perms = np.array(list(itertools.permutations(range(k))))
    _follow_substeps(track, roots, S, coeffs, perms)
    cur = track[-1]
    # real parts: sign kept, with margin over the uncertainty of the roots: first order
    # |δp(λ)|/|p'(λ)|, or √(2|δp(λ)|/|p''(λ)|) near a double root (where p' → 0)
    full = np.concatenate([np.ones((S.size, 1)), C], axis=1)             # (m, k+1)
    pw = np.arange(k, -1, -1)
    d1 = np.sum(full[:, :-1, None] * (pw[:-1, None] * track[:, None, :] ** np.maximum(
        pw[:-1, None] - 1, 0)), axis=1)
    d2 = np.sum(full[:, :-2, None] * ((pw[:-2] * (pw[:-2] - 1))[:, None] * track[:, None, :]
                                      ** np.maximum(pw[:-2, None] - 2, 0)), axis=1) \
        if k >= 2 else np.zeros_like(track)
    err = np.abs(sum(mis[q] * track ** (k - 1 - q) for q in range(k)))
    env = 16 * S ** 2 * (1 - S) ** 2
    with np.errstate(all="ignore"):
        lin = err / np.abs(d1)
        quad = np.sqrt(2 * err / np.abs(d2))
    # p' = p'' = 0 at a root of multiplicity ≥ 3 (e.g. lag roots shared by several nodes):
    # the estimates are unbounded (inf, or 0/0); but the envelope is 0 at the ends, where the
    # roots are the exact ones, so the uncertainty there is 0 — not 0·inf
    est = np.nan_to_num(np.minimum(lin, quad), nan=np.inf, posinf=np.inf)
    unc = np.multiply(env[:, None], est, out=np.zeros_like(est), where=env[:, None] > 0)
    flip = np.any(np.sign(track.real) != sign0, axis=1)
    thin = np.any(np.abs(track.real) < margin * unc, axis=1)
    if flip.any() or thin.any():
        if not flip.any():
            return None, None
        mc = int(np.argmax(flip))
        nreal = np.sum(track.imag == 0, axis=1)
        ev = np.nonzero(np.diff(nreal) != 0)[0] + 0.5          # branch points, in sub-steps
        if ev.size == 0:
            return None, None
        e = ev[np.argmin(np.abs(ev - mc))]
        return None, float(np.clip(0.5 * (e + mc) / _CLUSTER_SUBSTEPS, 0.05, 0.95))
    cost = np.abs(cur[:, None] - lb[None, :])
    rows, cols = linear_sum_assignment(cost)
    q = cols[np.argsort(rows)]
    if np.max(cost[np.arange(k), q]) > 1e-6 * scale:
        return None, None
    # unstable pairs of the first sample turning real: (s, member, partner, double root)
    events = []
    for i in np.nonzero((la.imag > 0) & (la.real > 0))[0]:
        real = np.nonzero(track[:, i].imag == 0)[0]
        if real.size:
            m = int(real[0])
            ic = int(np.argmin(np.abs(la - np.conj(la[i]))))
            n_real = int(np.count_nonzero(roots[m - 1].imag == 0))
            lo, hi = S[m - 1], S[m]
            for _ in range(12):        # the interpolated branch point, inside the sub-step
                mid = 0.5 * (lo + hi)
                cm = np.real(_hermite_eval(coeffs, mid))
                if np.count_nonzero(np.roots(np.concatenate([[1.0], cm])).imag == 0) == n_real:
                    lo = mid
                else:
                    hi = mid
            events.append((0.5 * (lo + hi), int(i), ic,
                           float(0.5 * (track[m - 1, i] + track[m - 1, ic]).real)))
    return q, events


def _closure(seed: set[int], perm: np.ndarray, inv: np.ndarray, a: _Node, b: _Node) -> set[int]:
    """Smallest row set containing ``seed`` closed under conjugation at both ends and perm."""
    S = set(seed)
    while True:
        S2 = S | {int(a.conj[i]) for i in S}
        T = {int(perm[i]) for i in S2}
        T |= {int(b.conj[j]) for j in T}
        S2 |= {int(inv[j]) for j in T}
        if S2 == S:
            return S
        S = S2


def _cluster_continuations(a: _Node, b: _Node, perm: np.ndarray, amb: np.ndarray,
                           rel_err: np.ndarray, disp: np.ndarray, opts: TrackingOptions):
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

    Accepted clusters get that assignment and lose their ambiguity flags; their members are
    then checked as a cluster, not by the per-root Hermite check.  Returns the clusters (raw
    row indices at a); when a cluster was refused because a root crosses the imaginary axis
    inside the step, a speed where to split the step (between the crossing and the nearest
    branch point) [m/s]; and the unstable pairs that turn real inside accepted clusters
    (estimated speed [m/s], raw rows of the pair at a, estimated double root [1/s]).
    """
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
    seeds = list(np.nonzero(amb)[0]) + list(np.nonzero(bad)[0])
    done: set[int] = set()
    out = []
    splits: list[float] = []
    events: list[tuple[float, int, int, float]] = []
    for seed in seeds:
        if int(seed) in done:
            continue
        base = _closure({int(seed)}, perm, inv, a, b)
        done.update(base)
        bl = np.array(sorted(base))
        if not (np.any(ra[bl]) or np.any(rb[perm[bl]])
                or np.any(np.abs(a.lam[bl].imag) <= mis[bl])):
            # complex pairs away from the real axis: a veering, unless their prediction
            # fails — then a real root may have joined them through branch points
            if not np.any(rel_err[bl] > opts.dist_max):
                continue
            d = np.abs(a.lam[:, None] - a.lam[bl][None, :]).min(axis=1)
            d[~ra] = np.inf
            d[bl] = np.inf
            near = [int(x) for x in np.argsort(d)[:3] if np.isfinite(d[x])]
            trials = [_closure(base | {x}, perm, inv, a, b) for x in near]
        elif len(base) > 1:
            trials = [base]
        else:                                   # a lone root: with one of its nearest others
            d = np.abs(a.lam - a.lam[seed])
            d[seed] = np.inf
            trials = [_closure(base | {int(x)}, perm, inv, a, b) for x in np.argsort(d)[:3]]
        tried: set[frozenset[int]] = set()
        while trials:
            S = trials.pop(0)
            if len(S) > 4 or frozenset(S) in tried:
                continue
            tried.add(frozenset(S))
            rows = np.array(sorted(S))
            q, info = _try_cluster(a, b, rows, perm[rows], rel_err[rows], disp, opts, h)
            if q is not None:
                perm[rows] = perm[rows][q]
                inv[perm] = np.arange(n)
                amb[rows] = False
                done.update(S)
                out.append(tuple(int(i) for i in rows))
                for s_ev, i, ic, sig in info:
                    events.append((a.V + s_ev * h, int(rows[i]), int(rows[ic]), sig))
                break
            if info is not None:
                splits.append(a.V + info * h)
            if len(tried) < 4:       # grow by one of the nearest other roots (at a)
                d = np.abs(a.lam[:, None] - a.lam[rows][None, :]).min(axis=1)
                d[rows] = np.inf
                for x in np.argsort(d)[:3]:
                    trials.append(_closure(S | {int(x)}, perm, inv, a, b))
    return tuple(out), (min(splits) if splits else None), tuple(events)


def _try_cluster(a: _Node, b: _Node, rows: np.ndarray, cols: np.ndarray, rel_err: np.ndarray,
                 disp: np.ndarray, opts: TrackingOptions, h: float):
    """The assignment inside an acceptable cluster (see :func:`_cluster_continuations`):
    (q, events of :func:`_follow_cluster`) with b[cols[q[i]]] the continuation of a[rows[i]];
    (None, where to split the step or None) if not acceptable."""
    la, da, lb, db = a.lam[rows], a.dlam[rows], b.lam[cols], b.dlam[cols]
    near_axis = np.abs(la.imag) <= rel_err * np.abs(la)
    if not (np.any(la.imag == 0) or np.any(lb.imag == 0) or np.any(near_axis)):
        return None, None     # complex pairs only: a veering, resolved by refinement
    scale = max(float(np.max(np.abs(la))), a.floor)
    ca, dca = _poly_and_derivative(la, da)
    cb, dcb = _poly_and_derivative(lb, db)
    e = float(_cluster_mismatch(ca, dca, cb, dcb, h, scale)[0])
    if not e <= opts.dist_max:
        return None, None
    q, events = _follow_cluster(ca, dca, cb, dcb, la, lb, h, opts.margin)
    if q is None:
        return None, events
    if _subspace_mac(a.X[:, rows], b.X[:, cols], disp) < opts.mac_min:
        return None, None
    n = a.lam.size
    oa = np.setdiff1d(np.arange(n), rows)
    ob = np.setdiff1d(np.arange(n), cols)
    alt = np.inf
    for m in range(rows.size if oa.size else 0):
        keep = np.delete(np.arange(rows.size), m)
        # a real member is interchangeable with the other real roots of its sign (no shape
        # identity is kept between them): they are no competitors
        for lam_o, dl_o, other, fix, dfix, at_a, x in (
                (la, da, oa, cb, dcb, True, la[m]), (lb, db, ob, ca, dca, False, lb[m])):
            node = a if at_a else b
            cand = other
            if x.imag == 0:
                cand = other[~((node.lam[other].imag == 0)
                               & (np.sign(node.lam[other].real) == np.sign(x.real)))]
            if cand.size:
                alt = min(alt, float(np.min(_alternative_mismatch(
                    lam_o[keep], dl_o[keep], node.lam[cand], node.dlam[cand], fix, dfix, at_a,
                    h, scale))))
    if e > opts.cost_ratio * alt:
        return None, None
    return q, events
