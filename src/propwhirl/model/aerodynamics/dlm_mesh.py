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

from dataclasses import dataclass

import numpy as np

from propwhirl import limits, validate as v
from propwhirl.model.structure.mesh import beam_interpolation
# the panel counts are the wing's own fields, checked with it (model/structure/wing.py)
from propwhirl.model.structure.wing import (DEFAULT_CHORDWISE, MAX_ASPECT,  # noqa: F401
                                           MAX_PANELS, panel_counts)

#: the reduced-frequency guideline: panel length < GUIDELINE · V / f (V [m/s], f [Hz])
GUIDELINE = 0.08


@dataclass(frozen=True)
class PanelMesh:
    """The panels of a half-wing (arrays in metres, x aft from the elastic axis, y spanwise,
    z up; panel p = i_span · n_chord + i_chord).

    corners (n, 4, 3): leading-edge inboard, trailing-edge inboard, trailing-edge outboard,
    leading-edge outboard corners; n_chord, n_span: the counts.
    """

    corners: np.ndarray
    n_chord: int
    n_span: int

    @property
    def n(self) -> int:
        """Number of panels."""
        return self.corners.shape[0]

    def _edges(self):
        p1, p2, p3, p4 = (self.corners[:, i] for i in range(4))
        return p1, p2 - p1, p3 - p4, p4 - p1, p3 - p2

    @property
    def length(self) -> np.ndarray:
        """Chordwise length of each panel (mean of its side edges) [m]."""
        _, l1, l2, _, _ = self._edges()
        return 0.5 * (l1[:, 0] + l2[:, 0])

    @property
    def width(self) -> np.ndarray:
        """Spanwise width of each panel [m]."""
        _, _, _, b1, b2 = self._edges()
        return 0.5 * (b1[:, 1] + b2[:, 1])

    @property
    def area(self) -> np.ndarray:
        """Area of each panel [m²] (trapezoid)."""
        _, l1, l2, b1, b2 = self._edges()
        return np.linalg.norm(np.cross(0.5 * (l1 + l2), 0.5 * (b1 + b2)), axis=1)

    def points(self, fraction: float) -> np.ndarray:
        """Points (n, 3) at ``fraction`` of each panel's chord, mid-width [m]: 0.25 the
        doublet line (force point), 0.75 the collocation point."""
        p1, l1, l2, b1, _ = self._edges()
        return p1 + fraction * 0.5 * (l1 + l2) + 0.5 * b1

    def mirrored(self) -> "PanelMesh":
        """The panels of both half-wings: the mirror image in the root plane y = 0 (panel p of
        the other half at index p), then these; every panel still defined from left to right
        (its corners reordered), so every normal points up."""
        m = self.corners[:, [3, 2, 1, 0]] * np.array([1.0, -1.0, 1.0])
        return PanelMesh(np.concatenate([m, self.corners]), self.n_chord, 2 * self.n_span)

    def aerogrid(self) -> dict:
        """The panels in PanelAero's ``aerogrid`` form (its DLM and VLM read l, A, N,
        offset_l / _k / _j at 1/4, 1/2, 3/4 chord, offset_P1 / _P3 the doublet line's ends)."""
        p1, l1, l2, b1, _ = self._edges()
        p4 = self.corners[:, 3]
        normal = np.cross(l1, b1)
        normal /= np.linalg.norm(normal, axis=1)[:, None]
        return {"l": self.length, "A": self.area, "N": normal,
                "offset_l": self.points(0.25), "offset_k": self.points(0.5),
                "offset_j": self.points(0.75), "offset_P1": p1 + 0.25 * l1,
                "offset_P3": p4 + 0.25 * l2, "n": self.n}


def check_memory(wing, n_chord: int | None = None, n_span: int | None = None) -> None:
    """InputError, before any panel is built, when one AIC of the wing's panels
    (:func:`panel_counts`; ``wing`` may also be a model, its doublet-lattice planform's counts)
    would exceed the memory limit (:func:`propwhirl.limits.check_panels`, naming the counts
    that fit)."""
    if n_chord is None and n_span is None:
        from propwhirl.model.aerodynamics.dlm_surface import surface_of
        limits.check_panels(*surface_of(wing).planform.counts())
        return
    limits.check_panels(*panel_counts(wing, n_chord, n_span))


def panel_mesh(wing, n_chord: int | None = None, n_span: int | None = None) -> PanelMesh:
    """The DLM panels of ``wing``'s half planform (counts: :func:`panel_counts`; refused when
    their AIC would exceed the memory limit, :func:`check_memory`): the panels of its
    :meth:`~propwhirl.model.aerodynamics.planform.Planform.from_wing`, one case of any
    planform's."""
    from propwhirl.model.aerodynamics.planform import Planform
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
