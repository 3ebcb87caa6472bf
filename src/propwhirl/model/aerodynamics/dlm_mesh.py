"""Doublet-lattice panels of a wing's planform and the spline from the beam to them (issue 23).

**Geometry.**  The wing is the straight cantilever of :class:`~propwhirl.model.structure.wing.Wing`: its
elastic axis is the y axis (spanwise, root y = 0 to tip y = semi_span), x points aft along
the flow, z up.  The planform at y has the chord c(y) = 2 b(y) and the elastic axis at
a(y) b(y) aft of mid-chord, so the leading edge is at x = −(1 + a) b and the trailing edge at
x = (1 − a) b; b and a are interpolated linearly between the wing's nodes
(:meth:`~propwhirl.model.structure.wing.Wing.node_properties`; a linear taper is exact).  The beam is
straight and flat: the panels have no sweep of the elastic axis and no dihedral (a tapered
planform sweeps the leading and trailing edges, which the DLM takes as it is).  The root
y = 0 is a plane of symmetry (the other half-wing mirrored: a semi-span wing on a wall or a
symmetric fuselage), so the aspect ratio of a rectangular wing is 2 semi_span / c.

**Panels.**  ``n_chord`` equal divisions of the local chord times ``n_span`` equal spanwise
strips; each panel's doublet line lies at 1/4 of its chord (where its force acts) and its
collocation point at 3/4 of its chord, at mid-width.  The defaults: 8 panels along the chord
(:data:`DEFAULT_CHORDWISE`) and the fewest strips whose width is at most
:data:`MAX_ASPECT` = 2 times the shortest panel length (:func:`panel_counts`; the usual
limit is 4, too coarse for the steady lift of a low-aspect-ratio wing).  The usual guideline for the reduced frequency: panel length Δx < 0.08 V/f at the highest frequency f
[Hz] of interest (:data:`GUIDELINE`, :func:`guideline_note`; about 12 panels per wavelength).

**Spline** (:func:`spline`): the wing's own finite-element interpolation, evaluated at a panel
point (x, y): the plunge h(y) (positive down) is the cubic Hermite interpolation of the node
values h_i and slopes φ_i = ∂h/∂y (the beam element's bending shape functions, 7.5–7.6), the
twist α(y) the linear one of the α_i (its torsion shapes, 7.7–7.8), and the chord is rigid:
the displacement (positive down) z(x, y) = h(y) + x α(y) (7.1) and its chordwise slope
∂z/∂x = α(y).  It is exact for every displacement the beam model itself represents (the
spline adds no error beyond the structural model's: the beam's own shape functions are the
interpolation, not a fit), and the only approximation is the rigid chord.  In-plane motion
(v, χ: displacement in the wing's plane) gives no normal wash on a flat lifting surface to
first order, so its spline columns are zero.
"""
from __future__ import annotations

import numpy as np

from propwhirl import limits, validate as v
from propwhirl.model.aerodynamics.planform import PanelMesh, Planform  # noqa: F401
from propwhirl.model.structure.mesh import beam_interpolation
# the panel counts are the wing's own fields, checked with it (model/structure/wing.py)
from propwhirl.model.structure.wing import (DEFAULT_CHORDWISE, MAX_ASPECT,  # noqa: F401
                                           MAX_PANELS, panel_counts)

#: the reduced-frequency guideline: panel length < GUIDELINE · V / f (V [m/s], f [Hz])
GUIDELINE = 0.08


def check_memory(wing, n_chord: int | None = None, n_span: int | None = None) -> None:
    """InputError, before any panel is built, when one AIC of the wing's panels
    (:func:`panel_counts`) would exceed the memory limit (:func:`propwhirl.limits.check_panels`,
    naming the counts that fit)."""
    limits.check_panels(*panel_counts(wing, n_chord, n_span))


def panel_mesh(wing, n_chord: int | None = None, n_span: int | None = None) -> PanelMesh:
    """The DLM panels of ``wing``'s half planform (counts: :func:`panel_counts`; refused when
    their AIC would exceed the memory limit, :func:`check_memory`): the panels of its
    :meth:`~propwhirl.model.aerodynamics.planform.Planform.from_wing`, one case of any
    planform's."""
    return Planform.from_wing(wing, n_chord, n_span).mesh()


def guideline_note(mesh: PanelMesh, V: float, f_hz: float) -> str | None:
    """A one-line note when the longest panel breaks the guideline Δx < 0.08 V/f at airspeed
    V [m/s] and frequency f [Hz] (:data:`GUIDELINE`), else None."""
    dx = float(np.max(mesh.length))
    limit = GUIDELINE * V / f_hz if f_hz > 0 else np.inf
    if dx < limit:
        return None
    return (f"DLM: panel length {dx:.3g} m exceeds the guideline 0.08 V/f = {limit:.3g} m at "
            f"V = {V:.4g} m/s, f = {f_hz:.4g} Hz: give more dlm_chordwise_panels (or read the "
            "results at this speed as coarse)")


def spline(wing, points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The beam-to-panel spline at ``points`` (n, 3) [m]: (Z, S), both (n, 3 n_nodes) over the
    wing's bending–torsion DOFs [h_i, φ_i, α_i]: Z q is the displacement, positive down, of
    each point (z = h(y) + x α(y), eq. 7.1) and S q its chordwise slope ∂z/∂x = α(y), with h
    the cubic Hermite interpolation of (h_i, φ_i) and α the linear one of α_i (the beam
    element's shape functions, 7.5–7.8: :func:`~propwhirl.model.structure.mesh.beam_interpolation`).
    Points must lie in [0, semi_span]."""
    ys = wing.node_y
    x, y = points[:, 0], points[:, 1]
    if np.any(y < ys[0] - 1e-9) or np.any(y > ys[-1] + 1e-9):
        raise ValueError("spline: a point lies outside the wing's span")
    nn = ys.size
    Hh, Hp, A = beam_interpolation(ys, y)                          # (n, nn) each
    Z = np.zeros((y.size, 3 * nn))
    S = np.zeros((y.size, 3 * nn))
    Z[:, 0::3], Z[:, 1::3], Z[:, 2::3] = Hh, Hp, x[:, None] * A
    S[:, 2::3] = A
    return Z, S
