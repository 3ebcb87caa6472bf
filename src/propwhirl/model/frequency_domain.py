"""Frequency-domain (exact Theodorsen) matrices for the p-k method: the typical section and the
wing's strip theory.

For harmonic motion at the reduced frequency k = ω b / V, Theodorsen's loads (thesis eq.
7.24–7.27, 7.64–7.66) with the exact C(k) = F(k) + iG(k) (eq. 4.31) are
Q = M_a q̈ + C_a(k) q̇ + K_a(k) q; the matrices are generated from ``derivations/strip_aero.py``
(``strip_aero.theodorsen_blocks``), the section's structure from
``derivations/typical_section.py``.  On a wing every node's strip has its own
k_i = ω b_i / V and acts with its tributary width, as the finite-state strips
(:func:`propwhirl.model.structure.assembly.wing_aero_blocks`; with the wing's
``compressibility = "prandtl-glauert"`` each slope C_lα/β at the speed's Mach,
:mod:`propwhirl.model.aerodynamics.compressibility`); the structure and the propellers
(Houbolt–Reed loads as they are) are the model's own second-order system with the wing
aerodynamics off.  The p-k solution itself is :mod:`propwhirl.analysis.pk`.
"""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from propwhirl import validate as v
from propwhirl.generated import strip_aero, typical_section
from propwhirl.model.aerodynamics.compressibility import lift_slope_factor, lift_slopes
from propwhirl.model.aerodynamics.dlm import DlmTables, dlm_aerodynamics, pk_system_dlm
from propwhirl.model.aerodynamics.dlm_surface import surface_of
from propwhirl.model.aerodynamics.theodorsen import theodorsen
from propwhirl.model.protocol import capabilities, refusal
from propwhirl.model.structure.assembly import free_dofs

#: reduced frequency used for a (numerically) non-oscillatory root: G(k)/k is singular at 0
K_MIN = 1e-6


def check_pk_model(model) -> None:
    """InputError unless the model contract says `model` runs the p-k method
    (:func:`~propwhirl.model.protocol.refusal`: a typical section with its aerodynamics on, a
    beam or modal propeller-wing with its wing aerodynamics on), with the model's reason."""
    why = refusal(model, "pk")
    if why is not None:
        raise v.InputError(f"model = {type(model).__name__} {getattr(model, 'name', '')!r} is "
                           f"invalid for the p-k method: {why}")


#: kept for the typical-section-only callers
check_section = check_pk_model


def reference_semichord(model) -> float:
    """Semichord [m] of the reduced frequency k = ω b / V reported: the section's b, the
    wing's root semichord (a modal model's: its doublet-lattice planform's root semichord,
    else its first strip's)."""
    can = capabilities(model)                       # the model contract says which it is
    structure = can.structure
    if structure == "section":
        return float(model.b)
    if can.aerodynamics == "doublet lattice":       # the doublet lattice's k, one b_ref
        return surface_of(model).b_ref
    if structure == "modes":                        # its first (root) strip's
        return float(0.5 * model.planform.chord[0])
    return float(model.wing.node_properties()["b"][0])


def section_structure(model) -> tuple[np.ndarray, np.ndarray]:
    """Structural mass [kg/m, kg, kg m] and stiffness [h, α] of a typical section."""
    S = model.m * model.x_alpha * model.b
    I = model.m * (model.r_alpha * model.b) ** 2
    blk = typical_section.blocks(m=model.m, S=S, I_alpha=I, K_h=model.m * model.omega_h**2,
                                 K_alpha=I * model.omega_alpha**2)
    return np.asarray(blk["mass"], float), np.asarray(blk["stiffness"], float)


def _strip(rho, V, b, a, Cla, ac, omega):
    """Exact-Theodorsen strip matrices (M_a, C_a, K_a) per unit span at frequency ω [rad/s];
    b, a, Cla, ac scalars or arrays (one per strip); ω a scalar, or an array (m, 1) for m
    frequencies at once (the blocks then (m, n_strips, 2, 2))."""
    k = np.maximum(np.asarray(omega * np.asarray(b, float) / V, float), K_MIN)
    C = theodorsen(k)
    aero = strip_aero.theodorsen_blocks(rho=rho, V=V, b=b, a=a, Cla=Cla, ac=ac, k=k,
                                        F=C.real, G=C.imag)
    return aero["theodorsen_M"], aero["theodorsen_C"], aero["theodorsen_K"]


def section_pk_matrices(model, V: float, k: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(M, C, K) of M q̈ + C q̇ + K q = 0 for the section at airspeed V [m/s] with the exact
    Theodorsen loads at the reduced frequency k [-] (k below :data:`K_MIN` is raised to it)."""
    Ma, Ca, Ka = _strip(model.flight.density, V, model.b, model.a, model.Cla, model.ac,
                        max(float(k), K_MIN) * V / model.b)
    Ms, Ks = section_structure(model)
    return Ms - Ma, -Ca, Ks - Ka


class Galerkin:
    """A Galerkin basis of a wing's p-k equation: Φ (n_dof, r) over the model's DOFs
    (:func:`pk_system`'s, the wing's first), real; on a doublet-lattice wing also its tables
    projected on Φ's wing rows once for every speed and k
    (:class:`~propwhirl.model.aerodynamics.dlm.ProjectedGaf`, reading ``tables``, the
    analysis's).  Made for one analysis (the projected tables are kept here)."""

    def __init__(self, model, Phi: np.ndarray, tables: DlmTables | None = None):
        self.Phi = np.asarray(Phi, dtype=float)
        self.gaf = None
        if capabilities(model).aerodynamics == "doublet lattice":
            aero = dlm_aerodynamics(surface_of(model), tables)
            Psi = np.zeros((aero.n_dof, self.Phi.shape[1]))
            Psi[aero.keep] = self.Phi[:aero.keep.size]
            self.gaf = aero.projected(Psi)

    @property
    def r(self) -> int:
        """The basis's size."""
        return self.Phi.shape[1]


def over_omega(matrices):
    """``matrices`` (ω ↦ (M, C, K) at one frequency) also taking an array of frequencies
    (m,), returning stacks (m, n, n): what :func:`pk_system` returns where its loads are not
    evaluated for several frequencies at once."""
    def system(omega):
        if np.ndim(omega) == 0:
            return matrices(float(omega))
        return tuple(np.stack(x) for x in zip(*(matrices(float(w)) for w in omega)))
    return system


def dry_assembly(model):
    """The assembly (:meth:`~propwhirl.model.systems.PropellerWing.assembly`) of a beam
    wing's ``model`` with its wing aerodynamics off: its structure and propellers, which the
    p-k system adds its loads to at every speed (:func:`pk_system`'s ``dry``), built once by
    an analysis instead of at every speed (the Goland wing's p-k analysis over 16 speeds
    assembled its structure 94 times, its sweep 77); None for a typical section or a modal model (they build
    their own)."""
    if capabilities(model).structure != "beam":
        return None
    return replace(model, wing_aero=False).assembly()


def pk_system(model, V: float, tables: DlmTables | None = None, own_mach: bool = False,
              basis: Galerkin | None = None, dry=None):
    """ω ↦ (M, C, K) of the p-k equation of `model` at airspeed V [m/s] and frequency ω [rad/s]:
    the typical section (:func:`section_pk_matrices`) or a PropellerWing (its structure and
    propellers, computed once, every wing strip with the exact Theodorsen loads at its own
    k = ω b_i / V; a wing with ``aero = "dlm"``: the doublet-lattice loads instead,
    :func:`propwhirl.model.aerodynamics.dlm.pk_system_dlm`), on the model's degrees of freedom (its
    ``dof_map``, without lag states).  ``tables``: the analysis's doublet-lattice tables
    (:class:`~propwhirl.model.aerodynamics.dlm.DlmTables`; None: new ones); ``own_mach``:
    a Mach-matched doublet-lattice wing's Q at its own Mach V/a (the fine columns around it),
    not between the tables' Mach nodes
    (:func:`~propwhirl.model.aerodynamics.dlm.pk_system_dlm`); ``basis``: a beam wing's
    :class:`Galerkin` basis Φ, the system projected on it, Φᵀ (M, C, K) Φ (r, r): the
    structure once per speed, the strips' loads summed over the strips on Φ's rows (a
    doublet-lattice wing's Q from the tables projected once, :class:`Galerkin`).  ω may be
    an array (m,) of frequencies: then stacks (m, n, n) (:func:`over_omega`; a beam wing's
    strips, projected or not, evaluated for all of them in one call — the p-k iteration of all
    followed modes at once, :func:`propwhirl.analysis.pk_basis.pk_roots`).  ``dry``: a beam
    wing's :func:`dry_assembly` of ``model``, built once by the analysis (None: built
    here)."""
    can = capabilities(model)                       # the model contract says which it is
    if basis is not None and can.structure in ("section", "modes"):
        raise v.InputError(f"basis = {type(basis).__name__} is invalid for the p-k system of "
                           f"a model of structure {can.structure!r}: a beam wing's only")
    if can.structure == "section":
        return over_omega(lambda omega: section_pk_matrices(model, V, omega * model.b / V))
    if can.aerodynamics == "doublet lattice":     # panels instead of the strips (any structure)
        system = pk_system_dlm(model, V, K_MIN, tables, own_mach,
                               None if basis is None else (basis.Phi, basis.gaf), dry)
        return system if basis is not None else over_omega(system)   # projected: vectorised
    if can.structure == "modes":
        return over_omega(modal_pk_system(model, V))
    dry = (dry_assembly(model) if dry is None else dry).second_order(np.array([V]))
    if dry.n_lag:
        raise v.InputError(f"model = {model.name!r} is invalid for the p-k method: its "
                           "propeller aerodynamics has lag states")
    node = model.wing.node_properties()
    factor = lift_slope_factor(model.wing, V, model.flight.speed_of_sound)  # None: incompressible
    cla = node["Cla"] if factor is None else lift_slopes(node["Cla"], factor)[0]
    nn = model.wing.n_nodes
    width = node["width"][:, None, None]
    qrows = 3 * np.arange(nn)[:, None] + np.array([0, 2])[None, :]   # h_i, α_i
    keep = free_dofs(nn)
    structure = (dry.S1[0], dry.S2[0], dry.S3[0])
    if basis is not None:
        Phi = basis.Phi
        rows = np.zeros((3 * nn, Phi.shape[1]))
        rows[keep] = Phi[:keep.size]
        P = rows[qrows]                                   # (n_strips, 2, r): [h, α] of η
        r = Phi.shape[1]
        # Σ_s P_sᵀ (w_s A_s) P_s as one product: (s, i, j) flattened against P_si,m P_sj,n
        G = np.einsum("sim,sjn->sijmn", P, P).reshape(-1, r * r)
        reduced = tuple(Phi.T @ S @ Phi for S in structure)

        def projected(omega):
            w = np.asarray(omega, float)
            strips = _strip(model.flight.density, V, node["b"], node["a"], cla, node["ac"],
                            w[..., None])       # (..., n_strips, 2, 2)
            return tuple(S - ((width * A).reshape(w.shape + (-1,)) @ G)
                         .reshape(w.shape + (r, r)) for S, A in zip(reduced, strips))

        return projected

    nk = keep.size
    rows, cols = qrows[:, :, None], qrows[:, None, :]

    def matrices(omega):
        # the strips' blocks of every ω at once, placed (non-overlapping: one strip per
        # node) and subtracted from the structure's on the free DOFs
        w = np.asarray(omega, float)
        strips = _strip(model.flight.density, V, node["b"], node["a"], cla, node["ac"],
                        w[..., None])                  # (..., n_strips, 2, 2)
        out = []
        for S, A in zip(structure, strips):
            loads = np.zeros(w.shape + (3 * nn, 3 * nn))
            loads[..., rows, cols] = width * A
            X = np.array(np.broadcast_to(S, w.shape + S.shape), dtype=float)
            X[..., :nk, :nk] -= loads[..., keep[:, None], keep[None, :]]
            out.append(X)
        return tuple(out)

    return matrices


def modal_pk_system(model, V: float):
    """ω ↦ (M, C, K) of the p-k equation of a modal model at V [m/s]: its modes and
    propellers as they are (:meth:`ModalAssembly.second_order` with the wing aerodynamics
    off), every strip with the exact Theodorsen loads at its own k = ω b_s / V projected on
    the coordinates as the finite-state strips are, (TΦ)ᵀ A_s (TΦ)
    (:mod:`propwhirl.model.modal`), a further surface's (a tail's) strips likewise."""
    assembly = model.with_(wing_aero=False).assembly()
    dry = assembly.second_order(np.array([V]))
    if dry.n_lag:
        raise v.InputError(f"model = {model.name!r} is invalid for the p-k method: its "
                           "propeller aerodynamics has lag states")
    # the wing's strips, then each further surface's (a tail): (nodes, P (n_strips, 2, n_dof))
    parts = [(p.node_properties(), P) for p, P in assembly.lifting_surfaces()]
    structure = (dry.S1[0], dry.S2[0], dry.S3[0])

    def matrices(omega: float):
        out = [np.array(S, dtype=float) for S in structure]
        for node, P in parts:
            strips = _strip(model.flight.density, V, node["b"], node["a"], node["Cla"],
                            node["ac"], omega)
            for X, A in zip(out, strips):
                X -= np.einsum("sim,sij,sjn->mn", P, node["width"][:, None, None] * A, P)
        return tuple(out)

    return matrices


def pk_matrices(model, V: float, omega: float,
                tables: DlmTables | None = None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(M, C, K) of the p-k equation of `model` at V [m/s] and ω [rad/s] (:func:`pk_system`)."""
    return pk_system(model, V, tables)(omega)
