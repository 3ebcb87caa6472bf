"""The p-k root of one mode at one speed and its mode shape (the k iteration), and when two
roots are one or form a cluster.

For an aeroelastic mode at airspeed V the p-k equation (NASTRAN's PK method)

    [ (M_s − M_a) p² − C_a(k) p + (K_s − K_a(k)) ] q̂ = 0,        k = ω b / V,  ω = Im p

is solved by fixed-point iteration on the reduced frequency (:func:`pk_root`): the
aerodynamic matrices evaluated at the mode's current k, the root of the first-order matrix
(:func:`pk_matrix`) nearest the mode's current root taken, k updated to that root's own
frequency until it no longer changes (:data:`KTOL`); several modes at once, one batched
eigensolve, :func:`propwhirl.analysis.pk_basis.pk_roots`.  :func:`pk_mode` and
:func:`pk_shape` give a converged root's eigenvector.  Where two followed roots are one
(:data:`SAME_ROOT`, :data:`MET`) and where near-identical modes form a cluster
(:data:`CLUSTER`, :data:`TIGHT`) is decided here, for the sweep
(:func:`propwhirl.analysis.pk.pk_sweep`) and the crossings
(:mod:`propwhirl.analysis.pk_crossings`) alike.
"""
from __future__ import annotations

import numpy as np

from propwhirl.analysis.pk_basis import first_order, pk_roots
from propwhirl.model.aerodynamics.dlm import DlmTables
from propwhirl.model.frequency_domain import K_MIN, pk_system, reference_semichord

#: accuracy of every flutter speed [m/s]
XTOL = 0.01
#: relative convergence of the reduced frequency in the p-k iteration (a wing's eigenvalues carry
#: ~1e-8 of rounding noise, so tighter stalls; the flutter speed moves by far less than XTOL)
KTOL = 1e-7
#: a root with Im p below this fraction of its in-vacuo frequency is non-oscillatory
#: (a crossing of such a root is divergence, not flutter)
STATIC = 1e-6


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
#: (:func:`propwhirl.analysis.pk._separate`): the iteration converges k to :data:`KTOL`, so one
#: root reached by two modes each at its own k differs by up to ~1e-6 (x57_like at 80 m/s: 8e-7,
#: which :data:`SAME_ROOT` missed, and one of its six whirl flutters went unfollowed); the
#: closest distinct roots of its near-identical propellers are ~1e-4 apart
MET = 1e-5


#: modes whose start roots' |p|, or whose roots extrapolated to the speed, are within this
#: fraction of each other form a cluster (near-identical propellers, a mount's pitch and yaw:
#: x57_like's are 0.7-7 % apart) whose roots :func:`propwhirl.analysis.pk._separate` keeps apart
CLUSTER = 0.1

#: a tight cluster: a followed root with another within this fraction of |p|.  The sweep follows
#: such modes by their shapes (:func:`propwhirl.analysis.pk._cluster_shapes`, the MAC in
#: :func:`~propwhirl.analysis.pk_basis.pk_roots`) in steps that move their roots by no more than
#: this fraction of |p| (up to :data:`~propwhirl.analysis.pk.MAX_SUBSTEPS` per interval of the
#: grid), and brackets their crossings in those steps.  x57_like (six near-identical propellers,
#: roots ~1e-3 of |p| apart, moving ~9 % of |p| per 10 m/s): with the nearest-root rule alone
#: the cluster's onsets on 1-250 m/s every 10 / 5 / 2.5 m/s were 5 / 3 / 5 of the default's five
#: and propeller 7's on two of the three grids; with 0.02 and 0.04 the same six onsets on every
#: grid (0.04: the sweep 1.7 times the time, 0.02: 2.8 times)
TIGHT = 0.04


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
