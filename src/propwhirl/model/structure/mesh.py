"""The spanwise mesh of a wing: node positions from stations and an element length.

The mesh rule (one place, used by :class:`propwhirl.model.structure.wing.Wing`):

1. The *breakpoints* are the root 0, the semi-span L and every station (positions that must be
   nodes: where a property changes, where the user wants output, every propeller installation
   — :class:`propwhirl.model.systems.PropellerWing` adds those).  Stations lie in (0, L]; a
   station within :data:`NODE_TOL` of another breakpoint is the same point (a duplicate in the
   user's list is refused).
2. The target element length is h = `max_element_length` if given, else L / `n_elements`.
3. Each interval [a, b] between breakpoints is divided into ⌈(b − a)/h⌉ equal elements (at
   least one), so no element exceeds h; with no stations the count is exactly `n_elements`.

Without stations and without a maximum length the single interval [0, L] gives
``numpy.linspace(0, L, n_elements + 1)`` itself: the uniform meshes of the thesis, bit for bit.
Elements shorter than :data:`MIN_ELEMENT_FRACTION` of the semi-span (stations too close
together) are refused: they add stiffness entries ~(L/l)³ times the others and no accuracy.
The total number of elements is bounded by :data:`propwhirl.limits.MAX_ELEMENTS`.

:func:`beam_interpolation` is the beam element's own interpolation between nodes (cubic
Hermite bending from the nodes' h and ∂h/∂y, linear torsion, eq. 7.5–7.8): the one
implementation behind the doublet-lattice spline (:func:`propwhirl.model.aerodynamics.dlm_mesh.spline`) and
the modal strips' (:func:`propwhirl.model.modal_structure.strip_interpolation`).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Sequence

import numpy as np

from propwhirl import limits
from propwhirl import validate as v

#: Two positions closer than NODE_TOL × max(1 m, L) are the same node (as
#: :func:`propwhirl.model.systems.node_at` finds a propeller's node).
NODE_TOL = 1e-6
#: Shortest element allowed, as a fraction of the semi-span (4.8 mm on a 4.8 m wing).
MIN_ELEMENT_FRACTION = 1e-3
#: Relative slack in ⌈(b − a)/h⌉, so that rounding of an interval that holds exactly k
#: elements of length h does not add one.
_COUNT_SLACK = 1e-9


@dataclass(frozen=True, eq=False)
class Mesh:
    """Node positions of a wing mesh (root node 0 at y = 0, last node at the tip).

    Parameters
    ----------
    node_y : spanwise node positions [m], strictly increasing, read-only
    breakpoints : the positions that are nodes by requirement (0, stations, L) [m]
    """

    node_y: np.ndarray
    breakpoints: tuple[float, ...]

    @property
    def n_elements(self) -> int:
        """Number of elements of the mesh."""
        return self.node_y.size - 1

    @property
    def element_length(self) -> np.ndarray:
        """Element lengths [m]."""
        return np.diff(self.node_y)

    @property
    def element_y(self) -> np.ndarray:
        """Element mid-span positions [m]."""
        return 0.5 * (self.node_y[:-1] + self.node_y[1:])

    def has_node(self, y: float) -> bool:
        """True when a node lies at y [m] (within :data:`NODE_TOL`)."""
        return bool(np.min(np.abs(self.node_y - y)) <= tolerance(self.node_y[-1]))


def tolerance(semi_span: float) -> float:
    """Distance [m] under which two spanwise positions are the same node."""
    return NODE_TOL * max(1.0, float(semi_span))


def check_station(name: str, y: float, semi_span: float, path: tuple | None = None) -> None:
    """InputError unless y [m] lies on the wing beyond the root: 0 < y ≤ semi_span."""
    tol = tolerance(semi_span)
    if not (-tol <= y <= semi_span + tol):
        raise v.fail(name, y, f"outside the wing: must be in (0, {semi_span:g}] m", "m", path)
    if y <= tol:
        raise v.fail(name, y, "the clamped root: must be > 0", "m", path)


def build(semi_span: float, n_elements: int, stations: Sequence[float] = (),
          max_element_length: float | None = None, names: Sequence[str] | None = None,
          paths: Sequence[tuple] | None = None) -> Mesh:
    """The mesh of the module's rule.

    Parameters
    ----------
    semi_span : L [m]
    n_elements : element count of the uniform mesh (L / n_elements is the target length when
        `max_element_length` is None)
    stations : positions [m] in (0, L] that must be nodes
    max_element_length : longest element [m]; None: L / n_elements
    names, paths : how errors name each station (default ``stations[i]``)

    Raises
    ------
    InputError
        a station outside (0, L], a duplicate, an element shorter than
        MIN_ELEMENT_FRACTION × L, a non-positive length, too many elements.
    """
    L = float(semi_span)
    tol = tolerance(L)
    names = list(names) if names is not None else [f"stations[{i}]" for i in range(len(stations))]
    paths = list(paths) if paths is not None else [("stations", i) for i in range(len(stations))]
    ys = [float(y) for y in stations]
    for y, name, path in zip(ys, names, paths):
        check_station(name, y, L, path)
    order = sorted(range(len(ys)), key=ys.__getitem__)
    for a, b in zip(order, order[1:]):
        if ys[b] - ys[a] <= tol:
            first, second = sorted((a, b))
            raise v.fail(names[second], ys[second], f"invalid: a duplicate of {names[first]} "
                         f"= {ys[first]:.6g} m (each station once)", "m", paths[second])
    # breakpoints: 0, the stations (one at the tip is the tip), L
    points: list[tuple[float, int | None]] = [(0.0, None)]
    points += [(ys[i], i) for i in order if ys[i] < L - tol]
    points.append((L, None))
    shortest = MIN_ELEMENT_FRACTION * L
    for (a, ia), (b, ib) in zip(points, points[1:]):
        if b - a < shortest:
            i = ib if ib is not None else ia
            raise v.fail(names[i], ys[i], f"invalid: it makes an element of {b - a:.3g} m "
                         f"between y = {a:.6g} and {b:.6g} m, shorter than the minimum "
                         f"{shortest:.3g} m ({MIN_ELEMENT_FRACTION:g} x semi_span); merge or "
                         "move the stations", "m", paths[i])
    if max_element_length is None:
        h = L / n_elements
    else:
        h = float(v.positive("max_element_length", max_element_length, "m"))
    counts = [max(1, math.ceil((b - a) / h * (1.0 - _COUNT_SLACK)))
              for (a, _), (b, _) in zip(points, points[1:])]
    total = sum(counts)
    if total > limits.MAX_ELEMENTS:
        what = (f"max_element_length = {h:g} m" if max_element_length is not None
                else f"n_elements = {n_elements}")
        raise v.InputError(f"{what} gives {total:,} elements on the {L:g} m wing: must give at "
                           f"most {limits.MAX_ELEMENTS:,} (limits.MAX_ELEMENTS)")
    pieces = [np.linspace(a, b, k + 1)[:-1] for ((a, _), (b, _)), k
              in zip(zip(points, points[1:]), counts)]
    node_y = np.concatenate(pieces + [np.array([L])])
    node_y.setflags(write=False)
    return Mesh(node_y, tuple(p for p, _ in points))


def beam_interpolation(node_y: np.ndarray, y: np.ndarray
                       ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The beam element's interpolation between nodes, as weights on the nodes' values.

    On the element [y_k, y_k+1] (length L) holding y, at t = (y − y_k)/L ∈ [0, 1]:

        h(y) = H₀₀(t) h_k + L H₁₀(t) φ_k + H₀₁(t) h_k+1 + L H₁₁(t) φ_k+1,
        α(y) = (1 − t) α_k + t α_k+1,

    with the cubic Hermite basis H₀₀ = 1 − 3t² + 2t³, H₁₀ = t − 2t² + t³, H₀₁ = 3t² − 2t³,
    H₁₁ = −t² + t³ (the bending shape functions 7.5–7.6 on ξ = 2t − 1, φ = ∂h/∂y) and the
    linear torsion shapes (7.7–7.8).  A point on a node takes the element starting there (the
    last node: the last element); t is clipped to [0, 1] (a point a rounding error beyond the
    end nodes: the end node's value).

    Parameters
    ----------
    node_y : numpy.ndarray
        The nodes' spanwise positions [m] (n_nodes,), strictly increasing, at least two.
    y : numpy.ndarray
        The points' spanwise positions [m] (n,).

    Returns
    -------
    H, P, T : numpy.ndarray
        Weights (n, n_nodes) [-, m, -]: h(y) = H @ h_i + P @ φ_i [m] for the node values h_i
        [m] and slopes φ_i [rad], and α(y) = T @ α_i [rad].
    """
    node_y = np.asarray(node_y, dtype=float)
    y = np.asarray(y, dtype=float)
    k = np.clip(np.searchsorted(node_y, y, side="right") - 1, 0, node_y.size - 2)
    L = node_y[k + 1] - node_y[k]
    t = np.clip((y - node_y[k]) / L, 0.0, 1.0)
    rows = np.arange(y.size)
    H = np.zeros((y.size, node_y.size))
    P = np.zeros((y.size, node_y.size))
    T = np.zeros((y.size, node_y.size))
    H[rows, k], P[rows, k] = 1 - 3 * t**2 + 2 * t**3, (t - 2 * t**2 + t**3) * L
    H[rows, k + 1], P[rows, k + 1] = 3 * t**2 - 2 * t**3, (-t**2 + t**3) * L
    T[rows, k], T[rows, k + 1] = 1 - t, t
    return H, P, T
