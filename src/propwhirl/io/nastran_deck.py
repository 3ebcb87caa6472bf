"""A NASTRAN bulk data file as read: pyNastran parses it (the optional extra ``nastran``, in an
environment of its own: it needs numpy < 2) without cross-referencing, and :class:`Deck` looks
up and checks every card propwhirl reads — its errors one line naming the file, the card and
its id.  What the cards make (the stick, the beam wing, the propellers) is
:mod:`propwhirl.io.nastran_read`'s.
"""
from __future__ import annotations

import contextlib
import io
import math
import re
import warnings
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from propwhirl import validate as v
from propwhirl.io.nastran import INSTALL_HINT, UnitSystem

#: The cards read (the model), and those that are solution settings (not read).
MODEL_CARDS = ("GRID", "CORD2R", "CBAR", "CBEAM", "PBAR", "PBARL", "PBEAM", "PBEAML", "MAT1",
               "CONM2", "RBE2", "RBAR", "CELAS2", "SPC", "SPC1", "SPCADD")
SETTING_CARDS = ("EIGRL", "EIGR", "PARAM", "ENDDATA")
#: Cards a user may expect to work, and why they do not (the rest: the generic reason).
_WHY_NOT = {
    "CBUSH": "a mount spring is a CELAS2 on a hinge (an RBE2 leaving R_y or R_z free)",
    "CELAS1": "a mount spring is a CELAS2 (K on the card) on a hinge",
    "CONM1": "a mass is a CONM2",
    "CORD1R": "coordinate systems are CORD2R",
    "CORD2C": "coordinate systems are rectangular (CORD2R)",
    "CORD2S": "coordinate systems are rectangular (CORD2R)",
    "MPC": "the nacelle is rigid bodies (RBE2, RBAR) and hinges",
    "RBE3": "an RBE3 is an interpolation, not a rigid body: use RBE2 or RBAR",
    "CROD": "the wing is CBAR or CBEAM elements along one line",
    "CBUSH1D": "a mount spring is a CELAS2 on a hinge",
}


def fail(where: str, text: str) -> v.InputError:
    """The one-line InputError of a NASTRAN file: `where` (the file), then `text`."""
    return v.InputError(f"{where}: {text}")


# ============================================================================ parsing
def _pynastran():
    """pyNastran's BDF class and its errors, or a one-line InputError naming the extra."""
    try:
        from pyNastran.bdf.bdf import BDF
    except ImportError:
        raise v.InputError(f"reading a BDF needs pyNastran, which is not installed here: "
                           f"{INSTALL_HINT}") from None
    return BDF


def require_pynastran() -> None:
    """Nothing when pyNastran can be imported; else the one-line InputError naming the extra
    (a command checks this before it reads anything)."""
    _pynastran()


#: Cards whose first field shares one id space (NASTRAN: element ids unique across all
#: elements, rigid and mass elements included; property ids across properties).
ID_SPACES = (("CBAR", "CBEAM", "CELAS2", "CONM2", "RBE2", "RBAR"),
             ("PBAR", "PBARL", "PBEAM", "PBEAML"), ("MAT1",), ("GRID",), ("CORD2R",),
             ("EIGRL", "EIGR"))


def _sharing(file_text: str, ident: str, family: tuple[str, ...]) -> list[str]:
    """The cards of ``family`` in the file whose id is ``ident`` ("CBAR 1", "CELAS2 1")."""
    return [f"{name} {ident}" for name in family
            for i in _scanned_ids(file_text, name) if i == ident]


def _given_twice(where: str, file_text: str, ident: str, hint: str | None) -> v.InputError:
    """The one line for an id given twice: the cards that share it, named."""
    for family in ID_SPACES:
        if hint is not None and hint not in family:
            continue
        cards = _sharing(file_text, ident, family)
        if len(cards) > 1:
            if len(set(cards)) == 1:
                return fail(where, f"{cards[0]} is given twice (ids must be unique)")
            kind = "element ids" if family == ID_SPACES[0] else "ids"
            return fail(where, f"{' and '.join(sorted(set(cards)))} share one id ({kind} must "
                                f"be unique among {', '.join(family)})")
    return fail(where, f"{hint or 'a card'} {ident} is given twice (ids must be unique)")


def _parse_error(where: str, exc: Exception, file_text: str = "") -> v.InputError:
    """pyNastran's exception as one line naming the file (and the card and id it names)."""
    text = str(exc)
    first = text.strip().split("\n")[0].strip() or type(exc).__name__
    dup = re.search(r"IDs are not unique=\[([^\]]*)\]", text)
    old = re.search(r"old_\w+=\s*\n\s*([A-Z][A-Z0-9]*)\*?\s", text)
    if dup:
        ids = dup.group(1).split(",")[0].strip()
        return _given_twice(where, file_text, ids, old.group(1) if old else None)
    bare = re.fullmatch(r"(eid|sid|pid|mid|cid)=(\d+)", first)
    if isinstance(exc, AssertionError) and bare:      # pyNastran's assert on a second card
        return _given_twice(where, file_text, bare.group(2), None)
    if "nid=" in text and "old_node=" in text:
        nid = re.search(r"nid=(\d+)", text)
        return fail(where, f"GRID {nid.group(1) if nid else '?'} is given twice (ids must be "
                            "unique)")
    card = re.search(r"card=\[\s*'([A-Z0-9*]+)',\s*'([^']*)'", text)
    if card:
        return fail(where, f"{card.group(1).rstrip('*')} {card.group(2).strip()}: {first}")
    return fail(where, f"pyNastran could not read it: {type(exc).__name__}: {first}")


def parse(path: Path, where: str, text: str):
    """The pyNastran BDF of the file (no cross-referencing); its messages kept off the
    terminal; any problem one InputError naming the file."""
    BDF = _pynastran()
    from cpylog import SimpleLogger       # pyNastran's own logger (a dependency of it)

    bulk_only = not re.search(r"^\s*BEGIN\s+BULK", text, re.IGNORECASE | re.MULTILINE)
    model = BDF(log=SimpleLogger(level="critical"))
    chatter = io.StringIO()
    try:
        with contextlib.redirect_stdout(chatter), contextlib.redirect_stderr(chatter), \
                warnings.catch_warnings():
            warnings.simplefilter("ignore")     # its checks of cards: propwhirl makes its own
            model.read_bdf(str(path), xref=False, punch=bulk_only)
    except (KeyboardInterrupt, MemoryError):
        raise
    except Exception as exc:              # a third-party parser: every failure is the file's
        raise _parse_error(where, exc, text) from None
    return model


def _scanned_ids(text: str, name: str) -> list[str]:
    """The first field (the id) of every card ``name`` in the text (small, large and free
    field; the file itself, not its includes): only to name a duplicated id."""
    ids = []
    for line in text.splitlines():
        if line.startswith("$"):
            continue
        head = line.split(",")[0] if "," in line[:9] else line[:8]
        if head.strip().upper().rstrip("*") != name:
            continue
        if "," in line[:9]:
            ids.append(line.split(",")[1].strip() if line.count(",") else "")
        elif head.strip().endswith("*"):
            ids.append(line[8:24].strip())
        else:
            ids.append(line[8:16].strip())
    return ids


# ============================================================================ the deck
def cord2r_axes(a: np.ndarray, b: np.ndarray, c: np.ndarray) -> np.ndarray | None:
    """The axes (rows: unit vectors x, y, z in the basic frame) of a CORD2R through its
    points A (origin), B (on +z) and C (in the xz plane), all in the basic frame; None when
    the three points lie on one line (no axes)."""
    k = b - a
    j = np.cross(k, c - a)
    if not (np.linalg.norm(k) > 0 and np.linalg.norm(j) > 1e-12 * np.linalg.norm(k)
            * max(np.linalg.norm(c - a), 1e-300)):
        return None
    k = k / np.linalg.norm(k)
    j = j / np.linalg.norm(j)
    return np.array([np.cross(j, k), j, k])


@dataclass(frozen=True)
class Grid:
    """A grid point: its id and its position in the basic frame [m]."""

    nid: int
    xyz: np.ndarray


class Deck:
    """A parsed BDF with propwhirl's lookups and checks: every card looked up by the card
    that refers to it (a missing one is an error naming both), positions in SI and in the
    basic frame, the constraints of the chosen SPC set."""

    def __init__(self, bdf, where: str, text: str, units: UnitSystem, notes: list[str]):
        self.bdf, self.where, self.text, self.u, self.notes = bdf, where, text, units, notes
        self._frames: dict[int, tuple[np.ndarray, np.ndarray]] = {}
        self._check_cards()
        self.wtmass = self._wtmass()
        self.grids = {nid: self._grid(g) for nid, g in sorted(bdf.nodes.items())}
        self.constraints = self._constraints()

    def fail(self, text: str) -> v.InputError:
        return fail(self.where, text)

    # ---------------------------------------------------------------- cards
    def _check_free_field(self) -> None:
        """A free-field line holds a card's name (or continuation) and at most nine fields:
        pyNastran drops what follows unsaid, so such a line is refused."""
        for number, line in enumerate(self.text.splitlines(), 1):
            if line.startswith("$") or "," not in line[:10]:
                continue
            fields = line.split("$")[0].split(",")
            if len(fields) > 10:
                name = fields[0].strip().rstrip("*") or "a continuation"
                ident = fields[1].strip() if fields[0].strip() else ""
                raise self.fail(f"line {number} ({name}{' ' + ident if ident else ''}): "
                                f"{len(fields) - 1} free fields on one line, more than nine: "
                                "continue the card on a line starting with a comma")

    def _check_cards(self) -> None:
        self._check_free_field()
        counts = dict(self.bdf.card_count)
        if "ENDDATA" not in counts:
            raise self.fail("no ENDDATA: the file ends before its bulk data does (truncated?)")
        for name in counts:
            if name not in MODEL_CARDS + SETTING_CARDS:
                first = self._first_id(name)
                why = _WHY_NOT.get(name, "propwhirl reads a beam stick and its propellers: "
                                   + ", ".join(MODEL_CARDS) + " (docs/modal-structures.md, "
                                   "'NASTRAN bulk data')")
                raise self.fail(f"{name}{f' {first}' if first is not None else ''}: not read: "
                                f"{why}")
        stored = {
            "GRID": len(self.bdf.nodes),
            "CORD2R": len([c for c in self.bdf.coords.values() if c.cid != 0]),
            "MAT1": len(self.bdf.materials), "CONM2": len(self.bdf.masses),
            "EIGRL": len(self.bdf.methods),
        }
        for name in ("CBAR", "CBEAM", "CELAS2"):
            stored[name] = sum(e.type == name for e in self.bdf.elements.values())
        for name in ("PBAR", "PBARL", "PBEAM", "PBEAML"):
            stored[name] = sum(p.type == name for p in self.bdf.properties.values())
        for name in ("RBE2", "RBAR"):
            stored[name] = sum(e.type == name for e in self.bdf.rigid_elements.values())
        seen: dict[int, str] = {}
        for store in (self.bdf.elements, self.bdf.rigid_elements, self.bdf.masses):
            for eid, card in sorted(store.items()):
                name = f"{card.type} {eid}"
                if eid in seen:
                    raise self.fail(f"{seen[eid]} and {name} share one id (element ids must "
                                    f"be unique among {', '.join(ID_SPACES[0])})")
                seen[eid] = name
        for name, n in stored.items():
            if counts.get(name, 0) > n:
                ids = _scanned_ids(self.text, name)
                twice = sorted({i for i in ids if ids.count(i) > 1})
                which = f"{name} {twice[0]}" if twice else f"a {name} id"
                raise self.fail(f"{which} is given twice (ids must be unique; {counts[name]} "
                                f"{name} cards, {n} ids)")

    def _first_id(self, name: str):
        try:
            cards = self.bdf.get_cards_by_card_types([name], reset_type_to_slot_map=False,
                                                     stop_on_missing_card=False)
        except Exception:                 # noqa: BLE001 (only to name an id; the card is refused)
            return None
        for card in cards.get(name, []):
            for attr in ("eid", "pid", "mid", "nid", "cid", "conid", "sid"):
                if isinstance(getattr(card, attr, None), (int, np.integer)):
                    return int(getattr(card, attr))
        return None

    def _wtmass(self) -> float:
        param = self.bdf.params.get("WTMASS")
        if param is None:
            return 1.0
        value = param.values[0] if param.values else None
        if not isinstance(value, float) or not math.isfinite(value) or value <= 0.0:
            raise self.fail(f"PARAM WTMASS = {value!r} is invalid: must be a number > 0 (the "
                            "factor on every mass)")
        return float(value)

    def card(self, store: dict, key: int, names: tuple[str, ...], by: str):
        """The card ``key`` of ``store`` (one of the types ``names``), looked up for the card
        ``by``; missing or of another type: one line naming both."""
        card = store.get(key)
        if card is None:
            raise self.fail(f"{by} refers to {' or '.join(names)} {key}, which is not in the file")
        if card.type not in names:
            raise self.fail(f"{by} refers to {card.type} {key}: must be {' or '.join(names)}")
        return card

    def grid(self, nid: Any, by: str) -> Grid:
        if not isinstance(nid, (int, np.integer)) or int(nid) not in self.grids:
            raise self.fail(f"{by} refers to GRID {nid}, which is not in the file")
        return self.grids[int(nid)]

    # ---------------------------------------------------------------- frames
    def frame(self, cid: int, by: str, seen: tuple = ()) -> tuple[np.ndarray, np.ndarray]:
        """(origin [deck length], rows: the axes' unit vectors) of coordinate system ``cid``
        in the basic frame; basic = origin + axes.T @ local."""
        if cid == 0:
            return np.zeros(3), np.eye(3)
        if cid in self._frames:
            return self._frames[cid]
        coord = self.bdf.coords.get(cid)
        if coord is None:
            raise self.fail(f"{by} refers to coordinate system {cid}, which is not in the file")
        if coord.type != "CORD2R":
            raise self.fail(f"{coord.type} {cid}: not read: coordinate systems are CORD2R")
        if cid in seen:
            raise self.fail(f"CORD2R {cid} is defined through itself (RID {coord.rid})")
        o, R = self.frame(int(coord.rid), f"CORD2R {cid}", seen + (cid,))
        a, b, c = (o + R.T @ np.asarray(p, dtype=float) for p in (coord.e1, coord.e2, coord.e3))
        axes = cord2r_axes(a, b, c)
        if axes is None:
            raise self.fail(f"CORD2R {cid}: its points A, B, C do not define axes (on one line)")
        self._frames[cid] = (a, axes)
        return a, axes

    def _grid(self, g) -> Grid:
        by = f"GRID {g.nid}"
        if getattr(g, "seid", 0):
            raise self.fail(f"{by}: superelement {g.seid}: not read (one structure per deck)")
        o, R = self.frame(int(g.cp or 0), by)
        cd = int(g.cd or 0)
        if cd > 0:
            _, axes = self.frame(cd, by)
            if not np.allclose(axes, np.eye(3), rtol=0.0, atol=1e-12):
                raise self.fail(f"{by}: CD = {cd} turns its displacement frame from the basic "
                                "one: propwhirl reads components in the basic directions "
                                "(give CD = 0, or a CORD2R parallel to the basic frame)")
        elif cd < 0:
            raise self.fail(f"{by}: CD = {cd} (a fluid grid): not read")
        xyz = (o + R.T @ np.asarray(g.xyz, dtype=float)) * self.u.length
        return Grid(int(g.nid), xyz)

    # ---------------------------------------------------------------- constraints
    def _spc_set(self) -> int | None:
        """The SPC set of the case control, or the deck's only one, or None (none at all)."""
        chosen = set()
        deck = self.bdf.case_control_deck
        if deck is not None:
            for subcase in deck.subcases.values():
                if "SPC" in subcase.params:
                    chosen.add(int(subcase.params["SPC"][0]))
        sets = sorted(set(self.bdf.spcs) | set(self.bdf.spcadds))
        if len(chosen) > 1:
            raise self.fail(f"the case control selects SPC {', '.join(map(str, sorted(chosen)))} "
                            "in different subcases: one structure per deck")
        if chosen:
            sid = chosen.pop()
            if sid not in sets:
                raise self.fail(f"the case control's SPC = {sid} is not in the file (no SPC, "
                                "SPC1 or SPCADD with that id)")
            return sid
        if len(sets) > 1:
            raise self.fail(f"SPC sets {', '.join(map(str, sets))} and no case control SPC = "
                            "selecting one: give the deck's SPC = or keep one set")
        if sets:
            self.notes.append(f"{self.where}: SPC set {sets[0]} taken as the constraints "
                              "(no case control selects one)")
            return sets[0]
        return None

    def _constraints(self) -> dict[int, set[int]]:
        """Each grid's held components (1-6): its PS field and the chosen SPC set."""
        held: dict[int, set[int]] = {}
        for nid, g in self.bdf.nodes.items():
            if g.ps:
                held.setdefault(int(nid), set()).update(int(c) for c in str(g.ps))
        sid = self._spc_set()
        if sid is None:
            return held
        sets = [sid] if sid in self.bdf.spcs else []
        for add in self.bdf.spcadds.get(sid, []):       # an SPCADD: the union of its sets
            sets += [int(s) for s in add.sets]
        for s in sets:
            if s not in self.bdf.spcs:
                raise self.fail(f"SPCADD {sid} refers to SPC {s}, which is not in the file")
            for spc in self.bdf.spcs[s]:
                by = f"{spc.type} {s}"
                if spc.type == "SPC":
                    pairs = list(zip(spc.nodes, spc.components, spc.enforced))
                else:
                    pairs = [(n, spc.components, 0.0) for n in spc.nodes]
                for nid, comps, enforced in pairs:
                    self.grid(nid, by)
                    if enforced not in (None, 0.0):
                        raise self.fail(f"{by} enforces {enforced!r} on GRID {nid} (component "
                                        f"{comps}): an enforced displacement, not a support")
                    held.setdefault(int(nid), set()).update(int(c) for c in str(comps))
        return held
