"""Writing OP2 files of a propwhirl structure's modes for the tests (pyNastran's writer): the
eigenvectors (OUGV1, table code 7, MSC format) with their eigenvalues, and the grids (GEOM1).

pyNastran 1.4.1 writes no eigenvalue table (LAMA: ``skipping table=LAMA``), so the OP2s here
hold mass-normalised eigenvectors (read with ``mass_normalised=True``), and it writes the
eigenvectors and the grids in single precision, as NASTRAN's OP2s are.
"""
from __future__ import annotations

import contextlib
import io
import warnings
from pathlib import Path

import numpy as np

from propwhirl.io.nastran import UNIT_SYSTEMS
from propwhirl.model.modal_structure import ModalStructure


def write_op2(s: ModalStructure, path: Path, units: str = "si", **options) -> Path:
    """``s`` (mass-normalised, SI) as a SOL 103 OP2 in ``units``: :func:`write_op2_arrays`."""
    assert np.allclose(s.modal_mass, 1.0), "mass-normalised modes only"
    return write_op2_arrays(path, s.grid_ids, s.xyz, (2.0 * np.pi * s.frequencies_hz) ** 2,
                            s.shapes, units, **options)


def write_op2_arrays(path: Path, grid_ids, xyz, eigenvalues, shapes, units: str = "si", *,
                     geometry: bool = True, subcases=(1,), cd: dict[int, tuple] | None = None,
                     scalar_points=()) -> Path:
    """Mass-normalised modes (SI: ``shapes`` (n_modes, n_grids, 6) [m, rad] with φᵀMφ = 1 kg,
    ``eigenvalues`` ω² [1/s²], possibly ≈ 0 for rigid-body modes) as a SOL 103 OP2 in
    ``units``: the deck's mass-normalised eigenvectors (translations / length unit, then
    every component × √(mass unit × length unit²): φᵀMφ = 1 in the deck's units), the
    grids' positions (/ length unit).  ``cd``: grid id -> (cid, A, B, C) a CORD2R (basic)
    its components are given in; ``scalar_points``: SPOINT ids added with zero motion."""
    from pyNastran.op2.op2_geom import OP2Geom
    from pyNastran.op2.tables.oug.oug_eigenvectors import RealEigenvectorArray

    from propwhirl.io.nastran_read import cord2r_axes

    u = UNIT_SYSTEMS[units]
    shapes = np.array(shapes, dtype=float)
    n_modes = shapes.shape[0]
    shapes[:, :, :3] /= u.length
    shapes *= np.sqrt(u.mass * u.length ** 2)
    cd = cd or {}
    op2 = OP2Geom(debug=None, log=None)
    op2.set_as_msc()
    ids = [int(i) for i in grid_ids]
    for i, gid in enumerate(ids):
        if gid in cd:                     # components in the CORD2R's axes: v_local = R v
            _, a, b, c = cd[gid]
            R = cord2r_axes(*(np.asarray(p, dtype=float) for p in (a, b, c)))
            shapes[:, i, :3] = shapes[:, i, :3] @ R.T
            shapes[:, i, 3:] = shapes[:, i, 3:] @ R.T
    gridtype = [(gid, 1) for gid in ids] + [(int(p), 2) for p in scalar_points]
    data = np.concatenate([shapes, np.zeros((n_modes, len(scalar_points), 6))], axis=1)
    eig = np.asarray(eigenvalues, dtype=float)
    modes = np.arange(1, n_modes + 1)
    for sc in subcases:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            ev = RealEigenvectorArray.add_modal_case(
                "OUGV1", np.array(gridtype), data, sc, modes, eig,
                np.sqrt(np.abs(eig)) / (2 * np.pi), is_sort1=True, is_msc=True)
        ev.table_code = 7
        op2.eigenvectors[sc] = ev
    if geometry:
        for gid, (cid, a, b, c) in cd.items():
            if cid not in op2.coords:
                op2.add_cord2r(cid, list(a), list(b), list(c))
        for i, gid in enumerate(ids):
            op2.add_grid(gid, list(np.asarray(xyz[i], dtype=float) / u.length),
                         cd=cd[gid][0] if gid in cd else 0)
    chatter = io.StringIO()
    with contextlib.redirect_stdout(chatter), contextlib.redirect_stderr(chatter), \
            warnings.catch_warnings():
        warnings.simplefilter("ignore")
        op2.write_op2(str(path), nastran_format="msc")
    return Path(path)


#: Root components a free structure's root leaves free, by case: the whole aircraft's wing
#: (heave, roll, pitch), a half aircraft's symmetric (heave, pitch) and antisymmetric (roll).
FREE_ROOTS = {"free": (0, 1, 2), "symmetric": (0, 2), "antisymmetric": (1,),
              "plunge-roll": (0, 1)}


def free_free_modes(wing, body_mass: float, body_roll_inertia: float,
                    body_pitch_inertia: float, free: str = "free", body_x: float = 0.0):
    """The modes of a beam wing whose root, instead of being clamped, carries a rigid body
    (a fuselage: mass [kg] on the root's heave, roll inertia [kg m²] on its bending slope φ,
    pitch inertia [kg m²] on its twist α) and is free in the components of
    ``FREE_ROOTS[free]`` (the others held); ``body_x`` [m]: the body's centre of gravity aft
    of the root's elastic axis (its pitch inertia about it: the root's twist carries
    m x² + I, and the heave–twist coupling m x): the beam's own element matrices
    (:func:`propwhirl.model.structure.assembly.wing_structure`), every mode mass-normalised,
    the rigid-body ones at ω² ≈ 0.  Returns (grid ids, xyz [m], ω² [1/s²], shapes
    (n_modes, n_grids, 6) [m, rad] in the wing frame: T_z = −h, R_x = −φ, R_y = α)."""
    import scipy.linalg

    from propwhirl.model.structure.assembly import wing_structure

    M, _, K = wing_structure(wing)
    M = np.array(M, dtype=float)
    M[0, 0] += body_mass
    M[1, 1] += body_roll_inertia
    M[2, 2] += body_pitch_inertia + body_mass * body_x ** 2
    M[0, 2] += body_mass * body_x                # down at x: h + x α
    M[2, 0] += body_mass * body_x
    keep = np.array([i for i in range(M.shape[0]) if i >= 3 or i in FREE_ROOTS[free]])
    w2, X = scipy.linalg.eigh(K[np.ix_(keep, keep)], M[np.ix_(keep, keep)])
    n = w2.size
    full = np.zeros((M.shape[0], n))
    full[keep] = X
    for k in range(n):                           # a sign convention: largest entry positive
        i = int(np.argmax(np.abs(full[:, k])))
        full[:, k] *= np.sign(full[i, k])
    nodal = full.reshape(wing.n_nodes, 3, n)
    shapes = np.zeros((n, wing.n_nodes, 6))
    shapes[:, :, 2] = -nodal[:, 0].T
    shapes[:, :, 3] = -nodal[:, 1].T
    shapes[:, :, 4] = nodal[:, 2].T
    xyz = np.zeros((wing.n_nodes, 3))
    xyz[:, 1] = wing.node_y
    return 1 + np.arange(wing.n_nodes), xyz, w2, shapes


def root_body(wing) -> tuple[float, float, float]:
    """The beam wing's own rigid-body mass [kg], roll and pitch inertia about its root
    [kg m²] (the body's are κ times these)."""
    from propwhirl.model.structure.assembly import wing_structure

    M = wing_structure(wing)[0]
    shapes = np.zeros((3, M.shape[0]))
    shapes[0, 0::3] = 1.0
    shapes[1, 0::3], shapes[1, 1::3] = wing.node_y, 1.0
    shapes[2, 2::3] = 1.0
    return tuple(float(r @ M @ r) for r in shapes)


def free_frequencies(wing, w2: np.ndarray, rigid_below_hz: float):
    """Frequencies [Hz] of the eigenvalues ``w2`` [rad²/s²] (those below ``rigid_below_hz``
    rigid: 0) and the wing's Rayleigh damping ratios at them (0 on the rigid modes)."""
    f = np.sqrt(np.abs(w2)) / (2.0 * np.pi)
    rigid = f < rigid_below_hz
    f = np.where(rigid, 0.0, f)
    w = 2.0 * np.pi * np.where(rigid, 1.0, f)
    mu, lam = wing.rayleigh
    return f, np.where(rigid, 0.0, 0.5 * (mu / w + lam * w))


def free_modal_model(base, kappa: float, free: str = "plunge-roll",
                     rigid_below_hz: float = 0.1):
    """The modal model of ``base`` (a one-propeller PropellerWing, mount "own") with its wing
    on a root body of κ times the wing's mass and inertias (:func:`free_free_modes`), free in
    ``FREE_ROOTS[free]``, every mode kept (``ModalStructure(free=True)``): the rigid-body ones
    (below ``rigid_below_hz``) at 0 Hz undamped, the elastic ones with the base wing's
    Rayleigh damping; the strips the base wing's.  Returns (model, number of rigid modes)."""
    from propwhirl.model.modal import ModalInstallation, ModalPropellerWing
    from propwhirl.model.modal_structure import StripPlanform

    mass, roll, pitch = root_body(base.wing)
    ids, xyz, w2, shapes = free_free_modes(base.wing, kappa * mass, kappa * roll,
                                           kappa * pitch, free)
    f, zeta = free_frequencies(base.wing, w2, rigid_below_hz)
    s = ModalStructure(grid_ids=ids, xyz=xyz, frequencies_hz=f, modal_mass=np.ones(f.size),
                       damping_ratio=zeta, shapes=shapes, free=True,
                       source=f"{free} root body, kappa {kappa:g}")
    inst = tuple(ModalInstallation(i.propeller, int(ids[n]), i.mount, i.aero)
                 for i, n in zip(base.propellers, base.nodes))
    model = ModalPropellerWing(s, [int(g) for g in ids], StripPlanform.from_wing(base.wing),
                               base.flight, inst, wing_aero=base.wing_aero,
                               propeller_aero=base.propeller_aero, rotating=base.rotating)
    return model, int(np.count_nonzero(f == 0.0))


#: The horizontal tail of the free-body cases (a half aircraft's, on a rigid arm from the root
#: body): its aerodynamic centre ``arm`` [m] aft of the body's centre of gravity, semi-span
#: [m], chord [m], strips, grids; the body's pitch radius of gyration [m] (its pitch inertia
#: κ m_wing r_y²) and its centre of gravity ``body_x`` [m] aft of the wing's elastic axis
#: (-0.25: the mean chord's quarter point, where an aircraft's centre of gravity usually is).
TAIL = dict(arm=3.5, semi_span=1.2, chord=0.7, n_strips=6, n_grids=5, radius_of_gyration=1.4,
            body_x=-0.25)


def tail_surface(x_ac: float, first_id: int = 101, aero_model: str = "leishman-nguyen"):
    """The :data:`TAIL`'s grids' positions (n_grids, 3) [m] (its reference axis along y at
    x = ``x_ac``, from the plane of symmetry) and its :class:`ModalSurface` (unswept strips,
    the aerodynamic centre and the reference axis at the quarter chord, C_lα = 2π)."""
    from propwhirl.model.modal_structure import StripPlanform
    from propwhirl.model.modal_surface import ModalSurface

    n, ns, b, c = TAIL["n_grids"], TAIL["n_strips"], TAIL["semi_span"], TAIL["chord"]
    xyz = np.zeros((n, 3))
    xyz[:, 0], xyz[:, 1] = x_ac, np.linspace(0.0, b, n)
    w = b / ns
    one = np.ones(ns)
    planform = StripPlanform(y=(np.arange(ns) + 0.5) * w, width=w * one, chord=c * one,
                             leading_edge_x=(x_ac - 0.25 * c) * one, elastic_axis=0.25 * one,
                             aerodynamic_centre=0.25 * one, lift_slope=2.0 * np.pi * one,
                             aero_model=aero_model, source="tail strips")
    return xyz, ModalSurface(grids=tuple(first_id + np.arange(n)), planform=planform)


def tailed_modal_model(base, kappa: float, arm: float = TAIL["arm"], tail: bool = True,
                       rigid_below_hz: float = 0.1):
    """The modal model of ``base`` (a one-propeller PropellerWing) on a root body free in
    plunge, roll and pitch (:func:`free_free_modes`, ``"free"``) of κ times the wing's mass
    and roll inertia, pitch inertia κ m_wing r_y² (:data:`TAIL`), with a horizontal tail on
    a rigid arm: its grids ``arm`` [m] aft of the body's centre of gravity (negative: ahead),
    moving with the body in every mode (the root grid's rigid motion, T_z = T_z0 + R_x0 y −
    R_y0 x, the rotations the root's), its strips a second lifting surface (``tail`` False:
    the grids without the surface).  The rigid-body modes below ``rigid_below_hz`` at 0 Hz
    undamped; the elastic ones with the base wing's Rayleigh damping.  Returns (model, number
    of rigid modes)."""
    from propwhirl.model.modal import ModalInstallation, ModalPropellerWing
    from propwhirl.model.modal_structure import StripPlanform

    mass, roll, _ = root_body(base.wing)
    pitch = kappa * mass * TAIL["radius_of_gyration"] ** 2
    x_b = TAIL["body_x"]
    ids, xyz, w2, shapes = free_free_modes(base.wing, kappa * mass, kappa * roll, pitch, "free",
                                           x_b)
    txyz, surface = tail_surface(x_b + arm, first_id=int(ids[-1]) + 100,
                                 aero_model=base.wing.aero_model)
    root = shapes[:, 0, :]                        # the root grid, at the origin
    moves = np.zeros((shapes.shape[0], txyz.shape[0], 6))
    moves[:, :, 2] = (root[:, 2:3] + root[:, 3:4] * txyz[None, :, 1]
                      - root[:, 4:5] * txyz[None, :, 0])
    moves[:, :, 3:] = root[:, None, 3:]
    f, zeta = free_frequencies(base.wing, w2, rigid_below_hz)
    s = ModalStructure(grid_ids=np.concatenate([ids, np.array(surface.grids)]),
                       xyz=np.concatenate([xyz, txyz]), frequencies_hz=f,
                       modal_mass=np.ones(f.size), damping_ratio=zeta,
                       shapes=np.concatenate([shapes, moves], axis=1), free=True,
                       source=f"tailed root body, kappa {kappa:g}")
    inst = tuple(ModalInstallation(i.propeller, int(ids[n]), i.mount, i.aero)
                 for i, n in zip(base.propellers, base.nodes))
    model = ModalPropellerWing(s, [int(g) for g in ids], StripPlanform.from_wing(base.wing),
                               base.flight, inst, wing_aero=base.wing_aero,
                               propeller_aero=base.propeller_aero, rotating=base.rotating,
                               surfaces=(surface,) if tail else ())
    return model, int(np.count_nonzero(f == 0.0))


def centre_of_gravity_x(model) -> float:
    """x [m] of the centre of gravity of a free modal model with a rigid plunge and pitch:
    from its structural mass (modes and propellers, :meth:`ModalAssembly.second_order`'s
    S1 with the aerodynamics off) on the rigid plunge q_h (T_z = 1 m at every grid) and
    pitch q_θ (R_y = 1 rad about x = 0, T_z = −x) in its rigid-body coordinates:
    x_cg = −q_hᵀ M q_θ / q_hᵀ M q_h."""
    s = model.structure
    rigid = [i for i, _ in s.rigid_body_modes()]
    Phi = s.shapes[rigid].reshape(len(rigid), -1).T          # (6 n_grids, n_rigid)
    M = model.without_aerodynamics().second_order(np.array([1.0])).S1[0]
    q = []
    for shape in ("plunge", "pitch"):
        u = np.zeros((s.grid_ids.size, 6))
        u[:, 2] = 1.0 if shape == "plunge" else -s.xyz[:, 0]
        if shape == "pitch":
            u[:, 4] = 1.0
        x = np.zeros(M.shape[0])
        x[rigid] = np.linalg.lstsq(Phi, u.reshape(-1), rcond=None)[0]
        q.append(x)
    return float(-(q[0] @ M @ q[1]) / (q[0] @ M @ q[0]))
