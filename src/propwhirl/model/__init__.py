"""Models: the wing, the propellers and their installation, assembled into A(V).

The rooms, by their physics: :mod:`.structure` (the beam wing, its mesh and the assembly of
the generated element matrices), :mod:`.aerodynamics` (Theodorsen's function, the doublet
lattice, what the aerodynamics refuse), :mod:`.propellers` (the flexibly mounted propeller and
its Houbolt–Reed derivatives).  Here, what puts them together: the flight condition
(:mod:`.flight`, :mod:`.atmosphere`), the complete systems (:mod:`.systems`, a structure given
by its normal modes :mod:`.modal_structure` and :mod:`.modal`, :mod:`.section`), an installed
propeller's block (:mod:`.propeller_blocks`), the first-order state space (:mod:`.statespace`,
:mod:`.blocks`, :mod:`.pencil`), its reduced and frequency-domain forms (:mod:`.reduction`,
:mod:`.dlm_modal`, :mod:`.frequency_domain`), parameter derivatives (:mod:`.derivatives`) and
the contract every model meets, with the explicit map of its states (:mod:`.protocol`).  SI
units throughout.  The modules' old paths (``propwhirl.model.wing`` …) are the same modules
(:data:`propwhirl.compat.MOVED`).
"""
from propwhirl.model.flight import FlightCondition
from propwhirl.model.modal import ModalInstallation, ModalPropellerWing
from propwhirl.model.modal_structure import ModalStructure, StripPlanform
from propwhirl.model.modal_surface import ModalSurface
from propwhirl.model.propellers.propeller import MeasuredDerivatives, PointMass, Propeller
from propwhirl.model.systems import (Installation, IsolatedPropeller,
                                     PropellerWing, TypicalSection, node_at)
from propwhirl.model.structure.wing import LiftSlope, Wing

__all__ = ["FlightCondition", "Installation", "IsolatedPropeller", "LiftSlope",
           "MeasuredDerivatives", "ModalInstallation", "ModalPropellerWing", "ModalStructure",
           "ModalSurface",
           "PointMass", "Propeller", "PropellerWing", "StripPlanform", "TypicalSection", "Wing",
           "node_at"]
