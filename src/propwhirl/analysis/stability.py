"""Stability analysis of a model: labelled V-g-f sweep, instabilities, the critical one.

:func:`analyse` runs the engine (:mod:`propwhirl.engine`) on any
:class:`~propwhirl.model.protocol.Model` — its state matrix A(V) and its DOF map — and names
the tracked modes the way the thesis does (chapters 9–11; :mod:`propwhirl.analysis.naming`:
"wing n", "backward k", "forward k", "lag k", ...).  A mode keeps its name along the sweep (it
is a tracked branch).  At each flutter event the whirl sense of the propeller motion is also
reported, because strongly coupled modes may change it.

Instabilities are the onsets of the engine's crossings (flutter: a complex pair; divergence: a
real root through zero), modes already unstable at the first speed, and *frequency-zero* events:
an already unstable oscillatory mode whose frequency falls to zero (the pair splits into real
roots) — the thesis's "whirl divergence" (Table 10.4).  :func:`critical` is the one definition
of the critical instability.  Results are saved and re-read with :meth:`ModelAnalysis.save` /
:func:`load` (the file format: :mod:`propwhirl.analysis.files`, re-exported here: ``load``,
``FORMAT``, ``FORMAT_VERSION``, ``READABLE_VERSIONS``, ``eigenvectors_path``).
"""
from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from propwhirl.engine import XTOL, Criticals, Sweep, TrackingOptions, frequency_zero_points
from propwhirl.engine import analyse as engine_analyse
from propwhirl.engine.options import check_speeds
from propwhirl import validate as v
# the analysis file; load, READABLE_VERSIONS and eigenvectors_path re-exported (public here)
from propwhirl.analysis.files import (FORMAT, FORMAT_VERSION, READABLE_VERSIONS,  # noqa: F401
                                      _event_dict, analysis_from_dict, eigenvectors_path, load,
                                      save_analysis)
from propwhirl.analysis.naming import mode_content, mode_names, whirl
from propwhirl.analysis.participation import (ModeParticipation, branch_point_shape, events_csv,
                                              events_table, participation_lines,
                                              with_participation)
from propwhirl.analysis.reduced import choose_method, reduced_engine_analysis
from propwhirl.analysis.summary import (FiniteState, FlutterSummary, MethodComparison,
                                        Reference, aero_model_of, compare_methods,
                                        flutter_summary, reference, text_table)
from propwhirl.model import validity
from propwhirl.model.protocol import DofMap, Model

#: Default airspeed grid of the thesis's analyses (0–350 m/s; the engine refines it) [m/s]
DEFAULT_SPEEDS = np.arange(1.0, 351.0, 10.0)


@dataclass(frozen=True)
class Instability:
    """One instability event of a tracked mode.

    kind:   "flutter" (oscillatory) or "divergence" (non-oscillatory)
    event:  "onset" (Re λ becomes positive), "recovery" (becomes negative again; hump modes),
            "frequency-zero" (an unstable pair turns into real roots: divergence of that mode),
            "unstable-at-start" (Re λ > 0 already at the first analysed speed, V = that speed)
    mode, label: tracked mode id and its name (e.g. "forward 1", "wing 2", "lag 1")
    V [m/s], frequency_hz [Hz] at the event; whirl: "forward"/"backward"/"planar" sense of the
    θ–ψ orbit of the propeller with the largest θ–ψ motion (None without flexible propellers);
    benignity [m/s] (eq. 5.13) at flutter onsets; participation: every flexibly mounted
    propeller's share of the mode's kinetic energy, whirl sense, relative amplitude and
    position at the event (:mod:`propwhirl.analysis.participation`; None without the mode
    shape).
    """

    kind: str
    event: str
    mode: int
    label: str
    V: float
    frequency_hz: float
    whirl: str | None = None
    benignity: float | None = None
    participation: ModeParticipation | None = None

    def propeller_text(self, count: int | None = None) -> str:
        """Which propellers take part: 'propeller 3 (y = 3 m): 61 %, backward whirl, ...'
        ("" without flexibly mounted propellers or without the mode shape)."""
        p = self.participation
        return "" if p is None or not p.propellers else p.describe(count)


#: Events that make the system (more) unstable, candidates for the critical instability.
UNSTABLE_EVENTS = ("onset", "unstable-at-start", "frequency-zero")

#: What :func:`critical` may leave out: kinds ("flutter", "divergence"), or a predicate on an
#: event that is True for events to leave out.
Exclusion = str | Sequence[str] | Callable[[Instability], bool]


def critical(events: Sequence[Instability], *, exclude: Exclusion = ()) -> Instability | None:
    """The critical instability: the lowest-speed event that makes the system unstable.

    This is the one definition used by the summary, the CLI, ``propwhirl run``, the studies and
    the result files.  Candidates are the onsets of flutter and of divergence (static
    divergence included), frequency-zero events (an unstable pair turning real), and modes
    already unstable at the first analysed speed — event "unstable-at-start", reported at that
    speed, never skipped.  Ties at one speed go to the lower mode id.

    Parameters
    ----------
    events : sequence of Instability
        The events of an analysis (:attr:`ModelAnalysis.events`).
    exclude : str, sequence of str or callable, optional
        Leave out events of these kinds ("flutter", "divergence"), or the events for which
        ``exclude(event)`` is True (e.g. the wing's static divergence, which the thesis's
        chapter-11 studies ignore).  Default: nothing is left out.

    Returns
    -------
    Instability or None
        None when nothing is unstable in the analysed range.

    Examples
    --------
    >>> from propwhirl.analysis.stability import Instability, critical
    >>> ev = [Instability("flutter", "onset", 3, "forward 1", 159.39, 11.25),
    ...       Instability("divergence", "onset", 0, "wing 1", 143.15, 0.0)]
    >>> critical(ev).label
    'wing 1'
    >>> critical(ev, exclude="divergence").V
    159.39
    """
    if callable(exclude):
        leave_out = exclude
    else:
        kinds = {exclude} if isinstance(exclude, str) else set(exclude)
        bad = sorted(kinds - {"flutter", "divergence"})
        if bad:
            raise v.InputError(f"exclude = {bad!r} is invalid: kinds are 'flutter' and 'divergence'")
        leave_out = lambda e: e.kind in kinds  # noqa: E731
    cands = [e for e in events if e.event in UNSTABLE_EVENTS and not leave_out(e)]
    return min(cands, key=lambda e: (e.V, e.mode)) if cands else None


def describe_critical(c: Instability | None, describe: Callable[[str], str] = str) -> str:
    """One line for the critical instability, e.g. 'flutter of forward 1 (yaw) at 159.39 m/s,
    11.247 Hz' or 'unstable from V = 150 m/s, the start of the range: divergence of wing 1'."""
    if c is None:
        return "none in the speed range"
    what = f"{c.kind} of {describe(c.label)}"
    if c.event == "unstable-at-start":
        f = f" ({c.frequency_hz:.3f} Hz)" if c.kind == "flutter" else ""
        who = c.propeller_text(count=3)
        return (f"unstable from V = {c.V:g} m/s, the start of the range: {what}{f}"
                + (f"; {who}" if who else ""))
    f = f", {c.frequency_hz:.3f} Hz" if c.kind == "flutter" else ""
    who = c.propeller_text(count=3)
    return f"{what} at {c.V:.2f} m/s{f}" + (f"; {who}" if who else "")


@dataclass
class ModelAnalysis:
    """A labelled sweep and its instabilities (sorted by speed)."""

    model_name: str
    sweep: Sweep
    events: tuple[Instability, ...]
    criticals: Criticals | None = field(default=None, repr=False)
    #: mode label -> share of its kinetic energy at the first speed per group of degrees of
    #: freedom ("bending": h, φ; "torsion": α; "pitch", "yaw": propeller θ, ψ; "plunge")
    content: dict[str, dict[str, float]] = field(default_factory=dict)
    #: what each state of the analysed model is (wing node and DOF, propeller, lag state)
    dof_map: DofMap | None = field(default=None, repr=False)
    #: results outside the methods' validity, one line each (:mod:`propwhirl.model.validity`:
    #: Mach above 0.7 or supersonic, supersonic propeller tips); saved and re-read
    warnings: tuple[str, ...] = ()
    #: reference length, density and speed of sound of the flutter summary (saved and re-read)
    reference: Reference | None = None
    #: with method="pk" (the events are then the p-k method's): the finite-state events of the
    #: same tracked modes and their aerodynamics (saved and re-read); None otherwise
    finite_state: FiniteState | None = None

    def method_comparison(self) -> MethodComparison | None:
        """The p-k events beside the finite-state ones (:func:`compare_methods`: V and f by
        each, their differences), or None unless analysed with method="pk"."""
        return None if self.finite_state is None else compare_methods(self.events,
                                                                      self.finite_state)

    def describe(self, label: str) -> str:
        """'label (dominant content)', e.g. 'wing 2 (torsion)'."""
        c = self.content.get(label)
        if not c:
            return label
        return f"{label} ({max(c, key=lambda g: c[g])})"

    @property
    def onsets(self) -> list[Instability]:
        """Events that make the system (more) unstable (:data:`UNSTABLE_EVENTS`): onsets,
        frequency-zero events and modes unstable at the first speed."""
        return [e for e in self.events if e.event in UNSTABLE_EVENTS]

    @property
    def critical(self) -> Instability | None:
        """The critical instability (:func:`critical`: the lowest-speed instability of any
        kind, static divergence included; a mode unstable at the first speed counts there)."""
        return critical(self.events)

    def critical_excluding(self, exclude: Exclusion) -> Instability | None:
        """The critical instability leaving out some events (see :func:`critical`), e.g.
        ``a.critical_excluding("divergence")`` as the thesis's chapter-11 studies."""
        return critical(self.events, exclude=exclude)

    def first(self, label: str, kind: str | None = None, event: str = "onset") -> Instability | None:
        """The lowest-speed event of the mode named `label` (optionally of one kind)."""
        hits = [e for e in self.events
                if e.label == label and e.event == event and (kind is None or e.kind == kind)]
        return min(hits, key=lambda e: e.V) if hits else None

    def summary(self) -> str:
        """The instabilities as a text table (the propeller column names the propeller whose
        whirl is given: the one with the largest θ–ψ amplitude, numbered from 1), each event's
        propeller participation, and the critical instability (last line)."""
        how = "" if self.finite_state is None else " (p-k method, exact Theodorsen function)"
        lines = [f"{self.model_name}: instabilities{how} between {self.sweep.V[0]:g} and {self.sweep.V[-1]:g} m/s"]
        rows = [[e.kind, e.event, self.describe(e.label), _leading(e), e.whirl or "-",
                 f"{e.V:.2f}", f"{e.frequency_hz:.3f}"] for e in self.events]
        table = text_table(rows, ["type", "event", "mode (content at V0)", "propeller", "whirl",
                                  "V [m/s]", "f [Hz]"], "lllllrr")
        lines += ["  " + line for line in table.splitlines()]
        lines += participation_lines(self.events, "  ")
        if self.finite_state is not None:
            lines += self.method_comparison().format().splitlines()
        lines.append("  critical: " + describe_critical(self.critical, self.describe))
        return "\n".join(lines)

    @property
    def reference_or_error(self) -> Reference:
        if self.reference is None:
            raise v.InputError("this analysis has no reference (b_ref, density, speed of sound):"
                               " give one, e.g. flutter_summary(Reference(...))")
        return self.reference

    def flutter_summary(self, reference: Reference | None = None) -> FlutterSummary:
        """Every physical mode at every analysed speed: V, k = ω b_ref/V, ζ, g = 2ζ, f, density,
        Mach (:mod:`propwhirl.analysis.summary`; `reference` defaults to the model's)."""
        return flutter_summary(self.sweep, reference or self.reference_or_error, self.model_name)

    def modes_of_interest(self, lowest: int = 8) -> list[int]:
        """Ids of the modes with an event and of the ``lowest`` oscillatory physical modes of
        lowest frequency at the first speed, by increasing frequency at the first speed."""
        sw = self.sweep
        f0 = sw.frequency_hz[0]
        osc = [k for k in range(sw.n_modes) if sw.physical[0, k] and f0[k] > 0]
        ids = set(sorted(osc, key=lambda k: f0[k])[:lowest]) | {e.mode for e in self.events}
        return sorted(ids, key=lambda k: (f0[k], k))

    def to_dataframe(self):
        """The V-g-f table (:meth:`Sweep.to_dataframe`) as a pandas DataFrame (``data`` extra)."""
        df = self.sweep.to_dataframe()
        df.attrs["model_name"] = self.model_name
        return df

    def to_xarray(self):
        """The sweep as an xarray Dataset, dims speed × mode (:meth:`Sweep.to_xarray`)."""
        ds = self.sweep.to_xarray()
        ds.attrs["model_name"] = self.model_name
        return ds

    def events_table(self) -> dict[str, np.ndarray]:
        """Tidy columns of the events' propeller participation: one row per event and flexibly
        mounted propeller (one row with an empty propeller for a model without them).
        Propellers numbered from 1; shares of the mode's kinetic energy (module
        :mod:`propwhirl.analysis.participation`)."""
        return events_table(self.events)

    def events_csv(self, path: str | Path | None = None) -> str:
        """:meth:`events_table` as CSV (also written to ``path``, atomically)."""
        return events_csv(self.events, path)

    def to_dict(self, include_eigenvectors: bool = False) -> dict[str, Any]:
        """The analysis as a JSON-able dict (the document :meth:`save` writes, format
        :data:`FORMAT` version :data:`FORMAT_VERSION`); a non-finite benignity becomes None."""
        c = self.critical
        pk = {} if self.finite_state is None else {
            "finite_state": {"aero_model": self.finite_state.aero_model,
                             "events": [_event_dict(e) for e in self.finite_state.events]},
            "method_comparison": self.method_comparison().to_dict()}
        return {
            "format": FORMAT, "format_version": FORMAT_VERSION,
            "model_name": self.model_name,
            "events": [_event_dict(e) for e in self.events],
            "critical": None if c is None else _event_dict(c),
            "dof_map": None if self.dof_map is None else self.dof_map.to_dict(),
            "content": self.content,
            "sweep": self.sweep.to_dict(include_eigenvectors=include_eigenvectors),
            "warnings": list(self.warnings),
            "reference": None if self.reference is None else self.reference.to_dict(),
            **pk,
        }

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> "ModelAnalysis":
        """The analysis of a dict written by :meth:`to_dict`, checked: format and version,
        every key, types, shapes (T speeds, n modes), finite numbers, mode ids and names, the
        DOF map against the sweep's states, the saved critical instability against the events.
        Anything else is an :class:`~propwhirl.validate.InputError` naming the key.

        A dict without "format" and "format_version" (written before they were introduced,
        otherwise the same layout) is read as version 1."""
        return analysis_from_dict(d)

    def save(self, path: str | Path, include_eigenvectors: bool = False) -> None:
        """Write the analysis as JSON (V-g-f table, labels, instabilities and their propeller
        participation); with ``include_eigenvectors`` also the eigenvectors of every speed, in
        a NumPy ``.npz`` file beside it (:func:`eigenvectors_path`: ``a.json`` →
        ``a.eigenvectors.npz``), which the JSON names.  The JSON stays readable on its own:
        :func:`load` without the npz gives the analysis without eigenvectors.

        Each file is replaced atomically (:func:`propwhirl.fileio.write_text`: a full disk or a
        Ctrl-C leaves the old file or none, never a partial one; the npz is written first).
        JSON without NaN or infinity: a non-finite number is an
        :class:`~propwhirl.validate.InputError` naming the key, and nothing is written."""
        save_analysis(self, path, include_eigenvectors)


# ----------------------------------------------------------------------------- analyse
def analyse(model: Model, speeds=None, *, xtol: float = XTOL, vgf: bool = False,
            options: TrackingOptions | None = None, method: str = "auto") -> ModelAnalysis:
    """Every instability of `model` over `speeds` [m/s], with tracked, named modes.

    Parameters
    ----------
    model : Model
        Any model of :mod:`propwhirl.model` (its state matrix A(V) and DOF map).
    speeds : array_like, optional
        Increasing airspeed grid [m/s], all > 0.  Default: the model's
        ``FlightCondition.speed_range`` (1–350 m/s every 10 m/s, the thesis's 0–350 m/s).
    xtol : float, optional
        Accuracy of every critical speed [m/s] (default :data:`propwhirl.engine.XTOL`,
        0.01 m/s).
    vgf : bool, optional
        Evaluate every grid speed (for V-g-f plots and tables).  By default the engine starts
        from grid speeds ≈ 50 m/s apart and adds speeds only where tracking or a possible
        crossing asks for them, so ``.sweep`` is coarse.
    options : TrackingOptions, optional
        Tuning of the mode tracker.
    method : {"auto", "dense", "reduced", "pk"}, optional
        "pk" (typical sections and wings): the modes tracked as "dense", their flutter and
        divergence crossings by the p-k method with the exact Theodorsen function
        (:mod:`propwhirl.analysis.pk`; each event's mode, whirl sense and participation from
        its p-k mode shape, the benignity from the p-k damping), and the finite-state events
        kept beside them (:attr:`ModelAnalysis.finite_state`, the side-by-side table of
        :meth:`ModelAnalysis.method_comparison` in the summary).
        "dense": every root of the full-order A(V) at each speed (the reference); "reduced":
        the modes below a frequency cut-off on a reduced-order model, every crossing then
        converged on the full-order model (:mod:`propwhirl.analysis.reduced`); "auto"
        (default): reduced for wing models of more than
        :data:`~propwhirl.analysis.reduced.REDUCED_ABOVE` states, else dense.

    Returns
    -------
    ModelAnalysis
        The tracked sweep, its instability events (sorted by speed) and
        :attr:`ModelAnalysis.critical`.

    Examples
    --------
    The isolated baseline propeller of §9.2 (Table 9.5: backward whirl flutter at 221 m/s):

    >>> from propwhirl.analysis import analyse
    >>> from propwhirl.cases.ch09_baseline import isolated_baseline_propeller
    >>> a = analyse(isolated_baseline_propeller(), speeds=[100.0, 200.0, 250.0])
    >>> e = a.critical
    >>> e.kind, e.event, e.label, round(e.V, 2), round(e.frequency_hz, 3)
    ('flutter', 'onset', 'backward', 221.5, 5.011)
    >>> print(a.summary().splitlines()[-1])
      critical: flutter of backward (pitch) at 221.50 m/s, 5.011 Hz; propeller 1: 100 %, backward whirl
    """
    if not isinstance(model, Model):
        raise v.InputError(f"model = {model!r:.60} is invalid: must be a model of "
                           "propwhirl.model (PropellerWing, IsolatedPropeller, TypicalSection)")
    grid = model.flight.speeds() if speeds is None else check_speeds(speeds)
    v.positive("xtol", xtol, "m/s")
    if not isinstance(vgf, (bool, np.bool_)):
        raise v.InputError(f"vgf = {vgf!r} is invalid: must be True or False")
    if options is not None and not isinstance(options, TrackingOptions):
        raise v.InputError(f"options = {options!r} is invalid: must be a TrackingOptions")
    dm = model.dof_map()
    chosen = choose_method(model, method)
    if chosen == "reduced":
        run = reduced_engine_analysis(model, grid, displacement=dm.displacement,
                                      state_labels=dm.state_labels, options=options, xtol=xtol,
                                      vgf=bool(vgf))
        an, matrix_fn, basis = run.analysis, run.model.state_matrix, run.model.dof_basis
        lift = run.model.lift
        unconverged = [p for p, s in zip(an.criticals.points, run.corrections) if s is None]
    else:
        matrix_fn = model.assembly().state_matrix     # built once for the analysis
        an = engine_analyse(matrix_fn, grid, displacement=dm.displacement,
                            state_labels=dm.state_labels, options=options, xtol=xtol,
                            **({"initial_step": None} if vgf else {}))
        basis, lift = None, None
        unconverged = []
    sw = an.sweep
    names = mode_names(model, sw, basis)
    sw = sw.relabel(names)
    events, shapes = [], []
    for p in an.criticals.points:
        sense = whirl(dm, p.eigenvector, p.eigenvalue) if p.kind == "flutter" else None
        events.append(Instability(p.kind, p.direction, p.mode, names[p.mode], float(p.V),
                                  float(p.frequency_hz), sense,
                                  None if p.benignity is None else float(p.benignity)))
        shapes.append((p.eigenvector, p.eigenvalue, float(p.V)))
    for k in an.criticals.unstable_at_start:
        lam0 = sw.eigenvalues[0, k]
        kind = "flutter" if abs(lam0.imag) > 0 else "divergence"
        events.append(Instability(kind, "unstable-at-start", int(k), names[k], float(sw.V[0]),
                                  float(abs(lam0.imag) / (2 * np.pi))))
        shapes.append((sw.eigenvectors[0, :, k], lam0, float(sw.V[0])))
    for p in frequency_zero_points(sw, matrix_fn, xtol=xtol):
        events.append(Instability("divergence", "frequency-zero", p.mode, names[p.mode], p.V, 0.0))
        shapes.append(branch_point_shape(model, sw, p.mode, p.bracket[0], matrix_fn, lift))
    events = with_participation(model, events, shapes)
    if chosen == "pk":  # the tracked finite-state modes, their crossings by the exact p-k method
        from propwhirl.analysis.pk import pk_instabilities

        pk_notes: list[str] = []
        finite_state = tuple(sorted(events, key=lambda e: (e.V, e.mode)))
        events = pk_instabilities(model, sw.eigenvalues[0], names, grid, xtol=xtol,
                                  notes=pk_notes, sweep=sw)
        unconverged_pk = tuple(pk_notes)
    else:
        unconverged_pk, finite_state = (), None
    events.sort(key=lambda e: (e.V, e.mode))
    notes = validity.analysis_warnings(
        model, (float(sw.V[0]), float(sw.V[-1])),
        [(e.V, f"{e.kind} {e.event} of {e.label}") for e in events],
        any(e.event in UNSTABLE_EVENTS for e in events))
    notes = tuple(notes) + tuple(
        f"V = {p.V:.2f} m/s ({p.kind} {p.direction} of {names[p.mode]}): not converged on the "
        "full-order model; the speed is the reduced model's (run method='dense' to check)"
        for p in unconverged) + unconverged_pk
    try:
        ref = reference(model)
    except v.InputError:                     # a model of another kind: no summary reference
        ref = None
    return ModelAnalysis(model.name, sw, tuple(events), an.criticals,
                         mode_content(model, sw, names), dm, notes, ref,
                         None if finite_state is None
                         else FiniteState(aero_model_of(model), finite_state))


def _leading(e: Instability) -> str:
    """'3 (y = 3.00 m)': the propeller with the largest θ–ψ amplitude at the event, or '-'."""
    p = None if e.participation is None else e.participation.leading
    return "-" if p is None else p.name().removeprefix("propeller ")


def speed_and_frequency(event: Instability | None) -> tuple[float, float]:
    """(V [m/s], f [Hz]) of an event; NaN (reported as not computed) when there is none."""
    if event is None:
        return float("nan"), float("nan")
    return event.V, event.frequency_hz


def first_of_kind(a: ModelAnalysis, kind: str, event: str = "onset") -> Instability | None:
    """The lowest-speed event of a kind ("flutter" or "divergence"), whatever the mode."""
    hits = [e for e in a.events if e.kind == kind and e.event == event]
    return min(hits, key=lambda e: e.V) if hits else None
