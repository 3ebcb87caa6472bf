"""Plots: V-g-f diagrams, Campbell diagrams, mode shapes and their animation, time histories.

Every function returns a matplotlib Figure (a :class:`~propwhirl.app.plots.canvas.PlotFigure`,
which Jupyter displays inline without magics) and, given ``path``, also writes it (PNG by the
suffix).  Matplotlib is optional: ``pip install propwhirl[plots]``.  Propellers are numbered
from 1 in every figure.

* :func:`vgf` — ζ (eq. 5.5) and f [Hz] against airspeed of the modes that matter, on a fine
  grid given the model, instabilities marked and annotated, the unstable half shaded
  (:mod:`~propwhirl.app.plots.vgf_plot`);
* :func:`campbell` / :func:`campbell_diagram` — tracked frequencies against propeller speed,
  families coloured, 1P and 2P lines per propeller speed
  (:mod:`~propwhirl.app.plots.campbell_plot`);
* :func:`mode_shape` / :func:`event_mode_shape` — the wing's h and α along the span and one
  θ–ψ orbit per propeller in a grid (:mod:`~propwhirl.app.plots.mode_plot`);
* :func:`animate_mode` / :func:`animate_event` — a GIF of a mode over one cycle
  (:mod:`~propwhirl.app.plots.animation`);
* :func:`time_history` — θ(t), ψ(t) and the θ–ψ path (:mod:`~propwhirl.app.plots.time_plot`);
* :func:`critical_map` / :func:`critical_sweep` — the critical speed over two parameters
  (filled contours, the critical kind, the design point) or one
  (:mod:`~propwhirl.app.plots.map_plot`);
* :func:`boundary_plot` / :func:`clearance_plot` — traced stability boundaries over a grid
  map, clearance margins (:mod:`~propwhirl.app.plots.boundary_plot`);
* :func:`spanwise_sensitivity` — where along the span EI, GJ or mass raise the critical speed
  (:mod:`~propwhirl.app.plots.sensitivity_plot`).
"""
from propwhirl.app.plots.animation import animate_event, animate_mode
from propwhirl.app.plots.boundary_plot import (FAIL_COLOUR, PASS_COLOUR, boundary_plot,
                                              clearance_plot)
from propwhirl.app.plots.campbell_plot import campbell, campbell_diagram
from propwhirl.app.plots.canvas import (DIVERGENCE_COLOUR, FLUTTER_COLOUR, INSTALL_HINT, save)
from propwhirl.app.plots.map_plot import critical_map, critical_sweep
from propwhirl.app.plots.mode_plot import event_eigenvector, event_mode_shape, mode_shape
from propwhirl.app.plots.sensitivity_plot import spanwise_sensitivity
from propwhirl.app.plots.time_plot import time_history
from propwhirl.app.plots.vgf_plot import (DAMPING_MARGIN, VgfRequirements, fine_sweep,
                                          select_modes, vgf)

__all__ = [
    "vgf", "VgfRequirements", "select_modes", "fine_sweep", "campbell", "campbell_diagram", "mode_shape",
    "event_mode_shape", "event_eigenvector", "animate_mode", "animate_event", "time_history",
    "critical_map", "critical_sweep", "boundary_plot", "clearance_plot", "spanwise_sensitivity",
    "save",
    "FLUTTER_COLOUR", "DIVERGENCE_COLOUR", "INSTALL_HINT", "DAMPING_MARGIN", "PASS_COLOUR",
    "FAIL_COLOUR",
]
