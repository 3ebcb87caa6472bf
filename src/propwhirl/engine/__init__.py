"""The model-agnostic stability engine (thesis chapter 5): eigen-analysis of ẋ = A(V) x along V.

A model supplies

* ``state_matrix(V) -> A`` — a callable, vectorised over a 1-D array of airspeeds V [m/s],
  returning the real first-order state matrices, shape ``(len(V), n, n)`` (eq. 5.3/5.4, 6.18,
  7.59, C.63, D.27);
* the state labels (``n`` strings) and which states are displacements: ``n_dof`` (the first
  ``n_dof`` states, eq. 5.7) or a boolean ``displacement`` mask.  Velocity states follow the
  displacements, aerodynamic lag states come last.

:func:`sweep` tracks every eigenvalue branch along the speeds (on :func:`follow`, the tracking
core over any scalar parameter), :func:`critical_points` refines
every sign change of a tracked mode's real part, :func:`analyse` does both in one call,
:func:`frequency_zero_points` locates unstable pairs turning real.

Modules (in dependency order; results is used by all)
-------------------------------------------------------
eigensolve
    Eigen-solutions, MAC (eq. 5.14), dλ/dV from left eigenvectors, shifted inverse iteration
    and its residual rules, one tracked mode's eigenvalue, checked state-matrix evaluation.
options
    :class:`TrackingOptions` (tuning of the tracker) and the check of a speed grid.
hermite
    Cubic Hermite models over one speed step.
nodes
    The full eigen-solution at one speed (a node of the sweep), evaluated in batches.
clusters
    Following 2–4 roots as a set through branch points on the real axis.
linking
    Which root at one speed continues which at the next (MAC, assignment, veering check).
ordering
    Branch (mode) ids along the chain of nodes, with the real-axis conventions.
crossings
    All critical-point refinement: crossings of Re λ = 0 (flutter, divergence), branch points
    of unstable pairs turning real, frequency-zero events; the default tolerance :data:`XTOL`.
tracker
    The one tracking core over any scalar parameter (:func:`follow`: nodes and linking plugged
    in, ambiguous steps split; also the Campbell diagram's and the mode naming's tracking over
    Ω) and the sweep over V on it (:func:`sweep`, :func:`analyse`): refinement of ambiguous
    steps, hump check, branch-point bracketing.
results
    Result types: :class:`Sweep`, :class:`CriticalPoint`, :class:`Hump`, :class:`Criticals`,
    :class:`FrequencyZero`, :class:`Analysis`.
free_response
    Free response of ẋ = A x in time (:func:`time_response`, :class:`TimeResponse`).

The state-matrix builder from M, C, K (eq. 5.4) lives in :mod:`propwhirl.model.statespace`;
whirl sense and modal content in :mod:`propwhirl.analysis.whirl`.
"""
from propwhirl.engine.crossings import XTOL, critical_points, frequency_zero_points
from propwhirl.engine.eigensolve import (eigen, eigenvalues, mac, single_thread_blas,
                                         tracked_eigenvalue)
from propwhirl.engine.options import TrackingOptions
from propwhirl.engine.results import Analysis, CriticalPoint, Criticals, FrequencyZero, Hump, Sweep
from propwhirl.engine.free_response import TimeResponse, time_response
from propwhirl.engine.tracker import ANALYSE_INITIAL_STEP, analyse, follow, sweep

__all__ = [
    "TrackingOptions", "Sweep", "CriticalPoint", "Hump", "Criticals", "FrequencyZero", "Analysis",
    "TimeResponse", "eigen", "eigenvalues", "single_thread_blas", "mac", "sweep",
    "critical_points", "frequency_zero_points", "analyse", "tracked_eigenvalue", "time_response",
    "ANALYSE_INITIAL_STEP", "XTOL", "follow",
]
