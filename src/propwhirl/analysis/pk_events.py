"""The p-k method's crossings as an analysis's events (``analyse(model, method="pk")``): each
crossing of :func:`propwhirl.analysis.pk.pk_sweep` an
:class:`~propwhirl.analysis.events.Instability` of the finite-state analysis's tracked modes —
named by its p-k shape (:mod:`propwhirl.analysis.pk_naming`), with its whirl sense, the
propellers' participation and its benignity — and the notes of a doublet-lattice p-k analysis
(:func:`dlm_notes`)."""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from propwhirl.analysis.events import Instability
from propwhirl.analysis.modes import InVacuo
from propwhirl.analysis.naming import event_label, whirl
from propwhirl.analysis.participation import with_participation
from propwhirl.analysis.pk import DLM_NOTE, PKSweep, pk_sweep
from propwhirl.analysis.pk_basis import pk_basis
from propwhirl.analysis.pk_crossings import pk_benignity
from propwhirl.analysis.pk_iteration import STATIC, XTOL, pk_mode, pk_shape
from propwhirl.analysis.pk_naming import one_to_one, tracked_mode
from propwhirl.model.aerodynamics.dlm import (DlmTables, check_tables, dlm_aerodynamics,
                                              fixed_mach, strip_twin)
from propwhirl.model.aerodynamics.dlm_mesh import guideline_note
from propwhirl.model.frequency_domain import Galerkin, dry_assembly


def dlm_notes(model, sweep: PKSweep, tables: DlmTables | None = None) -> list[str]:
    """What a doublet-lattice p-k analysis used (:data:`DLM_NOTE` first: panels, Mach, k
    convention) and, when broken, the panel-length guideline at the first speed and the
    highest followed frequency (:func:`propwhirl.model.aerodynamics.dlm_mesh.guideline_note`)."""
    aero = dlm_aerodynamics(model, tables)
    m = aero.mesh
    fixed = fixed_mach(getattr(model, "wing", model))
    mach = ("Mach V/a at each speed" if fixed is None
            else f"Mach {fixed:g} at every speed (dlm_mach: not matched to V/a)")
    out = [f"{DLM_NOTE} panels ({m.n_chord} chordwise x {m.n_span} spanwise on the half-wing, "
           f"root a plane of symmetry), {mach}, k = omega b_ref / V on the root "
           f"semichord b_ref = {aero.b_ref:.4g} m; the finite-state events beside them are the "
           "strip model's"]
    f = np.abs(sweep.roots[0].imag[np.isfinite(sweep.roots[0])]) / (2 * np.pi)
    if f.size:
        note = guideline_note(m, float(sweep.speeds[0]), float(f.max()))
        if note is not None:
            out.append(note)
    return out


def pk_instabilities(model, start_roots: np.ndarray, names, speeds, *, xtol: float = XTOL,
                     notes: list | None = None, sweep=None, mass: np.ndarray | None = None,
                     tables: DlmTables | None = None, basis: Galerkin | None = None):
    """The p-k crossings as :class:`~propwhirl.analysis.stability.Instability` events of the
    finite-state analysis's tracked modes (``analyse(model, method="pk")``).

    ``start_roots`` are the tracked modes' finite-state eigenvalues [1/s] at ``speeds[0]``
    and ``names`` their labels.  With the finite-state ``sweep`` (its eigenvectors), each
    event's mode is the tracked mode of its p-k mode shape at the event
    (:func:`tracked_mode`; those that name two events of one cluster assigned one to one,
    :func:`one_to_one`; where that is an aerodynamic lag root at the first speed, named
    after the structural mode the shape is, :func:`propwhirl.analysis.naming.event_label`,
    with the structural ``mass`` matrix — default: the finite-state model's); without it,
    the tracked mode whose root at the first speed is nearest the root the p-k mode started
    from.
    Events: "onset" / "recovery" of flutter or divergence, and "unstable-at-start" when
    Re p > 0 at the first speed, each with the whirl sense and the propellers' participation
    of its p-k mode shape (:mod:`propwhirl.analysis.participation`: the p-k eigenvector's
    displacements are on the model's own DOFs) and, for flutter crossings, the benignity
    (dζ/dV)⁻¹ of the p-k root [m/s] (:func:`pk_benignity`).  ``tables``: a doublet-lattice
    wing's (the analysis's; None: new ones).  ``basis``: the Galerkin basis of the sweep
    (:func:`~propwhirl.analysis.pk_basis.pk_basis`; None: built here).

    Returns the events and the basis the sweep kept (None where it ran on the model's DOFs:
    a typical section, a modal model, or a basis that failed the sweep's check at the top
    speed) — the analysis's Mach check's (:func:`propwhirl.analysis.mach_check.pk_warnings`).
    """
    dlm = strip_twin(model) is not model
    tables = check_tables(tables) if dlm else None
    dry = dry_assembly(model)                   # the sweep's and the events' one assembly
    basis = pk_basis(model, speeds, tables) if basis is None else basis
    r = pk_sweep(model, speeds, xtol=xtol, tables=tables, dry=dry, basis=basis)
    kept = basis if r.basis_size else None
    if notes is not None and dlm:
        notes.extend(dlm_notes(model, r, tables))
    dm = model.dof_map()
    n = dm.n_dof
    tracked = [int(np.argmin(np.abs(np.asarray(start_roots) - p))) for p in r.start]
    use_shape = sweep is not None and sweep.eigenvectors is not None
    if use_shape and mass is None:
        mass = InVacuo.of(strip_twin(model).without_aerodynamics()).M
    if notes is not None:                     # modes the p-k iteration lost: said, not dropped
        for label, V in r.lost:
            mode = names[tracked[r.labels.index(label)]]
            notes.append(f"p-k: the k iteration of {mode} did not converge at V = {V:.2f} m/s; "
                         "that mode is not followed beyond it (no crossing of it is reported "
                         "there: check it with method='dense')")
    events, shapes = [], []

    def add(kind: str, event: str, j: int, V: float, p0: complex, benign: bool,
            root: complex | None = None) -> None:
        # a crossing's shape at its own Mach's AICs, as it was converged (matched_crossing):
        # its own root's (root: the sweep's crossing), not one continued again from the swept
        # root before it (in a cluster that may be another member's)
        own = event != "unstable-at-start"
        if root is not None:
            p = complex(root)
            x = pk_shape(model, V, p, tables=tables, own_mach=own, dry=dry)
        else:
            p, _, x = pk_mode(model, V, p0, tables=tables, own_mach=own, dry=dry)
        mode = tracked_mode(sweep, x, p, V) if use_shape else tracked[j]
        label = event_label(sweep, names, mode, x, mass) if use_shape else names[mode]
        f_hz = 0.0 if kind == "divergence" else float(abs(p.imag) / (2 * np.pi))
        events.append(Instability(
            kind, event, mode, label, float(V), f_hz,
            whirl(dm, x[:n], p) if kind == "flutter" else None,
            pk_benignity(model, V, p, tables, dry) if benign else None))
        shapes.append((x[:n], p, float(V)))

    for j, p0 in enumerate(r.roots[0]):
        if p0.real > 0:
            kind = "flutter" if abs(p0.imag) > STATIC * abs(r.start[j]) else "divergence"
            add(kind, "unstable-at-start", j, float(r.speeds[0]), p0, False)
    for f in r.flutter:
        i = int(np.flatnonzero(r.speeds <= f.V)[-1])
        add(f.kind, "onset" if f.event == "onset" else "recovery", f.mode, f.V,
            complex(r.roots[i, f.mode]), f.kind == "flutter", f.root)
    if use_shape:                         # never two events of one cluster under one name
        modes = one_to_one(sweep, [e.mode for e in events], [s[0] for s in shapes],
                           [e.V for e in events], [(e.kind, e.event) for e in events])
        events = [e if m == e.mode else replace(e, mode=m, label=event_label(
            sweep, names, m, shapes[i][0], mass)) for i, (e, m) in enumerate(zip(events, modes))]
    events = with_participation(model, events, shapes)
    order = sorted(range(len(events)), key=lambda i: (events[i].V, events[i].mode))
    return [events[i] for i in order], kept
