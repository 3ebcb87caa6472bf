"""Exact parameter derivatives of a wing-with-propellers model's second-order system.

For a :class:`~propwhirl.model.systems.PropellerWing` the matrices of

    S1 q̈ + S2 q̇ + S3 q = S4 w,        ẇ = Ww w + Wv q̇ + Wq q           (7.59, D.18–D.29)

are sums of local blocks (:mod:`propwhirl.model.blocks`), each a generated function of a few
physical parameters.  The generated derivative functions (``<block function>_d`` of
`propwhirl.generated`: SymPy's exact ∂/∂p of every generated matrix) give ∂(block)/∂p, and the
chain rule to a model field is applied here where it is simple and exact.  A parameter of one
element, node or propeller touches only that one's block, so :func:`derivative_blocks`
returns, per parameter, a :class:`~propwhirl.model.blocks.BlockSystem` of the *derivatives*
(constant parts zero, the touched block(s) only, same DOF and lag-state layout as
``model.second_order_blocks(V)``): its ``dense()`` is ∂(S1, …, Wq)/∂p over the kept states,
:func:`pencil_derivative` the derivative of the sparse pencil (∂F, ∂E) and its
``project(Φ, Q)`` the projected derivative — the same three assemblies as the system itself.

Parameters covered (paths as :attr:`Parameter.path`; `wing` is ``model.wing``, the meshed wing):

=====================================================  ==========================================
``wing.EI[e]``, ``wing.GJ[e]``                         rigidities of element e [N m²]; the
                                                       Rayleigh damping λK follows (7.22)
``wing.mass_per_length[e]``                            m of element e [kg/m]; with a radius of
                                                       gyration ρI_p = m((r c)² + (x_α b)²)
                                                       follows, and the Rayleigh μM
``wing.lift_slope[i]``                                 C_lα at node i ≥ 1 [1/rad] (wing_aero)
``propellers[j].propeller.K_theta`` / ``K_psi``        mount stiffness [N m/rad] (with f given:
                                                       the stiffness at fixed inertia)
``propellers[j].propeller.f_theta`` / ``f_psi``        mount frequency [Hz], when the propeller
                                                       is given by it: K = I (2π f)², so
                                                       ∂K/∂f = 2K/f (model/propellers/propeller.py)
``propellers[j].propeller.damping_theta`` / ``_psi``   mount damping (ζ, or g with ζ = g/2)
``propellers[j].propeller.spin_inertia``               I_Ω [kg m²] (rotor mass held fixed)
``propellers[j].propeller.rotor.mass`` / ``.x``,       each point mass [kg] and its position [m]:
``propellers[j].propeller.masses[k].mass`` / ``.x``    M_P, S_θ,P, I_θ,P, I_ψ,P (8.5–8.6), the
                                                       elastic-axis inertias through
                                                       ``inertia``, K = I (2πf)² of a mount
                                                       given by its frequency, I_Ω = M_r R²/3,
                                                       and the rotor's x moves the propeller
                                                       plane (e_θ, e_ψ, e_α)
``propellers[j].propeller.pivot_pitch`` / ``_yaw``     pivot positions l_θ, l_ψ [m]: the pivot
                                                       inertias, ``inertia`` (l_θ), the arms
``propellers[j].propeller.derivatives.values[NAME]``   each of the 16 aerodynamic derivatives of
                                                       a MeasuredDerivatives source (propeller
                                                       aerodynamics on)
``wing.root_chord``, ``wing.tip_chord``,               the taper and the chord at node i [m]
``wing.chord[i]``                                      (linear taper): b at the nodes, x_α b and
                                                       ρI_p (with r_g) at the elements, a_P b_P
``wing.centre_of_gravity[e]``, ``elastic_axis[e]``,    section fields of element e [chord] and
``aerodynamic_centre[e]``, ``polar_inertia[e]`` /      ρI_p [kg m]: x_α b, ρI_p, and a, a_c at
``radius_of_gyration[e]``                              the nodes (interpolated), a_P b_P
                                                       (:mod:`~propwhirl.model.derivatives_section`)
``propellers[j].propeller.beta_075_deg``,              blade angle, zero-lift angle [deg] (fixed
``zero_lift_angle_deg``; ``rpm``                       pitch) or rpm (constant speed): Ω of the
                                                       gyroscopic terms and the Houbolt–Reed
                                                       derivatives through μ
                                                       (:mod:`~propwhirl.model.propellers.derivatives_blade`)
=====================================================  ==========================================

Not covered: a chord given as a function of y (no chord paths), an elastic axis or
aerodynamic centre given as a function of y (no per-element paths), the blade geometry of the
Houbolt–Reed derivatives (blade chord, radius, hub ratio), derivative sources other than
Houbolt–Reed and measured values (no rotation paths when their loads are on).
:func:`with_value` is the model with one parameter set to a value (for finite differences).
"""
from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Iterable

import numpy as np

from propwhirl.generated import beam_element, prop_flexwing
from propwhirl.model.structure.assembly import LAG_STATES, STRIP_AERO, element_dofs, free_dofs
from propwhirl.model.blocks import BlockSystem, LagBlocks, LocalBlocks
from propwhirl.model.propellers import derivatives_blade as _blade
from propwhirl.model import derivatives_section as _section
from propwhirl.model.propellers.propeller import MeasuredDerivatives
from propwhirl.model.propellers.propeller import CROSS_DERIVATIVES
from propwhirl.model.propellers.propeller_aero import DERIVATIVE_NAMES
from propwhirl.model.propeller_blocks import propeller_constants, propeller_values
from propwhirl.model.statespace import SecondOrder
from propwhirl.model.systems import PropellerWing
from propwhirl import validate as v

_PROP_AERO = ("Aa", "Ba", "Ca", "Da", "Ea", "Fa", "P1", "P2", "P3", "P4", "P5", "P6")
_AXES = ("theta", "psi")


@dataclass(frozen=True)
class Parameter:
    """One model parameter: its path, current value, unit, meaning and how its derivative is
    computed.

    kind: "element", "node", "section" (:mod:`propwhirl.model.derivatives_section`),
    "propeller" or "rotation" (:mod:`propwhirl.model.propellers.derivatives_blade`); and, in
    a model's ``parameter_paths()`` (:mod:`propwhirl.model.parameter_paths`), "factor",
    "flight" or "modal"; index: the element, node (−1 for the root and tip chords),
    installation or mode.  derivative: "exact" (the generated derivatives of this module) or
    "central difference" (:data:`propwhirl.model.protocol.DERIVATIVE_ROUTES`)."""

    path: str
    kind: str
    index: int
    name: str
    value: float
    unit: str
    doc: str
    derivative: str = "exact"


def parameters(model: PropellerWing, check: bool = True) -> tuple[Parameter, ...]:
    """Every parameter of `model` whose derivatives :func:`derivative_blocks` gives (table in
    the module docstring), in a fixed order: elements, nodes, section fields, propellers.
    ``check=False``: the same paths of a wing without exact derivatives (a doublet-lattice
    wing's, for finite differences: :func:`with_value`), a PropellerWing all the same."""
    if check:
        check_model(model)
    elif not isinstance(model, PropellerWing):
        raise v.InputError(f"model = {type(model).__name__} is invalid: parameter paths are "
                           "listed here for a PropellerWing")
    wing = model.wing
    p = wing.element_properties()
    out = []
    for name, key, unit, doc in (("EI", "EI", "N m^2", "bending rigidity"),
                                 ("GJ", "GJ", "N m^2", "torsional rigidity"),
                                 ("mass_per_length", "m", "kg/m", "mass per unit span")):
        for e in range(wing.element_count):
            out.append(Parameter(f"wing.{name}[{e}]", "element", e, name, float(p[key][e]),
                                 unit, f"{doc} of element {e}"))
    if model.wing_aero:
        cla = wing.node_properties()["Cla"]
        for i in range(1, wing.n_nodes):
            out.append(Parameter(f"wing.lift_slope[{i}]", "node", i, "lift_slope",
                                 float(cla[i]), "1/rad", f"lift-curve slope at node {i}"))
    for path, name, index, value, unit, doc in _section.parameters(wing):
        out.append(Parameter(path, "section", index, name, value, unit, doc))
    for j, inst in enumerate(model.propellers):
        prop = inst.propeller
        pre = f"propellers[{j}].propeller."
        aero = model.propeller_aero and inst.has_aero
        # a stopped or feathered rotor (Omega = 0) has no rotation parameters
        rotation = _blade.parameters(prop, aero) if inst.spinning else []
        for name, value, unit, doc in rotation:
            out.append(Parameter(pre + name, "rotation", j, name, value, unit, doc))
        K = prop.stiffness()
        zeta = prop.viscous_damping_ratios()
        for k, ax in enumerate(_AXES):
            out.append(Parameter(pre + f"K_{ax}", "propeller", j, f"K_{ax}", K[k], "N m/rad",
                                 f"{ax} mount stiffness"))
            f = getattr(prop, f"f_{ax}")
            if f is not None:
                out.append(Parameter(pre + f"f_{ax}", "propeller", j, f"f_{ax}", float(f), "Hz",
                                     f"uncoupled {ax} mount frequency"))
            out.append(Parameter(pre + f"damping_{ax}", "propeller", j, f"damping_{ax}",
                                 float(getattr(prop, f"damping_{ax}")), "",
                                 f"{ax} mount damping ({prop.damping}; zeta = {zeta[k]:.6g})"))
        out.append(Parameter(pre + "spin_inertia", "propeller", j, "spin_inertia",
                             prop.I_Omega, "kg m^2", "spin inertia I_Omega"))
        for ax, doc in (("pitch", "pitch pivot"), ("yaw", "yaw pivot")):
            out.append(Parameter(pre + f"pivot_{ax}", "propeller", j, f"pivot_{ax}",
                                 float(getattr(prop, f"pivot_{ax}")), "m",
                                 f"{doc} position aft of the mid-chord"))
        for k, (where, pm) in enumerate(_point_masses(prop)):
            out.append(Parameter(pre + f"{where}.mass", "propeller", j, f"mass:{k}",
                                 float(pm.mass), "kg", f"point mass {where}"))
            out.append(Parameter(pre + f"{where}.x", "propeller", j, f"x:{k}", float(pm.x),
                                 "m", f"position of point mass {where} aft of the mid-chord"))
        if (aero and inst.spinning                 # a feathered rotor's come from its blades
                and isinstance(prop.derivatives, MeasuredDerivatives)):
            for name in DERIVATIVE_NAMES:
                out.append(Parameter(pre + f"derivatives.values[{name}]", "propeller", j, name,
                                     float(prop.derivatives.values.get(name, 0.0)), "",
                                     f"aerodynamic derivative {name} (eq. 4.25)"))
    return tuple(out)


def check_model(model) -> None:
    """InputError unless `model` has exact parameter derivatives: a PropellerWing, its wing
    aerodynamics not the doublet lattice's, without in-plane bending."""
    if not isinstance(model, PropellerWing):
        raise v.InputError(f"model = {type(model).__name__} is invalid: parameter derivatives "
                           "are available for a PropellerWing")
    if model.wing_aero and model.wing.aero == "dlm":
        raise v.InputError(
            "wing.aero = 'dlm' is invalid for exact sensitivities and gradients: they need the "
            "parameter derivatives of the doublet-lattice (Roger) blocks, which propwhirl does "
            "not have; use finite differences (propwhirl.studies.sweep) or aero = 'strip'")
    if model.wing.in_plane:
        raise v.InputError(
            f"wing.EI_chordwise = {model.wing.EI_chordwise!r} N m^2 (in-plane bending): parameter "
            "derivatives are available for wings without in-plane bending (leave out "
            "wing.EI_chordwise, or use finite differences)")


def _lookup(model: PropellerWing, params: Iterable[str | Parameter] | None,
            check: bool = True) -> list[Parameter]:
    known = {p.path: p for p in parameters(model, check)}
    if params is None:
        return list(known.values())
    out = []
    for p in params:
        path = p.path if isinstance(p, Parameter) else p
        if path not in known:
            raise v.InputError(f"parameter = {path!r} is invalid: not a parameter with "
                               f"derivatives of this model (see propwhirl.model.derivatives."
                               f"parameters(model); e.g. {next(iter(known), 'none')!r})")
        out.append(known[path])
    return out


class _Context:
    """What the derivatives of one model at speeds V share: the layout of its BlockSystem
    and the generated derivatives of every element, node and propeller (computed once)."""

    def __init__(self, model: PropellerWing, V: np.ndarray, omega) -> None:
        self.model, self.V, self.omega = model, V, omega
        wing = model.wing
        self.nV = V.shape[0]
        self.nqw = 3 * wing.n_nodes
        self.flex = model.flexible
        self.n = self.nqw + 2 * len(self.flex)
        self.zero = np.zeros((self.n, self.n))
        self.zero.flags.writeable = False
        self.props = wing.element_properties()
        self.beam = None
        self.strip = None
        self.m = LAG_STATES[wing.aero_model] * wing.n_nodes if model.wing_aero else 0
        self.keep_q = np.concatenate([free_dofs(wing.n_nodes), np.arange(self.nqw, self.n)])
        if model.wing_aero:
            self.keep_w = np.arange(LAG_STATES[wing.aero_model], self.m)
            k = LAG_STATES[wing.aero_model]
            self.w_labels = tuple(f"node {i} w{r + 1}" for i in range(wing.n_nodes)
                                  for r in range(k))
        else:
            self.keep_w, self.w_labels = np.arange(0), ()
        self.q_labels = model.q_labels()
        self.prop: dict[int, tuple] = {}
        self.memo: dict = {}

    def system(self, blocks: tuple[LocalBlocks, ...], lag: LagBlocks | None) -> BlockSystem:
        return BlockSystem(self.V, self.zero, self.zero, self.zero, blocks, lag, self.m,
                           self.q_labels, self.w_labels, self.keep_q, self.keep_w)

    def const(self, x: np.ndarray) -> np.ndarray:
        """A V-independent block (nb, k, l) as (nV, nb, k, l), without copying."""
        return np.broadcast_to(x, (self.nV,) + x.shape)

    # ---------------------------------------------------------------- wing elements
    def element(self, par: Parameter) -> BlockSystem:
        if self.beam is None:
            self.beam = beam_element.blocks_d(**{a: self.props[a]
                                                 for a in beam_element.PARTIALS["blocks_d"][0]})
        e, wing = par.index, self.model.wing
        zero = np.zeros((1, 6, 6))
        dM, dK = zero, zero
        if par.name in ("EI", "GJ"):
            dK = self.beam["stiffness"][par.name][e:e + 1]
        else:  # mass per length: m, and ρI_p = m((r c)² + (x_α b)²) with a radius of gyration
            d = self.beam["mass"]
            dM = d["m"][e:e + 1]
            if wing.polar_inertia is None:
                dM = dM + d["rho_Ip"][e:e + 1] * (self.props["rho_Ip"][e] / self.props["m"][e])
        mu, lam = wing.rayleigh
        dofs = element_dofs(wing.element_count)[e:e + 1]
        block = LocalBlocks(f"wing element {e}", dofs, self.const(dM),
                            self.const(mu * dM + lam * dK), self.const(dK))
        return self.system((block,), None)

    # ---------------------------------------------------------------- strip aerodynamics
    def node(self, par: Parameter) -> BlockSystem:
        block, lag = self._strips("Cla", np.array([par.index]))
        return self.system((block,), lag)

    def _strips(self, arg: str, nodes: np.ndarray) -> tuple[LocalBlocks, LagBlocks]:
        """∂/∂arg (a generated argument of the strip aerodynamics: "Cla", "rho") of the strip
        blocks of `nodes`, with the widths and signs of the assembly."""
        wing = self.model.wing
        _, roles = STRIP_AERO[wing.aero_model]
        d, width, scale = _section.strip_partials(self)
        k = LAG_STATES[wing.aero_model]
        shape = {"M": (2, 2), "C": (2, 2), "K": (2, 2), "W0": (2, k), "Ww": (k, k),
                 "Wv": (k, 2), "Wq": (k, 2)}

        def get(role: str) -> np.ndarray:  # (nV, len(nodes), r, c)
            x = d[roles[role]].get(arg) if role in roles else None
            if x is None:
                return np.zeros((self.nV, nodes.size) + shape[role])
            x = np.broadcast_to(x, (self.nV, wing.n_nodes) + shape[role])[:, nodes]
            if arg == "Cla" and scale is not None:   # ∂(C_lα/β)/∂C_lα = 1/β
                x = scale[:, None, None, None] * x
            return x

        w = width[nodes][None, :, None, None]
        qrows = 3 * nodes[:, None] + np.array([0, 2])[None, :]
        wrows = k * nodes[:, None] + np.arange(k)[None, :]
        block = LocalBlocks("wing strips" if nodes.size > 1 else f"wing strip {nodes[0]}",
                            qrows, -w * get("M"), -w * get("C"), -w * get("K"))
        return block, LagBlocks(qrows, wrows, w * get("W0"), get("Ww"), get("Wv"), get("Wq"))

    # ---------------------------------------------------------------- flight
    def density(self) -> BlockSystem:
        """∂/∂ρ of the blocks [per kg/m³]: every strip's aerodynamic blocks and every
        propeller's with its loads on, through the generated ∂/∂rho (the lag dynamics, the
        structure and the nondimensional propeller derivatives do not depend on ρ)."""
        model = self.model
        groups, lag = [], None
        if model.wing_aero:
            block, lag = self._strips("rho", np.arange(model.wing.n_nodes))
            groups.append(block)
        for j, inst in enumerate(model.propellers):
            if model.propeller_aero and inst.aero:
                groups.append(self.propeller_block(j, [("rho", 1.0)]))
        return self.system(tuple(groups), lag)

    # ---------------------------------------------------------------- section fields
    def section(self, par: Parameter) -> BlockSystem:
        """A section field: the wing's blocks (:func:`propwhirl.model.derivatives_section.
        wing_blocks`) and those of the propellers whose node's a_P b_P = a b moves."""
        model, wing = self.model, self.model.wing
        ch = _section.chain(wing, par.name, par.index)
        groups, lag = _section.wing_blocks(self, ch)
        if model.propellers:
            node = wing.node_properties()
            dea = ch.node["a"] * node["b"] + node["a"] * ch.node["b"]    # ∂(a b) at the nodes
            for j, n in enumerate(model.nodes):
                if dea[n] != 0.0:
                    groups.append(self._elastic_axis_block(j, float(dea[n]),
                                                           float(node["a"][n] * node["b"][n])))
        return self.system(tuple(groups), lag)

    def _elastic_axis_block(self, j: int, dea: float, ea: float) -> LocalBlocks:
        """Propeller j's block for a change dea of the elastic axis a_P b_P at its node [m]:
        S_α,P, I_α,P, I_θα,P through ``inertia_d`` and e_α through ``e_alpha_geometry_d``."""
        prop = self.model.propellers[j].propeller
        values = self.prop_values(j)
        chain = [(name, f * dea) for name, f in
                 _through_inertia(prop, {**values, "ea": ea}, {"a_P_b_P": 1.0})]
        de = prop_flexwing.e_alpha_geometry_d(prop.e_theta, prop.pivot_pitch, ea)
        chain.append(("e_alpha", float(np.ravel(de["e_alpha_geometry"]["a_P_b_P"])[0]) * dea))
        return self.propeller_block(j, chain)

    # ---------------------------------------------------------------- rotation
    def rotation(self, par: Parameter) -> BlockSystem:
        """Blade angle, zero-lift angle or rpm of a propeller (:mod:`propwhirl.model.propellers.derivatives_blade`)."""
        return self.system((self.propeller_block(par.index, _blade.chain(self, par)),), None)

    # ---------------------------------------------------------------- propellers
    def propeller(self, par: Parameter) -> BlockSystem:
        j = par.index
        values = self.prop_values(j)
        node_ab = self.model.wing.node_properties()
        node = self.model.nodes[j]
        ea = float(node_ab["a"][node] * node_ab["b"][node])  # a_P b_P [m]
        return self.system((self.propeller_block(
            j, _chain(self.model.propellers[j], par, {**values, "ea": ea})),), None)

    def prop_values(self, j: int) -> dict:
        """The arguments of propeller j's generated blocks at the speeds V (computed once,
        with the generated derivatives of its structure and aerodynamic blocks)."""
        self._prop_derivatives(j)
        return self.prop[j][0]

    def _prop_derivatives(self, j: int) -> tuple:
        model, inst = self.model, self.model.propellers[j]
        if j not in self.prop:
            const = propeller_constants(inst.propeller, model.wing, model.nodes[j],
                                        model.flight.density)
            values = propeller_values(const, inst.propeller, self.V, self.omega,
                                      rotating=model.rotating,
                                      aero=model.propeller_aero and inst.has_aero,
                                      speed_of_sound=model.flight.speed_of_sound,
                                      derivatives=self.memo, state=inst.state,
                                      rotation=inst.sense)
            struct = prop_flexwing.structure_blocks_d(
                **{a: values[a] for a in prop_flexwing.PARTIALS["structure_blocks_d"][0]})
            aero = {}
            if model.propeller_aero and inst.has_aero:
                aero = prop_flexwing.aero_blocks_d(
                    **{a: values[a] for a in prop_flexwing.PARTIALS["aero_blocks_d"][0]})
            self.prop[j] = (values, struct, aero)
        return self.prop[j]

    def propeller_block(self, j: int, chain) -> LocalBlocks:
        """Propeller j's local block of Σ factor · ∂(M, C, K)/∂argument over `chain`
        [(generated argument, factor)], a factor a number or an array over the speeds."""
        inst = self.model.propellers[j]
        _, struct, aero = self._prop_derivatives(j)
        M, C, K = (np.zeros((self.nV, k, k)) for k in [2 if inst.mount == "rigid" else 4] * 3)
        for arg, factor in chain:
            f = np.reshape(np.asarray(factor, dtype=float), (-1, 1, 1))
            dM, dC, dK = self._local(inst.mount, struct, aero, arg)
            M, C, K = M + f * dM, C + f * dC, K + f * dK
        node = self.model.nodes[j]
        wing_idx = [3 * node, 3 * node + 2]
        if inst.mount == "flexible":
            pj = self.nqw + 2 * self.flex.index(j)
            idx = np.array([pj, pj + 1] + wing_idx)
        else:
            idx = np.array(wing_idx)
        return LocalBlocks(f"propeller {j}", idx[None, :], M[:, None], C[:, None], K[:, None])

    def _local(self, mount: str, struct: dict, aero: dict, arg: str):
        """∂(M, C, K)/∂arg of a propeller's local block, assembled as
        :func:`~propwhirl.model.propeller_blocks.propeller_matrices` assembles (M, C, K)."""
        z = np.zeros((self.nV, 2, 2))

        def g(d: dict, name: str) -> np.ndarray:
            x = d.get(name, {}).get(arg)
            return z if x is None else np.broadcast_to(x, z.shape)

        s = lambda name: g(struct, name)  # noqa: E731
        a = lambda name: g(aero, name)  # noqa: E731
        if mount == "rigid":
            return s("Gs") - a("P2"), -a("P4"), -a("P6")
        M = np.block([[s("As") - a("Aa"), s("Bs") - a("Ba")], [s("Fs") - a("P1"), s("Gs") - a("P2")]])
        C = np.block([[s("Cs_viscous") - a("Ca"), s("Ds") - a("Da")], [s("Hs") - a("P3"), -a("P4")]])
        K = np.block([[s("Es") - a("Ea"), -a("Fa")], [-a("P5"), -a("P6")]])
        return M, C, K


def _point_masses(prop) -> list[tuple[str, object]]:
    """("rotor" | "masses[k]", PointMass) of a propeller, in the order of ``all_masses``."""
    return [("rotor", prop.rotor)] + [(f"masses[{k}]", m) for k, m in enumerate(prop.masses)]


def _through_inertia(prop, values: dict, d: dict) -> list[tuple[str, float]]:
    """∂(S_α,P, I_α,P, I_θα,P) from the generated ``inertia`` (its ``inertia_d``, 8.5–8.6) for
    the derivatives ``d`` of its arguments (M_P, S_θ,P, I_θ,P, l_θ; missing ones zero)."""
    at = {"M_P": values["M_P"], "S_theta_P": values["S_theta_P"],
          "I_theta_P": values["I_theta_P"], "l_theta": prop.pivot_pitch,
          "a_P_b_P": float(values["ea"])}      # a_P b_P: elastic axis at the node [m]
    dinert = prop_flexwing.inertia_d(**{a: at[a] for a in prop_flexwing.PARTIALS["inertia_d"][0]})
    dinert = dinert["inertia"]
    return [(name, sum(float(np.asarray(dinert[a])[..., row, 0].ravel()[0]) * f
                       for a, f in d.items() if a in dinert))
            for row, name in enumerate(("S_alpha_P", "I_alpha_P", "I_theta_alpha_P"))]


def _mount_stiffness(prop, dI: dict) -> list[tuple[str, float]]:
    """∂K of each mount given by its frequency (K = I (2πf)², Propeller.stiffness) for the
    derivatives ``dI`` of I_θ,P and I_ψ,P."""
    out = []
    for ax, inert in (("theta", "I_theta_P"), ("psi", "I_psi_P")):
        f = getattr(prop, f"f_{ax}")
        if getattr(prop, f"K_{ax}") is None and f is not None and inert in dI:
            out.append((f"K_{ax}", dI[inert] * (2 * np.pi * f) ** 2))
    return out


def _mass_chain(prop, par: Parameter, values: dict) -> list[tuple[str, float]]:
    """The chain of a point mass's mass or position (8.5–8.6): M_P = Σm, S_θ,P = Σm(x − l_θ),
    I_θ,P = Σm(x − l_θ)², I_ψ,P = Σm(x − l_ψ)² (those not given in ``inertia``), then S_α,P,
    I_α,P, I_θα,P through the generated ``inertia`` (its ``inertia_d``), K = I (2πf)² where
    the mount is given by its frequency, I_Ω = M_r R²/3 for the rotor without a given spin
    inertia, and for the rotor's position the propeller plane's arms e_θ, e_ψ, e_α."""
    what, k = par.name.split(":")
    pm = prop.all_masses[int(k)]
    m, x, pp, py = float(pm.mass), float(pm.x), prop.pivot_pitch, prop.pivot_yaw
    if what == "mass":
        d = {"M_P": 1.0, "S_theta_P": x - pp, "I_theta_P": (x - pp) ** 2,
             "I_psi_P": (x - py) ** 2}
    else:
        d = {"M_P": 0.0, "S_theta_P": m, "I_theta_P": 2 * m * (x - pp),
             "I_psi_P": 2 * m * (x - py)}
    for key in (prop.inertia or {}):          # given inertias do not follow the masses
        d[key] = 0.0
    out = list(d.items()) + _through_inertia(prop, values, d) + _mount_stiffness(prop, d)
    if int(k) == 0 and what == "mass" and prop.spin_inertia is None:
        out.append(("I_Omega", prop.radius ** 2 / 3.0))
    if int(k) == 0 and what == "x":           # the rotor is the propeller plane: the load arms
        # e_θ = x_hub − l_θ, e_ψ = x_hub − l_ψ, e_α = e_θ + l_θ − a_P b_P (e_alpha_geometry)
        out += [("e_theta", 1.0), ("e_psi", 1.0), ("e_alpha", 1.0)]
    return out


def _pivot_chain(prop, par: Parameter, values: dict) -> list[tuple[str, float]]:
    """The chain of a pivot position l_θ (``pivot_pitch``) or l_ψ (``pivot_yaw``): S_θ,P and
    I_θ,P (resp. I_ψ,P) about the moved pivot, the elastic-axis inertias through ``inertia``
    (which also takes l_θ itself), K = I (2πf)², and the arms e_θ = x_hub − l_θ,
    e_ψ = x_hub − l_ψ (e_α = e_θ + l_θ − a_P b_P does not move with l_θ)."""
    inert = prop.pivot_inertia()
    given = set(prop.inertia or {})
    if par.name == "pivot_pitch":
        d = {"S_theta_P": -inert["M_P"], "I_theta_P": -2.0 * inert["S_theta_P"]}
        d = {k: (0.0 if k in given else x) for k, x in d.items()}
        return (list(d.items()) + [("e_theta", -1.0)]
                + _through_inertia(prop, values, {**d, "l_theta": 1.0})
                + _mount_stiffness(prop, d))
    dI = 0.0 if "I_psi_P" in given else -2.0 * float(np.sum(
        [q.mass * (q.x - prop.pivot_yaw) for q in prop.all_masses]))
    return [("I_psi_P", dI), ("e_psi", -1.0)] + _mount_stiffness(prop, {"I_psi_P": dI})


def _chain(inst, par: Parameter, values: dict) -> list[tuple[str, float]]:
    """[(generated argument, ∂argument/∂parameter)] of a parameter of the propeller of
    installation ``inst`` (exact)."""
    prop, name = inst.propeller, par.name
    if name.startswith(("mass:", "x:")):
        return _mass_chain(prop, par, values)
    if name in ("pivot_pitch", "pivot_yaw"):
        return _pivot_chain(prop, par, values)
    if name in ("K_theta", "K_psi"):
        return [(name, 1.0)]
    if name in ("f_theta", "f_psi"):        # K = I (2π f)²  (Propeller.stiffness)
        K = "K_" + name[2:]
        return [(K, 2.0 * float(values[K]) / par.value)]
    if name in ("damping_theta", "damping_psi"):  # ζ = g/2 or ζ (viscous_damping_ratios)
        return [("zeta_" + name[8:], 1.0 if prop.damping == "zeta" else 0.5)]
    if name == "spin_inertia":
        return [("I_Omega", 1.0)]
    # a measured aerodynamic derivative: mirrored where the installation turns the other way
    flip = name in CROSS_DERIVATIVES and inst.sense != prop.rotation
    return [(name, -1.0 if flip else 1.0)]


def derivative_blocks(model: PropellerWing, V, params: Iterable[str | Parameter] | None = None,
                      omega=None) -> dict[str, BlockSystem]:
    """{path: ∂(blocks)/∂p}: for each parameter (default all of :func:`parameters`), the
    derivative of ``model.second_order_blocks(V, omega)`` as a
    :class:`~propwhirl.model.blocks.BlockSystem` (same layout; zero constant parts, the
    touched block only): ``.dense()`` is ∂(S1, S2, S3, S4, Ww, Wv, Wq)/∂p over the kept
    states, :func:`pencil_derivative` of it ∂(F, E) (``.pencil(t)`` itself holds the pencil's
    constant identity blocks), ``.project(Φ, Q)`` the projected derivatives.
    V [m/s] (array); `omega` [rad/s] as in ``second_order``."""
    check_model(model)
    V = np.atleast_1d(v.positive("airspeed V", V, "m/s"))
    pars = _lookup(model, params)
    ctx = _Context(model, V, omega)
    with np.errstate(all="ignore"):
        return {p.path: getattr(ctx, p.kind)(p) for p in pars}


def density_blocks(model: PropellerWing, V, omega=None) -> BlockSystem:
    """∂(blocks)/∂ρ [per kg/m³] of ``model.second_order_blocks(V, omega)`` with respect to
    the air density ``flight.density`` (the layout of :func:`derivative_blocks`): the strip
    and propeller aerodynamic blocks, exact from the generated ∂/∂rho."""
    check_model(model)
    V = np.atleast_1d(v.positive("airspeed V", V, "m/s"))
    with np.errstate(all="ignore"):
        return _Context(model, V, omega).density()


def second_order_derivatives(model: PropellerWing, V,
                             params: Iterable[str | Parameter] | None = None,
                             omega=None) -> dict[str, SecondOrder]:
    """{path: ∂(second_order(V))/∂p} as dense :class:`SecondOrder` matrices (leading speed
    axis, root removed: the shapes of ``model.second_order(V, omega)``)."""
    return {k: b.dense() for k, b in derivative_blocks(model, V, params, omega).items()}


def pencil_derivative(blocks: BlockSystem, t: int = 0):
    """(∂F, ∂E) of the sparse pencil E ẋ = F x at speed index `t` from a derivative
    BlockSystem of :func:`derivative_blocks`: its ``pencil(t)`` less the constant identity
    blocks every pencil holds (E = diag(I, S1, I), F = [[0, I, 0], …]), CSC matrices."""
    import scipy.sparse as sparse

    F, E = blocks.pencil(t)
    n, m = blocks.keep_q.size, blocks.keep_w.size
    size = 2 * n + m
    k = np.arange(n)
    eye_E = sparse.csc_matrix((np.ones(n + m), (np.r_[k, 2 * n + np.arange(m)],
                                                np.r_[k, 2 * n + np.arange(m)])),
                              shape=(size, size))
    eye_F = sparse.csc_matrix((np.ones(n), (k, n + k)), shape=(size, size))
    return (F - eye_F).tocsc(), (E - eye_E).tocsc()


def with_value(model: PropellerWing, path: str, value: float) -> PropellerWing:
    """`model` with the parameter `path` (of :func:`parameters`) set to `value`, everything
    else unchanged (``dataclasses.replace`` of the wing or of installation j's propeller; a
    per-element value becomes a per-element array of the property, a nodal lift slope a
    function of y equal to the old one at every other node).  A wing without exact
    derivatives (a doublet-lattice wing's) is set the same way: it is for finite
    differences."""
    (par,) = _lookup(model, [path], check=False)
    wing = model.wing
    value = float(value)
    if par.kind == "element":
        key = {"EI": "EI", "GJ": "GJ", "mass_per_length": "m"}[par.name]
        arr = wing.element_properties()[key].copy()
        arr[par.index] = value
        return model.with_(wing=replace(wing, **{par.name: arr}))
    if par.kind == "section":
        return model.with_(wing=_section.with_value(wing, par.name, par.index, value))
    if par.kind == "node":
        ys = wing.node_y
        base = wing.lift_slope_at(ys)
        base[par.index] = value
        return model.with_(wing=replace(wing, lift_slope=_NodeValues(ys, base)))
    j = par.index
    inst = model.propellers[j]
    prop = inst.propeller
    if par.name.startswith(("mass:", "x:")):
        what, k = par.name.split(":")
        k = int(k)
        pm = replace(prop.all_masses[k], **{what: value})
        changes = ({"rotor": pm} if k == 0 else
                   {"masses": tuple(pm if i == k - 1 else q for i, q in enumerate(prop.masses))})
    elif par.name in ("K_theta", "K_psi"):
        changes = {par.name: value, "f_" + par.name[2:]: None}
    elif par.name in DERIVATIVE_NAMES:
        vals = dict(prop.derivatives.values)
        vals[par.name] = value
        changes = {"derivatives": MeasuredDerivatives(vals)}
    else:
        changes = {par.name: value}
    installs = list(model.propellers)
    installs[j] = replace(inst, propeller=replace(prop, **changes))
    return model.with_(propellers=tuple(installs))


@dataclass(frozen=True)
class _NodeValues:
    """A spanwise function of y equal to `values` at the nodes `ys` (and interpolated
    linearly between them): a lift slope given node by node."""

    ys: np.ndarray
    values: np.ndarray

    def __call__(self, y):
        return np.interp(np.asarray(y, dtype=float), self.ys, self.values)
