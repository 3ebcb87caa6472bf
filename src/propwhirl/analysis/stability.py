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
of the critical instability (:mod:`propwhirl.analysis.events`, with :class:`Instability`;
both re-exported here).  :class:`ModelAnalysis` is a :class:`~propwhirl.results.Result`: saved
and re-read with :meth:`ModelAnalysis.save` / :meth:`ModelAnalysis.load` (the analysis file,
format ``propwhirl.analysis/3``, defined in the class; ``load``, ``FORMAT``,
``FORMAT_VERSION``, ``READABLE_VERSIONS`` and ``eigenvectors_path`` are kept here under the
names of earlier releases).
"""
from __future__ import annotations

import json
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any, ClassVar

import numpy as np

from propwhirl import fileio
from propwhirl import validate as v
from propwhirl.analysis.events import (UNSTABLE_EVENTS, Exclusion, Instability,  # noqa: F401
                                       critical, describe_critical)
from propwhirl.analysis import mach_check
from propwhirl.analysis.naming import (event_label, mode_content, named_modes, whirl,
                                      with_content)
from propwhirl.analysis.participation import (ModeParticipation, branch_point_shape,  # noqa: F401
                                              events_csv, events_table, participation_lines,
                                              with_participation)
from propwhirl.analysis.pk import DLM_NOTE
from propwhirl.analysis.pk_events import pk_instabilities
from propwhirl.analysis.reduced import choose_method
from propwhirl.analysis.runners import Job, Tracked, track
from propwhirl.model.aerodynamics import compressibility
from propwhirl.model.aerodynamics.dlm import DlmTables, check_tables, strip_twin
from propwhirl.model.aerodynamics.dlm_rfa import RFA_NOTE, extrapolation_notes
from propwhirl.analysis.summary import (FiniteState, FlutterSummary, MethodComparison,
                                        Reference, aero_model_of, compare_methods,
                                        flutter_summary, reference, text_table)
from propwhirl.engine import XTOL, Criticals, Sweep, TrackingOptions
from propwhirl.engine.eigensolve import one_blas_thread
from propwhirl.engine.options import check_speeds
from propwhirl.engine.results import (eigenvectors_npz, eigenvectors_path,  # noqa: F401
                                      read_eigenvectors)
from propwhirl.model.aerodynamics import validity
from propwhirl.model.protocol import DofMap, HubDofs, Model, PropellerDofs
from propwhirl.results import Result, SavedDict, non_finite_key

#: Default airspeed grid of the thesis's analyses (0–350 m/s; the engine refines it) [m/s]
DEFAULT_SPEEDS = np.arange(1.0, 351.0, 10.0)


@dataclass
class ModelAnalysis(Result):
    """A labelled sweep and its instabilities (sorted by speed).

    A :class:`~propwhirl.results.Result`: :meth:`save` / :meth:`load` write and re-read the
    analysis file (format ``propwhirl.analysis/3``; the files of earlier releases,
    ``"propwhirl-analysis"`` with ``format_version`` 1 or 2 or without a format, still load).
    :func:`~propwhirl.analysis.analyse` makes it; :attr:`critical` is the critical
    instability, :meth:`summary` the text report.

    Attributes
    ----------
    model_name : str
        The analysed model's name.
    sweep : Sweep
        The tracked eigenvalues λ [1/s] along the speeds V [m/s], modes named.
    events : tuple of Instability
        Every instability event, sorted by speed [m/s].
    criticals : Criticals or None
        The engine's crossings (with their eigenvectors; None when re-read).
    content : dict of str to dict of str to float
        Mode label → share [-] of its kinetic energy at the first speed per group of degrees
        of freedom ("bending": h, φ; "torsion": α; "pitch", "yaw": propeller θ, ψ; "plunge").
    dof_map : DofMap or None
        What each state of the analysed model is (wing node and DOF, propeller, lag state).
    warnings : tuple of str
        Results outside the methods' validity, one line each
        (:mod:`propwhirl.model.aerodynamics.validity`: Mach above 0.7 or supersonic, supersonic
        propeller tips).
    reference : Reference or None
        Reference length [m], density [kg/m³] and speed of sound [m/s] of the flutter summary.
    finite_state : FiniteState or None
        With method="pk" (the events are then the p-k method's): the finite-state events of the
        same tracked modes; None otherwise.
    thesis_names : dict of str to str
        Mode name → the thesis's name of the mode ("backward 2") where they differ (several
        propellers, :func:`propwhirl.analysis.naming.named_modes`): :meth:`first` takes either;
        not saved.

    Examples
    --------
    >>> from propwhirl.analysis import analyse
    >>> from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
    >>> a = analyse(wingtip_propeller_wing())
    >>> [(e.kind, e.event, e.label, round(e.V, 1)) for e in a.events]      # doctest: +NORMALIZE_WHITESPACE
    [('divergence', 'onset', 'wing 1', 143.2), ('flutter', 'onset', 'forward 1', 159.4),
     ('flutter', 'onset', 'backward 1', 294.8), ('divergence', 'frequency-zero', 'forward 1', 320.9)]
    >>> a.critical.label, a.describe("forward 1"), len(a.warnings)
    ('wing 1', 'forward 1 (yaw)', 4)
    >>> print(a.warnings[2])                 # compressibility below Mach 0.7 (issue 37)
    V = 143.15 m/s (divergence onset of wing 1) is Mach 0.43, where compressibility raises the strips' lift slope by 11 % (Prandtl-Glauert): with compressible strips it is at 137.31 m/s (-4.1 %; the incompressible strips are unconservative here); set the wing's compressibility = "prandtl-glauert"
    """

    KIND: ClassVar[str] = "analysis"
    #: 3: the format tag ``propwhirl.analysis/3`` (the layout of version 2); 2 added the
    #: propellers' participation at each event, the summary's reference and the eigenvector
    #: file; 1: the first release
    VERSION: ClassVar[int] = 3
    READABLE: ClassVar[tuple[int, ...]] = (1, 2, 3)
    OLD_FORMATS: ClassVar[Mapping[str, Any]] = {
        "propwhirl-analysis": ("format_version", (1, 2))}
    UNTAGGED: ClassVar[int | None] = 1
    WHAT: ClassVar[str] = "analysis file"

    model_name: str
    sweep: Sweep
    events: tuple[Instability, ...]
    criticals: Criticals | None = field(default=None, repr=False)
    #: mode label -> share of its kinetic energy at the first speed per group of degrees of
    #: freedom ("bending": h, φ; "torsion": α; "pitch", "yaw": propeller θ, ψ; "plunge")
    content: dict[str, dict[str, float]] = field(default_factory=dict)
    #: what each state of the analysed model is (wing node and DOF, propeller, lag state)
    dof_map: DofMap | None = field(default=None, repr=False)
    #: results outside the methods' validity, one line each (:mod:`propwhirl.model.aerodynamics.validity`:
    #: Mach above 0.7 or supersonic, supersonic propeller tips); saved and re-read
    warnings: tuple[str, ...] = ()
    #: reference length, density and speed of sound of the flutter summary (saved and re-read)
    reference: Reference | None = None
    #: with method="pk" (the events are then the p-k method's): the finite-state events of the
    #: same tracked modes and their aerodynamics (saved and re-read); None otherwise
    finite_state: FiniteState | None = None
    #: mode name -> the thesis's name of the mode ("backward 2") where they differ (several
    #: propellers, :func:`propwhirl.analysis.naming.named_modes`): :meth:`first` takes either;
    #: not saved (an analysis re-read from a file knows its names only)
    thesis_names: dict[str, str] = field(default_factory=dict, repr=False, compare=False)

    def method_comparison(self) -> MethodComparison | None:
        """The p-k events beside the finite-state ones (:func:`compare_methods`: V and f by
        each, their differences), or None unless analysed with method="pk"."""
        if self.finite_state is None:
            return None
        out = compare_methods(self.events, self.finite_state)
        return replace(out, exact="p-k, doublet-lattice panels") if self.doublet_lattice else out

    def describe(self, label: str) -> str:
        """'label (dominant content)', e.g. 'wing 2 (torsion)'
        (:func:`~propwhirl.analysis.naming.with_content`)."""
        c = self.content.get(label)
        top = max(c, key=lambda g: c[g]) if c else ""
        # a modal structure's coordinates ("modal") say nothing of what moves: no content
        return with_content(label, top) if top and top != "modal" else label

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
        """The lowest-speed event of the mode named `label` (optionally of one kind); `label`
        may also be the thesis's name of the mode (:attr:`thesis_names`: "backward 2")."""
        hits = [e for e in self.events
                if label in (e.label, self.thesis_names.get(e.label)) and e.event == event and (kind is None or e.kind == kind)]
        return min(hits, key=lambda e: e.V) if hits else None

    @property
    def doublet_lattice(self) -> bool:
        """Whether the p-k events come from doublet-lattice wing aerodynamics (the analysis's
        note saying so, :data:`propwhirl.analysis.pk.DLM_NOTE`, is saved with it) or from
        the Roger state space of doublet-lattice wing aerodynamics
        (:data:`propwhirl.model.aerodynamics.dlm_rfa.RFA_NOTE`)."""
        return any(w.startswith((DLM_NOTE, RFA_NOTE)) for w in self.warnings)

    def summary(self) -> str:
        """The instabilities as a text table (the propeller column names the propeller whose
        whirl is given: the one with the largest θ–ψ amplitude, numbered from 1; '-' when every
        propeller's share is below 0.5 %), each event's
        propeller participation, and the critical instability (last line)."""
        how = ((" (Roger state space of doublet-lattice wing aerodynamics)"
                if self.doublet_lattice else "") if self.finite_state is None else
               " (p-k method, doublet-lattice wing aerodynamics)" if self.doublet_lattice else
               " (p-k method, exact Theodorsen function)")
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

    # ------------------------------------------------------------------ the analysis file
    def to_dict(self, include_eigenvectors: bool = False) -> dict[str, Any]:
        """The analysis as a JSON-able dict (the document :meth:`save` writes, format
        :data:`FORMAT`), the sweep with its eigenvectors only with ``include_eigenvectors``;
        a non-finite benignity becomes None."""
        d = {"format": self.format_name(), **self.encode()}
        if include_eigenvectors:
            d["sweep"] = self.sweep.to_dict(include_eigenvectors=True)
        return d

    def encode(self) -> dict[str, Any]:
        c = self.critical
        pk = {} if self.finite_state is None else {
            "finite_state": {"aero_model": self.finite_state.aero_model,
                             "events": [e.to_dict() for e in self.finite_state.events]},
            "method_comparison": self.method_comparison().to_dict()}
        return {
            "model_name": self.model_name,
            "events": [e.to_dict() for e in self.events],
            "critical": None if c is None else c.to_dict(),
            "dof_map": None if self.dof_map is None else self.dof_map.to_dict(),
            "content": self.content,
            "sweep": self.sweep.to_dict(include_eigenvectors=False),
            "warnings": list(self.warnings),
            "reference": None if self.reference is None else self.reference.to_dict(),
            **pk,
        }

    @classmethod
    def from_dict(cls, d: Any, where: str = "") -> "ModelAnalysis":
        """The analysis of a dict written by :meth:`to_dict`, checked: format and version
        (:data:`READABLE_VERSIONS`; an older format name, or none, is an older version), every
        key, types, shapes (T speeds, n modes), finite numbers, mode ids and names, the DOF
        map against the sweep's states, the saved critical instability against the events.
        Anything else is an :class:`~propwhirl.validate.InputError` naming the key."""
        return super().from_dict(d, where)

    @classmethod
    def decode(cls, d: Mapping[str, Any], version: int, where: str = "") -> "ModelAnalysis":
        keys = ("model_name", "events", "critical", "dof_map", "content", "sweep")
        r = SavedDict(d, where, keys, ("warnings", "reference", "eigenvectors_file",
                                       "finite_state", "method_comparison"))
        sweep = Sweep.from_dict(r.raw("sweep"), r.name("sweep"))
        events = _events_from(r, "events", sweep)
        dm = None if r.raw("dof_map") is None else _dof_map_from_dict(r.raw("dof_map"), sweep)
        notes = r.raw("warnings") if r.has("warnings") else []
        if not isinstance(notes, list) or not all(isinstance(w, str) for w in notes):
            raise v.InputError(f"{r.name('warnings')}: must be a list of strings")
        ref = r.raw("reference") if r.has("reference") else None
        if r.has("eigenvectors_file"):
            name = r.raw("eigenvectors_file")
            if (not isinstance(name, str) or not name or Path(name).name != name
                    or name in (".", "..")):
                raise v.InputError(f"{r.name('eigenvectors_file')} = {name!r} is invalid: must "
                                   "be the name of a file beside the analysis file")
        a = cls(r.string("model_name"), sweep, events,
                content=_content_from_dict(r.raw("content"), sweep), dof_map=dm,
                warnings=tuple(notes),
                reference=None if ref is None else Reference.from_dict(ref, r.name("reference")),
                finite_state=_finite_state_from_dict(r, sweep))
        c = a.critical
        if r.raw("critical") != (None if c is None else c.to_dict()):
            raise v.InputError(f"{r.name('critical')}: does not match the critical instability "
                               "of the events")
        if r.has("method_comparison") != (a.finite_state is not None) or (
                r.has("method_comparison")
                and r.raw("method_comparison") != a.method_comparison().to_dict()):
            raise v.InputError(f"{r.name('method_comparison')}: does not match the events and "
                               "finite_state (both or neither must be given)")
        return a

    def save(self, path: str | Path, include_eigenvectors: bool = False) -> Path:
        """Write the analysis as JSON (V-g-f table, labels, instabilities and their propeller
        participation); with ``include_eigenvectors`` also the eigenvectors of every speed, in
        a NumPy ``.npz`` file beside it (:func:`eigenvectors_path`: ``a.json`` →
        ``a.eigenvectors.npz``), which the JSON names.  The JSON stays readable on its own:
        :func:`load` without the npz gives the analysis without eigenvectors.

        Each file is replaced atomically (:func:`propwhirl.fileio.write_text`: a full disk or a
        Ctrl-C leaves the old file or none, never a partial one; the npz is written first).
        JSON without NaN or infinity: a non-finite number is an
        :class:`~propwhirl.validate.InputError` naming the key, and nothing is written."""
        path = Path(v.file_path("path", path, f"the {self.WHAT} to write"))
        d = self.to_dict()
        npz = None
        if include_eigenvectors:
            npz = eigenvectors_path(path)
            d["eigenvectors_file"] = npz.name
        bad = non_finite_key(d)
        if bad:
            raise v.InputError(f"cannot save the analysis to {fileio.quoted(path)}: {bad} is "
                               "not a finite number")
        text = json.dumps(d, allow_nan=False)
        if npz is not None:
            try:
                data = eigenvectors_npz(self.sweep)
            except v.InputError as exc:
                raise v.InputError(f"cannot save the analysis to {fileio.quoted(path)}: {exc}"
                                   ) from None
            try:
                fileio.write_bytes(npz, data, what="eigenvector file")
            except v.InputError as exc:     # name the file asked for (the JSON is untouched)
                why = str(exc).removeprefix(f"cannot write eigenvector file "
                                            f"{fileio.quoted(npz)}: ")
                raise v.InputError(f"cannot write analysis file {fileio.quoted(path)}: {why} "
                                   f"(writing its eigenvectors to {fileio.shown(npz.name)})"
                                   ) from None
        return fileio.write_text(path, text, what="analysis file")

    @classmethod
    def load(cls, path: str | Path) -> "ModelAnalysis":
        """Re-read an analysis written by :meth:`save` (any readable version), with its
        eigenvectors when the file names an eigenvector file and that file is beside it
        (:func:`~propwhirl.engine.results.read_eigenvectors`: checked against the analysis
        before it is read), without them otherwise.

        The file is checked throughout (:meth:`from_dict`): an empty, truncated or non-JSON
        file, another kind or version, a missing key, a wrong type, NaN or infinity,
        inconsistent shapes is an :class:`~propwhirl.validate.InputError` of one line starting
        with the path.

        Examples
        --------
        >>> import tempfile, pathlib
        >>> from propwhirl.analysis import ModelAnalysis, analyse
        >>> from propwhirl.cases.ch09_baseline import isolated_baseline_propeller
        >>> a = analyse(isolated_baseline_propeller(), speeds=[100.0, 200.0, 250.0])
        >>> path = pathlib.Path(tempfile.mkdtemp()) / "a.json"
        >>> _ = a.save(path)
        >>> ModelAnalysis.load(path).critical == a.critical
        True
        """
        return super().load(path)

    def loaded_from(self, path: Path, doc: Mapping[str, Any]) -> "ModelAnalysis":
        """With the eigenvectors of the file `doc` names, when it is beside `path`."""
        name = doc.get("eigenvectors_file")
        if name is None or self.sweep.eigenvectors is not None or not _is_file(path.parent / name):
            return self
        X = read_eigenvectors(path.parent / name, self.sweep, fileio.shown(path.parent / name))
        return replace(self, sweep=replace(self.sweep, eigenvectors=X))


#: The format tag of the analysis file this propwhirl writes, its version and the versions it
#: reads (:class:`ModelAnalysis`; kept under the names of earlier releases).
FORMAT = ModelAnalysis.format_name()
FORMAT_VERSION = ModelAnalysis.VERSION
READABLE_VERSIONS = ModelAnalysis.READABLE


def load(path: str | Path) -> ModelAnalysis:
    """Re-read an analysis file: :meth:`ModelAnalysis.load` (this function is its alias, the
    name scripts of earlier releases use).

    Parameters
    ----------
    path : str or Path
        The analysis file (JSON) written by :meth:`ModelAnalysis.save`; its eigenvectors are
        read from the ``.npz`` beside it when it was saved with them.

    Returns
    -------
    ModelAnalysis
        The analysis as saved (its events, sweep and names; no engine crossings).

    Examples
    --------
    >>> import pathlib, tempfile
    >>> from propwhirl.analysis import analyse, load
    >>> from propwhirl.cases.ch09_baseline import isolated_baseline_propeller
    >>> a = analyse(isolated_baseline_propeller(), speeds=[100.0, 200.0, 250.0])
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = a.save(pathlib.Path(folder) / "a.json")
    ...     again = load(path)
    >>> again.critical == a.critical, round(again.critical.V, 1)
    (True, 221.5)
    """
    return ModelAnalysis.load(path)


def _is_file(path: Path) -> bool:
    """Whether `path` is a file; an error of the operating system (a name too long, no
    permission for the folder) is one line naming it."""
    try:
        return path.is_file()
    except OSError as exc:
        raise v.InputError(f"cannot read eigenvector file {fileio.quoted(path)}: "
                           f"{fileio.reason(exc)}") from None


def _events_from(r: SavedDict, key: str, sweep: Sweep) -> tuple[Instability, ...]:
    if not isinstance(r.raw(key), list):
        raise v.InputError(f"{r.name(key)}: must be a list")
    return tuple(Instability.from_dict(e, f"{r.name(key)}[{i}]", sweep.mode_labels)
                 for i, e in enumerate(r.raw(key)))


def _dof_map_from_dict(d: Any, sweep: Sweep) -> DofMap:
    """The DOF map of an analysis file, checked against the sweep's states."""
    keys = ("q_labels", "q_kinds", "q_node", "q_propeller", "w_labels", "w_node", "node_y",
            "propellers")
    r = SavedDict(d, "dof_map", keys, ("hubs",))
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
              propellers=tuple(dofs), node_y=tuple(float(y) for y in r.array("node_y")),
              hubs=_hubs_from(r, n_dof))
    try:
        dm = DofMap(**kw)
    except v.InputError as exc:
        raise v.InputError(f"dof_map: {exc}") from None
    if dm.state_labels != sweep.state_labels:
        raise v.InputError(f"dof_map: its {dm.n_states} states do not match the sweep's "
                           f"{len(sweep.state_labels)} state labels")
    return dm


def _hubs_from(r: SavedDict, n_dof: int) -> tuple[HubDofs, ...]:
    """The DOF map's hubs (key "hubs": a modal structure's on-grid propellers; absent in
    every other map), checked."""
    if not r.has("hubs"):
        return ()
    if not isinstance(r.raw("hubs"), list):
        raise v.InputError("dof_map.hubs: must be a list")
    out = []
    for i, h in enumerate(r.raw("hubs")):
        hr = SavedDict(h, f"dof_map.hubs[{i}]", ("number", "pitch", "yaw", "inertia",
                                                 "rotation", "spinning", "y"),
                       ("heave", "twist", "coupling"))
        spinning = hr.raw("spinning")
        if not isinstance(spinning, bool):
            raise v.InputError(f"{hr.name('spinning')}: must be true or false")
        rows = [hr.array(k) for k in ("pitch", "yaw")]
        inertia = hr.array("inertia")
        for k, a, n in (("pitch", rows[0], n_dof), ("yaw", rows[1], n_dof),
                        ("inertia", inertia, 2)):
            if a.shape != (n,):
                raise v.InputError(f"{hr.name(k)}: must be a list of {n} numbers")
        wing = [tuple(float(x) for x in hr.array(k, shape=(n_dof,))) if hr.has(k) else ()
                for k in ("heave", "twist")]
        coupling = (tuple(tuple(float(c) for c in r) for r in hr.array(
            "coupling", ndim=2, shape=(2, 2))) if hr.has("coupling") else ())
        out.append(HubDofs(hr.integer("number", 0), tuple(float(x) for x in rows[0]),
                           tuple(float(x) for x in rows[1]),
                           (float(inertia[0]), float(inertia[1])),
                           hr.integer("rotation", -1, 1), spinning,
                           hr.number("y", optional=True), *wing, coupling))
    return tuple(out)


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


def _finite_state_from_dict(r: SavedDict, sweep: Sweep) -> FiniteState | None:
    """The finite-state events of a p-k analysis (key "finite_state", absent otherwise and in
    files written before it)."""
    if not r.has("finite_state"):
        return None
    f = r.sub("finite_state", ("aero_model", "events"))
    events = _events_from(f, "events", sweep)
    try:
        return FiniteState(f.string("aero_model"), events)
    except v.InputError as exc:
        raise v.InputError(f"finite_state: {exc}") from None


# ----------------------------------------------------------------------------- analyse
@one_blas_thread
def analyse(model: Model, speeds=None, *, xtol: float = XTOL, vgf: bool = False,
            options: TrackingOptions | None = None, method: str = "auto",
            progress: Callable[[int, int], None] | None = None,
            compressibility_check: bool = True,
            dlm_tables: DlmTables | None = None) -> ModelAnalysis:
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
        (default): reduced for every strip-theory wing model, kept where every crossing
        converged on the full-order model and every frequency-zero event's bracket holds the
        full-order branch point (:data:`~propwhirl.analysis.reduced.AUTO_NEEDS`), else the
        model is analysed again, dense; dense for the other models.  With "auto" a wing's
        sweep holds the modes below the reduction's cut-off only (give "dense" for V-g-f
        plots of every mode).  A wing with ``aero = "dlm"``: "auto" and "reduced" analyse its
        Roger state space (the lag states of the rational-function fit of Q(k, V/a)) on the
        in-vacuo modes below a cut-off and converge every crossing by the p-k method on Q(k)
        (:mod:`propwhirl.analysis.modal_dlm`: only critical speeds the p-k has), "dense" the
        Roger state space on every DOF (:mod:`propwhirl.model.aerodynamics.dlm_rfa`; modes far beyond the
        fit's reduced frequencies included), "pk" the p-k method on Q(k) itself.
    progress : callable, optional
        ``report(done, total)``: a wing with ``aero = "dlm"`` analysed on its Roger state space
        ("auto", "reduced", "dense") first computes the doublet-lattice AICs its fits at the
        first speeds read, their number known in advance (the fits' 20 reduced frequencies ×
        the Mach columns: :func:`~propwhirl.analysis.modal_dlm.compute_fit_aics`), and calls
        it before the first and after each; nothing else reports.  None (default): silent.
        The command line passes the stage of its spinner (:mod:`propwhirl.progress`).
    compressibility_check : bool, optional
        True (default): each onset and recovery of a wing with incompressible strips at Mach
        ≥ 0.2, and each near-neutral hump, recomputed from its own root with Prandtl–Glauert
        strips (a few sparse pencils per event, :mod:`propwhirl.analysis.mach_check`), a
        warning when it moves by 2 % or more.  The studies, which keep no warnings, pass False.
    dlm_tables : DlmTables, optional
        A wing with ``aero = "dlm"``: the doublet-lattice tables (AICs' Q(k, M) and their fits,
        :class:`~propwhirl.model.aerodynamics.dlm.DlmTables`) this analysis reads and fills.
        None (default): new ones, this analysis's own; a study passes one to all its analyses
        so that the variants of one planform compute their AICs once.

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
    if not isinstance(compressibility_check, (bool, np.bool_)):
        raise v.InputError(f"compressibility_check = {compressibility_check!r:.40} is invalid: "
                           "must be True or False")
    if options is not None and not isinstance(options, TrackingOptions):
        raise v.InputError(f"options = {options!r} is invalid: must be a TrackingOptions")
    if progress is not None and not callable(progress):
        raise v.InputError(f"progress = {progress!r:.60} is invalid: must be None or a callable "
                           "report(done, total)")
    compressibility.check_speeds(model, grid)   # matched Prandtl-Glauert strips: Mach <= 0.9
    tables = check_tables(dlm_tables)
    chosen = choose_method(model, method)
    # p-k: the strip twin tracks, names and starts the p-k modes (propwhirl.analysis.runners)
    finite = strip_twin(model) if chosen == "pk" else model
    dm = finite.dof_map()
    t = track(Job(model, finite, grid, xtol, bool(vgf), options, method == "auto", progress,
                  tables), chosen)
    sw = t.analysis.sweep
    names, thesis_names = named_modes(finite, sw, t.basis, t.in_vacuo, t.assembly)
    sw = sw.relabel(names)
    events = with_participation(finite, *_events(t, sw, names, dm), t.in_vacuo)
    finite_state, pk_notes = None, []
    if chosen == "pk":  # the tracked finite-state modes, their crossings by the exact p-k method
        finite_state = FiniteState(aero_model_of(model),
                                   tuple(sorted(events, key=lambda e: (e.V, e.mode))))
        events, basis = pk_instabilities(model, sw.eigenvalues[0], names, grid, xtol=xtol,
                                         notes=pk_notes, sweep=sw, mass=t.in_vacuo.M,
                                         tables=tables)
    events.sort(key=lambda e: (e.V, e.mode))
    notes = validity.analysis_warnings(
        model, (float(sw.V[0]), float(sw.V[-1])),
        [(e.V, f"{e.kind} {e.event} of {e.label}") for e in events],
        any(e.event in UNSTABLE_EVENTS for e in events))
    if chosen != "pk" and compressibility_check:   # each event's move, from its own root
        notes = tuple(notes) + mach_check.warnings(
            model, events, t.analysis.criticals.points if t.analysis.criticals else (), sw,
            t.assembly)
    elif compressibility_check:  # the p-k's events, by the p-k on the Prandtl-Glauert twin
        notes = tuple(notes) + mach_check.pk_warnings(model, events, float(sw.V[-1]), basis)
    notes = t.notes_first + tuple(notes) + tuple(
        f"V = {p.V:.2f} m/s ({p.kind} {p.direction} of {names[p.mode]}): not converged on the "
        "full-order model; the speed is the reduced model's (run method='dense' to check)"
        for p in t.unconverged) + tuple(pk_notes) + t.notes_last + (
        tuple(extrapolation_notes(model, events)) if t.extrapolation else ())
    try:
        ref = reference(model)
    except v.InputError:                     # a model of another kind: no summary reference
        ref = None
    return ModelAnalysis(model.name, sw, tuple(events), t.analysis.criticals,
                         mode_content(finite, sw, names, t.in_vacuo), dm, notes, ref,
                         finite_state, {a: b for a, b in zip(names, thesis_names) if a != b})


def _events(t: Tracked, sw: Sweep, names, dm: DofMap) -> tuple[list, list]:
    """The named events of a tracked analysis and each one's (shape, λ, V): the crossings,
    the modes unstable at the first speed and the frequency-zero events."""
    events, shapes = [], []
    for p in t.analysis.criticals.points:
        sense = whirl(dm, p.eigenvector, p.eigenvalue) if p.kind == "flutter" else None
        label = event_label(sw, names, p.mode, p.eigenvector, t.in_vacuo.M)  # a lag: its mode
        events.append(Instability(p.kind, p.direction, p.mode, label, float(p.V),
                                  float(p.frequency_hz), sense,
                                  None if p.benignity is None else float(p.benignity)))
        shapes.append((p.eigenvector, p.eigenvalue, float(p.V)))
    for k in t.analysis.criticals.unstable_at_start:
        lam0 = sw.eigenvalues[0, k]
        kind = "flutter" if abs(lam0.imag) > 0 else "divergence"
        events.append(Instability(kind, "unstable-at-start", int(k), names[k], float(sw.V[0]),
                                  float(abs(lam0.imag) / (2 * np.pi))))
        shapes.append((sw.eigenvectors[0, :, k], lam0, float(sw.V[0])))
    for p, shape in zip(t.fzero, t.fzero_shapes):
        label = event_label(sw, names, p.mode, shape[0], t.in_vacuo.M)
        events.append(Instability("divergence", "frequency-zero", p.mode, label, p.V, 0.0))
        shapes.append(shape)
    return events, shapes


#: Below this share of the mode's kinetic energy [-] in every propeller (0.5 %, printed as
#: 0 %), the summary's propeller column names none: the event is the wing's.
LEADING_SHARE_MIN = 0.005


def _leading(e: Instability) -> str:
    """'3 (y = 3.00 m)': the propeller with the largest θ–ψ amplitude at the event, or '-'
    (none, or every propeller's share below :data:`LEADING_SHARE_MIN`)."""
    part = e.participation
    p = None if part is None else part.leading
    if p is None or all(q.share < LEADING_SHARE_MIN for q in part.propellers):
        return "-"
    return p.name().removeprefix("propeller ")


def speed_and_frequency(event: Instability | None) -> tuple[float, float]:
    """(V [m/s], f [Hz]) of an event; NaN (reported as not computed) when there is none.

    Parameters
    ----------
    event : Instability or None
        The event.

    Returns
    -------
    V : float
        Its speed [m/s], or NaN.
    frequency_hz : float
        Its frequency [Hz], or NaN.

    Examples
    --------
    >>> from propwhirl.analysis import analyse, first_of_kind, speed_and_frequency
    >>> from propwhirl.cases.ch09_baseline import isolated_baseline_propeller
    >>> a = analyse(isolated_baseline_propeller(), speeds=[100.0, 200.0, 250.0])
    >>> V, f = speed_and_frequency(first_of_kind(a, "flutter"))
    >>> round(V, 1), round(f, 2)
    (221.5, 5.01)
    >>> speed_and_frequency(first_of_kind(a, "divergence"))      # none in this range
    (nan, nan)
    """
    if event is None:
        return float("nan"), float("nan")
    return event.V, event.frequency_hz


def first_of_kind(a: ModelAnalysis, kind: str, event: str = "onset") -> Instability | None:
    """The lowest-speed event of a kind ("flutter" or "divergence"), whatever the mode.

    Parameters
    ----------
    a : ModelAnalysis
        The analysis.
    kind : {"flutter", "divergence"}
        The kind of event.
    event : {"onset", "recovery", "frequency-zero", "unstable-at-start"}
        The event.

    Returns
    -------
    Instability or None
        The event of that kind at the lowest speed V [m/s]; None if there is none.

    Examples
    --------
    >>> from propwhirl.analysis import analyse, first_of_kind
    >>> from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
    >>> a = analyse(wingtip_propeller_wing())
    >>> e = first_of_kind(a, "flutter")
    >>> e.label, round(e.V, 2)
    ('forward 1', 159.39)
    >>> round(first_of_kind(a, "divergence", "frequency-zero").V, 2)
    320.94
    """
    hits = [e for e in a.events if e.kind == kind and e.event == event]
    return min(hits, key=lambda e: e.V) if hits else None
