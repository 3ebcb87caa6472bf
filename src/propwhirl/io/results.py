"""Result files: the V-g-f table of a sweep as CSV (:func:`write_vgf_csv`, :func:`read_vgf_csv`).

The tidy table of :meth:`propwhirl.engine.core.Sweep.table` with unit-suffixed column names;
floats are written with ``repr``, so a write → read round trip is exact.  (The whole analysis
is saved as JSON by :meth:`propwhirl.analysis.stability.ModelAnalysis.save`.)

The first line says how many rows follow — ``# propwhirl V-g-f table: 56 rows`` — so a table
cut at a line boundary (all rows of the last speeds gone, nothing else wrong) is refused, not
read as a shorter one.  Other programs skip that line (``pandas.read_csv(path,
skiprows=1)``, ``numpy.genfromtxt(path, delimiter=",", skip_header=1, names=True)``).  A
table written before the count (propwhirl 0.1.0 before issue 20) has no such line: it is
still read, with every other check, and a :class:`UserWarning` naming the file says that a
cut at a line boundary cannot be found in it (write it again to add the count).
"""
from __future__ import annotations

import csv
import io
import math
from pathlib import Path

import numpy as np

from propwhirl import fileio
from propwhirl import validate as v

VGF_COLUMNS: tuple[tuple[str, str], ...] = (
    ("V_m_per_s", "V"), ("mode", "mode"), ("label", "label"), ("frequency_hz", "frequency_hz"),
    ("damping_ratio", "damping_ratio"), ("real_per_s", "real"), ("imag_per_s", "imag"),
)
#: what the first line of a V-g-f table names (:func:`propwhirl.fileio.count_line`)
KIND = "V-g-f table"


def write_vgf_csv(result, path: str | Path) -> Path:
    """Write the V-g-f table of a ModelAnalysis or Sweep as CSV (one row per speed and
    physical mode: V [m/s], mode id, label, f [Hz], ζ (eq. 5.5), Re λ, Im λ [1/s]), after a
    first line with the number of rows (:func:`propwhirl.fileio.count_line`, module
    docstring).

    The file is replaced atomically (:func:`propwhirl.fileio.write_text`): a reader never
    sees a partial table, not after a full disk, a Ctrl-C or a second writer.

    Parameters
    ----------
    result : ModelAnalysis or Sweep
        The analysis (its sweep) or the sweep.
    path : str or Path
        The CSV file to write.

    Returns
    -------
    Path
        `path`.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> from propwhirl.analysis import analyse
    >>> from propwhirl.io import write_vgf_csv
    >>> from propwhirl.cases.ch09_baseline import isolated_baseline_propeller
    >>> a = analyse(isolated_baseline_propeller(), speeds=[100.0, 200.0, 250.0])
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     lines = write_vgf_csv(a, pathlib.Path(folder) / "vgf.csv").read_text().splitlines()
    >>> lines[0]                                  # the row count: 3 speeds x 2 modes
    '# propwhirl V-g-f table: 6 rows'
    >>> lines[1].split(",")                       # doctest: +NORMALIZE_WHITESPACE
    ['V_m_per_s', 'mode', 'label', 'frequency_hz', 'damping_ratio', 'real_per_s',
     'imag_per_s']
    """
    sweep = getattr(result, "sweep", result)
    table = sweep.table()
    for name, key in VGF_COLUMNS:
        if key != "label" and not np.isfinite(np.asarray(table[key], dtype=float)).all():
            raise v.InputError(f"cannot write {fileio.quoted(path)}: column {name} has "
                               "non-finite values")
    buf = io.StringIO()
    out = fileio.csv_writer(buf)
    buf.write(fileio.count_line(KIND, len(table["V"])) + "\r\n")
    out.writerow([c for c, _ in VGF_COLUMNS])
    cols = [table[k] for _, k in VGF_COLUMNS]
    for row in zip(*cols):
        out.writerow([repr(float(x)) if isinstance(x, (float, np.floating)) else
                      str(int(x)) if isinstance(x, (int, np.integer)) else str(x)
                      for x in row])
    return fileio.write_text(path, buf.getvalue(), what="V-g-f table")


def _header_error(where: str, header: list[str], line: int) -> v.InputError:
    expected = [c for c, _ in VGF_COLUMNS]
    missing = [c for c in expected if c not in header]
    unknown = [c for c in header if c not in expected]
    why = []
    if missing:
        why.append("missing column" + "s" * (len(missing) > 1) + " " + ", ".join(missing))
    if unknown:
        why.append("unknown column" + "s" * (len(unknown) > 1) + " "
                   + ", ".join(repr(c) for c in unknown[:5]))
    if not why:
        why.append("columns out of order")
    return v.InputError(f"{where}: not a V-g-f table: line {line}: {'; '.join(why)} "
                        f"(the header must be {','.join(expected)})")


def read_vgf_csv(path: str | Path) -> dict[str, np.ndarray]:
    """Read a table written by :func:`write_vgf_csv` back into Sweep.table() columns.

    The table is checked: the row count of its first line
    (:func:`propwhirl.fileio.count_line`: a table cut at a line boundary is refused), the exact
    header, at least one row, every row complete (seven columns, the last line ended by a line
    break), numbers finite, mode ids >= 0, rows in the writer's order (by speed, then mode id),
    and each row's frequency and damping ratio those of its eigenvalue (f = |Im λ|/2π,
    ζ = −Re λ/|λ|, eq. 5.5: a number cut short is found).  Anything else is an
    :class:`~propwhirl.validate.InputError` naming the file and the line.  A table without the
    count line (written before it) is read with a :class:`UserWarning` (module docstring).

    Parameters
    ----------
    path : str or Path
        The CSV file.

    Returns
    -------
    dict of str to ndarray
        One array per column, a row per speed and physical mode: ``V`` [m/s], ``mode``
        (id), ``label``, ``frequency_hz`` [Hz], ``damping_ratio`` ζ [-], ``real`` and
        ``imag`` (Re λ, Im λ [1/s]).

    Raises
    ------
    InputError
        A table that is not one :func:`write_vgf_csv` wrote, naming the file and the line.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> from propwhirl.analysis import analyse
    >>> from propwhirl.io import read_vgf_csv, write_vgf_csv
    >>> from propwhirl.cases.ch09_baseline import isolated_baseline_propeller
    >>> a = analyse(isolated_baseline_propeller(), speeds=[100.0, 200.0, 250.0])
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     table = read_vgf_csv(write_vgf_csv(a, pathlib.Path(folder) / "vgf.csv"))
    >>> list(table)
    ['V', 'mode', 'label', 'frequency_hz', 'damping_ratio', 'real', 'imag']
    >>> table["V"][:2].tolist(), table["label"][:2].tolist()
    ([100.0, 100.0], ['backward', 'forward'])
    >>> round(float(table["frequency_hz"][0]), 2)              # backward whirl at 100 m/s [Hz]
    6.25
    """
    path = Path(path)
    text = fileio.read_text(path, "V-g-f table")
    where = fileio.shown(path)
    count, text = fileio.split_count(text, KIND, where)
    skip = count is not None                # lines before the header
    try:
        rows = list(csv.reader(io.StringIO(text, newline="")))
    except csv.Error as exc:
        raise v.InputError(f"{where}: not a V-g-f table: {exc}") from None
    if not rows:
        raise v.InputError(f"{where}: the file ends after line 1: no header, no rows of the "
                           f"{count} its first line announces (truncated?)")
    expected = [c for c, _ in VGF_COLUMNS]
    if len(rows) == 1 and not text.endswith("\n"):
        raise v.InputError(f"{where}: line {1 + skip} (the header) is incomplete: the file "
                           "ends without a line break (truncated?)")
    if rows[0] != expected:
        raise _header_error(where, rows[0], 1 + skip)
    body = rows[1:]
    if not body:
        raise v.InputError(f"{where}: the V-g-f table has a header but no rows"
                           + (f" (its first line says {count}: truncated?)" if count else ""))
    out: dict[str, list] = {key: [] for _, key in VGF_COLUMNS}
    for i, row in enumerate(body):
        line = i + 2 + skip
        if len(row) != len(expected):
            raise v.InputError(f"{where}: line {line} has {len(row)} columns, need "
                               f"{len(expected)} (truncated?)")
        for (name, key), cell in zip(VGF_COLUMNS, row):
            if key == "label":
                if not cell.strip():
                    raise v.InputError(f"{where}: line {line}: column {name} is empty")
                out[key].append(fileio.csv_text(cell))
                continue
            try:
                x = int(cell) if key == "mode" else float(cell)
            except ValueError:
                need = "an integer" if key == "mode" else "a number"
                raise v.InputError(f"{where}: line {line}: column {name} = {cell[:40]!r} is not "
                                   f"{need}") from None
            if key == "mode" and x < 0:
                raise v.InputError(f"{where}: line {line}: column {name} = {x} is invalid: "
                                   "must be >= 0")
            if not math.isfinite(x):
                raise v.InputError(f"{where}: line {line}: column {name} = {cell!r} is invalid: "
                                   "must be finite")
            out[key].append(x)
    if not text.endswith("\n"):
        raise v.InputError(f"{where}: line {len(rows) + skip} is incomplete: the file ends "
                           "without a line break (truncated?)")
    table = {key: np.asarray(col, dtype=object if key == "label" else int if key == "mode"
                             else float) for key, col in out.items()}
    _check_rows(where, table, skip)
    fileio.check_count(count, len(body), KIND, where)
    if count is None:
        fileio.warn_uncounted(KIND, where)
    return table


def _check_rows(where: str, t: dict[str, np.ndarray], skip: int) -> None:
    """Rows in the writer's order; f and ζ those of λ (eq. 5.5)."""
    V, mode = t["V"], t["mode"]
    later = (V[1:] > V[:-1]) | ((V[1:] == V[:-1]) & (mode[1:] > mode[:-1]))
    if not later.all():
        i = int(np.argmin(later))
        raise v.InputError(f"{where}: line {i + 3 + skip}: (V, mode) = ({float(V[i + 1])!r}, "
                           f"{int(mode[i + 1])}) does not follow ({float(V[i])!r}, "
                           f"{int(mode[i])}): rows must be sorted by speed then mode id")
    lam = t["real"] + 1j * t["imag"]
    mag = np.abs(lam)
    f = np.abs(t["imag"]) / (2 * np.pi)
    zeta = np.divide(-t["real"], mag, out=np.zeros_like(mag), where=mag > 0)
    for key, want, scale in (("frequency_hz", f, float(f.max(initial=0.0))),
                             ("damping_ratio", zeta, 1.0)):
        ok = np.isclose(t[key], want, rtol=1e-9, atol=1e-12 * scale)
        if not ok.all():
            i = int(np.argmin(ok))
            raise v.InputError(f"{where}: line {i + 2 + skip}: column {key} = {float(t[key][i])!r} "
                               f"does not match the eigenvalue {complex(lam[i])!r}: expected "
                               f"{float(want[i])!r} (eq. 5.5)")
