"""NASTRAN bulk data (BDF): what the reader (:mod:`.nastran_read`) and the writer
(:mod:`.nastran_write`) share — the unit systems a deck may be in, and the way a deck holds a
beam model (docs/modal-structures.md, "NASTRAN bulk data").

NASTRAN has no units: a deck's numbers are in whatever consistent system its author chose.
propwhirl therefore asks for the system (``units``; the command line's ``--units``), one of
:data:`UNIT_SYSTEMS`, and converts every number to SI on reading (and from SI on writing).
Each system is consistent (force = mass × length / s²), as NASTRAN needs:

========== ========== ============== ====== ====================
system     length     mass           time   force
========== ========== ============== ====== ====================
si         m          kg             s      N
mm-t-s     mm         t (1000 kg)    s      N
in-lbf-s   in         lbf s²/in      s      lbf
========== ========== ============== ====== ====================

(``PARAM,WTMASS`` — a deck whose masses are weights — multiplies every mass on reading.)

How a deck holds a beam model (the writer writes it so, the reader reads it so):

* the wing: GRIDs on a straight line along the basic y axis from the clamped root (the elastic
  axis; x aft, z up), CBAR or CBEAM elements between consecutive grids; per element E·I1 the
  vertical bending rigidity EI, E·I2 the chordwise one (when the stick's T_x and R_z are free),
  G·J the torsional rigidity GJ, ρA + NSM the mass per length, the non-structural mass's
  chordwise offset (PBEAM M2) its centre of gravity and ρ(I1 + I2) + NSI + NSM·M2² the polar
  inertia about the axis;
* each propeller: rigid bodies (RBE2, RBAR) carrying its masses (CONM2; the rotor's on its hub
  grid), rigidly on a wing grid (a rigid mount) or through a pitch hinge and a yaw hinge, each
  an RBE2 that leaves one rotation free and a CELAS2 spring on it (a flexible mount).
"""
from __future__ import annotations

from dataclasses import dataclass

from propwhirl import validate as v

#: The extra that reads BDF files, and why it lives in an environment of its own.
INSTALL_HINT = ("pip install 'propwhirl[nastran]' in an environment of its own (pyNastran "
                "1.4.1 needs numpy < 2: python -m venv nastran-env && nastran-env/bin/pip "
                "install 'propwhirl[nastran]')")


@dataclass(frozen=True)
class UnitSystem:
    """A consistent system of units of a NASTRAN deck: each base unit in SI.

    Parameters
    ----------
    name : the name given as ``units`` (``--units``)
    length : the length unit [m]
    mass : the mass unit [kg]
    force : the force unit [N] (mass × length / s²: the systems are consistent)
    description : the units in words, for messages and deck headers
    """

    name: str
    length: float
    mass: float
    force: float
    description: str

    # the derived units of the cards' fields, in SI
    @property
    def area(self) -> float:
        """[m²] per deck unit of area (PBAR A)."""
        return self.length ** 2

    @property
    def moment_of_area(self) -> float:
        """[m⁴] per deck unit of a second moment of area (I1, I2, J)."""
        return self.length ** 4

    @property
    def modulus(self) -> float:
        """[N/m²] per deck unit of a modulus (MAT1 E, G)."""
        return self.force / self.length ** 2

    @property
    def density(self) -> float:
        """[kg/m³] per deck unit of density (MAT1 RHO)."""
        return self.mass / self.length ** 3

    @property
    def mass_per_length(self) -> float:
        """[kg/m] per deck unit of mass per length (NSM)."""
        return self.mass / self.length

    @property
    def inertia_per_length(self) -> float:
        """[kg m] per deck unit of mass moment of inertia per length (PBEAM NSI)."""
        return self.mass * self.length

    @property
    def inertia(self) -> float:
        """[kg m²] per deck unit of mass moment of inertia (CONM2 I11 ...)."""
        return self.mass * self.length ** 2

    @property
    def rotational_stiffness(self) -> float:
        """[N m/rad] per deck unit of a rotational spring (CELAS2 K on a rotation)."""
        return self.force * self.length

    @property
    def rigidity(self) -> float:
        """[N m²] per deck unit of a rigidity (E·I, G·J)."""
        return self.force * self.length ** 2


_LBF = 4.4482216152605          # N (exact by definition of the pound-force)
_INCH = 0.0254                  # m (exact)

#: The unit systems a deck may be in (``units``, ``--units``).
UNIT_SYSTEMS: dict[str, UnitSystem] = {
    "si": UnitSystem("si", 1.0, 1.0, 1.0, "m, kg, s, N"),
    "mm-t-s": UnitSystem("mm-t-s", 1e-3, 1e3, 1.0, "mm, t, s, N"),
    "in-lbf-s": UnitSystem("in-lbf-s", _INCH, _LBF / _INCH, _LBF, "in, lbf s^2/in, s, lbf"),
}


def unit_system(units: str | None, where: str) -> UnitSystem:
    """The :class:`UnitSystem` named ``units``; an InputError starting with ``where`` (the
    file) when it is not stated or not one of :data:`UNIT_SYSTEMS`."""
    choices = "|".join(UNIT_SYSTEMS)
    if units is None:
        raise v.InputError(f"{where}: units not stated: NASTRAN has none, state the deck's "
                           f"with --units {choices} (Python: units=...)")
    if not isinstance(units, str) or units not in UNIT_SYSTEMS:
        raise v.InputError(f"{where}: units = {v.short_repr(units)} is invalid: must be one of "
                           f"{', '.join(UNIT_SYSTEMS)}")
    return UNIT_SYSTEMS[units]

