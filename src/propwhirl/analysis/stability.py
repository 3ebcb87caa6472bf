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
:func:`load`.
"""
from __future__ import annotations

import json
from dataclasses import dataclass, field, fields, replace
from pathlib import Path
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from propwhirl.engine import XTOL, Criticals, Sweep, TrackingOptions, frequency_zero_points
from propwhirl.engine import analyse as engine_analyse
from propwhirl.engine.options import check_speeds
from propwhirl.engine.results import (SavedDict, eigenvectors_path, read_eigenvectors,
                                      eigenvectors_npz)
from propwhirl import fileio
from propwhirl import validate as v
from propwhirl.analysis.naming import mode_content, mode_names, whirl
from propwhirl.analysis.participation import (ModeParticipation, branch_point_shape, events_csv,
                                              events_table, participation_lines,
                                              with_participation)
from propwhirl.analysis.reduced import choose_method, reduced_engine_analysis
from propwhirl.analysis.summary import (FlutterSummary, Reference, flutter_summary, reference,
                                        text_table)
from propwhirl.model import validity
from propwhirl.model.protocol import DofMap, Model, PropellerDofs

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
        lines = [f"{self.model_name}: instabilities between {self.sweep.V[0]:g} and {self.sweep.V[-1]:g} m/s"]
        rows = [[e.kind, e.event, self.describe(e.label), _leading(e), e.whirl or "-",
                 f"{e.V:.2f}", f"{e.frequency_hz:.3f}"] for e in self.events]
        table = text_table(rows, ["type", "event", "mode (content at V0)", "propeller", "whirl",
                                  "V [m/s]", "f [Hz]"], "lllllrr")
        lines += ["  " + line for line in table.splitlines()]
        lines += participation_lines(self.events, "  ")
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
        }

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> "ModelAnalysis":
        """The analysis of a dict written by :meth:`to_dict`, checked: format and version,
        every key, types, shapes (T speeds, n modes), finite numbers, mode ids and names, the
        DOF map against the sweep's states, the saved critical instability against the events.
        Anything else is an :class:`~propwhirl.validate.InputError` naming the key.

        A dict without "format" and "format_version" (written before they were introduced,
        otherwise the same layout) is read as version 1."""
        return _analysis_from_dict(d)

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
        path = Path(path)
        d = self.to_dict(include_eigenvectors=False)
        npz = None
        if include_eigenvectors:
            npz = eigenvectors_path(path)
            d["eigenvectors_file"] = npz.name
        try:
            text = json.dumps(d, allow_nan=False)
        except ValueError:
            raise v.InputError(f"cannot save the analysis to {str(path)!r}: "
                               f"{_non_finite_key(d)} is not a finite number") from None
        if npz is not None:
            try:
                data = eigenvectors_npz(self.sweep)
            except v.InputError as exc:
                raise v.InputError(f"cannot save the analysis to {str(path)!r}: {exc}") from None
            try:
                fileio.write_bytes(npz, data, what="eigenvector file")
            except v.InputError as exc:     # name the file asked for (the JSON is untouched)
                why = str(exc).removeprefix(f"cannot write eigenvector file {str(npz)!r}: ")
                raise v.InputError(f"cannot write analysis file {str(path)!r}: {why} (writing "
                                   f"its eigenvectors to {npz.name})") from None
        fileio.write_text(path, text, what="analysis file")


#: The "format" of an analysis file and the version this propwhirl writes and reads.
FORMAT = "propwhirl-analysis"
FORMAT_VERSION = 2
#: Versions :func:`load` reads (2 added the propellers' participation at each event, the
#: summary's reference and the eigenvector file).
READABLE_VERSIONS = (1, 2)

_EVENT_KINDS = ("flutter", "divergence")
_EVENTS = ("onset", "recovery", "frequency-zero", "unstable-at-start")
_WHIRL = ("forward", "backward", "planar")


def _finite_or_none(x: float | None) -> float | None:
    return None if x is None or not np.isfinite(x) else float(x)


def _event_dict(e: Instability) -> dict[str, Any]:
    d = {f.name: getattr(e, f.name) for f in fields(e)}
    d["benignity"] = _finite_or_none(e.benignity)
    d["participation"] = None if e.participation is None else e.participation.to_dict()
    return d


def _non_finite_key(obj: Any, where: str = "") -> str:
    """The dotted key of the first non-finite number in a JSON-able document."""
    if isinstance(obj, dict):
        for k, x in obj.items():
            found = _non_finite_key(x, f"{where}.{k}" if where else str(k))
            if found:
                return found
    elif isinstance(obj, (list, tuple)):
        for i, x in enumerate(obj):
            found = _non_finite_key(x, f"{where}[{i}]")
            if found:
                return found
    elif isinstance(obj, float) and not np.isfinite(obj):
        return where or "the value"
    return ""


def _event_from_dict(d: Any, where: str, sweep: Sweep) -> Instability:
    r = SavedDict(d, where, ("kind", "event", "mode", "label", "V", "frequency_hz"),
                  ("whirl", "benignity", "participation"))
    mode = r.integer("mode", 0, sweep.n_modes - 1)
    label = r.string("label")
    if label != sweep.mode_labels[mode]:
        raise v.InputError(f"{where}.label = {label!r} is not the name of mode {mode} in the "
                           f"sweep ({sweep.mode_labels[mode]!r})")
    return Instability(r.string("kind", _EVENT_KINDS), r.string("event", _EVENTS), mode, label,
                       r.number("V"), r.number("frequency_hz"),
                       r.string("whirl", _WHIRL, optional=True) if r.has("whirl") else None,
                       r.number("benignity", optional=True) if r.has("benignity") else None,
                       None if not r.has("participation") or r.raw("participation") is None
                       else ModeParticipation.from_dict(r.raw("participation"),
                                                        f"{where}.participation"))


def _dof_map_from_dict(d: Any, sweep: Sweep) -> DofMap:
    keys = ("q_labels", "q_kinds", "q_node", "q_propeller", "w_labels", "w_node", "node_y",
            "propellers")
    r = SavedDict(d, "dof_map", keys)
    n_dof = len(r.strings("q_labels"))
    props = r.raw("propellers")
    if not isinstance(props, list):
        raise v.InputError("dof_map.propellers: must be a list")
    dofs = []
    for i, p in enumerate(props):
        pr = SavedDict(p, f"dof_map.propellers[{i}]",
                       ("number", "theta", "psi", "rotation", "spinning", "y", "node"))
        spinning = pr.raw("spinning")
        if not isinstance(spinning, bool):
            raise v.InputError(f"{pr.name('spinning')}: must be true or false")
        node = pr.raw("node")
        dofs.append(PropellerDofs(
            pr.integer("number", 0), pr.integer("theta", 0, n_dof - 1),
            pr.integer("psi", 0, n_dof - 1), pr.integer("rotation", -1, 1), spinning,
            pr.number("y", optional=True), None if node is None else pr.integer("node", 0)))
    kw = dict(q_labels=r.strings("q_labels"), q_kinds=r.strings("q_kinds"),
              q_node=tuple(int(k) for k in r.array("q_node", int)),
              q_propeller=tuple(int(k) for k in r.array("q_propeller", int)),
              w_labels=r.strings("w_labels"),
              w_node=tuple(int(k) for k in r.array("w_node", int)),
              propellers=tuple(dofs), node_y=tuple(float(y) for y in r.array("node_y")))
    try:
        dm = DofMap(**kw)
    except v.InputError as exc:
        raise v.InputError(f"dof_map: {exc}") from None
    if dm.state_labels != sweep.state_labels:
        raise v.InputError(f"dof_map: its {dm.n_states} states do not match the sweep's "
                           f"{len(sweep.state_labels)} state labels")
    return dm


def _content_from_dict(d: Any, sweep: Sweep) -> dict[str, dict[str, float]]:
    if not isinstance(d, dict):
        raise v.InputError("content: must be an object {mode name: {group: share}}")
    out = {}
    for label, shares in d.items():
        if label not in sweep.mode_labels:
            raise v.InputError(f"content: {label!r} is not a mode of the sweep")
        r = SavedDict(shares, f"content.{label}", (), tuple(shares) if isinstance(shares, dict)
                      else ())
        out[label] = {g: r.number(g) for g in shares}
    return out


def _analysis_from_dict(d: Any) -> ModelAnalysis:
    keys = ("model_name", "events", "critical", "dof_map", "content", "sweep")
    r = SavedDict(d, "", keys, ("format", "format_version", "warnings", "reference",
                                "eigenvectors_file"))
    if r.has("format") or r.has("format_version"):
        got = r.raw("format") if r.has("format") else None
        if got != FORMAT:
            raise v.InputError(f"format = {got!r} is invalid: not a propwhirl analysis file "
                               f"(format {FORMAT!r})")
        if not r.has("format_version"):
            raise v.InputError("missing key 'format_version'")
        version = r.raw("format_version")
        if version not in READABLE_VERSIONS or isinstance(version, bool):
            raise v.InputError(f"format_version = {version!r} is not supported: this propwhirl "
                               f"reads versions {', '.join(map(str, READABLE_VERSIONS))}")
    sweep = Sweep.from_dict(r.raw("sweep"))
    if not isinstance(r.raw("events"), list):
        raise v.InputError("events: must be a list")
    events = tuple(_event_from_dict(e, f"events[{i}]", sweep)
                   for i, e in enumerate(r.raw("events")))
    dm = None if r.raw("dof_map") is None else _dof_map_from_dict(r.raw("dof_map"), sweep)
    notes = r.raw("warnings") if r.has("warnings") else []
    if not isinstance(notes, list) or not all(isinstance(w, str) for w in notes):
        raise v.InputError("warnings: must be a list of strings")
    ref = r.raw("reference") if r.has("reference") else None
    if r.has("eigenvectors_file"):
        name = r.raw("eigenvectors_file")
        if not isinstance(name, str) or not name or Path(name).name != name or name in (".", ".."):
            raise v.InputError(f"eigenvectors_file = {name!r} is invalid: must be the name of a "
                               "file beside the analysis file")
    a = ModelAnalysis(r.string("model_name"), sweep, events,
                      content=_content_from_dict(r.raw("content"), sweep), dof_map=dm,
                      warnings=tuple(notes),
                      reference=None if ref is None else Reference.from_dict(ref))
    c = a.critical
    if r.raw("critical") != (None if c is None else _event_dict(c)):
        raise v.InputError("critical: does not match the critical instability of the events")
    return a


def _refuse_constant(name: str) -> Any:
    raise v.InputError(f"holds {name}, which an analysis file must not (numbers are finite)")


def load(path: str | Path) -> ModelAnalysis:
    """Re-read an analysis written by :meth:`ModelAnalysis.save` (with its eigenvectors when
    the file names an eigenvector file and that file is beside it; without them otherwise).

    The file is checked throughout (:meth:`ModelAnalysis.from_dict`): an empty, truncated or
    non-JSON file, another format or version, a missing key, a wrong type, NaN or infinity,
    inconsistent shapes is an :class:`~propwhirl.validate.InputError` of one line starting
    with the path.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from propwhirl.analysis import analyse, load
    >>> from propwhirl.cases.ch09_baseline import isolated_baseline_propeller
    >>> a = analyse(isolated_baseline_propeller(), speeds=[100.0, 200.0, 250.0])
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "a.json"
    >>> a.save(path)
    >>> load(path).critical == a.critical
    True
    """
    path = Path(path)
    text = fileio.read_text(path, "analysis file")
    try:
        doc = json.loads(text, parse_constant=_refuse_constant)
    except json.JSONDecodeError as exc:
        end = " (the file ends early: truncated?)" if exc.pos >= len(text.rstrip()) else ""
        what = exc.msg[:-3] if exc.msg.endswith(" at") else exc.msg   # "... starting at"
        raise v.InputError(f"{path}: not valid JSON: {what} (line {exc.lineno}, column "
                           f"{exc.colno}){end}") from None
    except RecursionError:
        raise v.InputError(f"{path}: not an analysis file: nested too deeply") from None
    except ValueError as exc:  # InputError from _refuse_constant, too-long integers
        raise v.InputError(f"{path}: not an analysis file: {exc}") from None
    try:
        a = ModelAnalysis.from_dict(doc)
    except v.InputError as exc:
        raise v.InputError(f"{path}: {exc}") from None
    except RecursionError:
        raise v.InputError(f"{path}: not an analysis file: nested too deeply") from None
    name = doc.get("eigenvectors_file")
    if name is not None and a.sweep.eigenvectors is None and (path.parent / name).is_file():
        X = read_eigenvectors(path.parent / name, a.sweep)
        a = replace(a, sweep=replace(a.sweep, eigenvectors=X))
    return a


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
    method : {"auto", "dense", "reduced"}, optional
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
    if choose_method(model, method) == "reduced":
        run = reduced_engine_analysis(model, grid, displacement=dm.displacement,
                                      state_labels=dm.state_labels, options=options, xtol=xtol,
                                      vgf=bool(vgf))
        an, matrix_fn, basis = run.analysis, run.model.state_matrix, run.model.dof_basis
        lift = run.model.lift
    else:
        an = engine_analyse(model.state_matrix, grid, displacement=dm.displacement,
                            state_labels=dm.state_labels, options=options, xtol=xtol,
                            **({"initial_step": None} if vgf else {}))
        matrix_fn, basis, lift = model.state_matrix, None, None
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
    events.sort(key=lambda e: (e.V, e.mode))
    notes = validity.analysis_warnings(
        model, (float(sw.V[0]), float(sw.V[-1])),
        [(e.V, f"{e.kind} {e.event} of {e.label}") for e in events],
        any(e.event in UNSTABLE_EVENTS for e in events))
    try:
        ref = reference(model)
    except v.InputError:                     # a model of another kind: no summary reference
        ref = None
    return ModelAnalysis(model.name, sw, tuple(events), an.criticals,
                         mode_content(model, sw, names), dm, notes, ref)


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
