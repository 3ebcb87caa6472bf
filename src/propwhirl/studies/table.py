"""The result table of a parametric study: one row per (model, parameter value)."""
from __future__ import annotations

import csv
import io
import math
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any, Mapping

import numpy as np

from propwhirl import fileio
from propwhirl import validate as v
from propwhirl.analysis.summary import text_table

#: Units of the result columns.
RESULT_UNITS: dict[str, str] = {
    "critical_speed": "m/s", "critical_frequency": "Hz", "critical_mode": "", "content": "", "kind": "",
    "event": "", "whirl": "", "static_divergence_speed": "m/s",
}


@dataclass(frozen=True)
class StudyTable:
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
    """

    name: str
    parameter: str
    columns: Mapping[str, np.ndarray]
    units: Mapping[str, str] = field(default_factory=dict)
    #: which events the critical instability counts (:func:`convention`)
    convention: str = "every instability counts (propwhirl.analysis.critical)"

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

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict: name, parameter, units and columns as lists (NaN → None)."""
        def clean(x):
            if isinstance(x, (float, np.floating)):
                return None if not math.isfinite(x) else float(x)
            if isinstance(x, np.integer):
                return int(x)
            return x if x is None or isinstance(x, (int, str)) else str(x)

        return {"name": self.name, "parameter": self.parameter, "convention": self.convention,
                "units": dict(self.units),
                "columns": {k: [clean(x) for x in np.asarray(c).tolist()] for k, c in self.columns.items()}}

    def to_csv(self, path: str | Path | None = None) -> str:
        """The table as CSV text (header "column [unit]"); also written to `path` if given
        (atomically, :func:`propwhirl.fileio.write_text`: never a partial file)."""
        buf = io.StringIO()
        w = csv.writer(buf, lineterminator="\n")
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
            name = f"{lab} ({c})" if c else lab
            rows.append([m, f"{x:.6g}", f"{V:.2f}", f"{f:.3f}", name, kind, f"{Vd:.2f}"])
        lines = [self.name, f"critical instability: {self.convention}",
                 text_table(rows, heads, "lrrrllr")]
        return "\n".join(lines)


