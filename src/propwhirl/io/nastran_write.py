"""A beam model as a NASTRAN SOL 103 deck (normal modes): :func:`write_bdf`, :func:`deck`.

Plain text in NASTRAN's large-field format (16 characters a field, continuation lines
starting with ``*``); no pyNastran is needed to write (it is needed to read:
:mod:`propwhirl.io.nastran_read`, which reads these decks back into the same model).  How the
deck holds the model is in :mod:`propwhirl.io.nastran` and docs/modal-structures.md
("NASTRAN bulk data"):

* the wing: GRID 1 … n+1 on its elastic axis along basic y (x aft, z up; the root grid 1
  clamped by SPC1 1, the other grids' axial T_y — and, for a wing rigid in its plane, T_x and
  R_z — held by their GRID PS field), CBEAM 1 … n with the orientation vector (0, 0, 1);
  one PBEAM per distinct section: MAT1 1 is a unit material (E = G = 1, RHO = 0) so that I1 is
  EI, I2 EI_chordwise (I1 again for a wing rigid in its plane: those DOFs are held) and J GJ,
  in the deck's units; the mass is the PBEAM's NSM (the mass per length), its c.g. offset M2
  aft of the axis (x_alpha_b) and NSI its polar inertia about that c.g.
  (ρI_p − m x_alpha_b²); K1 = K2 = 0 (no shear flexibility: Euler–Bernoulli);
* propeller j (from 1): grids and elements numbered from 1000 j — the hub grid 1000 j + 1
  with the rotor's CONM2 (I11 the spin inertia; I22, I33 the part of a measured pitch or yaw
  inertia its point masses do not give), each further point mass a CONM2 on a grid of its
  own (1000 j + 2, …), a balance mass (1000 j + 80) when a measured M_P or S_theta_P is not
  its point masses'; a rigid mount is one RBE2 from the wing grid; a flexible mount is the
  pitch hinge (grids 1000 j + 91, 92 at the pitch pivot: an RBE2 leaving R_y free and
  CELAS2 1000 j + 201 on R_y, K_theta, GE = the structural damping g) and the yaw hinge
  (grids 1000 j + 93, 94 at the yaw pivot: R_z, CELAS2 1000 j + 202, K_psi).

``PARAM,COUPMASS,1`` asks NASTRAN for coupled (consistent) beam masses, nearer propwhirl's
cubic-Hermite element than its default lumped masses; the deck is NASTRAN's model of the same
structure, not propwhirl's element matrices (docs/modal-structures.md states the
differences).  What the deck cannot hold is refused with one line naming the field: a model
that is not a wing with propellers (an isolated propeller, a typical section, a modal model),
spanwise properties given as functions of y, a measured inertia smaller than the point masses
give (a negative CONM2 inertia).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from propwhirl import __version__, fileio
from propwhirl import validate as v
from propwhirl.io.nastran import UNIT_SYSTEMS, UnitSystem, unit_system
from propwhirl.model.propellers.propeller import Propeller
from propwhirl.model.systems import Installation, PropellerWing

#: The first id of propeller j's grids and elements is PROPELLER_IDS × (j + 1).
PROPELLER_IDS = 1000
#: Offsets within a propeller's block: its balance mass, the hinge grids, rigid elements and springs.
BALANCE, PITCH_WING, PITCH_PROP, YAW_WING, YAW_PROP = 80, 91, 92, 93, 94
RIGID, SPRING = 100, 200
#: Eigenvalues asked of EIGRL (or every DOF, when fewer).
EIGENVALUES = 30
#: A measured inertia within this fraction of its point masses' own is theirs (no CONM2 I22, I33).
_SAME = 1e-12


@dataclass(frozen=True)
class Card:
    """One bulk data card: its name and its fields after the name (int, float, str or None
    for a blank field), in NASTRAN's order."""

    name: str
    fields: tuple


@dataclass(frozen=True)
class Deck:
    """A model as a NASTRAN deck.

    Parameters
    ----------
    text : the deck (executive and case control, bulk data)
    cards : the bulk data cards, in the order written
    hubs : the hub grid of each installation, in the model's order (``--hubs`` of
        ``propwhirl import``)
    units : the deck's unit system
    """

    text: str
    cards: tuple[Card, ...]
    hubs: tuple[int, ...]
    units: str


def _real(x: float) -> str:
    """A real number in 16 characters or fewer, with a decimal point (NASTRAN's rule): the
    most significant digits that fit (17, which read back as ``x`` exactly, when they do;
    else at least eleven — ten beyond 1e±99 —, the exponent's ``E`` left out when that gains
    a digit, as NASTRAN allows: ``-3.6519707064+16``)."""
    x = float(x)
    if not math.isfinite(x):
        raise ValueError(f"not a finite number: {x!r}")
    for digits in range(17, 0, -1):
        text = f"{x:.{digits}g}"
        if "e" not in text:
            text = text if "." in text else text + "."
            if len(text) <= 16:
                return text
            continue
        mantissa, exponent = text.split("e")
        mantissa = mantissa if "." in mantissa else mantissa + "."
        for form in (f"{mantissa}E{exponent}", f"{mantissa}{exponent}"):
            if len(form) <= 16:
                return form
    raise ValueError(f"{x!r} does not fit a large field")      # never: 1 digit fits


def _field(value) -> str:
    if value is None:
        return ""
    if isinstance(value, (bool, np.bool_)):
        raise TypeError("a NASTRAN field is no boolean")
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    if isinstance(value, (float, np.floating)):
        return _real(value)
    return str(value)


def card_text(card: Card) -> str:
    """The card in large-field format: ``NAME*`` and four 16-character fields a line,
    continuation lines starting with ``*``; trailing blank fields left out."""
    fields = [_field(f) for f in card.fields]
    while fields and fields[-1] == "":
        fields.pop()
    lines = []
    for start in range(0, max(len(fields), 1), 4):
        head = f"{card.name}*" if start == 0 else "*"
        body = "".join(f"{f:>16s}" for f in fields[start:start + 4])
        lines.append(f"{head:<8s}{body}".rstrip())
    return "\n".join(lines) + "\n"


def _propeller_ids(j: int) -> int:
    return PROPELLER_IDS * (j + 1)


class _Builder:
    """Collects the cards of one model in one unit system."""

    def __init__(self, model: PropellerWing, units: UnitSystem):
        self.model, self.u = model, units
        self.cards: list[Card] = []
        self.comments: list[str] = []

    def add(self, name: str, *fields) -> None:
        self.cards.append(Card(name, tuple(fields)))

    # lengths, masses, ... in the deck's units
    def L(self, x): return float(x) / self.u.length                    # noqa: E704
    def M(self, x): return float(x) / self.u.mass                      # noqa: E704

    def grid(self, gid: int, x: float, y: float, z: float, ps: str | None = None) -> None:
        self.add("GRID", gid, None, self.L(x), self.L(y), self.L(z), None, ps)

    def conm2(self, eid: int, gid: int, mass: float, i11=0.0, i22=0.0, i33=0.0) -> None:
        u = self.u
        inertia = [i11 / u.inertia, 0.0, i22 / u.inertia, 0.0, 0.0, i33 / u.inertia]
        if not any(inertia):
            self.add("CONM2", eid, gid, 0, self.M(mass))
        else:
            self.add("CONM2", eid, gid, 0, self.M(mass), 0.0, 0.0, 0.0, None, *inertia)


def _check_model(model) -> PropellerWing:
    if not isinstance(model, PropellerWing):
        what = type(model).__name__
        raise v.InputError(f"a {what} is not a beam model: a NASTRAN deck is written of a "
                           "wing with propellers (type \"propeller-wing\")")
    return model


def _wing(b: _Builder) -> None:
    """The wing: grids, CBEAMs, PBEAMs, MAT1, the root's SPC1."""
    wing = b.model.wing
    u = b.u
    p = wing.element_properties()
    inplane = wing.inplane_properties()
    EIc = inplane["EI_chordwise"] if inplane is not None else p["EI"]
    nsi = p["rho_Ip"] - p["m"] * p["x_alpha_b"] ** 2
    ps = "2" if wing.in_plane else "126"
    for i, y in enumerate(wing.node_y):
        b.grid(i + 1, 0.0, y, 0.0, None if i == 0 else ps)
    sections: dict[tuple, int] = {}
    for e in range(wing.element_count):
        key = (p["EI"][e] / u.rigidity, EIc[e] / u.rigidity, p["GJ"][e] / u.rigidity,
               p["m"][e] / u.mass_per_length, p["x_alpha_b"][e] / u.length,
               nsi[e] / u.inertia_per_length)
        pid = sections.setdefault(key, len(sections) + 1)
        b.add("CBEAM", e + 1, pid, e + 1, e + 2, 0.0, 0.0, 1.0)
    for (I1, I2, J, nsm, m2, nsi_e), pid in sections.items():
        # PBEAM: end A, its (blank) stress points, end B = end A, its stress points, then
        # K1 K2 S1 S2 NSI(A) NSI(B) CW(A) CW(B), M1(A) M2(A) M1(B) M2(B) N1(A) N2(A) N1(B) N2(B)
        b.add("PBEAM", pid, 1, 1.0, I1, I2, 0.0, J, nsm,
              *([None] * 8),
              "YES", 1.0, 1.0, I1, I2, 0.0, J, nsm,
              *([None] * 8),
              0.0, 0.0, 0.0, 0.0, nsi_e, nsi_e, 0.0, 0.0,
              0.0, m2, 0.0, m2, 0.0, 0.0, 0.0, 0.0)
    b.add("MAT1", 1, 1.0, 1.0, None, 0.0)
    b.comments.append(
        f"wing {_title(wing.name)!r}: GRID 1-{wing.n_nodes} on its elastic axis (GRID 1 the clamped "
        f"root), CBEAM 1-{wing.element_count}, PBEAM 1-{len(sections)}; MAT1 1 is a unit "
        "material (E = G = 1, RHO = 0): I1 = EI, I2 = EI_chordwise, J = GJ; the mass per "
        "length is NSM, its c.g. M2 aft of the axis, NSI its polar inertia about that c.g."
        + ("" if wing.in_plane else "; rigid in its plane (PS 126: T_x, R_z held)"))


def _masses(j: int, propeller: Propeller, in_plane: bool) -> tuple[list, float, float]:
    """The point masses (mass [kg], x [m] aft of the mid-chord) of propeller j as written —
    the rotor first, a balance mass last when a measured M_P or S_theta_P is not theirs —
    and the CONM2 I22, I33 [kg m²] on the rotor that carry the rest of a measured I_theta_P,
    I_psi_P."""
    p = propeller
    name = f"propellers[{j}].propeller.inertia"
    masses = [(pm.mass, pm.x) for pm in p.all_masses]
    given = dict(p.inertia or {})
    m = np.array([q[0] for q in masses])
    x = np.array([q[1] for q in masses])
    M0, S0 = float(m.sum()), float(np.sum(m * (x - p.pivot_pitch)))
    M_P, S_P = given.get("M_P", M0), given.get("S_theta_P", S0)
    if not (math.isclose(M_P, M0, rel_tol=_SAME) and math.isclose(S_P, S0, rel_tol=_SAME,
                                                                   abs_tol=_SAME * M0)):
        dM = M_P - M0
        if in_plane:
            raise v.InputError(f"{name}: a measured M_P or S_theta_P on a wing that bends in "
                               "its plane cannot be written as NASTRAN masses (its in-plane "
                               "static moment comes from the point masses): give them as "
                               "point masses")
        if not dM > _SAME * M0:
            raise v.InputError(f"{name}: M_P = {M_P!r} kg is not more than its point masses' "
                               f"{M0!r} kg: the difference cannot be a NASTRAN mass")
        masses.append((dM, p.pivot_pitch + (S_P - S0) / dM))
    m = np.array([q[0] for q in masses])
    x = np.array([q[1] for q in masses])
    rest = []
    for key, pivot in (("I_theta_P", p.pivot_pitch), ("I_psi_P", p.pivot_yaw)):
        own = float(np.sum(m * (x - pivot) ** 2))
        value = given.get(key, own)
        if math.isclose(value, own, rel_tol=_SAME):
            rest.append(0.0)
        elif value > own:
            rest.append(value - own)
        else:
            raise v.InputError(f"{name}: {key} = {value!r} kg m^2 is less than its point masses "
                               f"give ({own!r} kg m^2): the rest would be a negative CONM2 "
                               "inertia")
    return masses, rest[0], rest[1]


def _propeller(b: _Builder, j: int, inst: Installation, node: int) -> int:
    """Propeller j's grids, masses, rigid elements and springs; returns its hub grid."""
    wing, u = b.model.wing, b.u
    p = inst.propeller
    nodes = wing.node_properties()
    a_b = float(nodes["a"][node] * nodes["b"][node])      # elastic axis aft of mid-chord [m]
    y = float(wing.node_y[node])
    first = _propeller_ids(j)
    w = node + 1                                          # its wing grid

    def x_of(x_mid: float) -> float:                      # basic x of a position aft of mid-chord
        return x_mid - a_b

    masses, i22, i33 = _masses(j, p, wing.in_plane)
    mass_grids = []
    for k, (mass, x) in enumerate(masses):
        gid = first + (BALANCE if k == len(p.all_masses) else k + 1)
        b.grid(gid, x_of(x), y, 0.0)
        if k == 0:
            b.conm2(gid, gid, mass, p.I_Omega, i22, i33)
        else:
            b.conm2(gid, gid, mass)
        mass_grids.append(gid)
    hub = mass_grids[0]
    if inst.mount == "rigid":
        b.add("RBE2", first + RIGID + 1, w, "123456", *mass_grids)
        b.comments.append(f"propeller {j + 1} {_title(p.name)!r}: hub GRID {hub} (rotor CONM2 "
                          f"{hub}), rigid on wing GRID {w} (RBE2 {first + RIGID + 1})")
        return hub
    K_theta, K_psi = p.stiffness()
    g_theta, g_psi = (2.0 * z for z in p.viscous_damping_ratios())     # GE = g = 2 zeta
    b.grid(first + PITCH_WING, x_of(p.pivot_pitch), y, 0.0)
    b.grid(first + PITCH_PROP, x_of(p.pivot_pitch), y, 0.0)
    b.grid(first + YAW_WING, x_of(p.pivot_yaw), y, 0.0)
    b.grid(first + YAW_PROP, x_of(p.pivot_yaw), y, 0.0)
    b.add("RBE2", first + RIGID + 1, w, "123456", first + PITCH_WING)
    b.add("RBE2", first + RIGID + 2, first + PITCH_WING, "12346", first + PITCH_PROP)
    b.add("CELAS2", first + SPRING + 1, K_theta / u.rotational_stiffness,
          first + PITCH_WING, 5, first + PITCH_PROP, 5, g_theta)
    b.add("RBE2", first + RIGID + 3, first + PITCH_PROP, "123456", first + YAW_WING)
    b.add("RBE2", first + RIGID + 4, first + YAW_WING, "12345", first + YAW_PROP)
    b.add("CELAS2", first + SPRING + 2, K_psi / u.rotational_stiffness,
          first + YAW_WING, 6, first + YAW_PROP, 6, g_psi)
    b.add("RBE2", first + RIGID + 5, first + YAW_PROP, "123456", *mass_grids)
    b.comments.append(
        f"propeller {j + 1} {_title(p.name)!r}: hub GRID {hub} (rotor CONM2 {hub}), flexible mount "
        f"on wing GRID {w}: pitch hinge GRID {first + PITCH_WING}-{first + PITCH_PROP} "
        f"(CELAS2 {first + SPRING + 1} on R_y), yaw hinge GRID {first + YAW_WING}-"
        f"{first + YAW_PROP} (CELAS2 {first + SPRING + 2} on R_z)")
    return hub


def _title(name: str) -> str:
    text = "".join(c if " " <= c <= "~" and c != "$" else "?" for c in name)
    return text[:60] or "propwhirl model"


def deck(model, units: str = "si") -> Deck:
    """The NASTRAN SOL 103 deck of the beam model ``model`` (a
    :class:`~propwhirl.model.systems.PropellerWing`) in the unit system ``units`` (one of
    :data:`propwhirl.io.nastran.UNIT_SYSTEMS`).

    Parameters
    ----------
    model : PropellerWing
        the model; its wing's spanwise properties evaluated on its mesh (SI)
    units : str
        "si" (m, kg, s, N), "mm-t-s" (mm, t, s, N) or "in-lbf-s" (in, lbf s²/in, s, lbf)

    Returns
    -------
    Deck
        the text, the bulk data cards and the hub grid of each installation

    Raises
    ------
    InputError
        a model that is not a beam wing, unknown units, a measured propeller inertia the
        deck's masses cannot carry (one line naming the field)
    """
    model = _check_model(model)
    u = unit_system(units, "NASTRAN deck")
    b = _Builder(model, u)
    _wing(b)
    hubs = tuple(_propeller(b, j, inst, node)
                 for j, (inst, node) in enumerate(zip(model.propellers, model.nodes)))
    b.add("SPC1", 1, "123456", 1)
    n_dofs = (model.wing.n_nodes - 1) * (5 if model.wing.in_plane else 3) \
        + 2 * len(model.flexible)
    b.add("EIGRL", 1, None, None, min(EIGENVALUES, n_dofs))
    b.add("PARAM", "COUPMASS", 1)
    head = [f"$ propwhirl {__version__}: {_title(model.name)!r} as a NASTRAN SOL 103 "
            "deck (normal modes)",
            f"$ units: {u.name} ({u.description}); basic frame: x aft, y outboard along "
            "the wing, z up",
            *(f"$ {c}" for c in b.comments),
            "$ read back: propwhirl import THIS.bdf --out MODEL.toml --units "
            f"{u.name} --base BASE.toml" + (f" --hubs {' '.join(map(str, hubs))}" if hubs
                                            else "")]
    control = ["SOL 103", "CEND", f"TITLE = {_title(model.name)}", "ECHO = NONE",
               "SPC = 1", "METHOD = 1", "DISPLACEMENT = ALL", "BEGIN BULK"]
    text = "\n".join(head + control) + "\n" + "".join(card_text(c) for c in b.cards) \
        + "ENDDATA\n"
    return Deck(text, tuple(b.cards), hubs, u.name)


def write_bdf(model, path: str | Path, units: str = "si") -> Deck:
    """Write ``model`` as a NASTRAN SOL 103 deck to ``path`` (atomically: :func:`deck`).

    Parameters
    ----------
    model : PropellerWing
        the beam model
    path : str or Path
        the BDF file to write
    units : str
        the deck's unit system ("si", "mm-t-s", "in-lbf-s")

    Returns
    -------
    Deck
        what was written, with the hub grid of each installation

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     d = write_bdf(wingtip_propeller_wing(), pathlib.Path(folder) / "wingtip.bdf")
    >>> d.hubs
    (1001,)
    """
    d = deck(model, units)
    fileio.write_text(path, d.text, encoding="ascii", what="NASTRAN deck")
    return d


__all__ = ["Card", "Deck", "UNIT_SYSTEMS", "card_text", "deck", "write_bdf"]
