"""Hand-written NASTRAN decks for the BDF reader's tests (tests/nastran): a straight stick of
four CBARs along y with one propeller at its tip, its numbers given in SI and written in any
of propwhirl's unit systems, in free-field format (a comma between fields, eight fields a
line, continuation lines starting with a comma) — the way a person types a deck, independent
of propwhirl's own writer.

A card is ``[name, field, ...]``; a numeric field may be a :class:`Q`, a quantity in SI with
its kind, converted to the deck's units when the text is made.  :func:`standard` gives the
cards; tests change, add or drop cards (:func:`replace_card`, :func:`drop`) and write them
with :func:`text`.
"""
from __future__ import annotations

from dataclasses import dataclass

from propwhirl.io.nastran import UNIT_SYSTEMS, UnitSystem

#: The stick: grids 1-5 at y = 0 ... 2 m, x = STICK_X, z = STICK_Z [m].
STICK_X, STICK_Z = 0.3, 0.1
Y = (0.0, 0.5, 1.0, 1.5, 2.0)
E, G, RHO = 7.0e10, 2.7e10, 2700.0               # Pa, Pa, kg/m^3
A, I1, I2, J, NSM = 0.01, 2.0e-6, 8.0e-6, 3.0e-6, 5.0   # m^2, m^4, m^4, m^4, kg/m
#: The propeller at grid 5: the rotor CONM2 301 on hub GRID 101, a nacelle mass CONM2 302 on
#: GRID 102 (basic x [m]); flexible: the pitch hinge GRID 111-112 and yaw hinge GRID 113-114.
HUB_X, NACELLE_X, PITCH_X, YAW_X = -0.7, -0.2, -0.1, -0.3
ROTOR, NACELLE = 10.0, 20.0                      # kg
SPIN, I22, I33 = 2.0, 1.5, 2.5                   # kg m^2
K_THETA, K_PSI, GE_THETA, GE_PSI = 5.0e4, 6.0e4, 0.02, 0.04   # N m/rad, -
#: The mount beam (``standard("beam")``): CBAR 7 from the tip GRID 5 forward to GRID 115 at
#: basic x BEAM_X [m], PBAR 11 of MAT1 21 (massless, GE = GE_THETA) with E I / L = K_THETA in
#: its vertical plane and K_PSI in its chordwise one.
BEAM_X = STICK_X - 0.1
BEAM_L = STICK_X - BEAM_X


@dataclass(frozen=True)
class Q:
    """A quantity in SI: value and kind (a property of :class:`UnitSystem` giving the SI
    size of its deck unit)."""

    value: float
    kind: str


def L(x): return Q(x, "length")                  # noqa: E704


def grid(nid: int, x: float, y: float, z: float, ps: str | None = None, cp: int | None = None):
    return ["GRID", nid, cp, L(x), L(y), L(z), None, ps]


def conm2(eid: int, nid: int, mass: float, *, x=0.0, i11=0.0, i22=0.0, i33=0.0, cid=None,
          i21=0.0):
    return ["CONM2", eid, nid, cid, Q(mass, "mass"), L(x), L(0.0), L(0.0), None,
            Q(i11, "inertia"), Q(i21, "inertia"), Q(i22, "inertia"), Q(0.0, "inertia"),
            Q(0.0, "inertia"), Q(i33, "inertia")]


def pbeam(pid: int = 10, mid: int = 20, *, nsi: float = 0.0, m2: float = 0.0) -> list:
    """The standard section as a PBEAM (constant: end B = end A, stress output YESA), its
    NSM's polar inertia NSI [kg m] about its c.g. M2 [m] aft of the axis (plane 1 vertical),
    K1 = K2 = 0 (shear-rigid)."""
    end = [Q(A, "area"), Q(I1, "moment_of_area"), Q(I2, "moment_of_area"), 0.0,
           Q(J, "moment_of_area"), Q(NSM, "mass_per_length")]
    return ["PBEAM", pid, mid, *end, *([None] * 8), "YESA", 1.0, *end,
            0.0, 0.0, 0.0, 0.0, Q(nsi, "inertia_per_length"), Q(nsi, "inertia_per_length"),
            0.0, 0.0, 0.0, L(m2), 0.0, L(m2), 0.0, 0.0, 0.0, 0.0]


def beams(cards: list[list]) -> list[list]:
    """The cards with CBEAM for CBAR (the same fields)."""
    return [["CBEAM"] + c[1:] if c[0] == "CBAR" else c for c in cards]


def standard(mount: str = "rigid") -> list[list]:
    """The cards of the standard deck: stick, PBAR, MAT1, the propeller (``mount`` "rigid",
    "flexible" or "beam": a mount beam, CBAR 7), the root's SPC1 1, EIGRL."""
    cards = [grid(k + 1, STICK_X, y, STICK_Z, None if k == 0 else "2") for k, y in enumerate(Y)]
    cards += [["CBAR", k + 1, 10, k + 1, k + 2, 0.0, 0.0, 1.0] for k in range(4)]
    cards += [["PBAR", 10, 20, Q(A, "area"), Q(I1, "moment_of_area"), Q(I2, "moment_of_area"),
               Q(J, "moment_of_area"), Q(NSM, "mass_per_length")],
              ["MAT1", 20, Q(E, "modulus"), Q(G, "modulus"), None, Q(RHO, "density")],
              grid(101, HUB_X, 2.0, STICK_Z), grid(102, NACELLE_X, 2.0, STICK_Z),
              conm2(301, 101, ROTOR, i11=SPIN), conm2(302, 102, NACELLE, i22=I22, i33=I33),
              ["SPC1", 1, "123456", 1], ["EIGRL", 1, None, None, 10]]
    if mount == "rigid":
        cards.append(["RBE2", 201, 5, "123456", 101, 102])
        return cards
    if mount == "beam":
        i_v, i_c = K_THETA * BEAM_L / E, K_PSI * BEAM_L / E
        cards += [grid(115, BEAM_X, 2.0, STICK_Z),
                  ["CBAR", 7, 11, 5, 115, 0.0, 0.0, 1.0],
                  ["PBAR", 11, 21, Q(A, "area"), Q(i_v, "moment_of_area"),
                   Q(i_c, "moment_of_area"), Q(J, "moment_of_area")],
                  ["MAT1", 21, Q(E, "modulus"), Q(G, "modulus"), None, None, None, None,
                   GE_THETA],
                  ["RBE2", 201, 115, "123456", 101, 102]]
        return cards
    cards += [grid(111, PITCH_X, 2.0, STICK_Z), grid(112, PITCH_X, 2.0, STICK_Z),
              grid(113, YAW_X, 2.0, STICK_Z), grid(114, YAW_X, 2.0, STICK_Z),
              ["RBE2", 211, 5, "123456", 111],
              ["RBE2", 212, 111, "12346", 112],
              ["CELAS2", 221, Q(K_THETA, "rotational_stiffness"), 111, 5, 112, 5, GE_THETA],
              ["RBE2", 213, 112, "123456", 113],
              ["RBE2", 214, 113, "12345", 114],
              ["CELAS2", 222, Q(K_PSI, "rotational_stiffness"), 113, 6, 114, 6, GE_PSI],
              ["RBE2", 215, 114, "123456", 101, 102]]
    return cards


def replace_card(cards: list[list], name: str, cid: int, new: list | None) -> list[list]:
    """The cards with card ``name`` ``cid`` replaced by ``new`` (None: dropped)."""
    out = [c for c in cards if not (c[0] == name and c[1] == cid)]
    assert len(out) == len(cards) - 1, (name, cid)
    return out + ([new] if new is not None else [])


def drop(cards: list[list], name: str, cid: int) -> list[list]:
    return replace_card(cards, name, cid, None)


def _field(value, u: UnitSystem) -> str:
    if isinstance(value, Q):
        value = value.value / getattr(u, value.kind)
    if value is None:
        return ""
    if isinstance(value, float):
        text = repr(value)
        if "e" in text and "." not in text.split("e")[0]:
            text = text.replace("e", ".e")
        return text if ("." in text or "e" in text) else text + "."
    return str(value)


def card_lines(card: list, u: UnitSystem) -> str:
    fields = [_field(f, u) for f in card[1:]]
    lines = [",".join([card[0]] + fields[:8])]
    for k in range(8, len(fields), 8):
        lines.append("," + ",".join(fields[k:k + 8]))
    return "\n".join(lines) + "\n"


def text(cards: list[list], units: str = "si", *, control: bool = True, wtmass: float | None = None,
         enddata: bool = True) -> str:
    """The deck: executive and case control (SPC = 1, METHOD = 1) unless not ``control``,
    PARAM,WTMASS when given (every mass then divided by it), the cards, ENDDATA."""
    u = UNIT_SYSTEMS[units]
    if wtmass is not None:
        u = UnitSystem(u.name, u.length, u.mass * wtmass, u.force, u.description)
    head = "SOL 103\nCEND\nSPC = 1\nMETHOD = 1\nBEGIN BULK\n" if control else ""
    params = f"PARAM,WTMASS,{wtmass!r}\n" if wtmass is not None else ""
    body = "".join(card_lines(c, u) for c in cards)
    return head + params + body + ("ENDDATA\n" if enddata else "")


def with_mount_beams(deck, length: float) -> tuple[str, list[float]]:
    """A deck written by ``write_bdf`` (SI) with each propeller's two hinges (RBE2 + CELAS2
    pitch, then yaw) replaced by one mount beam: a massless CBAR of ``length`` [m] from the
    wing grid forward (−x) to a new grid that carries the propeller's rigid body, with
    E I / L = the pitch and yaw CELAS2's K in its vertical and chordwise planes and the
    pitch spring's GE on its MAT1 (a unit material, E = G = 1).  Returns the bulk data text
    and each mount beam's mid-point shift [m] (−length/2: where the spring model's pivots
    must be to be the same model)."""
    from propwhirl.io.nastran_write import Card, card_text
    assert deck.units == "si", deck.units
    cards = list(deck.cards)
    grids = {c.fields[0]: c for c in cards if c.name == "GRID"}
    rbe2 = [c for c in cards if c.name == "RBE2"]
    springs = [c for c in cards if c.name == "CELAS2"]
    hinge_grids, dropped, added, shifts = set(), set(), [], []
    for k, hub in enumerate(deck.hubs):
        # the chain: wing -> 1 (rigid), 1 -> 2 (pitch hinge), 2 -> 3 (rigid), 3 -> 4 (yaw
        # hinge), 4 -> the body (rigid, its last RBE2)
        last = next(c for c in rbe2 if hub in c.fields[3:])
        chain = [last]
        while True:
            before = [c for c in rbe2 if chain[-1].fields[1] in c.fields[3:]]
            if not before:
                break
            chain.append(before[0])
        chain = chain[::-1]                            # wing -> ... -> body
        assert len(chain) == 5, [c.fields for c in chain]
        wing = chain[0].fields[1]
        pitch = next(s for s in springs if s.fields[2:5:2] == (chain[1].fields[1],
                                                               chain[1].fields[3]))
        yaw = next(s for s in springs if s.fields[2:5:2] == (chain[3].fields[1],
                                                             chain[3].fields[3]))
        for c in chain[:-1]:
            dropped.add(("RBE2", c.fields[0]))
            hinge_grids |= {c.fields[1], c.fields[3]} - {wing}
        dropped |= {("CELAS2", pitch.fields[0]), ("CELAS2", yaw.fields[0])}
        x, y, z = grids[wing].fields[2:5]
        new, eid = 9000 + 10 * k, 9000 + 10 * k
        added += [Card("GRID", (new, None, x - length, y, z)),
                  Card("CBAR", (eid, eid, wing, new, 0.0, 0.0, 1.0)),
                  Card("PBAR", (eid, eid, 1.0, pitch.fields[1] * length,
                                yaw.fields[1] * length, 1.0)),
                  Card("MAT1", (eid, 1.0, 1.0, None, None, None, None, pitch.fields[6])),
                  Card("RBE2", (last.fields[0], new, "123456", *last.fields[3:]))]
        dropped.add(("RBE2", last.fields[0]))
        shifts.append(-length / 2)
    kept = [c for c in cards if (c.name, c.fields[0]) not in dropped
            and not (c.name == "GRID" and c.fields[0] in hinge_grids)]
    text = "".join(card_text(c) for c in kept + added) + "ENDDATA\n"
    return text, shifts
