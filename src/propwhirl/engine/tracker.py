"""The tracking core, and the sweep over V on it: eigen-analysis with mode tracking and refinement.

:func:`follow`
    The one tracking core: every eigen-solution branch followed along a scalar parameter
    (the airspeed, the rotational speed, a design parameter), with the problem's node
    evaluator and linking plugged in; an ambiguous step is split down to a smallest step and
    within a node budget.  The sweep over V below is this core with the engine's nodes and
    linking and the airspeed's own refinements layered on top; the Campbell diagram over Ω and
    the naming of modes from Ω = 0 (:mod:`propwhirl.analysis.modes`) are this core with the
    undamped gyroscopic system's Hermitian-definite nodes and their MAC in the energy norm.
:func:`sweep`
    Eigenvalues/eigenvectors along V with *mode tracking*: every eigenvalue branch is followed
    from speed to speed (nodes: :mod:`propwhirl.engine.nodes`; linking two speeds, clusters
    through branch points, veering and crossing: :mod:`propwhirl.engine.linking` and
    :mod:`propwhirl.engine.clusters`; branch ids: :mod:`propwhirl.engine.ordering`).

    An ambiguous step is bisected (down to ``min_step``; at a grid speed near its middle if
    there is one, between a crossing and a branch point when a cluster shows both, at an
    unstable pair's branch point when a cluster shows one).  Then the Hermite model of Re λ of
    each branch between samples — values and slopes, with the trapezoidal mismatch as its
    uncertainty (``margin``) — inserts samples where a crossing may hide inside a step
    (:func:`_hump_candidates`), and an unstable pair turning real (the thesis's "whirl
    divergence") is bracketed by two nodes 0.9·``min_step`` apart around its branch point
    (:func:`propwhirl.engine.crossings.branch_point_speeds`).  Intervals still ambiguous at
    ``min_step`` (or when the node budget runs out) are listed in ``Sweep.unresolved``.

    Memory: before the first evaluation the sweep's need is estimated
    (:func:`propwhirl.limits.sweep_bytes`: the eigenvectors kept per node and one batch's
    temporaries) and refused beyond :func:`propwhirl.limits.memory_limit`; speeds are
    evaluated in batches of at most :func:`propwhirl.limits.batch_size`; the refinement's node
    budget (:func:`propwhirl.limits.node_budget`) is bounded absolutely and by memory.
    :func:`sweep` evaluates every grid speed (the V-g-f table).
:func:`analyse`
    The sweep and :func:`~propwhirl.engine.crossings.critical_points`, in one call.  Locating
    critical speeds does not need an eigendecomposition at every grid speed: analyse starts
    from a subset of the grid ``initial_step`` (default 50 m/s) apart and lets the tracker add
    speeds where they are needed.

Cost on the wingtip propeller-wing (204 states, one thread; docs/performance.md): full
``eig`` ≈ 7 ms, ``eigvals`` ≈ 5 ms, dλ/dV of all roots ≈ 1 ms, ``state_matrix`` ≈ 0.7–0.9 ms
per speed in a batch (≈ 2.7 ms for a single speed), one inverse-iteration evaluation ≈ 1 ms.
"""
from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from propwhirl.engine.crossings import XTOL, branch_point_speeds, refine_crossings
from propwhirl import limits
from propwhirl.engine.eigensolve import (StateMatrixFn, call_state_matrix, displacement_mask,
                                         single_thread_blas)
from propwhirl.engine.hermite import CHECK_S, hermite_coeffs, hermite_eval
from propwhirl.engine.linking import Link, link_nodes
from propwhirl.engine.nodes import Node, evaluate_nodes
from propwhirl.engine.options import TrackingOptions, check_speeds
from propwhirl.engine.ordering import initial_order, order_chain
from propwhirl.engine.results import Analysis, Sweep
from propwhirl.validate import InputError, finite, increasing, integer_at_least, positive


#: default spacing [m/s] of the speeds :func:`analyse` evaluates first (see its docstring)
ANALYSE_INITIAL_STEP = 50.0


def initial_speeds(grid: np.ndarray, step: float | None) -> np.ndarray:
    """The grid speeds [m/s] the sweep evaluates first (its first batch): those nearest to an
    even division of [first, last] at spacing ≤ ``step`` [m/s] (:func:`analyse`'s
    ``initial_step``).

    Always the first and the last grid speed; the whole grid when ``step`` is None or the grid
    is already at least that coarse.
    """
    if step is None or grid.size <= 2:
        return grid
    m = int(math.ceil((grid[-1] - grid[0]) / step - 1e-9)) + 1
    if m >= grid.size:
        return grid
    targets = np.linspace(grid[0], grid[-1], m)
    idx = np.clip(np.searchsorted(grid, targets), 1, grid.size - 1)
    idx = np.where(np.abs(grid[idx - 1] - targets) <= np.abs(grid[idx] - targets), idx - 1, idx)
    return grid[np.unique(np.concatenate([[0], idx, [grid.size - 1]]))]


def _split_speed(Va: float, Vb: float, grid: np.ndarray) -> float:
    """Where to bisect the step (Va, Vb): the grid speed nearest its middle if one lies in its
    middle half (so refined sweeps report at asked speeds), else the midpoint."""
    mid = 0.5 * (Va + Vb)
    q = 0.25 * (Vb - Va)
    inside = grid[(grid > mid - q) & (grid < mid + q)]
    return float(inside[np.argmin(np.abs(inside - mid))]) if inside.size else mid


def sweep(state_matrix: StateMatrixFn, speeds, *, n_dof: int | None = None,
          displacement=None, state_labels: Sequence[str] | None = None,
          mode_labels: Sequence[str] | Callable[[complex, np.ndarray], str] | None = None,
          options: TrackingOptions | None = None) -> Sweep:
    """Eigen-analysis along the speeds with mode tracking (see the module docstring).

    Parameters
    ----------
    state_matrix : callable
        ``state_matrix(V) -> A``: the real state matrices ``(len(V), n, n)`` for a 1-D array of
        speeds V [m/s] (also called just above each speed, for dA/dV).
    speeds : array_like
        Increasing grid [m/s], all > 0 (the aerodynamic matrices carry 1/V); every grid
        speed is evaluated (the V-g-f table), and the grid is refined automatically where
        tracking is ambiguous and where a hump may hide between samples.
    n_dof : int, optional
        The first ``n_dof`` states are displacements (eq. 5.7); default: all states.
    displacement : array_like of bool, optional
        Mask of the displacement states instead of ``n_dof``.
    state_labels : sequence of str, optional
        The ``n`` state labels (used in error messages); default ``"x0"``, ``"x1"``, ….
    mode_labels : sequence of str or callable, optional
        ``n`` mode labels, or ``f(λ, eigenvector)`` at the first speed; default ``"mode k"``.
    options : TrackingOptions, optional
        Tuning of the tracker.

    Returns
    -------
    Sweep
        The tracked eigenvalues, eigenvectors and dλ/dV, one column per branch (mode id).

    Examples
    --------
    >>> import numpy as np
    >>> def state_matrix(V):     # ẍ + (0.5 − 0.01 V) ẋ + 100 x = 0: flutter at 50 m/s
    ...     A = np.zeros((V.size, 2, 2))
    ...     A[:, 0, 1] = 1.0
    ...     A[:, 1, 0] = -100.0
    ...     A[:, 1, 1] = -(0.5 - 0.01 * V)
    ...     return A
    >>> from propwhirl.engine import sweep
    >>> sw = sweep(state_matrix, np.arange(10.0, 101.0, 10.0), n_dof=1)
    >>> sw.mode_labels
    ('mode 0', "mode 0'")
    >>> np.round(sw.damping_ratio[[0, -1], 0], 4)     # ζ = −Re λ/|λ| of mode 0 at 10, 100 m/s
    array([ 0.02 , -0.025])
    >>> round(float(sw.frequency_hz[0, 0]), 3)            # f = |Im λ|/2π [Hz] at 10 m/s
    1.591
    """
    opts = options or TrackingOptions()
    grid = check_speeds(speeds)
    labels = None if state_labels is None else tuple(str(s) for s in state_labels)
    with single_thread_blas():
        return _sweep(state_matrix, grid, n_dof, displacement, labels, mode_labels, opts)


def _evaluate(fn, V, n: int, labels, opts: TrackingOptions, stats: dict[str, int]) -> list[Node]:
    """:func:`evaluate_nodes` in batches of at most :func:`propwhirl.limits.batch_size`
    speeds (bounds the temporaries of the model and of the eigen-solutions)."""
    V = np.asarray(V, dtype=float)
    b = limits.batch_size(n)
    if V.size <= b:
        return evaluate_nodes(fn, V, n, labels, opts, stats)
    out: list[Node] = []
    for i in range(0, V.size, b):
        out += evaluate_nodes(fn, V[i:i + b], n, labels, opts, stats)
    return out


def follow(evaluate: Callable[[np.ndarray], list], link: Callable[[Any, Any], Any],
           first, *, min_step: float, budget: int,
           split: Callable[[Any, Any, Any], float | None],
           bracket: Callable[[list], list[float]] | None = None,
           settle: Callable[[list, dict], list[float]] | None = None,
           at_start: Callable[[Any, Any], Any] | None = None) -> tuple[list, dict, int]:
    """The tracking core: follow every eigen-solution branch along a scalar parameter s.

    One loop for every tracked problem — the sweep over the airspeed V (:func:`sweep`), the
    Campbell diagram over the rotational speed Ω and the naming of modes from Ω = 0
    (:mod:`propwhirl.analysis.modes`), or a design parameter.  The problem plugs in how to
    solve it at given s and how to link two solutions; the core decides where to evaluate: an
    ambiguous step is split while its half is at least ``min_step`` and the node count stays
    below ``budget``; one still ambiguous is kept with its link (the caller reports it).

    Parameters
    ----------
    evaluate : callable
        ``evaluate(s) -> nodes``: the eigen-solutions at the parameter values ``s`` (1-D
        array, in the parameter's unit), one node per value, each with its value as ``.s``.
    link : callable
        ``link(a, b) -> link``: which root at node ``a`` continues which at the next node
        ``b``; the link has ``.ambiguous`` (the step does not resolve the continuation).
    first : array_like
        The parameter values evaluated first, increasing.
    min_step : float
        Smallest step of the refinement (the parameter's unit): a step is split only while
        its half is at least this.
    budget : int
        At most this many nodes for the splitting (and for what ``settle`` asks).
    split : callable
        ``split(a, b, link) -> s or None``: where to split an ambiguous step (inside it);
        None leaves the step to ``bracket``.
    bracket : callable, optional
        ``bracket([(a, b, link), ...]) -> s values``: new values for the steps ``split``
        left (e.g. bracketing a branch point found inside the step).
    settle : callable, optional
        ``settle(nodes, links) -> s values``: called when every step is linked; values to
        add still (e.g. where a crossing of Re λ = 0 may hide inside a step); none ends the
        loop.  Cut to the budget.
    at_start : callable, optional
        ``at_start(a, b) -> a``: the first node re-expressed for its continuation to the node
        next to it (a degenerate start, such as the repeated frequencies of a symmetric mount
        at Ω = 0); it replaces the first node, again whenever refinement puts a new node next
        to it.

    Returns
    -------
    nodes : list
        Every evaluated node, sorted by s.
    links : dict
        ``{(a.s, b.s): link}`` for each pair of consecutive nodes.
    refined : int
        Number of values added for ambiguous steps (by ``split`` and ``bracket``).

    Examples
    --------
    The eigenvalues of [[1, 0.1], [0.1, p]] veer at p = 1, where the eigenvectors turn fast;
    a link that calls a step ambiguous where the first eigenvector's MAC falls below 0.9 has
    the core refine there, and only there:

    >>> import numpy as np
    >>> from types import SimpleNamespace
    >>> from propwhirl.engine import follow
    >>> def evaluate(p):
    ...     return [SimpleNamespace(s=float(x), X=np.linalg.eigh([[1.0, 0.1], [0.1, x]])[1])
    ...             for x in p]
    >>> def link(a, b):
    ...     return SimpleNamespace(ambiguous=bool(abs(a.X[:, 0] @ b.X[:, 0]) ** 2 < 0.9))
    >>> nodes, links, refined = follow(evaluate, link, [0.0, 1.0, 2.0], min_step=0.01,
    ...                                budget=100, split=lambda a, b, lk: 0.5 * (a.s + b.s))
    >>> [nd.s for nd in nodes], refined
    ([0.0, 0.5, 0.75, 0.875, 1.0, 1.125, 1.25, 1.5, 2.0], 6)
    """
    first = finite("first", np.atleast_1d(np.asarray(first, dtype=float)))
    if first.size > 1 or first.ndim != 1:
        increasing("first", first)
    positive("min_step", min_step)
    integer_at_least("budget", budget, 2)

    def split_inside(a, b, lk):
        where = split(a, b, lk)
        if where is not None and not a.s < where < b.s:
            raise InputError(f"split returned s = {where!r} for the step ({a.s!r}, {b.s!r}): "
                             "must be inside it")
        return where

    def solve(s: np.ndarray) -> list:
        out = list(evaluate(s))
        if len(out) != s.size:
            raise InputError(f"evaluate returned {len(out)} nodes for {s.size} parameter values: "
                             "must return one per value")
        return out

    nodes = sorted(solve(first), key=lambda nd: nd.s)
    links: dict[tuple[float, float], Any] = {}
    refined = 0
    while True:
        new: list[float] = []
        located = []
        for t, (a, b) in enumerate(zip(nodes[:-1], nodes[1:])):
            key = (a.s, b.s)
            if key in links:
                continue
            if t == 0 and at_start is not None:
                a = nodes[0] = at_start(a, b)
            lk = link(a, b)
            if (lk.ambiguous and 0.5 * (b.s - a.s) >= min_step
                    and len(nodes) + len(new) < budget):
                where = split_inside(a, b, lk)
                if where is None:
                    located.append((a, b, lk))
                else:
                    new.append(where)
                continue
            links[key] = lk
        if located:
            if bracket is None:
                raise InputError("split returned None (leave the step to bracket) but no "
                                 "bracket was given")
            new += bracket(located)
        if not new:
            new = [] if settle is None else settle(nodes, links)
            new = new[: max(0, budget - len(nodes))]
            if not new:
                break
        else:
            refined += len(new)
        nodes = sorted(nodes + solve(np.array(new, dtype=float)), key=lambda nd: nd.s)
    return nodes, links, refined


def _sweep(fn, grid, n_dof, displacement, labels, mode_labels, opts,
           initial_step: float | None = None) -> Sweep:
    """The sweep over V: the tracking core (:func:`follow`) with the engine's nodes and
    linking, and the airspeed's own refinements layered on it — bisection at grid speeds or
    where a cluster asks, bracketing of unstable branch points, the Hermite hump check."""
    stats: dict[str, int] = {}
    first = initial_speeds(grid, initial_step)
    # the number of states before any batch: from the labels, else from A at one speed
    n = len(labels) if labels is not None else call_state_matrix(fn, first[:1], None,
                                                                   None).shape[-1]
    limits.check_sweep(first.size, n)
    given = labels
    if labels is None:
        labels = tuple(f"x{i}" for i in range(n))
    disp = displacement_mask(n, n_dof, displacement)
    budget = limits.node_budget(grid.size, first.size, n, opts.max_nodes)
    chain_order: list[np.ndarray] = []

    def evaluate(V):            # the first batch's errors name the labels only if given
        return _evaluate(fn, V, n, given if "eig" not in stats else labels, opts, stats)

    def split(a, b, lk):
        if lk.branch_points:        # refine there: bracket the unstable branch point
            return None
        return _split_speed(a.V, b.V, grid) if lk.split_at is None else lk.split_at

    def bracket(located):
        found = branch_point_speeds(fn, located, n, labels, opts, stats)
        stats["branch_point_nodes"] = stats.get("branch_point_nodes", 0) + len(found)
        new_V = []
        for a, b, _ in located:
            here = [v for v in found if a.V < v < b.V]
            new_V += here if here else [_split_speed(a.V, b.V, grid)]
        return new_V

    def settle(nodes, links):
        chain = [links[(a.V, b.V)] for a, b in zip(nodes[:-1], nodes[1:])]
        R = order_chain(nodes, [lk.perm for lk in chain])
        chain_order[:] = [R]
        if not opts.hump_check:
            return []
        V = np.array([nd.V for nd in nodes])
        fl = np.array([nd.floor for nd in nodes])
        new_V = _hump_candidates(V, _step_models(nodes, R, chain, opts.fd_rel), fl, opts)
        stats["hump_refined"] = stats.get("hump_refined", 0) + len(new_V)
        if not new_V:
            new_V = branch_point_speeds(fn, list(zip(nodes[:-1], nodes[1:], chain)), n,
                                        labels, opts, stats)
            stats["branch_point_nodes"] = stats.get("branch_point_nodes", 0) + len(new_V)
        return new_V

    nodes, links, refined = follow(evaluate, lambda a, b: link_nodes(a, b, disp, opts), first,
                                    min_step=opts.min_step, budget=budget, split=split,
                                    bracket=bracket, settle=settle)
    stats["refined"] = refined
    stats["nodes"] = len(nodes)
    unresolved = tuple((a.V, b.V) for a, b in zip(nodes[:-1], nodes[1:])
                       if links[(a.V, b.V)].ambiguous)
    return _assemble(nodes, chain_order[0], grid, labels, disp, mode_labels, unresolved, stats)


def _assemble(nodes, R, grid, labels, disp, mode_labels, unresolved, stats) -> Sweep:
    T, n = R.shape
    V = np.array([nd.V for nd in nodes])
    lam = np.stack([nd.lam[R[t]] for t, nd in enumerate(nodes)])
    dl = np.stack([nd.dlam[R[t]] for t, nd in enumerate(nodes)])
    X = np.stack([nd.X[:, R[t]] for t, nd in enumerate(nodes)])
    # phase: first speed — largest displacement entry real positive; then aligned step by step
    P = X[0][disp]
    big = P[np.argmax(np.abs(P), axis=0), np.arange(n)]
    ph0 = np.where(np.abs(big) > 0, np.conj(big) / np.where(big == 0, 1, np.abs(big)), 1.0)
    inner = np.einsum("tik,tik->tk", X[:-1].conj(), X[1:])
    step = np.where(np.abs(inner) > 0, np.conj(inner) / np.where(inner == 0, 1, np.abs(inner)),
                    1.0)
    phase = np.concatenate([ph0[None], ph0[None] * np.cumprod(step, axis=0)], axis=0)
    X *= phase[:, None, :]
    _, partner, n_phys = initial_order(nodes[0])
    if mode_labels is None:
        ml = tuple(f"mode {k}" if k < n_phys else f"mode {partner[k]}'" for k in range(n))
    elif callable(mode_labels):
        ml = tuple(str(mode_labels(lam[0, k], X[0, :, k])) for k in range(n))
    else:
        ml = tuple(str(s) for s in mode_labels)
        if len(ml) != n:
            raise InputError(f"mode_labels: got {len(ml)}, need {n}")
    return Sweep(V=V, eigenvalues=lam, eigenvectors=X, dlam_dV=dl, physical=lam.imag >= 0,
                 state_labels=labels, displacement=disp, mode_labels=ml, partner=partner,
                 grid=grid, floor=np.array([nd.floor for nd in nodes]),
                 unresolved=unresolved, stats=dict(stats))


def _hump_candidates(V: np.ndarray, models, floor: np.ndarray,
                     opts: TrackingOptions) -> list[float]:
    """Speeds where a branch may hide a sign change of Re λ between samples of equal sign.

    ``models``: the per-step models of :func:`_step_models` (T−1, n) — values and slopes of
    Re λ at both samples, their uncertainty, which branches to check.  Per step and branch
    with Re λ of equal sign at both samples: the cubic Hermite model p(s) of Re λ is
    evaluated at its stationary points and at ``CHECK_S``; a sample is inserted at the worst
    s where sign·p(s) < margin · err · 16 s²(1 − s)² (the model crosses zero, or comes
    closer to it than its uncertainty).  One sample per step.

    A sample where Re λ is zero within ``zero_tol`` (a grid speed that lands on a crossing)
    has no sign of its own: the step takes the sign of its other end, or, both ends zero,
    that of the branch's nearest signed sample — so a hump whose onset and recovery both
    fall on samples (Re λ: −, 0, 0, −) is still seen from the slopes at its ends.  A branch
    with no signed sample (Re λ zero throughout: an undamped mode without aerodynamics) is
    not checked.
    """
    fa, fb, ga, gb, e, phys = models
    h = np.diff(V)[:, None]
    tola = opts.zero_tol * np.maximum(np.abs(fa), floor[:-1, None])
    tolb = opts.zero_tol * np.maximum(np.abs(fb), floor[1:, None])
    sa = np.where(np.abs(fa) <= tola, 0, np.sign(fa))
    sb = np.where(np.abs(fb) <= tolb, 0, np.sign(fb))
    sa = np.where(sa == 0, np.where(sb != 0, sb, _nearest_sign(sa, sb)), sa)
    sb = np.where(sb == 0, sa, sb)
    ok = phys & (sa == sb) & (sa != 0) & (h >= 2 * opts.min_step)
    if not ok.any():
        return []
    t_i, k_i = np.nonzero(ok)
    hh = h[t_i, 0]
    c = hermite_coeffs(fa[t_i, k_i], fb[t_i, k_i], ga[t_i, k_i], gb[t_i, k_i], hh)
    A, B, C = 3 * c[3], 2 * c[2], c[1]
    disc = B * B - 4 * A * C
    sq = np.sqrt(np.maximum(disc, 0.0))
    with np.errstate(all="ignore"):
        s1 = np.where(np.abs(A) > 1e-300, (-B + sq) / (2 * A), -C / B)
        s2 = np.where(np.abs(A) > 1e-300, (-B - sq) / (2 * A), -C / B)
    S = np.concatenate([np.stack([s1, s2], axis=1),
                        np.broadcast_to(CHECK_S, (t_i.size, CHECK_S.size))], axis=1)
    valid = np.isfinite(S) & (S > 0) & (S < 1)
    S = np.where(valid, S, 0.5)
    p = hermite_eval(tuple(ci[:, None] for ci in c), S)
    tol_mid = np.maximum(tola[t_i, k_i], tolb[t_i, k_i])[:, None]
    env = opts.margin * e[t_i, k_i][:, None] * 16 * S ** 2 * (1 - S) ** 2
    viol = (p * sa[t_i, k_i][:, None] < np.maximum(env, 0.0) - tol_mid) & valid
    bad = viol.any(axis=1)
    out: dict[int, tuple[float, float]] = {}
    for r in np.nonzero(bad)[0]:
        score = np.where(viol[r], env[r] - p[r] * sa[t_i[r], k_i[r]], -np.inf)
        j = int(np.argmax(score))
        t = int(t_i[r])
        if t not in out or score[j] > out[t][1]:
            s = float(np.clip(S[r, j], 0.05, 0.95))
            out[t] = (V[t] + s * (V[t + 1] - V[t]), float(score[j]))
    return sorted(v for v, _ in out.values())


def _nearest_sign(sa: np.ndarray, sb: np.ndarray) -> np.ndarray:
    """Per step (T−1, n): the sign of the branch's nearest signed sample before the step,
    else after it (0 when the branch has none); ``sa``/``sb`` the signs (−1, 0, 1) of the
    samples at the steps' starts and ends."""
    s = np.concatenate([sa, sb[-1:]])                  # (T, n): every sample's sign
    T = s.shape[0]
    rows = np.arange(T)[:, None]
    last = np.maximum.accumulate(np.where(s != 0, rows, -1), axis=0)        # at or before
    nxt = np.minimum.accumulate(np.where(s != 0, rows, T)[::-1], axis=0)[::-1]  # at or after
    cols = np.arange(s.shape[1])[None, :]
    before = np.where(last >= 0, s[np.clip(last, 0, T - 1), cols], 0)[:-1]
    after = np.where(nxt < T, s[np.clip(nxt, 0, T - 1), cols], 0)[1:]
    return np.where(before != 0, before, after)


#: rounding noise of a computed eigenvalue, in units of the unit roundoff times the largest
#: |λ| of its node: measured ≈ 7–14 on the wingtip model with EI_chordwise = 1e14 N m²
#: (|λ| up to 1.4e8 1/s), where dλ/dV's imaginary part carried 1e-7/h_fd of noise
EIG_NOISE = 16.0


def _step_models(nodes: list[Node], R: np.ndarray, links: list[Link],
                 fd_rel: float = 1e-6):
    """Per step and branch: (Re λ_a, Re λ_b, Re λ'_a, Re λ'_b, uncertainty, checked) (T−1, n).

    Members of clusters followed as a set over a step (:func:`cluster_continuations`) were
    checked there and are not checked again.

    The uncertainty is the trapezoidal mismatch m of the step (:attr:`Link.err`, |m|)
    without the part of it that is rounding noise, and never less than |Re m| (the mismatch
    of the model of Re λ itself): each λ' is a forward difference over h_fd = ``fd_rel`` ·
    max(V, 1 m/s) of eigenvalues computed to ≈ :data:`EIG_NOISE` · u · max|λ| (u the unit
    roundoff), so m carries noise up to ν = ½ ΔV Σ EIG_NOISE · u · max|λ| / h_fd over its
    two ends.  Below that, refining cannot shrink m; with modes of very high frequency (a
    stiffness 1e14 N m²: |λ| ~ 1e8 1/s, ν ~ 1 1/s) the complex |m| of a lightly damped
    branch never fell below its |Re λ| and the hump check refined every step towards
    ``min_step``.  On ordinary models (max|λ| ≲ 1e4 1/s) ν is negligible.
    """
    lam = np.stack([nd.lam[R[t]] for t, nd in enumerate(nodes)])
    dl = np.stack([nd.dlam[R[t]] for t, nd in enumerate(nodes)])
    T, n = lam.shape
    e = np.empty((T - 1, n))
    phys = (lam[:-1].imag >= 0) & (lam[1:].imag >= 0)
    for t, lk in enumerate(links):
        inv = np.empty(n, dtype=int)
        inv[R[t]] = np.arange(n)
        e[t] = lk.err[R[t]]
        for rows in lk.clusters:
            phys[t, inv[list(rows)]] = False
    V = np.array([nd.V for nd in nodes])
    h = np.diff(V)[:, None]
    noise = EIG_NOISE * np.finfo(float).eps * np.abs(lam).max(axis=1) / (
        fd_rel * np.maximum(V, 1.0))                              # of each λ' [1/m]
    nu = 0.5 * h * (noise[:-1, None] + noise[1:, None])
    re_mis = np.abs((lam[1:] - lam[:-1] - 0.5 * (dl[:-1] + dl[1:]) * h).real)
    e = np.maximum(re_mis, e - nu)
    return lam[:-1].real, lam[1:].real, dl[:-1].real, dl[1:].real, e, phys


def analyse(state_matrix: StateMatrixFn, speeds, *, n_dof: int | None = None,
            displacement=None, state_labels: Sequence[str] | None = None,
            mode_labels=None, options: TrackingOptions | None = None,
            xtol: float = XTOL, benignity_step: float | None = None,
            initial_step: float | None = ANALYSE_INITIAL_STEP) -> Analysis:
    """:func:`sweep` followed by :func:`critical_points` (one BLAS-limited context).

    Locating the critical speeds does not need an eigendecomposition at every grid speed: the
    sweep starts from the grid speeds nearest an even division of the range at spacing
    ``initial_step`` [m/s] (default :data:`ANALYSE_INITIAL_STEP`; first and last speed always)
    and the tracker adds speeds — grid speeds where they fall in the middle of a step — only
    where the assignment is ambiguous or a Hermite model of Re λ may hide a crossing (see
    :class:`TrackingOptions`).  So ``Analysis.sweep.V`` is not the whole grid: for a V-g-f
    table at every grid speed use :func:`sweep` (or ``initial_step=None``).

    Parameters
    ----------
    state_matrix, speeds, n_dof, displacement, state_labels, mode_labels, options
        As for :func:`sweep`.
    xtol : float
        Width [m/s] to which each crossing is bracketed (default
        :data:`~propwhirl.engine.crossings.XTOL`).
    benignity_step : float, optional
        Central-difference step [m/s] of ζ for the benignity; default: from dλ/dV.
    initial_step : float or None
        Spacing [m/s] of the grid speeds evaluated first; None: every grid speed.

    Returns
    -------
    Analysis
        The sweep and its :class:`~propwhirl.engine.results.Criticals`.

    Examples
    --------
    >>> import numpy as np
    >>> def state_matrix(V):     # ẍ + (0.5 − 0.01 V) ẋ + 100 x = 0: flutter at 50 m/s
    ...     A = np.zeros((V.size, 2, 2))
    ...     A[:, 0, 1] = 1.0
    ...     A[:, 1, 0] = -100.0
    ...     A[:, 1, 1] = -(0.5 - 0.01 * V)
    ...     return A
    >>> from propwhirl.engine import analyse
    >>> an = analyse(state_matrix, np.arange(1.0, 201.0, 10.0), n_dof=1)
    >>> p = an.criticals.first_onset
    >>> p.kind, round(p.V, 2), round(p.frequency_hz, 3)
    ('flutter', 50.0, 1.592)
    >>> an.sweep.V.size < 20                      # a subset of the 20 grid speeds
    True
    """
    opts = options or TrackingOptions()
    grid = check_speeds(speeds)
    positive("xtol", xtol, "m/s")
    if initial_step is not None:
        positive("initial_step", initial_step, "m/s")
    labels = None if state_labels is None else tuple(str(s) for s in state_labels)
    with single_thread_blas():
        sw = _sweep(state_matrix, grid, n_dof, displacement, labels, mode_labels, opts,
                    initial_step)
        cr = refine_crossings(sw, state_matrix, xtol, benignity_step, opts.zero_tol)
    return Analysis(sw, cr)
