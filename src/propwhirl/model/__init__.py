"""Models: the wing, the propellers and their installation, assembled into A(V).

The physical components (:mod:`.wing`, :mod:`.propeller`, :mod:`.propeller_aero`), the
assembly of the generated element matrices (:mod:`.assembly`), the first-order state space
(:mod:`.statespace`) and the complete systems (:mod:`.systems`).  SI units throughout.
"""
from propwhirl.model.propeller import MeasuredDerivatives, PointMass, Propeller
from propwhirl.model.systems import (FlightCondition, Installation, IsolatedPropeller,
                                     PropellerWing, TypicalSection, node_at)
from propwhirl.model.wing import LiftSlope, Wing

__all__ = ["FlightCondition", "Installation", "IsolatedPropeller", "LiftSlope",
           "MeasuredDerivatives", "PointMass", "Propeller", "PropellerWing", "TypicalSection",
           "Wing", "node_at"]
