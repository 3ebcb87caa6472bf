"""Doublet-lattice panels and the beam-to-panel spline (issue 23, stage 1):
propwhirl.model.aerodynamics.dlm_mesh against the beam element's own shape functions (derivations/)."""
import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from propwhirl.model.aerodynamics.dlm_mesh import (GUIDELINE, MAX_ASPECT, guideline_note, panel_counts,
                                      panel_mesh, spline)
from propwhirl.model.structure.wing import Wing
from propwhirl.validate import InputError


def wing(**kw):
    base = dict(semi_span=6.0, mass_per_length=10.0, EI=1e5, GJ=1e5, radius_of_gyration=0.25,
                root_chord=2.0, tip_chord=1.0, elastic_axis=0.35, n_elements=5)
    base.update(kw)
    return Wing(**base)


def test_wing_aero_is_strip_by_default_and_checked():
    assert wing().aero == "strip"
    assert wing(aero="dlm").aero == "dlm"
    with pytest.raises(InputError, match="aero = 'vlm' is invalid: must be one of 'strip', 'dlm'"):
        wing(aero="vlm")
    with pytest.raises(InputError, match="dlm_chordwise_panels"):
        wing(dlm_chordwise_panels=0)


def test_panels_cover_the_tapered_planform():
    w = wing()
    m = panel_mesh(w, 6, 10)
    assert m.n == 60
    assert m.area.sum() == pytest.approx(6.0 * 0.5 * (2.0 + 1.0), rel=1e-12)
    # the leading edge at 35 % of the chord ahead of the elastic axis (the y axis)
    assert m.corners[0, 0, 0] == pytest.approx(-0.35 * 2.0)
    assert m.corners[-1, 2, 0] == pytest.approx(0.65 * 1.0)
    # doublet line at 1/4, collocation at 3/4 of each panel's chord, mid-width
    x25, x75 = m.points(0.25)[:, 0], m.points(0.75)[:, 0]
    le = 0.5 * (m.corners[:, 0, 0] + m.corners[:, 3, 0])
    assert np.allclose(x75 - x25, 0.5 * m.length)
    assert np.allclose(x25 - le, 0.25 * m.length)
    assert np.all(m.aerogrid()["N"][:, 2] == 1.0)


def test_default_counts_keep_the_panel_aspect_ratio():
    w = wing()
    nc, ns = panel_counts(w)
    assert nc == 8
    m = panel_mesh(w)
    assert np.max(m.width / m.length) <= MAX_ASPECT + 1e-12
    # one strip fewer breaks it
    assert np.max(panel_mesh(w, nc, ns - 1).width / panel_mesh(w, nc, ns - 1).length) > MAX_ASPECT
    with pytest.raises(InputError, match="panels is invalid: must be at most"):
        panel_counts(w, 64, 1000)
    with pytest.raises(InputError, match="dlm_spanwise_panels"):
        panel_counts(w, 8, 0)


def test_guideline_note():
    m = panel_mesh(wing(), 4, 12)
    dx = m.length.max()
    assert guideline_note(m, V=100.0, f_hz=GUIDELINE * 100.0 / dx * 0.99) is None
    assert "exceeds the guideline" in guideline_note(m, V=100.0, f_hz=GUIDELINE * 100.0 / dx * 1.01)


def _oracle(w, q, x, y):
    """z = h + x alpha with the derivation's own element shape functions (7.5-7.8)."""
    import sympy as sp
    from derivations.beam_element import l_e, shape_functions, xi
    N, T = shape_functions()
    ys = w.node_y
    e = min(int(np.searchsorted(ys, y, side="right")) - 1, ys.size - 2)
    le = ys[e + 1] - ys[e]
    val = {xi: 2 * (y - ys[e]) / le - 1, l_e: le}
    Nv = np.array([float(sp.N(f.subs(val))) for f in N])
    Tv = np.array([float(sp.N(f.subs(val))) for f in T])
    h1, p1, a1, h2, p2, a2 = q[3 * e:3 * e + 6]
    h = Nv @ [h1, p1, h2, p2]
    alpha = Tv @ [a1, a2]
    return h + x * alpha, alpha


@settings(max_examples=15, deadline=None)
@given(st.integers(0, 2**31 - 1))
def test_spline_is_the_beam_elements_interpolation(seed):
    pytest.importorskip("sympy")
    rng = np.random.default_rng(seed)
    w = wing(stations=(1.3, 4.0))                          # a non-uniform mesh
    q = rng.normal(size=3 * w.n_nodes)
    pts = np.column_stack([rng.uniform(-1, 1, 4), rng.uniform(0, w.semi_span, 4), np.zeros(4)])
    Z, S = spline(w, pts)
    for i, (x, y, _) in enumerate(pts):
        z, a = _oracle(w, q, x, y)
        assert (Z @ q)[i] == pytest.approx(z, rel=1e-10, abs=1e-12)
        assert (S @ q)[i] == pytest.approx(a, rel=1e-10, abs=1e-12)


def test_spline_at_the_nodes_and_in_plane_free():
    w = wing()
    ys = w.node_y
    pts = np.column_stack([np.full(ys.size, 0.3), ys, np.zeros(ys.size)])
    Z, S = spline(w, pts)
    q = np.arange(3 * w.n_nodes, dtype=float)
    assert np.allclose(Z @ q, q[0::3] + 0.3 * q[2::3])
    assert np.allclose(S @ q, q[2::3])
    assert np.all(S[:, 0::3] == 0) and np.all(S[:, 1::3] == 0)


def test_model_file_keys_round_trip_and_refuse():
    from propwhirl import io
    from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
    import dataclasses
    m = wingtip_propeller_wing()
    m = m.with_(wing=dataclasses.replace(m.wing, aero="dlm", dlm_chordwise_panels=4,
                                         dlm_spanwise_panels=12))
    text = io.dumps(m)
    assert 'aero = "dlm"' in text and "dlm_spanwise_panels = 12" in text
    back = io.loads(text)
    assert (back.wing.aero, back.wing.dlm_chordwise_panels, back.wing.dlm_spanwise_panels) == \
        ("dlm", 4, 12)
    old = io.loads(text.replace('aero = "dlm"\n', "").replace("dlm_chordwise_panels = 4\n", "")
                   .replace("dlm_spanwise_panels = 12\n", ""))
    assert old.wing.aero == "strip"                  # files without the key: the strip model
    with pytest.raises(InputError, match=r"\[wing\] aero = 'vlm' is invalid: must be one of"):
        io.loads(text.replace('aero = "dlm"', 'aero = "vlm"'))
    with pytest.raises(InputError, match="dlm_chordwise_panels"):
        io.loads(text.replace("dlm_chordwise_panels = 4", "dlm_chordwise_panels = 0"))
