"""A lifting surface's planform for the doublet lattice, independent of the structure
(issue 34 item 3).

:class:`Planform` is what NASTRAN's CAERO1 card gives: the leading-edge corners (x, y, z)
[m] and the chords [m] at the root and the tip (the chord streamwise, along +x), and the
chordwise and spanwise panel counts — generalised to any number of spanwise *stations* (two
for a CAERO1, :meth:`Planform.caero1`): between stations the leading edge (x, z) and the
chord are linear in y.  The leading edge may lie anywhere: sweep (x varying with y), taper,
dihedral (z varying with y) and a root away from the plane of symmetry (y₀ > 0) are all
planforms.  The frame is the wing frame of the structure it is splined to (x aft along the
flow, y spanwise outboard, z up); the plane y = 0 is the plane of symmetry (the other
half-wing mirrored, :meth:`~propwhirl.model.aerodynamics.dlm_mesh.PanelMesh.mirrored`).

**Panels** (:meth:`Planform.mesh`): the span y₀ … y_N divided into ``spanwise_panels``
equal strips in y, each local chord into ``chordwise_panels`` equal divisions (NASTRAN's
equal divisions without LSPAN/LCHORD).  Defaults: 8 along the chord
(:data:`~propwhirl.model.structure.wing.DEFAULT_CHORDWISE`) and, spanwise, the fewest strips
no wider than :data:`~propwhirl.model.structure.wing.MAX_ASPECT` = 2 times the shortest
panel length (:meth:`Planform.counts`): the beam wing's own defaults.

**The beam wing's planform** (:meth:`Planform.from_wing`): the stations are the edges of
its panel strips, each with the wing's leading and trailing edges there, −(1 + a) b and
(1 − a) b aft of the elastic axis (b, a linear between the wing's nodes), z = 0.  Its panels
are therefore, bit for bit, the panels the beam doublet lattice always had: the beam DLM is
one case of this planform (``tests/model/test_planform.py``).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from propwhirl import limits
from propwhirl import validate as v
from propwhirl.model.structure.wing import (DEFAULT_CHORDWISE, MAX_ASPECT, MAX_PANELS,
                                           panel_counts)

#: most spanwise stations of a planform
MAX_STATIONS = 1000


@dataclass(frozen=True)
class PanelMesh:
    """The panels of a half-wing (arrays in metres in the wing frame: x aft, y spanwise, z up; panel p = i_span · n_chord + i_chord).

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


@dataclass(frozen=True, eq=False)
class Planform:
    """A half-wing's lifting surface for the doublet lattice (module docstring).

    Parameters
    ----------
    leading_edge : ndarray
        (n_stations, 3) the leading edge (x, y, z) [m] at each spanwise station, y strictly
        increasing and >= 0 (the plane y = 0 is the plane of symmetry); at least two
        stations (a CAERO1's root and tip corners 1 and 4).
    chord : ndarray
        (n_stations,) the streamwise chord [m] at each station, > 0.
    chordwise_panels : int
        Panels along each chord (>= 1; default 8, the beam wing's).
    spanwise_panels : int or None
        Equal strips along the span (>= 1); None: the fewest with every panel's width at
        most :data:`~propwhirl.model.structure.wing.MAX_ASPECT` times the shortest panel
        length.
    source : str
        What it is called in error messages (the key of a model file: ``dlm_planform``).

    Examples
    --------
    A swept, tapered CAERO1 with 4 x 6 panels:

    >>> from propwhirl.model.aerodynamics.planform import Planform
    >>> p = Planform.caero1((0.0, 0.0, 0.0), (1.0, 5.0, 0.0), 2.0, 1.0, 4, 6)
    >>> m = p.mesh()
    >>> m.n, round(float(m.area.sum()), 6)             # 5 m x (2 + 1)/2 m
    (24, 7.5)
    >>> p.counts(), p.b_ref                            # b_ref: the root semichord [m]
    ((4, 6), 1.0)
    """

    leading_edge: np.ndarray
    chord: np.ndarray
    chordwise_panels: int = DEFAULT_CHORDWISE
    spanwise_panels: int | None = None
    source: str = "dlm_planform"

    def __post_init__(self) -> None:
        src = self.source if isinstance(self.source, str) else "dlm_planform"
        object.__setattr__(self, "source", src)
        le = v.shaped_array(src, "leading_edge", self.leading_edge, (-1, 3), unit="m")
        n = le.shape[0]
        if not 2 <= n <= MAX_STATIONS:
            raise v.InputError(f"{src}: leading_edge has {n} stations: give 2 to "
                               f"{MAX_STATIONS} (a CAERO1: the root and the tip)")
        c = v.shaped_array(src, "chord", self.chord, (n,), unit="m")
        y = le[:, 1]
        if y[0] < 0:
            raise v.InputError(f"{src}: leading_edge[0] y = {y[0]:.6g} m is invalid: must be "
                               ">= 0 (the plane y = 0 is the plane of symmetry)")
        bad = np.flatnonzero(np.diff(y) <= 0)
        if bad.size:
            i = int(bad[0]) + 1
            raise v.InputError(f"{src}: leading_edge[{i}] y = {y[i]:.6g} m is invalid: the "
                               "stations' y must increase from root to tip")
        bad = np.flatnonzero(c <= 0)
        if bad.size:
            i = int(bad[0])
            raise v.InputError(f"{src}: chord[{i}] = {c[i]:.6g} m is invalid: must be > 0")
        object.__setattr__(self, "leading_edge", le)
        object.__setattr__(self, "chord", c)
        v.integer_at_least("chordwise_panels", self.chordwise_panels, 1)
        if self.spanwise_panels is not None:
            v.integer_at_least("spanwise_panels", self.spanwise_panels, 1)
        nc, ns = self.counts()
        if nc * ns > MAX_PANELS:
            raise v.InputError(
                f"{src}: chordwise_panels x spanwise_panels = {nc} x {ns} = {nc * ns} panels "
                f"is invalid: must be at most {MAX_PANELS} (give fewer panels, or "
                "spanwise_panels explicitly)")

    # ------------------------------------------------------------------ constructors
    @classmethod
    def caero1(cls, root_leading_edge, tip_leading_edge, root_chord: float, tip_chord: float,
               chordwise_panels: int = DEFAULT_CHORDWISE, spanwise_panels: int | None = None,
               source: str = "dlm_planform") -> "Planform":
        """NASTRAN's CAERO1: the leading-edge corners (x, y, z) [m] at the root (point 1) and
        the tip (point 4), the streamwise chords [m] there (X12, X43) and the panel counts
        (NSPAN, NCHORD)."""
        return cls([root_leading_edge, tip_leading_edge], [root_chord, tip_chord],
                   chordwise_panels, spanwise_panels, source)

    @classmethod
    def from_wing(cls, wing, n_chord: int | None = None,
                  n_span: int | None = None) -> "Planform":
        """The planform of a beam :class:`~propwhirl.model.structure.wing.Wing` as its doublet
        lattice has always had it (module docstring): stations at its panel strips' edges
        (counts :func:`~propwhirl.model.structure.wing.panel_counts`: its
        ``dlm_chordwise_panels``, ``dlm_spanwise_panels`` or the defaults), the elastic axis
        at x = 0."""
        n_chord, n_span = panel_counts(wing, n_chord, n_span)
        ys = np.linspace(0.0, wing.semi_span, n_span + 1)
        node = wing.node_properties()
        b = np.interp(ys, node["y"], node["b"])
        a = np.interp(ys, node["y"], node["a"])
        le, te = -(1.0 + a) * b, (1.0 - a) * b
        return cls(np.stack([le, ys, np.zeros_like(ys)], axis=1), te - le, n_chord, n_span,
                   f"planform of wing {getattr(wing, 'name', '')}".rstrip())

    # ------------------------------------------------------------------ what it is
    @property
    def y(self) -> np.ndarray:
        """The stations' y [m]."""
        return self.leading_edge[:, 1]

    @property
    def span(self) -> float:
        """y_N − y₀ [m]."""
        return float(self.y[-1] - self.y[0])

    @property
    def b_ref(self) -> float:
        """The root semichord [m] (the reduced frequency's k = ω b_ref / V)."""
        return float(0.5 * self.chord[0])

    def counts(self) -> tuple[int, int]:
        """(chordwise, spanwise) panel counts, the spanwise default resolved (class
        docstring)."""
        nc = int(self.chordwise_panels)
        if self.spanwise_panels is not None:
            return nc, int(self.spanwise_panels)
        c_min = float(np.min(self.chord))
        return nc, max(1, int(np.ceil(self.span * nc / (MAX_ASPECT * c_min) - 1e-9)))

    def key(self) -> tuple:
        """What its panels depend on (two planforms with the same key have the same panels)."""
        return (self.leading_edge.tobytes(), self.chord.tobytes(), self.counts())

    def mesh(self):
        """The panels (:class:`PanelMesh`, panel
        p = i_span · n_chord + i_chord; module docstring); refused before any is built when
        one AIC of them would exceed the memory limit
        (:func:`propwhirl.limits.check_panels`)."""
        n_chord, n_span = self.counts()
        limits.check_panels(n_chord, n_span)
        y_st = self.y
        ys = np.linspace(y_st[0], y_st[-1], n_span + 1)
        le_x = np.interp(ys, y_st, self.leading_edge[:, 0])
        le_z = np.interp(ys, y_st, self.leading_edge[:, 2])
        c = np.interp(ys, y_st, self.chord)
        f = np.linspace(0.0, 1.0, n_chord + 1)
        x = le_x[:, None] + c[:, None] * f[None, :]                # (n_span + 1, n_chord + 1)
        i, j = np.meshgrid(np.arange(n_span), np.arange(n_chord), indexing="ij")
        i, j = i.ravel(), j.ravel()

        def corner(di, dj):
            return np.stack([x[i + di, j + dj], ys[i + di], le_z[i + di]], axis=1)

        corners = np.stack([corner(0, 0), corner(0, 1), corner(1, 1), corner(1, 0)], axis=1)
        return PanelMesh(corners, n_chord, n_span)
