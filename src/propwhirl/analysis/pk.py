"""The p-k method with the exact Theodorsen function (issue 14 item 2): typical section, wings.

For each aeroelastic mode and airspeed V the p-k equation (NASTRAN's PK method)

    [ (M_s − M_a) p² − C_a(k) p + (K_s − K_a(k)) ] q̂ = 0,        k = ω b / V,  ω = Im p

is solved by fixed-point iteration on the reduced frequency
(:mod:`propwhirl.analysis.pk_iteration`): the aerodynamic matrices are evaluated at the mode's
current k with the exact C(k) = F(k) + iG(k) (thesis eq. 4.31,
:func:`propwhirl.model.aerodynamics.theodorsen.theodorsen`), the root of the quadratic
eigenproblem nearest the mode's current root is taken, and k is updated to that root's own
frequency until it no longer changes.  The matrices M_a, C_a(k), K_a(k) are the
harmonic-motion form of Theodorsen's loads (7.24–7.27, 7.64–7.66) generated from
``derivations/strip_aero.py`` (``strip_aero.theodorsen_blocks``); the structure is
``typical_section.blocks``, or a wing's own structure and propellers with every strip at its
own k = ω b_i / V (:func:`propwhirl.model.frequency_domain.pk_system`; k reported on the root
semichord).

A wing with ``aero = "dlm"`` has doublet-lattice loads instead of the strips
(:mod:`propwhirl.model.aerodynamics.dlm`: Q(k, M) of the panels, the propellers' Houbolt–Reed loads
unchanged, Mach V/a of each speed or the wing's fixed ``dlm_mach``) in the same p-k equation
with M_a = 0, C_a = ½ρV² Im Q / ω, K_a = ½ρV² Re Q; the finite-state model it starts from, tracks and names
its modes with and reports beside its events is its strip twin
(:func:`propwhirl.model.aerodynamics.dlm.strip_twin`).

This module is the sweep (:func:`pk_sweep`): the modes to follow start from the finite-state
eigenvalues of the model's own state matrix (Leishman–Nguyen or Wagner lag states) at the
first speed and are continued speed by speed, each kept on its own root (:func:`_separate`),
a tight cluster of near-identical modes followed by their shapes in shorter steps
(:data:`MAX_SUBSTEPS`).  Divergence is also found where no followed root shows it: where the
p-k equation's matrix at p = 0 is singular (:mod:`propwhirl.analysis.pk_divergence`; a pair
split on the real axis may leave the sweep on its stable real root).  The flutter speed of a
mode is where its p-k decay rate Re p crosses zero; each crossing is refined in its bracket to
``xtol`` (0.01 m/s by default) as :mod:`propwhirl.analysis.pk_crossings` decides (the secant
from the bracket's ends, Brent's method where it fails, the mode's own branch where its root
hopped onto another's), on a Mach-matched doublet-lattice wing then with Q at the crossing's
own Mach.

**The sweep is modal, the crossings full-order** (issue 37 item 2).  A beam wing's sweep — every
speed's k iterations and each bracket's crossing — runs on a Galerkin basis Φ
(:mod:`propwhirl.analysis.pk_basis`: the followed modes and the p-k's own static correction,
r ≈ 10–30 instead of the model's hundreds of DOFs; a doublet-lattice wing's Q tables projected
on it once), the followed modes of a speed iterated together (one batched eigensolve,
:func:`~propwhirl.analysis.pk_basis.pk_roots`).  Every crossing it finds is then converged on
the full DOFs by the secant method within its bracket
(:func:`~propwhirl.analysis.pk_crossings.full_crossing`), so the reported speed, frequency and
mode shape are the full model's; its shift from the reduced crossing is
:attr:`PKFlutter.shift`.  Where the basis does not hold the full roots at the top speed
(:func:`~propwhirl.analysis.pk_basis.basis_error`), the whole sweep runs on the full DOFs;
``pk_sweep(modal=False)`` always does.  Typical sections and modal models are swept on their
own DOFs.  The p-k root is exact (Theodorsen's C at the mode's frequency) only at Re p = 0,
i.e. at the flutter point; elsewhere its damping is the usual p-k approximation.

In ``analyse(model, method="pk")``
(:func:`propwhirl.analysis.pk_events.pk_instabilities`) each crossing's p-k eigenvector
(:func:`~propwhirl.analysis.pk_iteration.pk_shape` of its root; its displacements on the
model's own DOFs) names the tracked finite-state mode it is
(:func:`~propwhirl.analysis.pk_naming.tracked_mode`, by MAC; events of one cluster of
near-identical modes one to one, :func:`~propwhirl.analysis.pk_naming.one_to_one`) and gives
the event's whirl sense and propeller participation; the benignity is the slope of the p-k
damping ratio at the crossing (:func:`~propwhirl.analysis.pk_crossings.pk_benignity`).

Which modes a wing's sweep follows (:func:`~propwhirl.analysis.pk_basis.followed_modes`) is the
default's choice: those its reduced or modal Roger state space keeps, each from a finite-state
root of its own (:func:`~propwhirl.analysis.pk_basis.start_roots`).

On a doublet-lattice wing every function reads Q(k, M) from ``tables``, the analysis's
:class:`~propwhirl.model.aerodynamics.dlm.DlmTables` (None: new ones for that call — give the
analysis's to reuse its AICs).

The names of :mod:`~propwhirl.analysis.pk_iteration` and
:mod:`~propwhirl.analysis.pk_crossings` (split from this module) are importable from here too.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import linear_sum_assignment

from propwhirl import validate as v
from propwhirl.analysis.pk_divergence import divergence_crossings
# the modes followed and their start, the k iteration, the crossings' refinement and the
# naming of events: with their own modules (their names here too, as before the split)
from propwhirl.analysis.pk_basis import (BASIS_REL, BASIS_TOL, WING_MODES,  # noqa: F401
                                        start_roots, basis_error, first_order, followed_modes,
                                        pk_basis, pk_roots)
from propwhirl.analysis.pk_crossings import (  # noqa: F401
    BENIGNITY_STEP, CONTINUATION_STEPS, CROSSING_SPREAD, HOP, JUMP, MATCHED_STEPS, SLOPE_JUMP,
    PKCrossing, at_own_mach, bracket_crossing, full_crossing, full_solver, matched_crossing,
    pk_benignity, pk_crossing)
from propwhirl.analysis.pk_iteration import (  # noqa: F401
    CLUSTER, KTOL, MET, SAME_ROOT, STATIC, TIGHT, XTOL, pk_matrix, pk_mode, pk_root, pk_shape)
from propwhirl.analysis.pk_naming import (MAC_BAND, TOGETHER, one_to_one,  # noqa: F401
                                         tracked_mode)
from propwhirl.model.aerodynamics import compressibility
from propwhirl.model.protocol import capabilities
from propwhirl.model.aerodynamics.dlm import (DlmTables, check_speed_mach, check_tables,
                                              fixed_mach, strip_twin)
from propwhirl.model.frequency_domain import (
    K_MIN,
    Galerkin,
    check_pk_model,
    dry_assembly,
    pk_system,
    reference_semichord,
)

#: the old private name of :func:`~propwhirl.analysis.pk_basis.start_roots`
_start_roots = start_roots

#: the note that opens a doublet-lattice analysis's notes (ModelAnalysis.doublet_lattice;
#: :func:`propwhirl.analysis.pk_events.dlm_notes`)
DLM_NOTE = "p-k aerodynamics: doublet-lattice"


def _is_section(model) -> bool:
    return capabilities(model).structure == "section"


@dataclass(frozen=True)
class PKFlutter:
    """A p-k flutter crossing of one mode.

    Attributes: mode index (in the order of the in-vacuo frequencies), its in-vacuo label,
    flutter speed V [m/s], frequency [rad/s] and frequency_hz [Hz], reduced frequency k [-],
    the direction ("onset": Re p becomes positive with increasing V; "end") and the kind
    ("flutter"; "divergence" for a non-oscillatory root, frequency 0) and the p-k root
    [1/s] at the crossing (None: not given) — what names the event
    (:func:`propwhirl.analysis.pk_events.pk_instabilities`): in a cluster of near-identical
    modes the swept root before the crossing is nearer another member's root at the crossing
    than its own.
    """

    mode: int
    label: str
    V: float
    frequency: float
    k: float
    event: str = "onset"
    kind: str = "flutter"
    root: complex | None = None
    #: the full-order crossing's speed minus the reduced sweep's [m/s] (the Galerkin basis's
    #: truncation error there, :mod:`propwhirl.analysis.pk_basis`; on a Mach-matched
    #: doublet-lattice wing with the move to Q at the crossing's own Mach,
    #: :func:`matched_crossing`); None: swept on the full DOFs
    shift: float | None = None

    @property
    def frequency_hz(self) -> float:
        return self.frequency / (2 * np.pi)


@dataclass(frozen=True)
class PKSweep:
    """The p-k roots of every mode over a speed grid.

    speeds [m/s] (nV,); roots (nV, nmodes) complex p [1/s] (on the Galerkin basis where
    :attr:`basis_size` > 0: within the basis check's 1 % of the full model's, the crossings
    the full model's); k (nV, nmodes) reduced frequencies;
    labels of the modes; flutter: the crossings, sorted by speed; start: the finite-state
    eigenvalues [1/s] at the first speed the modes started from.
    """

    speeds: np.ndarray
    roots: np.ndarray
    k: np.ndarray
    labels: tuple[str, ...]
    flutter: tuple[PKFlutter, ...]
    start: np.ndarray | None = None
    #: (mode label, V [m/s]) where the k iteration of a mode did not converge: the mode is not
    #: followed beyond that speed (its roots NaN there) — said, never silently dropped
    lost: tuple[tuple[str, float], ...] = ()
    #: the size r of the Galerkin basis the sweep iterated on (0: the model's own DOFs)
    basis_size: int = 0

    @property
    def damping(self) -> np.ndarray:
        """NASTRAN's damping g = 2 Re p / Im p of every root [-]."""
        return 2 * self.roots.real / np.abs(self.roots.imag)

    @property
    def critical(self) -> PKFlutter | None:
        """The lowest-speed onset (flutter or divergence), or None."""
        onsets = [f for f in self.flutter if f.event == "onset"]
        return onsets[0] if onsets else None


#: the most steps per interval of the grid in a tight cluster
MAX_SUBSTEPS = 8


def _separate(model, V: float, system, guess: np.ndarray, p: np.ndarray,
              k: np.ndarray, near: np.ndarray) -> None:
    """Modes whose p-k iterations at V [m/s] met one root each take a root of their own, in
    place (``p`` [1/s], ``k``).  Near-identical propellers' whirl modes (a cluster ~1e-3 apart
    in frequency, whose roots move by more than that between speeds) otherwise collapse onto
    one root speed by speed: x57_like's p-k followed 6 of its 18 modes as one and found none of
    the whirl flutter the default has at 80 m/s.  Only modes of one cluster are separated:
    roots within :data:`MET` of each other whose start roots' |p| (``near``), or whose
    ``guess``es (the roots extrapolated from the last two speeds), are within :data:`CLUSTER`
    of each other — a mode whose frequency falls fast with V meets another that way
    (x57_like's 11.24 Hz mode at 60 m/s landed on the 7.4 Hz one and propeller 7's backward
    whirl flutter at 83.5 m/s went unfollowed); modes far apart that jump onto one root are a
    flutter coalescence, where the p-k following the root both reach is its classical
    behaviour (the wingtip model's 7.8 and 17.8 Hz modes: backward whirl flutter).

    Such a group is iterated together at one k (its roots' mean): each step the roots of
    :func:`pk_matrix` at that k not held by another mode are assigned one to one to the
    group's roots (least total distance; first to their ``guess``es), until the k converges.
    Each member then takes the root of its own k (:func:`pk_root` from the group's) where
    that root is still nearest its own of the group's and apart from every other mode's, else
    keeps the group's: the group's frequencies differ by ~0.1 %, so Q at the mean k is theirs
    to that (a test measures the crossing speeds against the default's)."""
    b = reference_semichord(model)
    ok = np.flatnonzero(np.isfinite(p))
    done: set[int] = set()
    g_abs = np.abs(guess)
    for j in ok:
        if j in done:
            continue
        group = [int(l) for l in ok if abs(p[l] - p[j]) <= MET * abs(p[j])
                 and (abs(near[l] - near[j]) <= CLUSTER * near[j]
                      or abs(g_abs[l] - g_abs[j]) <= CLUSTER * g_abs[j])]
        done.update(group)
        if len(group) < 2:
            continue
        others = np.array([p[l] for l in ok if l not in group])
        cur = guess[group].copy()
        kg = float(np.mean(np.abs(cur.imag))) * b / V
        for _ in range(100):
            lam = np.linalg.eigvals(first_order(system, max(kg, K_MIN) * V / b))
            lam = lam[lam.imag >= 0]
            if others.size:                          # roots other modes hold are not theirs
                held = np.min(np.abs(lam[:, None] - others[None, :]), axis=1)
                lam = lam[held > MET * np.abs(lam)]
            if lam.size < len(group):
                break
            rows, cols = linear_sum_assignment(np.abs(cur[:, None] - lam[None, :]))
            cur = lam[cols][np.argsort(rows)]
            k_new = float(np.mean(np.abs(cur.imag))) * b / V
            if abs(k_new - kg) <= KTOL * max(k_new, K_MIN):
                break
            kg = k_new
        else:
            continue
        if lam.size < len(group):
            continue
        for r, l in enumerate(group):
            p[l], k[l] = cur[r], abs(cur[r].imag) * b / V
        for r, l in enumerate(group):                # each at its own k where it stays its own
            try:
                q, kq = pk_root(model, V, cur[r], system=system)
            except RuntimeError:
                continue
            rest = np.delete(p[ok], np.flatnonzero(ok == l))
            if (int(np.argmin(np.abs(cur - q))) == r
                    and np.all(np.abs(rest - q) > MET * abs(q))):
                p[l], k[l] = q, kq


def pk_sweep(model, speeds, *, xtol: float = XTOL, n_modes: int | None = None,
             tables: DlmTables | None = None, modal: bool = True, dry=None,
             basis: Galerkin | None = None) -> PKSweep:
    """p-k roots of the modes of a typical section or a wing over ``speeds`` [m/s] and their
    flutter and divergence crossings (Re p = 0, refined by Brent's method to ``xtol`` [m/s]).

    ``n_modes``: how many in-vacuo modes (lowest frequencies first) to follow; default every
    mode of a typical section, those up to the reduced models' cut-off of a wing
    (:func:`followed_modes`).  ``tables``: a
    doublet-lattice wing's (the analysis's; None: new ones for this sweep).  ``modal`` (a beam
    wing): the sweep and Brent's method on the Galerkin basis of
    :func:`propwhirl.analysis.pk_basis.pk_basis`, each crossing then converged on the full
    DOFs (:func:`full_crossing`; its shift from the reduced crossing in
    :attr:`PKFlutter.shift`); False: everything on the full DOFs.  ``dry``: the analysis's
    :func:`~propwhirl.model.frequency_domain.dry_assembly` (None: built here); ``basis``: the
    analysis's :func:`~propwhirl.analysis.pk_basis.pk_basis` of the model over ``speeds`` (None
    and ``modal``: built here; where the sweep keeps it, :attr:`PKSweep.basis_size` > 0,
    the analysis's Mach check uses it too).  A tight
    cluster of roots (:data:`TIGHT`: near-identical propellers) is followed by its modes'
    shapes in shorter steps between the speeds, its crossings bracketed in those steps.
    """
    check_pk_model(model)
    V = np.asarray(speeds, dtype=float)
    if V.ndim != 1 or V.size < 2 or np.any(~np.isfinite(V)) or np.any(V <= 0) \
            or np.any(np.diff(V) <= 0):
        raise v.InputError(f"speeds = {speeds!r:.60} is invalid: must be at least two "
                           "increasing airspeeds > 0 [m/s]")
    v.positive("xtol", xtol, "m/s")
    compressibility.check_speeds(model, V)      # matched Prandtl-Glauert strips: Mach <= 0.9
    matched = False
    if strip_twin(model) is not model:  # doublet-lattice tables: every Mach subsonic, first
        check_speed_mach(model, V)
        tables = check_tables(tables)
        matched = fixed_mach(getattr(model, "wing", model)) is None
    if n_modes is None:
        n_modes = None if _is_section(model) else followed_modes(model, V)
    elif not isinstance(n_modes, (int, np.integer)) or n_modes < 1:
        raise v.InputError(f"n_modes = {n_modes!r} is invalid: must be an integer >= 1")
    start, labels = start_roots(model, V[0], n_modes)
    if not modal:
        basis = None
    elif basis is None:
        basis = pk_basis(model, V, tables, n_modes)
    dry = dry_assembly(model) if dry is None else dry   # structure and propellers, once
    full = full_solver(model, tables, dry)
    solve = full if basis is None else (
        lambda x, p0: pk_root(model, x, p0,
                              system=pk_system(model, x, tables, basis=basis, dry=dry)))
    vacuum = np.abs(start)
    roots = np.empty((V.size, start.size), complex)
    ks = np.full((V.size, start.size), np.nan)
    p = start.copy()
    lost: list[tuple[str, float]] = []
    shapes = [None] * start.size
    hist = []                                     # (V, roots) of the last two solved speeds
    subs: dict[int, list] = {}                    # i -> (V, roots) of the steps to V[i]
    for i, Vi in enumerate(V):
        sub = [float(Vi)]
        members = [j for j, x in enumerate(shapes) if x is not None]
        if i >= 2 and members:   # a tight cluster: in steps moving its roots by ≤ TIGHT |p|
            last = roots[i - 1, members]
            move = np.abs(last - roots[i - 2, members]) * (Vi - V[i - 1]) / (V[i - 1] - V[i - 2])
            ratio = np.nanmax(move / (TIGHT * np.abs(last)))
            n = int(min(MAX_SUBSTEPS, np.ceil(ratio))) if np.isfinite(ratio) else 1
            if n > 1:
                sub = list(np.linspace(V[i - 1], Vi, n + 1)[1:])
        for x in sub:
            # the structure and propellers (projected) once per speed
            system = pk_system(model, x, tables, basis=basis, dry=dry)
            guess = p.copy() if len(hist) < 2 else (
                hist[-1][1] + (hist[-1][1] - hist[-2][1]) * (x - hist[-1][0])
                / (hist[-1][0] - hist[-2][0]))                      # extrapolated
            guess = np.where(np.isfinite(guess), guess, p)
            live = np.flatnonzero(np.isfinite(p))
            kk = np.full(start.size, np.nan)
            if live.size:                  # every followed mode's k iteration at once
                reach = (np.zeros(live.size) if len(hist) < 2 else
                         2 * np.abs(guess[live] - hist[-1][1][live]))
                p[live], kk[live] = pk_roots(model, x, p[live], system, ktol=KTOL,
                                             ref=[shapes[j] for j in live],
                                             window=np.where(np.isfinite(reach), reach, 0.0))
            for j in live[~np.isfinite(kk[live])]:  # k does not converge: not followed on
                lost.append((labels[j], float(x)))
            _separate(model, x, system, guess, p, kk, vacuum)
            shapes = _cluster_shapes(model, x, system, p, kk)
            hist = (hist + [(x, p.copy())])[-2:]
            if len(sub) > 1:
                subs.setdefault(i, []).append((x, p.copy()))
        ks[i] = kk
        roots[i] = p
    if basis is not None and np.any(np.array(basis_error(
            model, float(V[-1]), roots[-1], tables, dry=dry))
            > (BASIS_TOL, BASIS_REL)):
        # the basis does not hold the full model's roots at the top speed: the full DOFs
        return pk_sweep(model, V, xtol=xtol, n_modes=n_modes, tables=tables, modal=False)
    events = []
    for j in range(start.size):
        sigma = roots[:, j].real
        ok = np.isfinite(sigma[:-1]) & np.isfinite(sigma[1:])
        for i in np.flatnonzero(ok & (np.sign(sigma[:-1]) != np.sign(sigma[1:]))):
            if sigma[i] == 0.0:
                continue
            bracket = (float(V[i]), float(V[i + 1]), roots[i, j], roots[i + 1, j],
                       sigma[i], sigma[i + 1])
            # in a tight cluster: the step of the interval it crosses in
            steps = [(float(V[i]), roots[i, j])] + [(x, q[j]) for x, q in subs.get(i + 1, [])]
            for (xa, qa), (xb, qb) in zip(steps[:-1], steps[1:]):
                if np.isfinite(qa) and np.isfinite(qb) and qa.real * qb.real < 0:
                    bracket = (xa, xb, qa, qb, qa.real, qb.real)
                    break
            try:
                found = bracket_crossing(model, bracket, xtol, tables, solve, vacuum[j])
            except RuntimeError:
                lost.append((labels[j], float(V[i])))
                continue
            if found is None:      # no crossing of its own: the sign change was the hop's
                continue
            Vf, p, k, start_at = found
            shift = None
            if basis is not None:      # converged on the full DOFs (at its own Mach)
                slope = (sigma[i + 1] - sigma[i]) / (V[i + 1] - V[i])
                # within the bracket, each speed from the root Brent's method started from
                # (matched: continued, as matched_crossing converges a full-order crossing)
                exact = full_crossing(
                    model, Vf, p, slope, lo=float(V[0] if matched else V[i]),
                    hi=float(V[-1] if matched else V[i + 1]), xtol=xtol, tables=tables,
                    own_mach=matched, start=None if matched else start_at, dry=dry)
                if exact is None:      # the secant failed: the bracket on the full DOFs
                    try:
                        exact = bracket_crossing(model, bracket, xtol, tables, full, vacuum[j])
                    except RuntimeError:
                        lost.append((labels[j], float(V[i])))
                        continue
                    if exact is None:
                        continue
                    exact = at_own_mach(model, exact[:3], bracket, V, xtol, tables, matched, dry)
                shift = exact[0] - Vf
                Vf, p, k = exact
            else:
                Vf, p, k = at_own_mach(model, found[:3], bracket, V, xtol, tables, matched, dry)
            static = abs(p.imag) <= STATIC * vacuum[j]
            events.append(PKFlutter(j, labels[j], float(Vf), 0.0 if static else float(abs(p.imag)),
                                    0.0 if static else float(k),
                                    "onset" if sigma[i] < 0 else "end",
                                    "divergence" if static else "flutter", complex(p),
                                    None if shift is None else float(shift)))
    for c in divergence_crossings(model, V, xtol=xtol, tables=tables, dry=dry):
        event = "onset" if c.direction == "onset" else "end"
        Vd, pd = c.V, c.p
        if matched:                        # converged with the AICs at its own Mach
            exact = matched_crossing(model, Vd, pd, c.slope, lo=float(V[0]),
                                     hi=float(V[-1]), xtol=xtol, tables=tables, dry=dry)
            if exact is not None:
                Vd, pd = exact[0], complex(exact[1].real, 0.0)
        if any(e.kind == "divergence" and e.event == event
               and abs(e.V - Vd) <= 2 * xtol for e in events):
            continue                    # the sweep followed that real root itself
        i = int(np.flatnonzero(V <= Vd)[-1])
        ok = np.flatnonzero(np.isfinite(roots[i]))
        if ok.size == 0:
            continue
        j = int(ok[np.argmin(np.abs(roots[i, ok]))])   # the mode whose root is nearest p = 0
        events.append(PKFlutter(j, labels[j], Vd, 0.0, 0.0, event, "divergence", pd))
    events.sort(key=lambda e: (e.V, e.mode))
    unique: list[PKFlutter] = []
    for e in events:  # two followed modes that hopped onto the same root: report it once
        if not any(u.kind == e.kind and u.event == e.event and abs(u.V - e.V) <= 2 * xtol
                   and abs(u.frequency - e.frequency) <= 1e-4 * max(e.frequency, 1.0)
                   for u in unique):
            unique.append(e)
    events = unique
    return PKSweep(V, roots, ks, labels, tuple(events), start, tuple(lost),
                   0 if basis is None else basis.r)


def _cluster_shapes(model, V: float, system, p: np.ndarray, k: np.ndarray) -> list:
    """The first-order eigenvectors (the k-iteration's ``system`` at V [m/s], each root's own
    k) of the roots ``p`` [1/s] that have another followed root within :data:`TIGHT` of |p|
    (not on the same root, within :data:`MET`), None for the others: the shapes the tight
    cluster's modes are followed by at the next step
    (:func:`~propwhirl.analysis.pk_basis.pk_roots`' ``ref``)."""
    out = [None] * p.size
    ok = np.flatnonzero(np.isfinite(p))
    if ok.size < 2:
        return out
    d = np.abs(p[ok][:, None] - p[ok][None, :])
    # another root near, not the same one (two modes met on one root: a coalescence, which
    # shapes do not tell apart; _separate decides those)
    d = np.where(np.eye(ok.size, dtype=bool) | (d <= MET * np.abs(p[ok])[:, None]), np.inf, d)
    near = ok[np.min(d, axis=1) <= TIGHT * np.abs(p[ok])]
    if near.size == 0:
        return out
    b = reference_semichord(model)
    lam, X = np.linalg.eig(first_order(system, np.maximum(k[near], K_MIN) * V / b))
    for a, j in enumerate(near):
        out[j] = X[a][:, int(np.argmin(np.abs(lam[a] - p[j])))]
    return out


def pk_flutter(model, speeds, *, xtol: float = XTOL, n_modes: int | None = None,
               tables: DlmTables | None = None) -> tuple[PKFlutter, ...]:
    """The p-k flutter and divergence crossings of a typical section or a wing over ``speeds``
    [m/s], sorted by speed (exact Theodorsen aerodynamics; see :func:`pk_sweep`)."""
    return pk_sweep(model, speeds, xtol=xtol, n_modes=n_modes, tables=tables).flutter
