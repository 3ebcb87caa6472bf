"""A root of multiplicity ≥ 3 in a cluster (lag roots shared by the nodes of a Wagner wing)
gives no RuntimeWarning: the uncertainty at a step's ends is 0, not 0·inf."""
from __future__ import annotations

import warnings

import numpy as np

from propwhirl.analysis.stability import analyse
from propwhirl.model import FlightCondition, PropellerWing, Wing


def goland_wing(n_elements: int = 6, aero_model: str = "wagner") -> Wing:
    """Goland's wing: semi-span 20 ft, chord 6 ft, EI 23.65e6 lb ft², GJ 2.39e6 lb ft², 0.746
    slug/ft, polar inertia 1.943 slug ft, elastic axis 33 %, centre of gravity 43 % chord."""
    return Wing(semi_span=6.096, root_chord=1.8288, mass_per_length=35.71, polar_inertia=8.64,
                EI=9.77e6, GJ=0.987e6, elastic_axis=0.33, centre_of_gravity=0.43,
                n_elements=n_elements, aero_model=aero_model)


def test_goland_wing_without_runtime_warnings():
    model = PropellerWing(goland_wing(), FlightCondition(1.0), name="goland")
    with warnings.catch_warnings():
        warnings.simplefilter("error")           # the old code: invalid value in multiply
        a = analyse(model)
    c = a.critical
    assert c.kind == "flutter" and c.label == "wing 2" and 140.0 < c.V < 155.0
    assert np.isfinite(a.sweep.eigenvalues).all()
