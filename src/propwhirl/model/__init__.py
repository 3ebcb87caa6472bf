"""Models: the wing, the propellers and their installation, assembled into A(V).

The physical components (:mod:`.wing`, :mod:`.propeller`, :mod:`.propeller_aero`, :mod:`.flight`), the
assembly of the generated element matrices (:mod:`.assembly`), the first-order state space
(:mod:`.statespace`), the complete systems (:mod:`.systems`), a structure given by its normal modes (:mod:`.modal_structure`, :mod:`.modal`) and the contract every model
meets, with the explicit map of its states (:mod:`.protocol`).  SI units throughout.
"""
from propwhirl.model.flight import FlightCondition
from propwhirl.model.modal import ModalInstallation, ModalPropellerWing
from propwhirl.model.modal_structure import ModalStructure, StripPlanform
from propwhirl.model.propeller import MeasuredDerivatives, PointMass, Propeller
from propwhirl.model.systems import (Installation, IsolatedPropeller,
                                     PropellerWing, TypicalSection, node_at)
from propwhirl.model.wing import LiftSlope, Wing

__all__ = ["FlightCondition", "Installation", "IsolatedPropeller", "LiftSlope",
           "MeasuredDerivatives", "ModalInstallation", "ModalPropellerWing", "ModalStructure",
           "PointMass", "Propeller", "PropellerWing", "StripPlanform", "TypicalSection", "Wing",
           "node_at"]
