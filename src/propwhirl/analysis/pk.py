"""The p-k method with the exact Theodorsen function (issue 14 item 2): typical section, wings.

For each aeroelastic mode and airspeed V the p-k equation (NASTRAN's PK method)

    [ (M_s − M_a) p² − C_a(k) p + (K_s − K_a(k)) ] q̂ = 0,        k = ω b / V,  ω = Im p

is solved by fixed-point iteration on the reduced frequency: the aerodynamic matrices are
evaluated at the mode's current k with the exact C(k) = F(k) + iG(k) (thesis eq. 4.31,
:func:`propwhirl.model.aerodynamics.theodorsen.theodorsen`), the root of the quadratic eigenproblem nearest
the mode's current root is taken, and k is updated to that root's own frequency until it no
longer changes.  The matrices M_a, C_a(k), K_a(k) are the harmonic-motion form of Theodorsen's
loads (7.24–7.27, 7.64–7.66) generated from ``derivations/strip_aero.py``
(``strip_aero.theodorsen_blocks``); the structure is ``typical_section.blocks``, or a wing's
own structure and propellers with every strip at its own k = ω b_i / V
(:func:`propwhirl.model.frequency_domain.pk_system`; k reported on the root semichord).

A wing with ``aero = "dlm"`` has doublet-lattice loads instead of the strips
(:mod:`propwhirl.model.aerodynamics.dlm`: Q(k, M) of the panels, the propellers' Houbolt–Reed loads
unchanged, Mach V/a of each speed or the wing's fixed ``dlm_mach``) in the same p-k equation
with M_a = 0, C_a = ½ρV² Im Q / ω, K_a = ½ρV² Re Q; the finite-state model it starts from, tracks and names
its modes with and reports beside its events is its strip twin
(:func:`propwhirl.model.aerodynamics.dlm.strip_twin`).

The modes to follow start from the finite-state eigenvalues of the model's own state matrix
(Leishman–Nguyen or Wagner lag states) at the first speed, and are continued speed by speed.
Divergence is also found where no followed root shows it: where the p-k equation's matrix at
p = 0 is singular (:mod:`propwhirl.analysis.pk_divergence`; a pair split on the real axis may
leave the sweep on its stable real root).
The flutter speed of a mode is where its p-k decay rate Re p crosses zero from below, refined by
Brent's method to ``xtol`` (0.01 m/s by default; where the mode's root hopped onto another's
between two speeds, on its own branch continued across the bracket, :func:`_continued`); on
a Mach-matched doublet-lattice wing then converged with Q at the crossing's own Mach
(:func:`matched_crossing`).

**The sweep is modal, the crossings full-order** (issue 37 item 2).  A beam wing's sweep — every
speed's k iterations and Brent's method on each bracket — runs on a Galerkin basis Φ
(:mod:`propwhirl.analysis.pk_basis`: the default's reduced basis and the p-k's own static
correction, r ≈ 10–30 instead of the model's hundreds of DOFs; a doublet-lattice wing's Q
tables projected on it once), the followed modes of a speed iterated together (one batched
eigensolve, :func:`~propwhirl.analysis.pk_basis.pk_roots`).  Every crossing it finds is then
converged on the full DOFs by the secant method within its bracket, each speed's root from the
one Brent's method started from (:func:`full_crossing`; Brent's method on the full DOFs where
the secant fails), so the reported speed, frequency and mode shape are the full model's; its
shift from the reduced crossing is :attr:`PKFlutter.shift`.  Where the basis does not hold
the full roots at the top speed (:func:`~propwhirl.analysis.pk_basis.basis_error`), the whole
sweep runs on the full DOFs; ``pk_sweep(modal=False)`` always does.  Typical sections and modal
models are swept on their own DOFs.  The p-k root is exact
(Theodorsen's C at the mode's frequency) only at Re p = 0, i.e. at the flutter point;
elsewhere its damping is the usual p-k approximation.

In ``analyse(model, method="pk")``
(:func:`propwhirl.analysis.pk_events.pk_instabilities`) each crossing's p-k eigenvector
(:func:`pk_shape` of its root; its displacements on the model's own DOFs) names the tracked
finite-state mode it is (:func:`~propwhirl.analysis.pk_naming.tracked_mode`, by MAC; events of
one cluster of near-identical modes one to one,
:func:`~propwhirl.analysis.pk_naming.one_to_one`) and gives the event's whirl sense and
propeller participation; the benignity is the slope of the p-k damping ratio at the crossing
(:func:`pk_benignity`).

Which modes a wing's sweep follows (:func:`followed_modes`) is the default's choice: those its
reduced or modal Roger state space keeps, each from a finite-state root of its own
(:func:`~propwhirl.analysis.pk_basis.start_roots`) and kept on its own root speed by speed (:func:`_separate`).

On a doublet-lattice wing every function reads Q(k, M) from ``tables``, the analysis's
:class:`~propwhirl.model.aerodynamics.dlm.DlmTables` (None: new ones for that call — give the
analysis's to reuse its AICs).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq, linear_sum_assignment

from propwhirl import validate as v
from propwhirl.analysis.pk_divergence import divergence_crossings
# the modes followed and their start, and the naming of events: with their own modules
from propwhirl.analysis.pk_basis import (BASIS_REL, BASIS_TOL, WING_MODES,  # noqa: F401
                                        start_roots, basis_error, first_order, followed_modes,
                                        pk_basis, pk_roots)
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

#: accuracy of every flutter speed [m/s]
XTOL = 0.01
#: relative convergence of the reduced frequency in the p-k iteration (a wing's eigenvalues carry
#: ~1e-8 of rounding noise, so tighter stalls; the flutter speed moves by far less than XTOL)
KTOL = 1e-7
#: a root with Im p below this fraction of its in-vacuo frequency is non-oscillatory
#: (a crossing of such a root is divergence, not flutter)
STATIC = 1e-6
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


def pk_matrix(model, V: float, k: float, tables: DlmTables | None = None) -> np.ndarray:
    """First-order matrix of the p-k equation at airspeed V [m/s] and reduced frequency k [-]
    (on the reference semichord, :func:`~propwhirl.model.frequency_domain.reference_semichord`).

    Its eigenvalues p [1/s] solve (M_s − M_a) p² − C_a(k) p + (K_s − K_a(k)) = 0 with the
    exact Theodorsen C(k) (eq. 4.31): :func:`propwhirl.model.frequency_domain.pk_matrices`.
    """
    return _first_order(pk_system(model, V, tables),
                        max(k, K_MIN) * V / reference_semichord(model))


#: the first-order matrix of a p-k system (:func:`propwhirl.analysis.pk_basis.first_order`)
_first_order = first_order


def pk_root(model, V: float, p0: complex, *, ktol: float = KTOL, maxiter: int = 200,
            system=None, tables: DlmTables | None = None,
            own_mach: bool = False, dry=None, ref=None,
            window: float = 0.0) -> tuple[complex, float]:
    """The p-k root [1/s] of the mode nearest ``p0`` at airspeed V [m/s], and its k [-].

    Fixed-point iteration k ← Im p · b / V (b: the reference semichord) with the root of
    :func:`pk_matrix` nearest the previous one, under-relaxed (halving the step, down to
    1/64) while the steps oscillate without shrinking
    (:func:`propwhirl.analysis.pk_basis.pk_roots` of one mode); raises RuntimeError when k
    does not converge in ``maxiter`` iterations.  ``system``: :func:`pk_system` of (model, V)
    if already built (full or projected; else built with ``tables`` and ``own_mach``: a
    Mach-matched doublet-lattice wing's Q at its own Mach V/a, :func:`matched_crossing`, not
    between the tables' Mach nodes; ``dry``: the analysis's
    :func:`~propwhirl.model.frequency_domain.dry_assembly` of the model).  ``ref`` (a
    first-order eigenvector of ``system``'s size) and ``window`` [1/s]: with several roots
    within ``window`` of ``p0`` the one of ``ref``'s shape where its MAC is clearly the best
    (:func:`~propwhirl.analysis.pk_basis.pk_roots`: a tight cluster's member followed by
    its shape).
    """
    system = pk_system(model, V, tables, own_mach, dry=dry) if system is None else system
    p, k = pk_roots(model, V, [p0], system, ktol=ktol, maxiter=maxiter,
                    ref=None if ref is None else [ref], window=[window])
    if not np.isfinite(k[0]):
        raise RuntimeError(f"p-k iteration did not converge at V = {V} m/s (from p = {p0})")
    return complex(p[0]), float(k[0])


#: two modes' p-k roots closer than this fraction of |p| are one root (the iteration's own
#: accuracy is KTOL in k; the closest distinct roots of six near-identical propellers on
#: x57_like are ~1e-4 apart)
SAME_ROOT = 1e-7


#: two followed modes whose p-k roots are closer than this fraction of |p| met on one root
#: (:func:`_separate`): the iteration converges k to :data:`KTOL`, so one root reached by two
#: modes each at its own k differs by up to ~1e-6 (x57_like at 80 m/s: 8e-7, which
#: :data:`SAME_ROOT` missed, and one of its six whirl flutters went unfollowed); the closest
#: distinct roots of its near-identical propellers are ~1e-4 apart
MET = 1e-5


#: modes whose start roots' |p|, or whose roots extrapolated to the speed, are within this
#: fraction of each other form a cluster (near-identical propellers, a mount's pitch and yaw:
#: x57_like's are 0.7-7 % apart) whose roots :func:`_separate` keeps apart
CLUSTER = 0.1

#: a tight cluster: a followed root with another within this fraction of |p|.  The sweep
#: follows such modes by their shapes (:func:`_cluster_shapes`, the MAC in
#: :func:`~propwhirl.analysis.pk_basis.pk_roots`) in steps that move their roots by no more
#: than this fraction of |p| (up to :data:`MAX_SUBSTEPS` per interval of the grid), and
#: brackets their crossings in those steps.  x57_like (six near-identical propellers, roots
#: ~1e-3 of |p| apart, moving ~9 % of |p| per 10 m/s): with the nearest-root rule alone the
#: cluster's onsets on 1-250 m/s every 10 / 5 / 2.5 m/s were 5 / 3 / 5 of the default's five
#: and propeller 7's on two of the three grids; with 0.02 and 0.04 the same six onsets on
#: every grid (0.04: the sweep 1.7 times the time, 0.02: 2.8 times)
TIGHT = 0.04
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
            lam = np.linalg.eigvals(_first_order(system, max(kg, K_MIN) * V / b))
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


def pk_mode(model, V: float, p0: complex, *, system=None, tables: DlmTables | None = None,
            own_mach: bool = False, dry=None) -> tuple[complex, float, np.ndarray]:
    """The p-k root [1/s] nearest ``p0`` at V [m/s] (:func:`pk_root`), its k [-] and its
    eigenvector: the first-order state (q̂, p q̂) on the model's degrees of freedom (the
    first ``dof_map().n_dof`` entries are the displacement shape q̂, the same DOFs as the
    finite-state model's, which adds only its lag states after them), scaled to unit norm."""
    system = pk_system(model, V, tables, own_mach, dry=dry) if system is None else system
    p, k = pk_root(model, V, p0, system=system)
    return p, k, pk_shape(model, V, p, system=system)


def pk_shape(model, V: float, p: complex, *, system=None, tables: DlmTables | None = None,
             own_mach: bool = False, dry=None) -> np.ndarray:
    """The eigenvector of a converged p-k root ``p`` [1/s] at V [m/s] (:func:`pk_mode`'s: the
    first-order state on the model's DOFs, unit norm): that of the first-order matrix at
    k = |Im p| b / V whose eigenvalue is nearest p."""
    b = reference_semichord(model)
    system = pk_system(model, V, tables, own_mach, dry=dry) if system is None else system
    k = abs(complex(p).imag) * b / V
    lam, X = np.linalg.eig(_first_order(system, max(k, K_MIN) * V / b))
    i = int(np.argmin(np.abs(lam - p)))
    x = X[:, i] if lam[i].imag >= 0 else X[:, i].conj()
    return x / np.linalg.norm(x)


def _brent_between(model, a: float, b: float, pa: complex, pb: complex, xtol: float,
                   tables, solve=None) -> tuple[float, complex, float]:
    """Brent's method on Re p between the speeds a < b [m/s] whose p-k roots ``pa`` and
    ``pb`` [1/s] have opposite signs of Re p, each speed's root continued from the root
    interpolated linearly between them (so that both ends are the roots the bracket was
    found with, not another mode's a far start jumps to): (V, p, k).  RuntimeError when a
    root does not converge or the ends' roots lose their signs.  ``solve``: (V, p0) ↦ (p, k),
    the root at V from p0 (default: :func:`pk_root` on the full DOFs, with ``tables``)."""
    solve = _full_solver(model, tables) if solve is None else solve

    def guess(x: float) -> complex:
        return pa + (pb - pa) * (x - a) / (b - a)

    def decay(x: float) -> float:
        return solve(x, guess(x))[0].real

    try:
        V = brentq(decay, a, b, xtol=xtol)
    except ValueError:             # the ends' roots re-solved lost their signs: not a bracket
        raise RuntimeError(f"p-k bracket [{a}, {b}] m/s lost its sign change") from None
    p, k = solve(V, guess(V))
    return float(V), p, float(k)


def _full_solver(model, tables, dry=None, ref=None, window: float = 0.0):
    """(V, p0) ↦ :func:`pk_root` of ``model`` on its full DOFs (``tables``: a doublet-lattice
    wing's; ``dry``: the analysis's :func:`~propwhirl.model.frequency_domain.dry_assembly`;
    ``ref``, ``window``: the root by its shape in a tight cluster)."""
    return lambda x, p0: pk_root(model, x, p0, tables=tables, dry=dry, ref=ref, window=window)


#: a crossing whose root keeps more than this fraction of the larger |Re p| of its bracket's
#: ends is no crossing but a hop: Brent's method converged onto a speed where the root
#: continued from the bracket's left end jumps to another mode's (:func:`_continued`)
HOP = 0.05
#: a crossing across which the root, continued as Brent's method did, moves by more than this
#: fraction of the mode's frequency within ±2 xtol is a hop too (:func:`_jumps`)
JUMP = 0.01


def _jumps(solve, Vf: float, bracket: tuple[float, float], ends: tuple[complex, complex],
           xtol: float, scale: float) -> bool:
    """Whether the p-k root at the crossing speed Vf [m/s] jumps: continued by ``solve``
    (V, p0) ↦ (p, k) from the ``bracket``'s [m/s] left root ``ends[0]`` and from the root
    interpolated between its ends' (both ways Brent's method may have solved it), at
    Vf ∓ 2 ``xtol`` it differs by more than :data:`JUMP` × ``scale`` [1/s] (the mode's
    in-vacuo frequency or |p|).  A true crossing is continuous there (a change of ~1e-4 of the
    frequency); Brent's method converges onto a hop as readily — the wingtip example's
    17.7 Hz mode, whose root went from the 6 Hz mode's (Re p = −0.57) to the 7 Hz mode's
    (+18.4) between two speeds, had false flutter onsets and recoveries from 160.9 to
    256.2 m/s, which the |Re p| test (:data:`HOP`, of the larger end's) passed."""
    a, b = Vf - 2 * xtol, Vf + 2 * xtol
    v0, v1 = bracket
    for guess in (lambda x: ends[0],
                  lambda x: ends[0] + (ends[1] - ends[0]) * (x - v0) / (v1 - v0)):
        try:
            lo, _ = solve(a, guess(a))
            hi, _ = solve(b, guess(b))
        except RuntimeError:
            return True
        if abs(hi - lo) > JUMP * scale:
            return True
    return False


#: speed steps :func:`_continued` continues a mode by across a bracket
CONTINUATION_STEPS = 16


def _continued(model, a: float, b: float, pa: complex, xtol: float,
               tables, solve=None) -> tuple[float, complex, float] | None:
    """The crossing (Re p = 0) of the mode whose p-k root is ``pa`` [1/s] at a [m/s],
    continued to b [m/s] in :data:`CONTINUATION_STEPS` steps, each speed's root from the one
    extrapolated from the last two (so that it stays on its own branch where other modes' roots
    lie nearer its root at a than its own: a cluster of near-identical propellers), refined by
    Brent's method to ``xtol`` on the first step whose ends' roots change sign: (V, p, k), or
    None when the continued root keeps its sign (the bracket's sign change was a hop onto
    another mode's root).  RuntimeError when a root does not converge or hops again.
    ``solve``: as :func:`_brent_between`'s."""
    solve = _full_solver(model, tables) if solve is None else solve
    xs = np.linspace(a, b, CONTINUATION_STEPS + 1)
    prev, cur = complex(pa), complex(pa)
    for x0, x1 in zip(xs[:-1], xs[1:]):
        guess = 2 * cur - prev if x0 > a else cur
        nxt, _ = solve(float(x1), guess)
        if cur.real != 0 and nxt.real != 0 and (cur.real > 0) != (nxt.real > 0):
            left = cur

            def decay(x: float) -> float:
                return solve(x, left + (nxt - left) * (x - x0) / (x1 - x0))[0].real

            try:
                V = brentq(decay, float(x0), float(x1), xtol=xtol)
            except ValueError:
                raise RuntimeError(f"p-k continuation [{x0}, {x1}] m/s lost its sign "
                                   "change") from None
            p, k = solve(V, left + (nxt - left) * (V - x0) / (x1 - x0))
            if abs(p.real) > HOP * max(abs(left.real), abs(nxt.real)):
                raise RuntimeError(f"p-k root hops between {x0} and {x1} m/s")
            return float(V), p, float(k)
        prev, cur = cur, nxt
    return None


#: secant steps :func:`matched_crossing` takes at most
MATCHED_STEPS = 12
#: a secant that converges with a slope d Re p/dV over this many times the one it started
#: from converged onto a hop (:func:`full_crossing`): a root that jumps from one branch to
#: another with the opposite sign of Re p (x57_like's neighbouring propellers on panels,
#: ~1e-3 of |p| apart) draws the secant onto the jump with slopes growing without bound
#: (their two branches in tests/analysis/test_pk.py: 3.7 against 0.015 1/s per m/s, 250
#: times).  On the crossings of every case of benchmarks/pk_events_compare.py, p-k and
#: default, the ratio is 0.88-1.6.  A hop this lets pass (a jump of Re p under ~0.005 m/s ×
#: this × the slope) lies within ~0.05 m/s of its branch's true crossing
SLOPE_JUMP = 10.0


def matched_crossing(model, V0: float, p0: complex, slope: float, *, lo: float, hi: float,
                     xtol: float = XTOL, tables: DlmTables | None = None,
                     dry=None, ref=None,
                     window: float = 0.0) -> tuple[float, complex, float] | None:
    """The crossing Re p = 0 of a Mach-matched doublet-lattice wing with Q at the Mach V/a of
    every speed tried (issue 37 item 5): from the AICs of the fine columns
    (:data:`~propwhirl.model.aerodynamics.dlm.MACH_FINE` = 0.001 apart) around it, within 2e-7
    of max |Q| of that Mach's own AICs at Mach 0.6, from the crossing ``V0`` [m/s] (root
    ``p0`` [1/s]) found on the tables' Mach interpolation, whose ``slope`` d Re p/dV [1/s per
    m/s] starts the secant method: (V [m/s], p, k), V within ``xtol`` / 10 of the root (the
    last secant step: a fixed-Mach analysis at V/a moves its onset by (dV/dM)/a times that,
    ~9 on the wingtip wing's near-neutral whirl hump), or None when the secant leaves
    [``lo``, ``hi``], meets a flat Re p or takes more than :data:`MATCHED_STEPS` steps (the
    caller keeps V0).

    Between the tables' Mach nodes (0.05 apart) Q is linear in Mach, within ~5e-4 of max |Q| of
    the AICs at that Mach (Mach 0.6-0.66); a near-neutral whirl mode (a damping hump just
    touching zero) turns that into metres per second of onset.  At its own Mach, the onset
    is the one the same wing has with its ``dlm_mach`` fixed at the onset's own V/a (tested).
    ``ref``, ``window``: each root's by its shape in a tight cluster (:func:`pk_root`).
    """
    return full_crossing(model, V0, p0, slope, lo=lo, hi=hi, xtol=xtol, tables=tables,
                         own_mach=True, dry=dry, ref=ref, window=window)


def full_crossing(model, V0: float, p0: complex, slope: float, *, lo: float, hi: float,
                  xtol: float = XTOL, tables: DlmTables | None = None, own_mach: bool = False,
                  start=None, dry=None, ref=None,
                  window: float = 0.0) -> tuple[float, complex, float] | None:
    """The crossing Re p = 0 on the full DOFs of the mode whose root is near ``p0`` [1/s] at
    ``V0`` [m/s] (a crossing found on a Galerkin basis or on interpolated tables), by the secant
    method from ``slope`` d Re p/dV [1/s per m/s]: each step's p-k root from the last, until the
    step is within ``xtol`` / 10 [m/s]: (V, p, k), or None when the secant leaves [``lo``,
    ``hi``], meets a flat Re p or takes more than :data:`MATCHED_STEPS` steps.  ``own_mach``:
    a Mach-matched doublet-lattice wing's Q at each speed's own Mach (:func:`matched_crossing`).
    ``start``: V ↦ the root each speed's k iteration starts from (the one the crossing was
    bracketed with, :func:`_bracketed`: near a coalescence the p-k has two roots there, and the
    start decides which); None: from the previous step's root.  ``ref``, ``window``: each
    root's by its shape in a tight cluster (:func:`pk_root`).  Where the reduced crossing is
    within xtol / 10 of the full one, one p-k root decides it.  A root that hops from one
    mode's branch to another's between the last two steps makes the secant's slope steep and
    its step short without a crossing: a converged step whose slope is over :data:`SLOPE_JUMP`
    times the given ``slope`` is None."""
    if not np.isfinite(slope) or slope == 0.0:
        return None
    V, guess = float(V0), complex(p0)
    given = slope
    prev = None                                  # (V, Re p) of the previous exact point
    for _ in range(MATCHED_STEPS):
        try:
            p, k = pk_root(model, V, guess if start is None else start(V), tables=tables,
                           own_mach=own_mach, dry=dry, ref=ref, window=window)
        except RuntimeError:
            return None
        if prev is not None and p.real != prev[1]:
            slope = (p.real - prev[1]) / (V - prev[0])        # the secant's
        step = 0.0 if p.real == 0.0 else -p.real / slope
        if abs(step) <= 0.1 * xtol:
            if abs(slope) > SLOPE_JUMP * abs(given):           # a hop, not a crossing
                return None
            return V, p, float(k)
        if not (np.isfinite(step) and lo <= V + step <= hi):
            return None
        prev, guess, V = (V, p.real), p, V + step
    return None


#: half-widths of the brackets :func:`pk_crossing` tries around a finite-state crossing, as
#: fractions of its speed (the Roger fit's crossings lie within ~1 % of the p-k's)
CROSSING_SPREAD = (0.01, 0.02, 0.04, 0.08, 0.16)


@dataclass(frozen=True)
class PKCrossing:
    """A crossing converged by :func:`pk_crossing`: speed V [m/s], the p-k root p [1/s] and
    its k [-] there, and the direction ("onset": Re p − → + with V; "recovery")."""

    V: float
    p: complex
    k: float
    direction: str


def pk_crossing(model, V0: float, p0: complex, *, lo: float, hi: float,
                xtol: float = XTOL, tables: DlmTables | None = None,
                dry=None, shape: np.ndarray | None = None) -> PKCrossing | None:
    """The p-k crossing (Re p = 0) of the mode whose root is near ``p0`` [1/s] at V0 [m/s]:
    a bracket around V0 of half-width :data:`CROSSING_SPREAD` × V0 (widened in turn, within
    [``lo``, ``hi``] [m/s]) where the p-k root continued from ``p0`` changes sign, refined
    within it by the secant method from its ends' roots (:func:`full_crossing`, each speed's
    root from the one interpolated between the ends', to ``xtol`` / 10; 2-3 p-k roots where
    Brent's method took 5-6), by Brent's method to ``xtol`` [m/s] where the secant leaves
    the bracket.  ``shape``: the mode's displacement shape on the model's DOFs (n,) at V0
    (the state-space crossing's): in a tight cluster (near-identical propellers, roots within
    :data:`TIGHT` of |p0|) every root is that member's, the one of its shape where the MAC
    says so clearly (:func:`pk_root`), not the nearest — the nearest is another member's
    from one speed to the next, and Brent's method converged onto such a hop (x57_like on
    panels: "onsets" at 80.34-80.39 m/s with Re p = +0.0034 1/s, which the p-k does not
    have).  A Brent result whose |Re p| keeps :data:`HOP` of its ends' is such a hop: a
    wider bracket is tried.  None when the p-k root keeps its sign over the widest
    bracket (the p-k has no crossing there); RuntimeError when the k iteration does not
    converge.  What the default analysis of a doublet-lattice wing converges its modal Roger
    state space's crossings with (:mod:`propwhirl.analysis.modal_dlm`)."""
    tables = check_tables(tables) if strip_twin(model) is not model else None
    V0 = float(np.clip(V0, lo, hi))
    ref, window = None, 0.0
    if shape is not None:
        x = np.asarray(shape, dtype=complex)
        ref, window = np.concatenate([x, complex(p0) * x]), TIGHT * abs(p0)
    guess = {"lo": complex(p0), "hi": complex(p0)}
    for s in CROSSING_SPREAD:
        a, b = max(lo, V0 * (1 - s)), min(hi, V0 * (1 + s))
        pa, _ = pk_root(model, a, guess["lo"], tables=tables, dry=dry, ref=ref, window=window)
        pb, _ = pk_root(model, b, guess["hi"], tables=tables, dry=dry, ref=ref, window=window)
        guess["lo"], guess["hi"] = pa, pb
        if pa.real != 0 and pb.real != 0 and (pa.real > 0) != (pb.real > 0):
            def start(x: float, a=a, b=b, pa=pa, pb=pb) -> complex:
                return pa + (pb - pa) * (x - a) / (b - a)
            slope = (pb.real - pa.real) / (b - a)
            V1 = a - pa.real / slope                  # the secant from the ends' roots
            found = full_crossing(model, V1, start(V1), slope, lo=a, hi=b, xtol=xtol,
                                  tables=tables, start=start, dry=dry, ref=ref, window=window)
            if found is not None:
                V, p, k = found
            else:                         # the secant left the bracket: Brent's method
                try:
                    V, p, k = _brent_between(model, a, b, pa, pb, xtol, tables,
                                             _full_solver(model, tables, dry, ref, window))
                except RuntimeError:      # continued from a, another root at b: not this
                    continue              # root's bracket (was a traceback); a wider one
                if abs(p.real) > HOP * max(abs(pa.real), abs(pb.real)):
                    continue              # Brent's method converged onto a hop
            if tables is not None and fixed_mach(getattr(model, "wing", model)) is None:
                exact = matched_crossing(model, V, p, (pb.real - pa.real) / (b - a), lo=lo,
                                         hi=hi, xtol=xtol, tables=tables, dry=dry, ref=ref,
                                         window=window)
                if exact is not None:
                    V, p, k = exact
            return PKCrossing(float(V), p, float(k), "onset" if pa.real < 0 else "recovery")
        if a <= lo and b >= hi:
            break
    return None


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
    full = _full_solver(model, tables, dry)
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
                found = _bracketed(model, bracket, xtol, tables, solve, vacuum[j])
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
                        exact = _bracketed(model, bracket, xtol, tables, full, vacuum[j])
                    except RuntimeError:
                        lost.append((labels[j], float(V[i])))
                        continue
                    if exact is None:
                        continue
                    exact = _matched(model, exact[:3], bracket, V, xtol, tables, matched, dry)
                shift = exact[0] - Vf
                Vf, p, k = exact
            else:
                Vf, p, k = _matched(model, found[:3], bracket, V, xtol, tables, matched, dry)
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


def _bracketed(model, bracket, xtol: float, tables, solve, scale: float):
    """The crossing of one mode in a bracket of the sweep, ``bracket`` = (a, b, p_a, p_b,
    Re p_a, Re p_b) (speeds [m/s], the mode's roots [1/s] there, of opposite signs of Re p),
    each root by ``solve`` (V, p0) ↦ (p, k): Brent's method on Re p, each speed's root
    continued from the left root, or — where the ends' roots are within :data:`CLUSTER` of
    |p| of each other, one branch moving continuously — from the root interpolated between
    them (:func:`_brent_between`); either way the other where the first fails; where Brent
    met a hop onto another mode's root, the mode continued across the bracket
    (:func:`_continued`; None: no crossing of its own): (V, p, k, start), ``start`` V ↦ the
    root each speed's iteration started from.  RuntimeError when a root does not converge.

    From the left root every speed's iteration starts 1-10 m/s away from its root: in
    x57_like's cluster of near-identical propellers (roots ~1e-3 of |p| apart, moving ~1 %
    per 2.5 m/s) the modes of four brackets on a 2.5 m/s grid all took the same root inside
    their brackets and converged onto one crossing (80.66 m/s), and the critical (79.99 m/s,
    the default's 80.00) was not reported; from the interpolated root each keeps its own
    (79.99, 80.07, 80.10, 80.62 and 80.66 m/s).  Where the ends are far apart the sweep's
    mode hopped onto another's root between them (the wingtip example's 17.7 Hz mode onto the
    7 Hz mode's): the interpolation would pass the hop smoothly, the left root's own branch
    shows it (:func:`_jumps`).

    First the secant method from the ends' roots (:func:`_secant_in`, each speed's root from
    the same start as Brent's first choice): 2-3 roots where Brent's method and the hop
    check took ~10; Brent's method as above where the secant leaves the bracket or converges
    onto a hop."""
    a, b, pa, pb, sa, sb = bracket
    close = abs(pb - pa) <= CLUSTER * max(abs(pa), abs(pb))
    found = _secant_in(solve, bracket, xtol, max(scale, abs(pa)), close)
    if found is not None:
        return found

    def from_left():
        try:
            Vf = brentq(lambda x: solve(x, pa)[0].real, a, b, xtol=xtol)
        except ValueError:   # the right end, continued from the left root, is another mode's
            raise RuntimeError(f"p-k bracket [{a}, {b}] m/s: the left root's continuation "
                               "keeps its sign") from None
        return (Vf,) + solve(Vf, pa) + (lambda x: pa,)

    def between():
        return _brent_between(model, a, b, pa, pb, xtol, tables, solve) + (
            lambda x: pa + (pb - pa) * (x - a) / (b - a),)

    first, second = (between, from_left) if close else (from_left, between)
    try:
        Vf, p, k, start = first()
    except RuntimeError:
        Vf, p, k, start = second()
    if abs(p.real) > HOP * max(abs(sa), abs(sb)) or _jumps(
            solve, float(Vf), (a, b), (pa, pb), xtol, max(scale, abs(p))):
        # Brent met a hop onto another mode's root: the mode's own
        found = _continued(model, a, b, pa, xtol, tables, solve)
        return None if found is None else found + (None,)
    return float(Vf), p, float(k), start


def _secant_in(solve, bracket, xtol: float, scale: float, close: bool):
    """The crossing in a sweep's ``bracket`` (:func:`_bracketed`'s) by the secant method from
    its ends' roots, each speed's root by ``solve`` from the root interpolated between them
    (``close``: one branch moving continuously) or from the left one, until a step is within
    ``xtol`` / 10 [m/s]: (V, p, k, start), or None when the secant leaves the bracket, takes
    more than :data:`MATCHED_STEPS` steps, or converges onto a hop — its last slope over
    :data:`SLOPE_JUMP` times the bracket's, or its last two roots more than :data:`JUMP` ×
    ``scale`` [1/s] apart (as :func:`_jumps` tests Brent's).  RuntimeError when a root does
    not converge."""
    a, b, pa, pb, sa, sb = bracket

    def start(x: float) -> complex:
        return pa + (pb - pa) * (x - a) / (b - a) if close else pa

    given = slope = (sb - sa) / (b - a)
    V, prev = a - sa / slope, None
    for _ in range(MATCHED_STEPS):
        if not a <= V <= b:
            return None
        p, k = solve(V, start(V))
        if prev is not None and p.real != prev[1].real:
            slope = (p.real - prev[1].real) / (V - prev[0])
        step = 0.0 if p.real == 0.0 else -p.real / slope
        if abs(step) <= 0.1 * xtol:
            if abs(slope) > SLOPE_JUMP * abs(given) or (
                    prev is not None and abs(p - prev[1]) > JUMP * scale):
                return None
            return float(V), p, float(k), start
        prev, V = (V, p), V + step
    return None


def _matched(model, found, bracket, V, xtol: float, tables, matched: bool, dry=None):
    """``found`` (V, p, k), converged with the AICs at its own Mach on a Mach-matched
    doublet-lattice wing (:func:`matched_crossing`; kept where that fails)."""
    if not matched:
        return found
    a, b, _, _, sa, sb = bracket
    exact = matched_crossing(model, found[0], found[1], (sb - sa) / (b - a), lo=float(V[0]),
                             hi=float(V[-1]), xtol=xtol, tables=tables, dry=dry)
    return found if exact is None else exact


def pk_flutter(model, speeds, *, xtol: float = XTOL, n_modes: int | None = None,
               tables: DlmTables | None = None) -> tuple[PKFlutter, ...]:
    """The p-k flutter and divergence crossings of a typical section or a wing over ``speeds``
    [m/s], sorted by speed (exact Theodorsen aerodynamics; see :func:`pk_sweep`)."""
    return pk_sweep(model, speeds, xtol=xtol, n_modes=n_modes, tables=tables).flutter


#: central-difference step [m/s] of the p-k damping ratio for the benignity (eq. 5.13)
BENIGNITY_STEP = 0.1


def pk_benignity(model, V: float, p: complex,
                 tables: DlmTables | None = None, dry=None) -> float | None:
    """(dζ/dV)⁻¹ [m/s] (eq. 5.13) of the p-k root through ``p`` at V, ζ = −Re p/|p| (eq. 5.5),
    by a central difference of :data:`BENIGNITY_STEP`; None if dζ/dV is 0 or a root is lost.
    On the model's DOFs: on the sweep's Galerkin basis it would be ~2 ms faster on the Goland
    wing and 0.2 % off on the wingtip wing's 4 × 12 panels (−78.49 vs −78.66 m/s, the same
    with steps of 0.05-0.2 m/s: the basis's error in the slope, not the difference's)."""
    h = BENIGNITY_STEP
    try:
        lo, _ = pk_root(model, V - h, p, tables=tables, dry=dry)
        hi, _ = pk_root(model, V + h, p, tables=tables, dry=dry)
    except RuntimeError:
        return None
    dz = (-hi.real / abs(hi) + lo.real / abs(lo)) / (2 * h)
    return 1.0 / dz if dz != 0 else None
