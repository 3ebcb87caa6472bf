"""Aeroelastic models: wing with propellers (chapter 8, appendices C–D), isolated propeller
(chapter 6), and the state space they produce for the stability engine.

:class:`PropellerWing` assembles, for an array of airspeeds, the second-order system of
appendix D (D.18–D.29) with any number of propellers at any nodes:

    [M_s,g + G*_s,g − M_a,g − P*_2,g   F*_s,g − P*_1,g] [q̈_W]   (and likewise C, K)   = [W_0,g] w
    [(B_s,g − B_a,g)*                (A_s − A_a)*    ] [q̈_P]                          [  0  ]

Each propeller contributes a 4×4 block on its local coordinates [θ_j, ψ_j, h_P, α_P]:

    M_loc = [[A_s − A_a, B_s − B_a], [F_s − P_1, G_s − P_2]]
    C_loc = [[C_s − C_a, D_s − D_a], [H_s − P_3,    − P_4 ]]
    K_loc = [[E_s − E_a,     − F_a], [   − P_5,     − P_6 ]]

(all from `propwhirl.generated.prop_flexwing`), added at the propeller's node.  The clamped root
degrees of freedom and the root node's lag states are removed (7.59, D.27).  Switches: wing
aerodynamics, propeller aerodynamics, rotation, and per propeller flexible or rigid mounts (a
rigid mount keeps only the inert mass block G_s, §9.3.1).

In-plane bending (beyond the thesis): with ``wing.EI_chordwise`` given, every node also has its
in-plane displacement and slope [v_i, χ_i] (after all bending–torsion DOFs, before the
propellers' θ, ψ), the wing's in-plane element matrices (derivations/beam_inplane.py) join the
structure, and each propeller's block is 6×6 on [θ_j, ψ_j, h_P, α_P, v_P, χ_P]
(derivations/prop_flexwing_inplane.py: the nacelle yaws with χ_P; side force, yaw moment and
gyroscopic moment load the node in its plane).  A rigid mount then keeps G_s and the rotor's
gyroscopic coupling J_s of the node's twist and in-plane slope.
"""
from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import Literal

import numpy as np

from propwhirl import limits
from propwhirl import validate as v
from propwhirl.model.fields import check_fields, spec
from propwhirl.model.mesh import check_station
from propwhirl.model.assembly import (
    INPLANE_DOF_NAMES,
    LAG_STATES,
    WING_DOF_NAMES,
    call_blocks,
    free_dofs,
    inplane_dof_labels,
    inplane_structure,
    wing_aero_blocks,
    wing_dof_labels,
    wing_structure,
)
from propwhirl.generated import beam_element, beam_inplane, prop_rigid
from propwhirl.model.flight import SPEED_OF_SOUND_8000FT, FlightCondition  # noqa: F401 (re-export)
from propwhirl.model.propeller import Propeller
from propwhirl.model.propeller_blocks import (propeller_constants, propeller_matrices,
                                             propeller_values)
from propwhirl.model.blocks import BlockSystem, LagBlocks, LocalBlocks, RecentBlocks
from propwhirl.model.protocol import DofMap, PropellerDofs
from propwhirl.model import validity
from propwhirl.model.base import StateSpaceModel
from propwhirl.model.section import TypicalSection  # noqa: F401 (re-export: its former home)
from propwhirl.model.statespace import SecondOrder
from propwhirl.model.wing import Wing

#: Units of the arguments of the generated propeller blocks, for the error messages.
PROPELLER_UNITS = dict(
    M_P="kg", S_theta_P="kg m", I_theta_P="kg m^2", I_psi_P="kg m^2", S_alpha_P="kg m",
    I_alpha_P="kg m^2", I_theta_alpha_P="kg m^2", I_Omega="kg m^2", I_X="kg m^2",
    I_Y="kg m^2", I_Z="kg m^2", Omega="rad/s", K_theta="N m/rad", K_psi="N m/rad",
    rho="kg/m^3", V="m/s", R="m", e_theta="m", e_psi="m", e_alpha="m", S_psi_P="kg m",
    I_chi_P="kg m^2", I_psi_chi_P="kg m^2", l_psi="m", a_P_b_P="m")
#: Units of the wing element properties (:meth:`Wing.element_properties`) and Rayleigh terms.
ELEMENT_UNITS = dict(length="m", m="kg/m", rho_Ip="kg m", x_alpha_b="m", EI="N m^2",
                     GJ="N m^2", rayleigh_mu="1/s", rayleigh_lambda="s", rho_Iz="kg m",
                     EI_chordwise="N m^2")


@dataclass(frozen=True)
class Installation:
    """A propeller attached to the wing at spanwise position y [m], anywhere in (0, semi_span].

    :class:`PropellerWing` makes y a node of the mesh (it adds y to the wing's stations).

    `aero=False` switches this propeller's aerodynamic loads off (e.g. folded blades, as the
    X-57's inboard high-lift propellers in cruise); the model-wide `propeller_aero` switch
    acts on all propellers.
    """

    propeller: Propeller = field(metadata=spec(
        "propeller", "", "key of a [propellers.KEY] table", form="reference"))
    y: float = field(metadata=spec("y_m", "m", "spanwise position, in (0, semi_span] (made a node of the mesh)",
                                   range=(0.0, 1e3)))
    mount: Literal["flexible", "rigid"] = field(default="flexible", metadata=spec(
        "mount", "", "flexible (pitch and yaw DOFs) or rigid", default="setting"))
    aero: bool = field(default=True, metadata=spec(
        "aero", "", "this propeller's aerodynamic loads", default="setting"))

    def __post_init__(self) -> None:
        check_fields(self)  # a Propeller, y in range, mount one of the two, aero a bool


def node_at(wing: Wing, y: float, tol: float = 1e-6, name: str = "propeller position y",
            path: tuple = ("y",)) -> int:
    """Index of the node at spanwise position y; an error names the nearest nodes otherwise.

    Propellers sit on a node (§8.3.3); :class:`PropellerWing` makes its wing's mesh hold them.
    Errors name the position `name` and carry `path` (see :class:`propwhirl.validate.InputError`).
    """
    ys = wing.node_y
    if y < -tol or y > wing.semi_span + tol:
        raise v.fail(name, y, f"outside the wing: must be in [0, {wing.semi_span}] m", "m", path)
    i = int(np.argmin(np.abs(ys - y)))
    if abs(ys[i] - y) > tol * max(1.0, wing.semi_span):
        lo = int(np.searchsorted(ys, y)) - 1
        raise v.fail(
            name, y, f"not a node of the {wing.element_count}-element mesh: nearest nodes are "
            f"{lo} (y = {ys[lo]:.6g} m) and {lo + 1} (y = {ys[lo + 1]:.6g} m); add the "
            "position to the wing's stations", "m", path)
    if i == 0:
        raise v.fail(name, y, "the clamped root: must be > 0", "m", path)
    return i


@dataclass(frozen=True)
class PropellerWing(StateSpaceModel):
    """A cantilever wing with flexibly (or rigidly) mounted propellers (chapter 8, appendix D).

    With no propellers it is the wing model of chapter 7.  ``model.wing`` is the given wing, or,
    when a propeller is off its nodes, that wing with every installation's y added to its
    stations (so the mesh holds every propeller; rule in :mod:`propwhirl.model.mesh`).
    """

    wing: Wing = field(metadata=spec("wing", "", "the wing"))
    flight: FlightCondition = field(metadata=spec("flight", "", "the flight condition"))
    propellers: tuple[Installation, ...] = field(default=(), metadata=spec(
        "installations", "", "the installed propellers", default="none", form="installations"))
    wing_aero: bool = field(default=True, metadata=spec(
        "wing_aero", "", "strip aerodynamics of the wing", default="setting", section="switches"))
    propeller_aero: bool = field(default=True, metadata=spec(
        "propeller_aero", "", "propeller aerodynamic derivatives", default="setting",
        section="switches"))
    rotating: bool = field(default=True, metadata=spec(
        "rotating", "", "propellers spinning (gyroscopic terms)", default="setting",
        section="switches"))
    name: str = field(default="propeller-wing", metadata=spec(
        "name", "", "label", default="setting"))
    _nodes: tuple[int, ...] = field(default=(), repr=False, compare=False, metadata=spec(
        None, "", "node of each propeller (derived)", default="none", form="derived"))
    #: what is made once per model (shared with variants, :meth:`_shared`): the wing structure,
    #: the propeller constants, labels, DOF map, the quiet variant; the recent evaluations
    _memo: dict = field(init=False, default_factory=dict, repr=False, compare=False,
                        metadata=spec(None, "", "speed-independent matrices (derived)",
                                      default="none", form="derived"))

    def __post_init__(self) -> None:
        check_fields(self)  # a Wing, a FlightCondition, Installations, bool switches
        limits.check_propellers(len(self.propellers))
        object.__setattr__(self, "wing", self._meshed_wing())
        nodes = tuple(node_at(self.wing, inst.y, name=f"propellers[{j}].y",
                              path=("propellers", j, "y"))
                      for j, inst in enumerate(self.propellers))
        if len(set(nodes)) != len(nodes):
            dup = next(n for n in nodes if nodes.count(n) > 1)
            j = [k for k, n in enumerate(nodes) if n == dup][1]
            raise v.fail(
                f"propellers[{j}].y", self.propellers[j].y, f"invalid: two propellers at "
                f"node {dup} (y = {self.wing.node_y[dup]:.6g} m): at most one per node", "m",
                ("propellers", j, "y"))
        object.__setattr__(self, "_nodes", nodes)

    def _meshed_wing(self) -> Wing:
        """The wing whose mesh holds every installation: the wing as given when each propeller
        sits on one of its nodes (the thesis's uniform meshes, unchanged), else the wing with
        every installation's y added to its stations (:meth:`Wing.with_stations`), so that a
        propeller at any y in (0, semi_span] needs no choice of `n_elements`.  A position
        outside the wing, at the root, or too close to a station is an error naming it."""
        wing, ys = self.wing, [inst.y for inst in self.propellers]
        names = [f"propellers[{j}].y" for j in range(len(ys))]
        paths = [("propellers", j, "y") for j in range(len(ys))]
        for y, name, path in zip(ys, names, paths):
            check_station(name, y, wing.semi_span, path)
        if all(wing.mesh.has_node(y) for y in ys):
            return wing
        return wing.with_stations(ys, names, paths)

    def with_(self, **changes) -> "PropellerWing":
        """A copy with fields replaced (switches, flight condition, ...); it shares the
        speed-independent matrices that the change leaves as they are (:meth:`_shared`)."""
        return self._shared(replace(self, **changes))

    def _shared(self, other: "PropellerWing") -> "PropellerWing":
        """``other`` (a copy of this model with fields replaced) sharing this model's memos of
        what the change leaves as it is: the wing's (its structure) if it has the same wing,
        the installations' (the propeller constants) if it also has the same propellers and
        flight condition (same objects).  Shared, not copied: whichever of them computes an
        entry first computes it for both."""
        if other.wing is self.wing:
            other._memo["wing"] = self._memo.setdefault("wing", {})
            if other.propellers is self.propellers and other.flight is self.flight:
                other._memo["installations"] = self._memo.setdefault("installations", {})
        return other

    # ------------------------------------------------------------------ layout
    @property
    def nodes(self) -> tuple[int, ...]:
        return self._nodes

    @property
    def flexible(self) -> list[int]:
        """Indices (into `propellers`) of flexibly mounted propellers (those with θ, ψ DOFs)."""
        return [j for j, inst in enumerate(self.propellers) if inst.mount == "flexible"]

    def q_labels(self) -> tuple[str, ...]:
        """Labels of the DOFs q: the wing's ("node i h", ...), then "propeller k theta",
        "propeller k psi" of each flexibly mounted propeller, numbered from 1 for people
        (k = index in `propellers` + 1; :class:`PropellerDofs.number` keeps the index).
        Made once per model."""
        if "q labels" not in self._memo:
            self._memo["q labels"] = self._new_q_labels()
        return self._memo["q labels"]

    def _new_q_labels(self) -> tuple[str, ...]:
        wing = wing_dof_labels(self.wing.n_nodes)
        if self.wing.in_plane:
            wing = wing + inplane_dof_labels(self.wing.n_nodes)
        prop = tuple(f"propeller {j + 1} {d}" for j in self.flexible for d in ("theta", "psi"))
        return wing + prop

    # ------------------------------------------------------------------ propeller blocks
    def _propeller_blocks(self, j: int, V: np.ndarray, omega: np.ndarray | None = None,
                          derivatives: dict | None = None):
        """Local (M, C, K) over [θ, ψ, h_P, α_P] (flexible) or [h_P, α_P] (rigid), (nV, k, k).

        `omega` [rad/s] (shape of V) overrides the propeller's own rotational speed;
        `derivatives`: a memo {propeller: its aerodynamic derivatives at V}, shared by the
        installations of one propeller design in one assembly."""
        return self._propeller_matrices(j, self._propeller_values(j, V, omega, derivatives))

    def _propeller_values(self, j: int, V: np.ndarray, omega: np.ndarray | None = None,
                          derivatives: dict | None = None) -> dict:
        """:func:`propwhirl.model.propeller_blocks.propeller_values` of propeller j."""
        return propeller_values(self, j, V, omega, derivatives)

    def _propeller_constants(self, j: int) -> dict:
        """:func:`propwhirl.model.propeller_blocks.propeller_constants` of propeller j."""
        return propeller_constants(self, j)

    def _propeller_matrices(self, j: int, values: dict):
        """(M, C, K) of propeller j (:func:`propwhirl.model.propeller_blocks.propeller_matrices`)."""
        return propeller_matrices(self, j, values)

    def _propeller_dofs(self, j: int) -> tuple[str, ...]:
        """Global DOF labels of propeller j's local block ([θ, ψ,] h, α [, v, χ] at its node)."""
        node = self.nodes[j]
        wing = (f"node {node} h", f"node {node} alpha")
        if self.wing.in_plane:
            wing = wing + (f"node {node} v", f"node {node} chi")
        if self.propellers[j].mount == "rigid":
            return wing
        return (f"propeller {j + 1} theta", f"propeller {j + 1} psi") + wing

    def _contributions(self, V: np.ndarray, omega):
        out = []
        for j in range(len(self.propellers)):
            out.append((f"propeller {j + 1}", self._propeller_dofs(j),
                        lambda vals, j=j: self._propeller_matrices(j, vals),
                        self._propeller_values(j, V, omega), PROPELLER_UNITS))
        out += self._element_contributions(
            self.wing.element_properties(), (beam_element, "blocks", "mass", "stiffness"),
            WING_DOF_NAMES, "")
        pi = self.wing.inplane_properties()
        if pi is not None:
            out += self._element_contributions(
                pi, (beam_inplane, "inplane_blocks", "inplane_mass", "inplane_stiffness"),
                INPLANE_DOF_NAMES, " (in-plane)")
        return out

    def _element_contributions(self, props: dict, generated: tuple, dof_names, suffix: str):
        """One contribution per wing element: its (mass, Rayleigh damping, stiffness) from the
        generated block function ``generated`` = (module, function, mass, stiffness names)."""
        module, fn, mass, stiffness = generated
        mu, lam = self.wing.rayleigh

        def element(vals):
            b = call_blocks(module, fn, (1,), **{k: vals[k] for k in props})
            Mb, Kb = b[mass], b[stiffness]
            return Mb, vals["rayleigh_mu"] * Mb + vals["rayleigh_lambda"] * Kb, Kb

        out = []
        for e in range(self.wing.element_count):
            vals = {k: x[e:e + 1] for k, x in props.items()}
            vals.update(rayleigh_mu=mu, rayleigh_lambda=lam)
            dofs = tuple(f"node {i} {d}" for i in (e, e + 1) for d in dof_names)
            out.append((f"wing element {e}{suffix}", dofs, element, vals, ELEMENT_UNITS))
        return out

    # ------------------------------------------------------------------ system
    def second_order(self, V, omega=None) -> SecondOrder:
        """The reduced second-order system (root removed) at airspeeds V [m/s] (array).

        `omega` [rad/s], broadcast to V, overrides every propeller's rotational speed (used for
        Campbell diagrams and rotational-speed studies).  Refuses what the aerodynamics cannot
        represent (:mod:`propwhirl.model.validity`); a non-finite entry is an InputError naming
        the model parameter behind it."""
        V = np.atleast_1d(v.positive("airspeed V", V, "m/s"))
        if validity.has_aerodynamics(self):
            validity.check_mach(V, self.flight.speed_of_sound)
        if self.wing_aero:
            validity.check_lift_slope(self.wing.node_properties()["Cla"][1:], "lift_slope",
                                      "wing_aero = false")
        with np.errstate(all="ignore"):
            sys = self._assemble(V, omega)
        return self._checked(sys, V, {"omega": omega})

    def _assemble(self, V: np.ndarray, omega) -> SecondOrder:
        return self._blocks(V, omega).dense()

    def second_order_blocks(self, V, omega=None) -> BlockSystem:
        """:meth:`second_order` as constant matrices plus local blocks
        (:class:`~propwhirl.model.blocks.BlockSystem`: dense, sparse-pencil and projected
        forms, the last two linear in the number of elements).  Same checks of V."""
        V = np.atleast_1d(v.positive("airspeed V", V, "m/s"))
        if validity.has_aerodynamics(self):
            validity.check_mach(V, self.flight.speed_of_sound)
        with np.errstate(all="ignore"):
            return self._blocks(V, omega)

    def _blocks(self, V: np.ndarray, omega) -> BlockSystem:
        """The blocks of the system at the airspeeds V [m/s] (:meth:`_evaluate_blocks`); at
        speeds evaluated a moment ago (own rotational speeds), the kept evaluation's
        (:class:`~propwhirl.model.blocks.RecentBlocks`)."""
        if omega is not None:
            return self._evaluate_blocks(V, omega)
        recent = self._memo.setdefault("recent blocks", RecentBlocks())
        return recent.get(V) or recent.add(self._evaluate_blocks(V, None))

    def _evaluate_blocks(self, V: np.ndarray, omega) -> BlockSystem:
        """The blocks of the system: the wing structure (7.9–7.22), the strip aerodynamics of
        each node (signs applied: S1 = M − M_a, ...), each propeller's block at its node."""
        wing = self.wing
        nqw = 3 * wing.n_nodes
        nqi = 2 * wing.n_nodes if wing.in_plane else 0     # in-plane [v_i, χ_i] after them
        flex = self.flexible
        n = nqw + nqi + 2 * len(flex)
        memo = self._memo.setdefault("wing", {})
        if "structure" not in memo:
            mats = tuple(np.zeros((n, n)) for _ in range(3))
            for X, Xw in zip(mats, wing_structure(wing)):
                X[:nqw, :nqw] = Xw
            if nqi:
                for X, Xi in zip(mats, inplane_structure(wing)):
                    X[nqw:nqw + nqi, nqw:nqw + nqi] = Xi
            for X in mats:
                X.flags.writeable = False
            memo["structure"] = mats
        Ms, Cs, Ks = memo["structure"]
        groups = []
        lag, m, w_labels, keep_w = None, 0, (), np.arange(0)
        if self.wing_aero:
            aero = wing_aero_blocks(wing, self.flight.density, V)
            groups.append(LocalBlocks("wing strips", aero["qrows"], -aero["Ma"], -aero["Ca"],
                                      -aero["Ka"]))
            m, w_labels = aero["m"], aero["labels"]
            lag = LagBlocks(aero["qrows"], aero["wrows"], aero["W0"], aero["Ww"], aero["Wv"],
                            aero["Wq"])
            keep_w = np.arange(LAG_STATES[wing.aero_model], m)
        derivatives: dict = {}
        for j, inst in enumerate(self.propellers):
            node = self.nodes[j]
            wing_idx = [3 * node, 3 * node + 2]
            if nqi:
                wing_idx += [nqw + 2 * node, nqw + 2 * node + 1]
            if inst.mount == "flexible":
                pj = nqw + nqi + 2 * flex.index(j)
                idx = np.array([pj, pj + 1] + wing_idx)
            else:
                idx = np.array(wing_idx)
            M, C, K = self._propeller_blocks(j, V, omega, derivatives)
            groups.append(LocalBlocks(f"propeller {j}", idx[None, :], M[:, None], C[:, None],
                                      K[:, None]))
        keep_q = np.concatenate([free_dofs(wing.n_nodes), np.arange(nqw + 2 if nqi else nqw, n)])
        return BlockSystem(V, Ms, Cs, Ks, tuple(groups), lag, m, self.q_labels(), w_labels,
                           keep_q, keep_w)

    def without_aerodynamics(self) -> "PropellerWing":
        """The same wing and propellers with wing and propeller aerodynamics off (made once
        per model: the analyses of one model ask for it several times)."""
        if "quiet" not in self._memo:
            self._memo["quiet"] = self.with_(wing_aero=False, propeller_aero=False)
        return self._memo["quiet"]

    def dof_map(self) -> DofMap:
        """The states of :meth:`second_order`: the free wing DOFs (node ≥ 1: h, φ, α, eq. 7.20),
        with in-plane bending the in-plane v, χ of nodes ≥ 1, then θ, ψ of each flexibly
        mounted propeller, then the lag states of nodes ≥ 1 (made once per model)."""
        if "dof map" not in self._memo:
            self._memo["dof map"] = self._new_dof_map()
        return self._memo["dof map"]

    def _new_dof_map(self) -> DofMap:
        nn = self.wing.n_nodes
        keep = free_dofs(nn)
        labels = list(np.asarray(wing_dof_labels(nn), dtype=object)[keep])
        kinds = [WING_DOF_NAMES[i % 3] for i in keep]
        node = [int(i // 3) for i in keep]
        if self.wing.in_plane:
            labels += list(inplane_dof_labels(nn)[2:])
            kinds += [INPLANE_DOF_NAMES[i % 2] for i in range(2, 2 * nn)]
            node += [i // 2 for i in range(2, 2 * nn)]
        prop = [-1] * len(labels)
        props = []
        ys = self.wing.node_y
        for j in self.flexible:
            inst = self.propellers[j]
            props.append(PropellerDofs(j, len(labels), len(labels) + 1, inst.propeller.rotation,
                                       self.rotating, float(ys[self.nodes[j]]), self.nodes[j]))
            labels += [f"propeller {j + 1} theta", f"propeller {j + 1} psi"]
            kinds += ["theta", "psi"]
            node += [-1, -1]
            prop += [j, j]
        if self.wing_aero:
            k = LAG_STATES[self.wing.aero_model]
            w_node = tuple(i for i in range(1, nn) for _ in range(k))
            w_labels = tuple(f"node {i} w{r + 1}" for i in range(1, nn) for r in range(k))
        else:
            w_node, w_labels = (), ()
        return DofMap(tuple(labels), tuple(kinds), tuple(node), tuple(prop), w_labels, w_node,
                      tuple(props), tuple(float(y) for y in ys))


@dataclass(frozen=True)
class IsolatedPropeller(StateSpaceModel):
    """A propeller flexibly mounted on a rigid wing: 2-DOF pitch/yaw whirl (chapter 6, 6.18)."""

    propeller: Propeller = field(metadata=spec(
        "propeller", "", "key of a [propellers.KEY] table", form="reference"))
    flight: FlightCondition = field(metadata=spec("flight", "", "the flight condition"))
    propeller_aero: bool = field(default=True, metadata=spec(
        "propeller_aero", "", "propeller aerodynamic derivatives", default="setting",
        section="switches"))
    rotating: bool = field(default=True, metadata=spec(
        "rotating", "", "propeller spinning (gyroscopic terms)", default="setting",
        section="switches"))
    name: str = field(default="isolated propeller", metadata=spec(
        "name", "", "label", default="setting"))

    def __post_init__(self) -> None:
        check_fields(self)  # a Propeller, a FlightCondition, bool switches

    def with_(self, **changes) -> "IsolatedPropeller":
        return replace(self, **changes)

    def second_order(self, V) -> SecondOrder:
        """The 2-DOF pitch/yaw system (6.18) at airspeeds V [m/s] (array); checks as
        :meth:`PropellerWing.second_order`."""
        V = np.atleast_1d(v.positive("airspeed V", V, "m/s"))
        if self.propeller_aero:
            validity.check_mach(V, self.flight.speed_of_sound)
        with np.errstate(all="ignore"):
            sys = self._assemble(V)
        return self._checked(sys, V, {})

    def _values(self, V: np.ndarray) -> dict:
        """The arguments of the generated rigid-wing propeller blocks at airspeeds V."""
        p = self.propeller
        inertia = p.pivot_inertia()
        Kt, Kp = p.stiffness()
        zt, zp = p.viscous_damping_ratios()
        values = dict(
            I_X=p.I_Omega, I_Y=inertia["I_theta_P"], I_Z=inertia["I_psi_P"],
            Omega=p.spin_rate(V) if self.rotating else np.zeros_like(V),
            K_theta=Kt, K_psi=Kp, zeta_theta=zt, zeta_psi=zp, rho=self.flight.density, V=V,
            R=p.radius, e_theta=-p.e_theta, e_psi=-p.e_psi,  # chapter 6: distances, positive
        )
        if self.propeller_aero:
            values.update(p.aerodynamic_derivatives(V, self.flight.speed_of_sound))
        return values

    def _matrices(self, values: dict):
        """(S1, S2, S3) of the 2-DOF system from :meth:`_values`."""
        nV = np.shape(values["V"])[0]
        get = lambda group: call_blocks(prop_rigid, group, (nV,), **values)  # noqa: E731
        S1, S2, S3 = (get("structure_blocks")[n] for n in ("Ms", "Cs_viscous", "Ks"))
        if self.propeller_aero:
            Ma, Ca, Ka = (get("aero_blocks")[n] for n in ("Ma", "Ca", "Ka"))
            S1, S2, S3 = S1 - Ma, S2 - Ca, S3 - Ka
        return S1, S2, S3

    def _contributions(self, V: np.ndarray, omega):
        return [("propeller 1", ("propeller 1 theta", "propeller 1 psi"), self._matrices,
                 self._values(V), PROPELLER_UNITS)]

    def _assemble(self, V: np.ndarray) -> SecondOrder:
        nV = V.shape[0]
        S1, S2, S3 = self._matrices(self._values(V))
        z = np.zeros((nV, 0, 2))
        return SecondOrder(S1, S2, S3, np.zeros((nV, 2, 0)), np.zeros((nV, 0, 0)), z, z,
                           ("propeller 1 theta", "propeller 1 psi"), ())

    def without_aerodynamics(self) -> "IsolatedPropeller":
        """The same propeller with its aerodynamic derivatives off."""
        return replace(self, propeller_aero=False)

    def dof_map(self) -> DofMap:
        """Two states θ, ψ of the propeller (6.18) and their rates; no lag states."""
        return DofMap(("propeller 1 theta", "propeller 1 psi"), ("theta", "psi"), (-1, -1), (0, 0),
                      propellers=(PropellerDofs(0, 0, 1, self.propeller.rotation, self.rotating,
                                                None, None),))
