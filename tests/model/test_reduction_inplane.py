"""model.reduction on a wing that bends in its plane: the first chordwise-dominated in-vacuo
mode enters the reference frequency, so the cut-off covers the chord mode of whirl flutter;
without in-plane bending the basis is unchanged."""
from dataclasses import replace

import numpy as np

from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
from propwhirl.model.reduction import _reference_frequency, modal_basis

SPEEDS = np.arange(1.0, 351.0, 10.0)


def _modes(model):
    quiet = model.with_(rotating=False).without_aerodynamics()
    S = quiet.second_order_blocks(SPEEDS[:1]).dense()
    import scipy.linalg as sla
    w2, X = sla.eigh(S.S3[0], S.S1[0])
    return np.sqrt(np.abs(w2)) / (2 * np.pi), X, S.S1[0]


def _chordwise_hz(model):
    f, X, M = _modes(model)
    groups = model.dof_map().groups()
    e = np.real(X * (M @ X))
    e = e / e.sum(axis=0)
    share = {g: e[np.asarray(ix, dtype=int)].sum(axis=0) for g, ix in groups.items()}
    zero = np.zeros(f.size)
    chord = share["chordwise"]
    others = np.maximum.reduce([share.get(g, zero) for g in ("bending", "torsion", "pitch", "yaw")])
    return f[chord > others]


def test_the_first_chordwise_mode_is_a_reference_candidate():
    m0 = wingtip_propeller_wing()
    # a stiff in-plane rigidity: the first chord mode (27.3 Hz) above every other candidate
    # (the second bending mode, 17.7 Hz, without it)
    m = replace(m0, wing=replace(m0.wing, EI_chordwise=200.0 * m0.wing.EI))
    first_chord = _chordwise_hz(m)[0]
    f, X, M = _modes(m)
    assert _reference_frequency(m, f, X, M) >= first_chord
    b = modal_basis(m, SPEEDS)
    assert b.reference_hz >= first_chord and b.cutoff_hz >= 3 * first_chord


def test_without_inplane_bending_the_basis_is_unchanged():
    b = modal_basis(wingtip_propeller_wing(), SPEEDS)
    assert round(b.reference_hz, 2) == 17.74 and b.n_modes == 7 and b.r == 11
