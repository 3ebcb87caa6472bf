"""NASTRAN bulk data in: :func:`read_bdf` makes a beam model of a BDF's straight stick.

pyNastran (the optional extra ``nastran``, in an environment of its own: it needs numpy < 2)
parses the file, without cross-referencing; everything else is here: every card is looked up
and checked by propwhirl, so that a problem is one line naming the file, the card and its id
(``wing.bdf: CBAR 12 refers to PBAR 3, which is not in the file``), and a model is returned
whole or not at all.

What maps to what (docs/modal-structures.md, "NASTRAN bulk data", has the table):

* **the wing** — the GRIDs joined by CBAR/CBEAM elements, one line along the basic +y axis
  from the clamped root grid (all six components held by SPC/SPC1 or the GRID PS field):
  ``semi_span`` = the tip's y − the root's y, a node at every grid (``n_elements`` for equal
  elements, else ``stations`` at every grid and ``max_element_length`` the longest); per
  element EI = E·I (the vertical plane's I of the orientation vector's planes), GJ = G·J,
  ``EI_chordwise`` = E·I of the chordwise plane when the stick's T_x and R_z are free (held:
  the wing is rigid in its plane), ``mass_per_length`` = (ρA + NSM)·WTMASS,
  ``centre_of_gravity`` = the elastic axis + the mass's chordwise offset (PBEAM M1/M2 of the
  NSM) / the chord, ``polar_inertia`` = ρ(I1 + I2) + NSI + NSM·offset² (times WTMASS);
  PBARL/PBEAML of TYPE ROD or TUBE give A, I, J by their closed forms;
* **the propellers** — :mod:`propwhirl.io.nastran_mounts`: each hub grid (``hubs``, one per
  installation of ``base``) and the rigid body it belongs to.
* **a swept stick** — its grids on one line in the basic x-y plane at an angle Λ to y (aft
  positive), held in its plane and along its axis (T_x, T_y, R_z on every stick grid): the
  straight beam along its own axis as above (``semi_span`` its length), and the model a
  :class:`~propwhirl.model.modal.ModalPropellerWing` of that beam's modes turned into the
  basic frame on the stick's grids (the generated beam matrices:
  :meth:`~propwhirl.model.modal_structure.ModalStructure.from_wing`), each propeller on its
  wing grid with the deck's mount, its shaft along basic x; the strips refuse a sweep beyond
  :data:`~propwhirl.model.modal_structure.STRIP_SWEEP_LIMIT_DEG` by name (their aerodynamics
  are an unswept wing's), the base wing's doublet lattice (``aero = "dlm"``) takes it, its
  panels on the swept planform (a CAERO1; :func:`planform_corners`).

What a BDF cannot say comes from ``base``, a propwhirl model: the flight condition, the
chords, the elastic axis's and aerodynamic centre's chordwise positions, the aerodynamics,
the Rayleigh damping and, of each propeller, its rotor and aerodynamics (radius, blades,
operation, rotation, derivatives) — and the pivots and mount stiffness of a rigid mount.

Refused by name, with the reason (never dropped): any other card (shells, solids, CBUSH,
MPC, CORD1R, ...); a free-field line of more than nine fields (pyNastran drops the rest); a
bent or left-hand stick, one with dihedral, a swept one free in its plane; beam offsets
(WA/WB, PBEAM N1/N2) and a
non-structural mass off the chord line (vertical M1/M2); pin flags; CBEAM warping (SA/SB,
PBEAM CW); a product of inertia I12 or principal planes neither vertical nor chordwise; a
tapered element (PBEAM/PBEAML stations that differ); a second load path (two elements or a
rigid element between stick grids, branches); supports along the span; enforced
displacements; grids in a displacement frame turned from the basic one (CD); superelements.
Noted (``notes``): shear flexibility (PBEAM K1/K2 ≠ 0, PBAR K1/K2 given, PBARL/PBEAML, whose
shear factors NASTRAN computes), which propwhirl's Euler–Bernoulli beam leaves out; the
stick's free axial motion; MAT1 GE (the wing's damping is the base's Rayleigh damping).
Solution settings (EIGRL, EIGR, PARAM other than WTMASS) are not model data and are not read.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Sequence

import numpy as np

from propwhirl import fileio
from propwhirl import validate as v
from propwhirl.io import nastran_mounts
from propwhirl.io.nastran_deck import (  # noqa: F401 (re-exported: their old home)
    MODEL_CARDS, SETTING_CARDS, Deck, Grid, cord2r_axes, fail, parse, require_pynastran)
from propwhirl.io.nastran import unit_system
from propwhirl.model.aerodynamics.planform import Planform
from propwhirl.model.fields import check_values
from propwhirl.model.modal import ModalInstallation, ModalPropellerWing
from propwhirl.model.modal_structure import ModalStructure, StripPlanform
from propwhirl.model.structure.mesh import MIN_ELEMENT_FRACTION, tolerance
from propwhirl.model.systems import PropellerWing
from propwhirl.model.structure.wing import Wing

#: PBARL/PBEAML section types read (doubly symmetric, closed-form A, I and J).
SECTION_TYPES = ("ROD", "TUBE")
#: Cosine above which an axis is along another (principal planes vertical/chordwise).
_ALIGNED = 1.0 - 1e-9
#: pyNastran's value of a blank PBAR K1/K2 (infinite shear stiffness).
_PBAR_K_BLANK = 1e8


# ============================================================================ the stick
@dataclass(frozen=True)
class Stick:
    """The wing's stick as read.

    grids: grid ids from the root to the tip; y: their positions along the wing [m] from the
    root; origin: the root grid's basic position [m]; elements: "CBAR 3" ... per element;
    sections: per element EI, EI_chordwise, GJ [N m²], m [kg/m], x_cg [m, aft of the axis],
    polar [kg m]; in_plane: the stick's T_x and R_z are free; sweep: the angle of its axis
    to the basic y axis [deg, positive aft; 0: along y], ``y`` then the distance along it;
    positions: the grids' basic positions [m] (root to tip).
    """

    grids: tuple[int, ...]
    y: np.ndarray
    origin: np.ndarray
    elements: tuple[str, ...]
    sections: dict[str, np.ndarray]
    in_plane: bool
    mount_beams: tuple[nastran_mounts.MountBeam, ...] = ()
    sweep: float = 0.0
    positions: np.ndarray | None = None


def _beams(deck: Deck) -> list:
    return [e for e in deck.bdf.elements.values() if e.type in ("CBAR", "CBEAM")]


def _stick(deck: Deck, hubs: tuple[int, ...] = ()) -> Stick:
    beams = _beams(deck)
    bodies = nastran_mounts.rigid_body_grids(deck, hubs) if hubs else set()
    touching = [e for e in beams if {int(n) for n in e.node_ids if n} & bodies]
    mounting = [e for e in touching if _chordwise(deck, e)]
    stick_grids = {int(n) for e in beams if e not in touching for n in e.node_ids if n}
    for e in touching:                    # a vertical beam from the stick to a hub's body
        ends = [int(n) for n in e.node_ids if n]
        if e in mounting or not all(g in deck.grids for g in ends):
            continue
        on = [g for g in ends if g in stick_grids]
        if len(on) != 1:
            continue
        off = next(g for g in ends if g != on[0])
        d = deck.grids[off].xyz - deck.grids[on[0]].xyz
        if abs(d[2]) > max(abs(d[0]), abs(d[1])):
            raise deck.fail(f"{e.type} {e.eid} (GRID {on[0]}-{off}) joins a propeller's rigid "
                            f"body {abs(d[2]):.6g} m {'below' if d[2] < 0 else 'above'} the "
                            "stick to it: a pylon; propwhirl's beam model carries a propeller "
                            "on the wing's chord line (rigid, on hinges or a chordwise mount "
                            "beam): give the FE model's modes instead (an OP2 of it: propwhirl "
                            "import MODEL.op2 --mount on-grid)")
    beams = [e for e in beams if e not in mounting]
    if not beams:
        raise deck.fail("no CBAR or CBEAM: propwhirl reads a wing as a stick of beam elements")
    ends = {}
    for e in beams:
        a, b = (deck.grid(n, f"{e.type} {e.eid}").nid for n in e.node_ids)
        if a == b:
            raise deck.fail(f"{e.type} {e.eid} joins GRID {a} to itself")
        ends[e.eid] = (a, b)
    on_stick = {g for pair in ends.values() for g in pair}
    clamped = [g for g in sorted(on_stick) if deck.constraints.get(g, set()) >= set(range(1, 7))]
    if not clamped:
        raise deck.fail("no grid of the stick is clamped (all six components held by SPC, "
                        "SPC1 or the GRID PS field): propwhirl's wing is a cantilever")
    if len(clamped) > 1:
        raise deck.fail(f"GRID {clamped[0]} and GRID {clamped[1]} are both clamped: "
                        "propwhirl's wing is clamped at its root only")
    by_grid: dict[int, list[int]] = {}
    for eid, (a, b) in ends.items():
        by_grid.setdefault(a, []).append(eid)
        by_grid.setdefault(b, []).append(eid)
    for g, eids in sorted(by_grid.items()):
        if len(eids) > 2 or (g == clamped[0] and len(eids) > 1):
            names = ", ".join(f"{deck.bdf.elements[e].type} {e}" for e in sorted(eids))
            raise deck.fail(f"GRID {g} joins {len(eids)} beam elements ({names}): a branch or a "
                            "second load path; propwhirl's wing is one line of elements from "
                            "the root")
    order, elements, seen = [clamped[0]], [], set()
    while True:
        nxt = [e for e in by_grid[order[-1]] if e not in seen]
        if not nxt:
            break
        eid = nxt[0]
        seen.add(eid)
        a, b = ends[eid]
        order.append(b if a == order[-1] else a)
        elements.append(eid)
    for eid in sorted(set(ends) - seen):
        e = deck.bdf.elements[eid]
        raise deck.fail(f"{e.type} {eid} (GRID {ends[eid][0]}-{ends[eid][1]}) is not joined to "
                        f"the stick that starts at the clamped GRID {clamped[0]}: a second "
                        "load path or a second structure")
    pos = np.array([deck.grids[g].xyz for g in order])
    axis, sweep = _axis(deck, order, pos)
    L = float((pos[-1] - pos[0]) @ axis)
    tol = tolerance(abs(L))
    y = (pos - pos[0]) @ axis                       # along the stick's axis from the root
    for g, p, q, s, s0 in zip(order[1:], pos[1:], pos[:-1], y[1:], y[:-1]):
        if not s - s0 > tol:
            raise deck.fail(f"GRID {g} (y = {p[1]:.6g} m) is not outboard of the grid before "
                            f"it on the stick (y = {q[1]:.6g} m): the stick must run from the "
                            "root along +y (a left wing: mirror it)")
    names = tuple(f"{deck.bdf.elements[e].type} {e}" for e in elements)
    for name, dy in zip(names, np.diff(y)):
        if dy < MIN_ELEMENT_FRACTION * L:
            raise deck.fail(f"{name} is {dy:.3g} m long, shorter than {MIN_ELEMENT_FRACTION:g} "
                            f"of the semi-span ({MIN_ELEMENT_FRACTION * L:.3g} m): merge it "
                            "with a neighbour")
    in_plane = _stick_constraints(deck, order, sweep)
    sections = _sections(deck, [deck.bdf.elements[e] for e in elements], ends, names)
    mount_beams = tuple(_mount_beam(deck, e) for e in mounting)
    return Stick(tuple(order), y, pos[0], names, sections, in_plane, mount_beams, sweep, pos)


def _axis(deck: Deck, order: list[int], pos: np.ndarray) -> tuple[np.ndarray, float]:
    """The stick's axis (a unit vector in the basic x-y plane) and its sweep [deg, positive
    aft]: the basic y axis when every grid lies on the line along y through the root (within
    the mesh's tolerance), else the line from the root to the tip grid, on which every grid
    must lie (a bent stick, or one leaving the x-y plane, is refused naming its first grid
    off)."""
    tol = tolerance(float(np.linalg.norm(pos[-1] - pos[0])))
    off = pos - pos[0]
    if np.all(np.abs(off[:, [0, 2]]) <= tol):
        return np.array([0.0, 1.0, 0.0]), 0.0
    for g, o in zip(order[1:], off[1:]):
        if abs(o[2]) > tol:
            raise deck.fail(f"GRID {g} lies {abs(o[2]):.6g} m off (in z) the plane z = "
                            f"{pos[0, 2]:.6g} m of the root GRID {order[0]}: a stick with "
                            "dihedral or bent; propwhirl's wing (swept or not) lies in the "
                            "basic x-y plane")
    tip = off[-1]
    if not tip[1] > tol:
        raise deck.fail(f"GRID {order[-1]} (y = {pos[-1, 1]:.6g} m), the stick's tip, is not "
                        f"outboard of its root GRID {order[0]} (y = {pos[0, 1]:.6g} m): the "
                        "stick must run from the root along +y (a left wing: mirror it)")
    axis = np.array([tip[0], tip[1], 0.0]) / float(np.hypot(tip[0], tip[1]))
    for g, o in zip(order[1:-1], off[1:-1]):
        dist = float(np.linalg.norm(o - (o @ axis) * axis))
        if dist > tol:
            raise deck.fail(f"GRID {g} lies {dist:.6g} m off the line from the root GRID "
                            f"{order[0]} to the tip GRID {order[-1]}: a bent stick; "
                            "propwhirl's wing is straight (along y, or swept: its grids on one "
                            "line in the basic x-y plane)")
    return axis, float(np.degrees(np.arctan2(axis[0], axis[1])))


def _chordwise(deck: Deck, e) -> bool:
    """True when the beam element runs more along x than along y and z (not a stick's)."""
    ends = [deck.grids.get(int(n)) if n else None for n in e.node_ids]
    if any(g is None for g in ends):
        return False                      # a missing grid: refused with the stick's elements
    d = np.abs(ends[1].xyz - ends[0].xyz)
    return bool(d[0] > d[1] and d[0] > d[2])


def _mount_beam(deck: Deck, e) -> nastran_mounts.MountBeam:
    """A CBAR/CBEAM joining a propeller's rigid body to the stick (one end on the body, more
    along x than along y or z), as a mount: its E I per
    plane over its length (the rotational stiffnesses about its mid-point); massless, plain
    (no offsets, pins or warping), along the basic x axis (the shaft)."""
    name = f"{e.type} {e.eid}"
    a, b = (deck.grid(n, name).nid for n in e.node_ids)
    if a == b:
        raise deck.fail(f"{name} joins GRID {a} to itself")
    pa, pb = deck.grids[a].xyz, deck.grids[b].xyz
    d = pb - pa
    length = float(np.linalg.norm(d))
    if abs(d[0]) < _ALIGNED * length:
        raise deck.fail(f"{name} (a propeller's mount beam, GRID {a}-{b}) does not lie along "
                        "the basic x axis: propwhirl's mount beam lies on the shaft, "
                        "chordwise")
    s = _sections_of(deck, e, name, (a, b))
    deck.notes.append(f"{deck.where}: {name} is read as a mount: K_theta = {s['EI']/length:.6g}, "
                      f"K_psi = {s['EI_chordwise']/length:.6g} N m/rad (E I / L) about its "
                      f"mid-point; its translational compliance L^3/(12 E I) and its torsion "
                      f"(G J / L = {s['GJ']/length:.6g} N m/rad, about the shaft) are left out")
    return nastran_mounts.MountBeam(name, a, b, length, float(0.5 * (pa[0] + pb[0])),
                                    s["EI"], s["EI_chordwise"], s["GJ"], s["ge"])


def _stick_constraints(deck: Deck, order: list[int], sweep: float = 0.0) -> bool:
    """True when the stick bends in its plane (T_x and R_z free along it); refuses supports
    along the span and a mix; notes a free axial motion.  A swept stick (``sweep`` ≠ 0 deg)
    must be held in its plane and along its axis (T_x, T_y, R_z on every grid): in the basic
    frame its in-plane bending and its axial motion mix T_x and T_y."""
    held = [deck.constraints.get(g, set()) for g in order[1:]]
    for g, h in zip(order[1:], held):
        if h & {3, 4, 5}:
            raise deck.fail(f"GRID {g} (on the stick) holds component(s) "
                            f"{''.join(map(str, sorted(h & {3, 4, 5})))}: a support along the "
                            "span; propwhirl's wing is held at its root only")
    if sweep:
        for g, h in zip(order[1:], held):
            if not h >= {1, 2, 6}:
                raise deck.fail(f"GRID {g} (on the stick, swept by {sweep:.1f} deg) leaves "
                                f"component(s) {''.join(map(str, sorted({1, 2, 6} - h)))} "
                                "free: a swept stick is read rigid in its plane and along its "
                                "axis (hold T_x, T_y and R_z, components 126, on every stick "
                                "grid): propwhirl's swept wing bends out of its plane and "
                                "twists")
        return False
    plane = [h & {1, 6} for h in held]
    if all(p == {1, 6} for p in plane):
        in_plane = False
    elif all(not p for p in plane):
        in_plane = True
    else:
        g = next(g for g, p in zip(order[1:], plane) if p != plane[0])
        raise deck.fail(f"GRID {g}: its in-plane components T_x, R_z (1, 6) are held unlike "
                        f"GRID {order[1]}'s: hold both on every stick grid (a wing rigid in its "
                        "plane) or on none (it bends in its plane)")
    free = [g for g, h in zip(order[1:], held) if 2 not in h]
    if free:
        deck.notes.append(f"{deck.where}: the stick's axial motion (T_y, free at {len(free)} "
                          "grids) is not modelled: propwhirl's beam is rigid along its axis")
    return in_plane


def _tube(dims: Sequence[float], kind: str) -> tuple[float, float, float]:
    """A, I (= I1 = I2), J of a ROD (radius) or TUBE (outer, inner radius) [deck units]."""
    ro = float(dims[0])
    ri = float(dims[1]) if kind == "TUBE" else 0.0
    area = math.pi * (ro ** 2 - ri ** 2)
    inertia = math.pi * (ro ** 4 - ri ** 4) / 4.0
    return area, inertia, 2.0 * inertia


def _section(deck: Deck, prop, by: str, shear: list[str]) -> dict[str, float]:
    """One property card's section in deck units: A, I1, I2, J, NSM, NSI, M1, M2, mid."""
    name = f"{prop.type} {prop.pid}"
    if prop.type in ("PBARL", "PBEAML"):
        kind = prop.beam_type
        if kind not in SECTION_TYPES:
            raise deck.fail(f"{name}: TYPE {kind} is not read (its section constants depend on "
                            "NASTRAN's formulas for it): give the section as PBAR or PBEAM "
                            f"(A, I1, I2, J), or TYPE {' or '.join(SECTION_TYPES)}")
        dims = np.atleast_2d(np.asarray(prop.dim, dtype=float))
        nsm = np.atleast_1d(np.asarray(prop.nsm if prop.nsm is not None else 0.0, dtype=float))
        if not (np.all(dims == dims[0]) and np.all(nsm == nsm[0])):
            raise deck.fail(f"{name} changes along its element (tapered): propwhirl's element "
                            "properties are constant per element (split the element)")
        if np.any(dims[0] <= 0) or (kind == "TUBE" and not dims[0][1] < dims[0][0]):
            raise deck.fail(f"{name}: DIM = {dims[0].tolist()} is not a {kind} "
                            "(positive radii, inner < outer)")
        area, inertia, J = _tube(dims[0], kind)
        shear.append(name)
        return dict(A=area, I1=inertia, I2=inertia, J=J, NSM=float(nsm[0]), NSI=0.0,
                    M1=0.0, M2=0.0, mid=prop.mid)
    if prop.type == "PBAR":
        if prop.i12:
            raise deck.fail(f"{name}: I12 = {prop.i12!r}: principal axes turned from the "
                            "element's planes; propwhirl's beam bends vertically and chordwise "
                            "about principal axes")
        if prop.k1 != _PBAR_K_BLANK or prop.k2 != _PBAR_K_BLANK:
            shear.append(name)
        return dict(A=prop.A, I1=prop.i1, I2=prop.i2, J=prop.j, NSM=prop.nsm or 0.0, NSI=0.0,
                    M1=0.0, M2=0.0, mid=prop.mid)
    # PBEAM
    arrays = {k: np.asarray(getattr(prop, k), dtype=float) for k in
              ("A", "i1", "i2", "i12", "j", "nsm")}
    pairs = {"NSI": (prop.nsia, prop.nsib), "M1": (prop.m1a, prop.m1b),
             "M2": (prop.m2a, prop.m2b)}
    for k, arr in arrays.items():
        if not np.all(arr == arr[0]):
            raise deck.fail(f"{name} changes along its element ({k} {arr.tolist()}: tapered): "
                            "propwhirl's element properties are constant per element (split "
                            "the element)")
    for k, (a, b) in pairs.items():
        if b is not None and b != a:
            raise deck.fail(f"{name} changes along its element ({k} {a!r} at end A, {b!r} at "
                            "end B: tapered): propwhirl's element properties are constant per "
                            "element")
    if arrays["i12"][0]:
        raise deck.fail(f"{name}: I12 = {arrays['i12'][0]!r}: principal axes turned from the "
                        "element's planes; propwhirl's beam bends vertically and chordwise "
                        "about principal axes")
    for label, values in (("CW (warping)", (prop.cwa, prop.cwb)),
                          ("N1, N2 (the neutral axis off the shear centre)",
                           (prop.n1a, prop.n2a, prop.n1b, prop.n2b)),
                          ("S1, S2 (shear relief of a taper)", (prop.s1, prop.s2))):
        if any(x not in (None, 0.0) for x in values):
            raise deck.fail(f"{name}: {label} = {[x for x in values]}: not representable by "
                            "propwhirl's beam (an Euler-Bernoulli beam about its shear "
                            "centre, without warping)")
    if prop.k1 or prop.k2:
        shear.append(name)
    return dict(A=arrays["A"][0], I1=arrays["i1"][0], I2=arrays["i2"][0], J=arrays["j"][0],
                NSM=arrays["nsm"][0], NSI=prop.nsia or 0.0, M1=prop.m1a or 0.0,
                M2=prop.m2a or 0.0, mid=prop.mid)


def _axes(deck: Deck, e, a: int, b: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The element's axes (x, y, z) in the basic frame from its grids and orientation."""
    by = f"{e.type} {e.eid}"
    pa, pb = deck.grids[a].xyz, deck.grids[b].xyz
    ex = (pb - pa) / np.linalg.norm(pb - pa)
    if e.g0 is not None:
        vec = deck.grid(e.g0, by).xyz - pa
    elif e.x is not None and not any(x is None for x in e.x):
        # in GA's displacement frame (OFFT G..) or the basic one (B..): the same, CD checked
        vec = np.asarray(e.x, dtype=float)
    else:
        raise deck.fail(f"{by}: no orientation vector (X1-X3 or G0)")
    ey = vec - (vec @ ex) * ex
    if not np.linalg.norm(ey) > 1e-9 * np.linalg.norm(vec):
        raise deck.fail(f"{by}: its orientation vector lies along the element")
    ey = ey / np.linalg.norm(ey)
    return ex, ey, np.cross(ex, ey)


def _element(deck: Deck, e, name: str, ends: tuple[int, int], shear: list[str],
             damped: list[str]) -> dict:
    """One CBAR/CBEAM's section in SI: EI (vertical plane), EI_chordwise, GJ [N m²],
    m [kg/m], x_cg [m], polar [kg m], GE, and its property's name (checks of the element,
    its property and material; shear and GE noted in ``shear``, ``damped``)."""
    u, w = deck.u, deck.wtmass
    a, b = ends
    for label, values in (("WA", e.wa), ("WB", e.wb)):
        if values is not None and np.any(np.asarray(values, dtype=float) != 0.0):
            raise deck.fail(f"{name}: offset {label} = {np.asarray(values).tolist()}: the "
                            "element is off its grids; propwhirl's beam runs through them")
    for label, flag in (("PA", e.pa), ("PB", e.pb)):
        if flag not in (None, 0, "", "0"):
            raise deck.fail(f"{name}: pin flags {label} = {flag}: a released end; "
                            "propwhirl's beam is continuous")
    if e.type == "CBEAM":
        if e.sa or e.sb:
            raise deck.fail(f"{name}: warping scalar points SA, SB = {e.sa}, {e.sb}: "
                            "propwhirl's beam has no warping")
        if getattr(e, "bit", None) not in (None, 0.0):
            raise deck.fail(f"{name}: BIT = {e.bit!r}: not read")
    kinds = ("PBAR", "PBARL") if e.type == "CBAR" else ("PBEAM", "PBEAML")
    prop = deck.card(deck.bdf.properties, e.pid, kinds, name)
    s = _section(deck, prop, name, shear)
    pname = f"{prop.type} {prop.pid}"
    mat = deck.card(deck.bdf.materials, s["mid"], ("MAT1",), pname)
    mname = f"MAT1 {mat.mid}"
    E, G, rho = mat.e, mat.g, mat.rho or 0.0
    if not (isinstance(E, float) and E > 0 and isinstance(G, float) and G > 0):
        raise deck.fail(f"{mname}: E = {E!r}, G = {G!r}: both must be > 0 (give E and G, "
                        "or E and NU)")
    if rho < 0:
        raise deck.fail(f"{mname}: RHO = {rho!r} is negative")
    if rho > 0:
        speed = math.sqrt(E * u.modulus / (rho * u.density * w))
        if not 100.0 <= speed <= 3e4:
            raise deck.fail(f"{mname}: E and RHO give a wave speed sqrt(E/RHO) of "
                            f"{speed:.4g} m/s in {u.name} units (every solid: 100 to "
                            f"30,000 m/s): the deck is not in {u.name} ({u.description}), "
                            "or its units are mixed")
    if mat.ge:
        damped.append(mname)
    ex, ey, ez = _axes(deck, e, a, b)
    I1, I2 = s["I1"], s["I2"]
    if I1 == I2 or abs(ey[2]) >= _ALIGNED:
        I_v, I_c = I1, I2
    elif abs(ez[2]) >= _ALIGNED:
        I_v, I_c = I2, I1
    else:
        angle = math.degrees(math.acos(min(1.0, abs(ey[2]))))
        raise deck.fail(f"{name}: its orientation vector puts plane 1 at {angle:.3g} deg "
                        "to the vertical: propwhirl's beam bends in the vertical plane and "
                        "in the wing's plane (principal planes vertical and chordwise)")
    offset = s["M1"] * ey + s["M2"] * ez                  # the NSM's c.g. [deck length]
    if abs(offset[2]) > 1e-12 * np.linalg.norm(offset):
        raise deck.fail(f"{pname} (on {name}): its non-structural mass's c.g. is "
                        f"{offset[2] * u.length:.6g} m above the axis (M1, M2 = "
                        f"{s['M1']!r}, {s['M2']!r}): propwhirl's section has its c.g. on "
                        "the chord line")
    x_nsm = offset[0] * u.length
    m_struct = rho * s["A"] * u.mass_per_length * w
    nsm = s["NSM"] * u.mass_per_length * w
    m = m_struct + nsm
    polar = (rho * (I1 + I2) * u.inertia_per_length * w
             + s["NSI"] * u.inertia_per_length * w + nsm * x_nsm ** 2)
    return dict(EI=E * I_v * u.rigidity, EI_chordwise=E * I_c * u.rigidity,
                GJ=G * s["J"] * u.rigidity, m=m, x_cg=nsm * x_nsm / m if m else 0.0,
                polar=polar, ge=float(mat.ge or 0.0), pname=pname)


def _sections(deck: Deck, elements: list, ends: dict, names: tuple[str, ...]
              ) -> dict[str, np.ndarray]:
    """Per element EI, EI_chordwise, GJ [N m²], m [kg/m], x_cg [m], polar [kg m] (SI)."""
    out = {k: [] for k in ("EI", "EI_chordwise", "GJ", "m", "x_cg", "polar")}
    shear: list[str] = []
    damped: list[str] = []
    for e, name in zip(elements, names):
        s = _element(deck, e, name, ends[e.eid], shear, damped)
        if not s["m"] > 0.0:
            raise deck.fail(f"{s['pname']} (on {name}): no mass (RHO A + NSM = {s['m']!r} "
                            "kg/m): a wing element needs mass")
        if s["polar"] == 0.0:
            raise deck.fail(f"{s['pname']} (on {name}): no polar inertia (RHO = 0, no NSI, the "
                            "NSM on the axis): propwhirl's wing twists with inertia; give RHO, "
                            "or a PBEAM with NSI")
        for k in out:
            out[k].append(s[k])
    _note_sections(deck, shear, damped)
    return {k: np.array(x, dtype=float) for k, x in out.items()}


def _note_sections(deck: Deck, shear: list[str], damped: list[str]) -> None:
    if shear:
        deck.notes.append(f"{deck.where}: the shear flexibility of {', '.join(sorted(set(shear)))} "
                          "is left out: propwhirl's beam is Euler-Bernoulli")
    if damped:
        deck.notes.append(f"{deck.where}: GE of {', '.join(sorted(set(damped)))} (structural "
                          "damping) is not read: the wing's damping is the base model's "
                          "Rayleigh damping")


def _sections_of(deck: Deck, e, name: str, ends: tuple[int, int]) -> dict:
    """A mount beam's section (SI): it must be massless (propwhirl's mount is); its MAT1's
    GE is the mount's damping (read, so not noted)."""
    shear: list[str] = []
    s = _element(deck, e, name, ends, shear, [])
    if s["m"] != 0.0 or s["polar"] != 0.0:
        raise deck.fail(f"{s['pname']} (on {name}, a propeller's mount beam): it has mass (RHO A "
                        f"+ NSM = {s['m']:.6g} kg/m, or NSI): propwhirl's mount is massless; "
                        "give its MAT1 RHO = 0 and put the nacelle's mass on CONM2")
    if not 0.0 <= s["ge"] <= 2.0:
        raise deck.fail(f"{name}: the GE of its MAT1 ({s['ge']!r}) is outside the valid range "
                        "[0, 2] of a mount's structural damping g")
    _note_sections(deck, shear, [])
    return s


# ============================================================================ the model
def _values(arr: np.ndarray):
    """A per-element property as the Wing takes it: one number when every element has it."""
    return float(arr[0]) if np.all(arr == arr[0]) else tuple(float(x) for x in arr)


def _spanwise_at(wing: Wing, name: str, n: int) -> np.ndarray:
    """The wing's ``name`` (elastic_axis, ...) at its element mid-points (a number, one per
    element or a function of y, as the Wing evaluates it)."""
    value = getattr(wing, name)
    if callable(value):
        return np.asarray(value(wing.element_y), dtype=float)
    return np.broadcast_to(np.asarray(value, dtype=float), (n,)).copy()


def _check_range(deck: Deck, field: str, values: np.ndarray, names: Sequence[str],
                 what: str, unit: str) -> None:
    """Each value within the Wing field's valid range, else one line naming the card and the
    units the deck was read in (a value far out is the wrong units)."""
    for value, name in zip(values, names):
        try:
            check_values(Wing, field, np.array([value]))
        except v.InputError as exc:
            reason = exc.reason or str(exc)
            raise deck.fail(f"{name}: {what} = {value:.6g} {unit} (read in {deck.u.name} "
                            f"units: {deck.u.description}) is {reason}: are the deck's units "
                            f"{deck.u.name}, and not mixed?") from None


def _wing(deck: Deck, stick: Stick, base_wing: Wing, base: str) -> Wing:
    y, names = stick.y, stick.elements
    n, L = len(names), float(y[-1])
    s = stick.sections
    _check_range(deck, "EI", s["EI"], names, "EI (E I)", "N m^2")
    _check_range(deck, "GJ", s["GJ"], names, "GJ (G J)", "N m^2")
    _check_range(deck, "mass_per_length", s["m"], names, "mass per length", "kg/m")
    _check_range(deck, "polar_inertia", s["polar"], names, "polar inertia", "kg m")
    if stick.in_plane:
        _check_range(deck, "EI_chordwise", s["EI_chordwise"], names, "EI_chordwise (E I)",
                     "N m^2")
    for name in ("elastic_axis", "aerodynamic_centre"):
        value = getattr(base_wing, name)
        if not callable(value) and np.ndim(value) == 1 and np.size(value) != n:
            raise v.InputError(f"{base}: its wing's {name} has {np.size(value)} values, one per "
                               f"element of its own mesh; the BDF's stick has {n} elements: "
                               "give one number (or a function of y)")
    uniform = np.allclose(y, np.linspace(0.0, L, n + 1), rtol=0.0, atol=1e-9 * L)
    mesh = (dict(n_elements=n, stations=None, max_element_length=None) if uniform else
            dict(n_elements=n, stations=tuple(float(x) for x in y[1:-1]),
                 max_element_length=float(np.max(np.diff(y)))))
    structure = dict(semi_span=L, EI=_values(s["EI"]), GJ=_values(s["GJ"]),
                     mass_per_length=_values(s["m"]), polar_inertia=_values(s["polar"]),
                     radius_of_gyration=None,
                     EI_chordwise=_values(s["EI_chordwise"]) if stick.in_plane else None)
    draft = replace(base_wing, **mesh, **structure, centre_of_gravity=base_wing.elastic_axis)
    if not np.allclose(draft.node_y, y, rtol=0.0, atol=tolerance(L)):   # the mesh rule's nodes
        raise deck.fail("its grids do not make a propwhirl mesh (a bug: please report)")
    ea = _spanwise_at(draft, "elastic_axis", n)
    chord = draft.chord_at(draft.element_y)
    cg = ea + s["x_cg"] / chord
    for value, name, c in zip(cg, names, chord):
        if not 0.0 <= value <= 1.0:
            raise deck.fail(f"{name}: its centre of gravity ({value:.6g} of the {c:.6g} m "
                            "chord of the base model) lies outside the chord")
    return replace(draft, centre_of_gravity=_values(cg))


def modal_installation(inst, grid: int, mount: str, hub: int, fail, what: str
                       ) -> ModalInstallation:
    """The base model's installation ``inst`` as a modal model's, at ``grid`` with ``mount``:
    its propeller with the installation's ``rotation`` override applied, its ``aero`` kept;
    a stopped or feathered one (``state``) refused, ``fail(text)`` the error naming the file
    (a modal model's propellers operate).  The BDF's swept stick and the OP2's modes
    (:func:`propwhirl.io.nastran_op2.read_op2`) both read a base's installations so; ``what``
    says which, ``hub`` the hub grid the message names."""
    if inst.state != "operating":
        raise fail(f"hub GRID {hub}: the base's installation is {inst.state}: {what} is read "
                   "as a modal model, whose propellers operate")
    p = inst.propeller if inst.rotation is None else replace(inst.propeller,
                                                              rotation=inst.rotation)
    return ModalInstallation(p, grid, mount, inst.aero)

def _swept(deck: Deck, stick: Stick, wing: Wing, model: PropellerWing, mounts, installations,
           name: str) -> ModalPropellerWing:
    """The modal model of a swept stick: the modes of its straight beam (``wing``, the stick
    along its own axis: the generated beam matrices, :meth:`ModalStructure.from_wing`, every
    mode), turned into the basic frame on the stick's grids — each grid's translations and
    rotations in the stick's frame (x' aft normal to the axis, y' along it, z up) rotated by
    the sweep about z; the strips of the base's wing moved onto the swept axis (stations
    y = y_root + s cos Λ, widths × cos Λ, streamwise chords: the base's, its elastic axis on
    the stick); each propeller on its wing grid with the deck's mount (``installations``:
    "rigid" or "flexible", its shaft along the basic x axis, coupled through the grid's
    heave and basic R_y).  Strip aerodynamics refuse a stick swept by more than
    :data:`~propwhirl.model.modal_structure.STRIP_SWEEP_LIMIT_DEG` (by name); the base wing's
    doublet lattice (``aero = "dlm"``) takes it: its panels (the base's counts and Mach) on
    the swept planform, a CAERO1 of :func:`planform_corners`."""
    straight = ModalStructure.from_wing(wing)
    lam = math.radians(stick.sweep)
    c, s = math.cos(lam), math.sin(lam)
    turn = np.array([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]])   # columns: x', y', z
    local = straight.shapes
    shapes = np.concatenate([local[..., :3] @ turn.T, local[..., 3:] @ turn.T], axis=-1)
    source = f"{deck.where} (the modes of its stick, swept by {stick.sweep:.1f} deg)"
    structure = ModalStructure(grid_ids=np.array(stick.grids, dtype=np.int64),
                               xyz=stick.positions, frequencies_hz=straight.frequencies_hz,
                               modal_mass=straight.modal_mass,
                               damping_ratio=straight.damping_ratio, shapes=shapes,
                               source=source)
    strips = StripPlanform.from_wing(wing)
    x0, y0 = float(stick.origin[0]), float(stick.origin[1])
    planform = replace(strips, y=y0 + c * strips.y, width=c * strips.width,
                       leading_edge_x=x0 + s * strips.y + strips.leading_edge_x,
                       source=f"{deck.where} (the base's strips on its swept stick)")
    props = [modal_installation(inst, m.wing_grid, inst.mount, m.hub, deck.fail,
                                "a swept stick") for m, inst in zip(mounts, installations)]
    dlm = {}
    if wing.aero == "dlm":          # the base's doublet lattice: panels on the swept planform
        nodes = wing.node_properties()           # the chord 2b, the axis a b aft of mid-chord
        (p1, c1), (p4, c4) = ((stick.positions[k] - [(1.0 + nodes["a"][k]) * nodes["b"][k],
                                                     0.0, 0.0], 2.0 * nodes["b"][k])
                              for k in (0, -1))
        dlm = dict(aero="dlm", dlm_mach=wing.dlm_mach, dlm_planform=Planform.caero1(
            p1, p4, float(c1), float(c4), wing.dlm_chordwise_panels, wing.dlm_spanwise_panels,
            source=f"{deck.where} (the base's planform on its swept stick)"))
    deck.notes.append(f"{deck.where}: its stick is swept by {stick.sweep:.1f} deg: read as the "
                      f"{structure.n_modes} modes of its straight beam ({wing.element_count} "
                      f"elements, {wing.semi_span:.6g} m along its axis) on its grids, a modal "
                      "model (the propellers on their wing grids, the base's chords streamwise"
                      + (", its doublet-lattice panels on the swept planform)" if dlm else ")"))
    try:
        return ModalPropellerWing(structure, stick.grids, planform, model.flight, tuple(props),
                                  wing_aero=model.wing_aero, propeller_aero=model.propeller_aero,
                                  rotating=model.rotating, name=f"{model.name} (swept stick of "
                                  f"{name})", **dlm)
    except v.InputError as exc:
        msg = str(exc)
        raise v.InputError(msg if msg.startswith(deck.where) else f"{deck.where}: {msg}") \
            from None


def planform_corners(model: ModalPropellerWing) -> np.ndarray:
    """The lifting surface of a modal model as NASTRAN's CAERO1 gives one: its four corners
    [m] in the basic frame, (4, 3) — P1 the root's leading edge, P2 the root's trailing edge,
    P3 the tip's trailing edge, P4 the tip's leading edge (X12 = P2 − P1 and X43 = P3 − P4
    along x: the streamwise chords) — at the y and z of its first and last wing grid, the
    leading edge's x and the chord linear through the strips nearest each end (a swept
    stick's :func:`read_bdf` model has a strip at its tip grid; at the root, where no strip
    is, this is exact for a linear taper with one elastic-axis fraction).  What a
    doublet-lattice planform of a swept stick (issue 34, item 3) starts from.

    Examples
    --------
    A straight wing's modal model (the baseline wing: 5.7 m, its chord tapering from 1.25 m
    to 0.8 m, the elastic axis at mid-chord on x = 0):

    >>> from propwhirl.cases.ch09_baseline import baseline_flight, baseline_wing
    >>> from propwhirl.model import ModalPropellerWing, ModalStructure, StripPlanform
    >>> wing = baseline_wing(n_elements=6)
    >>> s = ModalStructure.from_wing(wing, n_modes=4)
    >>> m = ModalPropellerWing(s, tuple(int(g) for g in s.grid_ids),
    ...                        StripPlanform.from_wing(wing), baseline_flight())
    >>> planform_corners(m).round(3).tolist()
    [[-0.625, 0.0, 0.0], [0.625, 0.0, 0.0], [0.4, 5.7, 0.0], [-0.4, 5.7, 0.0]]
    """
    return _corners(model.structure, model.wing_grids, model.planform)


def _corners(s: ModalStructure, wing_grids, p: StripPlanform) -> np.ndarray:
    """:func:`planform_corners` of a structure, its wing grids and its strips."""
    ends = s.xyz[[s.index(wing_grids[0]), s.index(wing_grids[-1])]]
    out = []
    for end in ends:
        y = float(end[1])
        if p.y.size == 1:
            le, chord = float(p.leading_edge_x[0]), float(p.chord[0])
        else:
            i = int(np.clip(np.searchsorted(p.y, y) - 1, 0, p.y.size - 2))
            w = (y - p.y[i]) / (p.y[i + 1] - p.y[i])
            le = float(p.leading_edge_x[i] + w * (p.leading_edge_x[i + 1] - p.leading_edge_x[i]))
            chord = float(p.chord[i] + w * (p.chord[i + 1] - p.chord[i]))
        out.append((np.array([le, y, end[2]]), np.array([le + chord, y, end[2]])))
    (p1, p2), (p4, p3) = out
    return np.array([p1, p2, p3, p4])


def _as_model(base, where: str) -> PropellerWing:
    if base is None:
        raise fail(where, "a BDF holds the structure only: give the base model (base=...; "
                           "--base MODEL.toml) for the flight condition, the chords and "
                           "aerodynamics, and the propellers' rotors and aerodynamics")
    if not isinstance(base, PropellerWing):
        raise fail(where, f"the base model is a {type(base).__name__}: it must be a wing with "
                           "propellers (type \"propeller-wing\")")
    return base


def hub_ids(hubs, base: PropellerWing, where: str) -> tuple[int, ...]:
    """The hub grid ids ``hubs``, one per installation of ``base`` and distinct; else one
    line starting with ``where`` (the file)."""
    hubs = tuple(hubs or ())
    for h in hubs:
        if isinstance(h, (bool, np.bool_)) or not isinstance(h, (int, np.integer)) or h <= 0:
            raise fail(where, f"hub grid {h!r} is invalid: grid ids are integers > 0")
    if len(hubs) != len(base.propellers):
        raise fail(where, f"{len(hubs)} hub grid(s) for the base model's "
                           f"{len(base.propellers)} installation(s): give one hub grid per "
                           "installation, in its order (--hubs)")
    if len(set(hubs)) != len(hubs):
        twice = next(h for h in hubs if hubs.count(h) > 1)
        raise fail(where, f"hub GRID {twice} is given twice: one propeller per hub grid")
    return tuple(int(h) for h in hubs)


def read_bdf(path: str | Path, *, units: str | None = None, base=None,
             hubs: Sequence[int] = (), notes: list[str] | None = None,
             base_name: str = "the base model") -> PropellerWing:
    """The beam model of a NASTRAN bulk data file.

    Parameters
    ----------
    path : str or Path
        the BDF (a SOL 103 deck, or bulk data only); INCLUDEs are read
    units : str
        the deck's unit system, one of "si" (m, kg, s, N), "mm-t-s" (mm, t, s, N),
        "in-lbf-s" (in, lbf s²/in, s, lbf): NASTRAN has none, so it must be stated
    base : PropellerWing
        what a BDF cannot say (see the module's notes); its structure is replaced by the
        BDF's: the wing's span, mesh, rigidities, masses and inertias, each installation's
        position, mount and masses
    hubs : sequence of int
        the hub grid of each of ``base``'s installations, in their order (the grid carrying
        the rotor's CONM2)
    notes : list of str, optional
        receives one line per thing of the deck that is not modelled and not an error
        (shear flexibility, a free axial motion, MAT1 GE)
    base_name : str
        how messages name ``base`` (the command line: its file)

    Returns
    -------
    PropellerWing or ModalPropellerWing
        ``base`` with the BDF's structure, whole (or an InputError, one line naming the
        file, the card and its id); for a swept stick the modal model of its modes (the
        module's notes), whose strip aerodynamics refuse a sweep of more than
        :data:`~propwhirl.model.modal_structure.STRIP_SWEEP_LIMIT_DEG` (a base with
        ``wing_aero = False`` reads its structure alone)

    Examples
    --------
    The wingtip model written as a SOL 103 deck and read back (needs pyNastran, the
    ``nastran`` extra in an environment of its own: not run here; ``tests/nastran`` runs the
    same round trip in ``.venv-nastran``):

    >>> import pathlib, tempfile
    >>> from propwhirl.io import read_bdf, write_bdf
    >>> from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
    >>> m = wingtip_propeller_wing()
    >>> with tempfile.TemporaryDirectory() as folder:          # doctest: +SKIP
    ...     deck = write_bdf(m, pathlib.Path(folder) / "wingtip.bdf", "si")
    ...     back = read_bdf(pathlib.Path(folder) / "wingtip.bdf", units="si", base=m,
    ...                     hubs=deck.hubs)
    >>> back.wing.element_count == m.wing.element_count        # doctest: +SKIP
    True
    """
    where = fileio.shown(path) if isinstance(path, (str, Path)) else repr(path)
    u = unit_system(units, where)
    model = _as_model(base, where)
    hub_grids = hub_ids(hubs, model, where)
    text = fileio.read_text(path, "BDF file")
    notes_here: list[str] = []
    deck = Deck(parse(Path(path), where, text), where, text, u, notes_here)
    stick = _stick(deck, hub_grids)
    wing = _wing(deck, stick, model.wing, base_name)
    mounts = nastran_mounts.read(deck, stick, hub_grids)
    installations = tuple(nastran_mounts.installation(deck, m, inst, wing, stick)
                          for m, inst in zip(mounts, model.propellers))
    if stick.sweep:
        out = _swept(deck, stick, wing, model, mounts, installations, Path(str(path)).name)
        if notes is not None:
            notes.extend(notes_here)
        return out
    try:
        out = replace(model, wing=wing, propellers=installations)
    except v.InputError as exc:
        raise fail(where, f"the model it makes is invalid: {exc}") from None
    if notes is not None:
        notes.extend(notes_here)
    return out


__all__ = ["Deck", "MODEL_CARDS", "SECTION_TYPES", "SETTING_CARDS", "Stick", "cord2r_axes",
           "hub_ids", "planform_corners", "read_bdf", "require_pynastran"]
