"""The model contract: what the analyses need of a model, and an explicit map of its states.

Every model — :class:`~propwhirl.model.systems.PropellerWing`,
:class:`~propwhirl.model.systems.IsolatedPropeller`,
:class:`~propwhirl.model.systems.TypicalSection` — implements :class:`Model`:

* ``second_order(V)`` — the matrices of S1 q̈ + S2 q̇ + S3 q = S4 w, ẇ = Ww w + Wv q̇ + Wq q
  at airspeeds V [m/s] (:class:`~propwhirl.model.statespace.SecondOrder`);
* ``state_matrix(V)`` — A(V) of the first-order state x = [q, q̇, w] (eq. 5.3, 6.18, 7.59,
  D.27), always built by :func:`propwhirl.model.statespace.state_matrix` (one builder, one
  singularity rule);
* ``dof_map()`` — a :class:`DofMap` saying, for every state, what it is: which wing node and
  which of h, φ, α; which propeller and whether θ or ψ; the typical section's plunge or pitch;
  which aerodynamic lag state of which node; and for every flexibly mounted propeller its θ
  and ψ indices, sense of rotation and spanwise position;
* ``without_aerodynamics()`` — the same model with every aerodynamic load switched off (its
  structural matrices: kinetic and strain energies, in-vacuo modes);
* ``assembly()`` — the model's *evaluator*: an object with ``second_order(V)``,
  ``state_matrix(V)`` and ``dof_map()`` as above, holding what the matrices need that does
  not depend on the airspeed, built when it is made (a wing's structure, each propeller's
  constants: :class:`~propwhirl.model.systems.PropellerWingAssembly`; a model with nothing to
  build ahead is its own evaluator).  An analysis asks for it once and evaluates it at every
  speed; a new one each call, so nothing of an analysis stays with the model;
* ``name`` and ``flight`` (the :class:`~propwhirl.model.flight.FlightCondition`).

A model is an immutable value: it keeps no caches, and a copy with a field replaced
(``dataclasses.replace`` or ``with_``) evaluates to the matrices of a model built with that value.

The analyses read the states' meaning from the map only — never from a model's class name,
its attributes or its state labels.  Labels are for people: ``"node 3 h"``, ``"propeller 1
psi"``, ``"d/dt node 3 h"`` (the one rule for rates, :func:`~propwhirl.model.statespace.rate_label`), ``"node 3 w1"``.

Examples
--------
>>> from propwhirl.model.protocol import DofMap, PropellerDofs
>>> dm = DofMap(q_labels=("propeller 1 theta", "propeller 1 psi"), q_kinds=("theta", "psi"),
...             q_node=(-1, -1), q_propeller=(0, 0),
...             propellers=(PropellerDofs(0, 0, 1, rotation=1, spinning=True, y=None),))
>>> dm.state_labels
('propeller 1 theta', 'propeller 1 psi', 'd/dt propeller 1 theta', 'd/dt propeller 1 psi')
>>> dm.displacement.tolist()
[True, True, False, False]
>>> dm.groups()
{'pitch': array([0]), 'yaw': array([1])}
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol, runtime_checkable

import numpy as np

from propwhirl import validate as v

from propwhirl.model.flight import FlightCondition
from propwhirl.model.statespace import SecondOrder, rate_label

#: Kinds of degrees of freedom a model may have, with their units and the content group
#: (kinetic-energy shares, :meth:`DofMap.groups`) each belongs to.
DOF_KINDS: dict[str, tuple[str, str]] = {
    "h": ("m", "bending"),            # wing bending displacement, positive down (7.20)
    "phi": ("rad", "bending"),        # wing bending slope
    "alpha": ("rad", "torsion"),      # wing twist, nose up
    "v": ("m", "chordwise"),          # wing in-plane displacement, rearward (EI_chordwise)
    "chi": ("rad", "chordwise"),      # wing in-plane slope ∂v/∂y
    "theta": ("rad", "pitch"),        # propeller pitch about its pivot (6.1, 8.1)
    "psi": ("rad", "yaw"),            # propeller yaw about its pivot
    "plunge": ("m", "plunge"),        # typical-section plunge h, positive down
    "pitch": ("rad", "pitch"),        # typical-section pitch α, nose up
    "eta": ("", "modal"),             # modal coordinate of a modal structure (model/modal.py)
}


@dataclass(frozen=True)
class PropellerDofs:
    """The pitch and yaw degrees of freedom of one flexibly mounted propeller.

    number:   the propeller's index in its model (``PropellerWing.propellers``; 0 for the
              isolated propeller): internal, 0-based.  What people read numbers propellers
              from 1 (``number + 1``): the state labels "propeller 1 theta", the
              participation, warnings and figures.
    theta:    index of θ (pitch) in the displacement vector q (and in the state x = [q, q̇, w]).
    psi:      index of ψ (yaw) in q.
    rotation: +1 for a propeller spinning counter-clockwise seen from the front (the thesis's,
              Figure 6.1), −1 clockwise.
    spinning: whether the rotor turns in this model (gyroscopic terms on).
    y:        spanwise position of its wing node [m], None without a wing.
    node:     index of that wing node, None without a wing.
    """

    number: int
    theta: int
    psi: int
    rotation: int
    spinning: bool
    y: float | None
    node: int | None = None


@dataclass(frozen=True)
class HubDofs:
    """The pitch and yaw on its mount of a propeller without degrees of freedom of its own: a
    modal structure's propeller whose mount is in the modes (``mount = "on-grid"``,
    :mod:`propwhirl.model.modal`), its pitch and yaw a combination of the coordinates q.

    number:   the propeller's index in its model, 0-based (as :class:`PropellerDofs`).
    pitch:    (n_dof,) θ [rad] per unit of each q: the hub grid's nose-up rotation relative to
              the wing's at the hub's spanwise station.
    yaw:      (n_dof,) ψ [rad] per unit of each q: the hub grid's yaw (the thesis's ψ sense)
              relative to the wing's there.
    inertia:  (I_θ, I_ψ) [kg m²]: the propeller's moments of inertia about its pivots (the
              kinetic energy of its pitch and yaw, as a flexible mount's θ–θ and ψ–ψ masses).
    rotation, spinning, y: as :class:`PropellerDofs`.
    heave, twist: (n_dof,) the wing's h_P [m] (down) and α_P [rad] (nose up) under the hub
              per unit of each q; empty: not given.
    coupling: the 2×2 mass coupling [kg m, kg m²] of (θ, ψ) with (h_P, α_P) — a flexible
              mount's θψ–hα block: the energy 2 Re(ûᴴ coupling ŵ) of the propeller's pitch
              and yaw moving with its wing point, which a flexible mount's share leaves to
              no one (:mod:`propwhirl.analysis.participation`); empty: none.
    """

    number: int
    pitch: tuple[float, ...]
    yaw: tuple[float, ...]
    inertia: tuple[float, float]
    rotation: int
    spinning: bool
    y: float | None
    heave: tuple[float, ...] = ()
    twist: tuple[float, ...] = ()
    coupling: tuple[tuple[float, float], tuple[float, float]] | tuple = ()


@dataclass(frozen=True)
class PropellerMotion:
    """One propeller's pitch θ and yaw ψ on its mount as rows over q, whichever way the model
    holds them (:meth:`DofMap.whirling`): its own DOFs (``dofs`` = their indices in q, rows the
    unit rows there) or a combination of q (``dofs`` None, ``inertia`` its pitch and yaw
    moments of inertia [kg m²]).  number, rotation, spinning, y: as :class:`PropellerDofs`."""

    number: int
    rows: np.ndarray
    rotation: int
    spinning: bool
    y: float | None
    dofs: tuple[int, int] | None = None
    inertia: tuple[float, float] | None = None
    wing_rows: np.ndarray | None = None
    coupling: np.ndarray | None = None

    def pitch_yaw(self, x: np.ndarray) -> np.ndarray:
        """(θ̂, ψ̂) of shapes ``x`` ((n,) or (n, m), their first ``n_dof`` rows the
        displacements q): (2,) or (2, m)."""
        x = np.asarray(x)
        return self.rows @ x[: self.rows.shape[1]]

    def energy(self, x: np.ndarray, M: np.ndarray) -> np.ndarray:
        """The kinetic energy measure ûᴴ J û of its pitch and yaw û = (θ̂, ψ̂) in shapes ``x``
        ((n_dof, m) displacements), J its own DOFs' block of the mass matrices ``M`` ((m,
        n_dof, n_dof)) or diag(``inertia``): (m,) [kg m² rad² per unit shape²]."""
        u = self.pitch_yaw(x)
        if self.dofs is not None:
            ix = np.asarray(self.dofs)
            J = M[:, ix][:, :, ix]
            return np.real(np.einsum("ik,kij,jk->k", u.conj(), J, u))
        return np.real(self.inertia[0] * np.abs(u[0]) ** 2 + self.inertia[1] * np.abs(u[1]) ** 2)

    def coupling_energy(self, x: np.ndarray) -> np.ndarray:
        """2 Re(ûᴴ C ŵ) [as :meth:`energy`] of a hub's pitch and yaw û with the wing's heave
        and twist ŵ under it (C its ``coupling``): the part of the modes' kinetic energy a
        flexible mount's partition gives to no group; 0 for own DOFs or without coupling."""
        x = np.asarray(x)
        if self.coupling is None or self.wing_rows is None:
            return np.zeros(x.shape[1:] if x.ndim > 1 else ())
        u, w = self.pitch_yaw(x), self.wing_rows @ x[: self.rows.shape[1]]
        return 2.0 * np.real(np.einsum("i...,ij,j...->...", u.conj(), self.coupling, w))


@dataclass(frozen=True)
class DofMap:
    """What every state of a model is.  The state is x = [q, q̇, w] (eq. 5.3, D.27).

    q_labels:    labels of the displacement degrees of freedom q (n_dof).
    q_kinds:     kind of each DOF, a key of :data:`DOF_KINDS`.
    q_node:      wing node of each DOF (node 0 is the clamped root), −1 if not a wing DOF.
    q_propeller: propeller number of each DOF, −1 if not a propeller DOF.
    w_labels:    labels of the aerodynamic lag states w (n_lag).
    w_node:      wing node of each lag state, −1 for a typical section's.
    propellers:  the flexibly mounted propellers' pitch/yaw DOFs.
    node_y:      spanwise position [m] of every wing node, the clamped root (node 0)
                 included; empty without a wing.
    hubs:        the propellers whose pitch and yaw on their mounts are combinations of q
                 (a modal structure's "on-grid" mounts, :class:`HubDofs`).
    """

    q_labels: tuple[str, ...]
    q_kinds: tuple[str, ...]
    q_node: tuple[int, ...]
    q_propeller: tuple[int, ...]
    w_labels: tuple[str, ...] = ()
    w_node: tuple[int, ...] = ()
    propellers: tuple[PropellerDofs, ...] = ()
    node_y: tuple[float, ...] = ()
    hubs: tuple[HubDofs, ...] = ()

    def __post_init__(self) -> None:
        n = len(self.q_labels)
        for h in self.hubs:
            if len(h.pitch) != n or len(h.yaw) != n or len(h.heave) not in (0, n) \
                    or len(h.twist) != len(h.heave):
                raise v.InputError(f"DofMap.hubs: propeller {h.number + 1}'s pitch and yaw "
                                   f"rows have {len(h.pitch)} and {len(h.yaw)} entries, need "
                                   f"one per degree of freedom ({n})")
        for name in ("q_kinds", "q_node", "q_propeller"):
            if len(getattr(self, name)) != n:
                raise v.InputError(f"DofMap.{name} has {len(getattr(self, name))} entries, "
                                   f"need one per degree of freedom ({n})")
        if len(self.w_node) != len(self.w_labels):
            raise v.InputError(f"DofMap.w_node has {len(self.w_node)} entries, need one per "
                               f"lag state ({len(self.w_labels)})")
        bad = sorted(set(self.q_kinds) - set(DOF_KINDS))
        if bad:
            raise v.InputError(f"DofMap.q_kinds: unknown kind(s) {bad}; valid: {tuple(DOF_KINDS)}")

    @property
    def n_dof(self) -> int:
        """Number of displacement degrees of freedom (length of q)."""
        return len(self.q_labels)

    @property
    def n_lag(self) -> int:
        """Number of aerodynamic lag states (length of w)."""
        return len(self.w_labels)

    @property
    def n_states(self) -> int:
        """Number of first-order states, 2 n_dof + n_lag."""
        return 2 * self.n_dof + self.n_lag

    @property
    def state_labels(self) -> tuple[str, ...]:
        """Labels of x = [q, q̇, w]."""
        return self.q_labels + tuple(rate_label(s) for s in self.q_labels) + self.w_labels

    @property
    def displacement(self) -> np.ndarray:
        """Boolean mask (n_states,) of the displacement states q (eq. 5.7)."""
        mask = np.zeros(self.n_states, dtype=bool)
        mask[: self.n_dof] = True
        return mask

    def dofs(self, *kinds: str) -> np.ndarray:
        """Indices in q of the DOFs of the given kinds (e.g. ``dofs("h", "phi")``)."""
        bad = sorted(set(kinds) - set(DOF_KINDS))
        if bad:
            raise v.InputError(f"unknown DOF kind(s) {bad}; valid: {tuple(DOF_KINDS)}")
        return np.array([i for i, k in enumerate(self.q_kinds) if k in kinds], dtype=int)

    def groups(self) -> dict[str, np.ndarray]:
        """Content groups present in the model → indices in q: "bending" (h, φ), "torsion"
        (wing α), "pitch" (propeller θ, or the section's pitch), "yaw" (ψ), "plunge"."""
        out: dict[str, list[int]] = {}
        for i, k in enumerate(self.q_kinds):
            out.setdefault(DOF_KINDS[k][1], []).append(i)
        return {g: np.array(ix, dtype=int) for g, ix in out.items()}

    @property
    def has_wing(self) -> bool:
        """Whether the model has wing degrees of freedom (h, φ, α at nodes)."""
        return any(n >= 0 for n in self.q_node)

    @property
    def has_structure(self) -> bool:
        """Whether the model has a wing structure: wing DOFs at nodes, or the modal
        coordinates of a modal structure (kind "eta")."""
        return self.has_wing or "eta" in self.q_kinds

    def whirling(self) -> tuple[PropellerMotion, ...]:
        """Every propeller whose pitch and yaw on its mount the model has, by number: the
        flexibly mounted ones (their own θ, ψ DOFs, :attr:`propellers`) and the
        :attr:`hubs` (a combination of q).  The one view of "which propeller moves how" that
        participation and names read."""
        n = self.n_dof
        out = []
        for p in self.propellers:
            rows = np.zeros((2, n))
            rows[0, p.theta], rows[1, p.psi] = 1.0, 1.0
            rows.flags.writeable = False
            out.append(PropellerMotion(p.number, rows, p.rotation, p.spinning, p.y,
                                       dofs=(p.theta, p.psi)))
        for h in self.hubs:
            rows = np.array([h.pitch, h.yaw], dtype=float)
            rows.flags.writeable = False
            wing = np.array([h.heave, h.twist], dtype=float) if h.heave else None
            C = np.array(h.coupling, dtype=float) if h.coupling else None
            out.append(PropellerMotion(h.number, rows, h.rotation, h.spinning, h.y,
                                       inertia=tuple(h.inertia), wing_rows=wing, coupling=C))
        return tuple(sorted(out, key=lambda m: m.number))

    def wing_dof(self, node: int, kind: str) -> int | None:
        """Index in q of DOF ``kind`` ("h", "phi", "alpha") of wing node ``node``; None if that
        DOF is not a state (the clamped root)."""
        for i, (k, n) in enumerate(zip(self.q_kinds, self.q_node)):
            if n == node and k == kind:
                return i
        return None

    def wing_values(self, x: np.ndarray, kind: str) -> np.ndarray:
        """Complex DOF ``kind`` ("h", "phi", "alpha") of a shape ``x`` (its first ``n_dof``
        entries the displacements q) at every wing node, in the order of ``node_y``; 0 where
        the DOF is not a state (the clamped root)."""
        vals = np.zeros(len(self.node_y), dtype=complex)
        for node in range(vals.size):
            i = self.wing_dof(node, kind)
            if i is not None:
                vals[node] = x[i]
        return vals

    def to_dict(self) -> dict:
        """JSON-able dict (re-read with :meth:`from_dict`)."""
        d = {f: list(getattr(self, f)) for f in ("q_labels", "q_kinds", "q_node", "q_propeller",
                                                 "w_labels", "w_node", "node_y")}
        d["propellers"] = [vars(p).copy() for p in self.propellers]
        if self.hubs:                                 # (absent: every older map)
            d["hubs"] = [{k: ([list(r) for r in x] if k == "coupling" else list(x))
                          if isinstance(x, tuple) else x for k, x in vars(h).items()}
                         for h in self.hubs]
        return d

    @classmethod
    def from_dict(cls, d: dict) -> "DofMap":
        """The map written by :meth:`to_dict`."""
        kw = {f: tuple(d[f]) for f in ("q_labels", "q_kinds", "q_node", "q_propeller",
                                       "w_labels", "w_node", "node_y")}
        hubs = tuple(HubDofs(**{k: (tuple(map(tuple, x)) if k == "coupling" else tuple(x))
                                if isinstance(x, list) else x for k, x in h.items()})
                     for h in d.get("hubs", ()))
        return cls(**kw, propellers=tuple(PropellerDofs(**p) for p in d["propellers"]),
                   hubs=hubs)

    def propeller(self, number: int) -> PropellerDofs:
        """The pitch/yaw DOFs of propeller ``number`` (an error if it has none)."""
        for p in self.propellers:
            if p.number == number:
                return p
        have = [p.number for p in self.propellers]
        raise v.InputError(f"propeller {number} has no pitch/yaw degrees of freedom "
                           f"(flexibly mounted propellers: {have})")


@runtime_checkable
class Model(Protocol):
    """What the analyses need of a model (see the module docstring).

    A structural protocol: :class:`~propwhirl.model.systems.PropellerWing`,
    :class:`~propwhirl.model.systems.IsolatedPropeller`,
    :class:`~propwhirl.model.section.TypicalSection` and
    :class:`~propwhirl.model.modal.ModalPropellerWing` meet it, and so does any object with
    these attributes and the methods ``second_order(V)``, ``state_matrix(V)`` (V: airspeeds
    [m/s], an array; A(V) of shape (len(V), n, n) [1/s]), ``dof_map()``,
    ``without_aerodynamics()`` and ``assembly()``.  Optional: ``capabilities()`` (what it
    supports, :func:`capabilities`; its ``parameters`` names the model's parameter paths,
    listed with how each one's derivative is computed by
    :func:`propwhirl.model.parameter_paths.parameter_paths`).

    Attributes
    ----------
    name : str
        Label, used in reports.
    flight : FlightCondition
        Density [kg/m³], speed of sound [m/s] and the airspeed range [m/s].

    Examples
    --------
    >>> from propwhirl import Model
    >>> from propwhirl.cases.ch09_baseline import isolated_baseline_propeller
    >>> m = isolated_baseline_propeller()
    >>> isinstance(m, Model), isinstance("a wing", Model)
    (True, False)
    >>> m.state_matrix([100.0, 200.0]).shape          # two speeds [m/s], 4 states
    (2, 4, 4)
    """

    name: str

    @property
    def flight(self) -> FlightCondition: ...

    def second_order(self, V) -> SecondOrder: ...

    def state_matrix(self, V) -> np.ndarray: ...

    def dof_map(self) -> DofMap: ...

    def without_aerodynamics(self) -> "Model": ...

    def assembly(self) -> "Evaluator": ...


@runtime_checkable
class Evaluator(Protocol):
    """What :meth:`Model.assembly` returns: the model's matrices at airspeeds V [m/s],
    from parts built once (see the module docstring)."""

    def second_order(self, V) -> SecondOrder: ...

    def state_matrix(self, V) -> np.ndarray: ...

    def dof_map(self) -> DofMap: ...


#: What a command or method may ask of a model (:func:`refusal`): the command-line commands
#: and the analysis methods that need more than the contract above ("dense", "reduced",
#: "pk": the methods of ``analyse(model, method=...)``; "exact-sensitivity": the generated
#: parameter derivatives).
COMMANDS = ("analyse", "modes", "campbell", "sweep", "map", "boundary", "clearance",
            "certify", "sensitivity", "export", "upgrade-model")
METHODS = ("dense", "reduced", "pk")
FEATURES = COMMANDS + METHODS + ("exact-sensitivity",)

#: Where a model's structure comes from (:attr:`Capabilities.structure`).
STRUCTURES = {
    "beam": "Euler-Bernoulli beam elements from section properties (EI, GJ, m along the span)",
    "modes": "normal modes from any finite-element code (frequencies, modal masses, damping, "
             "shapes at grids)",
    "section": "a typical section (plunge and pitch springs)",
    "rigid": "a rigid wing: the propeller's mount is the only structure",
}
#: The parameter paths a model may have sensitivities for (:attr:`Capabilities.parameters`;
#: the lists: :mod:`propwhirl.model.parameter_paths`).
PARAMETER_SETS = {
    "beam": "a strip wing's generated-block parameters, the distributions' factors and the "
            "air density, all exact",
    "doublet lattice": "a doublet-lattice wing's: the beam's but those of the strips and of "
                       "the panels' geometry, by central differences",
    "in-plane": "a strip wing with in-plane bending: the beam's paths, by central "
                "differences of its state matrix",
    "modal": "each mode's frequency, modal mass and damping, the own mounts, the spin "
             "inertias and the air density, by central differences",
    "none": "no sensitivities",
}
#: The wing aerodynamics a model may have (:attr:`Capabilities.aerodynamics`): what the
#: finite-state methods (dense, reduced) and the p-k method each use.
AERODYNAMICS = {
    "strip": ("finite-state strips", "exact-Theodorsen strips"),
    "doublet lattice": ("doublet lattice, Roger state space", "doublet lattice, Q(k, Mach)"),
    "none": ("no wing aerodynamics", "no wing aerodynamics"),
}


@dataclass(frozen=True)
class Capabilities:
    """What a model can do: the contract's one statement of it, read by every command and
    method (:func:`capabilities`, :func:`refusal`) instead of the model's type.

    kind:         what people call it ("beam propeller-wing", "modal propeller-wing", ...).
    structure:    a key of :data:`STRUCTURES`.
    aerodynamics: a key of :data:`AERODYNAMICS` (the wing's; the propellers' Houbolt-Reed
                  loads are in every model with propellers).
    derivatives:  "exact" (generated parameter derivatives), "central difference" (of the
                  state matrix or of the critical eigenvalue) or "none": how ``propwhirl
                  sensitivity`` differentiates.
    parameters:   a key of :data:`PARAMETER_SETS`: which parameter paths the model has
                  sensitivities for (listed, each with its ``derivative`` of
                  :data:`DERIVATIVE_ROUTES`, by
                  :func:`propwhirl.model.parameter_paths.parameter_paths`).
    propellers:   "own mounts" (θ, ψ DOFs), "hub grids" (mounts in the modes), "both",
                  or "none".
    refusals:     {feature of :data:`FEATURES`: why it cannot run, the physical or modelling
                  reason in a few words}; every other feature runs.
    """

    kind: str
    structure: str
    aerodynamics: str
    derivatives: str
    propellers: str
    refusals: tuple[tuple[str, str], ...] = ()
    parameters: str = "none"

    def __post_init__(self) -> None:
        if self.structure not in STRUCTURES:
            raise ValueError(f"structure = {self.structure!r}: not one of {tuple(STRUCTURES)}")
        if self.aerodynamics not in AERODYNAMICS:
            raise ValueError(f"aerodynamics = {self.aerodynamics!r}: not one of "
                             f"{tuple(AERODYNAMICS)}")
        if self.parameters not in PARAMETER_SETS:
            raise ValueError(f"parameters = {self.parameters!r}: not one of "
                             f"{tuple(PARAMETER_SETS)}")
        bad = [f for f, _ in self.refusals if f not in FEATURES]
        if bad:
            raise ValueError(f"refusals of unknown features {bad}; valid: {FEATURES}")

    def refusal(self, feature: str) -> str | None:
        """Why ``feature`` cannot run, or None when it can."""
        if feature not in FEATURES:
            raise ValueError(f"feature = {feature!r} is not one of {FEATURES}")
        return dict(self.refusals).get(feature)

    def supports(self, feature: str) -> bool:
        """Whether ``feature`` runs on the model."""
        return self.refusal(feature) is None

    @property
    def methods(self) -> tuple[str, ...]:
        """The analysis methods that run (of :data:`METHODS`)."""
        return tuple(m for m in METHODS if self.supports(m))

    def aerodynamics_of(self, method: str) -> str:
        """The wing aerodynamics the method uses: the finite-state form (dense, reduced) or
        the frequency-domain one (pk), :data:`AERODYNAMICS`."""
        return AERODYNAMICS[self.aerodynamics][1 if method == "pk" else 0]


#: The refusals' reasons, one sentence each: the physical or modelling reason a model of a
#: kind cannot run a feature (the models' :meth:`capabilities` pick theirs from here, so the
#: capability table, docs/capabilities.md, lists them from one place).
REASONS = {
    "modal-reduced": "a modal model is reduced already (one coordinate per mode): the reduced "
                     "method would not pay; use the default method (dense)",
    "modal-exact": "exact derivatives exist for the beam model's generated blocks only "
                   "(model/derivatives.py): a modal model's sensitivities are central "
                   "differences of its state matrix",
    "modal-export": "a NASTRAN deck is written of a beam model (its elements and sections): a "
                    "modal model's structure is its modes, which came from a finite-element "
                    "model already",
    "modal-upgrade": "a modal model file has one format version (1): there is nothing to "
                     "upgrade",
    "no-whirl": "a Campbell diagram needs a flexibly mounted propeller (or a modal "
                "structure's on its hub grid): the rotational speed acts on the modes only "
                "through the propellers' pitch and yaw (the wing's own modes: propwhirl modes)",
    "dlm-exact": "the doublet-lattice (Roger) blocks have no generated parameter "
                 "derivatives: a doublet-lattice wing's sensitivities are central differences "
                 "of its critical eigenvalue, the AICs computed once for all",
    "inplane-derivatives": "in-plane bending (EI_chordwise) has no generated parameter "
                           "derivatives: a wing with it has sensitivities by central "
                           "differences of its state matrix",
    "free-pk": "the p-k method follows the oscillatory in-vacuo modes: a free structure's "
               "rigid-body roots (plunge, roll, with a tail pitch) and the slow flutter they "
               "make with the divergence root (0.04 Hz on a body 10^4 times the wing) are not "
               "among them; use the default method (dense), which tracks every root",
    "no-wing-aero-pk": "the p-k method iterates the wing's unsteady aerodynamics on the "
                       "frequency, and the wing aerodynamics are off: the dense method is exact",
    "rigid-pk": "the p-k method iterates the wing's unsteady aerodynamics on the frequency: an "
                "isolated propeller has none (its Houbolt-Reed loads are quasi-steady), the "
                "dense method is exact",
    "rigid-reduced": "an isolated propeller has two degrees of freedom: there is nothing to "
                     "reduce; use the default method (dense)",
    "rigid-sensitivity": "the parameter derivatives are generated for wing models' blocks: an "
                         "isolated propeller on a rigid wing has none; use `propwhirl sweep` "
                         "on the parameter path",
    "rigid-export": "a NASTRAN deck is written of a beam model (a wing with propellers): an "
                    "isolated propeller on a rigid wing is not a beam model",
    "no-propeller-campaign": "a clearance campaign's cases act on a propeller-wing's installed "
                             "propellers (mount failures, rotation, their states): this wing "
                             "has none",
    "rigid-campaign": "a clearance campaign is flown by a propeller-wing (its cases vary the "
                      "wing's damping and its installed propellers): an isolated propeller on "
                      "a rigid wing has no wing",
    "section-file": "a typical section has no model file: analyse it with the Python API "
                    "(propwhirl.analysis.analyse)",
    "section-reduced": "a typical section has two degrees of freedom: there is nothing to "
                       "reduce; use the default method (dense)",
    "own-class-reduced": "the reduced method projects the model's blocks "
                         "(second_order_blocks), which a model of its own class does not have",
    "own-class-pk": "the p-k method needs the model's frequency-domain aerodynamics, which a "
                    "model of its own class does not give",
    "own-class-sensitivity": "the parameter derivatives are generated for propwhirl's wing "
                             "model's blocks only",
}


#: How a parameter's derivative is computed (each path's ``derivative`` in
#: :func:`propwhirl.model.parameter_paths.parameter_paths`; :attr:`Capabilities.derivatives`
#: adds "none").
DERIVATIVE_ROUTES = {
    "exact": "the generated parameter derivatives of the beam model's blocks "
             "(model/derivatives.py) in the eigenvalue perturbation",
    "central difference": "central differences of the state matrix (or, on a doublet-lattice "
                          "wing, of the p-k root) at p ± h in the eigenvalue perturbation",
}


def capabilities(model) -> Capabilities:
    """What ``model`` can do (:class:`Capabilities`): ``model.capabilities()``; a model that
    does not state it (any other object meeting :class:`Model`, e.g. one of a user's own
    class) is refused nothing here: what it lacks fails where it is needed."""
    ask = getattr(model, "capabilities", None)
    if callable(ask):
        return ask()
    why = {"pk": REASONS["own-class-pk"], "sensitivity": REASONS["own-class-sensitivity"],
           "exact-sensitivity": REASONS["own-class-sensitivity"]}
    if not hasattr(model, "second_order_blocks"):
        why["reduced"] = REASONS["own-class-reduced"]
    return Capabilities(type(model).__name__, "section", "none", "none", "none",
                        tuple(why.items()))


def refusal(model, feature: str) -> str | None:
    """Why ``model`` cannot run ``feature`` (one of :data:`FEATURES`), as the physical or
    modelling reason in a few words, or None when it can: :func:`capabilities` of the model
    (the one place a command or method asks, not the model's type)."""
    return capabilities(model).refusal(feature)
