"""Whirl sense from the θ–ψ orbit (§9.2), modal content."""
from __future__ import annotations

import numpy as np
import pytest

from propwhirl.analysis.whirl import (content, dominant, orbit_signed_area,
                                      rotation_sign_from_gyroscopic, whirl_sense)
from propwhirl.engine import eigen, sweep
from propwhirl.validate import InputError

from helpers.engine_systems import propeller


def _shoelace(theta_hat, psi_hat, n=2001):
    t = np.linspace(0, 2 * np.pi, n)
    th = np.real(theta_hat * np.exp(1j * t))
    ps = np.real(psi_hat * np.exp(1j * t))
    return 0.5 * np.sum(th[:-1] * ps[1:] - th[1:] * ps[:-1])


@pytest.mark.parametrize("theta_hat, psi_hat", [
    (1.0, -1j), (1.0, 1j),                                   # circles
    (1.0, 0.3 * np.exp(-1.2j)), (0.7j, 1.4 * np.exp(0.4j)),  # ellipses, phase lag ≠ 90°
])
@pytest.mark.parametrize("rotation", [1, -1])
def test_whirl_sense_from_orbit(theta_hat, psi_hat, rotation):
    area = _shoelace(theta_hat, psi_hat)
    assert orbit_signed_area(theta_hat, psi_hat) == pytest.approx(area, rel=1e-5)
    ccw = area > 0
    expected = "forward" if ccw == (rotation > 0) else "backward"
    assert whirl_sense(theta_hat, psi_hat, rotation) == expected
    # the conjugate eigenvalue (ω < 0) runs the orbit the other way round
    other = "backward" if expected == "forward" else "forward"
    assert whirl_sense(theta_hat, psi_hat, rotation, eigenvalue=-0.1 - 3j) == other


def test_whirl_sense_planar_and_bad_sign():
    assert whirl_sense(1.0, 0.5, 1) == "planar"
    assert whirl_sense(1.0, 0.5j, 1, eigenvalue=-2.0 + 0j) == "planar"
    with pytest.raises(InputError, match="rotation_sign"):
        whirl_sense(1.0, 1j, 0)
    with pytest.raises(InputError, match="g_theta_psi"):
        rotation_sign_from_gyroscopic(0.0)


@pytest.mark.parametrize("omega", [60.0, -60.0])
def test_gyroscopic_propeller_backward_is_lower(omega):
    """Eq. (6.8), unequal stiffness (elliptical orbits): the lower mode whirls backward.

    §9.2: for the thesis' counter-clockwise rotation (Ω > 0) the backward orbit is clockwise
    with ψ on the Y-axis and θ on the X-axis.
    """
    lam, X = eigen(propeller()(np.array([omega])))
    keep = lam[0].imag > 0
    lam, X = lam[0][keep], X[0][:, keep]
    order = np.argsort(lam.imag)
    rot = rotation_sign_from_gyroscopic(0.5 * omega)       # I_X Ω
    assert [whirl_sense(X[0, j], X[1, j], rot, eigenvalue=lam[j]) for j in order] == \
        ["backward", "forward"]
    low = order[0]
    assert not 0.95 < abs(X[0, low]) / abs(X[1, low]) < 1.05                # elliptical
    assert np.sign(orbit_signed_area(X[0, low], X[1, low])) == -np.sign(omega)


def test_sweep_mode_labels_from_whirl_sense():
    sw = sweep(propeller(), np.linspace(5.0, 80.0, 6), n_dof=2)
    sw = sw.relabel(lambda lam, x: whirl_sense(x[0], x[1], 1, lam) + " whirl")
    assert sw.mode_labels[:2] == ("backward whirl", "forward whirl")
    # along Ω the backward frequency falls and the forward one rises (§9.2, Figure 9.16)
    f = sw.frequency_hz
    assert np.all(np.diff(f[:, 0]) < 0) and np.all(np.diff(f[:, 1]) > 0)
    senses = {whirl_sense(sw.eigenvectors[t, 0, k], sw.eigenvectors[t, 1, k], 1,
                             sw.eigenvalues[t, k]) for t in range(sw.V.size) for k in (0, 1)}
    assert senses == {"backward", "forward"}


def test_content_and_dominant():
    x = np.array([3.0, 4.0j, 0.0, 1.0])
    c = content(x, {"bending": [0, 1], "torsion": [3]})
    assert c == pytest.approx({"bending": 25 / 26, "torsion": 1 / 26})
    assert dominant(x, {"bending": [0, 1], "torsion": np.array([0, 0, 0, 1], bool)}) == \
        "bending"
    many = content(np.stack([x, x[::-1]], axis=1), {"a": [0], "b": [3]})
    np.testing.assert_allclose(many["a"], [0.9, 0.1])
    with pytest.raises(InputError):
        content(x, {"a": [7]})
