"""A free structure's rigid-body modes: what each is, and which a model may keep (issue 36).

A free structure's (a whole or half aircraft's) modes below
:data:`~propwhirl.model.modal_structure.RIGID_BODY_HZ` are rigid-body modes.  Each is
classified from its six components at the grids (:func:`rigid_body_kind`) and, when kept, taken
as its exactly rigid fit (:func:`rigid_shape`).  Which freedoms a model admits is decided here,
in one place:

* **the wing alone** — plunge and roll (:data:`KEPT_RIGID_BODY` without a tail): the strips'
  lift damps both (their velocity changes the angle of attack, their displacement does not);
* **with a tail** (a second lifting surface,
  :class:`~propwhirl.model.modal_surface.ModalSurface`) — plunge, roll and **pitch**: a rigid
  pitch needs the lift of a surface behind the centre of gravity to be statically stable, and
  with the wing alone (its aerodynamic centre ahead of any sensible centre of gravity) it is
  statically unstable by construction: its divergence would be the missing tail's, so a pitch
  without a tail is refused (:func:`check_rigid_freedoms`), never analysed;
* **never** — yaw (it needs a fin, a vertical lifting surface, which the strips do not model),
  surge and sway (the strips give an in-plane rigid translation no force: a neutral root), and
  a "mechanism" (no rigid motion of the grids).
"""
from __future__ import annotations

import numpy as np

from propwhirl import validate as v

#: Rigid-body modes a free structure may keep: plunge and roll with the wing alone, pitch too
#: with a tail (:func:`check_rigid_freedoms`; module docstring).
KEPT_RIGID_BODY = ("plunge", "roll", "pitch")
#: Those a model with the wing alone admits (no second lifting surface).
WING_ALONE = ("plunge", "roll")
#: Share of a rigid-body mode's largest motion below which a freedom is counted absent.
RIGID_SHARE = 1e-4
#: Residual of the rigid-body fit (relative) above which a mode is no rigid-body motion.
RIGID_FIT = 1e-3
#: Why a wing-alone model refuses a rigid pitch (:func:`check_rigid_freedoms`).
NO_TAIL = ("a wing alone has no tail, so a rigid pitch is statically unstable by construction "
           "and its divergence would be the missing tail's, not the wing's; add a tail: a "
           "second lifting surface on grids that move with the body (surfaces = "
           "(ModalSurface(grids=..., planform=StripPlanform(...)),); a modal model file's "
           "[[surfaces]]), or hold pitch (its SPC; or leave the rigid-body modes out: "
           "read_op2(free=True) without keep_rigid, the heavy-body limit)")
_REFUSED_RIGID = {
    "yaw": "a rigid yaw needs a fin (a vertical lifting surface) to be statically stable, and "
           "propwhirl's strips are horizontal surfaces only (a wing, a tail): hold yaw (its "
           "SPC; a symmetric half aircraft has none) or leave the rigid-body modes out",
    "surge": "the strips give an in-plane rigid translation no force (a neutral root): "
             "hold it in the FE model or leave it out",
    "mechanism": "its shape is no rigid-body motion of the grids (a mechanism of the FE "
                 "model): remove it",
}
_REFUSED_RIGID["pitch and yaw"] = _REFUSED_RIGID["yaw"]
_REFUSED_RIGID["sway"] = _REFUSED_RIGID["surge"]


def refusal(kind: str) -> str | None:
    """Why a free structure refuses a rigid-body mode of ``kind`` whatever its surfaces (None:
    one of :data:`KEPT_RIGID_BODY`, a pitch subject to :func:`check_rigid_freedoms`)."""
    return None if kind in KEPT_RIGID_BODY else _REFUSED_RIGID.get(kind, _REFUSED_RIGID["yaw"])


def check_rigid_freedoms(structure, n_surfaces: int) -> None:
    """Refuse a structure's rigid pitch when the model has no lifting surface besides the wing
    (``n_surfaces`` = 0; module docstring): one line naming the mode and what to do."""
    if n_surfaces:
        return
    for i, kind in structure.rigid_body_modes():
        if kind not in WING_ALONE:
            raise v.InputError(f"{structure.source}: mode {i + 1} "
                               f"({structure.frequencies_hz[i]:.3g} Hz) is a rigid-body "
                               f"{kind}: {NO_TAIL}")


def _rigid_fit(xyz: np.ndarray, shape: np.ndarray):
    """(x = [t, θ], A, L, residual ok) of the least-squares rigid motion of
    :func:`rigid_body_kind` (A maps x to the grids' [T, L R] stacked)."""
    xyz = np.asarray(xyz, dtype=float)
    u = np.asarray(shape, dtype=float)
    r = xyz - xyz.mean(axis=0)
    L = max(1.0, float(np.max(np.linalg.norm(r, axis=1))))
    n = xyz.shape[0]
    A = np.zeros((n, 6, 6))
    A[:, :3, :3] = np.eye(3)
    zero = np.zeros(n)                  # θ × r = −r × θ: the skew matrix of r, negated
    A[:, :3, 3:] = np.stack([np.stack([zero, r[:, 2], -r[:, 1]], -1),
                             np.stack([-r[:, 2], zero, r[:, 0]], -1),
                             np.stack([r[:, 1], -r[:, 0], zero], -1)], axis=1)
    A[:, 3:, 3:] = L * np.eye(3)
    b = np.concatenate([u[:, :3], L * u[:, 3:]], axis=1).reshape(6 * n)
    A = A.reshape(6 * n, 6)
    x = np.linalg.lstsq(A, b, rcond=None)[0]
    return x, A, L, bool(np.linalg.norm(A @ x - b) <= RIGID_FIT * np.linalg.norm(b))


def rigid_body_kind(xyz: np.ndarray, shape: np.ndarray) -> str:
    """What rigid-body motion a mode shape is, from its six components at the grids.

    The rule: the grids' motion is fitted (least squares) by a rigid motion about the grids'
    centroid c, T_g = t + θ × (x_g − c) and R_g = θ at every grid g, the rotations weighted
    by the grids' largest distance L from c (at least 1 m); a residual over
    :data:`RIGID_FIT` of the motion is a "mechanism".  Of the freedoms' sizes — the
    translations |t_x|, |t_y|, |t_z| and the rotations L |θ_x|, L |θ_y|, L |θ_z| — those over
    :data:`RIGID_SHARE` of the largest are present.  A rotation about y is a "pitch", about
    z a "yaw" ("pitch and yaw" both); a rotation about x alone is a "roll" — about an axis
    along x through any point, so its translation across x (y, z) only places the axis — but
    with a translation along x a "surge"; without rotation a translation along z is a
    "plunge", along x a "surge", along y a "sway" (the first that applies, in this order:
    "mechanism", "pitch and yaw", "pitch", "yaw", "surge", "roll", "sway", "plunge").

    Parameters
    ----------
    xyz : ndarray
        (n_grids, 3) grid positions [m] (x aft, y outboard, z up).
    shape : ndarray
        (n_grids, 6) the mode's [T_x, T_y, T_z, R_x, R_y, R_z] [m, rad].
    """
    x, _, L, ok = _rigid_fit(xyz, shape)
    if not ok:
        return "mechanism"
    size = np.abs(x) * np.array([1, 1, 1, L, L, L])
    on = size > RIGID_SHARE * size.max()
    if on[4] and on[5]:
        return "pitch and yaw"
    if on[4] or on[5]:
        return "pitch" if on[4] else "yaw"
    if on[0]:
        return "surge"
    if on[3]:
        return "roll"
    return "sway" if on[1] else "plunge"


def rigid_shape(xyz: np.ndarray, shape: np.ndarray) -> np.ndarray:
    """(n_grids, 6) a kept rigid-body mode (:data:`KEPT_RIGID_BODY`) as its fit
    (:func:`rigid_body_kind`) at the grids, exactly rigid [m, rad]: a plunge or roll
    T_y = t_y − θ_x (z − c_z), T_z = t_z + θ_x (y − c_y), R_x = θ_x, the rest 0 (t_y only with
    a roll: the height of its axis); a pitch (a rotation θ_y about y present) keeps t_x and
    θ_y too (T_x = t_x + θ_y (z − c_z), T_z − θ_y (x − c_x), R_y = θ_y; t_x the height of its
    axis), never a yaw.  A free structure's kept rigid-body modes are taken so: the fit's
    residual (an eigensolver's rounding, below :data:`RIGID_FIT`) and its freedoms below
    :data:`RIGID_SHARE` would otherwise be a spurious aerodynamic stiffness on a coordinate
    that has none (a twist of 1e-11 rad on the plunge gave a real root of +7e-7 1/s: a false
    divergence)."""
    x, A, L, _ = _rigid_fit(xyz, shape)
    keep = np.zeros(6)
    keep[1:4] = x[1:4]
    if rigid_body_kind(xyz, shape) == "pitch":
        keep[0], keep[4] = x[0], x[4]
    out = (A @ keep).reshape(-1, 6)
    out[:, 3:] /= L
    return out


def one_pitch(xyz: np.ndarray, shapes: np.ndarray, modal_mass: np.ndarray, rigid
              ) -> tuple[np.ndarray, np.ndarray]:
    """(shapes, modal masses), copies: the rigid-body modes ``rigid`` (indices) with the pitch
    in one of them.  An eigensolver returns any mass-orthonormal basis of the rigid-body modes
    (all at ω = 0), so a pitch is usually spread over several, each a plunge or roll with some
    pitch; the coordinate that keeps the aircraft's altitude (and roll angle) then has no
    stiffness only to rounding, and its root, ±1e-12 1/s instead of 0, flickers across zero as
    false divergences.  So where two or more carry a pitch, the basis is turned (a Householder
    reflection H of the rigid modes scaled to unit modal mass: Mᵣ = I and Kᵣ = 0 stay so) to
    put the whole pitch θ_y in the one that carried most; the others are then plunges and
    rolls whose exact fits (:func:`rigid_shape`) have no twist at all.  Their modal masses
    become 1 kg.  Idempotent: one pitch already, nothing changes."""
    shapes, mass = np.array(shapes, dtype=float), np.array(modal_mass, dtype=float)
    rigid = np.asarray(rigid, dtype=int)
    if rigid.size < 2:
        return shapes, mass
    unit = shapes[rigid] / np.sqrt(mass[rigid])[:, None, None]
    pitch = np.array([_rigid_fit(xyz, u)[0][4] for u in unit])
    size = np.abs(pitch)
    if np.count_nonzero(size > RIGID_SHARE * size.max()) < 2:
        return shapes, mass
    k = int(np.argmax(size))
    u = pitch.copy()
    u[k] += np.copysign(np.linalg.norm(pitch), pitch[k])
    H = np.eye(rigid.size) - 2.0 * np.outer(u, u) / (u @ u)
    shapes[rigid] = np.einsum("ij,jgc->igc", H, unit)
    mass[rigid] = 1.0
    return shapes, mass
