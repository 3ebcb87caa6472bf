"""Result files: the V-g-f table of a sweep as CSV (:func:`write_vgf_csv`, :func:`read_vgf_csv`).

The tidy table of :meth:`propwhirl.engine.core.Sweep.table` with unit-suffixed column names;
floats are written with ``repr``, so a write → read round trip is exact.  (The whole analysis
is saved as JSON by :meth:`propwhirl.analysis.stability.ModelAnalysis.save`.)
"""
from __future__ import annotations

import csv
from pathlib import Path

import numpy as np

from propwhirl import validate as v

VGF_COLUMNS: tuple[tuple[str, str], ...] = (
    ("V_m_per_s", "V"), ("mode", "mode"), ("label", "label"), ("frequency_hz", "frequency_hz"),
    ("damping_ratio", "damping_ratio"), ("real_per_s", "real"), ("imag_per_s", "imag"),
)


def write_vgf_csv(result, path: str | Path) -> Path:
    """Write the V-g-f table of a ModelAnalysis or Sweep as CSV (one row per speed and
    physical mode: V [m/s], mode id, label, f [Hz], ζ (eq. 5.5), Re λ, Im λ [1/s])."""
    sweep = getattr(result, "sweep", result)
    table = sweep.table()
    path = Path(path)
    try:
        with path.open("w", newline="", encoding="utf-8") as fh:
            out = csv.writer(fh)
            out.writerow([c for c, _ in VGF_COLUMNS])
            cols = [table[k] for _, k in VGF_COLUMNS]
            for row in zip(*cols):
                out.writerow([repr(float(x)) if isinstance(x, (float, np.floating)) else
                              str(int(x)) if isinstance(x, (int, np.integer)) else str(x)
                              for x in row])
    except OSError as exc:
        raise v.InputError(f"cannot write {str(path)!r}: {exc.strerror or exc}") from exc
    return path


def read_vgf_csv(path: str | Path) -> dict[str, np.ndarray]:
    """Read a table written by :func:`write_vgf_csv` back into Sweep.table() columns."""
    path = Path(path)
    try:
        with path.open(newline="", encoding="utf-8") as fh:
            rows = list(csv.reader(fh))
    except FileNotFoundError:
        raise v.InputError(f"V-g-f table {str(path)!r} not found") from None
    except OSError as exc:
        raise v.InputError(f"cannot read {str(path)!r}: {exc}") from exc
    expected = [c for c, _ in VGF_COLUMNS]
    if not rows or rows[0] != expected:
        raise v.InputError(f"{path}: not a V-g-f table: the header must be {','.join(expected)}")
    body = rows[1:]
    if any(len(r) != len(expected) for r in body):
        bad = next(i for i, r in enumerate(body) if len(r) != len(expected))
        raise v.InputError(f"{path}: row {bad + 2} has {len(body[bad])} columns, need {len(expected)}")
    cols = list(zip(*body)) if body else [()] * len(expected)
    out: dict[str, np.ndarray] = {}
    try:
        for (name, key), col in zip(VGF_COLUMNS, cols):
            if key == "label":
                out[key] = np.asarray(col, dtype=object)
            elif key == "mode":
                out[key] = np.asarray([int(x) for x in col], dtype=int)
            else:
                out[key] = np.asarray([float(x) for x in col], dtype=float)
    except ValueError as exc:
        raise v.InputError(f"{path}: column {name}: {exc}") from exc
    return out


