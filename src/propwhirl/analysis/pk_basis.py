"""The p-k sweep on modes (issue 37 item 2: modal reduction for the p-k): the Galerkin basis a
wing's sweep iterates on, and the k iteration of several modes at once.

A beam wing's p-k sweep (:func:`propwhirl.analysis.pk.pk_sweep`) follows its modes on the
projection Φᵀ (M, C(ω), K(ω)) Φ of the p-k equation (:func:`pk_basis`): Φ holds the in-vacuo
modes the sweep follows (:func:`followed_modes`, one place for that choice) and their static
correction under the p-k's steady loads at the middle and the top of the speed range,
M-orthonormal (a doublet-lattice wing's from its strip twin), r ≈ 10–30 instead of the model's
hundreds of DOFs.  The strips' loads are summed on Φ's rows
strip by strip; a doublet-lattice wing's Q tables are projected on Φ once for every speed and k
(the interpolation in k and Mach is linear in the tables' values, so it commutes with the
projection: :class:`~propwhirl.model.frequency_domain.Galerkin`).  Every crossing the reduced
sweep finds is then converged on the full DOFs
(:func:`propwhirl.analysis.pk_crossings.full_crossing`), so the reported speeds, frequencies
and mode shapes are the full model's; the shift from the reduced crossing is the basis's
truncation error there (:attr:`PKFlutter.shift <propwhirl.analysis.pk.PKFlutter>`).  Typical
sections (2 DOFs) and modal models (already modal) are swept on their own DOFs.

Which modes a wing's sweep follows and where each starts (:func:`followed_modes`,
:func:`start_roots`) is decided here too.

:func:`pk_roots` iterates the followed modes of one speed together — each with its own k and
its own rules (nearest root, relaxation; those of
:func:`propwhirl.analysis.pk_iteration.pk_root`, which is its one-mode case) — solving the
eigenproblems of all of them in one batched ``np.linalg.eigvals`` call.
"""
from __future__ import annotations

import numpy as np
import scipy.linalg as sla
from scipy.optimize import linear_sum_assignment

from propwhirl.analysis.modes import InVacuo
from propwhirl.engine import mac
from propwhirl.model.aerodynamics.dlm import DlmTables, strip_twin
from propwhirl.model.dlm_modal import kept_modes
from propwhirl.model.frequency_domain import K_MIN, Galerkin, pk_system, reference_semichord
from propwhirl.model.protocol import capabilities
from propwhirl.model.reduction import GRAM_TOL, cutoff

#: a mode with several roots within its reach at a new speed takes the one of its own shape
#: (:func:`pk_roots`' ``ref``) when that one's MAC with its last shape is at least this and
#: the next one's at most half of it, else the nearest root (x57_like's cluster, this rule
#: without the sweep's shorter steps: 0.9 left propeller 7's onset unfollowed on its 10 m/s
#: grid, 0.7 followed it)
MAC_CLEAR = 0.7

#: the fewest in-vacuo modes a wing's p-k sweep follows by default (lowest frequencies first;
#: :func:`followed_modes`)
WING_MODES = 6


#: the reduced sweep is kept when at the top speed (:func:`basis_error`) each reduced root is
#: within this fraction of its distance to the nearest other followed mode's from the full
#: model's root continued from it (each mode then takes the same root by the nearest-root rule
#: on the basis as on the full DOFs) ...
BASIS_TOL = 0.1
#: ... and within this fraction of |p| of it; else the sweep runs on the full DOFs.  Measured
#: (ratio, relative): strips and the benchmark's DLM wings at most 2.4e-4 and 6.8e-5; the
#: small DLM wings of the tests (3 × 8, 4 × 12 panels) 2.6e-3 and 3.0e-3; Patil's HALE wing
#: at 5.4 times its divergence speed 0.049 and 0.050 — there the reduced sweep missed a
#: divergence the full one has (a root that turns real 50 m/s later on the basis)
BASIS_REL = 0.01


def pk_basis(model, speeds, tables: DlmTables | None = None,
             n_modes: int | None = None) -> Galerkin | None:
    """The Galerkin basis of the p-k sweep of ``model`` over ``speeds`` [m/s] (module
    docstring), or None for a model swept on its own DOFs (a typical section, a modal model).
    ``tables``: a doublet-lattice wing's (the analysis's: the projected tables read them);
    ``n_modes``: how many in-vacuo modes the sweep follows (default :func:`followed_modes`).

    The in-vacuo modes Φ the sweep follows (of the strip twin's structure: the lowest
    ``n_modes``) and their static correction under the p-k's own steady loads,
    K_s⁻¹ (K(V, k → 0) − K_s) Φ at the middle and the top of the range (K_s the structure's
    stiffness, K(V, 0) the strip twin's p-k stiffness: the steady loads of the exact
    Theodorsen strips, the propellers' as they are), the whole M-orthonormal (dependent
    vectors dropped).  Measured at the top speed (:func:`basis_error`: the largest error
    relative to |p| and to the distance from the nearest other root; the examples over 60
    speeds), this basis / the one the sweep used before — the default's
    (:func:`~propwhirl.model.reduction.dof_basis`: its modes and their finite-state static
    correction) with this correction added:

    ==================  ======  ==================  ==================
    case                r       relative            to the nearest
    ==================  ======  ==================  ==================
    x57_like            29/35   3.2e-5 / 1.4e-6     1.8e-4 / 2.4e-5
    four_propeller      24/29   1.7e-5 / 1.3e-5     7.4e-5 / 6.1e-5
    wingtip             11/14   1.3e-4 / 9.2e-6     4.2e-4 / 3.0e-5
    Goland strips       14/17   1.5e-5 / 1.8e-5     1.0e-4 / 1.3e-4
    Goland 4 × 7 DLM    11/17   2.2e-4 / 6.8e-5     2.8e-4 / 2.4e-4
    ==================  ======  ==================  ==================

    Every crossing is converged on the full DOFs anyway
    (:func:`propwhirl.analysis.pk_crossings.full_crossing`): the same events on every case of
    ``benchmarks/pk_events_compare.py`` (speeds within 0.0014 m/s), the sweeps 4-23 %
    faster."""
    if capabilities(model).structure != "beam":
        return None
    V = np.asarray(speeds, float)
    twin = strip_twin(model)
    iv = InVacuo.of(twin.without_aerodynamics())
    _, shapes = sla.eigh(iv.K, iv.M)
    n = followed_modes(model, V) if n_modes is None else int(n_modes)
    Phi = shapes[:, :n]
    cho = sla.cho_factor(iv.K)
    B = np.hstack([Phi] + [sla.cho_solve(cho, (pk_system(twin, x)(0.0)[2] - iv.K) @ Phi)
                           for x in (0.5 * (V[0] + V[-1]), V[-1])])
    M = iv.M
    norm2 = np.einsum("ij,ij->j", B, M @ B)       # a zero correction (no steady load) adds
    B = B[:, norm2 > GRAM_TOL * norm2.max()]      # nothing: dropped before the normalisation
    for _ in range(2):                    # M-orthonormal, dependent vectors dropped; twice,
        B = B / np.sqrt(np.einsum("ij,ij->j", B, M @ B))     # for the rounding of the first
        g, U = sla.eigh(B.T @ M @ B)
        ok = g > GRAM_TOL * g.max()
        B = B @ (U[:, ok] / np.sqrt(g[ok]))
    return Galerkin(model, B, tables)


def basis_error(model, V: float, roots: np.ndarray, tables: DlmTables | None = None,
                *, dry=None) -> tuple[float, float]:
    """The largest |p_r − p| / d and |p_r − p| / |p| of the reduced sweep's ``roots`` p_r
    [1/s] at V [m/s] (the finite ones, each converged at its own k), p the full model's root
    at that same k nearest p_r (the root the full model's k iteration takes there: the full
    first-order matrices of every root's k in one batched eigensolve, no k iteration), d the
    distance of p from the nearest other of those roots (two modes on one root, within 1e-5
    of |p|, are one).  ``dry``: the analysis's
    :func:`~propwhirl.model.frequency_domain.dry_assembly`."""
    live = roots[np.isfinite(roots)]
    if live.size == 0:
        return 0.0, 0.0
    b = reference_semichord(model)
    lams = np.linalg.eigvals(first_order(pk_system(model, V, tables, dry=dry),
                                         np.maximum(np.abs(live.imag) * b / V, K_MIN) * V / b))
    full = np.array([lam[np.argmin(np.abs(lam - p))] for lam, p in zip(lams, live)])
    worst = 0.0
    for j, p in enumerate(full):
        d = np.abs(full - p)
        d = d[d > 1e-5 * abs(p)]
        worst = max(worst, abs(live[j] - p) / (d.min() if d.size else abs(p)))
    return float(worst), float(np.max(np.abs(live - full) / np.abs(full)))


def first_order(system, omega) -> np.ndarray:
    """The first-order matrix [[0, I], [−M⁻¹K, −M⁻¹C]] of the p-k system ``system`` (ω ↦ (M, C,
    K), :func:`~propwhirl.model.frequency_domain.pk_system`) at ω [rad/s]; ω an array (m,):
    the m matrices stacked (m, 2n, 2n), built together."""
    M, Cd, K = system(omega)
    n = M.shape[-1]
    A = np.zeros(M.shape[:-2] + (2 * n, 2 * n))
    A[..., :n, n:] = np.eye(n)
    A[..., n:, :] = -np.linalg.solve(M, np.concatenate([K, Cd], axis=-1))
    return A


def pk_roots(model, V: float, p0, system, *, ktol: float, maxiter: int = 200,
             secant: bool = True, ref=None, window=None) -> tuple[np.ndarray, np.ndarray]:
    """The p-k roots [1/s] at airspeed V [m/s] of the modes whose roots were ``p0`` [1/s], and
    their k [-]: for each mode the fixed point k = Im p(k) · b / V (b: the reference
    semichord; p(k) the root of the first-order matrix at k nearest the previous one), until
    an iterate's k moves by no more than ``ktol`` of itself.  Each step is the secant step on
    the residual h(k) = Im p(k) b / V − k through the last two iterates where that step is
    0.1 to 100 times the plain step h in its direction (the map k ↦ k + h has a slope in
    [−9, 0.99] there), else the plain step k ← k + h under-relaxed (halving, down to 1/64)
    while the steps oscillate without shrinking; the converged root is the same fixed point
    either way, the secant only takes fewer steps (in the Goland wing's sweep 3–4 instead of
    5–9; ``secant=False``: the plain steps only).  ``ref`` (one first-order eigenvector or None
    per mode) and ``window`` (a radius [1/s] per mode): at the first step a mode with several
    roots within its window of p0 takes the one whose eigenvector's MAC (eq. 5.14,
    :func:`propwhirl.engine.mac`) with its ``ref`` is clearly the best
    (:data:`MAC_CLEAR`), else the nearest — a tight cluster's modes followed by their shapes
    (:func:`propwhirl.analysis.pk.pk_sweep`).  The first-order matrices of all
    modes still iterating are built together and their eigenvalues solved in one batched
    call.  A mode whose k does not converge in ``maxiter`` iterations gets NaN (root and k).
    ``system``: the p-k system at V (full or projected; vectorised over ω,
    :func:`~propwhirl.model.frequency_domain.pk_system`)."""
    b = reference_semichord(model)
    p = np.array(p0, dtype=complex).ravel()
    k = np.abs(p.imag) * b / V
    m = p.size
    relax, last = np.ones(m), np.zeros(m)
    k_prev, h_prev = np.full(m, np.nan), np.full(m, np.nan)
    kout = np.full(m, np.nan)
    active = np.ones(m, dtype=bool)
    for it in range(maxiter):
        ids = np.flatnonzero(active)
        if ids.size == 0:
            break
        A = first_order(system, np.maximum(k[ids], K_MIN) * V / b)
        lams = np.linalg.eigvals(A)
        for a, (lam, j) in enumerate(zip(lams, ids)):
            lam = lam[lam.imag >= 0] if np.any(lam.imag > 0) else lam
            pick = int(np.argmin(np.abs(lam - p[j])))
            if it == 0 and ref is not None and ref[j] is not None:
                near = np.flatnonzero(np.abs(lam - p[j]) <= window[j])
                if near.size > 1:       # several roots within the mode's reach: its shape's
                    w, X = np.linalg.eig(A[a])
                    cols = [int(np.argmin(np.abs(w - lam[n]))) for n in near]
                    fit = np.ravel(mac(ref[j], X[:, cols]))
                    order = np.argsort(fit)[::-1]
                    if fit[order[0]] >= MAC_CLEAR and fit[order[1]] <= 0.5 * fit[order[0]]:
                        pick = int(near[order[0]])
            p[j] = lam[pick]
            k_new = abs(p[j].imag) * b / V
            step = k_new - k[j]
            if abs(step) <= ktol * max(k_new, K_MIN):
                kout[j], active[j] = k_new, False
                continue
            if step * last[j] < 0 and abs(step) >= 0.5 * abs(last[j]):  # oscillating
                relax[j] = max(relax[j] / 2, 1 / 64)
            elif step * last[j] > 0:                                    # monotone again
                relax[j] = min(2 * relax[j], 1.0)
            last[j] = step
            move = relax[j] * step
            dk = k[j] - k_prev[j]
            if secant and dk != 0 and np.isfinite(dk):                  # the secant
                gain = dk / (h_prev[j] - step) if h_prev[j] != step else np.inf
                if 0.1 <= gain <= 100:                                  # step = gain · h
                    move = gain * step
            k_prev[j], h_prev[j] = k[j], step
            k[j] = k[j] + move
    p[active] = complex(np.nan, np.nan)
    return p, kout


def followed_modes(model, speeds) -> int:
    """How many in-vacuo modes (lowest first) a wing's p-k sweep over ``speeds`` [m/s]
    follows by default: the modes the default's state space keeps — on strips every mode up
    to the reduced models' cut-off (:func:`propwhirl.model.reduction.cutoff`:
    :data:`~propwhirl.model.reduction.CUTOFF_FACTOR` times the highest of the second bending,
    first torsion, first chordwise and every propeller-dominated mode), at least
    :data:`WING_MODES`; on a doublet-lattice wing the modal Roger state space's
    (:func:`propwhirl.model.dlm_modal.kept_modes`: also no higher than its fit's range).
    A fixed six missed every whirl mode of a wing with many propellers (x57_like: its seven
    propellers' modes are its 2nd to 15th; the p-k found no instability where the default has
    whirl flutter at 80.0 m/s); on strips x57_like follows 18, the four-propeller example 15,
    the wingtip model 7."""
    twin = strip_twin(model)
    iv = InVacuo.of(twin.without_aerodynamics())
    w2, shapes = sla.eigh(iv.K, iv.M)
    f = np.sqrt(np.abs(w2)) / (2 * np.pi)
    if twin is not model:
        return kept_modes(model, model, f, shapes, iv.M, speeds)[0]
    _, fc = cutoff(model, f, shapes, iv.M)
    return max(int(np.sum(f <= fc)), min(WING_MODES, f.size))


def start_roots(model, V: float, n_modes: int | None) -> tuple[np.ndarray, tuple[str, ...]]:
    """The finite-state eigenvalues at V [m/s] of the model's oscillatory modes (one per
    in-vacuo mode, the lowest `n_modes`), and the modes' labels.

    Each in-vacuo root gets its own finite-state root: the one-to-one assignment of least
    total relative distance |p − ω|/|ω| (Hungarian method), not each root's nearest — two
    close modes (the wingtip wing's 16.68 and 18.06 Hz) would otherwise both start from the
    root at 17.96 Hz and the other mode, the one that flutters, would never be followed."""
    model = strip_twin(model)           # a doublet-lattice wing starts from its strips
    vac = np.linalg.eigvals(model.without_aerodynamics().state_matrix(np.array([V]))[0])
    vac = vac[vac.imag > 0]
    vac = vac[np.argsort(vac.imag)][:n_modes]
    fs = np.linalg.eigvals(model.state_matrix(np.array([V]))[0])
    fs = fs[fs.imag > 0]
    cost = np.abs(fs[None, :] - vac[:, None]) / np.abs(vac)[:, None]
    rows, cols = linear_sum_assignment(cost)       # rows: every in-vacuo mode (fewer than fs)
    vac = vac[rows]
    start = fs[cols]
    labels = tuple(f"mode {j + 1} ({w.imag / (2 * np.pi):.4g} Hz in vacuo)"
                   for j, w in enumerate(vac))
    return start, labels
