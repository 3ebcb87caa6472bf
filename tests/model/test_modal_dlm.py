"""Doublet lattice on a modal model (issue 34 item 3): the planform splined to the modes by
the strips' rule (propwhirl.model.modal, modal_structure.axis_spline), against the beam
doublet lattice on the same structure.

The tolerances come from the measured spline error: with a grid at every node the spline is
the beam's own interpolation, so the GAFs on the modes are the beam's projected,
Phi^T Q_beam Phi, to rounding (measured 4e-16 of max |Q|; asserted 1e-12).  The p-k method
then solves the same equations (the strip twin it starts and tracks from is the same too):
its crossings agree to Brent's rounding (measured <= 6e-8 m/s; asserted 1e-5 m/s).  The
default analysis converges each crossing by the p-k from its own modal Roger state space's
bracket, which keeps other modes on the two models (the modal model's DOF map has no
bending/torsion groups), so its speeds agree within the two analyses' xtol (each refined to
0.01 m/s: asserted 2 xtol), as the default and the p-k do on the beam model
(tests/analysis/test_modal_dlm.py)."""
from dataclasses import replace

import numpy as np
import pytest

pytest.importorskip("panelaero")

from propwhirl.analysis import analyse  # noqa: E402
from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing  # noqa: E402
from propwhirl.engine import XTOL  # noqa: E402
from propwhirl.io import load_modal_model, write_modes  # noqa: E402
from propwhirl.model import ModalPropellerWing, ModalStructure, StripPlanform  # noqa: E402
from propwhirl.model.aerodynamics.dlm import DlmAerodynamics  # noqa: E402
from propwhirl.model.aerodynamics.planform import Planform  # noqa: E402
from propwhirl.model.modal_structure import axis_spline  # noqa: E402
from propwhirl.model.protocol import capabilities  # noqa: E402
from propwhirl.validate import InputError  # noqa: E402

SPEEDS = np.arange(100.0, 241.0, 20.0)


def beam():
    """The wingtip model with doublet-lattice panels (8 elements, 4 x 8 panels: bounded
    work)."""
    m = wingtip_propeller_wing()
    return m.with_(wing=replace(m.wing, n_elements=8, aero="dlm", dlm_chordwise_panels=4,
                                dlm_spanwise_panels=8))


@pytest.fixture(scope="module")
def pair(tmp_path_factory):
    """The beam DLM model and its modal model written with write_modes (all modes, a grid at
    every node) and read back."""
    b = beam()
    toml, _ = write_modes(b, tmp_path_factory.mktemp("m") / "wingtip.toml")
    return b, load_modal_model(toml)


def _beam_modes(b, s: ModalStructure) -> np.ndarray:
    """The modes over the beam's DOFs [h, phi, alpha] per node (h = -T_z, phi = -R_x)."""
    Phi = np.zeros((3 * b.wing.n_nodes, s.n_modes))
    Phi[0::3], Phi[1::3], Phi[2::3] = (-s.shapes[:, :, 2].T, -s.shapes[:, :, 3].T,
                                       s.shapes[:, :, 4].T)
    return Phi


def test_the_file_holds_the_planform_and_the_model_says_doublet_lattice(pair):
    b, m = pair
    assert m.aero == "dlm" and m.dlm_mach == b.wing.dlm_mach
    assert np.array_equal(m.dlm_planform.mesh().corners,
                          Planform.from_wing(b.wing).mesh().corners)
    c = capabilities(m)
    assert c.aerodynamics == "doublet lattice" and c.supports("pk") and c.supports("reduced")
    assert c.supports("sensitivity") and c.derivatives == "central difference"
    assert not c.supports("exact-sensitivity")
    assert m.dof_map().w_labels[0] == "mode 1 lag 1"


def test_gafs_on_the_modes_are_the_beams_projected(pair):
    b, m = pair
    ab, am = DlmAerodynamics(b.wing), DlmAerodynamics(m.dlm_surface())
    assert am.b_ref == ab.b_ref
    Phi = _beam_modes(b, m.structure)
    for mach, k in ((0.0, 0.0), (0.3, 0.1), (0.5, 0.8)):
        Qb = Phi.T @ ab.exact(mach, k) @ Phi
        assert np.abs(am.exact(mach, k) - Qb).max() <= 1e-12 * np.abs(Qb).max()


@pytest.mark.parametrize("method, tol", [("pk", 1e-5), ("auto", 2 * XTOL)])
def test_modal_dlm_critical_speeds_are_the_beam_dlm_models(pair, method, tol):
    """The modal model's critical speeds are the beam model's: the p-k's to 1e-5 m/s, both
    swept on their own DOFs (the beam's ``analyse(method="pk")`` sweeps its Galerkin basis and
    converges each crossing on the full DOFs to xtol / 10: 1.3e-5 m/s from the full-order
    sweep's divergence here, 1.3e-4 from its second flutter onset — those within xtol / 10);
    the defaults' within 2 xtol."""
    b, m = pair
    if method == "pk":
        from propwhirl.analysis.pk import pk_sweep
        from propwhirl.model.aerodynamics.dlm import DlmTables
        sb, sm = pk_sweep(b, SPEEDS, modal=False, tables=DlmTables()), pk_sweep(m, SPEEDS)
        eb, em = ([(e.kind, e.V, e.frequency_hz) for e in s.flutter if e.event == "onset"]
                  for s in (sb, sm))
        ab, am = analyse(b, SPEEDS, method="pk"), analyse(m, SPEEDS, method="pk")
        for e, f in zip(ab.events, am.events):
            assert (e.kind, e.event) == (f.kind, f.event)
            assert e.V == pytest.approx(f.V, abs=XTOL / 10)
    else:
        ab, am = analyse(b, SPEEDS, method=method), analyse(m, SPEEDS, method=method)
        eb, em = ([(e.kind, e.V, e.frequency_hz) for e in a.events if e.event == "onset"]
                  for a in (ab, am))
    assert len(eb) == len(em) >= 2
    for (kb, Vb, fb), (km, Vm, fm) in zip(eb, em):
        assert kb == km and Vm == pytest.approx(Vb, abs=tol)
        assert fm == pytest.approx(fb, abs=1e-3)


def test_default_and_pk_agree_on_the_modal_model(pair):
    _, m = pair
    a, pk = analyse(m, SPEEDS), analyse(m, SPEEDS, method="pk")
    assert (a.critical.kind, a.critical.event) == (pk.critical.kind, pk.critical.event)
    assert a.critical.V == pytest.approx(pk.critical.V, abs=2 * XTOL)
    assert "every crossing converged by the p-k method" in a.warnings[0]


def _modal(b, **kw):
    s = ModalStructure.from_wing(b.wing, 4)
    return ModalPropellerWing(s, tuple(int(g) for g in s.grid_ids),
                              StripPlanform.from_wing(b.wing), b.flight, **kw)


@pytest.mark.parametrize("kw, match", [
    (dict(aero="dlm"), "dlm_planform = None is invalid with aero = 'dlm'"),
    (dict(aero="vlm"), "aero = 'vlm' is invalid"),
    (dict(aero="dlm", dlm_planform="wing"), "dlm_planform = 'wing' is invalid"),
    (dict(aero="dlm", dlm_planform=Planform.caero1((0, 0, 0), (0, 9.0, 0), 1.2, 0.8)),
     r"dlm_planform: leading_edge\[1\] y = 9 m is outside the wing grids' span \[0, 5.7\]"),
    (dict(aero="dlm", dlm_planform=Planform.caero1((0, 0, 0), (0, 5, 0), 1, 1), dlm_mach=2),
     r"dlm_mach = 2 is outside the valid range \[0, 0.9\]"),
])
def test_a_wrong_planform_is_one_line_naming_the_key(kw, match):
    with pytest.raises(InputError, match=match) as e:
        _modal(beam(), **kw)
    assert "\n" not in str(e.value)


def test_the_spline_along_a_swept_axis_carries_rigid_rotations_exactly():
    """Grids on a swept, kinked reference axis (x varying with y), each moving as a rigid
    rotation (r_x, r_y) of the wing would move it: T_z = r_x y - r_y x.  The spline's
    displacement at any point of the planform is the rigid one, -(r_x y - r_y x) positive
    down, and its streamwise slope r_y (the Hermite slope R_x - R_y dx_ref/dy; R_x alone, the
    unswept rule, misses it by r_y dx_ref/dy)."""
    y = np.array([0.0, 1.0, 2.5, 4.0])
    x = np.array([0.0, 0.4, 1.3, 1.9])                        # swept, kinked
    r = np.array([[0.01, 0.0], [0.0, 0.02], [0.015, -0.01]])  # (r_x, r_y) per mode
    shapes = np.zeros((3, 4, 6))
    shapes[:, :, 2] = r[:, :1] * y - r[:, 1:] * x
    shapes[:, :, 3], shapes[:, :, 4] = r[:, :1], r[:, 1:]
    s = ModalStructure(np.arange(1, 5), np.stack([x, y, 0 * y], 1), np.array([1.0, 2, 3]),
                       np.ones(3), np.zeros(3), shapes)
    p = np.random.default_rng(1).uniform([-0.5, 0.0], [3.0, 4.0], (50, 2))
    Z, S = axis_spline(s, (1, 2, 3, 4), p[:, 0], p[:, 1])
    z = np.einsum("pgc,mgc->pm", Z, shapes)
    slope = np.einsum("pgc,mgc->pm", S, shapes)
    assert np.allclose(z, -(np.outer(p[:, 1], r[:, 0]) - np.outer(p[:, 0], r[:, 1])),
                       atol=1e-14)
    assert np.allclose(slope, r[:, 1][None, :], atol=1e-15)


def test_a_modal_dlm_model_pickles_after_its_surface_is_built(pair):
    """A study sends models to worker processes: the surface built on first use (closures)
    stays behind, the copy builds its own, the same."""
    import pickle
    _, m = pair
    key = m.dlm_surface().key
    back = pickle.loads(pickle.dumps(m))
    assert "_dlm_surface" not in back.__dict__ and back.dlm_surface().key == key


def test_modal_dlm_sensitivities_are_the_beam_dlm_models(pair):
    """Issue 34 item 2 on the new kind: a modal doublet-lattice model's sensitivities are
    central differences of its crossing's p-k root (the AICs read from the analysis's tables),
    and equal the beam DLM model's where the modal model is the beam model (measured:
    dV/df_theta 0.165366 vs 0.165367 m/s per Hz, dV/drho -70.3127 vs -70.3127)."""
    from propwhirl.analysis import critical_sensitivities
    from propwhirl.model.aerodynamics.dlm import DlmTables

    b, m = pair
    paths = ["propellers[0].propeller.f_theta", "flight.density"]
    got = {}
    for key, model in (("beam", b), ("modal", m)):
        tables = DlmTables()
        a = analyse(model, SPEEDS, dlm_tables=tables)
        s = critical_sensitivities(model, a, dlm_tables=tables, params=paths)
        assert {x.derivative for x in s.sensitivities} == {"central difference (p-k)"}
        got[key] = {x.path: x.dV_dp for x in s.sensitivities}
    for path in paths:
        assert got["modal"][path] == pytest.approx(got["beam"][path], rel=1e-4)
