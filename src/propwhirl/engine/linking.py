"""Linking two consecutive speeds: which root at one speed continues which at the next.

The prediction of a branch over a step is trapezoidal, ``λ_b ≈ λ_a + ½(λ'_a + λ'_b) ΔV``
(λ' = dλ/dV of :mod:`propwhirl.engine.nodes`).  Linking two speeds (:func:`link_nodes`):

1. branches whose best candidate by prediction is mutual, close, with a MAC of the
   displacement part (eq. 5.14 in its Hermitian form, :func:`~propwhirl.engine.eigensolve.mac`)
   ≥ ``mac_min`` and clearly better than any other candidate are matched directly; so are
   those whose eigenvalue evidence alone is *decisive* (``decisive_ratio``: the shape may
   change a lot along V while the continuation is unique);
2. the rest by an optimal (Hungarian, :func:`scipy.optimize.linear_sum_assignment`)
   assignment on the cost (1 − MAC) + prediction distance, with the runner-up tests;
   real roots that stay real with the same sign need no shape identity (their crossings
   are found from signs, a real root through zero being checked by sign det A) and are
   matched by distance alone, never flagged;
3. where roots meet on the real axis — a pair turning real at its square-root branch point,
   two real roots merging, a split and a merge in one step — single-root predictions fail;
   small *clusters* (2–4 roots) are then followed as a set: the coefficients of their
   characteristic polynomial are analytic through the branch points, are predicted like
   single roots, and the roots of their Hermite interpolant, followed on sub-steps, fix
   who is who and show that no real part changes sign inside
   (:func:`propwhirl.engine.clusters.cluster_continuations`);
4. two complex branches whose paths (straight from the first sample, or the Hermite curves
   through both) approach each other inside the step mark it as an unresolved veering or
   crossing (:func:`_approach`).

*Identity through veering/crossing.*  A mode's identity is the analytic continuation of its
(eigenvalue, eigenvector) branch at the resolved step.  Pairs of complex eigenvalues whose
predicted paths approach within the step are refined until the step resolves the approach,
so a veering is followed along its branch (the shape rotates) while a true crossing
(decoupled modes) keeps each shape.  A veering is resolved only down to ``min_step``; one
narrower than that is treated like a crossing.  Repeated eigenvalues (degenerate within
``degenerate_tol``) have no defined shape identity; they are tracked by eigenvalue.
"""
from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from scipy.optimize import linear_sum_assignment

from propwhirl.engine.clusters import cluster_continuations
from propwhirl.engine.hermite import CHECK_S, hermite_coeffs, hermite_eval
from propwhirl.engine.nodes import Node
from propwhirl.engine.options import TrackingOptions


def _mac_matrix(Xa: np.ndarray, Xb: np.ndarray, disp: np.ndarray) -> np.ndarray:
    """MAC between all columns, on the displacement rows; full vectors where those vanish."""
    Pa, Pb = Xa[disp], Xb[disp]
    na = np.sum(np.abs(Pa) ** 2, axis=0)
    nb = np.sum(np.abs(Pb) ** 2, axis=0)
    m = np.abs(Pa.conj().T @ Pb) ** 2
    den = na[:, None] * nb[None, :]
    m = np.divide(m, den, out=np.zeros_like(m), where=den > 0)
    small_a, small_b = na < 1e-10, nb < 1e-10
    if small_a.any() or small_b.any():
        ia, ib = np.nonzero(small_a)[0], np.nonzero(small_b)[0]
        for rows, cols in ((ia, slice(None)), (slice(None), ib)):
            xa, xb = Xa[:, rows], Xb[:, cols]
            m[rows, cols] = np.abs(xa.conj().T @ xb) ** 2 / (
                np.sum(np.abs(xa) ** 2, axis=0)[:, None]
                * np.sum(np.abs(xb) ** 2, axis=0)[None, :])
    return m


def _mac_columns(Xa: np.ndarray, Xb: np.ndarray, disp: np.ndarray) -> np.ndarray:
    """MAC of corresponding columns (Xa[:, i] with Xb[:, i]), as :func:`_mac_matrix`."""
    Pa, Pb = Xa[disp], Xb[disp]
    na = np.sum(np.abs(Pa) ** 2, axis=0)
    nb = np.sum(np.abs(Pb) ** 2, axis=0)
    num = np.abs(np.sum(Pa.conj() * Pb, axis=0)) ** 2
    den = na * nb
    m = np.divide(num, den, out=np.zeros_like(num), where=den > 0)
    small = (na < 1e-10) | (nb < 1e-10)
    if small.any():
        xa, xb = Xa[:, small], Xb[:, small]
        m[small] = np.abs(np.sum(xa.conj() * xb, axis=0)) ** 2 / (
            np.sum(np.abs(xa) ** 2, axis=0) * np.sum(np.abs(xb) ** 2, axis=0))
    return m


def _near(lam: np.ndarray, conj: np.ndarray, scale: np.ndarray, tol: float,
          rows: np.ndarray) -> np.ndarray:
    """For each of ``rows``: another eigenvalue (not the conjugate) within tol·scale?"""
    d = np.abs(lam[rows, None] - lam[None, :])
    r = np.arange(rows.size)
    d[r, rows] = np.inf
    d[r, conj[rows]] = np.inf
    return (d <= tol * scale[rows, None]).any(axis=1)


#: a root with Re λ < 0 and |Im λ| ≤ SINK_IM · |Re λ| (damping ratio ζ ≥ 0.99995: a period
#: over 600 times its decay time) is treated like a real root of its sign (:func:`_sink`)
SINK_IM = 1e-2


def _sink(lam: np.ndarray) -> np.ndarray:
    """Roots that are non-oscillatory for stability tracking: Re λ < 0 and |Im λ| at most
    :data:`SINK_IM` · |Re λ| (exactly real negative roots included).

    Heavily over-damped modes give them: with stiffness-proportional Rayleigh damping
    C = μM + λK every mode of ω > 2/λ is over-damped, and its slow root tends to −1/λ —
    with λ = 1 s the wing's twenty-odd bending and torsion modes leave a near-multiple root
    at −1 s⁻¹, split by rounding into real roots and pairs of |Im λ| ~ 1e-9 … 1e-3.  Their
    shapes there are arbitrary combinations and no assignment among them is better than
    another, so a shape or distance test would flag every step (and refine it to
    ``min_step`` without end).  Like real roots of one sign (which carry no shape
    identity, :func:`link_nodes`), they are matched by distance alone and never flagged: which
    of them continues which does not change a sign of Re λ.
    """
    return (lam.real < 0) & (np.abs(lam.imag) <= SINK_IM * np.abs(lam.real))


def _free_columns(n: int, taken: np.ndarray) -> np.ndarray:
    """The columns 0..n-1 not in ``taken``, increasing (``np.setdiff1d(np.arange(n), taken)``
    by a mask, without its sort)."""
    used = np.zeros(n, dtype=bool)
    used[taken] = True
    return np.nonzero(~used)[0]


def _upper_pairs(cand: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Indices (i, k), i < k, of the True entries of a square boolean matrix in row-major
    order (``np.nonzero(np.triu(cand, 1))``, without forming the triangle)."""
    i, k = np.nonzero(cand)
    upper = i < k
    return i[upper], k[upper]


@dataclass
class Link:
    """Assignment raw(a) → raw(b) of one step and what the sweep needs to know about it.

    err:   absolute uncertainty of each a-row's continuation [1/s]: the mismatch of its
           trapezoidal prediction.
    clusters: roots followed as a set over the step (through branch points, see
           :func:`cluster_continuations`), raw indices at a; checked as a cluster, so left
           out of the per-root Hermite check.
    split_at: where to refine an ambiguous step other than its middle [m/s] (see
           :func:`cluster_continuations`).
    branch_points: unstable pairs turning real inside the step, estimated from accepted
           clusters: (V [m/s], raw rows at a, double root [1/s]).
    """

    perm: np.ndarray
    ambiguous: bool
    err: np.ndarray
    clusters: tuple[tuple[int, ...], ...] = ()
    split_at: float | None = None
    branch_points: tuple[tuple[float, int, int, float], ...] = ()


def link_nodes(a: Node, b: Node, disp: np.ndarray, opts: TrackingOptions) -> Link:
    """Optimal assignment raw(a) → raw(b) and whether it is ambiguous (see TrackingOptions).

    1. Branches whose best candidate by eigenvalue prediction is mutual, close, with a MAC
       above ``mac_min`` (complex) and clearly better than any other candidate (its cost below
       ``cost_ratio`` × the runner-up's distance, a lower bound of the runner-up's cost) are
       matched directly — they are unambiguous under the full test too — and so are those
       whose eigenvalue evidence alone is decisive (``decisive_ratio``).
    2. The rest go through an optimal (Hungarian) assignment on the full cost, MAC included,
       and the runner-up tests.  Real roots at both ends with the same sign of Re λ need no
       shape identity (the crossing detection only needs the sign; a real root through zero
       is checked by sign det A): they are matched by the distance alone and never flagged.
    3. A complex pair whose members fail the tests only because of the square-root branch
       point of a pair turning real (or two real roots merging) is accepted as a set when the
       pair's sum and product — analytic through the branch point — follow their prediction.
    """
    n = a.lam.size
    ar = np.arange(n)
    h = b.V - a.V
    scale = np.maximum(np.abs(a.lam), a.floor)
    dl = b.lam[None, :] - a.lam[:, None]
    trap = np.abs(dl - 0.5 * (a.dlam[:, None] + b.dlam[None, :]) * h)
    dist = np.minimum(trap, np.abs(dl)) / scale[:, None]
    ra, rb = a.lam.imag == 0, b.lam.imag == 0
    sa, sb = _sink(a.lam), _sink(b.lam)
    if n == 1:
        perm = np.zeros(1, dtype=int)
        return Link(perm, bool(dist[0, 0] > opts.dist_max), trap[0, :1].copy())
    # 1. direct matches
    j1 = np.argmin(dist, axis=1)
    i1 = np.argmin(dist, axis=0)
    d1 = dist[ar, j1]
    row = dist.copy()
    row[ar, j1] = np.inf
    row[ar, b.conj[j1]] = np.inf
    col = dist[:, j1].T.copy()           # col[i, r] = dist[r, j1[i]]
    col[ar, ar] = np.inf
    col[ar, a.conj] = np.inf
    alt = np.minimum(row.min(axis=1), col.min(axis=1))
    rr = ra & rb[j1]
    m1 = np.ones(n)
    cplx = ~rr
    if cplx.any():
        m1[cplx] = _mac_columns(a.X[:, cplx], b.X[:, j1[cplx]], disp)
    c1 = np.where(rr, 0.0, 1.0 - m1) + d1
    decisive = ((d1 < opts.decisive_ratio * alt) & (d1 <= 0.1 * opts.dist_max)
                & (alt >= opts.dist_max))
    easy = ((i1[j1] == ar) & (d1 <= opts.dist_max)
            & (((c1 <= opts.cost_ratio * alt) & (rr | (m1 >= opts.mac_min))) | decisive))
    easy &= easy[a.conj] & (b.conj[j1] == j1[a.conj])
    perm = np.where(easy, j1, -1)
    amb = np.zeros(n, dtype=bool)
    hard = np.nonzero(~easy)[0]
    if hard.size:
        free = _free_columns(n, j1[easy])
        w = np.where((ra[hard][:, None] & rb[None, :]) | (sa[hard][:, None] & sb[None, :]),
                     0.0, 1.0)
        macH = _mac_matrix(a.X[:, hard], b.X, disp)
        costH = w * (1.0 - macH) + dist[hard]
        r_, c_ = linear_sum_assignment(costH[:, free])
        perm[hard[r_]] = free[c_]
        inv = np.empty(n, dtype=int)
        inv[perm] = ar
        hh = np.arange(hard.size)
        ph = perm[hard]
        c0 = costH[hh, ph]
        rowH = costH.copy()
        for cols in (ph, b.conj[ph], perm[a.conj[hard]]):
            rowH[hh, cols] = np.inf
        wC = np.where(ra[:, None] & rb[ph][None, :], 0.0, 1.0)
        costC = (wC * (1.0 - _mac_matrix(a.X, b.X[:, ph], disp)) + dist[:, ph]).T
        for rows in (hard, a.conj[hard], inv[b.conj[ph]]):
            costC[hh, rows] = np.inf
        altH = np.minimum(rowH.min(axis=1), costC.min(axis=1))
        rowD = dist[hard].copy()
        for cols in (ph, b.conj[ph], perm[a.conj[hard]]):
            rowD[hh, cols] = np.inf
        colD = dist[:, ph].T.copy()
        for rows in (hard, a.conj[hard], inv[b.conj[ph]]):
            colD[hh, rows] = np.inf
        d0 = dist[hard, ph]
        altD = np.minimum(rowD.min(axis=1), colD.min(axis=1))
        decisiveH = ((d0 < opts.decisive_ratio * altD) & (d0 <= 0.1 * opts.dist_max)
                     & (altD >= opts.dist_max))
        shape_free = _near(a.lam, a.conj, scale, opts.degenerate_tol, hard) & _near(
            b.lam, b.conj, np.maximum(np.abs(b.lam), b.floor), opts.degenerate_tol, ph)
        same_real = ((ra[hard] & rb[ph] & (np.sign(a.lam[hard].real) == np.sign(b.lam[ph].real)))
                     | (sa[hard] & sb[ph]))
        amb[hard] = ~same_real & ~decisiveH & (
            (~shape_free & ((c0 > opts.cost_ratio * altH) | (macH[hh, ph] < opts.mac_min)))
            | (d0 > opts.dist_max))
    err = trap[ar, perm]
    cl = cluster_continuations(a, b, perm, amb, trap[ar, perm] / scale, disp, opts)
    perm, amb, clusters, split_at, events = cl.perm, cl.amb, cl.clusters, cl.split_at, cl.events
    err = trap[ar, perm]
    skip = [i for rows in clusters for i in rows] + list(np.nonzero(sa & sb[perm])[0])
    return Link(perm, bool(amb.any() or _approach(a, b, perm, opts, skip)), err,
                clusters, split_at, events)


def _approach(a: Node, b: Node, perm: np.ndarray, opts: TrackingOptions,
              skip: Sequence[int] = ()) -> bool:
    """Do two complex eigenvalues' paths approach each other inside the step?

    Two models of the paths of the physical complex branches i, k: the straight lines
    λ_i + λ'_i s from the first sample (s ∈ [0, h]), and the cubic Hermite curves through both
    samples (values and slopes).  A closest approach m inside the step below
    approach_ratio · min(separation at a, at b) flags the step: it does not resolve a veering
    or crossing there (a long step can otherwise take a veering for a crossing, the straight
    lines from either end both missing it).  Rows in ``skip`` (clusters followed as a set,
    whose single-root slopes are singular) are left out, and so are pairs repeated (within
    ``degenerate_tol``, as :func:`link_nodes` treats them) at both ends: identical, uncoupled
    subsystems — the mounts of equal stopped propellers — have one eigenvalue at every speed,
    and the approach of its copies is rounding (it refined every step of such a model to the
    node budget).
    """
    keep = (a.lam.imag > 0) & (b.lam[perm].imag > 0)
    keep[list(skip)] = False
    up = np.nonzero(keep)[0]
    if up.size < 2:
        return False
    h = b.V - a.V
    lam, d = a.lam[up], a.dlam[up]
    r0 = lam[:, None] - lam[None, :]
    rd = d[:, None] - d[None, :]
    rd2 = np.abs(rd) ** 2
    with np.errstate(all="ignore"):
        s = np.where(rd2 > 0, -np.real(r0.conj() * rd) / rd2, 0.0)
    interior = (s > 0) & (s < h)
    m = np.abs(r0 + rd * np.clip(s, 0, h))
    lb = b.lam[perm[up]]
    eb = np.abs(lb[:, None] - lb[None, :])
    ref = opts.approach_ratio * np.minimum(np.abs(r0), eb)
    flag = interior & (m < ref)
    # Hermite curves through both samples; only pairs that travel far enough to approach
    c = hermite_coeffs(lam[:, None], lb[:, None], d[:, None], b.dlam[perm[up]][:, None], h)
    path = hermite_eval(c, CHECK_S[None, :])                      # (p, 9)
    travel = np.max(np.abs(path - lam[:, None]), axis=1)
    cand = (travel[:, None] + travel[None, :]) > np.abs(r0) - ref
    i, k = _upper_pairs(cand)
    if i.size:
        dmin = np.min(np.abs(path[i] - path[k]), axis=1)
        flag[i, k] |= dmin < ref[i, k]
    np.fill_diagonal(flag, False)
    tol = opts.degenerate_tol * np.maximum(np.abs(lam), a.floor)
    flag &= ~((np.abs(r0) <= tol[:, None]) & (eb <= tol[:, None]))      # repeated at a and b
    return bool(flag.any())
