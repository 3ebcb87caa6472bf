"""Roger's rational-function approximation of the doublet-lattice GAFs and its state space
(issue 23, item 3b).

On the wing's free bending–torsion DOFs and at one Mach number M, the tabulated Q(k, M)
(:mod:`propwhirl.model.aerodynamics.dlm`) is fitted in the nondimensional Laplace variable p̄ = s b_ref / V
(p̄ = ik on the imaginary axis) by

    Q(p̄) ≈ A₀ + A₁ p̄ + A₂ p̄² + Σ_l A_{2+l} p̄ / (p̄ + β_l),        l = 1 … L

(Roger 1977), every A real, by linear least squares over the reduced frequencies ``ks``
(real and imaginary parts, all entries at once) for given lag roots β_l > 0.  Each lag term
is a set of aerodynamic states x_l (one per wing DOF) with ẋ_l = q̇_w − (V/b) β_l x_l, so the
aeroelastic system at airspeed V with q = ½ρV² is

    (M_s − q (b/V)² A₂) q̈ + (C_s − q (b/V) A₁) q̇ + (K_s − q A₀) q − q Σ_l A_{2+l} x_l = 0

on the model's DOFs (the wing block; the propellers' Houbolt–Reed loads as the model has
them), i.e. a constant-coefficient state matrix of size 2n + L n_w, which the eigenvalue engine
analyses like the strip model's.  :func:`roger_fit` is one fit at one Mach number (a matched
point); its error is reported (:attr:`RogerFit.error`: the largest |Q_fit − Q| over the fitted
k, relative to max |Q|; :attr:`RogerFit.entry_error` per entry).

**The runtime's state space** (:func:`second_order`, what ``PropellerWing.second_order`` and
``analyse(model)`` use on a wing with ``aero = "dlm"``): the Mach number is the wing's
``dlm_mach``, as the p-k method's (:func:`propwhirl.model.aerodynamics.dlm.pk_system_dlm`): by default V / a
at each analysed speed; a fixed number fits the one table column of that Mach
(:func:`column_fit`) and uses it at every speed.  Q is fitted
once at every Mach node of the tables (steps of :data:`~propwhirl.model.aerodynamics.dlm.MACH_STEP`) over the
table's reduced frequencies 0 … :data:`K_MAX` (:func:`fit_ks`) with the lag roots
:data:`DEFAULT_LAGS`, and the A's are interpolated linearly in Mach between the two nodes
around V / a.  The least squares being linear in Q, that is exactly the fit of the tables'
Q(k, V/a) (linear in Mach too): the state space approximates the very Q the p-k iterates on.
The fits are data (matrices fitted from Q(k), kept with the geometry's tables,
:meth:`~propwhirl.model.aerodynamics.dlm.DlmAerodynamics.fitted`, in the analysis's
:class:`~propwhirl.model.aerodynamics.dlm.DlmTables`), assembled here with the model's structure and
propellers at each speed.  The lag states are ordered lag by lag: x_1 of every free wing DOF,
then x_2, …; labelled "node i h lag 1" etc.
"""
from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from propwhirl import validate as v
from propwhirl.model.aerodynamics.dlm import (MACH_MAX, MACH_STEP, DlmAerodynamics, DlmTables,
                                              check_mach, dlm_aerodynamics, fixed_mach,
                                              snap_mach, wing_mach)
from propwhirl.model.aerodynamics.dlm_surface import surface_of
from propwhirl.model.statespace import SecondOrder
from propwhirl.model.statespace import state_matrix as statespace_matrix

#: default lag roots β_l (nondimensional, on the reference semichord)
DEFAULT_LAGS = (0.2, 0.5, 1.0, 2.0)
#: highest reduced frequency (on b_ref) of the runtime's fits (:func:`fit_ks`): the wing's
#: flutter and whirl-flutter roots of the thesis's models sit at k = 0.05–0.8
K_MAX = 2.0
#: the note that opens a Roger-state-space doublet-lattice analysis's notes
RFA_NOTE = "state-space aerodynamics: doublet-lattice"


def _basis(k: np.ndarray, lags: np.ndarray) -> np.ndarray:
    """The complex basis [1, ik, (ik)², ik/(ik + β_l) …] at the reduced frequencies k."""
    p = 1j * np.asarray(k, float)[:, None]
    return np.concatenate([np.ones_like(p), p, p * p, p / (p + lags[None, :])], axis=1)


@dataclass(frozen=True)
class RogerFit:
    """A Roger approximation: ``A`` (3 + L, n_w, n_w) real, ``lags`` β_l (L,), the fitted
    reduced frequencies ``ks``, the Mach number, ``b_ref`` [m] and the relative fit ``error``."""

    A: np.ndarray
    lags: np.ndarray
    ks: np.ndarray
    mach: float
    b_ref: float
    error: float
    #: per entry (n_w, n_w): max over the fitted k of |Q_fit − Q|_ij / max over k of |Q_ij|
    #: (NaN where Q_ij is zero at every k)
    entry_error: np.ndarray | None = None

    def __call__(self, k: float) -> np.ndarray:
        """Q_fit(ik) (n_w, n_w) complex."""
        return np.tensordot(_basis(np.array([k]), self.lags)[0], self.A, axes=1)


def roger_fit(model, mach: float, ks, lags=DEFAULT_LAGS,
              tables: DlmTables | None = None) -> RogerFit:
    """The Roger fit of ``model``'s doublet-lattice Q(k, mach) on its free wing DOFs over the
    reduced frequencies ``ks`` (at least 3 + len(lags) of them, >= 0) with lag roots
    ``lags`` (> 0, distinct), Q from ``tables`` (None: new ones).  InputError for bad
    arguments, before any AIC is computed."""
    if getattr(getattr(model, "wing", model), "aero", None) != "dlm":
        raise v.InputError(f"model = {getattr(model, 'name', model)!r:.60} is invalid for the "
                           "Roger fit: needs a wing with aero = 'dlm'")
    check_mach(float(mach))
    lags = np.asarray(v.positive("lags", lags), float).ravel()
    if lags.size < 1 or np.unique(lags).size != lags.size:
        raise v.InputError(f"lags = {list(lags)} is invalid: must be distinct numbers > 0")
    ks = np.asarray(v.finite("ks", ks), float).ravel()
    if np.any(ks < 0) or np.unique(ks).size < 3 + lags.size:
        raise v.InputError(f"ks has {np.unique(ks).size} distinct reduced frequencies >= 0: "
                           f"the fit needs at least {3 + lags.size}")
    aero = dlm_aerodynamics(model, tables)
    keep = aero.keep
    Q = np.stack([aero.gaf(mach, k)[np.ix_(keep, keep)] for k in ks])      # (m, n_w, n_w)
    return lstsq_fit(Q, ks, lags, float(mach), aero.b_ref)


def lstsq_fit(Q: np.ndarray, ks: np.ndarray, lags: np.ndarray, mach: float,
              b_ref: float) -> RogerFit:
    """The least-squares Roger fit of Q (m, n_w, n_w) tabulated at the m reduced frequencies
    ``ks`` with the lag roots ``lags``."""
    B = _basis(ks, lags)
    rows = np.concatenate([B.real, B.imag])                                  # (2m, 3 + L)
    rhs = np.concatenate([Q.real, Q.imag]).reshape(2 * ks.size, -1)
    coef, *_ = np.linalg.lstsq(rows, rhs, rcond=None)
    A = coef.reshape((3 + lags.size,) + Q.shape[1:])
    A.flags.writeable = False
    dev = np.abs(np.tensordot(B, A, axes=1) - Q)
    error = float(dev.max() / np.abs(Q).max())
    scale = np.abs(Q).max(axis=0)
    with np.errstate(all="ignore"):
        entry = np.where(scale > 0, dev.max(axis=0) / scale, np.nan)
    return RogerFit(A, lags, ks, mach, b_ref, error, entry)


def quasi_steady(model, V: np.ndarray, A: np.ndarray, b_ref: float):
    """``model``'s second-order matrices at the airspeeds V [m/s] (nV,) with the wing's
    doublet-lattice loads' polynomial part of a fit, q (A_0 + A_1 p̄ + A_2 p̄²) on the first n_w
    DOFs (p̄ = s b_ref / V, q = ½ρV²), moved to the left-hand side: (M, C, K, q), M, C, K of
    shape (nV, n, n) and q (nV,); the lag terms are the caller's (Roger's or the minimum
    state's)."""
    dry = replace(model, wing_aero=False).second_order(V)
    q = 0.5 * model.flight.density * V**2
    nw = A.shape[-1]
    M, C, K = (np.array(X, float) for X in (dry.S1, dry.S2, dry.S3))
    M[:, :nw, :nw] -= (q * (b_ref / V) ** 2)[:, None, None] * A[2]
    C[:, :nw, :nw] -= (q * (b_ref / V))[:, None, None] * A[1]
    K[:, :nw, :nw] -= q[:, None, None] * A[0]
    return M, C, K, q


def state_matrix(model, fit: RogerFit, V) -> np.ndarray:
    """The first-order state matrices (nV, 2n + L n_w, 2n + L n_w) of ``model`` with the Roger
    fit of its doublet-lattice loads at the airspeeds V [m/s]; states [q, q̇, x_1, …, x_L]
    (q the model's DOFs without lag states, x_l the lag states of the wing DOFs): the one
    builder, :func:`roger_system`, with ``fit`` at every speed."""
    V = np.atleast_1d(v.positive("airspeed V", V, "m/s"))
    dry = replace(model, wing_aero=False).second_order(V)
    A = np.broadcast_to(fit.A, (V.size,) + fit.A.shape)
    labels, _ = lag_labels(model, fit.lags)
    sys = roger_system(dry, A, V, fit.b_ref, model.flight.density, fit.lags, labels)
    return statespace_matrix(sys, V)


def roger_system(dry: SecondOrder, A: np.ndarray, V: np.ndarray, b_ref: float, rho: float,
                 lags, lag_labels: tuple[str, ...], Phi: np.ndarray | None = None,
                 q_labels: tuple[str, ...] | None = None) -> SecondOrder:
    """The one builder of a Roger state space: the second-order system of the structure and
    propellers ``dry`` (wing aerodynamics off; (nV, n, n), its lag states m₀) with the Roger
    terms of ``A`` (nV, 3 + L, n_w, n_w) on the first n_w DOFs at the airspeeds V [m/s]
    (ρ [kg/m³], b_ref [m], the lag roots ``lags``)

        S1 −= ½ρ b² A₂,  S2 −= ½ρ V b A₁,  S3 −= ½ρV² A₀,  S4 = ½ρV² [A₃ … A_{2+L}],
        ẋ_l = q̇_w − (V/b) β_l x_l,

    the lag states after the dry system's.  ``Phi`` None: on every DOF, a lag state per wing
    DOF and lag (n_w L of them).  ``Phi`` (n, r): on the modes q = Φη
    (:mod:`propwhirl.model.dlm_modal`), Φᵀ(·)Φ of every matrix and lag states x_l = Φ_w z_l,
    ż_l = η̇ − (V/b) β_l z_l (r L of them): the Galerkin projection of the first.
    ``lag_labels`` name the Roger lag states, ``q_labels`` the modes (default: the dry
    system's DOFs)."""
    n, m0, nw = dry.n_dof, dry.n_lag, A.shape[-1]
    T = np.eye(n) if Phi is None else np.asarray(Phi, float)           # q = T η
    Tw = T[:nw]                                                       # the wing DOFs' rows
    B = np.eye(nw) if Phi is None else Tw                             # x_l = B z_l
    G = Tw if Phi is None else np.eye(T.shape[1])                     # ż_l = G η̇ − …: B G = Tw
    nV, r, c, L = V.size, T.shape[1], B.shape[1], len(lags)
    full = Phi is None
    Ap = A[:, :3] if full else np.einsum("ia,vkij,jb->vkab", Tw, A[:, :3], Tw)
    Al = A[:, 3:] if full else np.einsum("ia,vkij,jc->vkac", Tw, A[:, 3:], B)
    q = (0.5 * rho * V**2)[:, None, None]
    S1, S2, S3 = ((np.array(X, float) for X in (dry.S1, dry.S2, dry.S3)) if full else
                  (T.T @ X @ T for X in (dry.S1, dry.S2, dry.S3)))
    w = slice(None, nw) if full else slice(None)                      # where Ap acts
    S1[:, w, w] -= 0.5 * rho * b_ref * b_ref * Ap[:, 2]
    S2[:, w, w] -= q * (b_ref / V)[:, None, None] * Ap[:, 1]
    S3[:, w, w] -= q * Ap[:, 0]
    m = m0 + L * c
    S4, Ww = np.zeros((nV, r, m)), np.zeros((nV, m, m))
    Wv, Wq = np.zeros((nV, m, r)), np.zeros((nV, m, r))
    S4[:, :, :m0], Ww[:, :m0, :m0] = T.T @ dry.S4, dry.Ww
    Wv[:, :m0], Wq[:, :m0] = dry.Wv @ T, dry.Wq @ T
    eye = np.eye(c)
    for l, beta in enumerate(lags):
        z = slice(m0 + l * c, m0 + (l + 1) * c)
        S4[:, w, z] = q * Al[:, l]
        Ww[:, z, z] = -(V / b_ref * beta)[:, None, None] * eye
        Wv[:, z, :] = G
    return SecondOrder(S1, S2, S3, S4, Ww, Wv, Wq,
                       dry.q_labels if q_labels is None else q_labels,
                       dry.w_labels + tuple(lag_labels))


# ----------------------------------------------------------------------------- the runtime's
def b_ref(wing) -> float:
    """The reference semichord [m] of the doublet-lattice k (the root semichord, as
    :class:`~propwhirl.model.aerodynamics.dlm.DlmAerodynamics` has it) of a beam wing or a
    model (:func:`~propwhirl.model.aerodynamics.dlm_surface.surface_of`), without any
    table."""
    return surface_of(wing).b_ref


def fit_ks(k_max: float = K_MAX) -> np.ndarray:
    """The reduced frequencies of the runtime's fits: the tables' own nodes 0, 0.01, … up to
    ``k_max`` (:meth:`~propwhirl.model.aerodynamics.dlm.DlmAerodynamics.k_node`: no interpolated Q fitted)."""
    out, i = [0.0], 1
    while DlmAerodynamics.k_node(i) <= k_max * (1 + 1e-12):
        out.append(DlmAerodynamics.k_node(i))
        i += 1
    return np.array(out)


#: the table nodes (indices of :meth:`~propwhirl.model.aerodynamics.dlm.DlmAerodynamics.k_node`) of the
#: modal state space's fits (:func:`tracking_ks`): every third node from k = 0.018 and the
#: top ones, 8 reduced frequencies with k = 0 instead of the full fit's 20 — the state space
#: only finds and follows the crossings, which the p-k method then converges on Q(k) itself
#: (:mod:`propwhirl.analysis.modal_dlm`), so it needs fewer AICs
TRACKING_K_NODES = (0, 3, 6, 9, 12, 15, 17, 19)


def tracking_ks() -> np.ndarray:
    """The reduced frequencies of the modal Roger state space's fits: the table nodes
    :data:`TRACKING_K_NODES` (0, 0.018, 0.042, 0.1, 0.24, 0.56, 1.0, 1.78), the same top k
    as :func:`fit_ks`."""
    return np.array([DlmAerodynamics.k_node(i) for i in TRACKING_K_NODES])


def node_fit(aero: DlmAerodynamics, im: int, ks: np.ndarray | None = None,
             lags=DEFAULT_LAGS) -> RogerFit:
    """The Roger fit of ``aero``'s tables at Mach node ``im`` (Mach im · MACH_STEP) on the free
    wing DOFs (root removed), over ``ks`` (default :func:`fit_ks`) with ``lags``; computed once
    per geometry and kept with its tables (:meth:`~propwhirl.model.aerodynamics.dlm.DlmAerodynamics.fitted`)."""
    return column_fit(aero, im * MACH_STEP, ks, lags)


def column_fit(aero: DlmAerodynamics, mach: float, ks: np.ndarray | None = None,
               lags=DEFAULT_LAGS) -> RogerFit:
    """The Roger fit of ``aero``'s table column of Mach ``mach`` (a Mach node's, or a wing's
    fixed ``dlm_mach``: :func:`~propwhirl.model.aerodynamics.dlm.snap_mach`) as :func:`node_fit`."""
    ks = fit_ks() if ks is None else np.asarray(ks, float)
    lags = np.asarray(lags, float)
    mach = snap_mach(mach)

    def make() -> RogerFit:
        keep = aero.keep
        nodes = {aero.k_node(i): i for i in range(len(ks) + 64)}
        if any(k not in nodes for k in ks):          # not the tables' own k: interpolated
            Q = np.stack([aero.gaf(mach, k, exact_mach=True)[np.ix_(keep, keep)] for k in ks])
        else:                                        # the table nodes themselves, no more
            Q = np.stack([aero.column_node(mach, nodes[k])[np.ix_(keep, keep)] for k in ks])
        return lstsq_fit(Q, ks, lags, mach, aero.b_ref)

    return aero.fitted(("roger", mach, ks.tobytes(), lags.tobytes()), make)


def mach_nodes(mach: float) -> tuple[int, float]:
    """(im, t): Mach = (im + t) · MACH_STEP, 0 <= t < 1, im the table node below (the top node
    at :data:`~propwhirl.model.aerodynamics.dlm.MACH_MAX`)."""
    x = float(mach) / MACH_STEP
    im = min(int(np.floor(x + 1e-12)), int(round(MACH_MAX / MACH_STEP)))
    return im, x - im


def coefficients(model, V, ks: np.ndarray | None = None,
                 tables: DlmTables | None = None) -> np.ndarray:
    """The Roger matrices A (nV, 3 + L, n_w, n_w) of ``model``'s doublet-lattice wing at the
    airspeeds V [m/s]: at Mach V / a, linear in Mach between the fits of the two Mach nodes
    around it (:func:`node_fit`); with a fixed ``dlm_mach``, the one fit of its own column
    (:func:`column_fit`) at every speed; fitted over the reduced frequencies ``ks`` (default
    :func:`fit_ks`; the modal state space's :func:`tracking_ks`), from ``tables`` (the
    analysis's; None: new ones).  InputError when V / a is beyond the tables' Mach."""
    V = np.atleast_1d(np.asarray(V, float))
    for Vi in V:
        check_mach(wing_mach(model, Vi), Vi)
    aero = dlm_aerodynamics(model, tables)
    fixed = fixed_mach(aero.surface)
    if fixed is not None:
        A = column_fit(aero, fixed, ks).A
        return np.broadcast_to(A, (V.size,) + A.shape).copy()
    a = model.flight.speed_of_sound
    out = None
    for i, Vi in enumerate(V):
        im, t = mach_nodes(Vi / a)
        A = node_fit(aero, im, ks).A
        if t > 1e-9:
            A = (1 - t) * A + t * node_fit(aero, im + 1, ks).A
        if out is None:
            out = np.empty((V.size,) + A.shape)
        out[i] = A
    return out


def lag_labels(model, lags=DEFAULT_LAGS) -> tuple[tuple[str, ...], tuple[int, ...]]:
    """Labels ("node i h lag l", a modal model's "mode i lag l") and wing nodes (-1: none) of
    the Roger lag states of ``model``: lag by lag, every DOF the panels load (a beam's free
    wing DOFs, h, φ, α of nodes >= 1; a modal model's modes)."""
    surface = surface_of(model)
    labels = tuple(f"{d} lag {l + 1}" for l in range(len(lags)) for d in surface.labels)
    nodes = tuple(n for _ in range(len(lags)) for n in surface.nodes)
    return labels, nodes


def second_order(assembly, V: np.ndarray, omega=None) -> SecondOrder:
    """The second-order system with lag states (:class:`~propwhirl.model.statespace.SecondOrder`)
    of a PropellerWing with ``aero = "dlm"`` at the airspeeds V [m/s] (1-D array): its structure
    and propellers (the ``assembly``'s blocks with the wing aerodynamics off, Houbolt–Reed loads
    unchanged at the hubs), and on the free wing DOFs the Roger terms of :func:`coefficients`
    (:func:`roger_system`), the lag states after any the structure and propellers have.
    ``omega`` [rad/s] as :meth:`~propwhirl.model.systems.PropellerWingAssembly.blocks`; the
    fits from the assembly's tables (``assembly.dlm_tables``, the analysis's) over its
    ``dlm_fit_ks`` (None: :func:`fit_ks`)."""
    model = assembly.model
    V = np.atleast_1d(np.asarray(V, float))
    ks = None if assembly.dlm_fit_ks is None else np.asarray(assembly.dlm_fit_ks, float)
    A = coefficients(model, V, ks, tables=assembly.dlm_tables)
    dry = assembly.with_switches(wing_aero=False).blocks(V, omega).dense()
    labels, _ = lag_labels(model, DEFAULT_LAGS)
    return roger_system(dry, A, V, b_ref(model), model.flight.density, DEFAULT_LAGS,
                        labels)


def fits_used(model, V, ks: np.ndarray | None = None,
              tables: DlmTables | None = None) -> list[RogerFit]:
    """The runtime's node fits (:func:`node_fit`, over ``ks``: default :func:`fit_ks`) that
    airspeeds between min(V) and max(V) [m/s] use (computed if not yet, in ``tables``: the
    analysis's), by Mach."""
    aero = dlm_aerodynamics(model, tables)
    fixed = fixed_mach(aero.surface)
    if fixed is not None:
        return [column_fit(aero, fixed, ks)]
    a = model.flight.speed_of_sound
    V = np.atleast_1d(np.asarray(V, float))
    lo, _ = mach_nodes(V.min() / a)
    hi, t = mach_nodes(V.max() / a)
    return [node_fit(aero, im, ks) for im in range(lo, hi + (2 if t > 1e-9 else 1))]



def rfa_note(model, V, modal=None, tables: DlmTables | None = None) -> str:
    """What a Roger-state-space doublet-lattice analysis over the speeds V [m/s] used
    (:data:`RFA_NOTE` first): panels, lag roots, fitted k, Mach, the worst fit error of the
    fits that analysis used (:func:`fits_used`: those of its speed range and reduced
    frequencies, whatever else the tables hold); with ``modal`` (a
    :class:`~propwhirl.model.dlm_modal.ModalRoger`, the default analysis: its fits over
    :func:`tracking_ks`) the modes it kept and that its crossings are the p-k method's;
    ``tables``: the analysis's (the fits it used)."""
    aero = dlm_aerodynamics(model, tables)
    m = aero.mesh
    V = np.atleast_1d(np.asarray(V, float))
    fixed = fixed_mach(aero.surface)
    where = ("at every Mach node, linear in Mach V/a" if fixed is None else
             f"at the fixed Mach {fixed:g} (dlm_mach) for every speed")
    fits = fits_used(model, V, None if modal is None else tracking_ks(), tables)
    worst = max(fits, key=lambda f: f.error)
    ks = fits[0].ks
    return (f"{RFA_NOTE} panels ({m.n_chord} chordwise x {m.n_span} spanwise on the half-wing), "
            f"Roger state space: lag roots {', '.join(f'{x:g}' for x in fits[0].lags)}, fitted "
            f"on k = {ks.min():g}-{ks.max():.3g} ({ks.size} values, root semichord b_ref = "
            f"{aero.b_ref:.4g} m) {where}; worst fit error "
            f"{100 * worst.error:.2g} % of max |Q| (Mach {worst.mach:.2f})"
            + ("" if modal is None else
               f"; on the {modal.r} in-vacuo modes up to {modal.frequencies_hz[-1]:.4g} Hz "
               f"(cut-off {modal.cutoff_hz:.4g} Hz: the lower of 3 x the reference "
               f"{modal.reference_hz:.4g} Hz and the fit's k at the top speed), every crossing "
               "converged by the p-k method on Q(k) with the whole structure"))


def extrapolation_notes(model, events) -> list[str]:
    """One note per event (``Instability``-like: kind, event, label, V [m/s], frequency_hz)
    whose reduced frequency k = 2π f b_ref / V lies beyond the fitted k (:func:`fit_ks`):
    there the Roger state space extrapolates Q (at low speeds a structural mode's k is large
    and its small aerodynamic damping can change sign), so the event is to be checked by the
    p-k method or by analysing from higher speeds."""
    b = b_ref(model)
    top = float(fit_ks()[-1])
    out = []
    for e in events:
        k = 2 * np.pi * e.frequency_hz * b / e.V
        if k > top * (1 + 1e-9):
            out.append(f"V = {e.V:.2f} m/s ({e.kind} {e.event} of {e.label}): reduced frequency "
                       f"k = {k:.3g} beyond the Roger fit's k <= {top:.3g}, where the state "
                       "space extrapolates the doublet-lattice loads; check it with method = "
                       "'pk' or analyse from higher speeds")
    return out
