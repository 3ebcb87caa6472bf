"""The undamped structure's modes: in-vacuo modes, their thesis names, and their paths over Ω.

:func:`model_modes`
    The in-vacuo modes of any model (K x = ω² M x, aerodynamics off), or its Rayleigh–Ritz
    modes on a reduced model's basis.
:func:`label_modes`
    The thesis's names of those modes ("wing n", "backward k", "forward k"), from how each
    frequency moves as the rotors spin up: every mode followed from Ω = 0 to a small spin rate.
:func:`track_gyroscopic`
    Every mode of the undamped gyroscopic system followed along the rotational speed Ω: the
    tracking over Ω of the Campbell diagram (:func:`propwhirl.analysis.campbell.campbell`) and
    of :func:`label_modes`.  It is the engine's tracking core
    (:func:`propwhirl.engine.follow`, the loop that also runs the sweep over the
    airspeed) with this problem's node evaluator and linking plugged in.

The gyroscopic system M q̈ + G(Ω) q̇ + K q = 0 (aerodynamics and dissipative damping off; G the
skew-symmetric gyroscopic matrix of the spinning rotors, linear in the rotational speed Ω),
with z = [q̇; q], is the Hermitian-definite problem

    ω B z = H(Ω) z,   B = [[M, 0], [0, K]],   H(Ω) = i [[G(Ω), K], [−K, 0]]

(B symmetric positive definite, H Hermitian because G is skew and K symmetric), so the
frequencies ω are real, the eigenvectors B-orthonormal, and the slope of each frequency is
exact, dω/dΩ = zᴴ (∂H/∂Ω) z.  The parameter is the rotational speed itself, starting at Ω = 0:
nothing in this problem divides by it (unlike the airspeed of the aeroelastic state matrix), so
no offset is needed.  At Ω = 0 the problem is the in-vacuo one (K x = ω² M x); a repeated
frequency there (a symmetric mount, f_θ = f_ψ) is resolved in the basis that continues
analytically, the eigenvectors of ∂H/∂Ω within the repeated subspace (first-order degenerate
perturbation theory: the backward and forward whirl combinations) — the core's degenerate
start (:func:`_continue_repeated`).

Between two evaluated speeds the modes are linked by the modal assurance criterion in the
energy norm, MAC = |z_aᴴ B z_b|², maximised by an optimal assignment (:func:`_link`).  A step
is split (by the core, at its middle) while a match has MAC < ``mac_min`` or the matching
reorders the frequencies (two curves cross inside it).  A veering pair — the thesis's Campbell
diagrams: "when the frequency of a propeller mode comes close to the frequency of a wing mode,
they do not cross" (§8.4.1) — is thus resolved into its two analytic branches (the curves do
not cross, the shapes exchange along them); a true crossing of uncoupled modes keeps its
reordering down to ``min_step`` with MAC ≈ 1 and is accepted there: the curves cross, each mode
keeps its shape (a diagram sorted by frequency at each speed would swap them).  A step left
ambiguous at ``min_step`` with a MAC below ``mac_min`` is reported as unresolved.
"""
from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Callable

import numpy as np
import scipy.linalg as sl
from scipy.optimize import linear_sum_assignment

from propwhirl import validate as v
from propwhirl.engine import follow, single_thread_blas
from propwhirl.model.modal_structure import RIGID_BODY_HZ


#: Relative gap below which two in-vacuo frequencies are one repeated frequency (ω_j − ω_i ≤
#: REPEATED_TOL · max(ω_j, 1 rad/s)): far above LAPACK's rounding of a repeated eigenvalue
#: (~1e-15 relative), far below any two distinct modes of a model (identical propellers'
#: yaw modes that the wing does not couple are equal to 1e-12; the closest distinct pair of
#: examples/x57_like.toml differs by 6e-4).  Within such a group the eigenvectors LAPACK
#: returns are any basis of the subspace, so nothing may depend on them one by one
#: (:func:`repeated_groups`).
REPEATED_TOL = 1e-8


def repeated_groups(omega: np.ndarray, tol: float = REPEATED_TOL) -> list[np.ndarray]:
    """The groups (index arrays, two or more) of repeated values in ascending ``omega``
    [rad/s]: consecutive values within ``tol`` · max(|ω|, 1) of the group's first.

    >>> [g.tolist() for g in repeated_groups(np.array([1.0, 2.0, 2.0 + 1e-12, 3.0]))]
    [[1, 2]]
    """
    w = np.asarray(omega, dtype=float)
    out, i = [], 0
    while i < w.size:
        j = i + 1
        while j < w.size and w[j] - w[i] <= tol * max(abs(w[j]), 1.0):
            j += 1
        if j - i > 1:
            out.append(np.arange(i, j))
        i = j
    return out


@dataclass(frozen=True)
class Modes:
    """Undamped modes: angular frequencies ω [rad/s], mass-normalised shapes (columns)."""

    omega: np.ndarray
    shapes: np.ndarray
    labels: tuple[str, ...]

    @property
    def frequency_hz(self) -> np.ndarray:
        return self.omega / (2.0 * np.pi)


def undamped_modes(M: np.ndarray, K: np.ndarray, labels: tuple[str, ...]) -> Modes:
    """Solve K x = ω² M x for symmetric M (positive definite) and K (symmetric)."""
    try:
        lam, X = sl.eigh(K, M)
    except np.linalg.LinAlgError as exc:
        raise v.InputError(f"structural mass matrix is not positive definite: {exc}") from exc
    return Modes(np.sqrt(np.clip(lam, 0.0, None)), X, labels)


@dataclass(frozen=True, eq=False)
class InVacuo:
    """A model without aerodynamics, assembled, and its structural matrices, evaluated once
    for an analysis (:func:`propwhirl.analysis.stability.analyse`) and passed to what reads the
    structure: the in-vacuo modes and their names (:func:`model_modes`, :func:`label_modes`),
    the content and the participation of modes (:mod:`propwhirl.analysis.naming`,
    :mod:`propwhirl.analysis.participation`).

    system:     the model without aerodynamics (``assembly.without_aerodynamics()``):
                ``second_order``, ``dof_map``;
    M, K:       its structural mass and stiffness S1, S3 over the kept DOFs [kg, kg m, kg m²;
                N/m, N, N m]; with aerodynamics off they depend on neither the airspeed nor the
                rotational speed (the rotors' speed enters the gyroscopic damping only);
    q_labels:   the labels of those DOFs;
    gyroscopic: for a wing whose rotors turn, (G(0), ∂G/∂Ω): the skew part of its damping at
                Ω = 0 and its slope [kg m²] (:class:`GyroscopicSystem`), from the same
                evaluation (at Ω = 0 and 1 rad/s); None otherwise.
    """

    system: object
    M: np.ndarray
    K: np.ndarray
    q_labels: tuple[str, ...]
    gyroscopic: tuple[np.ndarray, np.ndarray] | None = None

    @classmethod
    def of(cls, system) -> "InVacuo":
        """The structure of ``system``, a model without aerodynamics or its assembly: one
        evaluation (at V = 1 m/s, which plays no part; a wing whose rotors turn at Ω = 0 and
        1 rad/s, for :attr:`gyroscopic`)."""
        model = getattr(system, "model", system)
        if hasattr(system, "second_order_blocks") and model.dof_map().has_wing \
                and getattr(model, "rotating", False):
            s = system.second_order(np.ones(2), np.array([0.0, 1.0]))
            G = _skew_part(s.S2)
            return cls(system, s.S1[0], s.S3[0], s.q_labels, (G[0], G[1] - G[0]))
        s = system.second_order(np.array([1.0]))
        return cls(system, s.S1[0], s.S3[0], s.q_labels)


def in_vacuo_of(model, in_vacuo=None) -> InVacuo:
    """``in_vacuo`` as an :class:`InVacuo`: itself, the InVacuo of a model without aerodynamics
    already assembled, or (None) of ``model.without_aerodynamics()``."""
    if isinstance(in_vacuo, InVacuo):
        return in_vacuo
    return InVacuo.of(model.without_aerodynamics() if in_vacuo is None else in_vacuo)


def model_modes(model, basis: np.ndarray | None = None, in_vacuo=None
                ) -> tuple[Modes, np.ndarray]:
    """Undamped in-vacuo modes of any model (no aerodynamics; the gyroscopic and dissipative
    terms, which live in the damping matrix, play no part): K x = ω² M x with the structural
    M and K of ``model.without_aerodynamics()``.

    ``basis`` (n, r): Rayleigh–Ritz on its columns instead (a reduced model's basis,
    :mod:`propwhirl.model.reduction`): r modes, shapes lifted to the n DOFs.
    Returns the modes and the (reduced) structural mass matrix they are normalised with.
    ``in_vacuo``: its structure evaluated once (an :class:`InVacuo`, as an analysis passes), or
    the model without aerodynamics already assembled (``model.assembly().without_aerodynamics()``);
    default: assembled here (:func:`in_vacuo_of`).
    """
    iv = in_vacuo_of(model, in_vacuo)
    if basis is None:
        return undamped_modes(iv.M, iv.K, iv.q_labels), iv.M
    P = np.asarray(basis)
    m = undamped_modes(P.T @ iv.M @ P, P.T @ iv.K @ P, iv.q_labels)
    return Modes(m.omega, P @ m.shapes, iv.q_labels), iv.M


def label_modes(model, basis: np.ndarray | None = None, modes: Modes | None = None,
                in_vacuo=None) -> list[tuple[str, float]]:
    """All non-rotating modes of a PropellerWing as (label, frequency [Hz]), ascending.

    The thesis names one backward and one forward whirl mode per flexibly mounted propeller
    (at Ω = 0 the propeller pitch and yaw modes) and calls the others wing modes (§9.3.2,
    Tables 9.8, 10.3, 10.7); its names follow the Campbell diagrams (Figures 9.16, 10.3, 10.11):
    backward modes fall and forward modes rise as the rotor spins up.  Here the frequencies at
    Ω = 0 are compared with those at a small spin rate (one tenth of the lowest mount frequency,
    so the shifts stay far below the gaps between modes), each mode followed by
    :func:`track_gyroscopic` (the engine's tracking core, as in the Campbell diagram); with N
    flexible propellers the N modes that fall most are 'backward k', the N that rise most
    'forward k' (k by frequency), the rest 'wing n'.  A repeated frequency
    (:func:`repeated_groups`: identical propellers whose yaw the wing does not couple) has no
    shape per mode, only a subspace; its names are listed in the order of their frequencies
    just above Ω = 0 (the falling ones first), which does not depend on the basis LAPACK
    returns, and :func:`propwhirl.analysis.naming.named_modes` matches such a group as a
    subspace.  Stopped and feathered installations
    (``Installation.state``) do not turn, so their pitch and yaw modes do not split: they count
    as neither (N is the number of flexibly mounted propellers that turn).
    ``basis``: the modes of the Rayleigh–Ritz problem on its columns (:func:`model_modes`);
    ``modes``: those modes if already computed (``model_modes(model, basis)[0]``);
    ``in_vacuo``: the model's structure (:func:`model_modes`).
    """
    if in_vacuo is not None or modes is None:
        in_vacuo = in_vacuo_of(model, in_vacuo)
    if modes is None:
        modes, _ = model_modes(model, basis, in_vacuo)
    f0 = modes.frequency_hz
    kinds = ["wing"] * f0.size
    # a free structure's rigid-body modes (ω = 0: no stiffness) are 'rigid k'; the Campbell
    # diagram, whose pencil needs K > 0, follows the elastic modes alone (on their shapes)
    rigid = modes.omega < 2.0 * np.pi * RIGID_BODY_HZ
    for i in np.flatnonzero(rigid):
        kinds[i] = "rigid"
    elastic = np.flatnonzero(~rigid)
    flex = _flexible_propellers(model)
    if flex and elastic.size:
        own = [p for p, on_grid in flex if not on_grid]
        f_mount = min(min(p.stiffness()[0] / p.pivot_inertia()["I_theta_P"],
                          p.stiffness()[1] / p.pivot_inertia()["I_psi_P"])
                      for p in own) ** 0.5 if own else np.inf
        if len(own) < len(flex):     # mounts in the modes: their lowest frequency bounds them
            f_mount = min(f_mount, float(np.min(modes.omega[modes.omega > 0], initial=np.inf)))
        rpm = 0.1 * f_mount * 60.0 / (2.0 * np.pi)
        # 2 nodes resolve every thesis model; near-repeated mount modes (64 equal propellers
        # on a reduced basis) stay unresolved after any number: bounded (issue 20.9)
        on = basis if not rigid.any() else modes.shapes[:, elastic]
        tracks = track_gyroscopic(GyroscopicSystem.of(model, basis=on, in_vacuo=in_vacuo),
                                  np.array([0.0, rpm]) * 2.0 * np.pi / 60.0, max_nodes=32)
        delta = np.zeros(f0.size)
        delta[elastic] = tracks.omega[-1] - tracks.omega[0]
        n = len(flex)
        order = elastic[np.argsort(delta[elastic])]
        for i in order[:n]:
            kinds[i] = "backward"
        for i in order[::-1][:n]:
            kinds[i] = "forward"
        for g in repeated_groups(modes.omega[elastic]):   # by their frequency above Ω = 0
            g = elastic[g]
            by_slope = g[np.argsort(delta[g], kind="stable")]
            kinds_g = [kinds[i] for i in by_slope]
            for i, kind in zip(g, kinds_g):
                kinds[i] = kind
    counters = {"backward": 0, "forward": 0, "wing": 0, "rigid": 0}
    out = []
    for kind, f in zip(kinds, f0):
        counters[kind] += 1
        out.append((f"{kind} {counters[kind]}", float(f)))
    return out


def _flexible_propellers(model) -> list[tuple]:
    """(Propeller, on its hub grid) of each propeller that whirls on its mount and turns (by
    number, :meth:`~propwhirl.model.protocol.DofMap.whirling`: flexibly mounted, or a modal
    structure's on-grid one — its mount in the modes —; not the stopped or feathered
    installations) of a PropellerWing, a modal model or an IsolatedPropeller."""
    dm = model.dof_map()
    if not hasattr(model, "propellers"):       # an isolated propeller
        return [(model.propeller, False)] if dm.propellers else []
    return [(model.propellers[p.number].propeller, p.dofs is None) for p in dm.whirling()
            if getattr(model.propellers[p.number], "spinning", True)]


@dataclass(frozen=True)
class GyroscopicSystem:
    """M q̈ + G(Ω) q̇ + K q = 0 of a PropellerWing with aerodynamics and dissipation off.

    ``matrices(Ω)`` gives the model's (M, G, K) stacks at rotational speeds Ω [rad/s];
    ``dG``: ∂G/∂Ω [kg m²] (the rotor's gyroscopic moment I_Ω Ω is linear in Ω).
    """

    matrices: Callable[[np.ndarray], tuple[np.ndarray, np.ndarray, np.ndarray]]
    dG: np.ndarray
    #: (M, G, K) at Ω = 0 when already evaluated (for :meth:`_projected`)
    at_rest: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None

    @classmethod
    def of(cls, model, rpm_ratio: tuple[float, ...] | None = None,
           basis: np.ndarray | None = None, in_vacuo=None) -> "GyroscopicSystem":
        """The system of `model`, Ω the first propeller's speed; propeller j spins at
        ``rpm_ratio[j]`` × Ω (default: all at Ω).  ``basis`` (n, r): projected on its columns
        (a reduced model's basis, :mod:`propwhirl.model.reduction`); ``in_vacuo``: the model's
        structure (:func:`model_modes`; used when the model's rotors turn: an :class:`InVacuo`
        gives the matrices at Ω = 0 and ∂G/∂Ω without a new evaluation)."""
        if basis is not None:
            return cls.of(model, rpm_ratio, in_vacuo=in_vacuo)._projected(np.asarray(basis))
        if hasattr(model, "propellers") and (rpm_ratio is None
                                             or all(r == 1.0 for r in rpm_ratio)):
            if not model.rotating:
                quiet = model.with_(wing_aero=False, propeller_aero=False, rotating=True)
            else:
                quiet = model.without_aerodynamics() if in_vacuo is None else \
                    getattr(in_vacuo, "system", in_vacuo)

            def matrices(omega: np.ndarray):
                omega = np.asarray(omega, dtype=float)
                s = quiet.second_order(np.ones_like(omega), omega)   # V plays no part here
                return s.S1, _skew_part(s.S2), s.S3

            if model.rotating and getattr(in_vacuo, "gyroscopic", None) is not None:
                G0, dG = in_vacuo.gyroscopic               # evaluated at Ω = 0 and 1 rad/s
                return cls(matrices, dG, (in_vacuo.M, G0, in_vacuo.K))
            M, G, K = matrices(np.array([0.0, 1.0]))
            return cls(matrices, G[1] - G[0], (M[0], G[0], K[0]))
        return cls._per_propeller(model, rpm_ratio)

    @classmethod
    def _per_propeller(cls, model, rpm_ratio) -> "GyroscopicSystem":
        """Each propeller at its own speed: the model with every propeller turned into a
        constant-speed one at ratio_j × 1 rad/s gives ∂G/∂Ω (the gyroscopic moment I_Ω Ω_j of
        each rotor is linear in its speed), and G(Ω) = G(0) + Ω ∂G/∂Ω."""
        unit_rpm = 60.0 / (2.0 * np.pi)                  # 1 rad/s [rev/min]

        def spinning(p, ratio):
            return replace(p, operation="constant-speed", rpm=ratio * unit_rpm)

        if not hasattr(model, "propellers"):             # an isolated propeller
            ratio = (1.0,) if rpm_ratio is None else rpm_ratio
            still = model.with_(propeller_aero=False, rotating=False)
            spun = still if ratio[0] == 0 else model.with_(
                propeller_aero=False, rotating=True, propeller=spinning(model.propeller, ratio[0]))
        else:
            still = model.with_(wing_aero=False, propeller_aero=False, rotating=False)
            spun = still.with_(rotating=True, propellers=tuple(   # ratio 0: not turning
                replace(inst, propeller=spinning(inst.propeller, r)) if r > 0
                else replace(inst, state="stopped")
                for inst, r in zip(model.propellers, rpm_ratio)))
        V = np.array([1.0])                              # V plays no part here
        s0, s1 = still.second_order(V), spun.second_order(V)
        G0, dG = _skew_part(s0.S2)[0], _skew_part(s1.S2)[0] - _skew_part(s0.S2)[0]
        M, K = s0.S1[0], s0.S3[0]

        def matrices(omega: np.ndarray):
            omega = np.asarray(omega, dtype=float)
            n = omega.size
            return (np.broadcast_to(M, (n,) + M.shape), G0 + omega[:, None, None] * dG,
                    np.broadcast_to(K, (n,) + K.shape))

        return cls(matrices, dG)

    def _projected(self, P: np.ndarray) -> "GyroscopicSystem":
        """Pᵀ(M, G, K)P: M and K do not depend on Ω and G is linear in it (I_Ω Ω)."""
        rest = self.at_rest or tuple(X[0] for X in self.matrices(np.array([0.0])))
        M0, G0, K0 = (P.T @ X @ P for X in rest)
        dG = P.T @ self.dG @ P

        def projected(omega: np.ndarray):
            om = np.asarray(omega, dtype=float)[:, None, None]
            shape = (om.shape[0],) + M0.shape
            return np.broadcast_to(M0, shape), G0 + om * dG, np.broadcast_to(K0, shape)

        return GyroscopicSystem(projected, dG)


@dataclass(frozen=True)
class _Node:
    """Positive frequencies ω (n,) [rad/s] ascending, B-orthonormal z (2n, n), dω/dΩ (n,)."""

    Omega: float
    omega: np.ndarray
    Z: np.ndarray
    slope: np.ndarray
    B: np.ndarray
    dH: np.ndarray
    groups: tuple[np.ndarray, ...] = ()      # indices of repeated frequencies

    @property
    def s(self) -> float:
        """The tracked parameter (Ω [rad/s]) for the tracking core."""
        return self.Omega


def _hermitian_pencil(M, G, K):
    n = M.shape[0]
    Zn = np.zeros((n, n))
    H = 1j * np.block([[G, K], [-K, Zn]])
    B = np.block([[M, Zn], [Zn, K]])
    return 0.5 * (H + H.conj().T), 0.5 * (B + B.T)


def _evaluate(system: GyroscopicSystem, Omega: np.ndarray, degenerate_tol: float) -> list[_Node]:
    """Eigen-solutions of ω B z = H(Ω) z at each rotational speed (module docstring)."""
    Ms, Gs, Ks = system.matrices(Omega)
    n = Ms.shape[-1]
    dH, _ = _hermitian_pencil(np.zeros((n, n)), system.dG, np.zeros((n, n)))
    out = []
    for Om, M, G, K in zip(Omega, Ms, Gs, Ks):
        H, B = _hermitian_pencil(M, G, K)
        try:
            w, Z = sl.eigh(H, B, subset_by_index=[n, 2 * n - 1])
        except np.linalg.LinAlgError as exc:
            raise v.InputError(f"the Campbell diagram needs positive definite mass and stiffness "
                               f"matrices (a clamped, flexibly mounted structure): {exc}") from exc
        D = Z.conj().T @ dH @ Z
        groups, i = [], 0
        while i < n:                     # repeated frequencies: the analytic-continuation basis
            j = i + 1
            while j < n and w[j] - w[i] <= degenerate_tol * max(abs(w[j]), 1.0):
                j += 1
            if j - i > 1:                # first order: eigenvectors of ∂H/∂Ω in the subspace
                s_g, U = np.linalg.eigh(D[i:j, i:j])
                Z[:, i:j] = Z[:, i:j] @ U
                D[i:j, i:j] = np.diag(s_g)
                groups.append(np.arange(i, j))
            i = j
        out.append(_Node(float(Om), w, Z, np.real(np.diag(D)).copy(), B, dH, tuple(groups)))
    return out


def _continue_repeated(a: _Node, b: _Node) -> _Node:
    """``a`` with the basis of each repeated frequency rotated onto its continuation at ``b``.

    Where ∂H/∂Ω does not split a repeated frequency (e.g. two identical, uncoupled mounts)
    the first-order basis is arbitrary; the continuation is the limit of the eigenvectors as
    the speed approaches from the right, approximated by the unitary best fit (orthogonal
    Procrustes) of the subspace to the modes of the next speed it contains most of.
    """
    if not a.groups:
        return a
    Z = a.Z.copy()
    for g in a.groups:
        C = Z[:, g].conj().T @ b.B @ b.Z
        cols = np.sort(np.argsort(-np.sum(np.abs(C) ** 2, axis=0))[: g.size])
        U, _, Vh = np.linalg.svd(C[:, cols])
        Z[:, g] = Z[:, g] @ (U @ Vh)
    slope = np.real(np.sum(Z.conj() * (a.dH @ Z), axis=0))
    return replace(a, Z=Z, slope=slope)


@dataclass(frozen=True)
class _Link:
    """One step's linking: perm (b's index of each of a's modes); matched: every match has
    MAC ≥ mac_min; ambiguous: not matched, or the matching reorders the frequencies (the
    tracking core splits the step)."""

    perm: np.ndarray
    matched: bool
    ambiguous: bool


def _link(a: _Node, b: _Node, mac_min: float) -> _Link:
    """The perm maximising Σ MAC in the energy norm (an optimal assignment) and its verdict."""
    O = np.abs(a.Z.conj().T @ b.B @ b.Z) ** 2
    _, perm = linear_sum_assignment(-O)
    matched = bool(O[np.arange(perm.size), perm].min() >= mac_min)
    ordered = bool(np.all(perm == np.arange(perm.size)))
    return _Link(perm, matched, not (matched and ordered))


@dataclass(frozen=True)
class _Tracks:
    """Tracked modes at the asked rotational speeds Omega (T,) [rad/s]: omega (T, n) [rad/s]
    and slope (T, n) dω/dΩ, column k the mode that is k-th by frequency at Ω = 0 (omega0 (n,));
    resolved (T,): every step since the previous asked speed (or Ω = 0) was resolved;
    unresolved steps (Ω_a, Ω_b) [rad/s]; nodes: speeds evaluated."""

    Omega: np.ndarray
    omega: np.ndarray
    slope: np.ndarray
    omega0: np.ndarray
    resolved: np.ndarray
    unresolved: tuple[tuple[float, float], ...] = ()
    nodes: int = 0


def track_gyroscopic(system: GyroscopicSystem, Omega: np.ndarray, *, mac_min: float = 0.8,
                     min_step: float = 0.01 * 2.0 * np.pi / 60.0,
                     degenerate_tol: float = REPEATED_TOL,
                     max_nodes: int | None = None) -> _Tracks:
    """Follow every mode from Ω = 0 through the increasing speeds ``Omega`` [rad/s] ≥ 0."""
    with single_thread_blas():           # small dense eigenproblems: one BLAS thread is fastest
        return _track_nodes(system, np.asarray(Omega, dtype=float), mac_min, min_step,
                            degenerate_tol, max_nodes)


def _track_nodes(system, grid, mac_min, min_step, degenerate_tol, max_nodes) -> _Tracks:
    start = np.union1d([0.0], grid)
    nodes, links, _ = follow(
        lambda Omega: _evaluate(system, Omega, degenerate_tol),
        lambda a, b: _link(a, b, mac_min), start, min_step=min_step,
        budget=max_nodes or (20 * start.size + 200),
        split=lambda a, b, lk: 0.5 * (a.Omega + b.Omega), at_start=_continue_repeated)
    idx = np.arange(nodes[0].omega.size)
    om, sl_, ok, unresolved = [], [], [], []
    clean = True                         # every step since the last asked speed resolved
    for t, nd in enumerate(nodes):
        if t:
            lk = links[(nodes[t - 1].Omega, nd.Omega)]
            idx = lk.perm[idx]
            clean &= lk.matched
            if not lk.matched:
                unresolved.append((nodes[t - 1].Omega, nd.Omega))
        if nd.Omega in grid:
            om.append(nd.omega[idx])
            sl_.append(nd.slope[idx])
            ok.append(clean)
            clean = True
    return _Tracks(grid, np.array(om), np.array(sl_), nodes[0].omega.copy(), np.array(ok),
                   tuple(unresolved), len(nodes))


def _skew_part(C: np.ndarray) -> np.ndarray:
    """Skew (gyroscopic) part of damping matrices (..., n, n); the symmetric part dissipates."""
    return 0.5 * (C - np.swapaxes(C, -1, -2))
