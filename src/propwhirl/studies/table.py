"""The result table of a parametric study: one row per (model, parameter value)."""
from __future__ import annotations

import io
import math
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any, ClassVar, Mapping

import numpy as np

from propwhirl import fileio
from propwhirl import validate as v
from propwhirl.analysis.summary import text_table
from propwhirl.analysis.naming import with_content
from propwhirl.results import Result, SavedDict

def _column(c: SavedDict, key: str) -> np.ndarray:
    """A column of a study-table file: numbers (null: NaN) as floats, or strings."""
    x = c.raw(key)
    if not isinstance(x, list):
        raise v.InputError(f"{c.name(key)}: must be a list")
    if all(isinstance(y, str) for y in x):
        return np.array(x, dtype=object)
    if all(y is None or (isinstance(y, (int, float)) and not isinstance(y, bool)
                         and math.isfinite(y)) for y in x):
        return np.array([math.nan if y is None else float(y) for y in x], dtype=float)
    raise v.InputError(f"{c.name(key)}: must hold finite numbers (null for none) or strings "
                       "only")


#: Units of the result columns.
RESULT_UNITS: dict[str, str] = {
    "critical_speed": "m/s", "critical_frequency": "Hz", "critical_mode": "", "content": "", "kind": "",
    "event": "", "whirl": "", "static_divergence_speed": "m/s",
}


@dataclass(frozen=True)
class StudyTable(Result):
    """Result of a parametric study: equal-length columns, one row per (model, value).

    name:      what was varied (e.g. "nacelle stiffness, yaw varied")
    parameter: the column plotted on the x-axis (e.g. "mean_frequency")
    columns:   "model", the parameter column(s), then critical_speed [m/s],
               critical_frequency [Hz], critical_mode (the tracked mode's name), content (its
               dominant degrees of freedom at the first speed: "bending", "torsion", "pitch",
               "yaw" — with soft mounts a mode named "wing 1" can be the propeller pitch),
               kind, event, whirl (sense of the propeller orbit at the critical point),
               static_divergence_speed [m/s]
    units:     unit of each column ("" for text and dimensionless columns)
    convention: which events count as critical (module docstring)

    A :class:`~propwhirl.results.Result` of kind "study-table" (format
    ``propwhirl.study-table/1``; a dict of :meth:`to_dict` without a format, as written
    before it, is version 1): :meth:`save` / :meth:`load`.  A column of numbers (null: NaN)
    is read back as floats, a column of strings as strings.
    """

    name: str
    parameter: str
    columns: Mapping[str, np.ndarray]
    units: Mapping[str, str] = field(default_factory=dict)
    #: which events the critical instability counts (:func:`convention`)
    convention: str = "every instability counts (propwhirl.analysis.critical)"

    KIND: ClassVar[str] = "study-table"
    VERSION: ClassVar[int] = 1
    READABLE: ClassVar[tuple[int, ...]] = (1,)
    UNTAGGED: ClassVar[int | None] = 1
    WHAT: ClassVar[str] = "study table file"

    def __len__(self) -> int:
        return len(self.columns["model"])

    @property
    def models(self) -> tuple[str, ...]:
        """The models in the table, in order of appearance."""
        return tuple(dict.fromkeys(str(m) for m in self.columns["model"]))

    def for_model(self, model: str) -> "StudyTable":
        """The rows of one model (e.g. ``table.for_model("isolated")``)."""
        if model not in self.models:
            raise v.InputError(f"model = {model!r} is invalid: this table has {self.models}")
        keep = np.asarray(self.columns["model"]) == model
        return replace(self, columns={k: np.asarray(c)[keep] for k, c in self.columns.items()})

    def curve(self, model: str) -> tuple[np.ndarray, np.ndarray]:
        """(parameter values, critical speeds [m/s]) of one model, as plotted in chapter 11."""
        t = self.for_model(model)
        return np.asarray(t.columns[self.parameter], dtype=float), np.asarray(t.columns["critical_speed"], dtype=float)

    def encode(self) -> dict[str, Any]:
        """name, parameter, convention, units and columns as lists (NaN → None)."""
        def clean(x):
            if isinstance(x, (float, np.floating)):
                return None if not math.isfinite(x) else float(x)
            if isinstance(x, np.integer):
                return int(x)
            return x if x is None or isinstance(x, (int, str)) else str(x)

        return {"name": self.name, "parameter": self.parameter, "convention": self.convention,
                "units": dict(self.units),
                "columns": {k: [clean(x) for x in np.asarray(c).tolist()] for k, c in self.columns.items()}}

    @classmethod
    def decode(cls, d: Mapping[str, Any], version: int, where: str = "") -> "StudyTable":
        r = SavedDict(d, where, ("name", "parameter", "convention", "units", "columns"))
        units = r.raw("units")
        if not isinstance(units, dict) or not all(isinstance(u, str) for u in units.values()):
            raise v.InputError(f"{r.name('units')}: must be an object of unit strings")
        raw = r.raw("columns")
        if not isinstance(raw, dict) or "model" not in raw:
            raise v.InputError(f"{r.name('columns')}: must be an object of columns, with "
                               "'model'")
        c = r.sub("columns", (), tuple(raw))
        columns = {k: _column(c, k) for k in raw}
        sizes = {k: len(x) for k, x in columns.items()}
        if len(set(sizes.values())) > 1:
            k = next(k for k in sizes if sizes[k] != sizes["model"])
            raise v.InputError(f"{c.name(k)}: has {sizes[k]} entries, 'model' has "
                               f"{sizes['model']}")
        parameter = r.string("parameter")
        if parameter not in columns:
            raise v.InputError(f"{r.name('parameter')} = {parameter!r} is not a column")
        return cls(r.string("name"), parameter, columns, dict(units), r.string("convention"))

    def to_csv(self, path: str | Path | None = None) -> str:
        """The table as CSV text (header "column [unit]"); also written to `path` if given
        (atomically, :func:`propwhirl.fileio.write_text`: never a partial file)."""
        buf = io.StringIO()
        w = fileio.csv_writer(buf, lineterminator="\n")
        keys = list(self.columns)
        w.writerow([f"{k} [{self.units[k]}]" if self.units.get(k) else k for k in keys])
        for i in range(len(self)):
            row = []
            for k in keys:
                x = np.asarray(self.columns[k])[i]
                row.append("" if isinstance(x, (float, np.floating)) and not math.isfinite(x)
                           else (f"{x:.10g}" if isinstance(x, (float, np.floating)) else str(x)))
            w.writerow(row)
        text = buf.getvalue()
        if path is not None:
            fileio.write_text(path, text, what="study table")
        return text

    def format(self) -> str:
        """A text table for the terminal (:func:`propwhirl.analysis.summary.text_table`)."""
        keys = ["model", self.parameter, "critical_speed", "critical_frequency", "critical_mode",
                "content", "kind", "static_divergence_speed"]
        heads = ["model", self.parameter, "V_crit [m/s]", "f [Hz]", "mode (content)", "kind",
                 "V_div [m/s]"]
        rows = []
        for i in range(len(self)):
            m, x, V, f, lab, c, kind, Vd = (np.asarray(self.columns[k])[i] for k in keys)
            name = with_content(str(lab), str(c))
            rows.append([m, f"{x:.6g}", f"{V:.2f}", f"{f:.3f}", name, kind, f"{Vd:.2f}"])
        lines = [self.name, f"critical instability: {self.convention}",
                 text_table(rows, heads, "lrrrllr")]
        return "\n".join(lines)


