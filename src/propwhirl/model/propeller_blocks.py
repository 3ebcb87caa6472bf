"""The physics of one installed propeller's block: the arguments of the generated functions
and its local (M, C, K) (ch. 8: eq. 8.5–8.6 inertia about the pivots, 8.13–8.35 the
structural and aerodynamic blocks; issue 14: the in-plane terms).

Functions of explicit arguments (a propeller, its wing and node, the switches that apply):
the speed-independent arguments (:func:`propeller_constants`) are computed when a
:class:`~propwhirl.model.systems.PropellerWingAssembly` is built and kept there, the
speed-dependent ones — the spin rate and the aerodynamic derivatives
(:func:`propeller_values`) — at every evaluation.
"""
from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from propwhirl.generated import prop_flexwing, prop_flexwing_inplane
from propwhirl.model.structure.assembly import call_blocks
from propwhirl.model.propellers.propeller import CROSS_DERIVATIVES, Propeller
from propwhirl.model.propellers.propeller_aero import stopped_blades
from propwhirl.model.structure.wing import Wing


def design_key(p: Propeller) -> int:
    """Key of a propeller in a derivatives memo: its identity (installations sharing one
    Propeller object share its derivatives; equality would ignore fields compared loosely)."""
    return id(p)


def _stack_blocks(rows: list[list[np.ndarray]]) -> np.ndarray:
    """``np.block(rows)`` of a 2 × 2 block matrix of stacks (nV, r_i, c_j) — the same
    values, without np.block's generality (it is called for every propeller at every
    evaluation of the blocks)."""
    (a, b), (c, d) = rows
    r1, c1 = a.shape[-2:]
    out = np.empty(a.shape[:-2] + (r1 + c.shape[-2], c1 + b.shape[-1]))
    out[..., :r1, :c1] = a
    out[..., :r1, c1:] = b
    out[..., r1:, :c1] = c
    out[..., r1:, c1:] = d
    return out


def propeller_constants(propeller: Propeller, wing: Wing, node: int, density: float) -> dict:
    """The speed-independent arguments of the generated blocks of ``propeller`` installed at
    node ``node`` of ``wing`` in air of density [kg/m^3] (inertia about the pivots and the
    elastic axis, 8.5–8.6, 8.35; mount stiffness and damping; geometry; with in-plane
    bending the in-plane inertias).  A new dict each call."""
    a_b = wing.node_properties()
    ea = a_b["a"][node] * a_b["b"][node]  # elastic axis aft of mid-chord [m] (a_P b_P)
    return propeller_constants_at(propeller, float(ea), density, wing.in_plane)


def propeller_constants_at(propeller: Propeller, ea: float, density: float,
                           in_plane: bool = False) -> dict:
    """:func:`propeller_constants` of ``propeller`` on a point of a wing whose heave and twist
    are its [h_P, α_P]: ``ea`` [m] is that point's position aft of the wing mid-chord (a_P b_P,
    the elastic axis for a beam; a modal model's hub grid, :mod:`propwhirl.model.modal`)."""
    p = propeller
    inertia = p.pivot_inertia()
    S_alpha, I_alpha, I_theta_alpha = prop_flexwing.inertia(
        inertia["M_P"], inertia["S_theta_P"], inertia["I_theta_P"], p.pivot_pitch, ea
    )[..., 0]
    e_alpha = float(prop_flexwing.e_alpha_geometry(p.e_theta, p.pivot_pitch, ea)[..., 0, 0])
    Kt, Kp = p.stiffness()
    zt, zp = p.viscous_damping_ratios()
    values = dict(
        inertia, S_alpha_P=S_alpha, I_alpha_P=I_alpha, I_theta_alpha_P=I_theta_alpha,
        I_Omega=p.I_Omega, K_theta=Kt, K_psi=Kp, zeta_theta=zt, zeta_psi=zp,
        rho=density, R=p.radius, e_theta=p.e_theta, e_psi=p.e_psi,
        e_alpha=e_alpha,
    )
    if in_plane:
        m = np.array([pm.mass for pm in p.all_masses])
        x = np.array([pm.x for pm in p.all_masses])
        S_psi = float(np.sum(m * (x - p.pivot_yaw)))
        I_chi, I_psi_chi = prop_flexwing_inplane.inplane_inertia(
            inertia["M_P"], S_psi, inertia["I_psi_P"], p.pivot_yaw, ea)[..., 0]
        values.update(S_psi_P=S_psi, l_psi=p.pivot_yaw, a_P_b_P=ea, I_chi_P=I_chi,
                      I_psi_chi_P=I_psi_chi)
    return values


def installed_derivatives(propeller: Propeller, V: np.ndarray, speed_of_sound: float, *,
                          state: str = "operating", rotation: int | None = None
                          ) -> dict[str, np.ndarray]:
    """The 16 aerodynamic derivatives of ``propeller`` installed in ``state`` with the sense
    of rotation ``rotation`` (None: the propeller's) at airspeeds V [m/s].

    "operating": the propeller's own (:meth:`Propeller.aerodynamic_derivatives`), mirrored
    (the eight cross-coupling derivatives negated) when ``rotation`` is opposite to the
    propeller's — measured derivatives too, as they belong to the propeller's own sense;
    "feathered": the stopped, feathered blades of its geometry
    (:func:`~propwhirl.model.propellers.propeller_aero.stopped_blades`, no cross-coupling terms);
    "stopped": none (an error: a stopped rotor has no aerodynamic loads)."""
    p = propeller
    if state == "feathered":
        return stopped_blades(p.default_derivatives().geometry, V, speed_of_sound,
                              p.aero_settings)
    if state != "operating":
        raise ValueError(f"state {state!r} has no propeller aerodynamic derivatives")
    d = p.aerodynamic_derivatives(V, speed_of_sound)
    if rotation is not None and rotation != p.rotation:
        d = {k: (-x if k in CROSS_DERIVATIVES else x) for k, x in d.items()}
    return d


def propeller_values(constants: Mapping, propeller: Propeller, V: np.ndarray,
                     omega: np.ndarray | None, *, rotating: bool, aero: bool,
                     speed_of_sound: float, derivatives: dict | None = None,
                     state: str = "operating", rotation: int | None = None) -> dict:
    """The arguments of the generated propeller blocks at airspeeds V [m/s]: ``constants``
    (:func:`propeller_constants`) with the spin rate Ω [rad/s] (zero when not ``rotating``
    or when the installation's ``state`` is "stopped" or "feathered"; ``omega`` [rad/s],
    broadcast to V, overrides an operating propeller's own rotational speed; its sign is the
    sense ``rotation``, None: the propeller's) and, with ``aero``, the aerodynamic
    derivatives at V (:func:`installed_derivatives`).  ``derivatives``: a dict {key: the
    derivatives at V} shared by the installations of one propeller design, state and sense in
    one evaluation (keyed by :func:`design_key`), or None.  A new dict each call."""
    p = propeller
    sense = p.rotation if rotation is None else rotation
    if not rotating or state != "operating":
        Omega = np.zeros_like(V)
    elif omega is not None:
        Omega = sense * np.broadcast_to(np.asarray(omega, dtype=float), V.shape)
    else:
        Omega = sense * p.rotational_speed(V)
    values = dict(constants, Omega=Omega, V=V)
    if aero and state != "stopped":
        memo = {} if derivatives is None else derivatives
        key = (design_key(p), state, sense if state == "operating" else 0)
        if key not in memo:
            memo[key] = installed_derivatives(p, V, speed_of_sound, state=state,
                                              rotation=sense)
        values.update(memo[key])
    return values


def propeller_matrices(values: dict, *, mount: str, in_plane: bool, aero: bool):
    """(M, C, K) of a propeller's local block from :func:`propeller_values`: 4×4 over
    [θ, ψ, h_P, α_P] (``mount`` "flexible") or 2×2 over [h_P, α_P] ("rigid"); with
    ``in_plane`` bending 6×6 or 4×4 (:func:`_matrices_inplane`); ``aero``: its aerodynamic
    blocks on."""
    nV = np.shape(values["V"])[0]
    shape = (nV,)
    if in_plane:
        return _matrices_inplane(values, mount, aero)
    get = call_blocks(prop_flexwing, "structure_blocks", shape, **values).__getitem__
    if aero:
        aero_b = call_blocks(prop_flexwing, "aero_blocks", shape, **values)
    else:
        z = np.zeros((nV, 2, 2))
        aero_b = {n: z for n in ("Aa", "Ba", "Ca", "Da", "Ea", "Fa", "P1", "P2", "P3", "P4", "P5", "P6")}
    a = aero_b
    if mount == "rigid":
        return get("Gs") - a["P2"], -a["P4"], -a["P6"]
    M = _stack_blocks([[get("As") - a["Aa"], get("Bs") - a["Ba"]],
                       [get("Fs") - a["P1"], get("Gs") - a["P2"]]])
    C = _stack_blocks([[get("Cs_viscous") - a["Ca"], get("Ds") - a["Da"]],
                       [get("Hs") - a["P3"], -a["P4"]]])
    K = _stack_blocks([[get("Es") - a["Ea"], -a["Fa"]],
                       [-a["P5"], -a["P6"]]])
    return M, C, K


def _matrices_inplane(values: dict, mount: str, aero: bool):
    """(M, C, K) of a propeller with in-plane bending: 6×6 over [θ, ψ, h_P, α_P, v_P, χ_P]
    (flexible) or 4×4 over [h_P, α_P, v_P, χ_P] (rigid).  The θ–ψ blocks A, C, E are
    chapter 8's (prop_flexwing), the others prop_flexwing_inplane's."""
    nV = np.shape(values["V"])[0]
    shape = (nV,)
    s8 = call_blocks(prop_flexwing, "structure_blocks", shape, **values)
    s = call_blocks(prop_flexwing_inplane, "structure_blocks", shape, **values)
    if aero:
        a8 = call_blocks(prop_flexwing, "aero_blocks", shape, **values)
        a = call_blocks(prop_flexwing_inplane, "aero_blocks", shape, **values)
    else:
        z2, z24, z4 = np.zeros((nV, 2, 2)), np.zeros((nV, 2, 4)), np.zeros((nV, 4, 4))
        a8 = {n: z2 for n in ("Aa", "Ca", "Ea")}
        a = {n: z24 for n in ("Ba", "Da", "Fa")}
        a.update({n: z24.transpose(0, 2, 1) for n in ("P1", "P3", "P5")})
        a.update({n: z4 for n in ("P2", "P4", "P6")})
    if mount == "rigid":
        return s["Gs"] - a["P2"], s["Js"] - a["P4"], -a["P6"]
    M = _stack_blocks([[s8["As"] - a8["Aa"], s["Bs"] - a["Ba"]],
                       [s["Fs"] - a["P1"], s["Gs"] - a["P2"]]])
    C = _stack_blocks([[s8["Cs_viscous"] - a8["Ca"], s["Ds"] - a["Da"]],
                       [s["Hs"] - a["P3"], s["Js"] - a["P4"]]])
    K = _stack_blocks([[s8["Es"] - a8["Ea"], -a["Fa"]],
                       [-a["P5"], -a["P6"]]])
    return M, C, K
