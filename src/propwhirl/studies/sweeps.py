"""Sweeps and maps of the critical speed of any model over one or two parameters.

:func:`sweep` varies one parameter path (:mod:`propwhirl.studies.paths`), :func:`map2d` two
(their outer product); each point is one analysis (:func:`propwhirl.analysis.stability.analyse`)
of the model's variant, and its critical instability is the one definition
(:func:`propwhirl.analysis.stability.critical`) — or, with ``static_divergence=False`` and/or
``low_speed=False``, the thesis's exclusions (:func:`propwhirl.studies.critical.critical_instability`,
the chapter-11 convention).  Per point the result holds the critical speed [m/s] and frequency
[Hz], its kind ("flutter", "divergence", "none"), event, mode (name and dominant content), the
whirl sense, the propeller that dominates it (the largest share of the mode's kinetic energy
among the flexibly mounted propellers, numbered from 1; 0 when none takes part) with its share,
and the wing's static divergence speed.

The analyses are independent: ``processes > 1`` runs them in the study pool
(:func:`propwhirl.studies.runner.map_analyses`, called in one place: :func:`run_points`).
Results are :class:`CriticalMap` objects, saved and loaded as JSON (everything) or CSV (one
tidy row per point), and a pandas DataFrame with :meth:`CriticalMap.to_dataframe`.
"""
from __future__ import annotations

import csv
import io
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, ClassVar, Mapping, Sequence

import numpy as np

from propwhirl import fileio, limits
from propwhirl import validate as v
from propwhirl.analysis.reduced import METHODS, choose_method
from propwhirl.analysis.stability import ModelAnalysis, analyse
from propwhirl.analysis.summary import text_table
from propwhirl.model.aerodynamics.dlm import DlmTables
from propwhirl.results import Result, SavedDict
from propwhirl.studies import paths as P
from propwhirl.studies.critical import (convention, critical_instability, static_divergence_speed,
                                        wing_divergence_predicate)
from propwhirl.studies import execution
from propwhirl.studies.execution import TaskError
from propwhirl.studies.partial import Checkpoint, PointFormat, check_checkpoint, content_digest
from propwhirl.progress import Cumulative
from propwhirl.studies.warmstart import warm_started_rows

#: Default accuracy of every critical speed of a study [m/s]
STUDY_XTOL = 0.01

#: The result of one point and its units ("" for text and dimensionless columns).
RESULT_UNITS: dict[str, str] = {
    "critical_speed": "m/s", "critical_frequency": "Hz", "critical_mode": "", "content": "",
    "kind": "", "event": "", "whirl": "", "propeller": "", "propeller_share": "",
    "static_divergence_speed": "m/s", "error": "",
}
_FLOAT_COLUMNS = ("critical_speed", "critical_frequency", "propeller_share", "static_divergence_speed")
_INT_COLUMNS = ("propeller",)

#: Format version of the saved maps.


# ============================================================================ one point
def _dominant_content(a: ModelAnalysis, label: str) -> str:
    """Dominant degree-of-freedom group of mode `label` at the first speed ("bending",
    "torsion", "pitch", "yaw"; "" when not recorded, e.g. real roots)."""
    c = a.content.get(label.rstrip("'"))
    return max(c, key=lambda g: c[g]) if c else ""


def evaluate(task: tuple) -> dict[str, Any]:
    """Analyse one model and return its result row (small: no sweep is sent back).

    task: (model, speeds [m/s] or None, xtol [m/s], static_divergence, low_speed[, method[,
    tables]]) — see :func:`propwhirl.studies.critical.critical_instability` for the two
    flags; method: that of :func:`propwhirl.analysis.stability.analyse` (default "auto");
    tables: the study's :class:`~propwhirl.model.aerodynamics.dlm.DlmTables`, shared by its
    analyses so that the variants of one doublet-lattice planform compute their AICs once
    (default: the analysis's own; sent to a worker process, a task's tables arrive empty).
    """
    return _evaluate(task)     # (a model keeps nothing of its analysis: no memory per point)


def _evaluate(task: tuple) -> dict[str, Any]:
    model, speeds, xtol, static_div, low_speed, *rest = task
    a = analyse(model, speeds, xtol=xtol, method=rest[0] if rest else "auto",
                compressibility_check=False,         # a point keeps no warnings
                dlm_tables=rest[1] if len(rest) > 1 else None)
    is_wing = wing_divergence_predicate(model, a)
    e = critical_instability(a, static_divergence=static_div, low_speed=low_speed,
                             is_wing_divergence=is_wing)
    lead = None
    if e is not None and e.participation is not None and e.participation.propellers:
        lead = max(e.participation.propellers, key=lambda p: p.share)
    return {
        "critical_speed": float("nan") if e is None else float(e.V),
        "critical_frequency": float("nan") if e is None else float(e.frequency_hz),
        "critical_mode": "" if e is None else e.label,
        "content": "" if e is None else _dominant_content(a, e.label),
        "kind": "none" if e is None else e.kind,
        "event": "" if e is None else e.event,
        "whirl": "" if e is None or e.whirl is None else e.whirl,
        "propeller": 0 if lead is None else int(lead.propeller),
        "propeller_share": float("nan") if lead is None else float(lead.share),
        "static_divergence_speed": static_divergence_speed(a, is_wing),
    }


def error_row(message: str) -> dict[str, Any]:
    """The result row of a point that could not be analysed (an invalid variant, or an analysis
    that failed): no instability, kind "error", the one-line message in ``error``."""
    row = {k: float("nan") if k in _FLOAT_COLUMNS else 0 if k in _INT_COLUMNS else ""
           for k in RESULT_UNITS}
    return {**row, "kind": "error", "error": str(message)}


# ---------------------------------------------------------------- a row in a partial-results file
#: The entries of a study's result row (:func:`evaluate`) as kept in a partial-results file:
#: numbers that may be NaN (null in the file), a count, and strings (with their possible
#: values where they are few).
_ROW_NUMBERS = ("critical_speed", "critical_frequency", "propeller_share", "static_divergence_speed")
_ROW_STRINGS: dict[str, tuple[str, ...]] = {
    "critical_mode": (), "content": (), "kind": ("flutter", "divergence", "none"),
    "event": ("", "onset", "recovery", "frequency-zero", "unstable-at-start"),
    "whirl": ("", "forward", "backward", "planar")}
#: Longest name of a mode or content group in a result row [characters].
_ROW_TEXT = 200


def _encode_row(row: Any) -> dict[str, Any]:
    """A study row as plain JSON: NaN numbers as null (the schema of :func:`_decode_row`)."""
    if not isinstance(row, Mapping):
        raise v.InputError(f"a study row must be a dict, got {type(row).__name__}")
    out = {k: (None if not math.isfinite(float(row[k])) else float(row[k])) for k in _ROW_NUMBERS}
    out.update({k: str(row[k]) for k in _ROW_STRINGS})
    out["propeller"] = int(row["propeller"])
    return _decode_row(out, "row") and out  # a row the reader would refuse is not written


def _decode_row(d: Any, where: str, key: str | None = None) -> dict[str, Any]:
    """A study row of a partial-results file, checked: every key present and no other, the
    numbers finite and >= 0 or null (NaN), propeller_share in [0, 1], the propeller an index
    in [0, MAX_PROPELLERS], the strings short and of their kind; and consistent (a critical
    speed and frequency exactly when the kind is not "none", a share exactly with a
    propeller)."""
    r = SavedDict(d, where, (*_ROW_NUMBERS, *_ROW_STRINGS, "propeller"))
    row: dict[str, Any] = {}
    for k in _ROW_NUMBERS:
        x = r.number(k, optional=True)
        if x is not None and not (0.0 <= x <= (1.0 if k == "propeller_share" else math.inf)):
            raise v.InputError(f"{r.name(k)} = {x!r} is invalid: must be "
                               + ("in [0, 1]" if k == "propeller_share" else ">= 0"))
        row[k] = math.nan if x is None else x
    for k, choices in _ROW_STRINGS.items():
        text = r.string(k, choices)
        if len(text) > _ROW_TEXT or not text.isprintable():
            raise v.InputError(f"{r.name(k)}: must be a printable name of at most {_ROW_TEXT} "
                               "characters")
        row[k] = text
    row["propeller"] = r.integer("propeller", 0, limits.MAX_PROPELLERS)
    found = row["kind"] != "none"
    if found != math.isfinite(row["critical_speed"]) or \
            found != math.isfinite(row["critical_frequency"]) or (not found and (
                row["critical_mode"] or row["event"] or row["propeller"])):
        raise v.InputError(f"{where}: kind {row['kind']!r} does not match its critical speed, "
                           "frequency, mode and event")
    if (row["propeller"] > 0) != math.isfinite(row["propeller_share"]):
        raise v.InputError(f"{where}: propeller {row['propeller']} does not match its share")
    return {k: row[k] for k in ("critical_speed", "critical_frequency", "critical_mode", "content",
                                "kind", "event", "whirl", "propeller", "propeller_share",
                                "static_divergence_speed")}


#: The point format of a study's result rows in a partial-results file.
STUDY_ROW = PointFormat("study row", _encode_row, _decode_row)


def row_checkpoint(checkpoint: Checkpoint | None, models: Sequence[Any],
                   grids: Sequence[Any], *, xtol: float, static_divergence: bool,
                   low_speed: bool, method: str) -> Checkpoint | None:
    """The checkpoint of :func:`run_points`: the study-row format and the fingerprint entries
    that decide every row — the speed grids, xtol, method, the convention and, unless the
    study named its model already (entry "model"), the content of every variant analysed
    (:func:`propwhirl.studies.execution.content_digest`)."""
    if checkpoint is None:
        return None
    check_checkpoint(checkpoint)
    entries: dict[str, Any] = {
        "speeds": content_digest(list(grids)), "xtol": float(xtol), "method": method,
        "static_divergence": bool(static_divergence), "low_speed": bool(low_speed)}
    if "model" not in checkpoint.fingerprint:
        entries["variants"] = content_digest(
            [f"{type(m).__name__}: {m}" if isinstance(m, Exception) else m for m in models])
    return checkpoint.with_entries(STUDY_ROW, **entries)


def run_points(models: Sequence[Any], speeds: Any = None, *, speeds_each: Sequence[Any] | None = None,
               xtol: float = STUDY_XTOL, static_divergence: bool = True, low_speed: bool = True,
               processes: int = 1, client=None, progress=None, checkpoint=None,
               keys: Sequence[str] | None = None, desc: str = "points",
               method: str = "auto",
               dlm_tables: DlmTables | None = None) -> list[dict[str, Any]]:
    """One result row (:func:`evaluate`) per model, in order, each with an ``error`` entry
    ("" for an analysed point).

    speeds: one initial grid [m/s] for all (None: each model's own speed range); speeds_each:
    instead, one grid (or None) per model.  An entry of ``models`` that is an exception (the
    variant could not be built) and a point whose analysis fails give :func:`error_row`: the
    others go on.  client, progress, checkpoint, keys, desc: as
    :func:`propwhirl.studies.execution.map_analyses` (a Dask cluster, a progress bar, a
    partial-results file to resume from); method: each analysis's
    (:func:`propwhirl.analysis.stability.analyse`); dlm_tables: the study's doublet-lattice
    tables, shared by its analyses (None: new ones for this call).
    This is the one place where a study's analyses go to the pool.
    """
    v.positive("xtol", xtol, "m/s")
    if method not in METHODS:
        raise v.InputError(f"method = {method!r} is invalid: must be one of "
                           f"{', '.join(map(repr, METHODS))}")
    v.integer_at_least("processes", processes, 1)
    models = list(models)
    if speeds_each is not None:
        grids = list(speeds_each)
        if len(grids) != len(models):
            raise v.InputError(f"speeds_each has {len(grids)} grids, expected {len(models)} (one per model)")
    else:
        grid = None if speeds is None else v.increasing("speeds", speeds, "m/s")
        grids = [grid] * len(models)
    names = list(keys) if keys is not None else [str(i) for i in range(len(models))]
    run = [i for i, m in enumerate(models) if not isinstance(m, Exception)]
    tables = DlmTables() if dlm_tables is None else dlm_tables
    tasks = [(models[i], grids[i], xtol, bool(static_divergence), bool(low_speed), method,
              tables) for i in run]
    checkpoint = row_checkpoint(checkpoint, models, grids, xtol=xtol, method=method,
                                static_divergence=static_divergence, low_speed=low_speed)
    results = execution.map_analyses(evaluate, tasks, processes, client=client,
                                     progress=progress,
                                     errors="record", checkpoint=checkpoint,
                                     keys=[names[i] for i in run], desc=desc)
    rows: list[dict[str, Any]] = [error_row(f"{type(m).__name__}: {m}")
                                  if isinstance(m, Exception) else {} for m in models]
    for i, r in zip(run, results):
        rows[i] = error_row(str(r)) if isinstance(r, TaskError) else {**r, "error": ""}
    return rows


# ============================================================================ result
@dataclass(frozen=True)
class Axis:
    """One varied parameter: its path, values, unit, description and the model's own value.

    design: the value of the model as given (1 for a scale form; None when the field is not
    given as one number, e.g. f_theta of a propeller given K_theta).
    """

    path: str
    values: np.ndarray
    unit: str = ""
    design: float | None = None
    doc: str = ""

    @property
    def label(self) -> str:
        """Axis label: ``'wing.GJ [N m^2]'``, ``'wing.EI* (factor)'``."""
        if self.path.endswith("*"):
            return f"{self.path} (factor)"
        return f"{self.path} [{self.unit}]" if self.unit else self.path

    def to_dict(self) -> dict[str, Any]:
        return {"path": self.path, "values": [float(x) for x in self.values], "unit": self.unit,
                "design": self.design, "doc": self.doc}

    @classmethod
    def from_dict(cls, d: Any, where: str = "axis") -> "Axis":
        """The axis written by :meth:`to_dict`, checked (unit, design and doc may be absent)."""
        r = SavedDict(d, where, ("path", "values"), ("unit", "design", "doc"))
        values = r.array("values")
        if values.size == 0:
            raise v.InputError(f"{r.name('values')}: no values")
        return cls(r.string("path"), values, r.string("unit") if r.has("unit") else "",
                   r.number("design", optional=True) if r.has("design") else None,
                   r.string("doc") if r.has("doc") else "")


@dataclass(frozen=True)
class CriticalMap(Result):
    """The critical speed of a model over one (a sweep) or two (a map) parameters.

    A :class:`~propwhirl.results.Result` of kind "critical-map" (format
    ``propwhirl.critical-map/1``); :meth:`save` / :meth:`load` also write and read CSV by the
    file's suffix.

    Attributes
    ----------
    model_name : str
        The model's name.
    axes : tuple of Axis
        The varied parameters (path, values, unit, the model's own value), in order.
    columns : mapping of str to ndarray
        The result columns of :data:`RESULT_UNITS` (critical_speed [m/s],
        critical_frequency [Hz], critical_mode, kind, whirl, propeller, propeller_share [-],
        static_divergence_speed [m/s], error, ...), each an array of shape
        ``(len(axes[0].values), len(axes[1].values))`` (one axis: a vector).
    convention : str
        Which events count as critical (:func:`propwhirl.studies.critical.convention`).
    xtol : float
        Accuracy of each critical speed [m/s].
    units : mapping of str to str
        The unit of each column ("" for text and dimensionless ones).

    Examples
    --------
    >>> import pathlib, tempfile
    >>> from propwhirl.studies import CriticalMap, sweep
    >>> from propwhirl.cases.ch09_baseline import isolated_baseline_propeller
    >>> r = sweep(isolated_baseline_propeller(), "propeller.f_psi", [6.0, 8.0],
    ...           speeds=[100.0, 200.0, 300.0])
    >>> r.axes[0].label, r.axes[0].design, r.units["critical_speed"]
    ('propeller.f_psi [Hz]', 7.0, 'm/s')
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     again = CriticalMap.load(r.save(pathlib.Path(folder) / "sweep.csv"))
    >>> [round(float(V), 1) for V in again.critical_speed]
    [216.2, 257.6]
    """

    model_name: str
    axes: tuple[Axis, ...]
    columns: Mapping[str, np.ndarray]
    convention: str = "every instability counts (propwhirl.analysis.critical)"
    xtol: float = STUDY_XTOL
    units: Mapping[str, str] = field(default_factory=lambda: dict(RESULT_UNITS))

    KIND: ClassVar[str] = "critical-map"
    VERSION: ClassVar[int] = 1
    READABLE: ClassVar[tuple[int, ...]] = (1,)
    WHAT: ClassVar[str] = "critical map"

    @property
    def shape(self) -> tuple[int, ...]:
        return tuple(len(a.values) for a in self.axes)

    def __len__(self) -> int:
        return int(np.prod(self.shape))

    @property
    def critical_speed(self) -> np.ndarray:
        """Critical speed [m/s] at each point (NaN: nothing unstable in the speed range)."""
        return np.asarray(self.columns["critical_speed"], dtype=float)

    @property
    def kind(self) -> np.ndarray:
        """"flutter", "divergence" or "none" at each point."""
        return np.asarray(self.columns["kind"], dtype=object)

    def grids(self) -> tuple[np.ndarray, ...]:
        """The parameter values at each point (``numpy.meshgrid(..., indexing="ij")``)."""
        return tuple(np.meshgrid(*(a.values for a in self.axes), indexing="ij"))

    def table(self) -> dict[str, np.ndarray]:
        """Tidy columns, one row per point (last axis fastest): the parameter paths, then
        the results."""
        out = {a.path: g.ravel() for a, g in zip(self.axes, self.grids())}
        out.update({k: np.asarray(c).ravel() for k, c in self.columns.items()})
        return out

    def to_dataframe(self):
        """:meth:`table` as a pandas DataFrame; units in ``df.attrs["units"]`` (needs pandas:
        the ``data`` extra)."""
        try:
            import pandas as pd
        except ImportError:
            raise ImportError("DataFrames need pandas: pip install propwhirl[data]") from None
        df = pd.DataFrame(self.table())
        df.attrs["units"] = {**{a.path: a.unit for a in self.axes}, **dict(self.units)}
        df.attrs["convention"] = self.convention
        return df

    # ------------------------------------------------------------------ files
    def encode(self) -> dict[str, Any]:
        """JSON-ready fields (NaN → None)."""
        def clean(x):
            if isinstance(x, (float, np.floating)):
                return None if not math.isfinite(x) else float(x)
            if isinstance(x, (np.integer,)):
                return int(x)
            return x

        return {"model": self.model_name, "convention": self.convention,
                "xtol": self.xtol, "axes": [a.to_dict() for a in self.axes],
                "units": dict(self.units),
                "columns": {k: [clean(x) for x in np.asarray(c).ravel().tolist()]
                            for k, c in self.columns.items()}}

    @classmethod
    def decode(cls, d: Mapping[str, Any], version: int, where: str = "") -> "CriticalMap":
        """Every key checked: the axes, each result column of :data:`RESULT_UNITS` with one
        value per point (null: NaN)."""
        r = SavedDict(d, where, ("model", "convention", "xtol", "axes", "columns"), ("units",))
        axes = tuple(Axis.from_dict(a, w) for w, a in r.items("axes"))
        if not axes:
            raise v.InputError(f"{r.name('axes')}: no axes")
        shape = tuple(len(a.values) for a in axes)
        c = r.sub("columns", tuple(RESULT_UNITS))
        cols = {}
        for k in RESULT_UNITS:
            raw = c.raw(k)
            if not isinstance(raw, list):
                raise v.InputError(f"{c.name(k)}: must be a list")
            try:
                cols[k] = _column_array(k, raw, shape)
            except (ValueError, TypeError, OverflowError) as exc:
                raise v.InputError(f"{c.name(k)}: {exc}") from None
        return cls(r.string("model"), axes, cols, r.string("convention"), r.number("xtol"))

    def to_csv(self, path: str | Path | None = None) -> str:
        """One row per point (header "column [unit]"); also written to `path` if given
        (atomically).  NaN is an empty cell."""
        t = self.table()
        units = {**{a.path: a.unit for a in self.axes}, **dict(self.units)}
        return fileio.csv_table(t, units, path, what="critical map", count=True)

    @classmethod
    def from_csv(cls, text: str, where: str = "critical-map CSV") -> "CriticalMap":
        """The map of a CSV written by :meth:`to_csv` (the design point and the model name
        are only in the JSON form); its first line's row count is checked
        (:func:`propwhirl.fileio.check_count`: a table cut at a line boundary is refused)."""
        count, text = fileio.split_count(text, "critical map", where)
        try:
            rows = list(csv.reader(io.StringIO(text)))
        except csv.Error as exc:
            raise v.InputError(f"{where}: not a critical-map table: {exc}") from None
        if len(rows) < 2:
            raise v.InputError(f"{where}: no rows")
        short = [i for i, r in enumerate(rows) if len(r) != len(rows[0])]
        if short:
            raise v.InputError(f"{where}: line {short[0] + 1 + (count is not None)} has "
                               f"{len(rows[short[0]])} columns, need {len(rows[0])} (truncated?)")
        fileio.check_count(count, len(rows) - 1, "critical map", where)
        rows[0] = [fileio.csv_text(h) for h in rows[0]]
        heads = [h.split(" [")[0] for h in rows[0]]
        units = {h.split(" [")[0]: (h.split(" [", 1)[1].rstrip("]") if " [" in h else "")
                 for h in rows[0]}
        missing = [k for k in RESULT_UNITS if k not in heads]
        axes_names = [h for h in heads if h not in RESULT_UNITS]
        if missing or not axes_names:
            raise v.InputError(f"{where}: not a critical-map table (missing columns "
                               f"{missing or 'of parameters'})")
        data = {h: [fileio.csv_text(r[i]) for r in rows[1:]] for i, h in enumerate(heads)}
        try:
            axes = tuple(Axis(h, np.array(list(dict.fromkeys(float(x) for x in data[h]))),
                              units[h]) for h in axes_names)
            shape = tuple(len(a.values) for a in axes)
            cols = {k: _column_array(k, [None if x == "" else x for x in data[k]], shape)
                    for k in RESULT_UNITS}
        except ValueError as exc:
            raise v.InputError(f"{where}: malformed ({exc})") from None
        if count is None:
            fileio.warn_uncounted("critical map", where)
        return cls("", axes, cols, "")

    def save(self, path: str | Path) -> Path:
        """Write the map: CSV for a ``.csv`` suffix, else JSON (:meth:`Result.save`;
        atomically)."""
        path = Path(v.file_path("path", path, f"the {self.WHAT} to write"))
        if path.suffix.lower() == ".csv":
            self.to_csv(path)
            return path
        return super().save(path)

    @classmethod
    def load(cls, path: str | Path) -> "CriticalMap":
        """Read a map written by :meth:`save` (JSON, checked by :meth:`Result.load`, or CSV
        by its suffix)."""
        if Path(v.file_path("path", path, f"a {cls.WHAT}")).suffix.lower() == ".csv":
            return cls.from_csv(fileio.read_text(path, "critical map"), fileio.shown(path))
        return super().load(path)

    # ------------------------------------------------------------------ text
    def lowest(self) -> dict[str, Any] | None:
        """The point with the lowest critical speed (its row of :meth:`table`), None if
        nothing is unstable anywhere."""
        V = self.critical_speed.ravel()
        if not np.isfinite(V).any():
            return None
        i = int(np.nanargmin(V))
        return {k: c[i] for k, c in self.table().items()}

    def format(self, max_rows: int = 200) -> str:
        """A text table of the points (at most `max_rows`; a map of more points: a summary)."""
        t = self.table()
        lines = [f"{self.model_name}: critical speed over "
                 + " x ".join(f"{a.path} ({len(a.values)} values)" for a in self.axes),
                 f"critical instability: {self.convention}"]
        for a in self.axes:
            if a.design is not None:
                lines.append(f"design point: {a.path} = {a.design:.6g}{' ' + a.unit if a.unit else ''}")
        if len(self) <= max_rows:
            heads = [a.label for a in self.axes] + ["V_crit [m/s]", "f [Hz]", "kind",
                                                      "mode (content)", "propeller", "V_div [m/s]"]
            rows = []
            for i in range(len(self)):
                lab, c = t["critical_mode"][i], t["content"][i]
                prop = t["propeller"][i]
                share = t["propeller_share"][i]
                rows.append([f"{t[a.path][i]:.6g}" for a in self.axes]
                            + [f"{t['critical_speed'][i]:.2f}", f"{t['critical_frequency'][i]:.3f}",
                               t["kind"][i], f"{lab} ({c})" if c else lab,
                               f"{prop} ({100 * share:.0f} %)" if prop else "-",
                               f"{t['static_divergence_speed'][i]:.2f}"])
            lines.append(text_table(rows, heads, "r" * len(self.axes) + "rrlllr"))
        low = self.lowest()
        if low is None:
            lines.append("no instability in the speed range at any point")
        else:
            at = ", ".join(f"{a.path} = {low[a.path]:.6g}" for a in self.axes)
            lines.append(f"lowest critical speed: {low['critical_speed']:.2f} m/s "
                         f"({low['kind']} of {low['critical_mode']}) at {at}")
            n_none = int(np.sum(self.kind.ravel() == "none"))
            if n_none:
                lines.append(f"{n_none} of {len(self)} points: no instability in the speed range")
        return "\n".join(lines)


#: The format tag of the critical-map file (:class:`CriticalMap`; the name of earlier releases).
FORMAT = CriticalMap.format_name()


def _column_array(name: str, values: Sequence[Any], shape: tuple[int, ...]) -> np.ndarray:
    n = int(np.prod(shape))
    if len(values) != n:
        raise ValueError(f"column {name!r} has {len(values)} values, expected {n}")
    if name in _FLOAT_COLUMNS:
        arr = np.array([np.nan if x is None else float(x) for x in values], dtype=float)
    elif name in _INT_COLUMNS:
        arr = np.array([0 if x is None else int(x) for x in values], dtype=int)
    else:
        arr = np.array(["" if x is None else str(x) for x in values], dtype=object)
    return arr.reshape(shape)


# ============================================================================ studies
def _axis(model: Any, path: str, values: Any) -> tuple[P.Parameter, Axis]:
    """The resolved path and its axis; every value checked at once against the path's
    declared range (:meth:`propwhirl.studies.paths.Parameter.check_values`): a value outside it
    stops the study before any analysis."""
    p = P.resolve(model, path)
    arr = p.check_values(values, "values")
    if arr.size == 0:
        raise v.InputError(f"values of {p.path}: must be a non-empty 1-D sequence, got shape "
                           f"{arr.shape}")
    return p, Axis(p.path, arr, p.unit, p.value(model), p.doc)


def critical_map(model: Any, axes: Sequence[tuple[str, Any]], *, speeds=None,
                 xtol: float = STUDY_XTOL, static_divergence: bool = True, low_speed: bool = True,
                 processes: int = 1, client=None, progress=None, checkpoint=None,
                 method: str = "auto", warm_start: bool = True,
                 stats: dict | None = None) -> CriticalMap:
    """The critical speed of `model` over the outer product of `axes` ((path, values) pairs;
    one or more).  An unknown or non-numeric path, two paths that cannot vary together (the
    same value twice, a field and its alternative: f_theta and K_theta) and a value outside a
    path's declared range stop the study before any analysis; a point whose variant the model
    refuses (e.g. a hub radius beyond the radius) or whose analysis fails is recorded — kind
    "error", its one-line message in the column ``error`` — and the others go on.  client, progress, checkpoint: as
    :func:`propwhirl.studies.execution.map_analyses`; method: each analysis's
    (:func:`propwhirl.analysis.stability.analyse`; the default "auto" is the reduced analysis
    for wings, crossings converged on the full order; "dense" the reference);
    warm_start (default True): analyse most points only up to the speeds their neighbours
    found (:mod:`propwhirl.studies.warmstart`: the same rows to the accuracy xtol; not with
    ``low_speed=False``, where it is ignored); ``method="dense", warm_start=False`` is the
    brute-force reference (every point dense over its whole range); stats: a dict that
    receives the number of analyses of each pass.

    Parameters
    ----------
    model : Model
        The model.
    axes : sequence of (str, array_like)
        1 to 3 (parameter path, values [the path's unit]) pairs.
    speeds : array_like, optional
        Initial speed grid [m/s] of every analysis (default the model's speed range).
    xtol : float
        Accuracy of each critical speed [m/s].
    static_divergence, low_speed : bool
        False: the thesis's exclusions (:func:`propwhirl.studies.critical.critical_instability`).
    processes : int
        Local worker processes.
    client : dask.distributed.Client or str, optional
        Run on that cluster (or scheduler address).
    progress : bool or callable, optional
        A progress bar (True) or ``report(done, total)``.
    checkpoint : Checkpoint, optional
        Keep the finished points in a partial-results file and resume from it.
    method : {"auto", "dense", "reduced", "pk"}
        Each analysis's method.
    warm_start : bool
        Analyse most points only up to the speeds their neighbours found.
    stats : dict, optional
        Receives the number of analyses of each pass.

    Returns
    -------
    CriticalMap
        The result columns (:data:`RESULT_UNITS`: critical speed [m/s], frequency [Hz], ...)
        over the outer product of the axes.

    Examples
    --------
    Three parameters of the isolated baseline propeller, 2 values each (the second:
    its pitch-mount damping, g [-]):

    >>> from propwhirl.studies import critical_map
    >>> from propwhirl.cases.ch09_baseline import isolated_baseline_propeller
    >>> r = critical_map(isolated_baseline_propeller(),
    ...                  [("propeller.f_theta", [6.0, 8.0]), ("propeller.damping_theta", [0.0, 0.02]),
    ...                   ("propeller.f_psi", [6.0, 8.0])], speeds=[100.0, 200.0, 300.0])
    >>> r.shape, [a.label for a in r.axes][:2]
    ((2, 2, 2), ['propeller.f_theta [Hz]', 'propeller.damping_theta'])
    """
    if not 1 <= len(axes) <= 3:
        raise v.InputError(f"axes: {len(axes)} given, a study varies 1 to 3 parameters")
    resolved = [_axis(model, p, vals) for p, vals in axes]
    P.check_independent([p for p, _ in resolved])     # f_theta x K_theta: one would be ignored
    limits.check_study(model, math.prod(ax.values.size for _, ax in resolved), processes,
                       method=choose_method(model, method), cluster=client is not None,
                       progress=progress)
    variants: list[Any] = []
    keys = []
    for idx in np.ndindex(*(len(ax.values) for _, ax in resolved)):
        point = {p.path: float(ax.values[i]) for (p, ax), i in zip(resolved, idx)}
        keys.append(" ".join(f"{k}={x!r}" for k, x in point.items()))
        try:
            variants.append(P.set_values(model, point))
        except v.InputError as exc:             # recorded in its row, the others go on
            variants.append(exc)
    if all(isinstance(m, Exception) for m in variants):    # nothing to analyse: say why
        raise v.InputError(f"every point of the study is refused by the model, e.g. {keys[0]}: "
                           f"{variants[0]}")
    shape = tuple(len(ax.values) for _, ax in resolved)
    if checkpoint is not None and hasattr(checkpoint, "with_entries"):
        checkpoint = checkpoint.with_entries(study="critical map", model=content_digest(model),
                                             axes=[ax.to_dict() for _, ax in resolved])
    options = dict(xtol=xtol, static_divergence=static_divergence, low_speed=low_speed,
                   processes=processes, client=client, progress=progress, method=method,
                   dlm_tables=DlmTables())   # every pass's analyses: one set of AICs
    if not isinstance(warm_start, (bool, np.bool_)):
        raise v.InputError(f"warm_start = {warm_start!r} is invalid: must be True or False")
    if warm_start and low_speed and len(variants) > 1:
        grid = None if speeds is None else v.increasing("speeds", speeds, "m/s")
        grids = [None if isinstance(m, Exception) else grid if grid is not None
                 else m.flight.speeds() for m in variants]
        passes = None       # a callable's count over the passes, against every point
        if callable(progress) and not isinstance(progress, (bool, np.bool_)):
            passes = Cumulative(progress, len(variants))
        rows = warm_started_rows(
            variants, keys, shape, grids,
            lambda ms, **kw: run_points(ms, **{**options, **(
                {} if passes is None else {"progress": passes.stage()})}, **kw),
            checkpoint=checkpoint, stats=stats)
    else:
        rows = run_points(variants, speeds, checkpoint=checkpoint, keys=keys, **options)
        if stats is not None:
            stats.update(analyses=len(variants))
    cols = {k: _column_array(k, [r[k] for r in rows], shape) for k in RESULT_UNITS}
    return CriticalMap(getattr(model, "name", type(model).__name__), tuple(ax for _, ax in resolved),
                       cols, convention(static_divergence, low_speed), float(xtol))


def sweep(model: Any, path: str, values: Any, **options) -> CriticalMap:
    """The critical speed of `model` against one parameter `path` (:mod:`.paths`) at
    `values` [its unit; a factor for ``PATH*``].

    options: speeds (initial grid [m/s]; default the model's speed range), xtol [m/s],
    static_divergence and low_speed (False: the thesis's exclusions, see
    :func:`propwhirl.studies.critical.critical_instability`), processes.

    Parameters
    ----------
    model : Model
        The model (any; its paths: :func:`propwhirl.studies.paths.valid_paths`).
    path : str or tuple of str
        A parameter path (``"wing.GJ"``, ``"propellers[0].propeller.f_theta"``, the scale
        form ``"wing.EI*"``), or linked paths taking one value (docs/studies.md).
    values : array_like
        The values [the path's unit; a factor for ``PATH*``].
    **options
        Those of :func:`critical_map`: speeds [m/s], xtol [m/s], static_divergence,
        low_speed, processes, client, progress, checkpoint, method, warm_start, stats.

    Returns
    -------
    CriticalMap
        One point per value: the critical speed [m/s], frequency [Hz], mode, kind, ...

    Examples
    --------
    The isolated baseline propeller's backward whirl flutter against its yaw-mount
    frequency [Hz]:

    >>> from propwhirl.studies import sweep
    >>> from propwhirl.cases.ch09_baseline import isolated_baseline_propeller
    >>> r = sweep(isolated_baseline_propeller(), "propeller.f_psi", [6.0, 8.0],
    ...           speeds=[100.0, 200.0, 300.0])
    >>> r.shape, list(r.kind), list(r.columns["critical_mode"])
    ((2,), ['flutter', 'flutter'], ['backward', 'backward'])
    >>> [round(float(V), 1) for V in r.critical_speed]                 # [m/s]
    [216.2, 257.6]
    """
    return critical_map(model, [(path, values)], **options)


def map2d(model: Any, first: tuple[str, Any], second: tuple[str, Any], **options) -> CriticalMap:
    """The critical speed of `model` over two parameters: ``first = (path, values)`` (rows)
    and ``second = (path, values)`` (columns); options as :func:`sweep`.

    Parameters
    ----------
    model : Model
        The model.
    first, second : tuple of (str, array_like)
        (parameter path, its values [the path's unit]) of the rows and the columns.
    **options
        As :func:`sweep`.

    Returns
    -------
    CriticalMap
        The critical speed [m/s] (and the rest of :data:`RESULT_UNITS`) at every point,
        arrays of shape (len(first values), len(second values)).

    Examples
    --------
    >>> from propwhirl.studies import map2d
    >>> from propwhirl.cases.ch09_baseline import isolated_baseline_propeller
    >>> r = map2d(isolated_baseline_propeller(), ("propeller.f_theta", [6.0, 8.0]),
    ...           ("propeller.f_psi", [6.0, 8.0]), speeds=[100.0, 200.0, 300.0])
    >>> r.shape, [[round(float(V), 1) for V in row] for row in r.critical_speed]
    ((2, 2), [[184.5, 266.7], [266.7, 265.7]])
    """
    return critical_map(model, [first, second], **options)


__all__ = ["sweep", "map2d", "critical_map", "CriticalMap", "Axis", "evaluate", "run_points",
           "RESULT_UNITS", "STUDY_XTOL", "STUDY_ROW", "row_checkpoint"]
