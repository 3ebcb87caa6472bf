"""Free structures (issue 36, item 4): a free modal structure keeps its plunge and roll
rigid-body modes and is analysed without a false event; a rigid pitch or yaw is refused by
name (a wing alone has no tail); the heavy body's instabilities are the clamped wing's, a
light body's are not (docs/validation.md, "Free structures with plunge and roll kept")."""
from __future__ import annotations

import numpy as np
import pytest

from helpers.op2_files import free_free_modes, free_modal_model, root_body
from propwhirl import InputError
from propwhirl.analysis.modes import label_modes
from propwhirl.analysis.stability import analyse
from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
from propwhirl.io.modal_files import load_modal_model, save_modal_model, write_modes
from propwhirl.model.modal_structure import (ModalStructure, plunge_roll_shape,
                                             rigid_body_kind)

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
    out = plunge_roll_shape(XYZ, shape)
    assert np.all(out[:, [0, 4, 5]] == 0.0)           # no surge, pitch, yaw: not even 1e-15
    np.testing.assert_allclose(out, rigid(theta=(2e-4, 0, 0)), rtol=0, atol=1e-13)


def structure(shape, f=(0.0, 3.0), free=True):
    second = rigid(t=(0, 0, 1e-3))
    second[:, 2] *= (XYZ[:, 1] / 6.0) ** 2
    return ModalStructure(grid_ids=[1, 2, 3, 4], xyz=XYZ, frequencies_hz=list(f),
                          modal_mass=[1.0, 1.0], damping_ratio=[0.0, 0.02],
                          shapes=np.stack([shape, second]), free=free)


@pytest.mark.parametrize("theta, kind", [((0, 1e-3, 0), "pitch"), ((0, 0, 1e-3), "yaw")])
def test_a_rigid_pitch_or_yaw_is_refused_by_name(theta, kind):
    with pytest.raises(InputError, match=rf"^modal structure: mode 1 \(0 Hz\) is a "
                                         rf"rigid-body {kind}: .*no tail.*hold pitch"):
        structure(rigid(theta=theta))


def test_a_clamped_structure_refuses_a_rigid_mode_and_says_how_to_keep_it():
    with pytest.raises(InputError, match=r"frequencies_hz\[0\] = 0 Hz is a rigid-body mode.*"
                                         r"free = true"):
        structure(rigid(t=(0, 0, 1e-3)), free=False)
    with pytest.raises(InputError, match=r"frequencies_hz\[0\] = -1e-06 Hz is invalid"):
        structure(rigid(t=(0, 0, 1e-3)), f=(-1e-6, 3.0))
    assert structure(rigid(t=(0, 0, 1e-3))).free


@pytest.fixture(scope="module")
def clamped():
    return analyse(wingtip_propeller_wing()).events


def test_plunge_and_roll_kept_heavy_body_is_the_clamped_wing_without_a_false_event(clamped):
    """κ = 1e4: every clamped instability within 0.05 % (the divergence as the very slow
    flutter of its root with the plunge's aerodynamic root), nothing below the first, no
    event of a rigid-body mode, and the rigid roots stable (0, or damped by the strips)."""
    model, n_rigid = free_modal_model(wingtip_propeller_wing(), 1e4, "plunge-roll")
    assert n_rigid == 2 and model.structure.free
    assert [lab for lab, _ in label_modes(model)][:2] == ["rigid 1", "rigid 2"]
    got = analyse(model).events
    first = min(e.V for e in clamped)
    assert all(g.V > 0.999 * first for g in got)
    assert not any(g.label.startswith("rigid") for g in got)
    for e in clamped:
        near = min(got, key=lambda g: abs(g.V - e.V))
        assert abs(near.V - e.V) < 5e-4 * e.V, (e, near)
        assert near.kind == e.kind or near.frequency_hz < 0.1
    for V in (1.0, 100.0):
        lam = np.linalg.eigvals(model.state_matrix(np.array([V]))[0])
        assert np.max(lam.real) <= 1e-9 * np.max(np.abs(lam)), V


def test_a_light_body_changes_the_instabilities(clamped):
    """κ = 1: the body's freedom matters: the wing's divergence at 143.15 m/s is gone and the
    first instability is a flutter above the clamped wing's."""
    model, _ = free_modal_model(wingtip_propeller_wing(), 1.0, "plunge-roll")
    got = analyse(model).events
    first = min(got, key=lambda g: g.V)
    assert first.kind == "flutter" and first.V > 1.03 * clamped[1].V
    assert not any(abs(g.V - clamped[0].V) < 0.05 * clamped[0].V for g in got)


def test_a_free_root_with_pitch_is_refused_naming_the_mode():
    wing = wingtip_propeller_wing().wing
    mass, roll, pitch = root_body(wing)
    ids, xyz, w2, shapes = free_free_modes(wing, 1e2 * mass, 1e2 * roll, 1e2 * pitch, "free")
    f = np.sqrt(np.abs(w2)) / (2 * np.pi)
    f[f < 0.1] = 0.0
    with pytest.raises(InputError, match=r"mode [123] \(0 Hz\) is a rigid-body .*pitch"):
        ModalStructure(grid_ids=ids, xyz=xyz, frequencies_hz=f, modal_mass=np.ones(f.size),
                       damping_ratio=np.where(f > 0, 0.01, 0.0), shapes=shapes, free=True)


def test_old_files_load_clamped_and_a_free_structure_round_trips(tmp_path):
    toml, _ = write_modes(wingtip_propeller_wing(), tmp_path / "old.toml", n_modes=4)
    assert "free" not in toml.read_text()                 # as every file before the key
    assert load_modal_model(toml).structure.free is False
    model, _ = free_modal_model(wingtip_propeller_wing(), 1e4, "plunge-roll")
    toml2, _ = save_modal_model(model, tmp_path / "free.toml")
    assert "free = true" in toml2.read_text()
    back = load_modal_model(toml2)
    assert back.structure.free
    # the refit on reading rounds (1e-16 of the shapes): not bit for bit
    np.testing.assert_allclose(back.structure.shapes, model.structure.shapes, rtol=1e-12,
                               atol=1e-15 * np.abs(model.structure.shapes).max())
    edited = toml2.read_text().replace("free = true", "free = false")
    toml2.write_text(edited)
    with pytest.raises(InputError, match=r"rigid-body mode .*free = true"):
        load_modal_model(toml2)


def test_the_pk_and_the_doublet_lattice_refuse_kept_rigid_modes_in_one_line():
    """The p-k follows the oscillatory in-vacuo modes: on a free structure (κ = 10⁴) it missed
    the slow flutter the divergence root makes with the plunge (the default's critical,
    143.15 m/s) and reported 160.55 m/s. Refused through the capabilities, saying why; the
    doublet lattice (whose crossings the p-k converges) likewise, at construction."""
    from dataclasses import replace

    from propwhirl.model.aerodynamics.planform import Planform
    from propwhirl.model.protocol import capabilities

    base = wingtip_propeller_wing()
    model, _ = free_modal_model(base, 1e4, "plunge-roll")
    c = capabilities(model)
    assert not c.supports("pk") and "rigid-body roots" in c.refusal("pk")
    with pytest.raises(InputError, match=r"^method = 'pk' is invalid for this model: ") as exc:
        analyse(model, np.arange(120.0, 181.0, 30.0), method="pk")
    assert "\n" not in str(exc.value) and "rigid-body" in str(exc.value)
    with pytest.raises(InputError, match=r"^aero = 'dlm' is invalid with rigid-body modes "
                                         r"kept[^\n]*$"):
        replace(model, aero="dlm", dlm_planform=Planform.from_wing(base.wing))
