"""Lifting surfaces of a modal model besides its wing: a tail's strips (issue 36, item 4).

A free body needs aerodynamics on every surface that holds it.  With the wing alone a rigid
pitch is statically unstable by construction (:mod:`propwhirl.model.rigid_body`), so a
:class:`~propwhirl.model.modal.ModalPropellerWing` takes further lifting surfaces,
``surfaces = (ModalSurface(grids=..., planform=StripPlanform(...)),)``: each a
:class:`ModalSurface`, strips (:class:`~propwhirl.model.modal_structure.StripPlanform`)
splined to its own reference-axis grids by the wing's rule
(:func:`~propwhirl.model.modal_structure.strip_interpolation`), its loads the same generated
strip aerodynamics as the wing's (:func:`propwhirl.model.structure.assembly.strip_aero_blocks`,
:func:`strip_system`), its lag states labelled ``"<name> strip s w r"`` ("tail strip 1 w1").
A tail on a rigid arm is a surface whose grids move with the body (their six components the
body's rigid motion in every mode, as a FE model's grids on a rigid fuselage beam or an RBE2
give them).

What the strips are not: the tail sees the free stream, no downwash from the wing
(dε/dα = 0, which overstates a real tail's effectiveness by 1/(1 − dε/dα), typically 1.5–2:
a designer may put (1 − dε/dα) into its ``lift_slope``) and no fuselage; a fin (a vertical
surface) is none of them — the strips' normal is z — so a rigid yaw stays refused.

:func:`neutral_point` is the steady neutral-point estimate of the strips (every surface's lift
at its aerodynamic centres, no downwash): a free pitch is statically stable when the centre of
gravity is ahead of it (a positive static margin).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from propwhirl import validate as v
from propwhirl.model.modal_structure import (ModalStructure, StripPlanform, check_strip_sweep,
                                            strip_interpolation)
from propwhirl.model.structure.assembly import LAG_STATES, strip_aero_blocks

#: Most surfaces a model takes besides its wing (a tail, a canard, a second tail...).
MAX_SURFACES = 8


def grid_ids(name: str, grids) -> tuple[int, ...]:
    """``grids`` as a tuple of grid ids; an InputError naming ``name`` unless it is a sequence
    (or 1-D integer array) of integers."""
    arr = np.asarray(grids, dtype=object) if isinstance(grids, (tuple, list, np.ndarray)) \
        else None
    if arr is None or arr.ndim != 1 or not all(
            isinstance(g, (int, np.integer)) and not isinstance(g, (bool, np.bool_))
            for g in arr):
        raise v.InputError(f"{name} = {v.short_repr(grids)} is invalid: must be a sequence of "
                           "grid ids (integers)")
    return tuple(int(g) for g in arr)


@dataclass(frozen=True, eq=False)
class ModalSurface:
    """A lifting surface of a modal model besides its wing (a horizontal tail): strips splined
    to its own grids (module docstring).

    Parameters
    ----------
    grids : tuple of int
        Ids of its reference-axis grids in the model's
        :class:`~propwhirl.model.modal_structure.ModalStructure`, root to tip (y increasing),
        at least 2; its strips lie within their span.
    planform : StripPlanform
        Its strips (stations y [m], widths [m], chords [m], leading-edge x [m], elastic axis
        and aerodynamic centre [fraction of the chord], lift slopes [1/rad]) in the modes'
        frame; an unswept surface (its grids' line within
        :data:`~propwhirl.model.modal_structure.STRIP_SWEEP_LIMIT_DEG`).
    name : str
        Its name, the first word of its lag states' labels ("tail strip 1 w1"): letters,
        digits, "-" or "_", not "strip", "mode" or "propeller".

    Examples
    --------
    >>> from propwhirl.model.modal_structure import StripPlanform
    >>> from propwhirl.model.modal_surface import ModalSurface
    >>> tail = ModalSurface(grids=(101, 102), planform=StripPlanform(
    ...     y=[0.3, 0.9], width=[0.6, 0.6], chord=[0.7, 0.7], leading_edge_x=[3.3, 3.3],
    ...     elastic_axis=[0.25, 0.25], aerodynamic_centre=[0.25, 0.25],
    ...     lift_slope=[6.28, 6.28]))
    >>> tail.name, tail.lag_labels()[:2]
    ('tail', ('tail strip 1 w1', 'tail strip 1 w2'))
    """

    grids: tuple[int, ...]
    planform: StripPlanform
    name: str = "tail"

    def __post_init__(self) -> None:
        object.__setattr__(self, "grids", grid_ids("grids", self.grids))
        if len(self.grids) < 2:
            raise v.InputError(f"grids = {list(self.grids)} is invalid: a surface's strips are "
                               "splined to two or more grids, root to tip")
        if not isinstance(self.planform, StripPlanform):
            raise v.InputError(f"planform = {v.short_repr(self.planform)} is invalid: must be "
                               "a StripPlanform (the surface's strips)")
        name = self.name
        if not (isinstance(name, str) and name and len(name) <= 32
                and all(c.isalnum() or c in "-_" for c in name)
                and name not in ("strip", "mode", "propeller")):
            raise v.InputError(f"name = {v.short_repr(name)} is invalid: must be a word of 1 to "
                               "32 letters, digits, '-' or '_' (the first word of its lag "
                               "states' labels), not 'strip', 'mode' or 'propeller'")

    def lag_labels(self) -> tuple[str, ...]:
        """Its strips' lag states, ``"<name> strip s w r"`` (s, r from 1)."""
        k = LAG_STATES[self.planform.aero_model]
        return tuple(f"{self.name} strip {s + 1} w{r + 1}"
                     for s in range(self.planform.y.size) for r in range(k))


def check_surfaces(structure: ModalStructure, surfaces, sweep: bool) -> tuple:
    """``surfaces`` (a model's) as a tuple of :class:`ModalSurface`: each on grids of
    ``structure`` holding its strips (:func:`strip_interpolation`), unswept when ``sweep``
    (its strips' aerodynamics on), names distinct; else an InputError naming
    ``surfaces[j]``."""
    if isinstance(surfaces, (str, bytes)) or not isinstance(surfaces, (tuple, list)) \
            or not all(isinstance(s, ModalSurface) for s in surfaces):
        raise v.InputError(f"surfaces = {v.short_repr(surfaces)} is invalid: must be a "
                           "sequence of ModalSurface (a tail: its grids and strips)")
    if len(surfaces) > MAX_SURFACES:
        raise v.InputError(f"surfaces has {len(surfaces)} surfaces: at most {MAX_SURFACES}")
    seen: dict[str, int] = {}
    for j, surf in enumerate(surfaces):
        key = f"surfaces[{j}].grids"
        strip_interpolation(structure, surf.grids, surf.planform, key=key)
        if sweep:
            check_strip_sweep(structure, surf.grids, key)
        if surf.name in seen:
            raise v.InputError(f"surfaces[{j}].name = {surf.name!r} is invalid: surfaces"
                               f"[{seen[surf.name]}] has it already (names label the lag "
                               "states: each its own)")
        seen[surf.name] = j
    return tuple(surfaces)


def strip_rows(structure: ModalStructure, grids, planform: StripPlanform, n: int,
               key: str = "wing_grids") -> np.ndarray:
    """(n_strips, 2, n) read-only: each strip's [h, α] (heave at its elastic axis [m],
    positive down; twist [rad], nose up) from the model's coordinates q (its n_modes modes
    first): T Φ (:func:`strip_interpolation`)."""
    T = strip_interpolation(structure, grids, planform, key=key)
    P = np.zeros((planform.y.size, 2, n))
    P[:, :, :structure.n_modes] = np.einsum("scgk,mgk->scm", T, structure.shapes)
    P.flags.writeable = False
    return P


def strip_system(S: list, parts, density: float, V: np.ndarray):
    """The strips' loads of every lifting surface on the coordinates, at airspeeds V [m/s]:
    ``parts`` holds (planform, P) per surface (P its :func:`strip_rows`); the generated
    strip aerodynamics (:func:`~propwhirl.model.structure.assembly.strip_aero_blocks`)
    projected, PᵀA P subtracted from S = [S1, S2, S3] (each (nV, n, n), in place), and the
    lag states' (S4, Ww, Wv, Wq) returned, the surfaces' blocks one after another (Ww block
    diagonal: strip by strip)."""
    nV, n = V.shape[0], S[0].shape[-1]
    S4, Wv, Wq, Ww = [], [], [], []
    for planform, P in parts:
        a = strip_aero_blocks(planform.node_properties(), planform.aero_model, density, V)
        for Si, A in zip(S, (a["Ma"], a["Ca"], a["Ka"])):
            Si -= np.einsum("sim,vsij,sjn->vmn", P, A, P)
        ns, k = P.shape[0], a["Ww"].shape[-1]
        m = ns * k
        S4.append(np.einsum("sim,vsir->vmsr", P, a["W0"]).reshape(nV, n, m))
        Wv.append(np.einsum("vsri,sin->vsrn", a["Wv"], P).reshape(nV, m, n))
        Wq.append(np.einsum("vsri,sin->vsrn", a["Wq"], P).reshape(nV, m, n))
        Ww.extend(a["Ww"][:, s] for s in range(ns))
    m = sum(w.shape[-1] for w in Ww)
    W = np.zeros((nV, m, m))
    at = 0
    for w in Ww:
        k = w.shape[-1]
        W[:, at:at + k, at:at + k] = w
        at += k
    return (np.concatenate(S4, axis=2), W, np.concatenate(Wv, axis=1),
            np.concatenate(Wq, axis=1))


def neutral_point(planforms) -> float:
    """x [m] of the steady neutral point of the strips of ``planforms`` (the wing's and every
    surface's, in the modes' frame, x aft): the lift-weighted mean of their aerodynamic
    centres, x_np = Σ C_lα c w x_ac / Σ C_lα c w, with no downwash (module docstring).  A
    free pitch is statically stable about a centre of gravity at x_cg when x_cg < x_np: the
    static margin (x_np − x_cg) / c̄ > 0."""
    num = den = 0.0
    for p in planforms:
        weight = p.lift_slope * p.chord * p.width
        num += float(np.sum(weight * (p.leading_edge_x + p.aerodynamic_centre * p.chord)))
        den += float(np.sum(weight))
    return num / den
