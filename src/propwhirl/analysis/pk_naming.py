"""Which tracked finite-state mode a p-k event is (``analyse(model, method="pk")``,
:func:`propwhirl.analysis.pk.pk_instabilities`): the mode of its p-k shape by MAC
(:func:`tracked_mode`), and the events of one cluster of near-identical modes assigned one to
one (:func:`one_to_one`)."""
from __future__ import annotations

import numpy as np
from scipy.optimize import linear_sum_assignment

from propwhirl.engine import mac


def tracked_mode(sweep, x: np.ndarray, p: complex, V: float) -> int:
    """The finite-state tracked mode (a column of ``sweep``) a p-k mode shape is, at V [m/s].

    At the swept speed nearest V, of the physical modes whose displacement shape has a MAC
    (eq. 5.14) with the p-k shape ``x`` (its first ``n_dof`` entries) within
    :data:`MAC_BAND` of the best, the one whose eigenvalue is nearest the p-k root ``p``
    [1/s].  (The band matters for real roots: near divergence the static shapes of several
    real roots are almost collinear, and the diverging one is the root nearest p ≈ 0.)
    The p-k continuation may pass through a veering onto another finite-state branch than
    the one it started from (the wingtip model's forward-whirl flutter is reached from the
    in-vacuo "wing 2" mode), so the shape at the event, not the start, names the mode.
    """
    n = int(np.count_nonzero(sweep.displacement))      # the states q first, then q̇, lags
    t = int(np.argmin(np.abs(sweep.V - V)))
    q = np.asarray(x)[:n]
    ids = np.flatnonzero(sweep.physical[t])
    macs = np.array([mac(q, sweep.eigenvectors[t, sweep.displacement, k]) for k in ids])
    near = ids[macs >= MAC_BAND * macs.max()]
    lam = sweep.eigenvalues[t, near]
    lam = np.where(lam.imag < 0, lam.conj(), lam)
    return int(near[np.argmin(np.abs(lam - p))])


#: events of one kind and direction whose speeds are within this fraction of each other are one
#: cluster's (:func:`one_to_one`)
TOGETHER = 0.05


def one_to_one(sweep, modes, shapes, speeds, keys) -> list[int]:
    """The tracked modes of events (``modes``: each one's :func:`tracked_mode`), with those
    that name two or more events of one key (kind, direction) within :data:`TOGETHER` of each
    other's speed [m/s] assigned one to one instead: those events to the physical modes of
    ``sweep`` not named by another event of that key and window, by the least total 1 − MAC
    (eq. 5.14) of their displacement ``shapes`` against the modes' at each event's swept speed
    nearest (Hungarian method).  A cluster of near-identical propellers has one mode's name
    per event — never two different events under one name (issue 34 item 4); events of
    modes apart keep their own."""
    out = [int(m) for m in modes]
    V = np.asarray(speeds, dtype=float)
    n = int(np.count_nonzero(sweep.displacement))
    for a in range(len(out)):
        near = [b for b in range(len(out)) if keys[b] == keys[a]
                and abs(V[b] - V[a]) <= TOGETHER * V[a]]
        clash = [b for b in near if out[b] == out[a]]
        if len(clash) < 2:
            continue
        taken = {out[b] for b in near if b not in clash}
        t = np.argmin(np.abs(np.asarray(sweep.V)[None, :] - V[clash, None]), axis=1)
        ids = np.array([k for k in np.flatnonzero(np.all(sweep.physical[t], axis=0))
                        if k not in taken])
        if ids.size < len(clash):
            continue
        X = np.asarray(sweep.eigenvectors)[t][:, sweep.displacement][:, :, ids]  # (e, n, ids)
        q = np.stack([np.asarray(shapes[b])[:n] for b in clash])                 # (e, n)
        across = np.abs(np.einsum("en,enk->ek", q.conj(), X)) ** 2
        norms = (np.sum(np.abs(q) ** 2, axis=1)[:, None]
                 * np.sum(np.abs(X) ** 2, axis=1))
        cost = 1.0 - across / np.where(norms > 0, norms, 1.0)
        rows, cols = linear_sum_assignment(cost)
        for r, c in zip(rows, cols):
            out[clash[r]] = int(ids[c])
    return out


#: the modes whose MAC is within this fraction of the best are candidates (:func:`tracked_mode`)
MAC_BAND = 0.9
