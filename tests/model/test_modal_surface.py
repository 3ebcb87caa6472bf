"""A modal model's further lifting surfaces (issue 36, item 4): a tail's strips splined to its
own grids, loaded by the same generated strip functions as the wing's; with a tail a free
structure keeps its rigid pitch (docs/validation.md, "(4c) A free pitch with a tail")."""
from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from helpers.op2_files import TAIL, centre_of_gravity_x, tailed_modal_model
from propwhirl import InputError
from propwhirl.analysis.stability import analyse
from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
from propwhirl.model.aerodynamics.planform import Planform
from propwhirl.model.frequency_domain import modal_pk_system
from propwhirl.model.modal import ModalInstallation, ModalPropellerWing
from propwhirl.model.modal_structure import ModalStructure, StripPlanform
from propwhirl.model.modal_surface import ModalSurface, neutral_point
from propwhirl.model.protocol import capabilities


@pytest.fixture(scope="module")
def base():
    return wingtip_propeller_wing()


@pytest.fixture(scope="module")
def wing_model(base):
    """The wingtip wing's 8 lowest modes, clamped, with its propeller at the tip grid."""
    s = ModalStructure.from_wing(base.wing, n_modes=8)
    return ModalPropellerWing(s, tuple(int(g) for g in s.grid_ids),
                              StripPlanform.from_wing(base.wing), base.flight,
                              (ModalInstallation(base.propellers[0].propeller, grid=26),))


def test_a_surface_on_the_wing_own_grids_and_strips_doubles_the_wing_strip_loads(wing_model):
    """The tail's loads are the wing's generated strip loads through its own spline: put on
    the wing's grids with the wing's strips, every aerodynamic part of the system doubles and
    its lag states repeat the wing's, labelled "tail strip s w r"."""
    m = wing_model
    twin = m.with_(surfaces=(ModalSurface(m.wing_grids, m.planform),))
    V = np.array([60.0, 140.0])
    alone, dry, both = (x.second_order(V) for x in (m, m.with_(wing_aero=False), twin))
    for k in ("S1", "S2", "S3"):
        np.testing.assert_allclose(getattr(both, k) - getattr(dry, k),
                                   2.0 * (getattr(alone, k) - getattr(dry, k)),
                                   rtol=1e-12, atol=1e-12 * np.abs(getattr(alone, k)).max())
    n = alone.Ww.shape[-1]
    assert both.Ww.shape[-1] == 2 * n
    np.testing.assert_array_equal(both.S4, np.concatenate([alone.S4, alone.S4], axis=2))
    np.testing.assert_array_equal(both.Ww[:, n:, n:], alone.Ww)
    assert not both.Ww[:, :n, n:].any()
    np.testing.assert_array_equal(both.Wq, np.concatenate([alone.Wq, alone.Wq], axis=1))
    labels = twin.dof_map().w_labels
    assert labels[:n] == m.dof_map().w_labels
    assert labels[n:n + 2] == ("tail strip 1 w1", "tail strip 1 w2")
    # the p-k's exact Theodorsen strips take the surface too
    pk_one, pk_two = modal_pk_system(m, 100.0)(40.0), modal_pk_system(twin, 100.0)(40.0)
    no_wing = m.with_(wing_aero=False).second_order(np.array([100.0]))
    for one, two, X0 in zip(pk_one, pk_two, (no_wing.S1[0], no_wing.S2[0], no_wing.S3[0])):
        assert np.abs(one - X0).max() > 0
        np.testing.assert_allclose(two - X0, 2.0 * (one - X0), rtol=1e-12,
                                   atol=1e-12 * np.abs(one).max())


def test_a_surface_whose_grids_do_not_move_changes_nothing(wing_model):
    """A tail on grids at rest in every mode (as a clamped wing's root is): no load on the
    modes, only its lag states (driven by nothing)."""
    m = wing_model
    s = m.structure
    s2 = dataclasses.replace(
        s, grid_ids=np.append(s.grid_ids, [901, 902]),
        xyz=np.concatenate([s.xyz, [[3.0, 0.0, 0.0], [3.0, 1.0, 0.0]]]),
        shapes=np.concatenate([s.shapes, np.zeros((s.n_modes, 2, 6))], axis=1))
    tail = ModalSurface((901, 902), StripPlanform(
        y=[0.25, 0.75], width=[0.5, 0.5], chord=[0.7, 0.7], leading_edge_x=[2.8, 2.8],
        elastic_axis=[0.25, 0.25], aerodynamic_centre=[0.25, 0.25], lift_slope=[6.0, 6.0]))
    V = np.array([100.0])
    a, b = m.second_order(V), m.with_(structure=s2, surfaces=(tail,)).second_order(V)
    for k in ("S1", "S2", "S3"):
        np.testing.assert_array_equal(getattr(a, k), getattr(b, k))
    assert not b.S4[..., a.S4.shape[-1]:].any() and not b.Wq[:, a.Wq.shape[1]:].any()


def test_bad_surfaces_are_refused_in_one_line_naming_the_field(wing_model):
    m = wing_model
    p = m.planform
    cases = [
        (lambda: ModalSurface(grids=[1.5, 2], planform=p), r"^grids = .* is invalid: must be a "
                                                           r"sequence of grid ids"),
        (lambda: ModalSurface(grids=(1,), planform=p), r"^grids = \[1\] is invalid: .*two or "
                                                       r"more"),
        (lambda: ModalSurface(grids=(1, 2), planform="strips"), r"^planform = .* must be a "
                                                                 r"StripPlanform"),
        (lambda: ModalSurface(grids=(1, 2), planform=p, name="strip"), r"^name = 'strip' is "
                                                                        r"invalid"),
        (lambda: ModalSurface(grids=(1, 2), planform=p, name="a b"), r"^name = 'a b' is "
                                                                      r"invalid"),
        (lambda: m.with_(surfaces=ModalSurface(m.wing_grids, p)),
         r"^surfaces = .* must be a sequence of ModalSurface"),
        (lambda: m.with_(surfaces=(ModalSurface((1, 999), p),)),
         r"surfaces\[0\]\.grids\[1\] = 999 is not a grid of the modes"),
        (lambda: m.with_(surfaces=(ModalSurface((3, 1), p),)),
         r"surfaces\[0\]\.grids\[1\] = 1 .* is invalid: the surfaces\[0\]\.grids must be "
         r"ordered root to tip"),
        (lambda: m.with_(surfaces=(ModalSurface((1, 2), p),)),
         r"y\[1\] = .* m is outside the surfaces\[0\]\.grids' span"),
        (lambda: m.with_(surfaces=(ModalSurface(m.wing_grids, p),
                                   ModalSurface(m.wing_grids, p))),
         r"^surfaces\[1\]\.name = 'tail' is invalid: surfaces\[0\] has it already"),
        (lambda: m.with_(surfaces=(ModalSurface(m.wing_grids, p),), aero="dlm",
                         dlm_planform=Planform.from_wing(wingtip_propeller_wing().wing)),
         r"^surfaces is invalid with aero = 'dlm'"),
    ]
    for make, pattern in cases:
        with pytest.raises(InputError, match=pattern) as exc:
            make()
        assert "\n" not in str(exc.value)
    surf = ModalSurface(m.wing_grids, p)
    with pytest.raises(dataclasses.FrozenInstanceError):
        surf.name = "fin"                                    # immutable
    assert isinstance(m.with_(surfaces=[surf]).surfaces, tuple)


def test_the_neutral_point_is_the_lift_weighted_mean_of_the_aerodynamic_centres():
    def strips(x_ac, area):
        return StripPlanform(y=[0.5], width=[1.0], chord=[area], leading_edge_x=[x_ac - area / 4],
                             elastic_axis=[0.5], aerodynamic_centre=[0.25], lift_slope=[6.0])
    # 4 m² at x = -0.25 and 1 m² at 3.5: (4 (-0.25) + 3.5) / 5 = 0.5
    assert neutral_point([strips(-0.25, 4.0), strips(3.5, 1.0)]) == pytest.approx(0.5, 1e-12)


# ----------------------------------------------------------------- the free body with a tail
@pytest.fixture(scope="module")
def clamped(base):
    return analyse(base).events


@pytest.fixture(scope="module")
def heavy(base):
    model, n_rigid = tailed_modal_model(base, 1e4)
    return model, n_rigid, analyse(model)


def rigid_modes(a):
    return [k for k, lab in enumerate(a.sweep.mode_labels) if lab.startswith("rigid")]


def test_with_a_tail_a_free_pitch_is_kept_and_the_heavy_body_is_the_clamped_wing(heavy,
                                                                               clamped):
    """κ = 10⁴, the default analysis (method "auto"): the three rigid-body modes kept (the
    pitch among them), the short period stable well below the wing's instabilities, the
    elastic flutters and the high divergence the clamped wing's to 5e-4; nothing before the
    wing's divergence region (the free aircraft's pitch goes at 141.7 m/s, 1 % below the
    clamped divergence: the wing's flexible lift takes the static margin near its divergence)."""
    model, n_rigid, a = heavy
    assert n_rigid == 3
    assert sorted(k for _, k in model.structure.rigid_body_modes()) == ["pitch", "roll", "roll"]
    rigid = rigid_modes(a)
    below = a.sweep.V <= 120.0
    assert np.max(a.sweep.eigenvalues[np.ix_(below, rigid)].real) < 0.0
    lam = a.sweep.eigenvalues[np.argmin(np.abs(a.sweep.V - 100.0)), rigid]
    assert np.any((lam.imag > 0) & (lam.real < 0))              # the short period: damped
    got = a.events
    assert min(g.V for g in got) > 0.985 * clamped[0].V
    for e in clamped[1:]:
        near = min((g for g in got if g.kind == e.kind), key=lambda g: abs(g.V - e.V))
        assert abs(near.V - e.V) < 5e-4 * e.V, (e, near)
        assert not near.label.startswith(("rigid", "static"))
    x_cg = centre_of_gravity_x(model)
    assert x_cg == pytest.approx(TAIL["body_x"], abs=1e-3)
    assert neutral_point([model.planform, model.surfaces[0].planform]) > x_cg + 0.3


def test_a_light_body_with_a_tail_changes_the_instabilities(base, clamped):
    """κ = 1: the wing flutters 5.9 % later and its whirl flutter 9.7 % earlier; the rigid
    modes stay stable over the whole range."""
    model, _ = tailed_modal_model(base, 1.0)
    a = analyse(model)
    first = min(a.events, key=lambda g: g.V)
    assert first.kind == "flutter" and first.V > 1.03 * clamped[1].V
    assert not any(g.label.startswith(("rigid", "static")) for g in a.events)
    assert not any(abs(g.V - clamped[0].V) < 0.05 * clamped[0].V for g in a.events)


def test_without_the_tail_the_pitch_is_refused_and_ahead_of_the_centre_of_gravity_it_diverges(
        base):
    """No tail: refused, saying to add one.  The tail ahead of the centre of gravity (the
    neutral point ahead of it): statically unstable, reported as a divergence of the rigid
    pitch from the first speed ("unstable-at-start", a mode named "static"/"rigid"), never a
    flutter of an elastic mode — the first flutter is the clamped wing's region."""
    with pytest.raises(InputError, match=r"^[^\n]*mode \d \(0 Hz\) is a rigid-body pitch: a "
                                         r"wing alone has no tail[^\n]*add a tail[^\n]*$"):
        tailed_modal_model(base, 1e4, tail=False)
    model, _ = tailed_modal_model(base, 1e4, arm=-TAIL["arm"])
    assert neutral_point([model.planform, model.surfaces[0].planform]) \
        < centre_of_gravity_x(model)
    a = analyse(model)
    c = a.critical
    assert (c.kind, c.event) == ("divergence", "unstable-at-start")
    assert c.V == a.sweep.V[0] and c.label.split()[0] in ("static", "rigid")
    assert min(g.V for g in a.events if g.kind == "flutter") > 0.98 * 143.15


def test_the_pk_stays_refused_on_rigid_modes_with_a_tail(heavy):
    model = heavy[0]
    assert not capabilities(model).supports("pk")
    with pytest.raises(InputError, match=r"^method = 'pk' is invalid for this model: "
                                         r"[^\n]*rigid-body"):
        analyse(model, np.arange(120.0, 181.0, 30.0), method="pk")
