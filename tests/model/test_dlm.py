"""Doublet-lattice generalised aerodynamic forces (issue 23, stage 2): propwhirl.model.aerodynamics.dlm
against published lift-curve slopes, Theodorsen's two-dimensional limit and the strips."""
import dataclasses

import numpy as np
import pytest

pytest.importorskip("panelaero")

from propwhirl.cases.ch07_patil import patil_model  # noqa: E402
from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing  # noqa: E402
from propwhirl.model.aerodynamics import dlm  # noqa: E402
from propwhirl.model.frequency_domain import K_MIN, _strip, pk_system  # noqa: E402
from propwhirl.model.aerodynamics.theodorsen import theodorsen  # noqa: E402
from propwhirl.model.structure.wing import Wing  # noqa: E402
from propwhirl.validate import InputError  # noqa: E402


def helmbold(A):
    """Helmbold's (DATCOM's, unswept, incompressible) lift-curve slope [1/rad]."""
    return 2 * np.pi * A / (2 + np.sqrt(A * A + 4))


def flat_wing(semi_span, chord=1.0, **kw):
    base = dict(mass_per_length=1.0, EI=1e4, GJ=1e4, radius_of_gyration=0.25, n_elements=8)
    base.update(kw)
    if callable(chord):
        return Wing(semi_span=semi_span, chord=chord, **base)
    return Wing(semi_span=semi_span, root_chord=chord, **base)


def lift_slope(wing, n_chord, n_span):
    """C_L_alpha [1/rad] of the whole wing in steady uniform twist (Q's h-rows summed)."""
    aero = dlm.DlmAerodynamics(wing, n_chord=n_chord, n_span=n_span)
    Q = aero.exact(0.0, 0.0)
    nn = wing.n_nodes
    heave, twist = np.zeros(3 * nn), np.zeros(3 * nn)
    heave[0::3], twist[2::3] = 1.0, 1.0
    return float((-(heave @ Q @ twist)).real / aero.mesh.area.sum())


@pytest.mark.parametrize("A", [2.0, 6.0, 20.0])
def test_elliptic_wing_lift_slope_is_helmbolds(A):
    """An elliptic planform (c = c0 sqrt(1 - (y/s)^2), A = 8 s / (pi c0)): within 3 % of
    Helmbold's lifting-surface formula (AR 2: -2.3 %, 6: -2.3 %, 20: -0.6 % at 8 x 32)."""
    s = A * np.pi / 8
    w = flat_wing(s, chord=lambda y: np.maximum(np.sqrt(np.clip(1 - (y / s) ** 2, 0, 1)), 1e-3),
                  n_elements=40)
    assert lift_slope(w, 8, 32) == pytest.approx(helmbold(A), rel=0.03)


def test_rectangular_wings_tend_to_two_pi():
    """Rectangular flat wings: below Helmbold's elliptic-like value by at most 7 %, rising with
    the aspect ratio to within 5 % of the two-dimensional 2 pi at A = 200."""
    slopes = {A: lift_slope(flat_wing(A / 2), 8, int(4 * A)) for A in (2.0, 6.0, 20.0)}
    for A, a in slopes.items():
        assert -0.07 < a / helmbold(A) - 1 < 0.01
    assert slopes[2.0] < slopes[6.0] < slopes[20.0]
    a200 = lift_slope(flat_wing(100.0, n_elements=4), 4, 100)
    assert slopes[20.0] < a200 < 2 * np.pi and a200 > 0.95 * 2 * np.pi


@pytest.mark.parametrize("k", [0.1, 0.5])
def test_slender_wing_root_strip_is_theodorsen(k):
    """The lift of the root strip of an A = 40 wing oscillating rigidly in plunge and in pitch
    (about 40 % chord, Mach 0) is Theodorsen's within 3 %: the DLM tends to the strips."""
    a = -0.2
    w = flat_wing(20.0, elastic_axis=0.4, n_elements=4)
    aero = dlm.DlmAerodynamics(w, n_chord=4, n_span=40)
    Qjj = aero.aic(0.0, k)
    kbar = k / 0.5                                     # PanelAero's omega / U [1/m]
    x = aero.mesh.points(0.75)[:, 0]
    root = np.arange(4)
    width = aero.mesh.width[0]

    def strip_cl(wash):
        return (aero.mesh.area[root] * (Qjj @ wash)[root]).sum() / width / 1.0

    C = complex(theodorsen(np.array(k)))
    pitch = np.pi * (1j * k + a * k * k) + 2 * np.pi * C * (1 + (0.5 - a) * 1j * k)
    plunge = -np.pi * k * k + 2 * np.pi * C * 1j * k                 # h / b = 1, positive down
    assert abs(strip_cl(1 + 1j * kbar * x) - pitch) < 0.03 * abs(pitch)
    assert abs(strip_cl(1j * kbar * 0.5 * np.ones_like(x)) - plunge) < 0.03 * abs(plunge)


def test_gafs_of_the_patil_wing_are_the_strips_in_3d():
    """The rigid heave/twist generalised forces of the Patil wing (A = 32) at k = 0.4 by the
    DLM and by the exact-Theodorsen strips agree within 12 % (the tip losses of A = 32): signs,
    the k conversion (k_bar = k / b_ref) and the spline's load direction."""
    m = patil_model(10)
    V, k, b = 30.0, 0.4, 0.5
    omega = k * V / b
    aero = dlm.DlmAerodynamics(m.wing, n_chord=4, n_span=32)
    Qd = 0.5 * m.flight.density * V**2 * aero.exact(0.0, k)
    node = m.wing.node_properties()
    Ma, Ca, Ka = _strip(m.flight.density, V, node["b"], node["a"], node["Cla"], node["ac"], omega)
    blocks = node["width"][:, None, None] * (-omega**2 * Ma + 1j * omega * Ca + Ka)
    nn = m.wing.n_nodes
    Qs = np.zeros((3 * nn, 3 * nn), complex)
    for i in range(nn):
        idx = [3 * i, 3 * i + 2]
        Qs[np.ix_(idx, idx)] = blocks[i]
    h, t = np.zeros(3 * nn), np.zeros(3 * nn)
    h[0::3], t[2::3] = 1.0, 1.0
    for u, w in ((h, h), (h, t), (t, h), (t, t)):
        assert abs(u @ Qd @ w - u @ Qs @ w) < 0.12 * abs(u @ Qs @ w)


def test_tables_interpolate_and_are_computed_once():
    w = flat_wing(3.0, elastic_axis=0.4, n_elements=4)
    aero = dlm.DlmAerodynamics(w, n_chord=4, n_span=8)
    for M, k in ((0.0, 0.037), (0.23, 0.61), (0.41, 1.7)):
        before = aero.evaluations
        exact = aero.exact(M, k)
        Q = aero.gaf(M, k)
        assert np.abs(Q - exact).max() < 3e-3 * np.abs(exact).max()
        assert aero.evaluations - before <= 1 + 8          # 4 k nodes x 2 Mach nodes
        n = aero.evaluations
        aero.gaf(M, k)
        assert aero.evaluations == n                       # kept: nothing computed again
    with pytest.raises(InputError, match="Mach = 0.95 is invalid for aero = 'dlm'"):
        aero.gaf(0.95, 0.1)


def test_fill_computes_the_missing_table_nodes_once_and_counts_them():
    """DlmAerodynamics.fill (the analysis's counted AICs, issue 37 item 3): each missing node
    once, in order, reported 0 ... total; nodes already in the table neither computed nor
    counted; the same values as column_node's."""
    w = flat_wing(3.0, elastic_axis=0.4, n_elements=4)
    aero = dlm.DlmAerodynamics(w, n_chord=2, n_span=4)
    aero.column_node(0.3, 2)                              # already computed
    seen = []
    nodes = [(0.3, 1), (0.3, 2), (0.35, 1), (0.3, 1), (0.3, 3)]
    assert aero.fill(nodes, lambda done, total: seen.append((done, total))) == 3
    assert seen == [(0, 3), (1, 3), (2, 3), (3, 3)]
    assert aero.evaluations == 4
    fresh = dlm.DlmAerodynamics(w, n_chord=2, n_span=4)
    for mach, ik in nodes:
        assert np.array_equal(aero.column_node(mach, ik), fresh.column_node(mach, ik))
    assert aero.evaluations == 4 and aero.fill(nodes) == 0


def test_dlm_replaces_only_the_wing_strips():
    """The p-k matrices of a wing with a flexibly mounted propeller and in-plane bending: the
    DLM changes only the wing's bending-torsion block (the propeller's Houbolt-Reed loads and
    the in-plane DOFs as the dry system has them), and no mass term."""
    m = wingtip_propeller_wing()
    m = m.with_(wing=dataclasses.replace(m.wing, EI_chordwise=5e6, aero="dlm",
                                         dlm_chordwise_panels=2, dlm_spanwise_panels=6))
    V, omega = 80.0, 20.0
    M, C, K = pk_system(m, V)(omega)
    dry = dataclasses.replace(m, wing_aero=False).second_order(np.array([V]))
    nb = 3 * (m.wing.n_nodes - 1)                          # free bending-torsion DOFs first
    assert np.array_equal(M, dry.S1[0])
    for X, D in ((C, dry.S2[0]), (K, dry.S3[0])):
        diff = X - D
        assert np.any(diff[:nb, :nb] != 0)
        assert np.all(diff[nb:, :] == 0) and np.all(diff[:, nb:] == 0)
    with pytest.raises(InputError, match="Mach = .* is invalid for aero = 'dlm'"):
        pk_system(m, 0.95 * m.flight.speed_of_sound)
    assert K_MIN > 0
