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

A model is an immutable value and keeps nothing of its evaluations.  What its matrices need
that does not depend on the airspeed — the wing structure, each installation's constants and
DOFs, the labels and DOF map — is a :class:`PropellerWingAssembly` with those named parts,
built by :meth:`PropellerWing.assembly` (a new one each call) and evaluated at any speeds; an
analysis builds it once and passes it where the speeds are evaluated.  The physics of one
propeller's block is :mod:`propwhirl.model.propeller_blocks` (functions of explicit arguments).
"""
from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from types import MappingProxyType
from typing import Literal

import numpy as np

from propwhirl import limits
from propwhirl import validate as v
from propwhirl.model.fields import check_fields, spec
from propwhirl.model.structure.mesh import check_station
from propwhirl.model.structure.assembly import (
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
from propwhirl.model.propellers.propeller import Propeller
from propwhirl.model.propeller_blocks import (propeller_constants, propeller_matrices,
                                             propeller_values)
from propwhirl.model.blocks import BlockSystem, LagBlocks, LocalBlocks
from propwhirl.model.protocol import REASONS, Capabilities, DofMap, PropellerDofs
from propwhirl.model.aerodynamics import dlm_rfa, validity
from propwhirl.model.aerodynamics.dlm import DlmTables, check_tables
from propwhirl.model.base import EvaluatorBase, StateSpaceModel
from propwhirl.model.section import TypicalSection  # noqa: F401 (re-export: its former home)
from propwhirl.model.statespace import SecondOrder
from propwhirl.model.structure.wing import Wing

#: Units of the arguments of the generated propeller blocks, for the error messages.
PROPELLER_UNITS = dict(
    M_P="kg", S_theta_P="kg m", I_theta_P="kg m^2", I_psi_P="kg m^2", S_alpha_P="kg m",
    I_alpha_P="kg m^2", I_theta_alpha_P="kg m^2", I_Omega="kg m^2", I_X="kg m^2",
    I_Y="kg m^2", I_Z="kg m^2", Omega="rad/s", K_theta="N m/rad", K_psi="N m/rad",
    rho="kg/m^3", V="m/s", R="m", e_theta="m", e_psi="m", e_alpha="m", S_psi_P="kg m",
    I_chi_P="kg m^2", I_psi_chi_P="kg m^2", l_psi="m", a_P_b_P="m")
#: The fields of a PropellerWing that decide neither its structure nor its propellers'
#: constants (:meth:`PropellerWingAssembly.with_switches`).
SWITCHES = ("wing_aero", "propeller_aero", "rotating", "name")
#: Units of the wing element properties (:meth:`Wing.element_properties`) and Rayleigh terms.
ELEMENT_UNITS = dict(length="m", m="kg/m", rho_Ip="kg m", x_alpha_b="m", EI="N m^2",
                     GJ="N m^2", rayleigh_mu="1/s", rayleigh_lambda="s", rho_Iz="kg m",
                     EI_chordwise="N m^2")


@dataclass(frozen=True)
class Installation:
    """A propeller attached to the wing at spanwise position y [m], anywhere in (0, semi_span].

    :class:`PropellerWing` makes y a node of the mesh (it adds y to the wing's stations).

    Parameters
    ----------
    propeller : Propeller
        The propeller (in a model file: the key of a ``[propellers.KEY]`` table).
    y : float
        Spanwise position [m], in (0, semi_span] (made a node of the mesh).
    mount : {"flexible", "rigid"}
        "flexible": the propeller's own pitch θ and yaw ψ DOFs on its mount springs; "rigid":
        its mass and loads on the wing node (§9.3.1).
    aero : bool
        False switches this propeller's aerodynamic loads off while it still turns; the
        model-wide `propeller_aero` switch acts on all propellers.
    state : {"operating", "feathered", "stopped"}
        What this installation's rotor does (issue 25, item 3):

        - "operating" (default): as its propeller's `operation` says — "fixed-pitch" is the
          windmilling rotor (Ω = V/(μR), μ from the blade angle), "constant-speed" turns at
          `rpm`.  Windmilling is that operation, not a separate state.
        - "stopped": Ω = 0 (no gyroscopic coupling) and no propeller aerodynamic loads (e.g.
          the X-57's folded high-lift propellers in cruise); the mount, its stiffness and
          damping and every mass stay.
        - "feathered": Ω = 0 and the feathered blades' aerodynamics, the limit Ω → 0 of the
          Houbolt–Reed blade elements
          (:func:`~propwhirl.model.propellers.propeller_aero.stopped_blades`): each blade is a
          fin, giving the side forces C_Yψ = −C_Zθ only.  Needs the blade geometry
          (`blade_chord`, `n_blades`, `hub_radius`), also when the propeller's derivatives are
          measured (those are for the turning rotor).
    rotation : {1, -1}, optional
        +1 counter-clockwise seen from the front, −1 clockwise: overrides the propeller's
        `rotation` for this installation, so counter-rotating neighbours share one propeller
        table; None keeps the propeller's.

    Examples
    --------
    >>> from propwhirl.model import Installation
    >>> from propwhirl.cases.ch09_baseline import baseline_propeller
    >>> inst = Installation(baseline_propeller(), y=5.7, rotation=-1)
    >>> inst.sense, inst.spinning, inst.has_aero
    (-1, True, True)
    >>> Installation(baseline_propeller(), y=5.7, state="stopped").has_aero
    False
    """

    propeller: Propeller = field(metadata=spec(
        "propeller", "", "key of a [propellers.KEY] table", form="reference"))
    y: float = field(metadata=spec("y_m", "m", "spanwise position, in (0, semi_span] (made a node of the mesh)",
                                   range=(0.0, 1e3)))
    mount: Literal["flexible", "rigid"] = field(default="flexible", metadata=spec(
        "mount", "", "flexible (pitch and yaw DOFs) or rigid", default="setting"))
    aero: bool = field(default=True, metadata=spec(
        "aero", "", "this propeller's aerodynamic loads", default="setting"))
    state: Literal["operating", "feathered", "stopped"] = field(default="operating", metadata=spec(
        "state", "", "operating: turning as the propeller's operation says (windmilling is "
        "operation = fixed-pitch, not a state of its own); stopped: Omega = 0, no propeller "
        "aerodynamics (folded blades); feathered: Omega = 0, the feathered blades' side forces "
        "(the Omega -> 0 limit of Houbolt-Reed; needs the blade geometry); the mount and masses "
        "stay in every state", default="setting"))
    rotation: int | None = field(default=None, metadata=spec(
        "rotation", "", "+1 counter-clockwise seen from the front, -1 clockwise, overriding "
        "the propeller's rotation; omitted: the propeller's", default="none"))

    def __post_init__(self) -> None:
        if isinstance(self.state, str) and self.state == "windmilling":   # not a state: say what
            raise v.fail("state", self.state, "invalid: windmilling is state = 'operating' "
                         "of a propeller with operation = 'fixed-pitch' (Omega = V/(mu R)); "
                         "the states are operating, feathered, stopped")
        check_fields(self)  # a Propeller, y in range, mount and state of their choices, ...
        if self.rotation is not None and self.rotation not in (1, -1):
            raise v.fail("rotation", self.rotation, "invalid: must be +1 or -1 (or omitted: "
                         "the propeller's)")
        if self.state == "feathered" and self.propeller.blade_chord is None:
            raise v.fail("state", self.state, "invalid for a propeller without blade_chord: "
                         "the feathered blades' aerodynamics need the blade geometry "
                         "(blade_chord, n_blades, hub_radius)")

    @property
    def sense(self) -> int:
        """The sense of rotation of this installation's rotor: `rotation`, or the propeller's."""
        return self.propeller.rotation if self.rotation is None else self.rotation

    @property
    def spinning(self) -> bool:
        """Whether this rotor turns (state "operating")."""
        return self.state == "operating"

    @property
    def has_aero(self) -> bool:
        """Whether this installation has propeller aerodynamic loads of its own (`aero` on and
        not stopped; the model-wide switch `propeller_aero` is not included)."""
        return self.aero and self.state != "stopped"


def node_at(wing: Wing, y: float, tol: float = 1e-6, name: str = "propeller position y",
            path: tuple = ("y",)) -> int:
    """Index of the node at spanwise position y; an error names the nearest nodes otherwise.

    Propellers sit on a node (§8.3.3); :class:`PropellerWing` makes its wing's mesh hold them.
    Errors name the position `name` and carry `path` (see :class:`propwhirl.validate.InputError`).

    Parameters
    ----------
    wing : Wing
        The wing whose mesh is searched.
    y : float
        Spanwise position [m].
    tol : float
        Tolerance [-], relative to max(1 m, semi_span) [m].
    name : str
        How errors name the position.
    path : tuple
        The error's :attr:`~propwhirl.validate.InputError.path`.

    Returns
    -------
    int
        The node's index (0 is the root; a position at the clamped root is an error).

    Raises
    ------
    InputError
        y outside the wing, at the root, or not at a node (naming the nearest two).

    Examples
    --------
    >>> from propwhirl.model import node_at
    >>> from propwhirl.cases.ch09_baseline import baseline_wing
    >>> wing = baseline_wing(n_elements=4)                   # nodes every 1.425 m
    >>> node_at(wing, 2.85)
    2
    >>> node_at(wing, 2.0)
    Traceback (most recent call last):
    ...
    propwhirl.validate.InputError: propeller position y = 2.0 m is not a node of the
    4-element mesh: nearest nodes are 1 (y = 1.425 m) and 2 (y = 2.85 m); add the position
    to the wing's stations
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


_GROUP_NAME = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")


def check_groups(groups: object, n: int) -> dict[str, tuple[int, ...]]:
    """Named groups of installations (:attr:`PropellerWing.groups`) checked and normalised:
    name (an identifier) → the distinct indices (from 0) of `n` installations, in the order
    given.  One InputError naming the group, its value and what is valid."""
    if groups is None:
        return {}
    if not isinstance(groups, Mapping):
        raise v.fail("groups", groups, "invalid: must be a mapping NAME -> indices of "
                     "installations (from 0)")
    out: dict[str, tuple[int, ...]] = {}
    for name, members in groups.items():
        where = f"groups.{name}"
        if not isinstance(name, str) or not _GROUP_NAME.match(name):
            raise v.fail("groups", name, "invalid: a group name must be an identifier (letters, "
                         "digits, _; not starting with a digit), e.g. high_lift")
        try:
            items = list(members)
        except TypeError:
            items = None
        if not items or any(isinstance(i, (bool, np.bool_)) or not isinstance(i, (int, np.integer))
                            for i in items):
            raise v.fail(where, members, "invalid: must be a non-empty list of installation "
                         "indices (integers from 0: 0 is the first installation)")
        bad = [int(i) for i in items if not 0 <= i < n]
        if bad:
            raise v.fail(where, [int(i) for i in items], f"invalid: index {bad[0]} is outside the "
                         f"{n} installations (indices from 0 to {n - 1}: 0 is the first, "
                         "'propeller 1' of the reports)")
        if len(set(map(int, items))) != len(items):
            dup = next(int(i) for i in items if items.count(i) > 1)
            raise v.fail(where, [int(i) for i in items], f"invalid: lists installation {dup} twice")
        out[name] = tuple(int(i) for i in items)
    return out


@dataclass(frozen=True)
class PropellerWing(StateSpaceModel):
    """A cantilever wing with flexibly (or rigidly) mounted propellers (chapter 8, appendix D).

    With no propellers it is the wing model of chapter 7.  ``model.wing`` is the given wing, or,
    when a propeller is off its nodes, that wing with every installation's y added to its
    stations (so the mesh holds every propeller; rule in :mod:`propwhirl.model.structure.mesh`).

    A value: it keeps nothing of its evaluations.  What its matrices need that does not depend
    on the airspeed is built by :meth:`assembly` (a :class:`PropellerWingAssembly`, a new one
    each call); an analysis builds it once and evaluates it at every speed.

    Parameters
    ----------
    wing : Wing
        The wing.
    flight : FlightCondition
        Density [kg/m³], speed of sound [m/s] and the airspeed range [m/s].
    propellers : tuple of Installation
        The installed propellers, at most one per node (in a model file: ``installations``).
    wing_aero : bool
        Strip (or doublet-lattice) aerodynamics of the wing on.
    propeller_aero : bool
        Propeller aerodynamic derivatives on (every propeller).
    rotating : bool
        Propellers spinning (gyroscopic terms).
    name : str
        Label.
    groups : mapping of str to tuple of int
        Named groups of installations for parameter paths
        (``propellers[NAME].propeller.f_theta``): NAME → indices into `propellers`, from 0.

    Examples
    --------
    The baseline wing on 4 elements with the baseline propeller at its tip: a propeller between
    nodes adds a node; the state x = [q, q̇, lag states] at 100 m/s.

    >>> from propwhirl.model import Installation, PropellerWing
    >>> from propwhirl.cases.ch09_baseline import baseline_flight, baseline_propeller, baseline_wing
    >>> wing = baseline_wing(n_elements=4)
    >>> m = PropellerWing(wing, baseline_flight(), (Installation(baseline_propeller(), 5.7),))
    >>> m.nodes, m.state_matrix([100.0]).shape
    ((4,), (1, 36, 36))
    >>> m2 = PropellerWing(wing, baseline_flight(), (Installation(baseline_propeller(), 2.0),))
    >>> m2.nodes, [round(float(y), 2) for y in m2.wing.node_y]
    ((2,), [0.0, 1.0, 2.0, 3.23, 4.47, 5.7])
    >>> from propwhirl.analysis import analyse
    >>> c = analyse(m, speeds=[50.0, 100.0, 150.0, 200.0]).critical
    >>> c.kind, c.label, round(c.V)
    ('divergence', 'wing 1', 143)
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
    groups: Mapping[str, tuple[int, ...]] = field(default_factory=dict, metadata=spec(
        "groups", "", "named groups of installations for parameter paths "
        "(propellers[NAME].propeller.f_theta): NAME = [indices into installations, from 0]",
        default="none", form="groups"))
    _nodes: tuple[int, ...] = field(default=(), repr=False, compare=False, metadata=spec(
        None, "", "node of each propeller (derived)", default="none", form="derived"))

    def __post_init__(self) -> None:
        check_fields(self)  # a Wing, a FlightCondition, Installations, bool switches
        limits.check_propellers(len(self.propellers))
        object.__setattr__(self, "groups", check_groups(self.groups, len(self.propellers)))
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
        """A copy with fields replaced (switches, flight condition, ...): ``dataclasses.replace``."""
        return replace(self, **changes)

    # ------------------------------------------------------------------ layout
    @property
    def nodes(self) -> tuple[int, ...]:
        """The wing node of each installation (index into ``wing.node_y``)."""
        return self._nodes

    @property
    def flexible(self) -> list[int]:
        """Indices (into `propellers`) of flexibly mounted propellers (those with θ, ψ DOFs)."""
        return [j for j, inst in enumerate(self.propellers) if inst.mount == "flexible"]

    def q_labels(self) -> tuple[str, ...]:
        """Labels of the DOFs q: the wing's ("node i h", ...), then "propeller k theta",
        "propeller k psi" of each flexibly mounted propeller, numbered from 1 for people
        (k = index in `propellers` + 1; :class:`PropellerDofs.number` keeps the index)."""
        wing = wing_dof_labels(self.wing.n_nodes)
        if self.wing.in_plane:
            wing = wing + inplane_dof_labels(self.wing.n_nodes)
        prop = tuple(f"propeller {j + 1} {d}" for j in self.flexible for d in ("theta", "psi"))
        return wing + prop

    def propeller_dofs(self, j: int) -> tuple[np.ndarray, tuple[str, ...]]:
        """Full DOF indices and labels of propeller j's local block: [θ, ψ,] h, α [, v, χ]
        at its node (θ, ψ of a flexible mount after the wing's DOFs)."""
        wing, node = self.wing, self.nodes[j]
        nqw = 3 * wing.n_nodes
        nqi = 2 * wing.n_nodes if wing.in_plane else 0
        idx = [3 * node, 3 * node + 2]
        labels = (f"node {node} h", f"node {node} alpha")
        if nqi:
            idx += [nqw + 2 * node, nqw + 2 * node + 1]
            labels = labels + (f"node {node} v", f"node {node} chi")
        if self.propellers[j].mount == "flexible":
            pj = nqw + nqi + 2 * self.flexible.index(j)
            idx = [pj, pj + 1] + idx
            labels = (f"propeller {j + 1} theta", f"propeller {j + 1} psi") + labels
        return np.array(idx), labels

    # ------------------------------------------------------------------ system
    def assembly(self, dlm_tables: DlmTables | None = None) -> "PropellerWingAssembly":
        """What the matrices need that does not depend on the airspeed (the wing structure,
        each installation's constants, the DOF layout), built now: a new
        :class:`PropellerWingAssembly` each call.  An analysis builds it once and evaluates it
        at every speed (:meth:`PropellerWingAssembly.blocks`).  ``dlm_tables``: the
        doublet-lattice tables its evaluations read and fill (a wing with ``aero = "dlm"``:
        the analysis's :class:`~propwhirl.model.aerodynamics.dlm.DlmTables`; None: new ones,
        this assembly's own)."""
        return PropellerWingAssembly.build(self, dlm_tables)

    def second_order(self, V, omega=None) -> SecondOrder:
        """The reduced second-order system (root removed) at airspeeds V [m/s] (array).

        `omega` [rad/s], broadcast to V, overrides every propeller's rotational speed (used for
        Campbell diagrams and rotational-speed studies).  Refuses what the aerodynamics cannot
        represent (:mod:`propwhirl.model.aerodynamics.validity`); a non-finite entry is an InputError naming
        the model parameter behind it.  (:meth:`PropellerWingAssembly.second_order` of a new
        :meth:`assembly`.)"""
        return self.assembly().second_order(V, omega)

    def second_order_blocks(self, V, omega=None) -> BlockSystem:
        """:meth:`second_order` as constant matrices plus local blocks
        (:class:`~propwhirl.model.blocks.BlockSystem`: dense, sparse-pencil and projected
        forms, the last two linear in the number of elements).  Same checks of V."""
        return self.assembly().second_order_blocks(V, omega)

    def state_matrix(self, V, **options) -> np.ndarray:
        """A(V) (:meth:`PropellerWingAssembly.state_matrix` of a new :meth:`assembly`)."""
        return self.assembly().state_matrix(V, **options)

    def without_aerodynamics(self) -> "PropellerWing":
        """The same wing and propellers with wing and propeller aerodynamics off."""
        return self.with_(wing_aero=False, propeller_aero=False)

    def capabilities(self) -> Capabilities:
        """What this model can do (:class:`~propwhirl.model.protocol.Capabilities`): a beam
        structure, strip or doublet-lattice wing aerodynamics, exact parameter derivatives
        (a doublet-lattice wing's and in-plane bending's: central differences), every
        command; a Campbell diagram needs a flexibly mounted propeller, the p-k method the
        wing aerodynamics."""
        dlm = self.wing_aero and self.wing.aero == "dlm"
        aero = "doublet lattice" if dlm else ("strip" if self.wing_aero else "none")
        why: dict[str, str] = {}
        if dlm:
            why["exact-sensitivity"] = REASONS["dlm-exact"]
        elif self.wing.in_plane:
            why["exact-sensitivity"] = REASONS["inplane-derivatives"]
        if not self.wing_aero:
            why["pk"] = REASONS["no-wing-aero-pk"]
        if not self.flexible:
            why["campbell"] = REASONS["no-whirl"]
        if not self.propellers:
            why["certify"] = REASONS["no-propeller-campaign"]
        derivatives = "central difference" if dlm or self.wing.in_plane else "exact"
        params = "doublet lattice" if dlm else "in-plane" if self.wing.in_plane else "beam"
        return Capabilities("beam propeller-wing", "beam", aero, derivatives,
                            "own mounts" if self.flexible else "none", tuple(why.items()),
                            params)

    def dof_map(self) -> DofMap:
        """The states of :meth:`second_order`: the free wing DOFs (node ≥ 1: h, φ, α, eq. 7.20),
        with in-plane bending the in-plane v, χ of nodes ≥ 1, then θ, ψ of each flexibly
        mounted propeller, then the lag states of nodes ≥ 1 (with ``aero = "dlm"`` the Roger
        lag states, :func:`propwhirl.model.aerodynamics.dlm_rfa.lag_labels`)."""
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
            props.append(PropellerDofs(j, len(labels), len(labels) + 1, inst.sense,
                                       self.rotating and inst.spinning,
                                       float(ys[self.nodes[j]]), self.nodes[j]))
            labels += [f"propeller {j + 1} theta", f"propeller {j + 1} psi"]
            kinds += ["theta", "psi"]
            node += [-1, -1]
            prop += [j, j]
        if self.wing_aero and self.wing.aero == "dlm":     # the Roger lag states
            w_labels, w_node = dlm_rfa.lag_labels(self)
        elif self.wing_aero:
            k = LAG_STATES[self.wing.aero_model]
            w_node = tuple(i for i in range(1, nn) for _ in range(k))
            w_labels = tuple(f"node {i} w{r + 1}" for i in range(1, nn) for r in range(k))
        else:
            w_node, w_labels = (), ()
        return DofMap(tuple(labels), tuple(kinds), tuple(node), tuple(prop), w_labels, w_node,
                      tuple(props), tuple(float(y) for y in ys))


@dataclass(frozen=True, eq=False)
class InstalledPropeller:
    """One installation of a :class:`PropellerWingAssembly`: what its block needs that does
    not depend on the airspeed.

    number:      index in ``model.propellers`` (0-based);
    installation: the :class:`Installation`;
    dofs:        full DOF indices of its local block (read-only; :meth:`PropellerWing.propeller_dofs`);
    dof_labels:  their labels;
    constants:   the speed-independent arguments of its generated blocks
                 (:func:`~propwhirl.model.propeller_blocks.propeller_constants`, read-only).
    """

    number: int
    installation: Installation
    dofs: np.ndarray
    dof_labels: tuple[str, ...]
    constants: Mapping[str, object]


@dataclass(frozen=True, eq=False)
class PropellerWingAssembly(EvaluatorBase):
    """A :class:`PropellerWing` with everything its matrices need that does not depend on the
    airspeed, built once (:meth:`build`, :meth:`PropellerWing.assembly`) and then evaluated at
    any speeds: :meth:`blocks` (the hot path: no checks), :meth:`second_order_blocks`,
    :meth:`second_order` and :meth:`state_matrix` (with the model's checks).

    model:      the model it was built from (switches, flight condition, wing);
    structure:  the full (n_q, n_q) structural M, C (Rayleigh), K of the wing (7.9–7.22; with
                in-plane bending its in-plane block), read-only;
    propellers: one :class:`InstalledPropeller` per installation;
    q_labels:   labels of the full DOFs (root included);
    keep_q:     the kept DOFs (root removed, 7.59);
    states:     the model's :class:`~propwhirl.model.protocol.DofMap` (:meth:`dof_map`);
    dlm_tables: a wing with ``aero = "dlm"``: the doublet-lattice tables its evaluations read
                and fill (:class:`~propwhirl.model.aerodynamics.dlm.DlmTables`, the analysis's),
                else None;
    dlm_fit_ks: the reduced frequencies of its Roger fits (None: the full state space's
                :func:`~propwhirl.model.aerodynamics.dlm_rfa.fit_ks`; the default analysis's
                modal state space lifts to the full one with its own,
                :func:`~propwhirl.model.aerodynamics.dlm_rfa.tracking_ks`).

    Nothing is computed after construction and nothing is kept of an evaluation but the
    doublet-lattice table nodes and fits in ``dlm_tables`` (each computed once, the same
    whenever read): the same speeds give the same matrices every time.
    """

    model: PropellerWing
    structure: tuple[np.ndarray, np.ndarray, np.ndarray]
    propellers: tuple[InstalledPropeller, ...]
    q_labels: tuple[str, ...]
    keep_q: np.ndarray
    states: DofMap
    dlm_tables: DlmTables | None = None
    dlm_fit_ks: tuple[float, ...] | None = None

    @classmethod
    def build(cls, model: PropellerWing,
              dlm_tables: DlmTables | None = None) -> "PropellerWingAssembly":
        """The assembly of ``model``: its wing structure, each installation's constants and
        DOFs, the labels and the DOF map; a wing with ``aero = "dlm"``: its doublet-lattice
        tables ``dlm_tables`` (None: new ones)."""
        wing = model.wing
        nqw = 3 * wing.n_nodes
        nqi = 2 * wing.n_nodes if wing.in_plane else 0     # in-plane [v_i, χ_i] after them
        n = nqw + nqi + 2 * len(model.flexible)
        mats = tuple(np.zeros((n, n)) for _ in range(3))
        for X, Xw in zip(mats, wing_structure(wing)):
            X[:nqw, :nqw] = Xw
        if nqi:
            for X, Xi in zip(mats, inplane_structure(wing)):
                X[nqw:nqw + nqi, nqw:nqw + nqi] = Xi
        for X in mats:
            X.flags.writeable = False
        props = []
        for j, inst in enumerate(model.propellers):
            idx, labels = model.propeller_dofs(j)
            idx.flags.writeable = False
            const = propeller_constants(inst.propeller, wing, model.nodes[j],
                                        model.flight.density)
            for x in const.values():
                if isinstance(x, np.ndarray):
                    x.flags.writeable = False
            props.append(InstalledPropeller(j, inst, idx, labels, MappingProxyType(const)))
        keep_q = np.concatenate([free_dofs(wing.n_nodes), np.arange(nqw + 2 if nqi else nqw, n)])
        keep_q.flags.writeable = False
        tables = check_tables(dlm_tables) if wing.aero == "dlm" else None
        return cls(model, mats, tuple(props), model.q_labels(), keep_q, model.dof_map(),
                   tables)

    def with_switches(self, **switches) -> "PropellerWingAssembly":
        """The assembly of the model with switches changed (``wing_aero``, ``propeller_aero``,
        ``rotating``, ``name``): the same structure and installation constants (the switches
        decide neither), a new model and DOF map."""
        bad = sorted(set(switches) - set(SWITCHES))
        if bad:
            raise v.InputError(f"with_switches: {bad} are not switches (the structure and the "
                               f"propeller constants depend on them); switches: {SWITCHES}")
        model = self.model.with_(**switches)
        return replace(self, model=model, states=model.dof_map())

    def without_aerodynamics(self) -> "PropellerWingAssembly":
        """The assembly of ``model.without_aerodynamics()`` (:meth:`with_switches`)."""
        return self.with_switches(wing_aero=False, propeller_aero=False)

    def dof_map(self) -> DofMap:
        """The model's :class:`~propwhirl.model.protocol.DofMap` (built with the assembly)."""
        return self.states

    # ------------------------------------------------------------------ evaluation
    def second_order(self, V, omega=None) -> SecondOrder:
        """:meth:`PropellerWing.second_order` (same checks)."""
        model = self.model
        V = np.atleast_1d(v.positive("airspeed V", V, "m/s"))
        if validity.has_aerodynamics(model):
            validity.check_mach(V, model.flight.speed_of_sound)
        if model.wing_aero:
            validity.check_lift_slope(model.wing.node_properties()["Cla"][1:], "lift_slope",
                                      "wing_aero = false")
        with np.errstate(all="ignore"):
            if model.wing_aero and model.wing.aero == "dlm":     # Roger's state space of the DLM
                sys = dlm_rfa.second_order(self, V, omega)
            else:
                sys = self.blocks(V, omega).dense()
        return self._checked(sys, V, {"omega": omega})

    def second_order_blocks(self, V, omega=None) -> BlockSystem:
        """:meth:`PropellerWing.second_order_blocks` (same checks of V)."""
        V = np.atleast_1d(v.positive("airspeed V", V, "m/s"))
        if validity.has_aerodynamics(self.model):
            validity.check_mach(V, self.model.flight.speed_of_sound)
        with np.errstate(all="ignore"):
            return self.blocks(V, omega)

    def blocks(self, V: np.ndarray, omega=None) -> BlockSystem:
        """The blocks of the system at the airspeeds V [m/s] (1-D array, not checked): the
        wing structure (7.9–7.22), the strip aerodynamics of each node (signs applied:
        S1 = M − M_a, ...), each propeller's block at its node.  `omega` [rad/s], broadcast
        to V, overrides every propeller's rotational speed."""
        model, wing = self.model, self.model.wing
        Ms, Cs, Ks = self.structure
        groups = []
        lag, m, w_labels, keep_w = None, 0, (), np.arange(0)
        if model.wing_aero:
            if wing.aero == "dlm":      # the DLM's Roger state space is dense: no local blocks
                raise v.InputError(
                    f"model {model.name!r}: wing aero = 'dlm' has no local (block) form; its "
                    "Roger state space is dense (second_order, method = 'dense' or 'auto') or "
                    "analyse it with method = 'pk', or set aero = 'strip'")
            aero = wing_aero_blocks(wing, model.flight.density, V,
                                    model.flight.speed_of_sound)
            groups.append(LocalBlocks("wing strips", aero["qrows"], -aero["Ma"], -aero["Ca"],
                                      -aero["Ka"]))
            m, w_labels = aero["m"], aero["labels"]
            lag = LagBlocks(aero["qrows"], aero["wrows"], aero["W0"], aero["Ww"], aero["Wv"],
                            aero["Wq"])
            keep_w = np.arange(LAG_STATES[wing.aero_model], m)
        derivatives: dict = {}        # one design's derivatives, shared by its installations
        for p in self.propellers:
            M, C, K = self.propeller_matrices(p, self.propeller_values(p, V, omega, derivatives))
            groups.append(LocalBlocks(f"propeller {p.number}", p.dofs[None, :], M[:, None],
                                      C[:, None], K[:, None]))
        return BlockSystem(V, Ms, Cs, Ks, tuple(groups), lag, m, self.q_labels, w_labels,
                           self.keep_q, keep_w)

    def propeller_aero(self, p: InstalledPropeller) -> bool:
        """Whether installation ``p``'s aerodynamic loads are on (model switch, its own, and
        not stopped: :attr:`Installation.has_aero`)."""
        return self.model.propeller_aero and p.installation.has_aero

    def propeller_values(self, p: InstalledPropeller, V: np.ndarray, omega=None,
                         derivatives: dict | None = None) -> dict:
        """The arguments of installation ``p``'s generated blocks at airspeeds V
        (:func:`~propwhirl.model.propeller_blocks.propeller_values`; a new dict)."""
        model, inst = self.model, p.installation
        return propeller_values(p.constants, inst.propeller, V, omega,
                                rotating=model.rotating, aero=self.propeller_aero(p),
                                speed_of_sound=model.flight.speed_of_sound,
                                derivatives=derivatives, state=inst.state,
                                rotation=inst.sense)

    def propeller_matrices(self, p: InstalledPropeller, values: dict):
        """(M, C, K) of installation ``p`` from :meth:`propeller_values`."""
        return propeller_matrices(values, mount=p.installation.mount,
                                  in_plane=self.model.wing.in_plane, aero=self.propeller_aero(p))

    # ------------------------------------------------------------------ error messages
    def _contributions(self, V: np.ndarray, omega):
        out = []
        for p in self.propellers:
            out.append((f"propeller {p.number + 1}", p.dof_labels,
                        lambda vals, p=p: self.propeller_matrices(p, vals),
                        self.propeller_values(p, V, omega), PROPELLER_UNITS))
        wing = self.model.wing
        out += _element_contributions(
            wing, wing.element_properties(), (beam_element, "blocks", "mass", "stiffness"),
            WING_DOF_NAMES, "")
        pi = wing.inplane_properties()
        if pi is not None:
            out += _element_contributions(
                wing, pi, (beam_inplane, "inplane_blocks", "inplane_mass", "inplane_stiffness"),
                INPLANE_DOF_NAMES, " (in-plane)")
        return out


def _element_contributions(wing: Wing, props: dict, generated: tuple, dof_names, suffix: str):
    """One contribution per wing element: its (mass, Rayleigh damping, stiffness) from the
    generated block function ``generated`` = (module, function, mass, stiffness names)."""
    module, fn, mass, stiffness = generated
    mu, lam = wing.rayleigh

    def element(vals):
        b = call_blocks(module, fn, (1,), **{k: vals[k] for k in props})
        Mb, Kb = b[mass], b[stiffness]
        return Mb, vals["rayleigh_mu"] * Mb + vals["rayleigh_lambda"] * Kb, Kb

    out = []
    for e in range(wing.element_count):
        vals = {k: x[e:e + 1] for k, x in props.items()}
        vals.update(rayleigh_mu=mu, rayleigh_lambda=lam)
        dofs = tuple(f"node {i} {d}" for i in (e, e + 1) for d in dof_names)
        out.append((f"wing element {e}{suffix}", dofs, element, vals, ELEMENT_UNITS))
    return out


@dataclass(frozen=True)
class IsolatedPropeller(StateSpaceModel):
    """A propeller flexibly mounted on a rigid wing: 2-DOF pitch/yaw whirl (chapter 6, 6.18).

    Parameters
    ----------
    propeller : Propeller
        The propeller (in a model file: the key of a ``[propellers.KEY]`` table).
    flight : FlightCondition
        Density [kg/m³], speed of sound [m/s] and the airspeed range [m/s].
    propeller_aero : bool
        Propeller aerodynamic derivatives on.
    rotating : bool
        Propeller spinning (gyroscopic terms).
    name : str
        Label.

    Examples
    --------
    The baseline propeller of §9.2 (``propwhirl.cases.ch09_baseline.
    isolated_baseline_propeller()``): backward whirl flutter at 221.5 m/s.

    >>> from propwhirl.model import IsolatedPropeller
    >>> from propwhirl.cases.ch09_baseline import baseline_flight, baseline_propeller
    >>> m = IsolatedPropeller(baseline_propeller(), baseline_flight())
    >>> m.dof_map().q_labels
    ('propeller 1 theta', 'propeller 1 psi')
    >>> from propwhirl.analysis import analyse
    >>> c = analyse(m, speeds=[100.0, 200.0, 250.0]).critical
    >>> c.kind, c.label, round(c.V, 1), round(c.frequency_hz, 2)
    ('flutter', 'backward', 221.5, 5.01)
    """

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

    def capabilities(self) -> Capabilities:
        """What this model can do (:class:`~propwhirl.model.protocol.Capabilities`): a
        propeller on its mount on a rigid wing — the dense method and the commands of a
        model file; no wing: no p-k, reduced method, sensitivities or NASTRAN deck."""
        why = {"pk": REASONS["rigid-pk"], "reduced": REASONS["rigid-reduced"],
               "sensitivity": REASONS["rigid-sensitivity"],
               "exact-sensitivity": REASONS["rigid-sensitivity"],
               "export": REASONS["rigid-export"], "certify": REASONS["rigid-campaign"]}
        return Capabilities("isolated propeller", "rigid", "none", "none", "own mounts",
                            tuple(why.items()))

    def dof_map(self) -> DofMap:
        """Two states θ, ψ of the propeller (6.18) and their rates; no lag states."""
        return DofMap(("propeller 1 theta", "propeller 1 psi"), ("theta", "psi"), (-1, -1), (0, 0),
                      propellers=(PropellerDofs(0, 0, 1, self.propeller.rotation, self.rotating,
                                                None, None),))
