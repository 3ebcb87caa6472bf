"""Modal structures: a structure given by its normal modes, and the strips' spline (issue 22).

:class:`ModalStructure` holds what any finite-element code's normal-modes solution gives:
the natural frequencies, modal masses and modal damping ratios, and every mode's six
displacements and rotations at named grid points (checked: no rigid-body mode, unique ids,
finite values); :meth:`ModalStructure.from_wing` and :meth:`ModalStructure.with_mounts` give
a beam model's own.  :class:`StripPlanform` holds the wing's aerodynamic strips and
:func:`strip_interpolation` their heave and twist from the grids.  The model on them is
:class:`propwhirl.model.modal.ModalPropellerWing`.

**Frame and sign conventions** (the file format's, ``docs/modal-structures.md``): the wing
frame is right-handed, x aft (chordwise, rearward), y spanwise outboard, z up; each grid's
six components are [T_x, T_y, T_z, R_x, R_y, R_z] [m, m, m, rad, rad, rad].  The beam models'
heave h is positive down and twist α nose up, so h = −T_z, α = R_y and the bending slope
∂h/∂y = −R_x.

**The spline** (:func:`axis_spline`, one rule for the strips and the doublet-lattice
panels).  The heave and twist at a point (x, y) of the wing are interpolated from the
``wing_grids`` (the grids on the wing's reference axis, ordered root to tip, y increasing;
the axis may be swept, x_ref varying with y): along the span, T_z by the cubic Hermite
spline of each grid interval with the grids' rotations carried along the axis as its slopes
(∂T_z/∂y = R_x − R_y ∂x_ref/∂y: R_x on an unswept axis), R_y linearly; across the chord, the
streamwise section is rigid, so the displacement at x is z = −(T_z − R_y (x − x_ref)), positive
down, with x_ref the reference axis (the grids' x, linear in y), and its slope ∂z/∂x = R_y.
A strip takes it at its elastic axis (:func:`strip_interpolation`), a panel at its points
(:meth:`propwhirl.model.modal.ModalPropellerWing.dlm_surface`).  This is the beam element's own interpolation (Hermite cubic in
bending, linear in torsion), so with a grid at every node of a beam model the spline
reproduces the beam's modes exactly at every point; on a coarser grid its error is measured
in ``docs/validation.md`` ("Modal structures").
"""
from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np
import scipy.linalg
from scipy.interpolate import CubicSpline

from propwhirl import validate as v
from propwhirl.generated import prop_hub
from propwhirl.model.fields import spec
from propwhirl.model.structure.assembly import LAG_STATES, free_dofs, wing_structure
from propwhirl.model.structure.mesh import beam_interpolation
from propwhirl.model.propeller_blocks import propeller_constants
from propwhirl.model.rigid_body import (KEPT_RIGID_BODY, RIGID_FIT, RIGID_SHARE,  # noqa: F401
                                        one_pitch, refusal, rigid_body_kind, rigid_shape)

#: Components of a grid's motion in a mode shape, in the order of the last axis of ``shapes``.
COMPONENTS = ("T_x", "T_y", "T_z", "R_x", "R_y", "R_z")
#: Modes whose frequency is below this [Hz] are rigid-body modes: a cantilever wing has none.
RIGID_BODY_HZ = 1e-3
#: Highest natural frequency [Hz]: ω² = (2π f)² ≈ 4e49 1/s², within the rates an analysis
#: takes (:data:`propwhirl.model.statespace.RATE_LIMIT`, 1e50) and far from overflow — and far
#: above any structure's (a 200-element beam's highest mode is about 2e6 Hz).
MAX_FREQUENCY_HZ = 1e24
#: Most modes and strips of a model (a beam model has at most 3 × limits.MAX_ELEMENTS DOFs
#: and MAX_ELEMENTS + 1 strips): the analyses' matrices grow with their squares.
MAX_MODES = 1000
MAX_STRIPS = 1000


@dataclass(frozen=True, eq=False)
class ModalStructure:
    """The normal modes of a structure, at named grid points (SI units; frame in the module
    docstring).

    Parameters
    ----------
    grid_ids : ndarray of int
        (n_grids,) distinct positive integer ids.
    xyz : ndarray
        (n_grids, 3) grid positions [m] in the wing frame (x aft, y outboard, z up).
    frequencies_hz : ndarray
        (n_modes,) natural frequencies [Hz], all above :data:`RIGID_BODY_HZ` (but a free
        structure's rigid-body modes, ``free``).
    modal_mass : ndarray
        (n_modes,) generalised masses φᵀ M φ [kg, with φ in m and rad], > 0.
    damping_ratio : ndarray
        (n_modes,) modal viscous damping ratios ζ [-], in [0, 1).
    shapes : ndarray
        (n_modes, n_grids, 6) each mode's [T_x, T_y, T_z, R_x, R_y, R_z] at each grid
        [m, m, m, rad, rad, rad].
    source : str
        Where it came from (a file's name), for the error messages.
    free : bool
        The structure is free (a whole or half aircraft, not a clamped wing): its modes below
        :data:`RIGID_BODY_HZ` (at 0 <= f) are rigid-body modes, accepted when each is a
        plunge, a roll (about any axis along x) or a pitch
        (:func:`~propwhirl.model.rigid_body.rigid_body_kind`) and then taken as exactly rigid
        (:func:`~propwhirl.model.rigid_body.rigid_shape`); a rigid yaw (no fin), surge or
        sway is refused naming the mode.  A pitch needs a tail: the model on the structure
        refuses it with the wing alone (:mod:`propwhirl.model.rigid_body`).  False (the
        default): no mode below :data:`RIGID_BODY_HZ`.

    Examples
    --------
    A beam wing's own modes (:meth:`from_wing`): one grid per node, mass-normalised.

    >>> from propwhirl.model import ModalStructure
    >>> from propwhirl.cases.ch09_baseline import baseline_wing
    >>> s = ModalStructure.from_wing(baseline_wing(n_elements=6), n_modes=4)
    >>> s.grid_ids.tolist(), s.shapes.shape
    ([1, 2, 3, 4, 5, 6, 7], (4, 7, 6))
    >>> [round(float(f), 1) for f in s.frequencies_hz]                  # [Hz]
    [2.9, 16.7, 18.1, 47.6]
    """

    grid_ids: np.ndarray
    xyz: np.ndarray
    # the modes' numbers a parameter path reaches (studies/paths.py: structure.frequencies_hz[0])
    frequencies_hz: np.ndarray = field(metadata=spec(
        None, "Hz", "natural frequency of the mode", form="numbers",
        range=(RIGID_BODY_HZ, 1e6)))
    modal_mass: np.ndarray = field(metadata=spec(
        None, "kg", "generalised mass of the mode (phi in m and rad)", form="numbers",
        range=(0.0, 1e12), ends="(]"))
    damping_ratio: np.ndarray = field(metadata=spec(
        None, "", "modal viscous damping ratio of the mode", form="numbers",
        range=(0.0, 1.0), ends="[)"))
    shapes: np.ndarray
    source: str = "modal structure"
    free: bool = False

    def __post_init__(self) -> None:
        src = self.source
        ids = v.shaped_array(src, "grid_ids", self.grid_ids, (-1,), dtype=np.int64)
        ng = ids.size
        f = v.shaped_array(src, "frequencies_hz", self.frequencies_hz, (-1,))
        nm = f.size
        if nm > MAX_MODES:
            raise v.InputError(f"{src}: {nm} modes is too many: at most {MAX_MODES} (keep the "
                               "lowest)")
        if nm == 0 or ng == 0:
            raise v.InputError(f"{src}: {'no modes' if nm == 0 else 'no grids'}: a modal "
                               "structure needs at least one mode and one grid")
        put = lambda k, x: object.__setattr__(self, k, x)  # noqa: E731
        put("grid_ids", ids)
        put("xyz", v.shaped_array(src, "xyz", self.xyz, (ng, 3)))
        put("frequencies_hz", f)
        put("modal_mass", v.shaped_array(src, "modal_mass", self.modal_mass, (nm,)))
        put("damping_ratio", v.shaped_array(src, "damping_ratio", self.damping_ratio, (nm,)))
        put("shapes", v.shaped_array(src, "shapes", self.shapes, (nm, ng, 6)))
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
        high = np.flatnonzero(f > MAX_FREQUENCY_HZ)
        if high.size:
            i = int(high[0])
            raise v.InputError(
                f"{src}: frequencies_hz[{i}] = {f[i]:.6g} Hz is outside the valid range "
                f"[{v.fmt_bound(RIGID_BODY_HZ)}, {v.fmt_bound(MAX_FREQUENCY_HZ)}] Hz (mode "
                f"{i + 1}): (2π f)² beyond the rates an analysis takes")
        if not isinstance(self.free, (bool, np.bool_)):
            raise v.InputError(f"{src}: free = {v.short_repr(self.free)} is invalid: must be "
                               "true or false")
        put("free", bool(self.free))
        low = np.flatnonzero(f < RIGID_BODY_HZ)
        if low.size and (not self.free or np.any(f[low] < 0)):
            i = int(low[0]) if not self.free else int(low[np.argmax(f[low] < 0)])
            raise v.InputError(
                f"{src}: frequencies_hz[{i}] = {f[i]:.6g} Hz is a rigid-body mode (below "
                f"{RIGID_BODY_HZ:g} Hz): a cantilever wing has none; remove it, or keep a "
                f"plunge or roll of a free structure by saying it is free (free = true) "
                f"(mode {i + 1})"
                if not self.free else
                f"{src}: frequencies_hz[{i}] = {f[i]:.6g} Hz is invalid: a free structure's "
                f"rigid-body mode is at 0 <= f < {RIGID_BODY_HZ:g} Hz (mode {i + 1})")
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
        if low.size:                               # a free structure's rigid-body modes
            for i in low:
                kind = rigid_body_kind(self.xyz, self.shapes[i])
                why = refusal(kind)
                if why is not None:
                    raise v.InputError(f"{src}: mode {int(i) + 1} ({f[i]:.3g} Hz) is a "
                                       f"rigid-body {kind}: {why}")
            shapes, mass = one_pitch(self.xyz, self.shapes, self.modal_mass, low)
            for i in low:
                shapes[i] = rigid_shape(self.xyz, shapes[i])
            for k, x in (("shapes", shapes), ("modal_mass", mass)):
                x.flags.writeable = False
                put(k, x)

    @classmethod
    def from_wing(cls, wing, n_modes: int | None = None, first_id: int = 1) -> "ModalStructure":
        """The in-vacuo modes of a beam :class:`~propwhirl.model.structure.wing.Wing` (its structure
        alone, root clamped: 7.9–7.22), the lowest ``n_modes`` (default all), at one grid per
        node (ids ``first_id`` + node, the root's included, on the elastic axis at x = 0,
        y the node's station): T_z = −h, R_x = −∂h/∂y, R_y = α, the rest 0.  Mass-normalised
        (modal masses 1 kg); the modal damping ratio of the wing's Rayleigh damping
        C = μM + λK, ζ_i = (μ/ω_i + λ ω_i)/2 (exact: C is diagonal in these modes)."""
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
                               f"(grids {id_list(self.grid_ids)})")
        return int(hit[0])

    def rigid_body_modes(self) -> tuple[tuple[int, str], ...]:
        """(mode index, kind) of each rigid-body mode kept (a free structure's, below
        :data:`RIGID_BODY_HZ`; :func:`~propwhirl.model.rigid_body.rigid_body_kind`)."""
        return tuple((int(i), rigid_body_kind(self.xyz, self.shapes[i]))
                     for i in np.flatnonzero(self.frequencies_hz < RIGID_BODY_HZ))

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
        with np.errstate(over="ignore"):   # inf: the state matrix's check names the entry
            return np.diag(m), np.diag(2.0 * z * m * w), np.diag(m * w * w)


def id_list(ids, limit: int = 8) -> str:
    """Grid ids as error messages list them: the first `limit`, then ", ..."."""
    ids = [int(i) for i in ids]
    return ", ".join(map(str, ids[:limit])) + (", ..." if len(ids) > limit else "")


@dataclass(frozen=True, eq=False)
class StripPlanform:
    """The wing's aerodynamic strips: one per spanwise station (arrays of equal length).

    Parameters
    ----------
    y : ndarray
        Station of each strip [m], increasing.
    width : ndarray
        Strip width [m], > 0.
    chord : ndarray
        Local chord [m], > 0.
    leading_edge_x : ndarray
        x of the leading edge [m] in the wing frame (x aft).
    elastic_axis : ndarray
        Elastic axis [fraction of the chord aft of the leading edge].
    aerodynamic_centre : ndarray
        Aerodynamic centre [fraction of the chord aft of the leading edge].
    lift_slope : ndarray
        Section lift-curve slope C_lα [1/rad], > 0.
    aero_model : {"leishman-nguyen", "wagner"}
        Unsteady strip aerodynamics: 2 (Leishman–Nguyen) or 4 (Wagner) lag states per strip.
    source : str
        Where it came from (a file's name), for the error messages.

    Examples
    --------
    A beam wing's strips (:meth:`from_wing`): one at every node but the clamped root.

    >>> from propwhirl.model import StripPlanform
    >>> from propwhirl.cases.ch09_baseline import baseline_wing
    >>> p = StripPlanform.from_wing(baseline_wing(n_elements=6))
    >>> [round(float(y), 2) for y in p.y]
    [0.95, 1.9, 2.85, 3.8, 4.75, 5.7]
    >>> [round(float(w), 3) for w in p.width]
    [0.95, 0.95, 0.95, 0.95, 0.95, 0.475]
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
        y = v.shaped_array(src, "y", self.y, (-1,))
        n = y.size
        if n == 0 or n > MAX_STRIPS:
            raise v.InputError(f"{src}: y has {n} strips: give 1 to {MAX_STRIPS}")
        object.__setattr__(self, "y", y)
        for k in ("width", "chord", "leading_edge_x", "elastic_axis", "aerodynamic_centre",
                  "lift_slope"):
            object.__setattr__(self, k, v.shaped_array(src, k, getattr(self, k), (n,)))
        if n > 1 and np.any(np.diff(y) <= 0):
            i = int(np.argmax(np.diff(y) <= 0)) + 1
            raise v.InputError(f"{src}: y[{i}] = {y[i]:.6g} m is invalid: the strips' "
                               "stations must increase")
        for k in ("width", "chord", "lift_slope"):
            x = getattr(self, k)
            if np.any(x <= 0):
                i = int(np.argmax(x <= 0))
                raise v.InputError(f"{src}: {k}[{i}] = {x[i]:.6g} is invalid: must be > 0")
        if not (isinstance(self.aero_model, str) and self.aero_model in LAG_STATES):
            raise v.InputError(f"{src}: aero_model = {v.short_repr(self.aero_model)} is "
                               "invalid: must be "
                               f"one of {', '.join(map(repr, LAG_STATES))}")

    @classmethod
    def from_wing(cls, wing, nodes: np.ndarray | None = None) -> "StripPlanform":
        """The strips of a :class:`~propwhirl.model.structure.wing.Wing` at its nodes (default: every
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
        ac, Cla (for :func:`~propwhirl.model.structure.assembly.strip_aero_blocks`)."""
        return dict(y=self.y, width=self.width, b=0.5 * self.chord,
                    a=2.0 * self.elastic_axis - 1.0, ac=2.0 * self.aerodynamic_centre - 1.0,
                    Cla=self.lift_slope)

    def mid_chord_x(self, y: float) -> float:
        """x [m] of the mid-chord at station y (linear between the strips, constant beyond)."""
        return float(np.interp(y, self.y, self.leading_edge_x + 0.5 * self.chord))


def strip_interpolation(structure: ModalStructure, wing_grids, planform: StripPlanform,
                        twist_spline: str = "linear", key: str = "wing_grids") -> np.ndarray:
    """T (n_strips, 2, n_grids, 6): each strip's heave h [m] (positive down, at its elastic
    axis) and twist α [rad] (nose up) from the grids' six components: :func:`axis_spline`
    (the one rule, the doublet-lattice panels' too) at each strip's station and elastic axis.

    ``wing_grids``: ids of the reference-axis grids, strictly increasing in y; every strip
    must lie within their span (an error names the first that does not); ``key``: how the
    errors name the grids (a tail's ``surfaces[j].grids``)."""
    ys = planform.y
    x_ea = planform.leading_edge_x + planform.elastic_axis * planform.chord

    def outside(i: int, lo: float, hi: float) -> str:
        return (f"{planform.source}: y[{i}] = {ys[i]:.6g} m is outside the {_grids(key)}' "
                f"span [{lo:.6g}, {hi:.6g}] m")

    Z, S = axis_spline(structure, wing_grids, x_ea, ys, outside, twist_spline, key)
    return np.stack([Z, S], axis=1)


def _grids(key: str) -> str:
    """How an error names the grids of ``key``: "wing grids", or the key itself."""
    return "wing grids" if key == "wing_grids" else key


def axis_spline(structure: ModalStructure, wing_grids, x: np.ndarray, y: np.ndarray,
                outside=None, twist_spline: str = "linear", key: str = "wing_grids"
                ) -> tuple[np.ndarray, np.ndarray]:
    """The beam spline along the reference axis of the ``wing_grids``: at points (x, y) [m]
    of the wing's plane, (Z, S) each (n, n_grids, 6) — Z the weights of the grids' six
    components in the point's displacement normal to the wing, positive down [m] (z = Z · u),
    S in its streamwise slope ∂z/∂x [rad] (the nose-up twist).  The rule of the strips and of
    the doublet-lattice panels (one place; module docstring):

    * along the span T_z is the cubic Hermite spline in y of each grid interval, its slopes
      ∂T_z/∂y = R_x − R_y ∂x_ref/∂y (the grids' rotations carried along the reference axis:
      R_x alone on an unswept axis; the interval's own sweep ∂x_ref/∂y on a swept one), R_y
      (the twist) linear in y (``twist_spline = "cubic"``: the not-a-knot spline through
      the grids); the beam element's interpolation
      (:func:`~propwhirl.model.structure.mesh.beam_interpolation`), exact for a beam's modes
      with a grid at every node;
    * across the chord the streamwise section is rigid, attached to the axis at the same y:
      z = −(T_z − R_y (x − x_ref(y))), x_ref the grids' x linear in y, ∂z/∂x = R_y.

    Its measured error (docs/modal-structures.md, "Doublet lattice on the modes"): with a
    grid at every node of a beam model, the panels' GAFs on the modes equal the beam's
    projected ones to 5e-16 of max |Q|; on the wingtip wing (24 elements) with 13, 9, 7 and 5
    grids the six lowest modes' GAFs are within 3.5, 12, 18 and 40 % (mostly the linear twist
    of the torsion modes) and the doublet-lattice critical speeds within 0.21, 0.49, 0.96 and
    2.4 %.

    ``wing_grids`` strictly increasing in y, at least 2; ``outside(i, lo, hi)``: the one-line
    message for point i outside the grids' span [lo, hi] [m] (default a generic one);
    ``key``: how the errors name the grids."""
    src = structure.source
    idx = np.array([structure.index(int(g), f"{key}[{i}]")
                    for i, g in enumerate(wing_grids)], dtype=int)
    if idx.size < 2:
        raise v.InputError(f"{src}: {key} has {idx.size} grid(s): the spline needs at "
                           "least 2")
    yg = structure.xyz[idx, 1]
    if np.any(np.diff(yg) <= 0):
        i = int(np.argmax(np.diff(yg) <= 0)) + 1
        raise v.InputError(f"{src}: {key}[{i}] = {int(wing_grids[i])} (y = {yg[i]:.6g} m) "
                           f"is invalid: the {_grids(key)} must be ordered root to tip, y "
                           "increasing")
    x = np.asarray(x, dtype=float)
    ys = np.asarray(y, dtype=float)
    tol = 1e-9 * max(1.0, float(yg[-1] - yg[0]))
    out = np.flatnonzero((ys < yg[0] - tol) | (ys > yg[-1] + tol))
    if out.size:
        i = int(out[0])
        raise v.InputError(outside(i, float(yg[0]), float(yg[-1])) if outside is not None else
                           f"{src}: a point at y = {ys[i]:.6g} m is outside the {_grids(key)}' "
                           f"span [{yg[0]:.6g}, {yg[-1]:.6g}] m")
    Z = np.zeros((ys.size, structure.grid_ids.size, 6))
    S = np.zeros_like(Z)
    xg = structure.xyz[idx, 0]
    twist = _twist_weights(yg, ys, twist_spline)          # (n, n_wing_grids)
    # the beam's interpolation: T_z cubic Hermite with its slopes, x_ref linear
    H, P, linear = beam_interpolation(yg, ys)             # (n, n_wing_grids)
    lever = x - np.sum(linear * xg, axis=1)
    # the sweep of the interval holding each point (the one beam_interpolation takes)
    k = np.clip(np.searchsorted(yg, ys, side="right") - 1, 0, yg.size - 2)
    sweep = (np.diff(xg) / np.diff(yg))[k]
    # z = −(T_z − R_y · lever), slopes R_x − R_y ∂x_ref/∂y, ∂z/∂x = R_y splined
    Z[:, idx, 2], Z[:, idx, 3] = -H, -P
    Z[:, idx, 4] += twist * lever[:, None] + P * sweep[:, None]
    S[:, idx, 4] = twist
    return Z, S


#: Sweep [deg] of a modal model's reference axis (its wing grids' line) beyond which its strip
#: aerodynamics refuse it (:func:`check_strip_sweep`): a tapered wing's elastic axis at a chord
#: fraction leans a few degrees without being a swept wing (cos 5° = 0.996).
STRIP_SWEEP_LIMIT_DEG = 5.0


def reference_sweep(structure: ModalStructure, wing_grids, key: str = "wing_grids") -> float:
    """Sweep Λ [deg] of the wing grids' line, positive aft: the least-squares slope of their x
    against their y, Λ = atan(dx/dy) (0 for a line of grids along y)."""
    idx = np.array([structure.index(int(g), key) for g in wing_grids], dtype=int)
    y, x = structure.xyz[idx, 1], structure.xyz[idx, 0]
    if idx.size < 2 or not float(np.ptp(y)) > 0.0:
        return 0.0
    return float(np.degrees(np.arctan(np.polyfit(y - y.mean(), x - x.mean(), 1)[0])))


def check_strip_sweep(structure: ModalStructure, wing_grids, key: str = "wing_grids") -> None:
    """Refuse a reference axis swept by more than :data:`STRIP_SWEEP_LIMIT_DEG` under strip
    aerodynamics, one line: the key, the angle, why, and what to use.  The strips here are an
    unswept wing's: streamwise strips with the normal flow and the lift slope of an unswept
    section (no cos Λ); their spline (:func:`axis_spline`) follows a swept axis, their
    aerodynamics do not.  A swept wing's lifting surface is the doublet lattice's
    (``aero = "dlm"``: panels on its ``dlm_planform``, splined to the grids by the same
    rule)."""
    sweep = reference_sweep(structure, wing_grids, key)
    if abs(sweep) > STRIP_SWEEP_LIMIT_DEG:
        ids = [int(g) for g in wing_grids]
        raise v.InputError(
            f"{structure.source}: {key} (GRID {ids[0]} to GRID {ids[-1]}) make a reference "
            f"axis swept by {sweep:.1f} deg, more than the {STRIP_SWEEP_LIMIT_DEG:g} deg the "
            "strip aerodynamics take: propwhirl's strips are an unswept wing's (no cos(sweep) in "
            "the normal flow or the lift slope); a swept wing takes the doublet lattice (aero = "
            "'dlm' with a dlm_planform: panels on its planform), or wing_aero = false for its "
            "structure alone")


def _twist_weights(yg: np.ndarray, ys: np.ndarray, kind: str) -> np.ndarray:
    """Weights (n_strips, n_grids) of the twist at stations ``ys`` from its values at the
    grids ``yg``: "linear" (piecewise), or "cubic" (the not-a-knot cubic spline through the
    grids; a parabola through 3 grids, linear through 2)."""
    if kind == "linear" or yg.size == 2:
        eye = np.eye(yg.size)
        return np.stack([np.interp(ys, yg, eye[i]) for i in range(yg.size)], axis=1)
    return CubicSpline(yg, np.eye(yg.size), bc_type="not-a-knot")(ys)
