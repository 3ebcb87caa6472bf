"""The flutter summary (as NASTRAN SOL 145 prints it) and the text tables of propwhirl.

:func:`flutter_summary` tabulates every physical mode of a sweep at every speed: V [m/s], the
reduced frequency k = ω b_ref / V (ω = |Im λ| [rad/s], b_ref stated with the table: the
wing's root semichord, the typical section's semichord b, or the radius R of an isolated
propeller, :func:`reference`), 1/k, the damping ratio ζ = −Re λ/|λ| (eq. 5.5) and g = 2ζ,
f = |Im λ|/2π [Hz], the air density [kg/m³], the Mach number V/a and λ itself.

**Sign convention** (printed in the header of every table): ζ > 0 and g > 0 are damped
(stable), **g < 0 is unstable**.  NASTRAN's flutter summary has the opposite sign: its
"DAMPING" g = 2 Re p / |Im p| is positive when unstable.

The summary comes as text (:meth:`FlutterSummary.format`, one block per mode like SOL 145),
CSV (:meth:`FlutterSummary.to_csv`), a pandas DataFrame (:meth:`FlutterSummary.to_dataframe`,
the ``data`` extra) and a result file (:meth:`FlutterSummary.save`, format
``propwhirl.flutter-summary/1``, re-read checked by :meth:`FlutterSummary.load`).

:func:`text_table` lays out every text table of propwhirl (the instabilities of an analysis,
``make run``'s report, the studies) with `tabulate <https://pypi.org/project/tabulate/>`_
(format "simple"; the ``tables`` extra).  Without it installed the same layout comes from a
small built-in formatter, so a bare ``pip install propwhirl`` prints the same text (a test
compares the two).
"""
from __future__ import annotations

import io
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any, ClassVar

import numpy as np

from propwhirl import fileio
from propwhirl import validate as v
from propwhirl.engine.results import Sweep
from propwhirl.model.systems import IsolatedPropeller, PropellerWing, TypicalSection
from propwhirl.model.modal import ModalPropellerWing
from propwhirl.results import Result, SavedDict


# ----------------------------------------------------------------------------- text tables
def _plain_table(rows: list[list[str]], headers: Sequence[str], align: str) -> str:
    """tabulate's "simple" layout (two spaces between columns, a dashed rule under the
    header, columns at least two wider than their title) for cells that are already strings;
    used when tabulate is not installed."""
    if not rows:                                   # (tabulate: titles left without rows)
        align = "l" * len(headers)
    cols = list(zip(*rows)) if rows else [() for _ in headers]
    widths = [max([len(h) + 2] + [len(c) for c in col]) for h, col in zip(headers, cols)]

    def line(cells):
        out = [c.ljust(w) if a == "l" else c.rjust(w) for c, w, a in zip(cells, widths, align)]
        return "  ".join(out).rstrip()

    return "\n".join([line(headers), "  ".join("-" * w for w in widths)]
                     + [line(r) for r in rows])


def text_table(rows: Sequence[Sequence[Any]], headers: Sequence[str], align: str = "",
               *, use_tabulate: bool | None = None) -> str:
    """A text table of pre-formatted cells (``str(cell)``) in tabulate's "simple" format.

    Parameters
    ----------
    rows : sequence of sequences
        The cells, row by row (formatted by the caller: digits and units are its choice).
    headers : sequence of str
        Column titles (with units, e.g. "V [m/s]").
    align : str, optional
        One letter per column, "l" (left) or "r" (right); default: left for every column.
    use_tabulate : bool, optional
        Force (True) or avoid (False) tabulate; default: tabulate when it is installed.

    Examples
    --------
    >>> print(text_table([["wing 1", "1.809"], ["forward 1", "7.000"]], ["mode", "f [Hz]"], "lr"))
    mode         f [Hz]
    ---------  --------
    wing 1        1.809
    forward 1     7.000
    """
    headers = [str(h) for h in headers]
    align = (align or "l" * len(headers)).ljust(len(headers), "l")
    if set(align) - {"l", "r"}:
        raise v.InputError(f"align = {align!r} is invalid: one letter l or r per column")
    headers = [h.strip() for h in headers]
    cells = [[str(c).strip() for c in r] for r in rows]
    if use_tabulate is None:
        try:
            import tabulate  # noqa: F401
            use_tabulate = True
        except ImportError:
            use_tabulate = False
    if not use_tabulate:
        return _plain_table(cells, headers, align).rstrip()
    try:
        from tabulate import tabulate
    except ImportError:
        raise ImportError("text tables with tabulate need the tables extra: "
                          "pip install propwhirl[tables]") from None
    colalign = ["left" if a == "l" else "right" for a in align]
    text = tabulate(cells, headers, tablefmt="simple", disable_numparse=True,
                    colalign=colalign)
    return "\n".join(line.rstrip() for line in text.splitlines())


# ----------------------------------------------------------------------------- reference
@dataclass(frozen=True)
class Reference:
    """What the flutter summary needs besides the sweep.

    b_ref:          reference length of the reduced frequency k = ω b_ref / V [m].
    b_ref_is:       what it is ("root semichord of the wing", ...).
    density:        air density [kg/m³].
    speed_of_sound: [m/s] (Mach = V / speed_of_sound).
    """

    b_ref: float
    b_ref_is: str
    density: float
    speed_of_sound: float

    def __post_init__(self) -> None:
        v.positive("b_ref", self.b_ref, "m")
        v.positive("density", self.density, "kg/m^3")
        v.positive("speed_of_sound", self.speed_of_sound, "m/s")

    def to_dict(self) -> dict[str, Any]:
        return {"b_ref_m": self.b_ref, "b_ref_is": self.b_ref_is,
                "density_kg_per_m3": self.density, "speed_of_sound_m_per_s": self.speed_of_sound}

    @classmethod
    def from_dict(cls, d: Any, where: str = "reference") -> "Reference":
        r = SavedDict(d, where, ("b_ref_m", "b_ref_is", "density_kg_per_m3",
                                 "speed_of_sound_m_per_s"))
        try:
            return cls(r.number("b_ref_m"), r.string("b_ref_is"), r.number("density_kg_per_m3"),
                       r.number("speed_of_sound_m_per_s"))
        except v.InputError as exc:
            raise v.InputError(f"{where}: {exc}") from None


def reference(model) -> Reference:
    """The :class:`Reference` of a model: b_ref is the wing's root semichord (propeller-wing
    models; a modal model's: that of its root strip), the semichord b (typical section) or the propeller radius R (an isolated
    propeller); density and speed of sound of ``model.flight``."""
    if isinstance(model, PropellerWing):
        b, what = model.wing.root_chord / 2, "root semichord of the wing"
    elif isinstance(model, TypicalSection):
        b, what = model.b, "semichord of the section"
    elif isinstance(model, IsolatedPropeller):
        b, what = model.propeller.radius, "propeller radius R"
    elif isinstance(model, ModalPropellerWing):
        b, what = model.planform.chord[0] / 2, "semichord of the wing's root strip"
    else:
        raise v.InputError(f"model = {type(model).__name__} has no reference length: give a "
                           "Reference(b_ref, b_ref_is, density, speed_of_sound)")
    return Reference(float(b), what, float(model.flight.density),
                     float(model.flight.speed_of_sound))


# ----------------------------------------------------------------------------- the summary
#: Columns of the flutter summary: (key, CSV/DataFrame name, unit).
COLUMNS: tuple[tuple[str, str, str], ...] = (
    ("mode", "mode", ""), ("label", "label", ""), ("V", "V_m_per_s", "m/s"),
    ("k", "k", ""), ("inv_k", "inv_k", ""), ("zeta", "zeta", ""), ("g", "g", ""),
    ("frequency_hz", "frequency_hz", "Hz"), ("density", "density_kg_per_m3", "kg/m^3"),
    ("mach", "mach", ""), ("real", "real_per_s", "1/s"), ("imag", "imag_per_s", "1/s"),
)

CONVENTION = ("zeta = -Re(lambda)/|lambda| (eq. 5.5), g = 2 zeta: g > 0 damped, g < 0 UNSTABLE "
              "(opposite to NASTRAN's g, which is > 0 when unstable)")


@dataclass(frozen=True)
class FlutterSummary(Result):
    """Every physical mode at every speed (tidy: one row per speed and mode, sorted by mode
    then speed): the columns of :data:`COLUMNS` (module docstring).

    A :class:`~propwhirl.results.Result` of kind "flutter-summary" (format
    ``propwhirl.flutter-summary/1``): the columns under their CSV names (1/k null where
    k = 0), the reference and the model's name; :meth:`save` / :meth:`load`, checked."""

    columns: dict[str, np.ndarray]
    reference: Reference
    model_name: str = ""

    KIND: ClassVar[str] = "flutter-summary"
    VERSION: ClassVar[int] = 1
    READABLE: ClassVar[tuple[int, ...]] = (1,)
    WHAT: ClassVar[str] = "flutter summary file"

    def encode(self) -> dict[str, Any]:
        cols: dict[str, list] = {}
        for key, name, _ in COLUMNS:
            x = np.asarray(self.columns[key])
            cols[name] = ([str(y) for y in x] if key == "label"
                          else [int(y) for y in x] if key == "mode"
                          else [float(y) if math.isfinite(y) else None for y in x]
                          if key == "inv_k" else x.astype(float).tolist())
        return {"model_name": self.model_name, "reference": self.reference.to_dict(),
                "columns": cols}

    @classmethod
    def decode(cls, d: Mapping[str, Any], version: int, where: str = "") -> "FlutterSummary":
        """Every column of :data:`COLUMNS` (by its CSV name) with one entry per row: mode
        ids >= 0, labels, finite numbers (1/k > 0 or null); the reference checked
        (:meth:`Reference.from_dict`).  InputError naming the key."""
        r = SavedDict(d, where, ("model_name", "reference", "columns"))
        ref = Reference.from_dict(r.raw("reference"), r.name("reference"))
        c = r.sub("columns", [name for _, name, _ in COLUMNS])
        mode = c.array("mode", kind=int)
        if (mode < 0).any():
            raise v.InputError(f"{c.name('mode')}: mode ids must be >= 0")
        n = mode.size
        cols: dict[str, np.ndarray] = {"mode": mode,
                                       "label": np.asarray(c.strings("label", n), dtype=object)}
        for key, name, _ in COLUMNS:
            if key in ("mode", "label"):
                continue
            if key == "inv_k":
                cols[key] = _inverse_k(c, name, n)
            else:
                cols[key] = c.array(name, shape=(n,))
        return cls(cols, ref, r.string("model_name"))

    def __len__(self) -> int:
        return len(self.columns["V"])

    def header(self) -> list[str]:
        """The lines stating b_ref, density, speed of sound and the sign convention."""
        r = self.reference
        name = f"{self.model_name}: " if self.model_name else ""
        return [f"{name}flutter summary (per mode and speed, as NASTRAN SOL 145)",
                f"  k = omega b_ref / V with b_ref = {r.b_ref:.4g} m ({r.b_ref_is}); density "
                f"{r.density:.4g} kg/m^3; Mach = V / {r.speed_of_sound:.5g} m/s",
                f"  {CONVENTION}"]

    def format(self, modes: Sequence[int | str] | None = None) -> str:
        """The summary as text: the header, then one table per mode (ids or names, in the
        given order; default every mode)."""
        c = self.columns
        ids = list(dict.fromkeys(int(k) for k in c["mode"]))
        if modes is not None:
            by_name = {str(c["label"][i]): int(c["mode"][i]) for i in range(len(self))}
            want = []
            for m in modes:
                k = by_name.get(m) if isinstance(m, str) else int(m)
                if k is None or k not in ids:
                    raise v.InputError(f"modes: {m!r} is not a physical mode of the summary")
                want.append(k)
            ids = want
        heads = ["V [m/s]", "k", "1/k", "zeta", "g", "f [Hz]", "density [kg/m^3]", "Mach",
                 "Re lambda [1/s]", "Im lambda [1/s]"]
        out = self.header()
        for k in ids:
            rows = np.flatnonzero(c["mode"] == k)
            label = c["label"][rows[0]]
            table = [[f"{c['V'][i]:.2f}", f"{c['k'][i]:.4f}", _inv(c["inv_k"][i]),
                      f"{c['zeta'][i]:.5f}", f"{c['g'][i]:.5f}", f"{c['frequency_hz'][i]:.4f}",
                      f"{c['density'][i]:.4g}", f"{c['mach'][i]:.4f}", f"{c['real'][i]:.5g}",
                      f"{c['imag'][i]:.5g}"] for i in rows]
            out += ["", f"mode {k}: {label}", text_table(table, heads, "r" * len(heads))]
        return "\n".join(out)

    def to_csv(self, path: str | Path | None = None) -> str:
        """The summary as CSV (header: the names of :data:`COLUMNS`; floats written with
        ``repr``, 1/k empty where k = 0); also written to ``path`` if given (atomically)."""
        buf = io.StringIO()
        w = fileio.csv_writer(buf, lineterminator="\n")
        w.writerow([name for _, name, _ in COLUMNS])
        for i in range(len(self)):
            row = []
            for key, _, _ in COLUMNS:
                x = self.columns[key][i]
                if key == "label":
                    row.append(str(x))
                elif key == "mode":
                    row.append(str(int(x)))
                else:
                    row.append("" if not math.isfinite(x) else repr(float(x)))
            w.writerow(row)
        text = buf.getvalue()
        if path is not None:
            fileio.write_text(path, text, what="flutter summary")
        return text

    def to_dataframe(self):
        """The summary as a pandas DataFrame (columns as in the CSV; units in ``df.attrs``)."""
        pd = require_pandas()
        df = pd.DataFrame({name: self.columns[key] for key, name, _ in COLUMNS})
        df.attrs["units"] = {name: unit for _, name, unit in COLUMNS if unit}
        df.attrs["reference"] = self.reference.to_dict()
        df.attrs["convention"] = CONVENTION
        return df


def _inverse_k(c: SavedDict, name: str, n: int) -> np.ndarray:
    """The 1/k column: n numbers > 0, null for k = 0 (read as infinity)."""
    raw = c.raw(name)
    if not isinstance(raw, list) or len(raw) != n:
        raise v.InputError(f"{c.name(name)}: must be a list of {n} entries (one per row)")
    out = np.empty(n)
    for i, x in enumerate(raw):
        if x is None:
            out[i] = np.inf
            continue
        ok = isinstance(x, (int, float)) and not isinstance(x, bool)
        try:
            out[i] = float(x) if ok else np.nan
        except OverflowError:
            out[i] = np.nan
        if not (math.isfinite(out[i]) and out[i] > 0):
            raise v.InputError(f"{c.name(name)}[{i}]: must be a number > 0 or null (k = 0), "
                               f"got {x!r:.40}")
    return out


def _inv(x: float) -> str:
    return "-" if not math.isfinite(x) else f"{x:.4f}"


def require_pandas():
    """pandas, or an ImportError naming the extra that installs it."""
    try:
        import pandas
    except ImportError:
        raise ImportError("DataFrames need pandas: pip install propwhirl[data]") from None
    return pandas


def flutter_summary(sweep: Sweep, ref: Reference, model_name: str = "") -> FlutterSummary:
    """The :class:`FlutterSummary` of a sweep (its physical modes, :meth:`Sweep.table`)."""
    if not isinstance(ref, Reference):
        raise v.InputError(f"reference = {ref!r:.60} is invalid: must be a Reference")
    t = sweep.table()
    order = np.lexsort((t["V"], t["mode"]))
    t = {key: np.asarray(col)[order] for key, col in t.items()}
    omega = np.abs(t["imag"])
    k = omega * ref.b_ref / t["V"]
    with np.errstate(divide="ignore"):
        inv_k = np.where(k > 0, 1.0 / np.where(k > 0, k, 1.0), np.inf)
    cols = {"mode": t["mode"].astype(int), "label": t["label"], "V": t["V"], "k": k,
            "inv_k": inv_k, "zeta": t["damping_ratio"], "g": 2.0 * t["damping_ratio"],
            "frequency_hz": t["frequency_hz"], "density": np.full(k.shape, ref.density),
            "mach": t["V"] / ref.speed_of_sound, "real": t["real"], "imag": t["imag"]}
    return FlutterSummary(cols, ref, model_name)


# ----------------------------------------------------------------------------- p-k vs finite state
#: the names of the finite-state forms of the strip aerodynamics (``aero_model``)
AERO_NAMES = {"leishman-nguyen": "Leishman-Nguyen", "wagner": "Wagner"}


def aero_model_of(model) -> str:
    """The finite-state aerodynamics of a typical section or a wing (``aero_model``:
    "leishman-nguyen" or "wagner")."""
    owner = getattr(model, "wing", getattr(model, "planform", model))   # a modal model's strips
    return str(getattr(owner, "aero_model"))


@dataclass(frozen=True)
class FiniteState:
    """The finite-state instabilities of an analysis whose events are the p-k method's
    (``analyse(model, method="pk")``): the events of the tracked finite-state modes
    (:class:`~propwhirl.analysis.stability.Instability`, with participation and benignity)
    and the finite-state form of the strip aerodynamics they come from ("leishman-nguyen"
    or "wagner", thesis §7.3)."""

    aero_model: str
    events: tuple

    def __post_init__(self) -> None:
        if self.aero_model not in AERO_NAMES:
            raise v.InputError(f"aero_model = {self.aero_model!r} is invalid: must be one of "
                               f"{', '.join(AERO_NAMES)}")

    @property
    def name(self) -> str:
        """'Leishman-Nguyen' or 'Wagner'."""
        return AERO_NAMES[self.aero_model]


@dataclass(frozen=True)
class ComparedEvent:
    """One instability by the exact p-k method and by the finite-state analysis.

    kind, event, mode, label: as :class:`~propwhirl.analysis.stability.Instability`;
    V_pk, f_pk: speed [m/s] and frequency [Hz] by the p-k method (None: not found by it);
    V_fs, f_fs: by the finite-state analysis (None: not found by it).
    """

    kind: str
    event: str
    mode: int
    label: str
    V_pk: float | None
    f_pk: float | None
    V_fs: float | None
    f_fs: float | None

    @property
    def found_by(self) -> str:
        """"both", "p-k only" or "finite state only"."""
        return ("both" if self.V_pk is not None and self.V_fs is not None
                else "p-k only" if self.V_pk is not None else "finite state only")

    @property
    def dV(self) -> float | None:
        """V_pk − V_fs [m/s] (None unless found by both)."""
        return None if self.found_by != "both" else self.V_pk - self.V_fs

    @property
    def dV_percent(self) -> float | None:
        """100 (V_pk − V_fs) / V_fs [%]."""
        return None if self.dV is None else 100.0 * self.dV / self.V_fs

    @property
    def df(self) -> float | None:
        """f_pk − f_fs [Hz] (None unless found by both)."""
        return None if self.found_by != "both" else self.f_pk - self.f_fs

    @property
    def df_percent(self) -> float | None:
        """100 (f_pk − f_fs) / f_fs [%] (None at zero frequency: divergence)."""
        return None if self.df is None or self.f_fs == 0 else 100.0 * self.df / self.f_fs

    def to_dict(self) -> dict[str, Any]:
        d = {k: getattr(self, k) for k in ("kind", "event", "mode", "label", "V_pk", "f_pk",
                                          "V_fs", "f_fs")}
        d.update(found_by=self.found_by, dV=self.dV, dV_percent=self.dV_percent, df=self.df,
                 df_percent=self.df_percent)
        return d


@dataclass(frozen=True)
class MethodComparison:
    """Every instability of a p-k analysis beside the finite-state one (:func:`compare_methods`):
    the rows sorted by speed, and the name of the finite-state aerodynamics."""

    aerodynamics: str
    rows: tuple[ComparedEvent, ...]
    #: the p-k side's aerodynamics (the table's heading; not saved: the analysis's notes say it)
    exact: str = "p-k, Theodorsen's C(k)"

    def format(self, indent: str = "  ") -> str:
        """The side-by-side table as text, with its legend."""
        def num(x: float | None, fmt: str) -> str:
            return "-" if x is None else format(x, fmt)

        def pct(x: float | None) -> str:
            return "-" if x is None else f"{x:+.2f}"

        heads = ["type", "event", "mode", "V p-k [m/s]", "V fs [m/s]", "dV [m/s]", "dV [%]",
                 "f p-k [Hz]", "f fs [Hz]", "df [Hz]", "df [%]"]
        rows = [[r.kind, r.event, r.label, num(r.V_pk, ".2f"), num(r.V_fs, ".2f"),
                 num(r.dV, "+.2f"), pct(r.dV_percent), num(r.f_pk, ".3f"), num(r.f_fs, ".3f"),
                 num(r.df, "+.3f"), pct(r.df_percent)] for r in self.rows]
        lines = [f"exact ({self.exact}) vs finite-state ({self.aerodynamics}) "
                 "aerodynamics, per instability:"]
        lines += text_table(rows, heads, "lll" + "r" * 8).splitlines()
        lines.append(f"dV = V p-k - V finite state, df = f p-k - f finite state (%: of the "
                     "finite-state value); '-': not found by that method")
        lines += [f"  {r.kind} {r.event} of {r.label}: found by the "
                  f"{'p-k method' if r.found_by == 'p-k only' else 'finite-state analysis'} only"
                  + (" (the p-k continuation follows oscillatory roots, not a pair turning "
                     "real)" if r.event == "frequency-zero" else "")
                  for r in self.rows if r.found_by != "both"]
        return "\n".join(indent + line for line in lines)

    def to_dict(self) -> dict[str, Any]:
        return {"aerodynamics": self.aerodynamics, "rows": [r.to_dict() for r in self.rows]}


def compare_methods(exact: Sequence, finite_state: FiniteState) -> MethodComparison:
    """The p-k events ``exact`` beside the finite-state events of ``finite_state``.

    Events are matched by mode (the tracked mode id, which the p-k events take from their
    mode shape, :func:`propwhirl.analysis.pk.tracked_mode`), kind and event: the n-th such
    event by speed of one method with the n-th of the other.  An event without a partner is
    a row with the other side None ("found by ... only").
    """
    def groups(events):
        out: dict[tuple, list] = {}
        for e in sorted(events, key=lambda e: (e.V, e.mode)):
            out.setdefault((e.mode, e.kind, e.event), []).append(e)
        return out

    a, b = groups(exact), groups(finite_state.events)
    rows = []
    for key in dict.fromkeys(list(a) + list(b)):
        pk, fs = a.get(key, []), b.get(key, [])
        for i in range(max(len(pk), len(fs))):
            e = pk[i] if i < len(pk) else None
            g = fs[i] if i < len(fs) else None
            ref = e or g
            rows.append(ComparedEvent(ref.kind, ref.event, ref.mode, ref.label,
                                      None if e is None else float(e.V),
                                      None if e is None else float(e.frequency_hz),
                                      None if g is None else float(g.V),
                                      None if g is None else float(g.frequency_hz)))
    rows.sort(key=lambda r: (min(x for x in (r.V_pk, r.V_fs) if x is not None), r.mode))
    return MethodComparison(finite_state.name, tuple(rows))
