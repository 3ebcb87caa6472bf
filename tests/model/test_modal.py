"""Modal structures (issue 22, item 2): a wing given by its normal modes.

The exactness check: a beam model's own modes, all of them, at one grid per node, with the
strips at the nodes, give the same A(V) (its eigenvalues) and the same critical speeds as the
beam model itself — bare wing, wingtip propeller, two propellers.  The spline: exact for the
beam's own interpolation (cubic heave, linear twist).  Errors: one line naming the key and id.
"""
from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.optimize import linear_sum_assignment

from helpers.eigen import matched_gap
from propwhirl import InputError
from propwhirl.analysis.stability import analyse
from propwhirl.cases.ch10_other_wings import two_propeller_wing, wingtip_propeller_wing
from propwhirl.engine import XTOL
from propwhirl.model.modal import (ModalInstallation, ModalPropellerWing, ModalStructure,
                                   StripPlanform, strip_interpolation)
from propwhirl.model.protocol import Model


def modal_of(full, n_modes=None):
    """The modal model of a PropellerWing: its wing's modes at its nodes, propellers at the
    nodes' grids with their own mounts (what io.write_modes writes)."""
    w = full.wing
    s = ModalStructure.from_wing(w, n_modes)
    inst = tuple(ModalInstallation(i.propeller, 1 + node, i.mount, i.aero)
                 for i, node in zip(full.propellers, full.nodes))
    return ModalPropellerWing(s, tuple(int(g) for g in s.grid_ids), StripPlanform.from_wing(w),
                              full.flight, inst, full.wing_aero, full.propeller_aero,
                              full.rotating)


MODELS = {"bare wing": lambda: wingtip_propeller_wing().with_(propellers=()),
          "wingtip": wingtip_propeller_wing,
          "wingtip rigid": lambda: wingtip_propeller_wing(mount="rigid"),
          "two propellers": two_propeller_wing}


@pytest.mark.parametrize("name", MODELS)
def test_all_modes_at_the_nodes_give_the_beam_models_state_matrix(name):
    full = MODELS[name]()
    modal = modal_of(full)
    assert isinstance(modal, Model)
    V = np.array([20.0, 150.0, 300.0])
    Af, Am = full.state_matrix(V), modal.state_matrix(V)
    assert Af.shape == Am.shape
    for t in range(V.size):
        assert matched_gap(Af[t], Am[t]) < 1e-6


@pytest.mark.parametrize("name", ["bare wing", "wingtip", "two propellers"])
def test_all_modes_give_the_beam_models_critical_speeds(name):
    full = MODELS[name]()
    a, b = analyse(full), analyse(modal_of(full))
    assert [e.kind for e in a.events] == [e.kind for e in b.events]
    for x, y in zip(a.events, b.events):
        assert abs(x.V - y.V) <= 2 * XTOL, (x, y)
    assert abs(a.critical.V - b.critical.V) <= 2 * XTOL


def test_the_dof_map_names_modes_and_propellers():
    m = modal_of(two_propeller_wing(), 6)
    dm = m.dof_map()
    assert dm.q_labels[:6] == tuple(f"mode {k}" for k in range(1, 7))
    assert dm.q_labels[6:] == ("propeller 1 theta", "propeller 1 psi", "propeller 2 theta",
                               "propeller 2 psi")
    assert [p.theta for p in dm.propellers] == [6, 8]
    assert dm.n_lag == 2 * m.planform.y.size
    assert m.second_order(np.array([100.0])).S1.shape == (1, 10, 10)
    quiet = m.without_aerodynamics().dof_map()
    assert quiet.n_lag == 0


def test_fewer_modes_converge_to_the_full_models_matrix_eigenvalues():
    full = wingtip_propeller_wing()
    V = np.array([150.0])
    ref = np.linalg.eigvals(full.state_matrix(V)[0])
    target = ref[np.argmax(ref.real)]           # the least stable root at 150 m/s
    errors = []
    for n in (2, 4, 8, 16):
        lam = np.linalg.eigvals(modal_of(full, n).state_matrix(V)[0])
        errors.append(float(np.min(np.abs(lam - target)) / abs(target)))
    assert errors[-1] < errors[0]
    assert errors[-1] < 1e-2


# ------------------------------------------------------------------------------- the spline
def _structure_from_field(y_grid, h, dh, alpha, x_grid=None):
    """One mode whose heave h, slope dh/dy and twist alpha at the grids are given."""
    n = len(y_grid)
    xyz = np.zeros((n, 3))
    xyz[:, 1] = y_grid
    if x_grid is not None:
        xyz[:, 0] = x_grid
    shapes = np.zeros((1, n, 6))
    shapes[0, :, 2], shapes[0, :, 3], shapes[0, :, 4] = -h, -dh, alpha
    shapes[0, :, 0] = 1.0             # chordwise motion: not read by the strips, never zero
    return ModalStructure(np.arange(1, n + 1), xyz, [5.0], [1.0], [0.0], shapes)


def _planform(ys, ea=0.4, chord=1.0, x_le=None):
    n = len(ys)
    x_le = -ea * chord * np.ones(n) if x_le is None else x_le
    return StripPlanform(np.asarray(ys), np.full(n, 0.1), np.full(n, chord), x_le,
                         np.full(n, ea), np.full(n, 0.25), np.full(n, 2 * np.pi))


@settings(max_examples=40, deadline=None)
@given(st.lists(st.floats(-1, 1), min_size=4, max_size=4),
       st.lists(st.floats(-1, 1), min_size=2, max_size=2),
       st.lists(st.floats(0.05, 1.0), min_size=2, max_size=6))
def test_the_spline_is_exact_for_cubic_heave_and_linear_twist(c, d, steps):
    """The beam element's own interpolation (Hermite cubic heave, linear twist) is
    reproduced exactly between any grids: the spline's error is only the field's departure
    from a cubic (heave) or a straight line (twist) between two grids."""
    yg = np.concatenate([[0.0], np.cumsum(steps)])
    h = lambda y: c[0] + c[1] * y + c[2] * y**2 + c[3] * y**3            # noqa: E731
    dh = lambda y: c[1] + 2 * c[2] * y + 3 * c[3] * y**2                # noqa: E731
    s = _structure_from_field(yg, h(yg), dh(yg), d[0] + d[1] * yg)
    ys = np.linspace(0, yg[-1], 17)
    T = strip_interpolation(s, s.grid_ids, _planform(ys))
    hs = np.einsum("scgk,gk->sc", T, s.shapes[0])
    scale = 1 + np.max(np.abs(h(ys)))
    np.testing.assert_allclose(hs[:, 0], h(ys), atol=1e-12 * scale)
    np.testing.assert_allclose(hs[:, 1], d[0] + d[1] * ys, atol=1e-12)


def test_the_heave_is_carried_to_the_elastic_axis_by_the_rigid_chord():
    """A reference axis 0.3 m ahead of the strips' elastic axis: h_ea = h_ref + 0.3 α (x aft,
    nose up α lowers the points behind the reference axis: h down)."""
    yg = np.array([0.0, 1.0, 2.0])
    s = _structure_from_field(yg, np.zeros(3), np.zeros(3), np.full(3, 0.01),
                              x_grid=np.full(3, -0.3))
    T = strip_interpolation(s, s.grid_ids, _planform([0.5, 1.5]))
    hs = np.einsum("scgk,gk->sc", T, s.shapes[0])
    np.testing.assert_allclose(hs[:, 0], 0.3 * 0.01)
    np.testing.assert_allclose(hs[:, 1], 0.01)


def test_the_beams_own_modes_are_reproduced_exactly_at_every_strip():
    full = two_propeller_wing()
    s = ModalStructure.from_wing(full.wing, 10)
    T = strip_interpolation(s, s.grid_ids, StripPlanform.from_wing(full.wing))
    got = np.einsum("scgk,mgk->msc", T, s.shapes)
    want = np.stack([-s.shapes[:, 1:, 2], s.shapes[:, 1:, 4]], axis=-1)
    np.testing.assert_allclose(got, want, atol=1e-14)


# ------------------------------------------------------------------------------- errors
def _good():
    return ModalStructure.from_wing(wingtip_propeller_wing().wing, 4)


def _replace(s, **kw):
    d = dict(grid_ids=s.grid_ids, xyz=s.xyz, frequencies_hz=s.frequencies_hz,
             modal_mass=s.modal_mass, damping_ratio=s.damping_ratio, shapes=s.shapes,
             source="wing.modes.npz")
    d.update(kw)
    return ModalStructure(**d)


@pytest.mark.parametrize("change, words", [
    (lambda s: dict(frequencies_hz=np.r_[0.0, s.frequencies_hz[1:]]),
     ["wing.modes.npz", "frequencies_hz[0]", "rigid-body mode", "mode 1"]),
    (lambda s: dict(grid_ids=np.r_[s.grid_ids[:-1], s.grid_ids[0]]),
     ["wing.modes.npz", "grid_ids", "grid 1 twice"]),
    (lambda s: dict(modal_mass=-s.modal_mass), ["wing.modes.npz", "modal_mass[0]", "> 0"]),
    (lambda s: dict(damping_ratio=np.full(4, 1.5)), ["damping_ratio[0]", "[0, 1)"]),
    (lambda s: dict(shapes=s.shapes[:, :3]), ["wing.modes.npz", "shapes", "shape"]),
    (lambda s: dict(xyz=np.where(np.arange(3) == 1, np.nan, s.xyz)), ["xyz", "finite"]),
    (lambda s: dict(grid_ids=-s.grid_ids), ["grid_ids[0]", "positive"]),
    (lambda s: dict(shapes=np.concatenate([s.shapes[:3], 0 * s.shapes[3:]])),
     ["shapes[3]", "no motion"]),
])
def test_a_bad_structure_is_one_line_naming_the_source_key_and_id(change, words):
    s = _good()
    with pytest.raises(InputError) as e:
        _replace(s, **change(s))
    msg = str(e.value)
    assert "\n" not in msg
    for w in words:
        assert w in msg, msg


def test_a_hub_grid_not_in_the_modes_or_not_moving_is_refused():
    full = wingtip_propeller_wing()
    m = modal_of(full, 4)
    prop = full.propellers[0].propeller
    with pytest.raises(InputError, match=r"propellers\[0\]\.grid = 999 is not a grid"):
        m.with_(propellers=(ModalInstallation(prop, 999),))
    with pytest.raises(InputError, match=r"grid = 1 does not move in any mode"):
        m.with_(propellers=(ModalInstallation(prop, 1),))           # the clamped root
    with pytest.raises(InputError, match=r"propellers\[1\]\.grid = 5 .*at most one"):
        m.with_(propellers=(ModalInstallation(prop, 5), ModalInstallation(prop, 5)))
    with pytest.raises(InputError, match="must be one of .flexible., .rigid., .on-grid."):
        ModalInstallation(prop, 5, mount="rigid-on-hub")


def test_strips_outside_the_grids_or_unordered_grids_are_refused():
    m = modal_of(wingtip_propeller_wing(), 4)
    ys = m.planform.y.copy()
    ys[-1] += 1.0
    bad = _planform(ys)
    with pytest.raises(InputError, match=r"y\[\d+\] = .* outside the wing grids' span"):
        m.with_(planform=bad)
    with pytest.raises(InputError, match=r"wing_grids\[1\] = 1 .* ordered root to tip"):
        m.with_(wing_grids=(2, 1, 3))
    with pytest.raises(InputError, match=r"wing_grids\[0\] = 77 is not a grid"):
        m.with_(wing_grids=(77, 1))


# ------------------------------------------------------------------------------- way (b)
def on_grid_of(full, n_modes=None):
    """The mount-in-the-modes model (way b) of a PropellerWing: the whole structure's modes
    (wing, propeller masses, mount springs), each propeller rigid on its hub grid."""
    s, hubs, _ = ModalStructure.with_mounts(full, n_modes)
    inst = tuple(ModalInstallation(i.propeller, h, "on-grid", i.aero)
                 for i, h in zip(full.propellers, hubs))
    nn = full.wing.n_nodes
    return ModalPropellerWing(s, tuple(int(g) for g in s.grid_ids[:nn]),
                              StripPlanform.from_wing(full.wing), full.flight, inst,
                              full.wing_aero, full.propeller_aero, full.rotating)


def undamped_mounts(full):
    from dataclasses import replace

    return full.with_(propellers=tuple(
        replace(i, propeller=replace(i.propeller, damping_theta=0.0, damping_psi=0.0))
        for i in full.propellers))


@pytest.mark.parametrize("name", ["wingtip", "two propellers"])
def test_on_grid_with_all_modes_is_the_spring_model_when_its_damping_is_modal(name):
    """Way (b): the propellers rigid on hub grids, their mounts' springs and masses in the
    modes, give the spring model's A(V) exactly when the structure's damping is diagonal in
    its modes (here: undamped mounts): the hub's loads are chapter 8's (generated prop_hub)."""
    full = undamped_mounts(MODELS[name]())
    s, _, coupling = ModalStructure.with_mounts(full)
    assert coupling == 0.0
    modal = on_grid_of(full)
    assert modal.dof_map().n_dof == full.dof_map().n_dof
    assert not modal.dof_map().propellers                 # no θ, ψ of their own
    V = np.array([20.0, 150.0, 300.0])
    Af, Am = full.state_matrix(V), modal.state_matrix(V)
    for t in range(V.size):
        assert matched_gap(Af[t], Am[t]) < 1e-6


def test_on_grid_gives_the_spring_models_whirl_flutter_speed():
    """Issue 22, 4(c): the wingtip model with its mount in the modes (the thesis's springs and
    damping, the damping made modal) against the spring model: every instability within 0.2 %
    (the whirl flutter 0.13 % higher: the mount damping's couplings between modes, dropped by
    modal damping, docs/validation.md); with undamped mounts all within the crossing tolerance."""
    full = wingtip_propeller_wing()
    a, b = analyse(full), analyse(on_grid_of(full))
    assert [e.kind for e in a.events] == [e.kind for e in b.events]
    for x, y in zip(a.events, b.events):
        assert abs(x.V - y.V) <= 2e-3 * x.V, (x, y)
    quiet = undamped_mounts(full)
    a, b = analyse(quiet), analyse(on_grid_of(quiet))
    for x, y in zip(a.events, b.events):
        assert abs(x.V - y.V) <= 2 * XTOL, (x, y)


def test_a_propeller_on_grid_is_spinning_and_loaded_only_through_its_hub():
    full = undamped_mounts(wingtip_propeller_wing())
    m = on_grid_of(full, 8)
    V = np.array([100.0])
    still = m.with_(rotating=False, propeller_aero=False).second_order(V)
    spin = m.with_(propeller_aero=False).second_order(V)
    G = spin.S2[0] - still.S2[0]                          # the gyroscopic matrix alone
    np.testing.assert_allclose(G, -G.T, atol=1e-12 * np.abs(G).max())
    assert np.abs(G).max() > 0
    np.testing.assert_array_equal(spin.S1, still.S1)      # no mass of its own: in the modes


def test_the_events_of_a_modal_model_are_named_by_its_modes_and_the_wing_participates():
    """The analyses read a modal model from its DOF map: its events named as a beam model's
    ("wing n", "backward k", "forward k", issue 34 item 4 — no longer after their largest
    coordinate, "mode 3" or "propeller 1 psi", which gave two events one name), the modes
    counted as the wing in the participation (not "other")."""
    a = analyse(modal_of(wingtip_propeller_wing(), 12))
    labels = {e.label for e in a.events}
    assert labels and all(lab.split()[0] in ("wing", "backward", "forward")
                          for lab in labels), labels
    for e in a.events:
        assert e.participation.other == 0.0
        assert e.participation.wing > 0.0
    whirl = max((e for e in a.events if e.kind == "flutter"),
                key=lambda e: e.participation.propellers[0].share)
    assert whirl.whirl in ("forward", "backward")


# ------------------------------------------------------------------------------- convergence
def _relative_errors(ref, got):
    """|ΔV|/V of each event of ``ref`` from its match in ``got`` (same kind and event, one to
    one by nearest speed); inf for an event with no match."""
    cost = np.full((len(ref), max(1, len(got))), np.inf)
    for i, a in enumerate(ref):
        for j, b in enumerate(got):
            if (a.kind, a.event) == (b.kind, b.event):
                cost[i, j] = abs(b.V - a.V) / a.V
    out = np.full(len(ref), np.inf)
    finite = np.where(np.isfinite(cost), cost, 1e9)
    for i, j in zip(*linear_sum_assignment(finite)):
        out[i] = cost[i, j]
    return out


@pytest.mark.parametrize("name, build, enough", [
    ("wingtip", on_grid_of, 10), ("two propellers", on_grid_of, 10),
    ("wingtip", modal_of, 16),
])
def test_the_critical_speeds_converge_to_the_beam_models_as_modes_are_added(name, build,
                                                                             enough):
    """Issue 22, 4(b) (docs/validation.md, "Modal structures"): every instability of the beam
    model within 0.5 % from ``enough`` modes on (the mounts in the modes: 10; the bare wing's
    modes with the propellers' own mounts: 16 for the wingtip model), and not with a third of
    them."""
    full = MODELS[name]()
    ref = analyse(full).events
    for n in (enough, enough + 2, 20):
        err = _relative_errors(ref, analyse(build(full, n)).events)
        assert err.max() <= 5e-3, (n, err)
    err = _relative_errors(ref, analyse(build(full, enough // 3)).events)
    assert err.max() > 5e-3


ANY_ARRAY = st.one_of(
    st.none(), st.text(max_size=3), st.floats(), st.lists(st.floats(), max_size=4),
    st.lists(st.lists(st.floats(allow_nan=True), min_size=1, max_size=3), max_size=3),
    st.lists(st.integers(-3, 30), max_size=4), st.lists(st.text(max_size=2), max_size=3))


@settings(max_examples=150, deadline=None)
@given(key=st.sampled_from(["grid_ids", "xyz", "frequencies_hz", "modal_mass",
                            "damping_ratio", "shapes"]), value=ANY_ARRAY)
def test_any_array_gives_a_structure_or_one_line_naming_the_key(key, value):
    """Every field of a ModalStructure replaced by anything: a structure, or one line
    naming the source (never a NumPy traceback)."""
    try:
        _replace(_good(), **{key: value})
    except InputError as exc:
        assert "\n" not in str(exc) and "wing.modes.npz" in str(exc), str(exc)


@settings(max_examples=12, deadline=None)
@given(d=st.floats(-0.6, 0.6), speed=st.floats(30.0, 320.0))
def test_grids_off_the_elastic_axis_give_the_same_model(d, speed):
    """The grids (wing and hub) moved a distance d [m] along x off the elastic axis, the mode
    shapes carried rigidly with them (T_z at x = d is T_z − R_y d): the strips' heave is taken
    back to the elastic axis and the propeller's block is written about the hub grid
    (a_P b_P = x_grid − x_mid-chord), so A(V) is unchanged."""
    m = modal_of(wingtip_propeller_wing(), 8)
    s = m.structure
    shapes = s.shapes.copy()
    shapes[..., 2] -= d * s.shapes[..., 4]
    xyz = s.xyz.copy()
    xyz[:, 0] += d
    moved = m.with_(structure=ModalStructure(s.grid_ids, xyz, s.frequencies_hz, s.modal_mass,
                                             s.damping_ratio, shapes))
    V = np.array([speed])
    assert matched_gap(m.state_matrix(V)[0], moved.state_matrix(V)[0]) < 1e-8
