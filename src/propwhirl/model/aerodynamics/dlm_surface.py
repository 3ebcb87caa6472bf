"""What the doublet lattice needs of a model: its lifting surface and the spline from its
degrees of freedom to the panels (issue 34 item 3).

A :class:`DlmSurface` is the one thing the doublet-lattice GAFs
(:class:`~propwhirl.model.aerodynamics.dlm.DlmAerodynamics`), their tables, the Roger fits
and the p-k read of a model, whatever its structure:

* its :class:`~propwhirl.model.aerodynamics.planform.Planform` (the panels);
* its spline: for panel points (n, 3) [m], (Z, S) (n, n_dof): Z q the displacement of each
  point normal to the surface, positive down [m], and S q its streamwise slope ∂z/∂x [rad],
  for the model's DOFs q (the beam's [h_i, φ_i, α_i],
  :func:`~propwhirl.model.aerodynamics.dlm_mesh.spline`; a modal model's modal coordinates,
  :func:`propwhirl.model.modal_structure.axis_spline` composed with the modes);
* the DOFs the panels load (``keep``: the first ``keep.size`` DOFs of the model's
  second-order system, in that order), their labels and wing nodes (the Roger lag states'
  names);
* the reference semichord b_ref [m] of k = ω b_ref / V (the root semichord) and the Mach
  setting ``dlm_mach`` ("speed" or a fixed number);
* ``key``: what its GAFs depend on (two surfaces with one key share their tables,
  :class:`~propwhirl.model.aerodynamics.dlm.DlmTables`).

:func:`surface_of` gives a model's (its own ``dlm_surface()``, or its beam wing's,
:meth:`DlmSurface.from_wing`, the same panels, spline and numbers as the beam doublet lattice
always had).
"""
from __future__ import annotations

import functools
from collections.abc import Callable

import numpy as np

from propwhirl.model.aerodynamics.dlm_mesh import spline
from propwhirl.model.aerodynamics.planform import Planform
from propwhirl.model.structure.assembly import free_dofs, wing_dof_labels
from propwhirl.model.structure.wing import panel_counts


class DlmSurface:
    """A model's lifting surface and spline (module docstring); built lazily (the planform,
    key and labels on first use) so that asking for one costs nothing until its panels are
    needed."""

    def __init__(self, planform: Callable[[], Planform] | Planform,
                 spline: Callable[[np.ndarray], tuple[np.ndarray, np.ndarray]], n_dof: int,
                 keep: np.ndarray, b_ref: Callable[[], float] | float, dlm_mach,
                 key: Callable[[], tuple] | tuple, labels: Callable[[], tuple] | tuple,
                 nodes: tuple[int, ...] | None = None):
        self._planform, self._b_ref, self._key, self._labels = planform, b_ref, key, labels
        self.spline = spline
        self.n_dof = int(n_dof)
        self.keep = np.asarray(keep, dtype=int)
        self.keep.flags.writeable = False
        self.dlm_mach = dlm_mach
        self._nodes = nodes

    @staticmethod
    def _value(x):
        return x() if callable(x) else x

    @functools.cached_property
    def planform(self) -> Planform:
        """The :class:`~propwhirl.model.aerodynamics.planform.Planform`."""
        return self._value(self._planform)

    @functools.cached_property
    def b_ref(self) -> float:
        """The reference semichord [m]."""
        return float(self._value(self._b_ref))

    @functools.cached_property
    def key(self) -> tuple:
        """What its GAFs depend on."""
        return self._value(self._key)

    @functools.cached_property
    def labels(self) -> tuple[str, ...]:
        """Labels of the loaded DOFs (``keep``)."""
        return tuple(self._value(self._labels))

    @property
    def nodes(self) -> tuple[int, ...]:
        """The wing node of each loaded DOF (-1: none, a mode)."""
        return (-1,) * self.keep.size if self._nodes is None else self._nodes

    @classmethod
    def from_wing(cls, wing, n_chord: int | None = None,
                  n_span: int | None = None) -> "DlmSurface":
        """A beam :class:`~propwhirl.model.structure.wing.Wing`'s: its planform
        (:meth:`Planform.from_wing`, counts as given or the wing's), the beam's own spline
        on its 3 n_nodes bending–torsion DOFs, the free ones loaded (the root's removed),
        b_ref its root semichord, its ``dlm_mach``."""
        nn = wing.n_nodes
        keep = free_dofs(nn)

        def key() -> tuple:
            node = wing.node_properties()
            return ("beam", tuple(np.round(node["y"], 12)), tuple(np.round(node["b"], 12)),
                    tuple(np.round(node["a"], 12)), panel_counts(wing, n_chord, n_span))

        return cls(lambda: Planform.from_wing(wing, n_chord, n_span),
                   functools.partial(spline, wing), 3 * nn, keep,
                   lambda: wing.node_properties()["b"][0], wing.dlm_mach, key,
                   lambda: np.asarray(wing_dof_labels(nn), dtype=object)[keep],
                   tuple(int(i // 3) for i in keep))


def surface_of(x) -> DlmSurface:
    """The :class:`DlmSurface` of ``x``: a DlmSurface itself, a model's own
    (``x.dlm_surface()``), a beam model's wing's, or a beam
    :class:`~propwhirl.model.structure.wing.Wing`'s (:meth:`DlmSurface.from_wing`)."""
    if isinstance(x, DlmSurface):
        return x
    own = getattr(x, "dlm_surface", None)
    if callable(own):
        return own()
    return DlmSurface.from_wing(getattr(x, "wing", x))
