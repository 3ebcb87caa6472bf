"""Ordering the chain of linked nodes into branches (mode ids), with the real-axis conventions.

*Branches and mode ids.*  All ``n`` eigenvalues are tracked as ``n`` continuous branches, so
the count never changes.  A complex-conjugate pair occupies two branches; only the member with
``Im λ > 0`` is *physical* (reported); its conjugate partner branch is hidden while complex.
Real eigenvalues are always physical.  When a pair meets the real axis and splits into two
real roots (a divergence branch), **the branch that carried the physical (Im > 0) member keeps
the larger real root** (the less stable one) and the partner branch — until then hidden —
becomes physical with the smaller root.  When two real roots merge into a pair, **the branch
with the smaller id takes the member with Im > 0**.  So a mode id may own a real eigenvalue
(frequency 0, ζ = ±1) over some speed range.  Ids are given at the first speed: physical
oscillatory modes first by increasing frequency, then real roots by decreasing real part, then
the hidden conjugate partners in the order of their partners.  Default labels: ``"mode k"``
and ``"mode k'"`` for the partner of mode k.
"""
from __future__ import annotations

import numpy as np

from propwhirl.engine.nodes import Node


def initial_order(node: Node) -> tuple[np.ndarray, np.ndarray, int]:
    """Raw indices in branch order at the first speed, partner ids, number of physical modes."""
    lam = node.lam
    phys = np.nonzero(lam.imag >= 0)[0]
    osc = phys[lam[phys].imag > 0]
    real = phys[lam[phys].imag == 0]
    osc = osc[np.lexsort((lam[osc].real, lam[osc].imag))]
    real = real[np.argsort(-lam[real].real, kind="stable")]
    first = np.concatenate([osc, real])
    hidden = node.conj[osc]
    order = np.concatenate([first, hidden]).astype(int)
    n = lam.size
    partner = np.full(n, -1, dtype=int)
    k_osc = np.arange(osc.size)
    k_hid = first.size + np.arange(osc.size)
    partner[k_osc] = k_hid
    partner[k_hid] = k_osc
    return order, partner, first.size


def order_chain(nodes: list[Node], perms: list[np.ndarray]) -> np.ndarray:
    """R[t, k] = raw index of branch k at node t, with the real-axis conventions applied."""
    T = len(nodes)
    n = nodes[0].lam.size
    R = np.empty((T, n), dtype=int)
    R[0] = initial_order(nodes[0])[0]
    for t in range(1, T):
        R[t] = perms[t - 1][R[t - 1]]
    for t in range(1, T):
        _canonical_events(nodes[t - 1], nodes[t], R, t)
    return R


def _canonical_events(prev: Node, cur: Node, R: np.ndarray, t: int) -> None:
    """Apply the split/merge conventions at node t (swap branch columns of R[t:])."""
    n = R.shape[1]
    inv_prev = np.empty(n, dtype=int)
    inv_prev[R[t - 1]] = np.arange(n)
    lp = prev.lam[R[t - 1]]
    # split: pair (k upper, k') at t-1 -> both real at t; k keeps the larger root
    for k in np.nonzero(lp.imag > 0)[0]:
        kp = inv_prev[prev.conj[R[t - 1, k]]]
        lk, lkp = cur.lam[R[t, k]], cur.lam[R[t, kp]]
        if lk.imag == 0 and lkp.imag == 0 and lk.real < lkp.real:
            R[t:, [k, kp]] = R[t:, [kp, k]]
    # merge: a conjugate pair at t whose branches were not partners at t-1 (two reals
    # merging, or roots of a cluster that split and merged within the step): the smaller id
    # takes Im > 0
    inv_cur = np.empty(n, dtype=int)
    inv_cur[R[t]] = np.arange(n)
    lc = cur.lam[R[t]]
    for k in np.nonzero(lc.imag < 0)[0]:
        kp = inv_cur[cur.conj[R[t, k]]]
        if k < kp and prev.conj[R[t - 1, k]] != R[t - 1, kp]:
            R[t:, [k, kp]] = R[t:, [kp, k]]
            inv_cur[R[t]] = np.arange(n)
