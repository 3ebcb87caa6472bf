"""A wing given by its normal modes, with strip aerodynamics and propellers (issue 22, item 2).

:class:`ModalPropellerWing` implements the :class:`~propwhirl.model.protocol.Model` contract
on a :class:`~propwhirl.model.modal_structure.ModalStructure` (the modes, their frame and sign
conventions, and the strips' spline are in :mod:`propwhirl.model.modal_structure`), so the
engine and the analyses work unchanged: its degrees of freedom are the modal coordinates η
(then θ, ψ of each flexibly mounted propeller), its structure generalised M = diag(m_i),
K = diag(m_i ω_i²), C = diag(2 ζ_i m_i ω_i).

**Strip aerodynamics on the modes.**  The wing's strips (the same generated strip
aerodynamics as a :class:`~propwhirl.model.structure.wing.Wing`'s,
:func:`propwhirl.model.structure.assembly.strip_aero_blocks`) sit at the stations of a
:class:`~propwhirl.model.modal_structure.StripPlanform`; with T the spline
(:func:`~propwhirl.model.modal_structure.strip_interpolation`) the aerodynamic matrices are
(TΦ)ᵀ A_strip (TΦ), the lag states' couplings projected the same way.

**Further lifting surfaces** (``surfaces``, issue 36 item 4).  A tail
(:class:`~propwhirl.model.modal_surface.ModalSurface`): strips on its own grids, splined and
loaded as the wing's, its lag states after the wing's ("tail strip s w r"); with strip
aerodynamics only.  A free structure's rigid pitch needs one
(:mod:`propwhirl.model.rigid_body`: the wing alone admits plunge and roll).

**Doublet lattice on the modes** (``aero = "dlm"``, issue 34 item 3).  The panels of the
``dlm_planform`` (:class:`~propwhirl.model.aerodynamics.planform.Planform`, a CAERO1's
corners, chords and counts) are splined to the modes by the strips' own rule
(:func:`~propwhirl.model.modal_structure.axis_spline` at each panel's points: the normal
displacement and the streamwise slope from the wing grids' six components), so the
generalised aerodynamic forces are Q(k, M) = −(Z_l Φ)ᵀ diag(A) Q_jj (S_j Φ + i k̄ Z_j Φ) on
the modal coordinates (:mod:`propwhirl.model.aerodynamics.dlm`), fitted by Roger's
rational functions (:mod:`propwhirl.model.aerodynamics.dlm_rfa`: the default analysis's
modal Roger state space, its crossings converged by the p-k) or iterated by the p-k
(``method = "pk"``); the strips stay the model's finite-state twin (what the p-k tracks
and names its modes with).  On a beam model written with all its modes and a grid at every
node the spline is the beam's own interpolation, exact, and the GAFs are the beam's:
docs/modal-structures.md gives the measured differences.

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

import functools
import hashlib
from dataclasses import dataclass, field, replace
from types import MappingProxyType
from typing import Literal

import numpy as np

from propwhirl import limits
from propwhirl import validate as v
from propwhirl.generated import prop_hub
from propwhirl.model.aerodynamics import dlm_rfa, validity
from propwhirl.model.aerodynamics.dlm import DlmTables, check_tables
from propwhirl.model.aerodynamics.dlm_surface import DlmSurface
from propwhirl.model.aerodynamics.planform import Planform
from propwhirl.model.structure.assembly import LAG_STATES, call_blocks
from propwhirl.model.base import EvaluatorBase, StateSpaceModel
from propwhirl.model.fields import spec
from propwhirl.model.flight import FlightCondition
from propwhirl.model.modal_structure import (RIGID_BODY_HZ, ModalStructure, StripPlanform,
                                            axis_spline, check_strip_sweep, id_list,
                                            strip_interpolation)
from propwhirl.model.modal_surface import (ModalSurface, check_surfaces, strip_rows,
                                          strip_system)
from propwhirl.model.modal_surface import grid_ids as _grid_ids
from propwhirl.model.rigid_body import check_rigid_freedoms
from propwhirl.model.propellers.propeller import Propeller
from propwhirl.model.propeller_blocks import (propeller_constants_at, propeller_matrices,
                                             propeller_values)
from propwhirl.model.protocol import REASONS, Capabilities, DofMap, HubDofs, PropellerDofs
from propwhirl.model.statespace import SecondOrder
from propwhirl.model.structure.wing import DLM_MATCHED, check_dlm_mach

#: How a propeller sits on its hub grid (module docstring).
MOUNTS = ("flexible", "rigid", "on-grid")
#: The wing aerodynamics of a modal model (its ``aero``): the strips, or the doublet lattice
#: on its ``dlm_planform`` (module docstring).
AERO = ("strip", "dlm")


@dataclass(frozen=True)
class ModalInstallation:
    """A propeller at hub grid ``grid`` of a :class:`ModalPropellerWing`.

    Parameters
    ----------
    propeller : Propeller
        The propeller.
    grid : int
        Id of its hub grid in the :class:`ModalStructure`.
    mount : {"flexible", "rigid", "on-grid"}
        "flexible" (its own pitch and yaw DOFs and springs), "rigid" (the rigid-mount block on
        the hub grid's heave and twist) or "on-grid" (rigid on the hub grid, its mount and mass
        in the modes: only its aerodynamic and gyroscopic loads added).
    aero : bool
        Its aerodynamic loads on.

    Examples
    --------
    >>> from propwhirl.model import ModalInstallation
    >>> from propwhirl.cases.ch09_baseline import baseline_propeller
    >>> ModalInstallation(baseline_propeller(), grid=7).mount
    'flexible'
    """

    propeller: Propeller = field(metadata=spec(None, "", "the propeller", form="reference"))
    grid: int = field(metadata=spec(None, "", "hub grid id", form="string"))  # not varied
    mount: Literal["flexible", "rigid", "on-grid"] = "flexible"
    aero: bool = True

    def __post_init__(self) -> None:
        if not isinstance(self.propeller, Propeller):
            raise v.InputError(f"propeller = {v.short_repr(self.propeller)} is invalid: must "
                               "be a Propeller")
        if isinstance(self.grid, bool) or not isinstance(self.grid, (int, np.integer)):
            raise v.InputError(f"grid = {v.short_repr(self.grid)} is invalid: must be a grid "
                               "id (an integer)")
        if not (isinstance(self.mount, str) and self.mount in MOUNTS):
            raise v.InputError(f"mount = {v.short_repr(self.mount)} is invalid: must be one of "
                               + ", ".join(map(repr, MOUNTS)))
        v.boolean("aero", self.aero)


def check_hub_grids(structure: ModalStructure, grids, name: str = "propellers") -> None:
    """Each of the hub grids `grids` (one per installation) a grid of the modes, moving in some
    mode, and carrying at most one installation; else an InputError naming ``name[j].grid``
    (``propellers[j]`` of a :class:`ModalPropellerWing`; a modal model file's reader names
    its ``installations[j]``)."""
    s = structure
    seen: dict[int, int] = {}
    for j, g in enumerate(grids):
        hit = np.flatnonzero(s.grid_ids == int(g))
        if not hit.size:
            raise v.InputError(f"{name}[{j}].grid = {g} is not a grid of {s.source}: the modes "
                               f"have no hub grid {g} (grids {id_list(s.grid_ids)})")
        if not np.any(s.shapes[:, int(hit[0]), :]):
            raise v.InputError(f"{s.source}: {name}[{j}].grid = {g} does not move in any mode: "
                               "the modes do not include the hub grid")
        if int(g) in seen:
            raise v.InputError(f"{name}[{j}].grid = {g} is invalid: {name}[{seen[int(g)]}] is "
                               "on it already (at most one per hub grid)")
        seen[int(g)] = j


@dataclass(frozen=True, eq=False)
class ModalPropellerWing(StateSpaceModel):
    """A wing given by its normal modes, with strip aerodynamics and propellers at hub grids
    (the module docstring).  Implements the :class:`~propwhirl.model.protocol.Model` contract.

    Parameters
    ----------
    structure : ModalStructure
        The modes: frequencies [Hz], modal masses [kg], damping ratios, shapes at grids.
    wing_grids : tuple of int
        Ids of its reference-axis grids, root to tip (the strips' spline).
    planform : StripPlanform
        The aerodynamic strips.
    flight : FlightCondition
        Density [kg/m³], speed of sound [m/s] and the airspeed range [m/s].
    propellers : tuple of ModalInstallation
        The propellers, at most one per hub grid.
    wing_aero, propeller_aero, rotating : bool
        Switches as :class:`~propwhirl.model.systems.PropellerWing`'s: wing aerodynamics,
        propeller aerodynamics, propellers spinning.  The strips (``aero = "strip"``) are an
        unswept wing's: a reference axis (the wing grids' line) swept by more than
        :data:`~propwhirl.model.modal_structure.STRIP_SWEEP_LIMIT_DEG` is refused with them
        (:func:`~propwhirl.model.modal_structure.check_strip_sweep`), not without them nor
        with the doublet lattice (``aero = "dlm"``), which takes a swept planform (nor when a
        ``dlm_planform`` is given: the doublet lattice's strip twin, which its p-k tracks
        with, is such a model).
    name : str
        Label.
    aero : {"strip", "dlm"}
        The wing aerodynamics: the strips, or the doublet lattice on ``dlm_planform``
        (module docstring; the strips then the finite-state twin the p-k tracks with).
    dlm_planform : Planform or None
        The lifting surface (:class:`~propwhirl.model.aerodynamics.planform.Planform`, in
        the modes' frame [m]); needed with ``aero = "dlm"``, within the wing grids' span.
    dlm_mach : float or "speed"
        The Mach number of the doublet-lattice loads, as a beam wing's ``dlm_mach``:
        "speed" (V/a at each analysed speed) or one number in [0, 0.9].
    surfaces : tuple of ModalSurface
        Lifting surfaces besides the wing (a tail:
        :class:`~propwhirl.model.modal_surface.ModalSurface`, strips on its own grids), their
        strips' loads switched with ``wing_aero``; with the strips only (``aero = "strip"``).
        A free structure's rigid pitch needs one (:mod:`propwhirl.model.rigid_body`: the wing
        alone admits plunge and roll).

    Examples
    --------
    The baseline wing's four lowest modes (6 elements) with the baseline propeller at the tip
    grid: its divergence where the beam model's is (143 m/s).

    >>> from propwhirl.model import (ModalInstallation, ModalPropellerWing, ModalStructure,
    ...                              StripPlanform)
    >>> from propwhirl.cases.ch09_baseline import baseline_flight, baseline_propeller, baseline_wing
    >>> wing = baseline_wing(n_elements=6)
    >>> s = ModalStructure.from_wing(wing, n_modes=4)
    >>> m = ModalPropellerWing(s, tuple(int(g) for g in s.grid_ids), StripPlanform.from_wing(wing),
    ...                        baseline_flight(), (ModalInstallation(baseline_propeller(), grid=7),))
    >>> m.dof_map().q_labels
    ('mode 1', 'mode 2', 'mode 3', 'mode 4', 'propeller 1 theta', 'propeller 1 psi')
    >>> from propwhirl.analysis import analyse
    >>> c = analyse(m, speeds=[50.0, 100.0, 150.0, 200.0]).critical
    >>> c.kind, round(c.V)
    ('divergence', 143)
    """

    # what parameter paths reach (studies/paths.py): the modes' frequencies, masses and
    # damping (structure.frequencies_hz[i], ...), the flight condition and the propellers
    structure: ModalStructure = field(metadata=spec(None, "", "the modes", form="table"))
    wing_grids: tuple[int, ...]
    planform: StripPlanform
    flight: FlightCondition = field(metadata=spec(None, "", "the flight condition",
                                                  form="table"))
    propellers: tuple[ModalInstallation, ...] = field(default=(), metadata=spec(
        None, "", "the propellers at hub grids", form="tables"))
    wing_aero: bool = True
    propeller_aero: bool = True
    rotating: bool = True
    name: str = "modal propeller-wing"
    aero: Literal["strip", "dlm"] = "strip"
    dlm_planform: Planform | None = None
    dlm_mach: float | Literal["speed"] = DLM_MATCHED
    surfaces: tuple[ModalSurface, ...] = ()

    def __post_init__(self) -> None:
        for k in ("wing_aero", "propeller_aero", "rotating"):
            v.boolean(k, getattr(self, k))
        if not isinstance(self.flight, FlightCondition):
            raise v.InputError(f"flight = {v.short_repr(self.flight)} is invalid: must be a "
                               "FlightCondition")
        if not isinstance(self.structure, ModalStructure):
            raise v.InputError(f"structure = {v.short_repr(self.structure)} is invalid: must be "
                               "a ModalStructure (the modes: load_modes or read_op2)")
        if not isinstance(self.planform, StripPlanform):
            raise v.InputError(f"planform = {v.short_repr(self.planform)} is invalid: must be "
                               "a StripPlanform (the aerodynamic strips)")
        object.__setattr__(self, "wing_grids", _grid_ids("wing_grids", self.wing_grids))
        props = self.propellers
        if isinstance(props, (str, bytes)) or not isinstance(props, (tuple, list)) \
                or not all(isinstance(p, ModalInstallation) for p in props):
            raise v.InputError(f"propellers = {v.short_repr(props)} is invalid: must be a "
                               "sequence of ModalInstallation (one per propeller)")
        object.__setattr__(self, "propellers", tuple(props))
        limits.check_propellers(len(self.propellers))
        s = self.structure
        check_hub_grids(s, [inst.grid for inst in self.propellers])
        strip_interpolation(s, self.wing_grids, self.planform)   # checks the grids now
        self._check_dlm()
        object.__setattr__(self, "surfaces", check_surfaces(s, self.surfaces, self.wing_aero))
        if self.surfaces and self.aero == "dlm":
            raise v.InputError("surfaces is invalid with aero = 'dlm': the doublet lattice "
                               "takes the wing's dlm_planform alone; a tail's strips go with "
                               "aero = 'strip'")
        check_rigid_freedoms(s, len(self.surfaces))
        # the strips are an unswept wing's: refused on a swept axis as the model's own wing
        # aerodynamics; a model with a dlm_planform is (or is the strip twin of, which the
        # doublet lattice's p-k tracks with) a doublet-lattice model
        if self.wing_aero and self.aero == "strip" and self.dlm_planform is None:
            check_strip_sweep(s, self.wing_grids)

    def _check_dlm(self) -> None:
        """The doublet-lattice fields: ``aero`` one of :data:`AERO`, ``dlm_planform`` a
        Planform (needed with "dlm") whose span lies within the wing grids', ``dlm_mach``."""
        if not (isinstance(self.aero, str) and self.aero in AERO):
            raise v.InputError(f"aero = {v.short_repr(self.aero)} is invalid: must be one of "
                               + ", ".join(map(repr, AERO)))
        check_dlm_mach(self.dlm_mach)
        if self.aero == "dlm" and self.wing_aero \
                and np.any(self.structure.frequencies_hz < RIGID_BODY_HZ):
            raise v.InputError(
                "aero = 'dlm' is invalid with rigid-body modes kept (a free structure's plunge "
                "or roll, frequencies_hz < 0.001 Hz): the doublet lattice's crossings are "
                "converged by the p-k method, which follows the oscillatory modes only; use "
                "aero = 'strip' on the free structure, or leave the rigid-body modes out")
        p = self.dlm_planform
        if p is None:
            if self.aero == "dlm":
                raise v.InputError("dlm_planform = None is invalid with aero = 'dlm': the "
                                   "doublet lattice needs its panels' planform (a Planform: "
                                   "leading-edge corners, chords, panel counts)")
            return
        if not isinstance(p, Planform):
            raise v.InputError(f"dlm_planform = {v.short_repr(p)} is invalid: must be a "
                               "Planform (propwhirl.model.aerodynamics.planform) or None")
        s = self.structure
        yg = s.xyz[[s.index(g) for g in self.wing_grids], 1]
        tol = 1e-9 * max(1.0, float(yg[-1] - yg[0]))
        bad = np.flatnonzero((p.y < yg[0] - tol) | (p.y > yg[-1] + tol))
        if bad.size:
            i = int(bad[0])
            raise v.InputError(f"{p.source}: leading_edge[{i}] y = {p.y[i]:.6g} m is outside "
                               f"the wing grids' span [{yg[0]:.6g}, {yg[-1]:.6g}] m: its "
                               "panels cannot be splined to the modes (give stations within "
                               "the wing_grids' span)")

    def dlm_surface(self) -> DlmSurface:
        """The doublet lattice's view of this model
        (:class:`~propwhirl.model.aerodynamics.dlm_surface.DlmSurface`): its ``dlm_planform``,
        the spline to its modal coordinates
        (:func:`~propwhirl.model.modal_structure.axis_spline` composed with the modes), every
        mode loaded, b_ref the planform's root semichord, its ``dlm_mach``; built once per
        model."""
        return self._dlm_surface

    def __getstate__(self) -> dict:
        """Pickled (a study's worker processes) without the doublet-lattice surface built
        on first use: the receiving process builds its own."""
        state = dict(self.__dict__)
        state.pop("_dlm_surface", None)
        return state

    @functools.cached_property
    def _dlm_surface(self) -> DlmSurface:
        p = self.dlm_planform
        if p is None:
            raise v.InputError(f"model {self.name!r} has no dlm_planform: the doublet lattice "
                               "needs one (aero = 'dlm')")
        s, grids = self.structure, self.wing_grids
        Phi = s.shapes                                          # (n_modes, n_grids, 6)

        def outside(i: int, lo: float, hi: float) -> str:
            return (f"{p.source}: a panel point is outside the wing grids' span "
                    f"[{lo:.6g}, {hi:.6g}] m")

        def spline(points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
            Z, S = axis_spline(s, grids, points[:, 0], points[:, 1], outside)
            return (np.einsum("pgc,mgc->pm", Z, Phi), np.einsum("pgc,mgc->pm", S, Phi))

        digest = hashlib.sha256()
        for a in (Phi, s.xyz, np.asarray(grids, dtype=np.int64)):
            digest.update(np.ascontiguousarray(a).tobytes())
        n = s.n_modes
        return DlmSurface(p, spline, n, np.arange(n), p.b_ref, self.dlm_mach,
                          ("modes", p.key(), digest.hexdigest()),
                          tuple(f"mode {k + 1}" for k in range(n)))

    def capabilities(self) -> Capabilities:
        """What this model can do (:class:`~propwhirl.model.protocol.Capabilities`): its
        structure the modes, strip aerodynamics on its strips or doublet-lattice panels on
        its planform, sensitivities by central differences (of the state matrix; of the p-k
        root on panels), every command but the reduced method (it is reduced already), a NASTRAN
        deck and a file upgrade; a Campbell diagram needs a propeller that whirls (own mount
        or hub grid)."""
        dlm = self.wing_aero and self.aero == "dlm"
        why = {"reduced": REASONS["modal-reduced"], "exact-sensitivity": REASONS["modal-exact"],
               "export": REASONS["modal-export"], "upgrade-model": REASONS["modal-upgrade"]}
        if dlm:     # "reduced": the modal Roger state space (its modes below a cut-off)
            del why["reduced"]
        if not self.wing_aero:
            why["pk"] = REASONS["no-wing-aero-pk"]
        elif np.any(self.structure.frequencies_hz < RIGID_BODY_HZ):    # rigid-body modes kept
            why["pk"] = REASONS["free-pk"]
        if not self.dof_map().whirling():
            why["campbell"] = REASONS["no-whirl"]
        mounts = {inst.mount for inst in self.propellers} - {"rigid"}
        props = ("both" if mounts == {"flexible", "on-grid"} else "own mounts"
                 if mounts == {"flexible"} else "hub grids" if mounts else "none")
        return Capabilities("modal propeller-wing", "modes",
                            "doublet lattice" if dlm else "strip" if self.wing_aero else "none",
                            "central difference", props, tuple(why.items()), "modal")

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

    def assembly(self, dlm_tables: DlmTables | None = None) -> "ModalAssembly":
        """The speed-independent parts (a new :class:`ModalAssembly` each call);
        ``dlm_tables``: with ``aero = "dlm"`` the doublet-lattice tables its evaluations read
        and fill (the analysis's; None: new ones)."""
        return ModalAssembly.build(self, dlm_tables)

    def second_order(self, V, omega=None) -> SecondOrder:
        """The second-order system at airspeeds V [m/s] (:meth:`ModalAssembly.second_order`)."""
        return self.assembly().second_order(V, omega)

    def state_matrix(self, V, **options) -> np.ndarray:
        """A(V) (:meth:`ModalAssembly.state_matrix` of a new :meth:`assembly`)."""
        return self.assembly().state_matrix(V, **options)

    def dof_map(self) -> DofMap:
        """The states: η of every mode ("mode k", kind "eta"), then θ, ψ of each flexibly
        mounted propeller, then the lag states of every strip ("strip s w1", ...), then
        those of each further surface's ("tail strip s w1", ...)."""
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
        if self.wing_aero and self.aero == "dlm":       # the Roger lag states ("mode i lag l")
            w_labels = dlm_rfa.lag_labels(self)[0]
        elif self.wing_aero:
            k = LAG_STATES[self.planform.aero_model]
            w_labels = tuple(f"strip {s + 1} w{r + 1}" for s in range(self.planform.y.size)
                             for r in range(k))
            w_labels += tuple(x for surf in self.surfaces for x in surf.lag_labels())
        return DofMap(tuple(labels), tuple(kinds), tuple(node), tuple(prop), w_labels,
                      (-1,) * len(w_labels), tuple(props), hubs=self._hubs(len(labels)))

    def _hubs(self, n_dof: int) -> tuple[HubDofs, ...]:
        """The on-grid propellers' pitch and yaw as rows over q (:class:`HubDofs`): the hub
        grid's rotations θ_H = R_y, ψ_H = −R_z less the wing's at the hub's spanwise station
        (the wing grids' R_y, R_z interpolated linearly in y, held beyond the ends) — the
        propeller's rotation on its mount, a flexible mount's θ and ψ (θ_H = θ + α_P,
        ψ_H = ψ + χ_P: derivations/prop_hub.py); J the propeller's pivot inertias."""
        s, out = self.structure, []
        wing = np.array([s.index(g) for g in self.wing_grids])
        yw = s.xyz[wing, 1]
        order = np.argsort(yw, kind="stable")
        for j, inst in enumerate(self.propellers):
            if inst.mount != "on-grid":
                continue
            g = s.index(inst.grid)
            y = float(s.xyz[g, 1])
            # linear-interpolation weights of the wing grids at y (one per grid)
            weights = np.array([np.interp(y, yw[order], e[order]) for e in np.eye(wing.size)])
            under = np.einsum("w,mwc->mc", weights, s.shapes[:, wing, :])
            rel = s.shapes[:, g, :] - under
            pitch, yaw, heave, twist = (np.zeros(n_dof) for _ in range(4))
            pitch[: s.n_modes], yaw[: s.n_modes] = rel[:, 4], -rel[:, 5]
            heave[: s.n_modes], twist[: s.n_modes] = -under[:, 2], under[:, 4]
            B = _mount_mass(inst.propeller, float(np.dot(weights, s.xyz[wing, 0]))
                            - self.planform.mid_chord_x(y), self.flight.density)
            out.append(HubDofs(j, tuple(pitch.tolist()), tuple(yaw.tolist()),
                               (float(B[0, 0]), float(B[1, 1])),
                               inst.propeller.rotation, self.rotating, y,
                               tuple(heave.tolist()), tuple(twist.tolist()),
                               tuple(tuple(float(c) for c in r) for r in B[:2, 2:])))
        return tuple(out)


@dataclass(frozen=True, eq=False)
class ModalAssembly(EvaluatorBase):
    """A :class:`ModalPropellerWing` with its speed-independent parts, built once.

    structure:  the generalised (n_q, n_q) M, C, K (modes and propeller DOFs), read-only;
    strips:     (n_strips, 2, n_q): each strip's [h, α] from q (T Φ);
    surfaces:   the same, one array per further lifting surface (``model.surfaces``);
    hubs:       per installation (its local DOFs, 2 or 4, n_q): [θ, ψ,] h_P, α_P from q;
    constants:  per installation its generated blocks' speed-independent arguments;
    states:     the :class:`~propwhirl.model.protocol.DofMap`;
    dlm_tables, dlm_fit_ks: with ``aero = "dlm"`` as a
                :class:`~propwhirl.model.systems.PropellerWingAssembly`'s (the analysis's
                doublet-lattice tables; the Roger fits' reduced frequencies, None: the full
                state space's).
    """

    model: ModalPropellerWing
    structure: tuple[np.ndarray, np.ndarray, np.ndarray]
    strips: np.ndarray
    hubs: tuple[np.ndarray, ...]
    constants: tuple
    states: DofMap
    dlm_tables: DlmTables | None = None
    dlm_fit_ks: tuple[float, ...] | None = None
    surfaces: tuple[np.ndarray, ...] = ()

    @classmethod
    def build(cls, model: ModalPropellerWing,
              dlm_tables: DlmTables | None = None) -> "ModalAssembly":
        s = model.structure
        nm = s.n_modes
        flex = model.flexible
        n = nm + 2 * len(flex)
        mats = tuple(np.zeros((n, n)) for _ in range(3))
        for X, Xm in zip(mats, s.generalised()):
            X[:nm, :nm] = Xm
        Phi = s.shapes.transpose(1, 2, 0)                      # (n_grids, 6, n_modes)
        strips = strip_rows(s, model.wing_grids, model.planform, n)
        tails = tuple(strip_rows(s, surf.grids, surf.planform, n, f"surfaces[{j}].grids")
                      for j, surf in enumerate(model.surfaces))
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
        for X in mats:
            X.flags.writeable = False
        tables = check_tables(dlm_tables) if model.aero == "dlm" else None
        return cls(model, mats, strips, tuple(hubs), tuple(consts), model.dof_map(), tables,
                   surfaces=tails)

    def lifting_surfaces(self) -> tuple[tuple[StripPlanform, np.ndarray], ...]:
        """(planform, strip rows) of the wing, then of each further surface."""
        return ((self.model.planform, self.strips),
                *zip((surf.planform for surf in self.model.surfaces), self.surfaces))

    def dof_map(self) -> DofMap:
        return self.states

    def without_aerodynamics(self) -> "ModalAssembly":
        """The assembly of ``model.without_aerodynamics()`` (same parts)."""
        return self.with_switches(wing_aero=False, propeller_aero=False)

    def with_switches(self, **switches) -> "ModalAssembly":
        """The assembly of the model with switches changed (``wing_aero``,
        ``propeller_aero``, ``rotating``, ``name``): the same parts, a new model and DOF
        map."""
        bad = sorted(set(switches) - {"wing_aero", "propeller_aero", "rotating", "name"})
        if bad:
            raise v.InputError(f"with_switches: {bad} are not switches (wing_aero, "
                               "propeller_aero, rotating, name)")
        model = self.model.with_(**switches)
        return replace(self, model=model, states=model.dof_map())

    def blocks(self, V: np.ndarray, omega=None) -> "_Dense":
        """The system at the airspeeds V [m/s] (1-D, not checked) as
        :meth:`~propwhirl.model.systems.PropellerWingAssembly.blocks` gives a beam's, for
        what reads ``blocks(V).dense()`` (the doublet-lattice Roger state space's dry part):
        a modal model's matrices are dense already.  Not with the wing's doublet lattice on
        (its Roger state space: :meth:`second_order`)."""
        if self.model.wing_aero and self.model.aero == "dlm":
            raise v.InputError(f"model {self.model.name!r}: aero = 'dlm' has no block form; "
                               "its Roger state space is second_order's")
        with np.errstate(all="ignore"):
            return _Dense(self._assemble(np.atleast_1d(np.asarray(V, float)), omega))

    def second_order(self, V, omega=None) -> SecondOrder:
        """S1 q̈ + S2 q̇ + S3 q = S4 w, ẇ = Ww w + Wv q̇ + Wq q at airspeeds V [m/s] (array).
        `omega` [rad/s] overrides every propeller's rotational speed.  The checks of
        :meth:`PropellerWingAssembly.second_order`."""
        model = self.model
        V = np.atleast_1d(v.positive("airspeed V", V, "m/s"))
        if validity.has_aerodynamics(model):
            validity.check_mach(V, model.flight.speed_of_sound)
        with np.errstate(all="ignore"):
            if model.wing_aero and model.aero == "dlm":    # the doublet lattice's Roger fit
                sys = dlm_rfa.second_order(self, V, omega)
            else:
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
        S4, Ww, Wv, Wq = strip_system(S, self.lifting_surfaces(), model.flight.density, V)
        return SecondOrder(*S, S4, Ww, Wv, Wq, self.states.q_labels, self.states.w_labels)


@dataclass(frozen=True)
class _Dense:
    """A modal system where a beam's local blocks are asked for: ``dense()`` is it."""

    system: SecondOrder

    def dense(self) -> SecondOrder:
        return self.system


def _mount_mass(propeller: Propeller, ea: float, density: float) -> np.ndarray:
    """The 4×4 mass block [kg, kg m, kg m²] over [θ, ψ, h_P, α_P] the propeller would have on
    a flexible mount at a wing point ``ea`` [m] aft of the mid-chord (the generated
    :func:`~propwhirl.model.propeller_blocks.propeller_matrices`): its pivot inertias and the
    coupling of its pitch and yaw with the point's heave and twist (for the participation of
    an on-grid propeller, :class:`~propwhirl.model.protocol.HubDofs`)."""
    c = propeller_constants_at(propeller, ea, density)
    vals = propeller_values(c, propeller, np.array([1.0]), None, rotating=False, aero=False,
                            speed_of_sound=1.0)
    return np.asarray(propeller_matrices(vals, mount="flexible", in_plane=False,
                                         aero=False)[0][0], dtype=float)


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
