"""The Campbell diagram: natural frequencies against propeller rotational speed, each mode followed.

Figures 8.6, 9.16, 10.3, 10.11 of the thesis; the mode names at Ω = 0 are those of
:func:`propwhirl.analysis.vibration.label_modes` (which uses this module's tracker).

:func:`campbell` follows every mode of the undamped gyroscopic system M q̈ + G(Ω) q̇ + K q = 0
(aerodynamics and dissipative damping off; G the skew-symmetric gyroscopic matrix of the
spinning rotors, linear in the rotational speed Ω) from Ω = 0 up the asked speeds.  With
z = [q̇; q] it is the Hermitian-definite problem

    ω B z = H(Ω) z,   B = [[M, 0], [0, K]],   H(Ω) = i [[G(Ω), K], [−K, 0]]

(B symmetric positive definite, H Hermitian because G is skew and K symmetric), so the
frequencies ω are real, the eigenvectors B-orthonormal, and the slope of each frequency is
exact, dω/dΩ = zᴴ (∂H/∂Ω) z.  The parameter is the rotational speed itself, starting at Ω = 0:
nothing in this problem divides by it (unlike the airspeed of the aeroelastic state matrix), so
no offset is needed.  At Ω = 0 the problem is the in-vacuo one (K x = ω² M x); a repeated
frequency there (a symmetric mount, f_θ = f_ψ) is resolved in the basis that continues
analytically, the eigenvectors of ∂H/∂Ω within the repeated subspace (first-order degenerate
perturbation theory: the backward and forward whirl combinations).

Between two evaluated speeds the modes are matched by the modal assurance criterion in the
energy norm, MAC = |z_aᴴ B z_b|², maximised by an optimal assignment.  A step is split while a
match has MAC < ``mac_min`` or the matching reorders the frequencies (two curves cross inside
it).  A veering pair — the thesis's Campbell diagrams: "when the frequency of a propeller mode
comes close to the frequency of a wing mode, they do not cross" (§8.4.1) — is thus resolved
into its two analytic branches (the curves do not cross, the shapes exchange along them); a
true crossing of uncoupled modes keeps its reordering down to ``min_step`` with MAC ≈ 1 and is
accepted there: the curves cross, each mode keeps its shape (a diagram sorted by frequency at
each speed would swap them).  A step left ambiguous at ``min_step`` is reported as unresolved.
"""
from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Any, Callable

import numpy as np
import scipy.linalg as sl
from scipy.optimize import linear_sum_assignment

from propwhirl import limits
from propwhirl import validate as v
from propwhirl.engine import single_thread_blas

#: Default propeller speeds of :func:`campbell`: 0–6000 rev/min every 250 (covers the
#: operating range of chapters 9–10; 4433 rev/min at the flutter point of Table 9.5)
CAMPBELL_RPM = np.arange(0.0, 6001.0, 250.0)


def _flexible_propellers(model) -> list:
    """The Propeller of each flexibly mounted propeller (DOF-map order) of a PropellerWing or
    an IsolatedPropeller."""
    dm = model.dof_map()
    if not dm.has_wing:
        return [model.propeller] if dm.propellers else []
    return [model.propellers[p.number].propeller for p in dm.propellers]


#: mode families of a Campbell diagram
FAMILIES = ("wing bending", "wing torsion", "backward whirl", "forward whirl")


def mode_families(model, labels: tuple[str, ...] | None = None) -> tuple[str, ...]:
    """Family of each in-vacuo mode (ascending frequency, as :func:`label_modes`): "backward
    whirl" / "forward whirl" for the modes :func:`label_modes` names so, and for the others
    "wing torsion" where the wing twist α holds more of the mode's kinetic energy than the
    bending DOFs (h, φ), else "wing bending" (shares as
    :func:`propwhirl.analysis.naming.kinetic_energy_shares`)."""
    from propwhirl.analysis.naming import kinetic_energy_shares
    from propwhirl.analysis.vibration import label_modes, model_modes

    labels = labels if labels is not None else tuple(lab for lab, _ in label_modes(model))
    modes, M = model_modes(model)
    groups = model.without_aerodynamics().dof_map().groups()
    shares = kinetic_energy_shares(modes.shapes, M, groups)
    zero = np.zeros(modes.shapes.shape[1])
    out = []
    for k, lab in enumerate(labels):
        kind = lab.split(" ")[0]
        if kind in ("backward", "forward"):
            out.append(f"{kind} whirl")
        else:
            tors = float(shares.get("torsion", zero)[k])
            bend = float(shares.get("bending", zero)[k])
            out.append("wing torsion" if tors > bend else "wing bending")
    return tuple(out)


def operating_rpm_ratio(model) -> tuple[float, ...]:
    """Each propeller's rotational speed relative to the first's, from their operation
    (:meth:`propwhirl.model.propeller.Propeller.rotational_speed`): constant-speed rpm, or
    fixed-pitch windmilling Ω = V/(μR) — a ratio that holds at every airspeed when the
    propellers run in the same operation.  Where it depends on the airspeed (fixed-pitch and
    constant-speed propellers mixed) every ratio is 1 (pass ``rpm_ratio`` to
    :func:`campbell`).  An isolated propeller: (1.0,)."""
    props = ([model.propeller] if not model.dof_map().has_wing
             else [inst.propeller for inst in model.propellers])
    if not props:
        return ()
    Vs = np.array([100.0, 200.0])
    speeds = np.array([p.rotational_speed(Vs) for p in props])     # (n, 2) [rad/s]
    ratio = speeds / speeds[0]
    if not np.allclose(ratio[:, 0], ratio[:, 1], rtol=1e-12, atol=0.0):
        return (1.0,) * len(props)
    return tuple(float(r) for r in ratio[:, 0])


@dataclass(frozen=True)
class CampbellResult:
    """A tracked Campbell diagram: natural frequencies against propeller rotational speed.

    rpm:           (T,) rotational speeds [rev/min] of the first propeller, increasing;
                   propeller j spins at ``rpm_ratio[j]`` × rpm (all at rpm when the ratios are 1).
    frequency_hz:  (T, K) natural frequencies [Hz]; column k is one mode followed along rpm
                   (columns ordered by frequency at rpm = 0).
    labels:        K mode names at rpm = 0 (:func:`label_modes`: "wing n", "backward k",
                   "forward k").
    families:      K mode families (:func:`mode_families`: "wing bending", "wing torsion",
                   "backward whirl", "forward whirl").
    rpm_ratio:     each propeller's speed relative to the first's (one per propeller of the
                   model, numbered from 0 in ``model.propellers``).
    slope_hz_per_rpm: (T, K) exact df/d(rpm) [Hz per rev/min] of each curve.
    resolved:      (T,) bool, False where a step of the tracking between the previous speed
                   (or rpm = 0) and this one was left ambiguous at the smallest step.
    unresolved:    the ambiguous steps as (rpm_a, rpm_b) [rev/min].
    nodes:         speeds evaluated (asked speeds, rpm = 0 and the refinement).
    """

    rpm: np.ndarray
    frequency_hz: np.ndarray
    labels: tuple[str, ...]
    slope_hz_per_rpm: np.ndarray
    resolved: np.ndarray
    unresolved: tuple[tuple[float, float], ...] = ()
    nodes: int = 0
    families: tuple[str, ...] = ()
    rpm_ratio: tuple[float, ...] = ()

    @property
    def n_modes(self) -> int:
        return self.frequency_hz.shape[1]

    def propeller_rpm(self) -> np.ndarray:
        """(T, P) rotational speed [rev/min] of each propeller along the diagram."""
        return np.outer(self.rpm, np.asarray(self.rpm_ratio or (1.0,), dtype=float))

    def curve(self, label: str) -> np.ndarray:
        """Frequencies [Hz] of the mode named ``label`` along rpm."""
        if label not in self.labels:
            raise v.InputError(f"label = {label!r} is invalid: must be one of {list(self.labels)}")
        return self.frequency_hz[:, self.labels.index(label)]

    def table(self) -> dict[str, np.ndarray]:
        """Tidy columns sorted by rpm then mode: rpm [rev/min], mode (int), label,
        frequency_hz [Hz], resolved (bool)."""
        T, K = self.frequency_hz.shape
        return {
            "rpm": np.repeat(self.rpm, K),
            "mode": np.tile(np.arange(K), T),
            "label": np.tile(np.asarray(self.labels, dtype=object), T),
            "frequency_hz": self.frequency_hz.reshape(-1),
            "resolved": np.repeat(self.resolved, K),
        }

    def to_dict(self) -> dict[str, Any]:
        """JSON-able dict of the fields (units as in the field names and docstring)."""
        return {
            "rpm": self.rpm.tolist(), "frequency_hz": self.frequency_hz.tolist(),
            "labels": list(self.labels), "slope_hz_per_rpm": self.slope_hz_per_rpm.tolist(),
            "resolved": self.resolved.tolist(), "unresolved": [list(u) for u in self.unresolved],
            "nodes": self.nodes, "families": list(self.families),
            "rpm_ratio": list(self.rpm_ratio),
        }


@dataclass(frozen=True)
class _GyroscopicSystem:
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
           basis: np.ndarray | None = None) -> "_GyroscopicSystem":
        """The system of `model`, Ω the first propeller's speed; propeller j spins at
        ``rpm_ratio[j]`` × Ω (default: all at Ω).  ``basis`` (n, r): projected on its columns
        (a reduced model's basis, :mod:`propwhirl.model.reduction`)."""
        if basis is not None:
            return cls.of(model, rpm_ratio)._projected(np.asarray(basis))
        if model.dof_map().has_wing and (rpm_ratio is None or all(r == 1.0 for r in rpm_ratio)):
            quiet = (model.without_aerodynamics() if model.rotating
                     else model.with_(wing_aero=False, propeller_aero=False, rotating=True))

            def matrices(omega: np.ndarray):
                omega = np.asarray(omega, dtype=float)
                s = quiet.second_order(np.ones_like(omega), omega)   # V plays no part here
                return s.S1, _skew_part(s.S2), s.S3

            M, G, K = matrices(np.array([0.0, 1.0]))
            return cls(matrices, G[1] - G[0], (M[0], G[0], K[0]))
        return cls._per_propeller(model, rpm_ratio)

    @classmethod
    def _per_propeller(cls, model, rpm_ratio) -> "_GyroscopicSystem":
        """Each propeller at its own speed: the model with every propeller turned into a
        constant-speed one at ratio_j × 1 rad/s gives ∂G/∂Ω (the gyroscopic moment I_Ω Ω_j of
        each rotor is linear in its speed), and G(Ω) = G(0) + Ω ∂G/∂Ω."""
        unit_rpm = 60.0 / (2.0 * np.pi)                  # 1 rad/s [rev/min]

        def spinning(p, ratio):
            return replace(p, operation="constant-speed", rpm=ratio * unit_rpm)

        if not model.dof_map().has_wing:
            ratio = (1.0,) if rpm_ratio is None else rpm_ratio
            still = model.with_(propeller_aero=False, rotating=False)
            spun = model.with_(propeller_aero=False, rotating=True,
                               propeller=spinning(model.propeller, ratio[0]))
        else:
            still = model.with_(wing_aero=False, propeller_aero=False, rotating=False)
            spun = still.with_(rotating=True, propellers=tuple(
                replace(inst, propeller=spinning(inst.propeller, r))
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

    def _projected(self, P: np.ndarray) -> "_GyroscopicSystem":
        """Pᵀ(M, G, K)P: M and K do not depend on Ω and G is linear in it (I_Ω Ω)."""
        rest = self.at_rest or tuple(X[0] for X in self.matrices(np.array([0.0])))
        M0, G0, K0 = (P.T @ X @ P for X in rest)
        dG = P.T @ self.dG @ P

        def projected(omega: np.ndarray):
            om = np.asarray(omega, dtype=float)[:, None, None]
            shape = (om.shape[0],) + M0.shape
            return np.broadcast_to(M0, shape), G0 + om * dG, np.broadcast_to(K0, shape)

        return _GyroscopicSystem(projected, dG)


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


def _hermitian_pencil(M, G, K):
    n = M.shape[0]
    Zn = np.zeros((n, n))
    H = 1j * np.block([[G, K], [-K, Zn]])
    B = np.block([[M, Zn], [Zn, K]])
    return 0.5 * (H + H.conj().T), 0.5 * (B + B.T)


def _evaluate(system: _GyroscopicSystem, Omega: np.ndarray, degenerate_tol: float) -> list[_Node]:
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


def _link(a: _Node, b: _Node) -> tuple[np.ndarray, np.ndarray]:
    """perm (b's index of each of a's modes) maximising Σ MAC, and the MACs of the matches."""
    O = np.abs(a.Z.conj().T @ b.B @ b.Z) ** 2
    _, perm = linear_sum_assignment(-O)
    return perm, O[np.arange(perm.size), perm]


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


def _track(system: _GyroscopicSystem, Omega: np.ndarray, *, mac_min: float = 0.8,
           min_step: float = 0.01 * 2.0 * np.pi / 60.0, degenerate_tol: float = 1e-8,
           max_nodes: int | None = None) -> _Tracks:
    """Follow every mode from Ω = 0 through the increasing speeds ``Omega`` [rad/s] ≥ 0."""
    with single_thread_blas():           # small dense eigenproblems: one BLAS thread is fastest
        return _track_nodes(system, np.asarray(Omega, dtype=float), mac_min, min_step,
                            degenerate_tol, max_nodes)


def _track_nodes(system, grid, mac_min, min_step, degenerate_tol, max_nodes) -> _Tracks:
    start = np.union1d([0.0], grid)
    nodes = _evaluate(system, start, degenerate_tol)
    budget = max_nodes or (20 * start.size + 200)
    links: dict[tuple[float, float], tuple[np.ndarray, bool]] = {}
    while True:
        new = []
        for t, (a, b) in enumerate(zip(nodes[:-1], nodes[1:])):
            if (a.Omega, b.Omega) in links:
                continue
            if t == 0:                   # Ω = 0: repeated in-vacuo frequencies
                a = nodes[0] = _continue_repeated(nodes[0], b)
            perm, mac = _link(a, b)
            good = bool(mac.min() >= mac_min)
            ordered = bool(np.all(perm == np.arange(perm.size)))
            if (not (good and ordered) and 0.5 * (b.Omega - a.Omega) >= min_step
                    and len(nodes) + len(new) < budget):
                new.append(0.5 * (a.Omega + b.Omega))
                continue
            links[(a.Omega, b.Omega)] = (perm, good)
        if not new:
            break
        nodes = sorted(nodes + _evaluate(system, np.array(new), degenerate_tol),
                       key=lambda nd: nd.Omega)
    idx = np.arange(nodes[0].omega.size)
    om, sl_, ok, unresolved = [], [], [], []
    clean = True                         # every step since the last asked speed resolved
    for t, nd in enumerate(nodes):
        if t:
            perm, good = links[(nodes[t - 1].Omega, nd.Omega)]
            idx = perm[idx]
            clean &= good
            if not good:
                unresolved.append((nodes[t - 1].Omega, nd.Omega))
        if nd.Omega in grid:
            om.append(nd.omega[idx])
            sl_.append(nd.slope[idx])
            ok.append(clean)
            clean = True
    return _Tracks(grid, np.array(om), np.array(sl_), nodes[0].omega.copy(), np.array(ok),
                   tuple(unresolved), len(nodes))


def campbell(model, rpm=None, *, rpm_ratio=None, max_frequency_hz: float | None = None,
             mac_min: float = 0.8, min_step: float = 0.01) -> CampbellResult:
    """Tracked Campbell diagram of a propeller–wing model (Figures 8.6, 9.16, 10.3, 10.11).

    Parameters
    ----------
    model : PropellerWing or IsolatedPropeller
        With at least one flexibly mounted propeller; aerodynamics and dissipative damping are
        switched off (the undamped gyroscopic system; the airspeed plays no part).
    rpm : array_like, optional
        Rotational speeds [rev/min] of the first propeller, ≥ 0, increasing (default
        :data:`CAMPBELL_RPM`, 0–6000 every 250).  The modes are followed from rpm = 0
        whether or not it is asked for.
    rpm_ratio : sequence of float, optional
        Each propeller's speed relative to the first's (one per propeller, > 0; the first
        1).  Default :func:`operating_rpm_ratio`: as the propellers operate (all 1 for equal
        propellers: every propeller spins at rpm).
    max_frequency_hz : float, optional
        Keep only the modes below this frequency [Hz] at rpm = 0.
    mac_min : float
        A step whose matching has a MAC below this is split (module docstring).
    min_step : float
        Smallest step of the refinement [rev/min].

    Returns
    -------
    CampbellResult
        Frequencies [Hz] of each mode along rpm, named at rpm = 0 by :func:`label_modes`.
        At rpm = 0 they are the in-vacuo frequencies of :func:`model_modes`.

    Examples
    --------
    >>> from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
    >>> c = campbell(wingtip_propeller_wing(), [0.0, 2000.0, 4000.0], max_frequency_hz=10.0)
    >>> c.labels
    ('wing 1', 'backward 1', 'forward 1')
    >>> bool(c.curve("backward 1")[-1] < c.curve("backward 1")[0] < c.curve("forward 1")[-1])
    True
    """
    from propwhirl.analysis.vibration import label_modes

    dm = model.dof_map()
    if not dm.propellers or not (dm.has_wing or hasattr(model, "propeller")):
        raise v.InputError("campbell needs a propeller-wing model or an isolated propeller with a "
                           "flexibly mounted propeller (the rotational speed acts through the "
                           "pitch/yaw mounts)")
    r = CAMPBELL_RPM.copy() if rpm is None else _check_rpm(rpm)
    ratio = operating_rpm_ratio(model) if rpm_ratio is None else _check_ratio(model, rpm_ratio)
    if max_frequency_hz is not None:
        v.positive("max_frequency_hz", max_frequency_hz, "Hz")
    v.in_range("mac_min", mac_min, 0.0, 1.0)
    v.positive("min_step", min_step, "rev/min")
    per_rpm = 2.0 * np.pi / 60.0                      # [rad/s per rev/min]
    tr = _track(_GyroscopicSystem.of(model, ratio), r * per_rpm, mac_min=mac_min,
                min_step=min_step * per_rpm)
    names = tuple(lab for lab, _ in label_modes(model))
    families = mode_families(model, names)
    keep = np.arange(tr.omega0.size)
    if max_frequency_hz is not None:
        keep = keep[tr.omega0 / (2.0 * np.pi) <= max_frequency_hz]
    return CampbellResult(
        rpm=r, frequency_hz=tr.omega[:, keep] / (2.0 * np.pi),
        labels=tuple(names[k] for k in keep), slope_hz_per_rpm=tr.slope[:, keep] / 60.0,
        resolved=tr.resolved, nodes=tr.nodes, families=tuple(families[k] for k in keep),
        rpm_ratio=ratio,
        unresolved=tuple((a / per_rpm, b / per_rpm) for a, b in tr.unresolved))


#: the valid form of Campbell rotational speeds, for error messages
RPM_FORM = (f"an increasing 1-D array of propeller speeds in [0, {limits.MAX_RPM:,.0f}] rev/min, "
            "e.g. numpy.linspace(0.0, 6000.0, 25)")


def _check_rpm(rpm) -> np.ndarray:
    """Rotational speeds [rev/min]: 1-D, finite, in [0, MAX_RPM], strictly increasing, at
    most :data:`propwhirl.limits.MAX_SPEEDS` values (a number: one speed)."""
    bad = v.InputError(f"rpm = {rpm!r:.60} is invalid: must be {RPM_FORM}")
    if rpm is None or isinstance(rpm, (str, bytes, dict, set, frozenset, bool, np.bool_)):
        raise bad
    try:
        raw = np.atleast_1d(np.asarray(rpm))
    except (TypeError, ValueError, OverflowError) as exc:
        raise bad from exc
    if raw.dtype.kind not in "iuf":
        raise bad
    if raw.ndim != 1 or raw.size == 0:
        raise v.InputError(f"rpm must be a 1-D array of at least 1 value, got shape "
                           f"{raw.shape}: give {RPM_FORM}")
    limits.check_speed_count("rpm", raw.size, "fewer rotational speeds")
    r = v.in_range("rpm", raw.astype(float), 0.0, limits.MAX_RPM, "rev/min")
    return v.increasing("rpm", r, "rev/min") if r.size > 1 else r


def _check_ratio(model, rpm_ratio) -> tuple[float, ...]:
    """rpm_ratio: one positive finite number per propeller of `model`."""
    n = len(operating_rpm_ratio(model))
    r = np.atleast_1d(np.asarray(rpm_ratio, dtype=float))
    if r.ndim != 1 or r.size != n:
        raise v.InputError(f"rpm_ratio = {rpm_ratio!r:.60} is invalid: must give one ratio per "
                           f"propeller ({n})")
    v.positive("rpm_ratio", r)
    return tuple(float(x) for x in r)


def _skew_part(C: np.ndarray) -> np.ndarray:
    """Skew (gyroscopic) part of damping matrices (..., n, n); the symmetric part dissipates."""
    return 0.5 * (C - np.swapaxes(C, -1, -2))
