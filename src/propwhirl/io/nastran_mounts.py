"""The propellers of a NASTRAN deck: each hub grid's rigid body, its mount and its masses
(:func:`read`), and the installation they make of a base model's (:func:`installation`).

A propeller is the rigid body its hub grid belongs to: the grids joined to it by RBE2 or RBAR
elements that hold all six components.  Its mount is one of two patterns:

* **rigid** — the body holds a grid of the wing's stick: ``mount = "rigid"``;
* **flexible** — the body reaches the stick through exactly two hinges in a row, one
  about y (pitch, component 5) and one about z (yaw, 6), with no mass between them.  A hinge
  is a rigid element between two coincident grids that leaves one rotation free (RBE2 CM =
  12346 or 12345; RBAR CMB likewise) and the CELAS2 spring between the same grids on that
  component: K → K_theta or K_psi [N m/rad], GE → the structural damping g (damping_theta,
  damping_psi), the grids' x → the pivot (pivot_pitch, pivot_yaw);
* **flexible, a mount beam** — the body reaches a stick grid through one short massless
  CBAR/CBEAM along the shaft (:class:`MountBeam`, read by the BDF reader): K_theta = E I/L of
  its vertical plane, K_psi = E I/L of its chordwise plane, both pivots at its mid-point, GE of
  its MAT1 → damping_theta = damping_psi.  A beam's end flexibility, moved to its mid-point,
  is a rotational compliance L/(E I) and a translational one L³/(12 E I) that do not couple
  (the cantilever's tip flexibility L³/3, L²/2, L over E I, its force moved by L/2): the
  rotation is the spring model's, the translation and the beam's torsion (G J/L, about the
  shaft) are left out (noted), which a stiff short beam makes small.

Its masses are the CONM2 on the body's grids, each a point mass on the shaft: the one on the
hub grid is the rotor (its c.g. the propeller plane, its I11 the spin inertia I_Omega — only:
a rotor on its bearings is not turned by the nacelle's roll, so it adds no roll inertia to the
wing, where NASTRAN's rigid CONM2 counts I11 as the hub grid's R_x inertia too;
docs/modal-structures.md, "The rotor's I11", and tests/nastran/test_spin_inertia.py), the
others ``masses``; their I22 and I33 (about y and z through their c.g.) add to the pitch and
yaw inertias (``inertia`` I_theta_P, I_psi_P).  Positions are measured aft of the wing's
mid-chord at the hub's wing node (the base model's chord and elastic axis place the stick on
the chord).

Refused by name: a hub grid not in the file, two hubs on one body or one wing grid, a mass
off the shaft line (y and z of its wing grid) or with products of inertia or, but the rotor,
an I11 (propwhirl's nacelle does not roll), a mass between the hinges or on the wing outside
every propeller, a rigid element leaving other components free, a spring that is no hinge's,
a hinge without its spring, grids that belong to no propeller or to nothing.
"""
from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from propwhirl import validate as v
from propwhirl.model.structure.mesh import tolerance
from propwhirl.model.propellers.propeller import PointMass
from propwhirl.model.systems import Installation
from propwhirl.model.structure.wing import Wing

ALL = frozenset(range(1, 7))
#: The free rotation of a hinge and what it is.
HINGES = {5: "pitch (R_y)", 6: "yaw (R_z)"}


@dataclass(frozen=True)
class Link:
    """A rigid element's link of grid ``a`` (independent) to grid ``b``: all six components
    (``free`` None) or all but the rotation ``free`` (5 or 6: a hinge)."""

    card: str
    a: int
    b: int
    free: int | None


@dataclass(frozen=True)
class Hinge:
    """A hinge: its rigid element, its spring's card, stiffness [N m/rad], GE and the pivot's
    basic x [m]."""

    link: Link
    spring: str
    K: float
    ge: float
    x: float


@dataclass(frozen=True)
class Mass:
    """A CONM2: card, grid, mass [kg], c.g. in the basic frame [m], I11, I22, I33 about its
    c.g. [kg m²]."""

    card: str
    grid: int
    mass: float
    cg: tuple[float, float, float]
    i11: float
    i22: float
    i33: float

    @property
    def x(self) -> float:
        return self.cg[0]


@dataclass(frozen=True)
class MountBeam:
    """A CBAR/CBEAM read as a propeller's mount: its card, end grids ``a``, ``b``, length
    L [m], the basic x of its mid-point [m], E I of its vertical and chordwise planes [N m²],
    G J [N m²] and its MAT1's GE."""

    card: str
    a: int
    b: int
    length: float
    x_mid: float
    EI_vertical: float
    EI_chordwise: float
    GJ: float
    ge: float


@dataclass(frozen=True)
class Mount:
    """What the deck says of one propeller: its hub and wing grid (its index on the stick),
    its masses (the rotor first), and its hinges (None for a rigid mount)."""

    hub: int
    wing_grid: int
    node: int
    masses: tuple[Mass, ...]
    pitch: Hinge | None
    yaw: Hinge | None


def _components(text, card: str, deck) -> frozenset[int]:
    digits = str(text or "").strip()
    if not digits or not digits.isdigit() or not set(digits) <= set("123456"):
        raise deck.fail(f"{card}: components {text!r} are not NASTRAN components (digits 1-6)")
    return frozenset(int(c) for c in digits)


def _link(deck, card: str, a: int, b: int, comps: frozenset[int]) -> Link:
    deck.grid(a, card)
    deck.grid(b, card)
    if comps == ALL:
        return Link(card, a, b, None)
    free = ALL - comps
    if len(free) == 1 and next(iter(free)) in HINGES:
        return Link(card, a, b, next(iter(free)))
    raise deck.fail(f"{card} leaves component(s) {''.join(map(str, sorted(free)))} of GRID {b} "
                    "free: propwhirl's rigid elements hold all six components, or all but one "
                    "hinge rotation (5: pitch, 6: yaw) with a CELAS2 on it")


def _links(deck) -> list[Link]:
    out = []
    for e in sorted(deck.bdf.rigid_elements.values(), key=lambda e: e.eid):
        card = f"{e.type} {e.eid}"
        if e.type == "RBE2":
            comps = _components(e.cm, card, deck)
            out += [_link(deck, card, int(e.gn), int(g), comps) for g in e.Gmi]
            continue
        ends = [str(x or "").strip() for x in (e.cna, e.cnb, e.cma, e.cmb)]
        ends = ["" if x == "0" else x for x in ends]
        if ends[0] == "123456" and not ends[1] and not ends[2] and ends[3]:
            out.append(_link(deck, card, int(e.ga), int(e.gb), _components(ends[3], card, deck)))
        elif ends[1] == "123456" and not ends[0] and not ends[3] and ends[2]:
            out.append(_link(deck, card, int(e.gb), int(e.ga), _components(ends[2], card, deck)))
        else:
            raise deck.fail(f"{card}: CNA, CNB, CMA, CMB = {', '.join(x or '-' for x in ends)}: "
                            "propwhirl reads an RBAR as one end's six components driving the "
                            "other end's (CNA = 123456 and CMB, or the mirror)")
    return out


class _Bodies:
    """Union-find of grids joined by rigid links."""

    def __init__(self):
        self.parent: dict[int, int] = {}

    def find(self, g: int) -> int:
        self.parent.setdefault(g, g)
        while self.parent[g] != g:
            self.parent[g] = self.parent[self.parent[g]]
            g = self.parent[g]
        return g

    def join(self, a: int, b: int) -> None:
        self.parent[self.find(a)] = self.find(b)

    def members(self, grids) -> dict[int, set[int]]:
        out: dict[int, set[int]] = {}
        for g in grids:
            out.setdefault(self.find(g), set()).add(g)
        return out


def rigid_body_grids(deck, hubs) -> set[int]:
    """Every grid joined to one of the ``hubs`` by rigid elements holding all six components
    (the propellers' rigid bodies): a beam element touching one is a mount beam."""
    bodies = _Bodies()
    for link in _links(deck):
        if link.free is None:
            bodies.join(link.a, link.b)
    roots = {bodies.find(h) for h in hubs}
    return {g for g in bodies.parent if bodies.find(g) in roots} | set(hubs)


def _hinges(deck, links: list[Link], tol: float) -> list[Hinge]:
    springs = {}
    for e in sorted(deck.bdf.elements.values(), key=lambda e: e.eid):
        if e.type != "CELAS2":
            continue
        card = f"CELAS2 {e.eid}"
        n1, n2 = (int(n) if n else 0 for n in e.nodes)
        if not n1 or not n2:
            raise deck.fail(f"{card} is grounded (one grid only): propwhirl's springs are mount "
                            "hinges between two grids")
        deck.grid(n1, card)
        deck.grid(n2, card)
        springs[card] = (frozenset((n1, n2)), int(e.c1 or 0), int(e.c2 or 0), e)
    out, used = [], set()
    for link in links:
        if link.free is None:
            continue
        pair = frozenset((link.a, link.b))
        on = [c for c, (p, c1, c2, _) in springs.items()
              if p == pair and c1 == c2 == link.free]
        if not on:
            raise deck.fail(f"{link.card} leaves {HINGES[link.free]} free between GRID {link.a} "
                            f"and GRID {link.b} but no CELAS2 joins them on component "
                            f"{link.free}: a hinge without its spring")
        if len(on) > 1:
            raise deck.fail(f"{on[0]} and {on[1]} both spring the hinge of {link.card}: one "
                            "CELAS2 per hinge")
        card = on[0]
        used.add(card)
        e = springs[card][3]
        pa, pb = deck.grids[link.a].xyz, deck.grids[link.b].xyz
        if np.linalg.norm(pa - pb) > tol:
            raise deck.fail(f"{link.card}: GRID {link.a} and GRID {link.b} are "
                            f"{np.linalg.norm(pa - pb):.6g} m apart: a hinge joins two grids at "
                            "one point")
        K = float(e.k) * deck.u.rotational_stiffness
        if not K > 0:
            raise deck.fail(f"{card}: K = {e.k!r} must be > 0 (a mount stiffness)")
        ge = float(e.ge or 0.0)
        if not 0.0 <= ge <= 2.0:
            raise deck.fail(f"{card}: GE = {e.ge!r} is outside the valid range [0, 2] of a "
                            "mount's structural damping g")
        out.append(Hinge(link, card, K, ge, float(pa[0])))
    for card in springs:
        if card not in used:
            raise deck.fail(f"{card} is no hinge's spring: propwhirl's springs are CELAS2 on a "
                            "hinge (an RBE2 or RBAR leaving R_y or R_z free between the same "
                            "two grids, on that component)")
    return out


def _masses(deck) -> dict[int, list[Mass]]:
    """The CONM2 by grid, in SI and the basic frame; the shaft and inertia checks are the
    mount's (they need its wing grid)."""
    u, w = deck.u, deck.wtmass
    out: dict[int, list[Mass]] = {}
    for eid, c in sorted(deck.bdf.masses.items()):
        card = f"{c.type} {eid}"
        if c.type != "CONM2":
            raise deck.fail(f"{card}: not read: a mass is a CONM2")
        g = deck.grid(c.nid, card)
        X = np.asarray(c.X, dtype=float)
        i11, i21, i22, i31, i32, i33 = (float(x) for x in c.I)
        T = np.array([[i11, i21, i31], [i21, i22, i32], [i31, i32, i33]])
        cid = int(c.cid)
        if cid == -1:
            cg = X * u.length
        else:
            o, R = deck.frame(cid, card)
            cg = g.xyz + (R.T @ X) * u.length
            T = R.T @ T @ R
        T = T * u.inertia * w
        scale = max(float(np.trace(np.abs(T))), 1e-300)
        off = max(abs(T[0, 1]), abs(T[0, 2]), abs(T[1, 2]))
        if off > 1e-12 * scale:
            raise deck.fail(f"{card}: products of inertia (I21, I31, I32 in the basic frame, up "
                            f"to {off:.6g} kg m^2): propwhirl's masses have their inertia about "
                            "the pitch and yaw axes only")
        mass = float(c.mass) * u.mass * w
        if not mass > 0:
            raise deck.fail(f"{card}: mass {c.mass!r} must be > 0")
        if np.any(np.diag(T) < 0):
            raise deck.fail(f"{card}: a negative moment of inertia ({np.diag(T).tolist()})")
        out.setdefault(g.nid, []).append(Mass(card, g.nid, mass, tuple(float(c) for c in cg),
                                              float(T[0, 0]), float(T[1, 1]), float(T[2, 2])))
    return out


def read(deck, stick, hubs: tuple[int, ...]) -> list[Mount]:
    """The mount of each hub grid (in the order given), every grid, rigid element, spring and
    mass of the deck off the stick accounted for (one line naming what is not)."""
    stick_grids = set(stick.grids)
    links = _links(deck)
    bodies = _Bodies()
    for link in links:
        if link.free is None:
            bodies.join(link.a, link.b)
    tol = tolerance(float(stick.y[-1]))
    hinges = _hinges(deck, links, tol)
    masses = _masses(deck)
    used_grids = {g for link in links for g in (link.a, link.b)} | set(masses)
    groups = bodies.members(used_grids | stick_grids)
    body_of = {g: root for root, members in groups.items() for g in members}
    for root, members in groups.items():
        on = sorted(members & stick_grids)
        if len(on) > 1:
            card = next(k.card for k in links if k.free is None and body_of.get(k.a) == root)
            raise deck.fail(f"GRID {on[0]} and GRID {on[1]} of the stick are joined rigidly "
                            f"({card} ...): a second load path along the wing")
    at: dict[int, list[Hinge]] = {}
    for h in hinges:
        a, b = body_of[h.link.a], body_of[h.link.b]
        if a == b:
            raise deck.fail(f"{h.link.card}: its hinge joins two grids of one rigid body")
        at.setdefault(a, []).append(h)
        at.setdefault(b, []).append(h)

    def other(h: Hinge, body: int) -> int:
        a, b = body_of[h.link.a], body_of[h.link.b]
        return b if a == body else a

    def wing_grid(body: int) -> int | None:
        on = groups[body] & stick_grids
        return next(iter(on)) if on else None

    mounts, claimed, consumed, used_beams = [], set(), set(), set()
    for i, hub in enumerate(hubs):
        who = f"hub GRID {hub} (installation {i + 1})"
        if hub not in deck.grids:
            raise deck.fail(f"{who} is not in the file")
        if hub not in body_of:
            raise deck.fail(f"{who} is joined to nothing (no rigid element, no mass)")
        b0 = body_of[hub]
        w = wing_grid(b0)
        pitch = yaw = None
        on_beams = [mb for mb in stick.mount_beams if {mb.a, mb.b} & groups[b0]]
        if w is not None:
            if at.get(b0) or on_beams:
                other_mount = at[b0][0].link.card if at.get(b0) else on_beams[0].card
                raise deck.fail(f"{who} is rigid on wing GRID {w} and its body also has the "
                                f"mount {other_mount}: two mounts in one")
            chain = [b0]
        elif on_beams:
            if at.get(b0) or len(on_beams) > 1:
                cards = [mb.card for mb in on_beams] + [h.link.card for h in at.get(b0, [])]
                raise deck.fail(f"{who}: its body has the mounts {', '.join(cards)}: a propeller "
                                "is mounted through one mount beam, or two hinges in a row")
            mb = on_beams[0]
            if {mb.a, mb.b} <= groups[b0]:
                raise deck.fail(f"{mb.card} joins two grids of {who}'s rigid body")
            w = mb.b if mb.a in groups[b0] else mb.a
            if w not in stick_grids:
                raise deck.fail(f"{who}: its mount beam {mb.card} reaches GRID {w}, not a grid "
                                "of the wing's stick: a mount beam joins the propeller's rigid "
                                "body to a stick grid")
            pitch, yaw = (Hinge(Link(mb.card, w, mb.b if w == mb.a else mb.a, free), mb.card,
                                K, mb.ge, mb.x_mid)
                          for free, K in ((5, mb.EI_vertical / mb.length),
                                          (6, mb.EI_chordwise / mb.length)))
            used_beams.add(mb.card)
            chain = [b0]
        else:
            h0 = at.get(b0, [])
            if len(h0) != 1:
                raise deck.fail(f"{who}: its body (GRID {', '.join(map(str, sorted(groups[b0])))}) "
                                f"has {len(h0)} hinges: a propeller is rigid on a wing grid or "
                                "mounted through a pitch and a yaw hinge in a row")
            b1 = other(h0[0], b0)
            h1 = [h for h in at.get(b1, []) if h is not h0[0]]
            if wing_grid(b1) is not None or len(h1) != 1:
                raise deck.fail(f"{who}: its mount has the hinge {h0[0].link.card} "
                                f"({HINGES[h0[0].link.free]}) "
                                + ("and then the wing" if wing_grid(b1) is not None else
                                   f"and then {len(h1)} more") + ": a flexible mount is a pitch "
                                "and a yaw hinge in a row between the propeller and a wing grid")
            b2 = other(h1[0], b1)
            w = wing_grid(b2)
            if w is None:
                raise deck.fail(f"{who}: its mount's hinges {h0[0].link.card} and "
                                f"{h1[0].link.card} do not reach a wing grid: a flexible mount "
                                "is two hinges between the propeller and a wing grid")
            if h0[0].link.free == h1[0].link.free:
                raise deck.fail(f"{who}: both hinges of its mount ({h0[0].link.card}, "
                                f"{h1[0].link.card}) are {HINGES[h0[0].link.free]}: a flexible "
                                "mount has a pitch (R_y) and a yaw (R_z) hinge")
            for g in groups[b1] | (groups[b2] - stick_grids):
                if g in masses:
                    raise deck.fail(f"{masses[g][0].card} on GRID {g} is part of {who}'s "
                                    "mount but not of the propeller (it sits "
                                    + ("between the hinges" if g in groups[b1] else
                                       "on the wing's side of the hinges") + "): propwhirl's "
                                    "mount is massless")
            pitch, yaw = sorted((h0[0], h1[0]), key=lambda h: h.link.free)
            chain = [b0, b1, b2]
        on_hub = masses.get(hub, [])
        if len(on_hub) != 1:
            raise deck.fail(f"{who} carries {len(on_hub)} CONM2"
                            + (f" ({', '.join(m.card for m in on_hub)})" if on_hub else "")
                            + ": the rotor is one CONM2 on the hub grid")
        wing_xyz = deck.grids[w].xyz
        body = [m for g in sorted(groups[b0]) for m in masses.get(g, [])]
        rotor = on_hub[0]
        props = [rotor] + [m for m in body if m is not rotor]
        for m in props:
            off = np.asarray(m.cg) - wing_xyz
            if abs(off[1]) > tol or abs(off[2]) > tol:
                axis = "y" if abs(off[1]) >= abs(off[2]) else "z"
                raise deck.fail(f"{m.card} on GRID {m.grid}: its mass lies "
                                f"{max(abs(off[1]), abs(off[2])):.6g} m off (in {axis}) the "
                                f"propeller's shaft through wing GRID {w}: propwhirl's "
                                "propeller masses lie on the shaft, chordwise through the "
                                "wing's axis")
            if m is not rotor and m.i11 > 0.0:
                raise deck.fail(f"{m.card}: I11 = {m.i11:.6g} kg m^2 (roll, about the shaft): "
                                "only the rotor's (the hub's CONM2: its spin inertia) is read; "
                                "propwhirl's nacelle does not roll")
        for h in (pitch, yaw):
            if h is None:
                continue
            for g in (h.link.a, h.link.b):
                off = deck.grids[g].xyz - wing_xyz
                if abs(off[1]) > tol or abs(off[2]) > tol:
                    raise deck.fail(f"{h.link.card}: its hinge GRID {g} lies off the "
                                    f"propeller's shaft through wing GRID {w} (y, z offsets "
                                    f"{off[1]:.6g}, {off[2]:.6g} m): propwhirl's pivots lie on "
                                    "the shaft")
        for m in props:
            consumed.add(m.card)
        for b in chain:
            claimed |= groups[b] - stick_grids
        mounts.append(Mount(hub, w, stick.grids.index(w), tuple(props), pitch, yaw))
    for mb in stick.mount_beams:
        if mb.card not in used_beams:
            raise deck.fail(f"{mb.card} (GRID {mb.a}-{mb.b}) is off the stick and mounts no "
                            "named hub: name its propeller's hub grid (--hubs), or remove it")
    _shared(deck, mounts, hubs, body_of)
    _leftovers(deck, stick, masses, consumed, used_grids, claimed, links)
    return mounts


def _shared(deck, mounts: list[Mount], hubs, body_of) -> None:
    for i, a in enumerate(mounts):
        for j in range(i):
            b = mounts[j]
            if body_of[a.hub] == body_of[b.hub]:
                raise deck.fail(f"hub GRID {b.hub} and hub GRID {a.hub} (installations {j + 1} "
                                f"and {i + 1}) are one rigid body: one propeller per body")
            if a.wing_grid == b.wing_grid:
                raise deck.fail(f"hub GRID {b.hub} and hub GRID {a.hub} (installations {j + 1} "
                                f"and {i + 1}) are both mounted on wing GRID {a.wing_grid}: one "
                                "propeller per wing grid")


def _leftovers(deck, stick, masses, consumed, used_grids, claimed, links) -> None:
    stick_grids = set(stick.grids)
    for g, ms in sorted(masses.items()):
        for m in ms:
            if m.card in consumed:
                continue
            if g in stick_grids:
                raise deck.fail(f"{m.card} on wing GRID {g}: a point mass on the wing outside "
                                "every propeller: propwhirl's wing carries distributed mass "
                                "only (add it to the NSM of the elements beside it), or name "
                                "its propeller's hub grid (--hubs)")
            raise deck.fail(f"{m.card} on GRID {g} belongs to no propeller: name its hub grid "
                            "(--hubs)")
    for g in sorted(used_grids - stick_grids - claimed):
        card = next((k.card for k in links if g in (k.a, k.b)), "a rigid element")
        raise deck.fail(f"GRID {g} ({card}) belongs to no propeller: name its hub grid "
                        "(--hubs), or remove it")
    refs = {int(e.g0) for e in deck.bdf.elements.values()
            if e.type in ("CBAR", "CBEAM") and e.g0 is not None}
    for g in sorted(set(deck.grids) - used_grids - stick_grids - refs):
        raise deck.fail(f"GRID {g} is joined to nothing (no element, rigid element or mass): "
                        "remove it")


def installation(deck, mount: Mount, inst: Installation, wing: Wing, stick) -> Installation:
    """The base model's installation ``inst`` with the deck's mount: its position (the wing
    grid's y), mount, masses, inertia and spin inertia, and for a flexible mount its pivots,
    stiffness and damping (the base propeller's damping kind kept: GE is g = 2 zeta)."""
    nodes = wing.node_properties()
    a_b = float(nodes["a"][mount.node] * nodes["b"][mount.node])
    # the stick's x at the propeller's wing grid (a swept stick's grids move aft outboard)
    x0 = float(stick.positions[mount.node][0] if stick.sweep else stick.origin[0])
    who = f"hub GRID {mount.hub}"

    def aft(x_basic: float) -> float:          # aft of the mid-chord at the propeller's node
        return x_basic - x0 + a_b

    p = inst.propeller
    try:
        points = [PointMass(m.mass, aft(m.x)) for m in mount.masses]
    except v.InputError as exc:
        raise deck.fail(f"{who}: its masses: {exc}") from None
    changes: dict = dict(rotor=points[0], masses=tuple(points[1:]),
                         spin_inertia=mount.masses[0].i11 or None)
    if mount.pitch is not None:
        factor = 0.5 if p.damping == "zeta" else 1.0
        changes.update(pivot_pitch=aft(mount.pitch.x), pivot_yaw=aft(mount.yaw.x),
                       K_theta=mount.pitch.K, K_psi=mount.yaw.K, f_theta=None, f_psi=None,
                       damping_theta=factor * mount.pitch.ge, damping_psi=factor * mount.yaw.ge)
    l_theta = changes.get("pivot_pitch", p.pivot_pitch)
    l_psi = changes.get("pivot_yaw", p.pivot_yaw)
    i22 = sum(m.i22 for m in mount.masses)
    i33 = sum(m.i33 for m in mount.masses)
    if i22 or i33:
        m = np.array([q.mass for q in points])
        x = np.array([q.x for q in points])
        changes["inertia"] = {"I_theta_P": float(np.sum(m * (x - l_theta) ** 2) + i22),
                              "I_psi_P": float(np.sum(m * (x - l_psi) ** 2) + i33)}
    else:
        changes["inertia"] = None
    try:
        propeller = replace(p, **changes)
    except v.InputError as exc:
        raise deck.fail(f"{who}: the propeller it makes is invalid: {exc}") from None
    mount_kind = "rigid" if mount.pitch is None else "flexible"
    return replace(inst, propeller=propeller, y=float(stick.y[mount.node]), mount=mount_kind)


__all__ = ["Hinge", "Link", "Mass", "Mount", "MountBeam", "installation", "read",
           "rigid_body_grids"]
