"""Modal structures: a wing whose structure is given by its normal modes (issue 22, item 2).

:class:`ModalStructure` holds what any finite-element code's normal-modes solution gives:
the natural frequencies, modal masses and modal damping ratios, and every mode's six
displacements and rotations at named grid points.  :class:`ModalPropellerWing` implements the
:class:`~propwhirl.model.protocol.Model` contract on it, so the engine and the analyses work
unchanged: its degrees of freedom are the modal coordinates η (then θ, ψ of each flexibly
mounted propeller), its structure generalised M = diag(m_i), K = diag(m_i ω_i²),
C = diag(2 ζ_i m_i ω_i).

**Frame and sign conventions** (the file format's, ``docs/modal-structures.md``): the wing
frame is right-handed, x aft (chordwise, rearward), y spanwise outboard, z up; each grid's
six components are [T_x, T_y, T_z, R_x, R_y, R_z] [m, m, m, rad, rad, rad].  The beam models'
heave h is positive down and twist α nose up, so h = −T_z, α = R_y and the bending slope
∂h/∂y = −R_x.

**Strip aerodynamics on the modes.**  The wing's strips (the same generated strip
aerodynamics as a :class:`~propwhirl.model.wing.Wing`'s, :func:`propwhirl.model.assembly.strip_aero_blocks`)
sit at spanwise stations of a :class:`StripPlanform`.  The heave and twist of each strip
are interpolated from the ``wing_grids`` (the grids on the wing's reference axis, ordered
root to tip) by :func:`strip_interpolation`: along the span, T_z by the cubic Hermite spline
of each grid interval with the grids' R_x as its slopes (∂T_z/∂y = R_x), R_y linearly; across
the chord, the section is rigid, so the heave at the strip's elastic axis is
h = −(T_z − R_y (x_ea − x_ref)) with x_ref the reference axis (the grids' x, linear in y).
This is the beam element's own interpolation (Hermite cubic in bending, linear in torsion),
so with a grid at every node of a beam model the spline reproduces the beam's modes exactly
at every point; on a coarser grid its error is measured in ``docs/validation.md``
("Modal structures").  The aerodynamic matrices are then (TΦ)ᵀ A_strip (TΦ), the lag
states' couplings projected the same way.

**Propellers.**  Each sits at a hub grid.  ``mount = "flexible"`` (way a): its own pitch and
yaw DOFs and springs, as a :class:`~propwhirl.model.systems.PropellerWing`'s, its generated
block (:mod:`propwhirl.model.propeller_blocks`, 4×4 on [θ, ψ, h_P, α_P]) coupled through the
hub grid's heave and twist, h_P = −T_z, α_P = R_y, with a_P b_P the hub grid's x aft of the
local mid-chord; ``mount = "rigid"``: the 2×2 rigid-mount block on [h_P, α_P] (its mass and
aerodynamic loads, §9.3.1).  ``mount = "on-grid"`` (way b, Rodden/Čečrdle practice): the
propeller rigid on its hub grid, which sits at the hub (the centre of the propeller plane), the
mount's flexibility and the propeller's mass inside the modes; its Houbolt–Reed loads and its
rotor's gyroscopic moments act on the hub grid's motion u = [z_H, y_H, θ_H, ψ_H] =
[−T_z, T_y, R_y, −R_z] (down, outboard, nose up, and yaw in the sense of the thesis's ψ) by the
generated :mod:`propwhirl.generated.prop_hub` (derivations/prop_hub.py, checked there to be
chapter 8's loads through the hub's motion).
"""
from __future__ import annotations

from dataclasses import dataclass, field, replace
from types import MappingProxyType
from typing import Literal

import numpy as np

from propwhirl import limits
from propwhirl import validate as v
from propwhirl.model import validity
from propwhirl.generated import prop_hub
from propwhirl.model.assembly import LAG_STATES, call_blocks, strip_aero_blocks
from propwhirl.model.base import EvaluatorBase, StateSpaceModel
from propwhirl.model.flight import FlightCondition
from propwhirl.model.propeller import Propeller
from propwhirl.model.propeller_blocks import (propeller_constants_at, propeller_matrices,
                                             propeller_values)
from propwhirl.model.protocol import DofMap, PropellerDofs
from propwhirl.model.statespace import SecondOrder

#: Components of a grid's motion in a mode shape, in the order of the last axis of ``shapes``.
COMPONENTS = ("T_x", "T_y", "T_z", "R_x", "R_y", "R_z")
#: Modes whose frequency is below this [Hz] are rigid-body modes: a cantilever wing has none.
RIGID_BODY_HZ = 1e-3
#: Most modes and strips of a model (a beam model has at most 3 × limits.MAX_ELEMENTS DOFs
#: and MAX_ELEMENTS + 1 strips): the analyses' matrices grow with their squares.
MAX_MODES = 1000
MAX_STRIPS = 1000
#: How a propeller sits on its hub grid (module docstring).
MOUNTS = ("flexible", "rigid", "on-grid")


def _array(source: str, key: str, value, shape: tuple, dtype=float) -> np.ndarray:
    """`value` as a read-only copy of `shape` (-1: any length) and dtype, finite; else a
    one-line error naming `source` and `key`."""
    try:
        arr = None if isinstance(value, (str, bytes)) else np.array(value, dtype=dtype, copy=True)
    except (TypeError, ValueError, OverflowError):
        arr = None
    if arr is not None and np.dtype(dtype).kind == "i":
        raw = np.asarray(value)
        if raw.dtype.kind not in "iu" or not np.array_equal(raw, arr):
            raise v.InputError(f"{source}: {key} has dtype {raw.dtype}, must be integers")
    if arr is None or arr.ndim != len(shape) or any(
            s not in (-1, n) for s, n in zip(shape, arr.shape)):
        got = None if arr is None else arr.shape
        raise v.InputError(f"{source}: {key} has shape {got}, must be "
                           f"{tuple('n' if s == -1 else s for s in shape)}")
    if arr.dtype.kind == "f" and not np.all(np.isfinite(arr)):
        i = tuple(int(x) for x in np.argwhere(~np.isfinite(arr))[0])
        raise v.InputError(f"{source}: {key}{list(i)} = {arr[i]} is invalid: must be finite")
    arr.flags.writeable = False
    return arr


@dataclass(frozen=True, eq=False)
class ModalStructure:
    """The normal modes of a structure, at named grid points (SI units; frame in the module
    docstring).

    grid_ids:        (n_grids,) distinct positive integer ids;
    xyz:             (n_grids, 3) grid positions [m] in the wing frame;
    frequencies_hz:  (n_modes,) natural frequencies [Hz], all above :data:`RIGID_BODY_HZ`;
    modal_mass:      (n_modes,) generalised masses φᵀ M φ [kg, with φ in m and rad], > 0;
    damping_ratio:   (n_modes,) modal viscous damping ratios ζ, in [0, 1);
    shapes:          (n_modes, n_grids, 6) each mode's [T_x, T_y, T_z, R_x, R_y, R_z] at
                     each grid [m, rad];
    source:          where it came from (a file's name), for the error messages.
    """

    grid_ids: np.ndarray
    xyz: np.ndarray
    frequencies_hz: np.ndarray
    modal_mass: np.ndarray
    damping_ratio: np.ndarray
    shapes: np.ndarray
    source: str = "modal structure"

    def __post_init__(self) -> None:
        src = self.source
        ids = _array(src, "grid_ids", self.grid_ids, (-1,), dtype=np.int64)
        ng = ids.size
        f = _array(src, "frequencies_hz", self.frequencies_hz, (-1,))
        nm = f.size
        if nm > MAX_MODES:
            raise v.InputError(f"{src}: {nm} modes is too many: at most {MAX_MODES} (keep the "
                               "lowest)")
        if nm == 0 or ng == 0:
            raise v.InputError(f"{src}: {'no modes' if nm == 0 else 'no grids'}: a modal "
                               "structure needs at least one mode and one grid")
        put = lambda k, x: object.__setattr__(self, k, x)  # noqa: E731
        put("grid_ids", ids)
        put("xyz", _array(src, "xyz", self.xyz, (ng, 3)))
        put("frequencies_hz", f)
        put("modal_mass", _array(src, "modal_mass", self.modal_mass, (nm,)))
        put("damping_ratio", _array(src, "damping_ratio", self.damping_ratio, (nm,)))
        put("shapes", _array(src, "shapes", self.shapes, (nm, ng, 6)))
        if np.any(ids <= 0):
            i = int(np.argmax(ids <= 0))
            raise v.InputError(f"{src}: grid_ids[{i}] = {ids[i]} is invalid: grid ids must be "
                               "positive integers")
        uniq, counts = np.unique(ids, return_counts=True)
        if np.any(counts > 1):
            dup = int(uniq[np.argmax(counts > 1)])
            where = [int(i) for i in np.flatnonzero(ids == dup)]
            raise v.InputError(f"{src}: grid_ids has grid {dup} twice (at {where}): each grid "
                               "id once")
        low = np.flatnonzero(f < RIGID_BODY_HZ)
        if low.size:
            i = int(low[0])
            raise v.InputError(
                f"{src}: frequencies_hz[{i}] = {f[i]:.6g} Hz is a rigid-body mode (below "
                f"{RIGID_BODY_HZ:g} Hz): a cantilever wing has none; remove it (mode {i + 1})")
        bad = np.flatnonzero(self.modal_mass <= 0)
        if bad.size:
            i = int(bad[0])
            raise v.InputError(f"{src}: modal_mass[{i}] = {self.modal_mass[i]:.6g} kg is "
                               f"invalid: must be > 0 (mode {i + 1})")
        bad = np.flatnonzero((self.damping_ratio < 0) | (self.damping_ratio >= 1))
        if bad.size:
            i = int(bad[0])
            raise v.InputError(f"{src}: damping_ratio[{i}] = {self.damping_ratio[i]:.6g} is "
                               f"invalid: must be in [0, 1) (mode {i + 1})")
        zero = np.flatnonzero(~np.any(self.shapes.reshape(nm, -1), axis=1))
        if zero.size:
            raise v.InputError(f"{src}: shapes[{int(zero[0])}] is zero at every grid: mode "
                               f"{int(zero[0]) + 1} has no motion")

    @classmethod
    def from_wing(cls, wing, n_modes: int | None = None, first_id: int = 1) -> "ModalStructure":
        """The in-vacuo modes of a beam :class:`~propwhirl.model.wing.Wing` (its structure
        alone, root clamped: 7.9–7.22), the lowest ``n_modes`` (default all), at one grid per
        node (ids ``first_id`` + node, the root's included, on the elastic axis at x = 0,
        y the node's station): T_z = −h, R_x = −∂h/∂y, R_y = α, the rest 0.  Mass-normalised
        (modal masses 1 kg); the modal damping ratio of the wing's Rayleigh damping
        C = μM + λK, ζ_i = (μ/ω_i + λ ω_i)/2 (exact: C is diagonal in these modes)."""
        import scipy.linalg

        from propwhirl.model.assembly import free_dofs, wing_structure

        M, _, K = wing_structure(wing)
        f = free_dofs(wing.n_nodes)
        w2, X = scipy.linalg.eigh(K[np.ix_(f, f)], M[np.ix_(f, f)])
        n = w2.size if n_modes is None else v.integer_at_least("n_modes", n_modes, 1)
        if n > w2.size:
            raise v.InputError(f"n_modes = {n} is invalid: the wing has {w2.size} modes")
        w2, X = w2[:n], X[:, :n]
        full = np.zeros((3 * wing.n_nodes, n))
        full[f] = X
        for k in range(n):                         # a sign convention: largest entry positive
            i = int(np.argmax(np.abs(full[:, k])))
            full[:, k] *= np.sign(full[i, k])
        nodal = full.reshape(wing.n_nodes, 3, n)   # [h, φ, α] per node
        shapes = np.zeros((n, wing.n_nodes, 6))
        shapes[:, :, 2] = -nodal[:, 0].T
        shapes[:, :, 3] = -nodal[:, 1].T
        shapes[:, :, 4] = nodal[:, 2].T
        omega = np.sqrt(w2)
        mu, lam = wing.rayleigh
        xyz = np.zeros((wing.n_nodes, 3))
        xyz[:, 1] = wing.node_y
        return cls(grid_ids=first_id + np.arange(wing.n_nodes), xyz=xyz,
                   frequencies_hz=omega / (2 * np.pi), modal_mass=np.ones(n),
                   damping_ratio=0.5 * (mu / omega + lam * omega), shapes=shapes,
                   source=f"modes of wing {getattr(wing, 'name', '')}".rstrip())

    @classmethod
    def with_mounts(cls, model, n_modes: int | None = None, first_hub_id: int = 1001
                    ) -> tuple["ModalStructure", tuple[int, ...], float]:
        """The in-vacuo modes of a :class:`~propwhirl.model.systems.PropellerWing`'s whole
        structure — the wing, every propeller's mass and its pitch and yaw springs (not
        spinning) — for propellers mounted "on-grid" (way b): the wing's node grids as
        :meth:`from_wing`, and a hub grid per propeller (ids ``first_hub_id`` + its index) at
        its hub, x = e_α aft of the elastic axis, moving as chapter 8's hub
        (:func:`propwhirl.generated.prop_hub.hub_motion`): T_z = −z_H, T_y = y_H, R_y = θ_H,
        R_z = −ψ_H, R_x the node's.  Mass-normalised; the modal damping ratio of each mode
        from the structure's damping C, ζ_i = φ_iᵀ C φ_i / (2 ω_i) (its couplings between
        modes dropped).  Returns (structure, hub grid ids, the largest coupling dropped,
        |φ_iᵀ C φ_j| / √(c_ii c_jj), 0 when C is diagonal in the modes)."""
        import scipy.linalg

        from propwhirl.model.assembly import free_dofs
        from propwhirl.model.propeller_blocks import propeller_constants

        wing = model.wing
        if wing.in_plane:
            raise v.InputError("ModalStructure.with_mounts: in-plane bending (EI_chordwise) "
                               "is not supported")
        quiet = model.with_(wing_aero=False, propeller_aero=False, rotating=False)
        sys = quiet.second_order(np.array([1.0]))
        M, C, K = sys.S1[0], sys.S2[0], sys.S3[0]
        w2, X = scipy.linalg.eigh(K, M)
        n = w2.size if n_modes is None else v.integer_at_least("n_modes", n_modes, 1)
        if n > w2.size:
            raise v.InputError(f"n_modes = {n} is invalid: the structure has {w2.size} modes")
        w2, X = w2[:n], X[:, :n]
        for k in range(n):
            i = int(np.argmax(np.abs(X[:, k])))
            X[:, k] *= np.sign(X[i, k])
        omega = np.sqrt(w2)
        Cm = X.T @ C @ X
        d = np.sqrt(np.abs(np.outer(np.diag(Cm), np.diag(Cm))))
        off = Cm - np.diag(np.diag(Cm))
        coupling = float(np.max(np.where(d > 0, np.abs(off) / np.where(d > 0, d, 1), 0.0)))
        nn, f = wing.n_nodes, free_dofs(wing.n_nodes)
        nodal = np.zeros((3 * nn, n))
        nodal[f] = X[: f.size]
        nodal = nodal.reshape(nn, 3, n)                # [h, φ, α] per node
        props = list(model.propellers)
        shapes = np.zeros((n, nn + len(props), 6))
        shapes[:, :nn, 2] = -nodal[:, 0].T
        shapes[:, :nn, 3] = -nodal[:, 1].T
        shapes[:, :nn, 4] = nodal[:, 2].T
        xyz = np.zeros((nn + len(props), 3))
        xyz[:nn, 1] = wing.node_y
        flex = model.flexible
        for j, inst in enumerate(props):
            node = model.nodes[j]
            c = propeller_constants(inst.propeller, wing, node, model.flight.density)
            G = prop_hub.hub_motion(c["e_theta"], c["e_psi"], c["e_alpha"])[:, :4]
            q = np.zeros((4, n))                        # [θ, ψ, h_P, α_P]
            if inst.mount == "flexible":
                pj = f.size + 2 * flex.index(j)
                q[0], q[1] = X[pj], X[pj + 1]
            q[2], q[3] = nodal[node, 0], nodal[node, 2]
            z, y, th, ps = G @ q
            g = nn + j
            shapes[:, g, 1], shapes[:, g, 2] = y, -z
            shapes[:, g, 3], shapes[:, g, 4], shapes[:, g, 5] = -nodal[node, 1], th, -ps
            xyz[g] = (c["e_alpha"], wing.node_y[node], 0.0)
        hub_ids = tuple(first_hub_id + j for j in range(len(props)))
        ids = np.concatenate([1 + np.arange(nn), np.array(hub_ids, dtype=np.int64)])
        out = cls(grid_ids=ids, xyz=xyz, frequencies_hz=omega / (2 * np.pi),
                  modal_mass=np.ones(n), damping_ratio=np.diag(Cm) / (2 * omega),
                  shapes=shapes, source=f"modes of {model.name}")
        return out, hub_ids, coupling

    @property
    def n_modes(self) -> int:
        """Number of modes."""
        return self.frequencies_hz.size

    @property
    def omega(self) -> np.ndarray:
        """Circular frequencies ω_i = 2π f_i [rad/s]."""
        return 2.0 * np.pi * self.frequencies_hz

    def index(self, grid: int, key: str = "grid") -> int:
        """Position of grid id ``grid`` in :attr:`grid_ids`; an error naming ``key`` if absent."""
        hit = np.flatnonzero(self.grid_ids == grid)
        if not hit.size:
            raise v.InputError(f"{self.source}: {key} = {grid} is not a grid of the modes "
                               f"(grids {_id_list(self.grid_ids)})")
        return int(hit[0])

    def truncated(self, n_modes: int) -> "ModalStructure":
        """The structure with its first ``n_modes`` modes only."""
        n = v.integer_at_least("n_modes", n_modes, 1)
        if n > self.n_modes:
            raise v.InputError(f"n_modes = {n} is invalid: the structure has {self.n_modes} "
                               "modes")
        return replace(self, frequencies_hz=self.frequencies_hz[:n],
                       modal_mass=self.modal_mass[:n], damping_ratio=self.damping_ratio[:n],
                       shapes=self.shapes[:n])

    def generalised(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The generalised M = diag(m_i), C = diag(2 ζ_i m_i ω_i), K = diag(m_i ω_i²)."""
        m, w, z = self.modal_mass, self.omega, self.damping_ratio
        return np.diag(m), np.diag(2.0 * z * m * w), np.diag(m * w * w)


def _id_list(ids, limit: int = 8) -> str:
    ids = [int(i) for i in ids]
    return ", ".join(map(str, ids[:limit])) + (", ..." if len(ids) > limit else "")


@dataclass(frozen=True, eq=False)
class StripPlanform:
    """The wing's aerodynamic strips: one per spanwise station (arrays of equal length).

    y:                  station of each strip [m], increasing;
    width:              strip width [m], > 0;
    chord:              local chord [m], > 0;
    leading_edge_x:     x of the leading edge [m] in the wing frame (x aft);
    elastic_axis:       elastic axis, fraction of the chord aft of the leading edge;
    aerodynamic_centre: aerodynamic centre, fraction of the chord aft of the leading edge;
    lift_slope:         section C_lα [1/rad], > 0;
    aero_model:         "leishman-nguyen" (2 lag states per strip) or "wagner" (4).
    """

    y: np.ndarray
    width: np.ndarray
    chord: np.ndarray
    leading_edge_x: np.ndarray
    elastic_axis: np.ndarray
    aerodynamic_centre: np.ndarray
    lift_slope: np.ndarray
    aero_model: str = "leishman-nguyen"
    source: str = "strips"

    def __post_init__(self) -> None:
        src = self.source
        y = _array(src, "y", self.y, (-1,))
        n = y.size
        if n == 0 or n > MAX_STRIPS:
            raise v.InputError(f"{src}: y has {n} strips: give 1 to {MAX_STRIPS}")
        object.__setattr__(self, "y", y)
        for k in ("width", "chord", "leading_edge_x", "elastic_axis", "aerodynamic_centre",
                  "lift_slope"):
            object.__setattr__(self, k, _array(src, k, getattr(self, k), (n,)))
        if n > 1 and np.any(np.diff(y) <= 0):
            i = int(np.argmax(np.diff(y) <= 0)) + 1
            raise v.InputError(f"{src}: y[{i}] = {y[i]:.6g} m is invalid: the strips' "
                               "stations must increase")
        for k in ("width", "chord", "lift_slope"):
            x = getattr(self, k)
            if np.any(x <= 0):
                i = int(np.argmax(x <= 0))
                raise v.InputError(f"{src}: {k}[{i}] = {x[i]:.6g} is invalid: must be > 0")
        if self.aero_model not in LAG_STATES:
            raise v.InputError(f"{src}: aero_model = {self.aero_model!r} is invalid: must be "
                               f"one of {', '.join(map(repr, LAG_STATES))}")

    @classmethod
    def from_wing(cls, wing, nodes: np.ndarray | None = None) -> "StripPlanform":
        """The strips of a :class:`~propwhirl.model.wing.Wing` at its nodes (default: every
        node but the clamped root), the elastic axis at x = 0 (its nodes' grids' x)."""
        p = wing.node_properties()
        nodes = np.arange(1, wing.n_nodes) if nodes is None else np.asarray(nodes)
        c = 2.0 * p["b"][nodes]
        ea = 0.5 * (p["a"][nodes] + 1.0)
        return cls(y=p["y"][nodes], width=p["width"][nodes], chord=c,
                   leading_edge_x=-ea * c, elastic_axis=ea,
                   aerodynamic_centre=0.5 * (p["ac"][nodes] + 1.0),
                   lift_slope=p["Cla"][nodes], aero_model=wing.aero_model)

    def node_properties(self) -> dict[str, np.ndarray]:
        """The strips as :meth:`Wing.node_properties` gives a wing's nodes: y, width, b, a,
        ac, Cla (for :func:`~propwhirl.model.assembly.strip_aero_blocks`)."""
        return dict(y=self.y, width=self.width, b=0.5 * self.chord,
                    a=2.0 * self.elastic_axis - 1.0, ac=2.0 * self.aerodynamic_centre - 1.0,
                    Cla=self.lift_slope)

    def mid_chord_x(self, y: float) -> float:
        """x [m] of the mid-chord at station y (linear between the strips, constant beyond)."""
        return float(np.interp(y, self.y, self.leading_edge_x + 0.5 * self.chord))


def strip_interpolation(structure: ModalStructure, wing_grids, planform: StripPlanform,
                        twist_spline: str = "linear") -> np.ndarray:
    """T (n_strips, 2, n_grids, 6): each strip's heave h [m] (positive down, at its elastic
    axis) and twist α [rad] (nose up) from the grids' six components (rule in the module
    docstring: Hermite cubic in y for T_z with R_x as slope, linear for R_y, rigid chord).

    ``wing_grids``: ids of the reference-axis grids, strictly increasing in y; every strip
    must lie within their span (an error names the first that does not)."""
    src = structure.source
    idx = np.array([structure.index(int(g), f"wing_grids[{i}]")
                    for i, g in enumerate(wing_grids)], dtype=int)
    if idx.size < 2:
        raise v.InputError(f"{src}: wing_grids has {idx.size} grid(s): the spline needs at "
                           "least 2")
    yg = structure.xyz[idx, 1]
    if np.any(np.diff(yg) <= 0):
        i = int(np.argmax(np.diff(yg) <= 0)) + 1
        raise v.InputError(f"{src}: wing_grids[{i}] = {int(wing_grids[i])} (y = {yg[i]:.6g} m) "
                           "is invalid: the wing grids must be ordered root to tip, y "
                           "increasing")
    ys = planform.y
    tol = 1e-9 * max(1.0, float(yg[-1] - yg[0]))
    out = np.flatnonzero((ys < yg[0] - tol) | (ys > yg[-1] + tol))
    if out.size:
        i = int(out[0])
        raise v.InputError(f"{planform.source}: y[{i}] = {ys[i]:.6g} m is outside the wing "
                           f"grids' span [{yg[0]:.6g}, {yg[-1]:.6g}] m")
    T = np.zeros((ys.size, 2, structure.grid_ids.size, 6))
    xg = structure.xyz[idx, 0]
    x_ea = planform.leading_edge_x + planform.elastic_axis * planform.chord
    twist = _twist_weights(yg, ys, twist_spline)          # (n_strips, n_wing_grids)
    for s, y in enumerate(ys):
        k = int(np.clip(np.searchsorted(yg, y, side="right") - 1, 0, yg.size - 2))
        i0, i1 = idx[k], idx[k + 1]
        L = yg[k + 1] - yg[k]
        t = float(np.clip((y - yg[k]) / L, 0.0, 1.0))
        # cubic Hermite basis: value and slope at each end
        h00, h10 = 1 - 3 * t**2 + 2 * t**3, (t - 2 * t**2 + t**3) * L
        h01, h11 = 3 * t**2 - 2 * t**3, (-t**2 + t**3) * L
        lever = x_ea[s] - ((1 - t) * xg[k] + t * xg[k + 1])
        # h = −(T_z − α · lever), α = R_y splined
        T[s, 0, i0, 2], T[s, 0, i0, 3] = -h00, -h10
        T[s, 0, i1, 2], T[s, 0, i1, 3] = -h01, -h11
        T[s, 0, idx, 4] += twist[s] * lever
        T[s, 1, idx, 4] = twist[s]
    return T


def _twist_weights(yg: np.ndarray, ys: np.ndarray, kind: str) -> np.ndarray:
    """Weights (n_strips, n_grids) of the twist at stations ``ys`` from its values at the
    grids ``yg``: "linear" (piecewise), or "cubic" (the not-a-knot cubic spline through the
    grids; a parabola through 3 grids, linear through 2)."""
    if kind == "linear" or yg.size == 2:
        eye = np.eye(yg.size)
        return np.stack([np.interp(ys, yg, eye[i]) for i in range(yg.size)], axis=1)
    from scipy.interpolate import CubicSpline

    return CubicSpline(yg, np.eye(yg.size), bc_type="not-a-knot")(ys)


@dataclass(frozen=True)
class ModalInstallation:
    """A propeller at hub grid ``grid`` of a :class:`ModalPropellerWing`.

    mount: "flexible" (its own pitch and yaw DOFs and springs), "rigid" (the rigid-mount
    block on the hub grid's heave and twist) or "on-grid" (rigid on the hub grid, its mount
    and mass in the modes: only its aerodynamic and gyroscopic loads added); aero: its
    aerodynamic loads on."""

    propeller: Propeller
    grid: int
    mount: Literal["flexible", "rigid", "on-grid"] = "flexible"
    aero: bool = True

    def __post_init__(self) -> None:
        if not isinstance(self.propeller, Propeller):
            raise v.InputError(f"propeller = {v.short_repr(self.propeller)} is invalid: must "
                               "be a Propeller")
        if isinstance(self.grid, bool) or not isinstance(self.grid, (int, np.integer)):
            raise v.InputError(f"grid = {v.short_repr(self.grid)} is invalid: must be a grid "
                               "id (an integer)")
        if self.mount not in MOUNTS:
            raise v.InputError(f"mount = {self.mount!r} is invalid: must be one of "
                               + ", ".join(map(repr, MOUNTS)))
        v.boolean("aero", self.aero)


@dataclass(frozen=True, eq=False)
class ModalPropellerWing(StateSpaceModel):
    """A wing given by its normal modes, with strip aerodynamics and propellers at hub grids
    (the module docstring).  Implements the :class:`~propwhirl.model.protocol.Model` contract.

    structure:  the :class:`ModalStructure`;
    wing_grids: ids of its reference-axis grids, root to tip (the strips' spline);
    planform:   the :class:`StripPlanform`;
    flight:     the :class:`~propwhirl.model.flight.FlightCondition`;
    propellers: :class:`ModalInstallation` s, at most one per hub grid;
    wing_aero, propeller_aero, rotating: switches as :class:`~propwhirl.model.systems.PropellerWing`'s.
    """

    structure: ModalStructure
    wing_grids: tuple[int, ...]
    planform: StripPlanform
    flight: FlightCondition
    propellers: tuple[ModalInstallation, ...] = ()
    wing_aero: bool = True
    propeller_aero: bool = True
    rotating: bool = True
    name: str = "modal propeller-wing"

    def __post_init__(self) -> None:
        for k in ("wing_aero", "propeller_aero", "rotating"):
            v.boolean(k, getattr(self, k))
        if not isinstance(self.flight, FlightCondition):
            raise v.InputError(f"flight = {v.short_repr(self.flight)} is invalid: must be a "
                               "FlightCondition")
        object.__setattr__(self, "wing_grids", tuple(int(g) for g in self.wing_grids))
        object.__setattr__(self, "propellers", tuple(self.propellers))
        limits.check_propellers(len(self.propellers))
        s = self.structure
        seen: dict[int, int] = {}
        for j, inst in enumerate(self.propellers):
            i = s.index(int(inst.grid), f"propellers[{j}].grid")
            if not np.any(s.shapes[:, i, :]):
                raise v.InputError(f"{s.source}: propellers[{j}].grid = {inst.grid} does not "
                                   "move in any mode: the modes do not include the hub grid")
            if int(inst.grid) in seen:
                raise v.InputError(f"propellers[{j}].grid = {inst.grid} is invalid: "
                                   f"propellers[{seen[int(inst.grid)]}] is on it already (at "
                                   "most one per hub grid)")
            seen[int(inst.grid)] = j
        strip_interpolation(s, self.wing_grids, self.planform)   # checks the grids now

    def with_(self, **changes) -> "ModalPropellerWing":
        """A copy with fields replaced (``dataclasses.replace``)."""
        return replace(self, **changes)

    @property
    def flexible(self) -> list[int]:
        """Indices of the flexibly mounted propellers (those with θ, ψ DOFs)."""
        return [j for j, inst in enumerate(self.propellers) if inst.mount == "flexible"]

    def without_aerodynamics(self) -> "ModalPropellerWing":
        """The same structure and propellers with wing and propeller aerodynamics off."""
        return self.with_(wing_aero=False, propeller_aero=False)

    def assembly(self) -> "ModalAssembly":
        """The speed-independent parts (a new :class:`ModalAssembly` each call)."""
        return ModalAssembly.build(self)

    def second_order(self, V, omega=None) -> SecondOrder:
        """The second-order system at airspeeds V [m/s] (:meth:`ModalAssembly.second_order`)."""
        return self.assembly().second_order(V, omega)

    def state_matrix(self, V, **options) -> np.ndarray:
        """A(V) (:meth:`ModalAssembly.state_matrix` of a new :meth:`assembly`)."""
        return self.assembly().state_matrix(V, **options)

    def dof_map(self) -> DofMap:
        """The states: η of every mode ("mode k", kind "eta"), then θ, ψ of each flexibly
        mounted propeller, then the lag states of every strip ("strip s w1", ...)."""
        n = self.structure.n_modes
        labels = [f"mode {k + 1}" for k in range(n)]
        kinds, node, prop = ["eta"] * n, [-1] * n, [-1] * n
        props = []
        for j in self.flexible:
            inst = self.propellers[j]
            y = float(self.structure.xyz[self.structure.index(inst.grid), 1])
            props.append(PropellerDofs(j, len(labels), len(labels) + 1,
                                       inst.propeller.rotation, self.rotating, y, None))
            labels += [f"propeller {j + 1} theta", f"propeller {j + 1} psi"]
            kinds += ["theta", "psi"]
            node += [-1, -1]
            prop += [j, j]
        w_labels: tuple[str, ...] = ()
        if self.wing_aero:
            k = LAG_STATES[self.planform.aero_model]
            w_labels = tuple(f"strip {s + 1} w{r + 1}" for s in range(self.planform.y.size)
                             for r in range(k))
        return DofMap(tuple(labels), tuple(kinds), tuple(node), tuple(prop), w_labels,
                      (-1,) * len(w_labels), tuple(props))


@dataclass(frozen=True, eq=False)
class ModalAssembly(EvaluatorBase):
    """A :class:`ModalPropellerWing` with its speed-independent parts, built once.

    structure:  the generalised (n_q, n_q) M, C, K (modes and propeller DOFs), read-only;
    strips:     (n_strips, 2, n_q): each strip's [h, α] from q (T Φ);
    hubs:       per installation (its local DOFs, 2 or 4, n_q): [θ, ψ,] h_P, α_P from q;
    constants:  per installation its generated blocks' speed-independent arguments;
    states:     the :class:`~propwhirl.model.protocol.DofMap`.
    """

    model: ModalPropellerWing
    structure: tuple[np.ndarray, np.ndarray, np.ndarray]
    strips: np.ndarray
    hubs: tuple[np.ndarray, ...]
    constants: tuple
    states: DofMap

    @classmethod
    def build(cls, model: ModalPropellerWing) -> "ModalAssembly":
        s = model.structure
        nm = s.n_modes
        flex = model.flexible
        n = nm + 2 * len(flex)
        mats = tuple(np.zeros((n, n)) for _ in range(3))
        for X, Xm in zip(mats, s.generalised()):
            X[:nm, :nm] = Xm
        Phi = s.shapes.transpose(1, 2, 0)                      # (n_grids, 6, n_modes)
        T = strip_interpolation(s, model.wing_grids, model.planform)
        strips = np.zeros((model.planform.y.size, 2, n))
        strips[:, :, :nm] = np.einsum("scgk,gkm->scm", T, Phi)
        hubs, consts = [], []
        for j, inst in enumerate(model.propellers):
            g = s.index(inst.grid)
            if inst.mount == "on-grid":
                hub = np.zeros((4, n))
                hub[:, :nm] = Phi[g, [2, 1, 4, 5]] * np.array([-1.0, 1.0, 1.0, -1.0])[:, None]
                hub.flags.writeable = False
                hubs.append(hub)
                p = inst.propeller
                consts.append(MappingProxyType(dict(I_Omega=p.I_Omega, rho=model.flight.density,
                                                    R=p.radius)))
                continue
            hub = np.zeros((2, n))
            hub[0, :nm] = -Phi[g, 2]                           # h_P = −T_z
            hub[1, :nm] = Phi[g, 4]                            # α_P = R_y
            if inst.mount == "flexible":
                pj = nm + 2 * flex.index(j)
                rows = np.zeros((2, n))
                rows[0, pj], rows[1, pj + 1] = 1.0, 1.0
                hub = np.vstack([rows, hub])
            ea = float(s.xyz[g, 0]) - model.planform.mid_chord_x(float(s.xyz[g, 1]))
            c = propeller_constants_at(inst.propeller, ea, model.flight.density)
            hub.flags.writeable = False
            hubs.append(hub)
            consts.append(MappingProxyType(c))
        for X in (*mats, strips):
            X.flags.writeable = False
        return cls(model, mats, strips, tuple(hubs), tuple(consts), model.dof_map())

    def dof_map(self) -> DofMap:
        return self.states

    def without_aerodynamics(self) -> "ModalAssembly":
        """The assembly of ``model.without_aerodynamics()`` (same parts)."""
        model = self.model.without_aerodynamics()
        return replace(self, model=model, states=model.dof_map())

    def second_order(self, V, omega=None) -> SecondOrder:
        """S1 q̈ + S2 q̇ + S3 q = S4 w, ẇ = Ww w + Wv q̇ + Wq q at airspeeds V [m/s] (array).
        `omega` [rad/s] overrides every propeller's rotational speed.  The checks of
        :meth:`PropellerWingAssembly.second_order`."""
        model = self.model
        V = np.atleast_1d(v.positive("airspeed V", V, "m/s"))
        if validity.has_aerodynamics(model):
            validity.check_mach(V, model.flight.speed_of_sound)
        with np.errstate(all="ignore"):
            sys = self._assemble(V, omega)
        return self._checked(sys, V, {"omega": omega})

    def _assemble(self, V: np.ndarray, omega) -> SecondOrder:
        model, nV = self.model, V.shape[0]
        n = self.structure[0].shape[0]
        S = [np.broadcast_to(X, (nV, n, n)).copy() for X in self.structure]
        derivatives: dict = {}
        for inst, hub, const in zip(model.propellers, self.hubs, self.constants):
            aero = model.propeller_aero and inst.aero
            vals = propeller_values(const, inst.propeller, V, omega, rotating=model.rotating,
                                    aero=aero, speed_of_sound=model.flight.speed_of_sound,
                                    derivatives=derivatives)
            if inst.mount == "on-grid":
                mats = _on_grid_matrices(vals, aero, nV)
            else:
                mats = propeller_matrices(vals, mount=inst.mount, in_plane=False, aero=aero)
            for Si, B in zip(S, mats):
                Si += hub.T @ B @ hub
        if not model.wing_aero:
            z = np.zeros((nV, 0, n))
            return SecondOrder(*S, np.zeros((nV, n, 0)), np.zeros((nV, 0, 0)), z, z.copy(),
                               self.states.q_labels, ())
        a = strip_aero_blocks(model.planform.node_properties(), model.planform.aero_model,
                              model.flight.density, V)
        P = self.strips                                           # (ns, 2, n)
        for Si, A in zip(S, (a["Ma"], a["Ca"], a["Ka"])):
            Si -= np.einsum("sim,vsij,sjn->vmn", P, A, P)
        ns, k = P.shape[0], a["Ww"].shape[-1]
        m = ns * k
        S4 = np.einsum("sim,vsir->vmsr", P, a["W0"]).reshape(nV, n, m)
        Wv = np.einsum("vsri,sin->vsrn", a["Wv"], P).reshape(nV, m, n)
        Wq = np.einsum("vsri,sin->vsrn", a["Wq"], P).reshape(nV, m, n)
        Ww = np.zeros((nV, m, m))
        for s in range(ns):
            Ww[:, s * k:(s + 1) * k, s * k:(s + 1) * k] = a["Ww"][:, s]
        return SecondOrder(*S, S4, Ww, Wv, Wq, self.states.q_labels, self.states.w_labels)


def _on_grid_matrices(values: dict, aero: bool, nV: int):
    """(M, C, K) (nV, 4, 4) on the hub's [z_H, y_H, θ_H, ψ_H] of a propeller rigid on its hub
    grid: the generated gyroscopic matrix and, with ``aero``, the Houbolt–Reed loads (signs
    applied: S1 = −M_a, S2 = C_g − C_a, S3 = −K_a)."""
    if not aero:
        Cg = call_blocks(prop_hub, "hub_blocks", (nV,), **_zero_derivatives(values))["Cg"]
        z = np.zeros((nV, 4, 4))
        return z, Cg, z.copy()
    b = call_blocks(prop_hub, "hub_blocks", (nV,), **values)
    return -b["Ma_hub"], b["Cg"] - b["Ca_hub"], -b["Ka_hub"]


def _zero_derivatives(values: dict) -> dict:
    """``values`` with every aerodynamic derivative 0 (the gyroscopic matrix alone)."""
    out = dict(values)
    for name in prop_hub.BLOCKS["hub_blocks"][0]:
        out.setdefault(name, 0.0)
    return out
