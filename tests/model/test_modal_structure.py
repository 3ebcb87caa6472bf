"""Free structures (issue 36, item 4): a free modal structure keeps its plunge and roll
rigid-body modes and is analysed without a false event; a rigid pitch is refused by name on a
wing-alone model (no tail: tests/model/test_modal_surface.py has the tail); the heavy body's
instabilities are the clamped wing's, a light body's are not (docs/validation.md, "Free
structures with plunge and roll kept"). The rigid-body modes' classification:
tests/model/test_rigid_body.py."""
from __future__ import annotations

import numpy as np
import pytest

from helpers.op2_files import free_free_modes, free_modal_model, root_body
from propwhirl import InputError
from propwhirl.analysis.modes import label_modes
from propwhirl.analysis.stability import analyse
from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
from propwhirl.io.modal_files import load_modal_model, save_modal_model, write_modes
from propwhirl.model.modal import ModalPropellerWing
from propwhirl.model.modal_structure import ModalStructure, StripPlanform

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


def test_a_free_root_with_pitch_is_refused_naming_the_mode_without_a_tail():
    """The structure keeps its pitch (a tail may hold it); the wing-alone model refuses it,
    naming the mode and saying to add a tail surface."""
    base = wingtip_propeller_wing()
    mass, roll, pitch = root_body(base.wing)
    ids, xyz, w2, shapes = free_free_modes(base.wing, 1e2 * mass, 1e2 * roll, 1e2 * pitch,
                                           "free")
    f = np.sqrt(np.abs(w2)) / (2 * np.pi)
    f[f < 0.1] = 0.0
    s = ModalStructure(grid_ids=ids, xyz=xyz, frequencies_hz=f, modal_mass=np.ones(f.size),
                       damping_ratio=np.where(f > 0, 0.01, 0.0), shapes=shapes, free=True)
    assert "pitch" in [kind for _, kind in s.rigid_body_modes()]
    with pytest.raises(InputError, match=r"^[^\n]*mode [123] \(0 Hz\) is a rigid-body pitch: "
                                         r"a wing alone has no tail.*add a tail.*surfaces"
                                         r"[^\n]*$"):
        ModalPropellerWing(s, [int(g) for g in ids], StripPlanform.from_wing(base.wing),
                           base.flight)


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
