"""The doublet-lattice planform independent of the beam wing (issue 34 item 3):
propwhirl.model.aerodynamics.planform."""
import numpy as np
import pytest

from propwhirl.model.aerodynamics.dlm_mesh import panel_mesh
from propwhirl.model.aerodynamics.planform import Planform
from propwhirl.model.structure.wing import MAX_ASPECT, Wing
from propwhirl.validate import InputError


def wing(**kw):
    base = dict(semi_span=6.0, mass_per_length=10.0, EI=1e5, GJ=1e5, radius_of_gyration=0.25,
                root_chord=2.0, tip_chord=1.0, elastic_axis=[0.3, 0.35, 0.4, 0.32, 0.45],
                n_elements=5)
    base.update(kw)
    return Wing(**base)


@pytest.mark.parametrize("nc, ns", [(4, None), (3, 7), (8, 13)])
def test_the_beam_wing_is_one_planform_bit_for_bit(nc, ns):
    """The beam DLM's panels (the formula it always had: leading and trailing edges
    -(1 + a) b, (1 - a) b with b, a linear between nodes, equal strips in y) are the panels
    of Planform.from_wing, to the last bit (an elastic axis varying along the span too)."""
    w = wing()
    m = Planform.from_wing(w, nc, ns).mesh()
    assert m is not None and panel_mesh(w, nc, ns).n == m.n
    node = w.node_properties()
    n_span = m.n_span
    ys = np.linspace(0.0, w.semi_span, n_span + 1)
    b, a = np.interp(ys, node["y"], node["b"]), np.interp(ys, node["y"], node["a"])
    le, te = -(1.0 + a) * b, (1.0 - a) * b
    x = le[:, None] + (te - le)[:, None] * np.linspace(0.0, 1.0, m.n_chord + 1)[None, :]
    assert np.array_equal(m.corners[:, 0, 0], x[:-1, :-1].ravel())
    assert np.array_equal(m.corners[:, 2, 0], x[1:, 1:].ravel())
    assert np.array_equal(m.corners[:, 0, 1], np.repeat(ys[:-1], m.n_chord))
    assert not np.any(m.corners[:, :, 2])


def test_a_swept_tapered_dihedral_caero1():
    """Any leading edge: the panels cover the trapezoid, their corners on the straight
    leading edge, the chords streamwise, the default spanwise count keeps the aspect ratio."""
    p = Planform.caero1((1.0, 0.5, 0.0), (3.0, 6.5, 0.6), 2.0, 1.0, 4)
    m = p.mesh()
    nc, ns = p.counts()
    assert (m.n_chord, m.n_span) == (nc, ns) == (4, int(np.ceil(6.0 * 4 / (MAX_ASPECT * 1.0))))
    proj = np.cross(m.corners[:, 2] - m.corners[:, 0], m.corners[:, 3] - m.corners[:, 1])
    assert 0.5 * np.abs(proj[:, 2]).sum() == pytest.approx(6.0 * 1.5, rel=1e-12)
    le = m.corners[:: nc, 0]                          # inboard leading-edge corners
    assert np.allclose(le[:, 0], 1.0 + (le[:, 1] - 0.5) / 3.0)
    assert np.allclose(le[:, 2], 0.1 * (le[:, 1] - 0.5))
    assert np.max(m.width / m.length) <= MAX_ASPECT + 1e-12
    assert p.b_ref == 1.0


@pytest.mark.parametrize("args, match", [
    (dict(leading_edge=[[0, 0, 0]], chord=[1.0]), "leading_edge has 1 stations"),
    (dict(leading_edge=[[0, -1, 0], [0, 2, 0]], chord=[1, 1]), r"leading_edge\[0\] y = -1"),
    (dict(leading_edge=[[0, 1, 0], [0, 1, 0]], chord=[1, 1]), r"leading_edge\[1\] y = 1 m"),
    (dict(leading_edge=[[0, 0, 0], [0, 2, 0]], chord=[1, 0]), r"chord\[1\] = 0 m"),
    (dict(leading_edge=[[0, 0], [0, 2]], chord=[1, 1]), "leading_edge = .* must be real"),
    (dict(leading_edge=[[0, 0, np.nan], [0, 2, 0]], chord=[1, 1]), r"leading_edge\[0, 2\]"),
    (dict(leading_edge="wing", chord=[1, 1]), "leading_edge = 'wing' is invalid"),
    (dict(leading_edge=[[0, 0, 0], [0, 2, 0]], chord=[1, 1], chordwise_panels=0),
     "chordwise_panels"),
    (dict(leading_edge=[[0, 0, 0], [0, 2, 0]], chord=[1, 1], chordwise_panels=40,
          spanwise_panels=60), "panels is invalid: must be at most"),
])
def test_wrong_planforms_are_one_line_errors_naming_the_key(args, match):
    with pytest.raises(InputError, match=match) as e:
        Planform(**args)
    assert "\n" not in str(e.value)
