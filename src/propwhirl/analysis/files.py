"""The analysis file: a :class:`~propwhirl.analysis.stability.ModelAnalysis` as JSON (and its
eigenvectors as a NumPy ``.npz`` beside it), written atomically and re-read with every key
checked.

:meth:`~propwhirl.analysis.stability.ModelAnalysis.save` calls :func:`save_analysis`,
:meth:`~propwhirl.analysis.stability.ModelAnalysis.from_dict` calls :func:`analysis_from_dict`;
:func:`load` re-reads a file.  The format (:data:`FORMAT`, version :data:`FORMAT_VERSION`,
readable versions :data:`READABLE_VERSIONS`) is defined here.  ``propwhirl.analysis.stability``
re-exports ``load``, ``FORMAT``, ``FORMAT_VERSION`` and ``eigenvectors_path`` (the paths users'
scripts import them from).
"""
from __future__ import annotations

import json
from dataclasses import fields, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from propwhirl import fileio
from propwhirl import validate as v
from propwhirl.analysis.participation import ModeParticipation
from propwhirl.analysis.summary import FiniteState, Reference
from propwhirl.engine import Sweep
from propwhirl.engine.results import (SavedDict, eigenvectors_npz, eigenvectors_path,
                                      read_eigenvectors)
from propwhirl.model.protocol import DofMap, PropellerDofs

if TYPE_CHECKING:  # pragma: no cover
    from propwhirl.analysis.stability import Instability, ModelAnalysis

__all__ = ["FORMAT", "FORMAT_VERSION", "READABLE_VERSIONS", "analysis_from_dict",
           "eigenvectors_path", "load", "save_analysis"]

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


def _event_dict(e: "Instability") -> dict[str, Any]:
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


def save_analysis(a: "ModelAnalysis", path: str | Path, include_eigenvectors: bool = False) -> None:
    """Write `a` as JSON to `path` (and its eigenvectors to :func:`eigenvectors_path` with
    ``include_eigenvectors``): :meth:`~propwhirl.analysis.stability.ModelAnalysis.save`,
    which documents the files."""
    path = Path(path)
    d = a.to_dict(include_eigenvectors=False)
    npz = None
    if include_eigenvectors:
        npz = eigenvectors_path(path)
        d["eigenvectors_file"] = npz.name
    try:
        text = json.dumps(d, allow_nan=False)
    except ValueError:
        raise v.InputError(f"cannot save the analysis to {fileio.quoted(path)}: "
                           f"{_non_finite_key(d)} is not a finite number") from None
    if npz is not None:
        try:
            data = eigenvectors_npz(a.sweep)
        except v.InputError as exc:
            raise v.InputError(f"cannot save the analysis to {fileio.quoted(path)}: {exc}"
                               ) from None
        try:
            fileio.write_bytes(npz, data, what="eigenvector file")
        except v.InputError as exc:     # name the file asked for (the JSON is untouched)
            why = str(exc).removeprefix(f"cannot write eigenvector file {fileio.quoted(npz)}: ")
            raise v.InputError(f"cannot write analysis file {fileio.quoted(path)}: {why} "
                               f"(writing its eigenvectors to {fileio.shown(npz.name)})"
                               ) from None
    fileio.write_text(path, text, what="analysis file")


def _event_from_dict(d: Any, where: str, sweep: Sweep) -> "Instability":
    from propwhirl.analysis.stability import Instability

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


def analysis_from_dict(d: Any) -> "ModelAnalysis":
    """The analysis of a dict written by :meth:`~propwhirl.analysis.stability.ModelAnalysis.to_dict`, checked (see
    :meth:`~propwhirl.analysis.stability.ModelAnalysis.from_dict`)."""
    from propwhirl.analysis.stability import ModelAnalysis

    keys = ("model_name", "events", "critical", "dof_map", "content", "sweep")
    r = SavedDict(d, "", keys, ("format", "format_version", "warnings", "reference",
                                "eigenvectors_file", "finite_state", "method_comparison"))
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
                      reference=None if ref is None else Reference.from_dict(ref),
                      finite_state=_finite_state_from_dict(r, sweep))
    c = a.critical
    if r.raw("critical") != (None if c is None else _event_dict(c)):
        raise v.InputError("critical: does not match the critical instability of the events")
    if r.has("method_comparison") != (a.finite_state is not None) or (
            r.has("method_comparison")
            and r.raw("method_comparison") != a.method_comparison().to_dict()):
        raise v.InputError("method_comparison: does not match the events and finite_state "
                           "(both or neither must be given)")
    return a


def _finite_state_from_dict(r: SavedDict, sweep: Sweep) -> FiniteState | None:
    """The finite-state events of a p-k analysis (key "finite_state", absent otherwise and in
    files written before it)."""
    if not r.has("finite_state"):
        return None
    f = r.sub("finite_state", ("aero_model", "events"))
    if not isinstance(f.raw("events"), list):
        raise v.InputError("finite_state.events: must be a list")
    events = tuple(_event_from_dict(e, f"finite_state.events[{i}]", sweep)
                   for i, e in enumerate(f.raw("events")))
    try:
        return FiniteState(f.string("aero_model"), events)
    except v.InputError as exc:
        raise v.InputError(f"finite_state: {exc}") from None


def _refuse_constant(name: str) -> Any:
    raise v.InputError(f"holds {name}, which an analysis file must not (numbers are finite)")


def load(path: str | Path) -> "ModelAnalysis":
    """Re-read an analysis written by :meth:`~propwhirl.analysis.stability.ModelAnalysis.save` (with its eigenvectors when
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
    where = fileio.shown(path)
    try:
        doc = json.loads(text, parse_constant=_refuse_constant)
    except json.JSONDecodeError as exc:
        end = " (the file ends early: truncated?)" if exc.pos >= len(text.rstrip()) else ""
        what = exc.msg[:-3] if exc.msg.endswith(" at") else exc.msg   # "... starting at"
        raise v.InputError(f"{where}: not valid JSON: {what} (line {exc.lineno}, column "
                           f"{exc.colno}){end}") from None
    except RecursionError:
        raise v.InputError(f"{where}: not an analysis file: nested too deeply") from None
    except ValueError as exc:  # InputError from _refuse_constant, too-long integers
        raise v.InputError(f"{where}: not an analysis file: {exc}") from None
    try:
        a = analysis_from_dict(doc)
    except v.InputError as exc:
        raise v.InputError(f"{where}: {exc}") from None
    except RecursionError:
        raise v.InputError(f"{where}: not an analysis file: nested too deeply") from None
    name = doc.get("eigenvectors_file")
    if name is not None and a.sweep.eigenvectors is None and _is_file(path.parent / name):
        X = read_eigenvectors(path.parent / name, a.sweep, fileio.shown(path.parent / name))
        a = replace(a, sweep=replace(a.sweep, eigenvectors=X))
    return a


def _is_file(path: Path) -> bool:
    """Whether `path` is a file; an error of the operating system (a name too long, no
    permission for the folder) is one line naming it."""
    try:
        return path.is_file()
    except OSError as exc:
        raise v.InputError(f"cannot read eigenvector file {fileio.quoted(path)}: "
                           f"{fileio.reason(exc)}") from None
