"""The rigid-body modes of a free structure (issue 36, item 4): each classified from its
shape at the grids, kept exactly rigid, and the freedoms a model admits decided in one place
(propwhirl.model.rigid_body): plunge and roll with the wing alone, pitch with a tail, never a
yaw (no fin), surge or sway."""
from __future__ import annotations

import numpy as np
import pytest

from propwhirl import InputError
from propwhirl.model.modal_structure import ModalStructure
from propwhirl.model.rigid_body import (KEPT_RIGID_BODY, WING_ALONE, check_rigid_freedoms,
                                        rigid_body_kind, rigid_shape)

XYZ = np.array([[0.0, 0.0, 0.0], [0.1, 2.0, 0.0], [-0.1, 4.0, 0.05], [0.3, 6.0, 0.0]])


def rigid(t=(0.0, 0.0, 0.0), theta=(0.0, 0.0, 0.0), about=(0.0, 0.0, 0.0)) -> np.ndarray:
    """The grids' six components of a rigid motion: translation t [m], rotation θ [rad] about
    the point ``about``."""
    out = np.zeros((XYZ.shape[0], 6))
    out[:, :3] = np.asarray(t) + np.cross(theta, XYZ - np.asarray(about))
    out[:, 3:] = theta
    return out


@pytest.mark.parametrize("shape, kind", [
    (rigid(t=(0, 0, 1e-3)), "plunge"),
    (rigid(theta=(2e-4, 0, 0), about=(0, 3.0, 0.0125)), "roll"),
    (rigid(theta=(2e-4, 0, 0)), "roll"),            # about the root's axis: still a roll
    (rigid(t=(0, 3e-4, 0), theta=(2e-4, 0, 0)), "roll"),      # an axis higher up
    (rigid(t=(1e-4, 0, 0), theta=(2e-4, 0, 0)), "surge"),     # along the roll axis
    (rigid(t=(0, 1e-3, 0)), "sway"),
    (rigid(theta=(0, 1e-3, 0)), "pitch"),
    (rigid(t=(0, 0, 1e-3), theta=(0, 0, 1e-3)), "yaw"),
    (rigid(theta=(0, 1e-3, 1e-3)), "pitch and yaw"),
    (rigid(t=(1e-3, 0, 0)), "surge"),
])
def test_a_rigid_mode_is_classified_from_its_shape_at_the_grids(shape, kind):
    assert rigid_body_kind(XYZ, shape) == kind


def test_a_shape_that_bends_is_a_mechanism():
    shape = rigid(t=(0, 0, 1e-3))
    shape[:, 2] += 1e-3 * (XYZ[:, 1] / 6.0) ** 2              # bending: no rigid motion
    assert rigid_body_kind(XYZ, shape) == "mechanism"


def test_the_kept_shape_is_exactly_rigid():
    shape = rigid(theta=(2e-4, 0, 0)) + 1e-15 * np.arange(24).reshape(4, 6)
    out = rigid_shape(XYZ, shape)
    assert np.all(out[:, [0, 4, 5]] == 0.0)           # no surge, pitch, yaw: not even 1e-15
    np.testing.assert_allclose(out, rigid(theta=(2e-4, 0, 0)), rtol=0, atol=1e-13)


def test_a_kept_pitch_keeps_its_axis_and_drops_the_yaw_noise():
    """A pitch about an axis aft of the grids and above them (with a plunge): T_x, T_z and
    R_y kept exactly rigid; the rounding's 1e-15 yaw is 0."""
    exact = rigid(t=(0, 0, 2e-3), theta=(0, 1e-3, 0), about=(3.0, 0.0, 0.4))
    out = rigid_shape(XYZ, exact + 1e-15 * np.arange(24).reshape(4, 6))
    assert np.all(out[:, 5] == 0.0)
    np.testing.assert_allclose(out, exact, rtol=0, atol=1e-13)


def structure(shape, f=(0.0, 3.0), free=True):
    second = rigid(t=(0, 0, 1e-3))
    second[:, 2] *= (XYZ[:, 1] / 6.0) ** 2
    return ModalStructure(grid_ids=[1, 2, 3, 4], xyz=XYZ, frequencies_hz=list(f),
                          modal_mass=[1.0, 1.0], damping_ratio=[0.0, 0.02],
                          shapes=np.stack([shape, second]), free=free)


@pytest.mark.parametrize("theta, kind", [((0, 0, 1e-3), "yaw"), ((0, 1e-3, 1e-3),
                                                                   "pitch and yaw")])
def test_a_rigid_yaw_is_refused_by_name_it_needs_a_fin(theta, kind):
    with pytest.raises(InputError, match=rf"^modal structure: mode 1 \(0 Hz\) is a "
                                         rf"rigid-body {kind}: a rigid yaw needs a fin[^\n]*$"):
        structure(rigid(theta=theta))


@pytest.mark.parametrize("t, kind", [((1e-3, 0, 0), "surge"), ((0, 1e-3, 0), "sway")])
def test_an_in_plane_translation_is_refused_by_name(t, kind):
    with pytest.raises(InputError, match=rf"mode 1 \(0 Hz\) is a rigid-body {kind}: the "
                                         r"strips give an in-plane"):
        structure(rigid(t=t))


def test_the_structure_keeps_a_pitch_which_the_model_refuses_without_a_tail():
    """One place decides the freedoms (rigid_body.check_rigid_freedoms): the structure keeps
    plunge, roll and pitch; a model refuses the pitch when it has no surface besides the
    wing, and takes it with one."""
    s = structure(rigid(theta=(0, 1e-3, 0), about=(0.2, 0, 0)))
    assert s.rigid_body_modes() == ((0, "pitch"),)
    with pytest.raises(InputError, match=r"^modal structure: mode 1 \(0 Hz\) is a rigid-body "
                                         r"pitch: a wing alone has no tail.*add a tail"):
        check_rigid_freedoms(s, 0)
    check_rigid_freedoms(s, 1)
    check_rigid_freedoms(structure(rigid(t=(0, 0, 1e-3))), 0)       # a plunge: the wing's
    assert KEPT_RIGID_BODY == ("plunge", "roll", "pitch") and WING_ALONE == ("plunge", "roll")


def test_a_clamped_structure_refuses_a_rigid_mode_and_says_how_to_keep_it():
    with pytest.raises(InputError, match=r"frequencies_hz\[0\] = 0 Hz is a rigid-body mode.*"
                                         r"free = true"):
        structure(rigid(t=(0, 0, 1e-3)), free=False)
    with pytest.raises(InputError, match=r"frequencies_hz\[0\] = -1e-06 Hz is invalid"):
        structure(rigid(t=(0, 0, 1e-3)), f=(-1e-6, 3.0))
    assert structure(rigid(t=(0, 0, 1e-3))).free


def test_a_pitch_spread_over_the_rigid_modes_is_turned_into_one_without_changing_the_roots():
    """Any mass-orthonormal basis of the rigid-body modes is the same structure: the tailed
    free body's rigid modes mixed by a rotation (and scaled to other modal masses) give a
    structure with the pitch in one mode again, modal masses 1, and the same roots; the
    altitude and roll angle keep exactly zero roots (no false divergence)."""
    from dataclasses import replace

    from helpers.op2_files import tailed_modal_model
    from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing

    model, n = tailed_modal_model(wingtip_propeller_wing(), 1e2)
    s = model.structure
    assert [k for _, k in s.rigid_body_modes()].count("pitch") == 1
    Q = np.linalg.qr(np.random.default_rng(3).normal(size=(n, n)))[0]
    mass = np.array([2.0, 0.5, 3.0])
    shapes = np.array(s.shapes)
    shapes[:n] = np.einsum("ij,jgc->igc", Q, s.shapes[:n]) * np.sqrt(mass)[:, None, None]
    modal_mass = np.array(s.modal_mass)
    modal_mass[:n] = mass
    mixed = replace(s, shapes=shapes, modal_mass=modal_mass)
    assert [k for _, k in mixed.rigid_body_modes()].count("pitch") == 1
    assert np.all(mixed.modal_mass[:n] == 1.0)
    V = np.array([60.0, 130.0])
    a = np.linalg.eigvals(model.state_matrix(V))
    b = np.linalg.eigvals(model.with_(structure=mixed).state_matrix(V))
    for x, y in zip(a, b):
        x, y = np.sort_complex(x), np.sort_complex(y)
        np.testing.assert_allclose(y, x, rtol=1e-7, atol=1e-9 * np.abs(x).max())
        assert np.count_nonzero(y == 0) >= 2                  # altitude and roll angle
    K = model.with_(structure=mixed).second_order(V).S3
    assert np.count_nonzero(np.all(K == 0.0, axis=1)) >= 2       # their columns: exactly 0
