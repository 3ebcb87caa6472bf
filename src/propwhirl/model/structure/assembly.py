"""Assembly of global matrices from generated element functions (index arithmetic, no loops).

Global wing degrees of freedom (7.20): node i contributes [h_i, φ_i, α_i] at indices 3i..3i+2,
node 0 is the clamped root.  Element e couples nodes e and e+1, i.e. global indices 3e..3e+5,
the order of the generated element matrices ([h1, φ1, α1, h2, φ2, α2]).

With in-plane bending (``wing.EI_chordwise`` given) the in-plane DOFs [v_i, χ_i] of every node
follow all of these, at 3N + 2i, 3N + 2i + 1 (N nodes): the bending–torsion indices, the strip
aerodynamics and everything built on them are those of the model without in-plane bending.
"""
from __future__ import annotations

import functools

import numpy as np

from propwhirl import validate as v
from propwhirl.generated import beam_element, beam_inplane, strip_aero
from propwhirl.model.aerodynamics.compressibility import (
    is_compressible,
    lift_slope_factor,
    lift_slopes,
)
from propwhirl.model.structure.wing import Wing

WING_DOF_NAMES = ("h", "phi", "alpha")
#: in-plane DOFs of a node (derivations/beam_inplane.py): displacement v, slope χ = ∂v/∂y
INPLANE_DOF_NAMES = ("v", "chi")


def element_dofs(n_elements: int) -> np.ndarray:
    """Global indices (n_elements, 6) of each element's degrees of freedom."""
    return 3 * np.arange(n_elements)[:, None] + np.arange(6)[None, :]


def scatter(blocks: np.ndarray, dofs: np.ndarray, size: int) -> np.ndarray:
    """Sum element blocks (..., n_el, k, k) into global matrices (..., size, size).

    One `np.add.at` over all leading indices, elements and entries (overlapping element
    degrees of freedom add up, as in standard finite-element assembly).
    """
    lead = blocks.shape[:-3]
    nlead = int(np.prod(lead)) if lead else 1
    b = blocks.reshape((nlead,) + blocks.shape[-3:])
    lin = dofs[:, :, None] * size + dofs[:, None, :]  # (n_el, k, k) flat global index
    out = np.zeros((nlead, size * size))
    np.add.at(out, (np.arange(nlead)[:, None, None, None], lin[None]), b)
    return out.reshape(lead + (size, size))


def wing_structure(wing: Wing) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Global structural mass, damping and stiffness of the free wing (root included).

    Mass and stiffness from the generated beam element (7.9–7.15, assembled as in (C.18)),
    each element with its own length (non-uniform meshes, :mod:`propwhirl.model.structure.mesh`);
    damping by the Rayleigh model C = μM + λK (7.22).  Shapes (3 n_nodes, 3 n_nodes).
    """
    p = wing.element_properties()
    blocks = call_blocks(beam_element, "blocks", (wing.element_count,), **p)
    Me, Ke = blocks["mass"], blocks["stiffness"]
    size = 3 * wing.n_nodes
    dofs = element_dofs(wing.element_count)
    M = scatter(Me, dofs, size)
    K = scatter(Ke, dofs, size)
    mu, lam = wing.rayleigh
    return M, mu * M + lam * K, K


def inplane_structure(wing: Wing) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Global in-plane mass, damping and stiffness of the free wing over [v_i, χ_i] of every
    node (root included), shapes (2 n_nodes, 2 n_nodes); the generated in-plane element
    (derivations/beam_inplane.py) assembled as the bending one, Rayleigh damping μM + λK with
    the wing's (μ, λ).  The wing must have ``EI_chordwise``."""
    p = wing.inplane_properties()
    if p is None:
        raise ValueError("inplane_structure: the wing has no EI_chordwise")
    blocks = call_blocks(beam_inplane, "inplane_blocks", (wing.element_count,), **p)
    dofs = 2 * np.arange(wing.element_count)[:, None] + np.arange(4)[None, :]
    size = 2 * wing.n_nodes
    M = scatter(blocks["inplane_mass"], dofs, size)
    K = scatter(blocks["inplane_stiffness"], dofs, size)
    mu, lam = wing.rayleigh
    return M, mu * M + lam * K, K


@functools.lru_cache(maxsize=64)
def inplane_dof_labels(n_nodes: int) -> tuple[str, ...]:
    """Labels 'node i v' / 'node i chi' of the in-plane DOFs of all nodes (root = node 0)."""
    return tuple(f"node {i} {d}" for i in range(n_nodes) for d in INPLANE_DOF_NAMES)


def free_dofs(n_nodes: int) -> np.ndarray:
    """Indices of the unconstrained wing degrees of freedom (root node clamped)."""
    return np.arange(3, 3 * n_nodes)


@functools.lru_cache(maxsize=64)
def wing_dof_labels(n_nodes: int) -> tuple[str, ...]:
    """Labels 'node i h' / 'node i phi' / 'node i alpha' for all wing DOFs (root = node 0)."""
    return tuple(f"node {i} {d}" for i in range(n_nodes) for d in WING_DOF_NAMES)


def place(blocks: np.ndarray, rows: np.ndarray, cols: np.ndarray, shape: tuple[int, int]) -> np.ndarray:
    """Put non-overlapping blocks (..., nb, r, c) at global rows (nb, r) and cols (nb, c)."""
    out = np.zeros(blocks.shape[:-3] + shape)
    out[..., rows[:, :, None], cols[:, None, :]] = blocks
    return out


LAG_STATES = {"leishman-nguyen": 2, "wagner": 4}

#: Strip aerodynamics of each model: the generated block function and, per role of
#: Q_W = M q̈ + C q̇ + K q + W0 w, ẇ = Ww w + Wv q̇ + Wq q, the generated matrix (Wagner has no Wv).
#: Its parameter derivatives are the block function with the suffix ``_d``
#: (:mod:`propwhirl.model.derivatives`).
STRIP_AERO: dict[str, tuple[str, dict[str, str]]] = {
    "leishman-nguyen": ("ln_blocks", dict(M="ln_M", C="ln_C", K="ln_K", W0="ln_W0", Ww="ln_W1",
                                          Wv="ln_W2", Wq="ln_W3")),
    "wagner": ("wagner_blocks", dict(M="wagner_M", C="wagner_C", K="wagner_K", W0="wagner_W0",
                                     Ww="wagner_W2", Wq="wagner_W1")),
}


def call_blocks(module, name: str, shape: tuple[int, ...], **values) -> dict[str, np.ndarray]:
    """Call generated block function `name` — the matrices of one group in one call, common
    subexpressions computed once — with the arguments it takes (picked from `values` by name,
    per the module's BLOCKS table); each matrix broadcast to `shape` + its matrix shape."""
    argnames = module.BLOCKS[name][0]
    out = getattr(module, name)(**{a: values[a] for a in argnames})
    return {k: x if x.shape[:-2] == shape else np.broadcast_to(x, shape + x.shape[-2:])
            for k, x in out.items()}


def wing_aero_blocks(wing: Wing, rho: float, V: np.ndarray, speed_of_sound: float | None = None
                     ) -> dict[str, np.ndarray | tuple[str, ...]]:
    """Strip-aerodynamic blocks of every node (root included), before placement.

    The section loads of the generated strip-aerodynamics module (per unit span, §7.2, §7.5)
    act at the nodes, each multiplied by the node's tributary strip width (C.38–C.52, D.1–D.16);
    each node carries its own lag states (2 Leishman–Nguyen or 4 Wagner).  Returns, for the
    speeds V (nV,): "Ma", "Ca", "Ka" (nV, nn, 2, 2) on each node's [h, α] with
    Q_W = Ma q̈ + Ca q̇ + Ka q + W0 w; "W0" (nV, nn, 2, k); "Ww" (nV, nn, k, k); "Wv", "Wq"
    (nV, nn, k, 2) of ẇ = Ww w + Wv q̇ + Wq q; "qrows" (nn, 2) and "wrows" (nn, k), the global
    indices of each node's [h, α] and lag states; "m" the number of lag states; "labels".
    With the wing's ``compressibility = "prandtl-glauert"`` every slope is C_lα/β at the Mach
    of its ``strip_mach`` (V / ``speed_of_sound`` [m/s] when matched):
    :mod:`propwhirl.model.aerodynamics.compressibility`.
    """
    factor = lift_slope_factor(wing, V, _speed_of_sound(wing, speed_of_sound))
    return strip_aero_blocks(wing.node_properties(), wing.aero_model, rho, V, factor)


def _speed_of_sound(wing, speed_of_sound: float | None) -> float:
    """The speed of sound [m/s] a matched Prandtl–Glauert wing needs (NaN when not needed)."""
    if speed_of_sound is None:
        if is_compressible(wing) and isinstance(wing.strip_mach, str):
            raise v.InputError(
                f"wing {wing.name!r}: compressibility = \"prandtl-glauert\" with strip_mach = "
                "\"speed\" needs the flight's speed of sound (pass speed_of_sound [m/s])")
        return float("nan")
    return float(speed_of_sound)


def strip_aero_blocks(node: dict[str, np.ndarray], aero_model: str, rho: float,
                      V: np.ndarray, factor: np.ndarray | None = None
                      ) -> dict[str, np.ndarray | tuple[str, ...]]:
    """:func:`wing_aero_blocks` of any strips: ``node`` holds per strip its width [m], b
    (semichord) [m], a and ac (elastic axis and aerodynamic centre, semichords aft of
    mid-chord) and Cla [1/rad] (the keys of :meth:`Wing.node_properties`); ``aero_model`` a key
    of :data:`LAG_STATES`.  The wing's strips, or a modal model's
    (:mod:`propwhirl.model.modal`); "qrows"/"wrows" index the strips in order as nodes.
    ``factor`` (nV,): the lift-curve slopes' compressibility factor 1/β at each speed
    (:func:`~propwhirl.model.aerodynamics.compressibility.lift_slope_factor`), None: the
    slopes as given."""
    nn = len(node["b"])
    k = LAG_STATES[aero_model]
    Vc = np.asarray(V, dtype=float)[:, None]
    values = dict(rho=rho, V=Vc, b=node["b"], a=node["a"], Cla=lift_slopes(node["Cla"], factor),
                  ac=node["ac"])
    shape = (Vc.shape[0], nn)
    width = node["width"][None, :, None, None]
    group, names = STRIP_AERO[aero_model]
    blocks = call_blocks(strip_aero, group, shape, **values)
    mats = {role: blocks[fn] for role, fn in names.items()}
    M, C, K, W0, Ww, Wq = (mats[r] for r in ("M", "C", "K", "W0", "Ww", "Wq"))
    Wv = mats.get("Wv", np.zeros_like(Wq))
    qrows, wrows, labels = _strip_layout(nn, k)
    return {
        "Ma": width * M, "Ca": width * C, "Ka": width * K, "W0": width * W0,
        "Ww": Ww, "Wv": Wv, "Wq": Wq, "qrows": qrows, "wrows": wrows, "m": k * nn,
        "labels": labels,
    }


@functools.lru_cache(maxsize=64)
def _strip_layout(nn: int, k: int) -> tuple[np.ndarray, np.ndarray, tuple[str, ...]]:
    """Global indices of each node's [h, α] (nn, 2) and lag states (nn, k), and the lag-state
    labels, of a wing of ``nn`` nodes with ``k`` lag states per node (read-only: shared by
    every evaluation)."""
    qrows = 3 * np.arange(nn)[:, None] + np.array([0, 2])[None, :]      # h_i, α_i
    wrows = k * np.arange(nn)[:, None] + np.arange(k)[None, :]
    qrows.flags.writeable = wrows.flags.writeable = False
    return qrows, wrows, tuple(f"node {i} w{j + 1}" for i in range(nn) for j in range(k))


def wing_aero(wing: Wing, rho: float, V: np.ndarray, speed_of_sound: float | None = None
              ) -> dict[str, np.ndarray | tuple[str, ...]]:
    """Global strip-aerodynamic matrices of the wing over all nodes (root included).

    :func:`wing_aero_blocks` placed: Ma, Ca, Ka (nV, 3N, 3N) with
    Q_W = Ma q̈ + Ca q̇ + Ka q + W0 w, the state equation ẇ = Ww w + Wv q̇ + Wq q, and the
    lag-state labels (``speed_of_sound`` [m/s]: for a matched Prandtl–Glauert wing).
    """
    b = wing_aero_blocks(wing, rho, V, speed_of_sound)
    nq, m, qrows, wrows = 3 * wing.n_nodes, b["m"], b["qrows"], b["wrows"]
    return {
        "Ma": place(b["Ma"], qrows, qrows, (nq, nq)),
        "Ca": place(b["Ca"], qrows, qrows, (nq, nq)),
        "Ka": place(b["Ka"], qrows, qrows, (nq, nq)),
        "W0": place(b["W0"], qrows, wrows, (nq, m)),
        "Ww": place(b["Ww"], wrows, wrows, (m, m)),
        "Wv": place(b["Wv"], wrows, qrows, (m, nq)),
        "Wq": place(b["Wq"], wrows, qrows, (m, nq)),
        "labels": b["labels"],
    }


# ----------------------------------------------------------------------------- diagnosis
_ROLE_INDEX = {"S1": (0, "mass"), "S2": (1, "damping"), "S3": (2, "stiffness")}


def _badness(mats, k: int, r: int, c: int, ratio: bool) -> float:
    """Orders of magnitude of entry (r, c) of matrix k (over the mass diagonal if `ratio`)
    away from 1: |log10 |x||, inf where it is not finite."""
    x = abs(float(np.asarray(mats[k])[0, r, c]))
    if ratio:
        x = x / abs(float(np.asarray(mats[0])[0, r, r]))
    if not np.isfinite(x) or x == 0.0:
        return np.inf
    return abs(float(np.log10(x)))


def blame_entry(contributions, err) -> str | None:
    """Which block and model parameter make the state-matrix entry of `err` bad.

    `contributions`: (label, global DOF labels, evaluate(values) -> (M, C, K), values, units)
    of each block of a model at the one failing speed; `err`: a
    :class:`~propwhirl.model.statespace.StateMatrixError` (matrix, row, col).  The block
    containing the entry whose value there is furthest from 1 (in orders of magnitude, a
    non-finite one first) is the culprit; within it, the argument whose replacement by 1 (sign
    kept) brings the entry back by the most — at least three orders of magnitude, or to a
    finite value — is named with its value.  Returns e.g. "propeller 1: K_theta =
    3.2e+305 N m/rad makes its stiffness block far too large (…)", or None.
    """
    matrix = err.matrix.split()[-1]
    if matrix not in _ROLE_INDEX:
        return None
    k, role = _ROLE_INDEX[matrix]
    ratio = err.matrix.startswith("S1^-1")
    found = []
    for label, dofs, evaluate, values, units in contributions:
        for row, col in err.entries:
            if row in dofs and col in dofs:
                r, c = dofs.index(row), dofs.index(col)
                found.append((_badness(evaluate(values), k, r, c, ratio), label, evaluate,
                              values, units, r, c))
    if not found:
        return None
    base, label, evaluate, values, units, r, c = max(found, key=lambda f: f[0])
    best, cause = 3.0, None
    for name, x in values.items():
        if isinstance(x, (bool, np.bool_)) or not isinstance(x, (int, float, np.ndarray)):
            continue
        arr = np.asarray(x, dtype=float)
        trial = dict(values)
        trial[name] = np.where(arr < 0, -1.0, 1.0) if arr.ndim else (-1.0 if arr < 0 else 1.0)
        gain = base - _badness(evaluate(trial), k, r, c, ratio)
        if gain > best or (np.isinf(base) and gain == np.inf and cause is None):
            best, cause = gain, name
    entry = np.asarray(evaluate(values)[k], dtype=float)[0, r, c]
    if ratio:
        entry = entry / np.asarray(evaluate(values)[0], dtype=float)[0, r, r]
    what = ("non-finite" if np.isinf(base) else
            "far too large" if abs(entry) > 1 else "far too small")
    if cause is None:
        return f"{label} makes its {role} block {what} ({err})"
    val = float(np.ravel(np.asarray(values[cause], dtype=float))[0])
    unit = units.get(cause, "")
    return (f"{label}: {cause} = {val:.3g}{' ' + unit if unit else ''} makes its {role} block "
            f"{what} ({err})")
