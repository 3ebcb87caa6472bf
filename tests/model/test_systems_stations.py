"""Propellers at any station: PropellerWing makes every installation a node of its wing's mesh
(model/structure/mesh.py), keeps the thesis's uniform meshes, and converges to the uniform fine mesh."""
from dataclasses import replace

import numpy as np
import pytest
from threadpoolctl import threadpool_limits

from propwhirl.analysis.stability import analyse
from propwhirl.analysis.vibration import model_modes
from propwhirl.cases.ch09_baseline import (baseline_flight, baseline_propeller, baseline_wing,
                                           propeller_wing)
from propwhirl.model.systems import Installation, PropellerWing
from propwhirl.validate import InputError

DESIGN_Y = (0.95, 1.5, 2.05, 3.1, 4.8)


def on(wing, ys, **kw) -> PropellerWing:
    return PropellerWing(wing, baseline_flight(),
                         tuple(Installation(baseline_propeller(), y) for y in ys), **kw)


def design_wing(**mesh):
    """The baseline wing (Table 9.1) shortened to the issue's 4.8 m semi-span."""
    return replace(baseline_wing(), semi_span=4.8, **mesh)


def test_propellers_at_any_station_sit_on_nodes_without_choosing_n_elements():
    m = on(design_wing(max_element_length=0.2), DESIGN_Y)
    assert m.wing.element_count == 26 and m.wing.element_length.max() <= 0.2
    np.testing.assert_array_equal(m.wing.node_y[list(m.nodes)], DESIGN_Y)
    dm = m.dof_map()
    assert dm.node_y == tuple(m.wing.node_y)
    assert [p.y for p in dm.propellers] == list(DESIGN_Y)
    # 26 free nodes: 2 x (3 x 26 + 2 x 5) displacements and rates + 2 x 26 lag states
    assert m.state_matrix(np.array([100.0])).shape == (1, 228, 228)


def test_with_the_default_n_elements_alone_the_propellers_are_added_as_stations():
    m = on(design_wing(), DESIGN_Y)  # n_elements = 20: target length 0.24 m
    np.testing.assert_array_equal(m.wing.node_y[list(m.nodes)], DESIGN_Y)
    assert m.wing.element_length.max() <= 4.8 / 20 * (1 + 1e-12)
    assert m.wing.stations == DESIGN_Y


def test_the_wing_is_kept_when_every_propeller_is_on_a_node():
    """The thesis's models (propellers on nodes of the uniform mesh) are not re-meshed."""
    wing = baseline_wing(25)
    m = propeller_wing((wing.node_y[7], 5.7))
    assert m.wing is not None and m.wing.stations is None and m.wing.uniform
    assert np.array_equal(m.wing.node_y, np.linspace(0.0, 5.7, 26))


def test_installations_join_the_users_stations():
    wing = design_wing(stations=(1.2, 2.05), max_element_length=0.3)
    m = on(wing, (2.05, 3.1))
    assert m.wing.stations == (1.2, 2.05, 3.1)
    for y in (1.2, 2.05, 3.1):
        assert np.min(np.abs(m.wing.node_y - y)) == 0.0
    assert on(m.wing, (2.05, 3.1)).wing == m.wing  # a saved, re-read model is the same


def test_one_propeller_off_the_uniform_mesh_re_meshes_all_of_them():
    """Adding one station moves the other nodes: every installation becomes a station."""
    wing = baseline_wing(25)
    m = on(wing, (wing.node_y[7], 3.0))
    np.testing.assert_array_equal(m.wing.node_y[list(m.nodes)], (wing.node_y[7], 3.0))


@pytest.mark.parametrize("ys, words", [
    ((1.0, 6.0), "propellers[1].y = 6.0 m is outside the wing: must be in (0, 4.8] m"),
    ((0.0,), "propellers[0].y = 0.0 m is the clamped root: must be > 0"),
    ((1.0, 1.0), "propellers[1].y = 1.0 m is invalid: two propellers at node"),
    ((1.0, 1.002), "propellers[1].y = 1.002 m is invalid: it makes an element of 0.002 m"),
])
def test_installation_errors_name_the_installation(ys, words):
    with pytest.raises(InputError) as exc:
        on(design_wing(max_element_length=0.2), ys)
    msg = str(exc.value)
    assert words in msg and "\n" not in msg
    assert exc.value.path[:2] == ("propellers", len(ys) - 1)


def test_an_installation_too_close_to_a_users_station_names_one_of_them():
    with pytest.raises(InputError, match=r"propellers\[0\]\.y = 2\.003 m is invalid: it makes"):
        on(design_wing(stations=(2.0,)), (2.003,))


# ----------------------------------------------------------------------------- convergence
def test_a_non_uniform_mesh_converges_to_the_uniform_fine_mesh():
    """Baseline wing (5.7 m), propellers at 2.0 m and the tip.  A graded 16-element mesh
    (stations 0.3, 0.45, 1.2 m, h ≤ 0.4 m: elements 0.15–0.4 m) against the uniform 57-element
    mesh (0.1 m, the coarsest uniform one with a node at 2.0 m).  Mesh-convergence experiment
    (first 5 in-vacuo frequencies, critical speed = wing divergence, first whirl-flutter onset):

    ==========================  ========================  ===========  ==========
    mesh                        f3 [Hz] (largest change)  V_crit       V_flutter
    ==========================  ========================  ===========  ==========
    graded, h ≤ 0.8 m (9 el)    6.155349                  141.198      196.82
    graded, h ≤ 0.4 m (16 el)   6.155614                  141.193      196.28
    uniform 57                  6.155702                  141.205      196.13
    uniform 114                 6.155708                  —            —
    ==========================  ========================  ===========  ==========

    The 16-element graded mesh differs from the uniform 57 by ≤ 1.5e-5 in every frequency,
    0.012 m/s in the critical speed (the crossings are refined to 0.01 m/s) and 0.16 m/s
    (0.08 %) in the flutter onset; the tolerances below are about 5× those differences
    (frequencies 1e-4 relative, critical speed 0.05 m/s, flutter onset 0.5 %)."""
    graded = on(replace(baseline_wing(), stations=(0.3, 0.45, 1.2), max_element_length=0.4),
                (2.0, 5.7))
    fine = on(baseline_wing(57), (2.0, 5.7))
    assert graded.wing.element_count == 16 and fine.wing.uniform  # fine: 2.0 m is node 20
    assert np.ptp(graded.wing.element_length) > 0.2
    fg = model_modes(graded)[0].frequency_hz[:5]
    ff = model_modes(fine)[0].frequency_hz[:5]
    np.testing.assert_allclose(fg, ff, rtol=1e-4)
    with threadpool_limits(1):
        ag, af = analyse(graded), analyse(fine)
    assert ag.critical.kind == af.critical.kind == "divergence"
    assert abs(ag.critical.V - af.critical.V) <= 0.05
    flutter = lambda a: next(e for e in a.onsets if e.kind == "flutter")  # noqa: E731
    assert flutter(ag).V == pytest.approx(flutter(af).V, rel=5e-3)
