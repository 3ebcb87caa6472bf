"""Models: the wing, the propellers and their installation, assembled into A(V).

The rooms, by their physics: :mod:`.structure` (the beam wing and its mesh, the assembly of
the generated element matrices, structures given by their normal modes), :mod:`.aerodynamics`
(Theodorsen's function and the p-k's exact strip matrices, the doublet lattice, what the
aerodynamics refuse), :mod:`.propellers` (the flexibly mounted propeller, its Houbolt–Reed
derivatives, an installed propeller's block).  Here: the flight condition (:mod:`.flight`,
:mod:`.atmosphere`), the first-order state space (:mod:`.statespace`, :mod:`.blocks`,
:mod:`.pencil`), the complete systems (:mod:`.systems`, :mod:`.modal`, :mod:`.section`), their
reduction and parameter derivatives (:mod:`.reduction`, :mod:`.derivatives`) and the contract
every model meets, with the explicit map of its states (:mod:`.protocol`).  SI units
throughout.  The modules' old paths (``propwhirl.model.wing`` …) are the same modules
(:data:`propwhirl.compat.MOVED`).
"""
from propwhirl.model.flight import FlightCondition
from propwhirl.model.modal import ModalInstallation, ModalPropellerWing
from propwhirl.model.structure.modal_structure import ModalStructure, StripPlanform
from propwhirl.model.propellers.propeller import MeasuredDerivatives, PointMass, Propeller
from propwhirl.model.systems import (Installation, IsolatedPropeller,
                                     PropellerWing, TypicalSection, node_at)
from propwhirl.model.structure.wing import LiftSlope, Wing

__all__ = ["FlightCondition", "Installation", "IsolatedPropeller", "LiftSlope",
           "MeasuredDerivatives", "ModalInstallation", "ModalPropellerWing", "ModalStructure",
           "PointMass", "Propeller", "PropellerWing", "StripPlanform", "TypicalSection", "Wing",
           "node_at"]
