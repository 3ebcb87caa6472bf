"""The default analysis of a doublet-lattice wing: the modal Roger state space tracks, the p-k
method converges (issue 37, item 1).

``analyse(model)`` on a wing with ``aero = "dlm"`` (``method="auto"`` or ``"reduced"``):

1. the engine tracks every mode of the modal Roger state space
   (:class:`~propwhirl.model.dlm_modal.ModalRoger`: the in-vacuo modes below the cut-off, the
   Roger fit's lag states on them) and locates its crossings;
2. every crossing is converged by the p-k method on the whole structure with the computed
   Q(k, M) at the mode's own k (:func:`propwhirl.analysis.pk_crossings.pk_crossing`): its speed,
   frequency, p-k root and mode shape are the p-k's (at Re p = 0 the p-k root is exact).  A
   crossing the p-k does not have (its root keeps its sign over ±16 % of the speed) is not
   reported: a note gives the state space's speed and the p-k's verdict.  A crossing whose k
   iteration does not converge keeps the state space's speed, with a note.  Two crossings
   that converge onto one p-k root are one event (:func:`one_per_root`), with a note; each
   flutter crossing is named after the tracked mode of its own branch that its p-k shape is
   (:func:`propwhirl.analysis.pk_naming.by_shape`);
3. a mode the state space finds unstable at the first speed is reported only when its p-k
   root there is unstable too.

So the default reports only critical speeds the p-k method has, at the p-k's speed; the
modes above the cut-off (far beyond the fit's k and the panels' validity at the analysed
speeds) enter the p-k's matrices, where they respond to the loads quasi-statically.
"""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, replace

import numpy as np

from propwhirl.analysis.pk_crossings import CROSSING_SPREAD, pk_benignity, pk_crossing
from propwhirl.analysis.pk_iteration import pk_mode, pk_root
from propwhirl.analysis.pk_naming import by_shape
from propwhirl.analysis.reduced import LiftedEigenvectors
from propwhirl.engine import analyse as engine_analyse
from propwhirl.engine import mac, single_thread_blas
from propwhirl.engine.results import Analysis, Criticals
from propwhirl.engine.tracker import ANALYSE_INITIAL_STEP, initial_speeds
from propwhirl.model.aerodynamics.dlm import (MACH_STEP, DlmTables, dlm_aerodynamics,
                                              fixed_mach, snap_mach)
from propwhirl.model.dlm_modal import ModalRoger, modal_roger
from propwhirl.model.aerodynamics.dlm_rfa import TRACKING_K_NODES, b_ref, mach_nodes


#: two converged crossings whose p-k roots are within this fraction of |p| (and speeds within
#: 2 xtol) are one (x57_like: two of its six near-identical propellers' state-space crossings,
#: 80.80 and 81.09 m/s, both converge onto the root at 79.952 m/s, 2e-7 apart; the closest
#: distinct roots of that cluster are ~1e-4 apart)
ONE_ROOT = 1e-5


@dataclass(frozen=True)
class ModalDlmRun:
    """What :func:`modal_dlm_analysis` returns: the engine Analysis (its sweep lifted to the
    full Roger state, its crossings the p-k's), the modal state space, and the notes on the
    state space's events the p-k did not confirm or could not converge."""

    analysis: Analysis
    model: ModalRoger
    notes: tuple[str, ...]


def fit_table_nodes(model, speeds) -> list[tuple[float, int]]:
    """The doublet-lattice table nodes (Mach, k index) that the Roger fits of ``model`` (a wing
    with ``aero = "dlm"``) at the airspeeds ``speeds`` [m/s] read
    (:func:`propwhirl.model.aerodynamics.dlm_rfa.coefficients`), in the order the fits compute them: every
    reduced frequency of :func:`~propwhirl.model.aerodynamics.dlm_rfa.tracking_ks` in the column of the wing's
    fixed ``dlm_mach``, or in the columns of the Mach nodes around each speed's V/a."""
    fixed = fixed_mach(getattr(model, "wing", model))
    if fixed is not None:
        columns = [snap_mach(fixed)]
    else:
        nodes: list[int] = []
        for V in np.atleast_1d(np.asarray(speeds, float)):
            im, t = mach_nodes(V / model.flight.speed_of_sound)
            nodes += [im, im + 1] if t > 1e-9 else [im]
        columns = [snap_mach(im * MACH_STEP) for im in dict.fromkeys(nodes)]
    return [(mach, ik) for mach in columns for ik in TRACKING_K_NODES]


def compute_fit_aics(model, grid: np.ndarray, *, vgf: bool,
                     report: Callable[[int, int], None] | None, tables: DlmTables) -> int:
    """Compute the doublet-lattice AICs that the analysis of ``model`` over the speeds
    ``grid`` [m/s] reads first — those of the Roger fits at the engine's first batch of speeds
    (every grid speed with ``vgf``, else :func:`~propwhirl.engine.tracker.initial_speeds` at
    the default initial step), which its tracking would compute anyway — now, counted:
    ``report(done, total)`` before the first and after each AIC, total known in advance
    (issue 37 item 3; ``report`` None: silent).  The AICs a refinement or a p-k convergence
    adds later are not counted.  A big batch runs on ``tables.processes`` worker processes
    (:meth:`~propwhirl.model.aerodynamics.dlm.DlmAerodynamics.fill`: the same numbers).
    Returns how many were computed (those not in ``tables``, the analysis's, yet)."""
    first = initial_speeds(np.asarray(grid, float), None if vgf else ANALYSE_INITIAL_STEP)
    return dlm_aerodynamics(model, tables).fill(fit_table_nodes(model, first), report,
                                                     tables.processes)


def full_state(assembly, V: float, p: complex, q: np.ndarray) -> np.ndarray:
    """The full Roger state [q, q̇, w] (unit norm) of the harmonic motion q e^{pt} of the
    model's DOFs at V [m/s]: q̇ = p q and every lag state w = (p I − Ww)⁻¹ (p Wv + Wq) q, its
    response to that motion (:func:`propwhirl.model.aerodynamics.dlm_rfa.second_order`)."""
    sys = assembly.second_order(np.array([float(V)]))
    Ww, Wv, Wq = sys.Ww[0], sys.Wv[0], sys.Wq[0]
    w = np.linalg.solve(p * np.eye(Ww.shape[0]) - Ww, (p * Wv + Wq) @ q)
    x = np.concatenate([q, p * q, w])
    return x / np.linalg.norm(x)


def one_per_root(sweep, converged: list, xtol: float) -> tuple[list, list[str]]:
    """The converged crossings (``converged``: (point, its p-k displacement shape, what the
    state-space crossing was), returned so) with those that converged onto one p-k root (speeds within
    2 ``xtol`` [m/s], roots within :data:`ONE_ROOT` of |p|) reported once, and a note for
    each left out.  Of such a group the point kept is the state-space mode whose shape at the
    swept speed nearest the crossing is most the p-k's (MAC, eq. 5.14): x57_like's
    near-identical propellers gave two events at 79.952 m/s, one named after a mode whose
    own crossing was at 80.80 m/s."""
    n = int(np.count_nonzero(sweep.displacement))
    speeds = np.asarray(sweep.V)
    kept: list = []
    notes = []
    for pt, x, what in converged:
        t = int(np.argmin(np.abs(speeds - pt.V)))
        fit = float(mac(x, sweep.eigenvectors[t, sweep.displacement, pt.mode][:n]))
        same = [i for i, (q, _, _, _) in enumerate(kept)
                if q.kind == pt.kind and q.direction == pt.direction
                and abs(q.V - pt.V) <= 2 * xtol
                and abs(q.eigenvalue - pt.eigenvalue) <= ONE_ROOT * abs(pt.eigenvalue)]
        if not same:
            kept.append((pt, x, what, fit))
            continue
        _, _, what_q, fit_q = kept[same[0]]
        if fit > fit_q:
            kept[same[0]] = (pt, x, what, fit)
            what, what_q = what_q, what
        notes.append(f"V = {pt.V:.2f} m/s: the {what} converged onto the same p-k crossing "
                     f"as the {what_q}: reported once, as the latter (the MAC of its "
                     f"state-space shape with the p-k's {max(fit, fit_q):.3f}, the other's "
                     f"{min(fit, fit_q):.3f})")
    return [(q, x, what) for q, x, what, _ in kept], notes


def modal_dlm_analysis(model, grid: np.ndarray, *, displacement, state_labels, options=None,
                       xtol: float, vgf: bool = False, assembly=None,
                       structure: tuple[np.ndarray, np.ndarray] | None = None) -> ModalDlmRun:
    """The engine on the modal Roger state space of ``model``, its crossings converged by the
    p-k method (module docstring) over the airspeeds ``grid`` [m/s], to ``xtol`` [m/s].
    ``displacement`` and ``state_labels``: the model's full state's (its DOF map);
    ``assembly`` and ``structure`` (M, K): the model's, if already built (the assembly holds
    the analysis's doublet-lattice tables, which the p-k convergence reads too).  BLAS at one
    thread."""
    with single_thread_blas():
        R = modal_roger(model, grid, assembly=assembly, structure=structure)
        tables = R.assembly.dlm_tables
        dry = R.assembly.with_switches(wing_aero=False)  # the p-k's structure, not re-assembled
        an = engine_analyse(R.state_matrix, grid, displacement=R.displacement,
                            state_labels=R.labels(), options=options, xtol=xtol,
                            **({"initial_step": None} if vgf else {}))
        lift = R.lift
        n = R.Phi.shape[0]
        lo, hi = float(grid[0]), float(grid[-1])
        b = b_ref(model)
        points, notes = [], []
        converged: list = []         # (point, its p-k displacement shape, what)
        for pt in an.criticals.points:
            what = f"{pt.kind} {pt.direction} of state-space mode {pt.mode + 1}"
            try:
                c = pk_crossing(model, pt.V, pt.eigenvalue, lo=lo, hi=hi, xtol=xtol,
                                tables=tables, dry=dry, shape=(lift @ pt.eigenvector)[:n])
            except RuntimeError:
                x0 = lift @ pt.eigenvector
                points.append(replace(pt, eigenvector=x0 / np.linalg.norm(x0)))
                notes.append(f"V = {pt.V:.2f} m/s ({what}): the p-k iteration did not converge "
                             "near it; the speed is the Roger state space's (check it with "
                             "method = 'pk')")
                continue
            if c is None:
                k = 2 * np.pi * pt.frequency_hz * b / pt.V
                notes.append(f"V = {pt.V:.2f} m/s ({what}, {pt.frequency_hz:.4g} Hz, k = "
                             f"{k:.3g}) of the Roger state space is not a crossing of the p-k "
                             "method on Q(k) (its root keeps its sign from "
                             f"{max(lo, (1 - CROSSING_SPREAD[-1]) * pt.V):.2f} to "
                             f"{min(hi, (1 + CROSSING_SPREAD[-1]) * pt.V):.2f} m/s): not "
                             "reported")
                continue
            p, k, x = pk_mode(model, c.V, c.p, tables=tables, own_mach=True, dry=dry)
            p = p if p.imag >= 0 else p.conjugate()
            flutter = pt.kind == "flutter"
            half = 0.5 * (pt.bracket[1] - pt.bracket[0])
            bz = pk_benignity(model, c.V, p, tables, dry) if flutter else None
            converged.append((replace(
                pt, V=c.V, bracket=(c.V - half, c.V + half), direction=c.direction,
                eigenvalue=p, frequency_hz=float(abs(p.imag) / (2 * np.pi)) if flutter else 0.0,
                eigenvector=full_state(R.assembly, c.V, p, x[:n]),
                benignity=bz, dzeta_dV=None if bz is None else 1.0 / bz), x[:n], what))
        start = []
        for k in an.criticals.unstable_at_start:
            lam0 = complex(an.sweep.eigenvalues[0, k])
            try:
                p, _ = pk_root(model, lo, lam0, tables=tables, dry=dry)
            except RuntimeError:
                start.append(k)
                continue
            if p.real > 0:
                start.append(k)
            else:
                notes.append(f"V = {lo:.2f} m/s: state-space mode {k + 1} "
                             f"({abs(lam0.imag) / (2 * np.pi):.4g} Hz) is unstable at the first "
                             f"speed in the Roger state space but stable in the p-k method on "
                             f"Q(k) (Re p = {p.real:.3g} 1/s): not reported")
        sw = an.sweep
        lifted = replace(sw, eigenvectors=LiftedEigenvectors(sw.eigenvectors, lift),
                         state_labels=tuple(state_labels), displacement=np.asarray(displacement),
                         stats=dict(sw.stats, reduced_states=R.n_states, reduced_r=R.r))
        once, merged = one_per_root(lifted, converged, xtol)
        # each named after the mode its p-k shape is (in a cluster the p-k may converge a
        # crossing onto another member's root)
        modes = by_shape(lifted, [q.mode for q, _, _ in once], [x for _, x, _ in once],
                         [q.eigenvalue for q, _, _ in once], [q.V for q, _, _ in once],
                         [(q.kind, q.direction) for q, _, _ in once])
        points += [q if m == q.mode else replace(q, mode=m)
                   for (q, _, _), m in zip(once, modes)]
        notes += merged
        points.sort(key=lambda q: q.V)
        crit = Criticals(tuple(points), an.criticals.humps, tuple(start),
                         dict(an.criticals.stats, pk_converged=len(points)))
        return ModalDlmRun(Analysis(lifted, crit), R, tuple(notes))
