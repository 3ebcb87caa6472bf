"""How a model's modes are tracked: one small runner per method, chosen from one table
(issue 38 item 7, issue 34 item 5).

:func:`track` runs the runner :data:`RUNNERS` holds for the method
:func:`~propwhirl.analysis.reduced.choose_method` chose and the kind of model, and returns a
:class:`Tracked`: what :func:`propwhirl.analysis.stability.analyse` names and reports whatever
the method — the engine's sweep and crossings on the model's full state, the state matrix that
was tracked (for the frequency-zero events), the basis of a reduced state space, the structure
evaluated once (:class:`~propwhirl.analysis.modes.InVacuo`) and the method's notes.

=================  ==============  ===========================================================
method             model           runner
=================  ==============  ===========================================================
``"dense"``        any             :func:`run_dense`: the engine on the model's own A(V) (a
                                   doublet-lattice wing: the Roger state space on every DOF)
``"reduced"``      strip wing      :func:`run_reduced`: the engine on the reduced model, every
                                   crossing converged on the full order; under ``"auto"``
                                   :func:`run_dense` again where
                                   :data:`~propwhirl.analysis.reduced.AUTO_NEEDS` fails
``"reduced"``      DLM wing        :func:`run_modal_dlm`: the modal Roger state space, every
                                   crossing converged by the p-k
                                   (:mod:`propwhirl.analysis.modal_dlm`)
``"pk"``           section, wing   :func:`run_dense` on the strip twin; ``analyse`` then
                                   replaces its events by the p-k's
=================  ==============  ===========================================================
"""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, replace

import numpy as np

from propwhirl.analysis.modal_dlm import compute_fit_aics, modal_dlm_analysis
from propwhirl.analysis.modes import InVacuo
from propwhirl.analysis.participation import branch_point_shape
from propwhirl.analysis.reduced import frequency_zero_on_full_order, reduced_engine_analysis
from propwhirl.engine import analyse as engine_analyse
from propwhirl.engine import frequency_zero_points
from propwhirl.engine.results import Analysis
from propwhirl.model.aerodynamics.dlm import DlmTables, check_speed_mach
from propwhirl.model.aerodynamics.dlm_rfa import rfa_note, tracking_ks
from propwhirl.model.protocol import capabilities


@dataclass(frozen=True)
class Job:
    """What every runner is given: the ``model`` asked for and the ``finite`` model whose modes
    are tracked (the model itself; for the p-k its strip twin), the airspeed ``grid`` [m/s],
    ``xtol`` [m/s], ``vgf`` (every grid speed), the tracker's ``options``, ``auto``
    (the user left the method to the analysis), ``progress``, a reporter
    ``report(done, total)`` of the doublet-lattice AICs computed first, or None, and
    ``tables``: the analysis's doublet-lattice tables (a wing with ``aero = "dlm"``; the
    model's assembly and the p-k read and fill them)."""

    model: object
    finite: object
    grid: np.ndarray
    xtol: float
    vgf: bool
    options: object = None
    auto: bool = False
    progress: Callable[[int, int], None] | None = None
    tables: DlmTables | None = None

    def engine_kwargs(self) -> dict:
        """The engine's options of this job (``initial_step=None``: every grid speed)."""
        return {"options": self.options, **({"initial_step": None} if self.vgf else {})}


@dataclass(frozen=True)
class Tracked:
    """What a runner returns (module docstring).

    analysis: the engine's sweep (lifted to the model's full state) and crossings;
    state_matrix: the A(V) that was tracked; assembly, in_vacuo: the model's, built once;
    basis: q = basis η of a reduced state space (None: the model's own DOFs); lift: its map to
    the full state; fzero, fzero_shapes: the frequency-zero events and their shapes;
    unconverged: crossings not converged on the full order; notes_first, notes_last: the
    method's notes before and after the analysis's own; extrapolation: the events are to be
    checked against the Roger fit's reduced frequencies
    (:func:`~propwhirl.model.aerodynamics.dlm_rfa.extrapolation_notes`); method: the runner that ran.
    """

    analysis: Analysis
    state_matrix: Callable
    assembly: object
    in_vacuo: InVacuo
    method: str
    basis: np.ndarray | None = None
    lift: np.ndarray | None = None
    fzero: tuple = ()
    fzero_shapes: tuple = ()
    unconverged: tuple = ()
    notes_first: tuple[str, ...] = ()
    notes_last: tuple[str, ...] = ()
    extrapolation: bool = False


def is_dlm_wing(model) -> bool:
    """Whether ``model``'s wing has doublet-lattice loads on (the one test of it here: the
    model contract's :attr:`~propwhirl.model.protocol.Capabilities.aerodynamics`)."""
    return capabilities(model).aerodynamics == "doublet lattice"


def frequency_zero_events(model, sweep, state_matrix, xtol: float, lift):
    """The frequency-zero events of a tracked sweep of ``model`` (brackets of width ≤ xtol
    [m/s], :func:`~propwhirl.engine.frequency_zero_points`) and each one's shape at its
    bracket's lower end (:func:`~propwhirl.analysis.participation.branch_point_shape`;
    ``lift``: a reduced model's map to the full state, or None)."""
    points = frequency_zero_points(sweep, state_matrix, xtol=xtol)
    shapes = [branch_point_shape(model, sweep, p.mode, p.bracket[0], state_matrix, lift)
              for p in points]
    return tuple(points), tuple(shapes)


def _structure(job: Job, assembly=None) -> tuple[object, InVacuo]:
    """The model's assembly (a doublet-lattice wing's with the job's tables) and its
    structure without aerodynamics, each built once."""
    if assembly is None:
        dlm = getattr(getattr(job.finite, "wing", job.finite), "aero", "") == "dlm"
        assembly = (job.finite.assembly(dlm_tables=job.tables) if dlm else
                    job.finite.assembly())
    return assembly, InVacuo.of(assembly.without_aerodynamics())


def run_dense(job: Job, assembly=None, in_vacuo: InVacuo | None = None) -> Tracked:
    """Every root of the model's own A(V) at each speed (the reference)."""
    if assembly is None or in_vacuo is None:
        assembly, in_vacuo = _structure(job, assembly)
    dm = job.finite.dof_map()
    an = engine_analyse(assembly.state_matrix, job.grid, displacement=dm.displacement,
                        state_labels=dm.state_labels, xtol=job.xtol, **job.engine_kwargs())
    fzero, shapes = frequency_zero_events(job.finite, an.sweep, assembly.state_matrix,
                                          job.xtol, None)
    dlm = is_dlm_wing(job.finite)
    return Tracked(an, assembly.state_matrix, assembly, in_vacuo, "dense", fzero=fzero,
                   fzero_shapes=shapes,
                   notes_first=(rfa_note(job.model, job.grid, tables=job.tables),) if dlm
                   else (),
                   extrapolation=dlm)


def run_reduced(job: Job) -> Tracked:
    """The reduced strip wing: crossings converged on the full order; under "auto" the dense
    analysis again where a crossing did not converge or a frequency-zero bracket misses the
    full order's branch point (:data:`~propwhirl.analysis.reduced.AUTO_NEEDS`)."""
    assembly, in_vacuo = _structure(job)
    dm = job.finite.dof_map()
    run = reduced_engine_analysis(job.model, job.grid, displacement=dm.displacement,
                                  state_labels=dm.state_labels, options=job.options,
                                  xtol=job.xtol, vgf=job.vgf, assembly=assembly,
                                  structure=(in_vacuo.M, in_vacuo.K))
    an = run.analysis
    unconverged = tuple(p for p, s in zip(an.criticals.points, run.corrections) if s is None)
    fzero, shapes = frequency_zero_events(job.finite, an.sweep, run.model.state_matrix,
                                          job.xtol, run.model.lift)
    if job.auto and (unconverged or not frequency_zero_on_full_order(fzero, shapes, run.model)):
        return run_dense(job, assembly, in_vacuo)
    return Tracked(an, run.model.state_matrix, assembly, in_vacuo, "reduced",
                   run.model.dof_basis, run.model.lift, fzero, shapes, unconverged)


def run_modal_dlm(job: Job) -> Tracked:
    """A doublet-lattice wing's modal Roger state space, its crossings the p-k's
    (:mod:`propwhirl.analysis.modal_dlm`)."""
    assembly, in_vacuo = _structure(job)
    # the full Roger state the modal one lifts to (names, shapes): the same fits, no others
    assembly = replace(assembly, dlm_fit_ks=tuple(float(k) for k in tracking_ks()))
    dm = job.finite.dof_map()
    run = modal_dlm_analysis(job.model, job.grid, displacement=dm.displacement,
                             state_labels=dm.state_labels, options=job.options, xtol=job.xtol,
                             vgf=job.vgf, assembly=assembly, structure=(in_vacuo.M, in_vacuo.K))
    R = run.model
    fzero, shapes = frequency_zero_events(job.finite, run.analysis.sweep, R.state_matrix,
                                          job.xtol, R.lift)
    return Tracked(run.analysis, R.state_matrix, assembly, in_vacuo, "modal-dlm", R.dof_basis,
                   R.lift, fzero, shapes,
                   notes_first=(rfa_note(job.model, job.grid, R, job.tables),),
                   notes_last=run.notes)


def run_pk_tracking(job: Job) -> Tracked:
    """The p-k's finite-state tracking: the strip twin's modes, every root (``analyse`` then
    puts the p-k's crossings in place of its events)."""
    t = run_dense(job)
    return Tracked(t.analysis, t.state_matrix, t.assembly, t.in_vacuo, "pk", fzero=t.fzero,
                   fzero_shapes=t.fzero_shapes)


#: (method chosen, doublet-lattice wing) → runner: the one table of how a model is tracked
RUNNERS: dict[tuple[str, bool], Callable[[Job], Tracked]] = {
    ("dense", False): run_dense, ("dense", True): run_dense,
    ("reduced", False): run_reduced, ("reduced", True): run_modal_dlm,
    ("pk", False): run_pk_tracking, ("pk", True): run_pk_tracking,
}


def track(job: Job, chosen: str) -> Tracked:
    """The runner of :data:`RUNNERS` for ``chosen`` (a method of
    :func:`~propwhirl.analysis.reduced.choose_method`) on ``job``'s model; a doublet-lattice
    wing's Mach numbers checked against its tables first (before any work), and the AICs of
    its first speeds computed first, counted with ``job.progress`` and a big batch on worker
    processes (:func:`~propwhirl.analysis.modal_dlm.compute_fit_aics`)."""
    dlm = chosen != "pk" and is_dlm_wing(job.model)
    if dlm:
        check_speed_mach(job.model, (job.grid[0], job.grid[-1]))
    if dlm:            # the AICs of its first speeds first: counted, on processes if many
        compute_fit_aics(job.model, job.grid, vgf=job.vgf, report=job.progress,
                         tables=job.tables)
    return RUNNERS[(chosen, dlm)](job)
