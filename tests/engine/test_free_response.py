"""Free response of ẋ = A x against closed forms and an ODE integrator."""
from __future__ import annotations

import json

import numpy as np
import pytest

from propwhirl.engine import TimeResponse, time_response
from propwhirl.model.statespace import second_order_labels, state_matrix_from_mck
from propwhirl.validate import InputError

from helpers.engine_systems import propeller


def test_time_response_matches_closed_form():
    k, c = 40.0, 0.8
    A = state_matrix_from_mck(np.eye(1), c * np.eye(1), k * np.eye(1))[0]
    t = np.linspace(0.0, 5.0, 501)
    wn, z = np.sqrt(k), c / (2 * np.sqrt(k))
    wd = wn * np.sqrt(1 - z**2)
    exact = np.exp(-z * wn * t) * (np.cos(wd * t) + z * wn / wd * np.sin(wd * t))
    for method in ("expm", "ivp"):
        r = time_response(A, [1.0, 0.0], t, second_order_labels(["h"]), method=method)
        np.testing.assert_allclose(r["h"], exact, atol=1e-7)
    back = TimeResponse.from_dict(json.loads(json.dumps(r.to_dict())))
    np.testing.assert_array_equal(back.x, r.x)
    with pytest.raises(InputError, match="no state"):
        r["alpha"]


def test_time_response_nonuniform_and_whirl_orbit():
    """Propeller of eq. (6.8), 1° initial pitch: the backward mode survives; orbit clockwise."""
    fn = propeller(c=0.0, K_p=4000.0, I_Z=2.0)
    A = fn(np.array([60.0]))[0]
    t = np.concatenate([np.linspace(0, 1, 300), np.linspace(1.01, 3, 50)])
    r = time_response(A, [np.radians(1.0), 0, 0, 0], t)
    ivp = time_response(A, [np.radians(1.0), 0, 0, 0], t, method="ivp")
    np.testing.assert_allclose(r.x, ivp.x, atol=1e-7)
    energy = 0.5 * 2.0 * (r.x[:, 2] ** 2 + r.x[:, 3] ** 2) + 0.5 * 4000 * (r.x[:, 0] ** 2 +
                                                                          r.x[:, 1] ** 2)
    np.testing.assert_allclose(energy, energy[0], rtol=1e-9)      # gyroscopic: conservative
