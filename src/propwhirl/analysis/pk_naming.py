"""Which tracked finite-state mode a p-k event is (``analyse(model, method="pk")``,
:func:`propwhirl.analysis.pk_events.pk_instabilities`; the doublet-lattice default's crossings
converged by the p-k, :mod:`propwhirl.analysis.modal_dlm`): the mode of its p-k shape by MAC
(:func:`tracked_mode`), and the events of one cluster of near-identical modes assigned one to
one (:func:`one_to_one`); :func:`by_shape` both, where the mode's own root is the p-k's."""
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


#: the tracked mode a p-k shape names must have its root, at the swept speed nearest the
#: event, within this fraction of |p| of the p-k root (:func:`by_shape`,
#: :func:`one_to_one` given the roots): the same branch, not a lag root or another mode
#: whose shape happens to resemble it
SAME_BRANCH = 0.1

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


def by_shape(sweep, modes, shapes, roots, speeds, keys) -> list[int]:
    """The tracked modes of p-k crossings found from the tracked modes ``modes`` of ``sweep``
    (each event's p-k displacement shape in ``shapes``, root p [1/s] in ``roots``, speed
    [m/s] in ``speeds``, (kind, direction) in ``keys``): the flutter crossings of one key
    within :data:`TOGETHER` of each other's speed assigned one to one to the modes their
    shapes are — the least total 1 − MAC (eq. 5.14) at each event's swept speed nearest —
    among the modes of their own branch there (a root within :data:`SAME_BRANCH` of |p| of
    the p-k root: a Roger state space's lag roots have displacement parts).  A group
    without such an assignment keeps the modes it was found from, and so does a divergence.

    The doublet-lattice default converges each crossing of its state space by the p-k
    (:func:`propwhirl.analysis.pk_crossings.pk_crossing`), which in a cluster of near-identical
    propellers may land on another member's root: x57_like's critical (79.95 m/s, the
    backward whirl of propellers 1-6 in its shape and participation) was named after
    propeller 7's forward whirl, the state-space mode it was found from (MAC 0.00; with the
    backward collective 1.00).  The names stay those of the modes at the first speed: that
    mode, named propeller 7's forward whirl there, whirls backward at the cluster's
    frequency near 80 m/s, and one of the cluster's crossings is its own."""
    out = [int(m) for m in modes]
    V = np.asarray(sweep.V)
    n = int(np.count_nonzero(sweep.displacement))
    flutter = [i for i, p in enumerate(roots) if complex(p).imag != 0]
    done: set[int] = set()
    for a in flutter:
        if a in done:
            continue
        group = [b for b in flutter if b not in done and keys[b] == keys[a]
                 and abs(speeds[b] - speeds[a]) <= TOGETHER * speeds[a]]
        done.update(group)
        cost = np.full((len(group), sweep.eigenvalues.shape[1]), 2.0)
        for r, b in enumerate(group):
            t = int(np.argmin(np.abs(V - speeds[b])))
            p = complex(roots[b])
            p = p.conjugate() if p.imag < 0 else p
            q = np.asarray(shapes[b])[:n]
            for k in np.flatnonzero(sweep.physical[t]):
                lam = complex(sweep.eigenvalues[t, k])
                lam = lam.conjugate() if lam.imag < 0 else lam
                if abs(lam - p) <= SAME_BRANCH * abs(p):
                    cost[r, k] = 1.0 - mac(q, sweep.eigenvectors[t, sweep.displacement, k])
        rows, cols = linear_sum_assignment(cost)
        if len(rows) == len(group) and np.all(cost[rows, cols] < 2.0):
            for r, c in zip(rows, cols):
                out[group[r]] = int(c)
    return out
