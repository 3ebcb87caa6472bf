"""Model files (TOML): :func:`loads` / :func:`load_model` read them, :func:`dumps` /
:func:`save_model` write them.

A file holds a :class:`~propwhirl.model.systems.PropellerWing`, an
:class:`~propwhirl.model.systems.IsolatedPropeller` or a bare
:class:`~propwhirl.model.propellers.propeller.Propeller`.  Reader and writer are driven by the field
declarations of the model dataclasses (:mod:`propwhirl.io.schema`); every key, unit and
default is listed in ``docs/model-file.md``.  Reading uses the standard library's ``tomllib``;
writing uses tomli-w (the optional extra ``pip install propwhirl[toml]``), with the informative
header of :func:`propwhirl.io.schema.header` prepended.  Floats are written as their shortest
round-trip text, so save → load reproduces every number exactly, and the text is
deterministic.

Layout of a file (TOML tables in this order)::

    format = "propwhirl-model"
    format_version = 2               # older versions are read too (io/versions.py)
    type = "propeller-wing"          # or "isolated-propeller", "propeller"
    name = "..."
    installations = [...]            # propeller-wing: propeller key, y_m, mount, aero
    propeller = "p1"                 # isolated-propeller / propeller files
    [wing]                           # propeller-wing
    [flight]
    [switches]
    [propellers.p1]                  # identical propellers share one key
    [propellers.p1.rotor]            # and .inertia, .aero_settings, .derivatives, ...
"""
from __future__ import annotations

import contextvars
import difflib
import math
import re
import tomllib
from pathlib import Path
from typing import Any, Iterable

import numpy as np

from propwhirl import limits
from propwhirl import fileio
from propwhirl import validate as v
from propwhirl.io import alternatives, schema, versions
from propwhirl.io.schema import DERIVATIVE_SOURCES, FORMAT, FORMAT_VERSION, MODEL_TYPES, Field
from propwhirl.model.propellers.propeller import Propeller
from propwhirl.model.propellers.propeller_aero import Distribution
from propwhirl.model.systems import Installation

_MISSING = object()
_FAILED = object()   # a [propellers.KEY] table that could not be read (its errors reported)
_NUMBER_HELP = {"spanwise": "give a number or one value per element (evaluate the function at "
                            "wing.element_y)",
                "number_or_string": "give a number or one of the strings",
                "distribution": "give a number or a propwhirl.model.propellers.propeller_aero.Distribution "
                                "(tabulated)"}


_join = schema.join


# =============================================================================== reading
def _table_label(where: str) -> str:
    return f"[{where}]" if where else "the top level"


def _in_file(exc: v.InputError) -> v.InputError:
    exc.in_file = True  # type: ignore[attr-defined]  # restated with the file's keys already
    return exc


#: Most errors of one file reported (the rest are counted).
MAX_ERRORS = 20
#: The errors of the file being read (set by :func:`loads`: every error of a file is reported
#: at once); None outside it: the first error is raised (campaign and modal files).
_ERRORS: contextvars.ContextVar[list[str] | None] = contextvars.ContextVar("_ERRORS", default=None)


class _Failed(Exception):
    """A table (or a key) that could not be read: its errors are recorded already; whatever
    depends on it is not read (no error follows from another)."""


def _report(exc: v.InputError) -> None:
    """Record `exc` (one error of the file) when every error is collected; else raise it."""
    errors = _ERRORS.get()
    if errors is None:
        raise exc
    text = str(exc)
    if text not in errors:
        errors.append(text)


class Table:
    """A TOML table being read: known keys only; errors name the table and the key as written."""

    def __init__(self, data: Any, where: str, allowed: Iterable[str]):
        if not isinstance(data, dict):
            raise _in_file(v.InputError(f"{where} = {v.short_repr(data)} is invalid: must be a "
                                        "table"))
        self.data, self.where = data, where
        allowed = tuple(allowed)
        #: unknown keys (reported): a key missing from this table may be one of them misspelled
        self.unknown = [k for k in data if k not in allowed]
        for key in self.unknown:   # each one reported
            close = difflib.get_close_matches(key, allowed, 1)
            hint = f" (did you mean {close[0]}?)" if close else ""
            _report(_in_file(v.InputError(
                f"unknown key {key!r} in {_table_label(where)}{hint}: valid keys are "
                f"{', '.join(allowed)}")))

    def name(self, key: str) -> str:
        return _join(self.where, key)

    def has(self, key: str) -> bool:
        return key in self.data

    def missing(self, key: str, what: str = "", kind: str = "key") -> Exception:
        if self.unknown:     # perhaps misspelled as an unknown key: that one is reported
            return _Failed()
        return _in_file(v.InputError(f"missing {kind} {key!r} in {_table_label(self.where)}"
                                     + (f" ({what})" if what else "")))

    def raw(self, key: str, what: str = "") -> Any:
        if key not in self.data:
            raise self.missing(key, what)
        return self.data[key]

    def bad(self, key: str, must: str, what: str = "") -> v.InputError:
        prefix = f"[{self.where}] " if self.where else ""
        return _in_file(v.InputError(
            f"{prefix}{key} = {v.short_repr(self.data[key])} is invalid: must be {must}"
            + (f" ({what})" if what else "")))

    def number(self, key: str, what: str = "") -> float:
        x = self.raw(key, what)
        if isinstance(x, bool) or not isinstance(x, (int, float)):
            raise self.bad(key, "a number", what)
        return float(x)

    def numbers(self, key: str, what: str = "", length: int | None = None) -> list[float]:
        x = self.raw(key, what)
        if (not isinstance(x, list) or not x or (length is not None and len(x) != length)
                or any(isinstance(i, bool) or not isinstance(i, (int, float)) for i in x)):
            raise self.bad(key, f"a list of {length or 'one or more'} numbers", what)
        return [float(i) for i in x]

    def integer(self, key: str, what: str = "") -> int:
        x = self.raw(key, what)
        if isinstance(x, bool) or not isinstance(x, int):
            raise self.bad(key, "an integer", what)
        return x

    def string(self, key: str, what: str = "", choices: tuple[str, ...] = ()) -> str:
        x = self.raw(key, what)
        if not isinstance(x, str):
            raise self.bad(key, "a string", what)
        if choices and x not in choices:
            raise self.bad(key, f"one of {', '.join(choices)}", what)
        return x

    def boolean(self, key: str, what: str = "") -> bool:
        x = self.raw(key, what)
        if not isinstance(x, bool):
            raise self.bad(key, "true or false", what)
        return x

    def sub(self, key: str, allowed: Iterable[str]) -> "Table":
        return Table(self.raw(key), self.name(key), allowed)


_what = schema.what


def _required(f: Field, t: Table | None) -> bool:
    """The file must give `f` in table `t` (always, or under the field's condition)."""
    if f.required:
        return True
    data = t.data if t is not None else {}
    if f.required_when == "houbolt-reed":
        return "derivatives" not in data
    if f.required_when == "fixed-pitch":
        return data.get("operation", "fixed-pitch") != "constant-speed"
    return False


def _read_scalar(f: Field, t: Table, key: str) -> Any:
    what, form = _what(f), f.form
    if form == "number":
        return t.number(key, what)
    if form == "integer":
        return t.integer(key, what)
    if form == "boolean":
        return t.boolean(key, what)
    if form == "string":
        return t.string(key, what, f.choices)
    if form == "numbers":
        return tuple(t.numbers(key, what, f.spec.length))
    if form == "spanwise":
        x = t.raw(key)
        return np.asarray(t.numbers(key, what)) if isinstance(x, list) else t.number(key, what)
    if form == "number_or_string":
        return (t.string(key, what, f.choices) if isinstance(t.raw(key), str)
                else t.number(key, what))
    raise AssertionError(form)


def _read_distribution(f: Field, t: Table) -> Any:
    s = f.spec
    given = [k for k in (s.number_key, s.key) if k and t.has(k)]
    if not given:
        if _required(f, t):
            raise t.missing(s.number_key or s.key, _what(f)
                            + (f"; or a table [{t.name(s.key)}]" if s.number_key else ""))
        return _MISSING
    if len(given) == 2:
        raise _in_file(v.InputError(
            f"[{t.where}]: give exactly one of {s.number_key} (a number) or "
            f"[{t.name(s.key)}] (a table eta, {s.value_key})"))
    if given[0] == s.number_key:
        return t.number(s.number_key, _what(f))
    d = t.sub(s.key, ("name", "eta", s.value_key))
    eta, values = d.numbers("eta"), d.numbers(s.value_key)
    name = d.string("name") if d.has("name") else schema.distribution_name(s)
    with _Context(d.where):
        return Distribution.tabulated(eta, values, name)


def _read_field(f: Field, t: Table | None, ctx: dict[str, Propeller],
                parent: Table | None = None) -> Any:
    """The value of field `f` from table `t`; _MISSING when optional and not given.

    `parent`: the table holding `t` when `t` is a section such as [switches] (None if absent)."""
    s, form = f.spec, f.form
    if form == "flat":
        return from_table(f.item, t, ctx)
    if form == "distribution":
        return _read_distribution(f, t)
    keys = s.key if form == "split" else (s.key,)
    if t is None or not any(t.has(k) for k in keys):
        if _required(f, t):
            kind = "table" if form in ("table", "mapping", "derivatives") else "key"
            if t is None:
                where = _join(parent.where if parent else "", s.section or "")
                raise _in_file(v.InputError(f"missing key {keys[0]!r} in {_table_label(where)} "
                                            f"({_what(f)})"))
            raise t.missing(keys[0], _what(f), kind)
        return s.file_default if s.file_default is not None else _MISSING
    if form == "split":
        return tuple(t.number(k, _what(f, i)) if t.has(k) else f.default[i]
                     for i, k in enumerate(keys))
    if form == "table":
        return from_table(f.item, t.sub(s.key, schema.table_keys(f.item)), ctx)
    if form in ("tables", "installations"):
        item = Installation if form == "installations" else f.item
        raw = t.raw(s.key)
        if not isinstance(raw, list):
            raise t.bad(s.key, "a list of tables", _what(f))
        out, failed = [], False
        for i, x in enumerate(raw):   # every entry read, its errors reported
            try:
                out.append(from_table(item, Table(x, f"{t.name(s.key)}[{i}]",
                                                  schema.table_keys(item)), ctx))
            except v.InputError as exc:
                _report(exc)
                failed = True
            except _Failed:
                failed = True
        if failed:
            raise _Failed
        return tuple(out)
    if form == "mapping":
        m = t.sub(s.key, [e.key for e in s.entries])
        out = {}
        for e in s.entries:
            if m.has(e.key):
                rng = f"; valid range {e.range}{' ' + e.unit if e.unit else ''}" if e.range else ""
                out[e.name] = m.number(e.key, e.doc + rng)
        return out
    if form == "derivatives":
        raw = t.raw(s.key)
        source = raw.get("source") if isinstance(raw, dict) else None
        if source not in DERIVATIVE_SOURCES:
            choices = ", ".join(f'"{k}"' for k in DERIVATIVE_SOURCES)
            if isinstance(raw, dict) and "source" not in raw:
                raise _in_file(v.InputError(f"missing key 'source' in [{t.name(s.key)}] "
                                            f"(one of {choices})"))
            raise _in_file(v.InputError(f"[{t.name(s.key)}] source = {v.short_repr(source)} is "
                                        f"invalid: must be one of {choices}"))
        cls = DERIVATIVE_SOURCES[source]
        return from_table(cls, t.sub(s.key, ("source",) + schema.table_keys(cls)), ctx)
    if form == "groups":
        return _read_groups(t, s.key)
    if form == "reference":
        key = t.raw(s.key)
        if not isinstance(key, str) or key not in ctx:
            raise t.bad(s.key, f"the key of a [propellers.*] table ({', '.join(ctx) or 'none given'})")
        if ctx[key] is _FAILED:       # the table's own errors are reported
            raise _Failed
        return ctx[key]
    return _read_scalar(f, t, s.key)


def _read_groups(t: Table, key: str) -> dict[str, tuple[int, ...]]:
    """The [groups] table: NAME = [indices of installations, from 0] (checked further by the
    model: :func:`propwhirl.model.systems.check_groups`)."""
    raw = t.raw(key)
    if not isinstance(raw, dict):
        raise t.bad(key, "a table [groups] of NAME = [indices of installations, from 0]")
    out = {}
    for name, members in raw.items():
        if (not isinstance(members, list) or not members
                or any(isinstance(i, bool) or not isinstance(i, int) for i in members)):
            raise _in_file(v.InputError(
                f"[{t.name(key)}] {name} = {v.short_repr(members)} is invalid: must be a "
                "non-empty list of installation indices (integers from 0: 0 is the first entry "
                "of installations, 'propeller 1' of the reports)"))
        out[name] = tuple(members)
    return out


def _old_default(cls: type, f: Field, t: Table | None) -> Any:
    """The value the file's older format version gives field `f` of `cls` where the file
    omits it and this version requires it (:mod:`propwhirl.io.versions`); else _MISSING."""
    if (t is not None and any(t.has(k) for k in f.keys())) or not _required(f, t):
        return _MISSING
    return versions.current().default(cls, f.name, t.where if t is not None else "",
                                      f.keys()[0], _MISSING)


def from_table(cls: type, t: Table, ctx: dict[str, Propeller]) -> Any:
    """An instance of schema class `cls` from table `t` (whose keys were checked)."""
    kw: dict[str, Any] = {}
    sections: dict[str, Table | None] = {}
    failed = False          # a key could not be read: its error is reported, cls not built
    try:  # keys standing for other fields (the ISA altitude of [flight]): io/alternatives.py
        given, replaced = alternatives.read(cls, t, {f.name: f.key for f in schema.fields_of(cls)})
    except v.InputError as exc:
        _report(_in_file(exc))
        alt = alternatives.ALTERNATIVES.get(cls)
        given, replaced, failed = {}, set(alt.replaces if alt else ()), True
    kw.update(given)
    for f in schema.fields_of(cls):
        if f.spec.key is None or f.name in replaced:
            continue
        try:
            table: Table | None = t
            if f.spec.section is not None:
                sec = f.spec.section
                if sec not in sections:
                    allowed = [k for g in schema.section_fields(cls, sec) for k in g.keys()]
                    sections[sec] = t.sub(sec, allowed) if t.has(sec) else None
                table = sections[sec]
            value = _old_default(cls, f, table)
            if value is _MISSING:
                value = _read_field(f, table, ctx, t)
        except v.InputError as exc:   # reported; the other keys are read on
            _report(exc)
            failed = True
            continue
        except _Failed:
            failed = True
            continue
        if value is not _MISSING:
            kw[f.name] = value
    if failed:
        raise _Failed
    with _Context(t.where, cls, t):
        return cls(**kw)


_NAME = re.compile(r"(?<![\w.\[])([A-Za-z_]\w*)(?![\w(])")


class _Context:
    """Restate an InputError raised while building an object from table `where` (of class
    `cls`) with the table and the keys as the file writes them."""

    def __init__(self, where: str, cls: type | None = None, table: Table | None = None):
        self.where, self.cls, self.table = where, cls, table

    def __enter__(self) -> None:
        return None

    def __exit__(self, kind, exc, tb) -> None:
        if not isinstance(exc, v.InputError) or getattr(exc, "in_file", False):
            return
        raise _in_file(v.InputError(self.restate(exc))) from exc

    def restate(self, exc: v.InputError) -> str:
        located = (schema.locate(self.cls, self.where, exc.path)
                   if self.cls is not None and exc.structured else None)
        if located is not None:
            where, key, what = located
            reason = self.keys(exc.reason)
            if "valid range" in reason:  # the range (and its unit) is already stated
                what = what.split("; ")[0]
            prefix = f"[{where}] " if where else ""
            return f"{prefix}{key} = {v.short_repr(exc.value)} is {reason} ({what})"
        prefix = f"[{self.where}]: " if self.where else ""
        return prefix + self.keys(str(exc))

    def keys(self, text: str) -> str:
        """`text` with the Python names of the fields of `cls` replaced by their file keys."""
        if self.cls is None:
            return text
        names = {f.name: f.keys()[0] for f in schema.fields_of(self.cls)
                 if f.spec.key is not None and f.keys() and f.keys()[0] != f.name
                 and f.form not in ("flat", "installations", "tables", "table")}
        if not names:
            return text
        return _NAME.sub(lambda m: names.get(m.group(1), m.group(1)), text)


def _from_dict(data: dict[str, Any]) -> Any:
    if data.get("format") == "propwhirl-modal-model":
        raise _in_file(v.InputError(
            'format = "propwhirl-modal-model": this is a modal model: read it with '
            "propwhirl.io.load_modal_model (the command line's model commands read it as it "
            "is)"))
    if "type" not in data:
        raise _in_file(v.InputError("missing key 'type' at the top level (one of "
                                    + ", ".join(f'"{k}"' for k in MODEL_TYPES) + ")"))
    kind = data["type"]
    if kind not in MODEL_TYPES:
        raise _in_file(v.InputError(f"type = {v.short_repr(kind)} is invalid: must be one of "
                                    + ", ".join(f'"{k}"' for k in MODEL_TYPES)))
    cls = MODEL_TYPES[kind]
    file_keys = ("format", "format_version", "type")
    body = ("name", "propeller") if cls is Propeller else schema.table_keys(cls)
    top = Table(data, "", file_keys + body + ("propellers",))
    if top.has("format") and top.string("format") != FORMAT:
        raise top.bad("format", repr(FORMAT))
    versions.current().read_version(top)
    props_raw = data.get("propellers", {})
    if not isinstance(props_raw, dict):
        raise top.bad("propellers", "tables [propellers.KEY]")
    keys = schema.table_keys(Propeller)
    ctx: dict[str, Any] = {}
    for k, p in props_raw.items():   # every table read; a failed one is not referred to again
        try:
            ctx[k] = from_table(Propeller, Table(p, f"propellers.{k}", keys), {})
        except v.InputError as exc:
            _report(exc)
            ctx[k] = _FAILED
        except _Failed:
            ctx[k] = _FAILED
    if cls is Propeller:
        if top.has("name"):
            top.string("name")
        ref = next(f for f in schema.fields_of(Installation) if f.form == "reference")
        return _read_field(ref, top, ctx)  # the top-level key "propeller"
    # Cross-field checks of a wing (propellers on nodes, one per node) name the installation.
    return from_table(cls, top, ctx)


def toml_error(exc: tomllib.TOMLDecodeError, text: str) -> str:
    """tomllib's error with the offending line of `text` quoted (the error names its number)."""
    m = re.search(r"line (\d+)", str(exc))
    lines = text.splitlines()
    if m and 0 < int(m.group(1)) <= len(lines):
        return f"{exc}: {lines[int(m.group(1)) - 1].strip()!r}"
    return str(exc)


def loads(text: str, source: str = "<string>", *, notes: list[str] | None = None) -> Any:
    """The model in TOML `text` (a PropellerWing, IsolatedPropeller or Propeller).

    Every problem — bad TOML, a key given twice, an unknown or missing key, a wrong type, an
    invalid value, a format version newer than this propwhirl — is a one-line error starting
    with `source` and naming the key as written in the file.  Every error of the file is
    reported at once (one InputError, one line per error, at most :data:`MAX_ERRORS` of them;
    the lines are also its attribute ``errors``); a table that cannot be read is not used
    further, so no error follows from another.  Bad TOML and an unknown format version stop
    the reading at once.

    A file of an older format version (``format_version = 1``, or none) is read as that
    version built its model (:mod:`propwhirl.io.versions`); one line starting with `source` and
    naming the values assumed for omitted keys is appended to the list `notes`, if given.

    Parameters
    ----------
    text : str
        The TOML text of a model file (SI units, the unit of each quantity the suffix of its
        key: ``radius_m``, ``f_theta_hz``, ...; docs/model-file.md).
    source : str
        How errors and notes name the text (a file's path).
    notes : list of str, optional
        Receives one line per older-format assumption.

    Returns
    -------
    PropellerWing or IsolatedPropeller or Propeller
        The model the file's ``type`` names.

    Raises
    ------
    InputError
        Every problem of the file, one line each.

    Examples
    --------
    >>> from propwhirl.io import loads
    >>> p = loads('''
    ... type = "propeller"
    ... propeller = "p"
    ... [propellers.p]
    ... radius_m = 1.0
    ... rotor = { mass_kg = 10.0, x_m = -0.5 }
    ... f_theta_hz = 5.0
    ... f_psi_hz = 5.0
    ... pivot_pitch_m = 0.0
    ... pivot_yaw_m = 0.0
    ... rotation = 1
    ... n_blades = 3
    ... hub_radius_m = 0.1
    ... blade_chord_m = 0.08
    ... beta_075_deg = 30.0
    ... zero_lift_angle_deg = -3.0
    ... ''')
    >>> p.radius, p.beta_075_deg, p.damping
    (1.0, 30.0, 'g')
    """
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise v.InputError(f"{source}: not valid TOML: {toml_error(exc, text)}") from exc
    except RecursionError:          # tomllib recurses per level of nested arrays/tables
        raise limits.nesting_error(source) from None
    limits.check_nesting(data, source)
    reading = versions.Reading()
    token = versions.CURRENT.set(reading)
    errors: list[str] = []
    collecting = _ERRORS.set(errors)
    try:
        model = _from_dict(data)
    except v.InputError as exc:
        _report(exc)
    except _Failed:
        pass
    except (TypeError, ValueError) as exc:  # anything a constructor let through unchecked
        errors.append(f"invalid model: {exc}")
    finally:
        _ERRORS.reset(collecting)
        versions.CURRENT.reset(token)
    if errors:
        raise _file_errors(source, errors)
    note = reading.note(source)
    if notes is not None and note is not None:
        notes.append(note)
    return model


def _file_errors(source: str, errors: list[str]) -> v.InputError:
    """One InputError of every error of file `source`: one line each, naming the file (its
    lines also as the attribute ``errors``)."""
    def table(e: str) -> bool:     # the [propellers.KEY] tables last, as the file has them
        m = re.search(r"\[([^\]]*)\]", e)
        return bool(m) and m.group(1).startswith("propellers.")

    errors = sorted(errors, key=table)
    lines = [f"{source}: {e}" for e in errors[:MAX_ERRORS]]
    if len(errors) > MAX_ERRORS:
        lines.append(f"{source}: and {len(errors) - MAX_ERRORS} more errors")
    exc = v.InputError("\n".join(lines))
    exc.errors = lines  # type: ignore[attr-defined]
    return exc


def load_model(path: str | Path, *, notes: list[str] | None = None) -> Any:
    """Read a TOML model file written by :func:`save_model` (or by hand); errors and `notes`
    (the values assumed for an older format version) as :func:`loads`, naming the path.

    Parameters
    ----------
    path : str or Path
        The model file (``.toml``; SI units, the unit of each quantity the suffix of its key,
        docs/model-file.md).
    notes : list of str, optional
        Receives one line per older-format assumption (:func:`loads`).

    Returns
    -------
    PropellerWing or IsolatedPropeller or Propeller
        The model the file describes.

    Raises
    ------
    InputError
        An unreadable file, or every problem of its content, one line each naming the path
        and the key.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> from propwhirl.io import load_model, save_model
    >>> from propwhirl.cases.ch09_baseline import isolated_baseline_propeller
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = save_model(isolated_baseline_propeller(), pathlib.Path(folder) / "p.toml")
    ...     model = load_model(path)
    >>> type(model).__name__, model.propeller.radius, model.flight.density
    ('IsolatedPropeller', 0.762, 0.96287)
    """
    path = Path(path)
    return loads(fileio.read_text(path, "model file", empty_ok=True,
                                 limit=fileio.MAX_TOML_BYTES), str(path), notes=notes)


# =============================================================================== writing
def _float(x: Any, where: str) -> float:
    f = float(x)
    if not math.isfinite(f):
        raise v.InputError(f"{where} = {f!r} cannot be saved: must be finite")
    return f


def _function(where: str, form: str) -> v.InputError:
    return v.InputError(f"{where} is a function and cannot be saved to TOML: {_NUMBER_HELP[form]}")


class Writer:
    """Encodes schema objects as dicts for tomli-w; numbers distinct propellers p1, p2, ..."""

    def __init__(self) -> None:
        self.keys: dict[int, str] = {}
        self.by_text: dict[str, str] = {}
        self.propellers: dict[str, dict[str, Any]] = {}

    def propeller_key(self, p: Propeller) -> str:
        """Identical propellers (identical tables) share one key."""
        if id(p) not in self.keys:
            key = f"p{len(self.propellers) + 1}"
            table = self.encode(p, f"propellers.{key}")
            text = repr(table)
            if text not in self.by_text:
                self.by_text[text] = key
                self.propellers[key] = table
            self.keys[id(p)] = self.by_text[text]
        return self.keys[id(p)]

    def encode(self, obj: Any, where: str) -> dict[str, Any]:
        out: dict[str, Any] = {}
        fields = schema.fields_of(type(obj))
        for f in sorted(fields, key=lambda f: f.name != "name"):  # the name first
            target = out if f.spec.section is None else out.setdefault(f.spec.section, {})
            self.field(f, getattr(obj, f.name), target, where)
        return out

    def field(self, f: Field, value: Any, out: dict[str, Any], where: str) -> None:
        s, form = f.spec, f.form
        name = _join(where, f.name)
        if form == "derived":
            return
        if form == "unsaved":
            if value is not f.default:
                raise v.InputError(f"{name} is set and cannot be saved to TOML: {s.doc}")
            return
        if value is None:
            return
        if form == "flat":
            out.update(self.encode(value, where))
        elif form == "split":
            out.update({k: _float(x, name) for k, x in zip(s.key, value)})
        elif form == "distribution":
            if isinstance(value, Distribution):
                if s.number_key and value.eta == (0.0, 1.0) and value.values[0] == value.values[1]:
                    out[s.number_key] = value.values[0]
                else:
                    out[s.key] = {"name": value.name, "eta": list(value.eta),
                                  s.value_key: list(value.values)}
            elif callable(value) or not s.number_key:
                raise _function(name, form)
            else:
                out[s.number_key] = _float(value, name)
        elif form == "table":
            out[s.key] = self.encode(value, _join(where, s.key))
        elif form in ("tables", "installations"):
            out[s.key] = [self.encode(x, f"{_join(where, s.key)}[{i}]") for i, x in enumerate(value)]
        elif form == "mapping":
            out[s.key] = {e.key: _float(value[e.name], name) for e in s.entries if e.name in value}
        elif form == "derivatives":
            source = next((k for k, c in DERIVATIVE_SOURCES.items() if type(value) is c), None)
            if source is None:
                raise v.InputError(
                    f"{name} = {value!r} cannot be saved to TOML: only "
                    + " and ".join(c.__name__ for c in DERIVATIVE_SOURCES.values())
                    + " (or None, Houbolt-Reed from the propeller) can")
            out[s.key] = {"source": source, **self.encode(value, _join(where, s.key))}
        elif form == "reference":
            out[s.key] = self.propeller_key(value)
        elif form == "groups":
            if value:
                out[s.key] = {k: [int(i) for i in x] for k, x in value.items()}
        elif form in ("spanwise", "number_or_string") and callable(value) and not isinstance(value, str):
            raise _function(name, form)
        elif form == "spanwise":
            arr = np.asarray(value, dtype=float)
            out[s.key] = _float(arr, name) if arr.ndim == 0 else [_float(x, name) for x in arr]
        elif form == "number_or_string":
            out[s.key] = value if isinstance(value, str) else _float(value, name)
        elif form == "number":
            out[s.key] = _float(value, name)
        elif form == "integer":
            out[s.key] = int(value)
        elif form == "boolean":
            out[s.key] = bool(value)
        elif form == "string":
            out[s.key] = str(value)
        elif form == "numbers":
            out[s.key] = [_float(x, name) for x in value]
        else:
            raise AssertionError(form)


def to_dict(model: Any) -> dict[str, Any]:
    """The TOML document of a model as plain Python data (what :func:`dumps` writes)."""
    kind = next((k for k, c in MODEL_TYPES.items() if type(model) is c), None)
    if kind is None:
        raise v.InputError(
            f"cannot save a {type(model).__name__}: model files hold a "
            + ", ".join(c.__name__ for c in MODEL_TYPES.values()))
    w = Writer()
    doc: dict[str, Any] = {"format": FORMAT, "format_version": FORMAT_VERSION, "type": kind}
    if isinstance(model, Propeller):
        doc["name"] = model.name
        doc["propeller"] = w.propeller_key(model)
    else:
        doc.update(w.encode(model, ""))
    doc["propellers"] = w.propellers
    return doc


def dumps(model: Any) -> str:
    """The TOML text of a model: the header comment, then the tables (see the module docs).

    Needs tomli-w (``pip install propwhirl[toml]``).

    Parameters
    ----------
    model : PropellerWing or IsolatedPropeller or Propeller
        The model (every value finite; a wing's chord given as a function of y cannot be
        saved).

    Returns
    -------
    str
        The model file's text: SI units, the unit of each quantity the suffix of its key.

    Examples
    --------
    >>> from propwhirl.io import dumps, loads
    >>> from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
    >>> model = wingtip_propeller_wing()
    >>> text = dumps(model)
    >>> loads(text).wing == model.wing
    True
    >>> [line for line in text.splitlines() if line.startswith("semi_span_m")]
    ['semi_span_m = 5.7']
    """
    doc = to_dict(model)  # fails first if the model cannot be saved
    try:
        import tomli_w
    except ImportError:
        raise v.InputError("writing a model file needs tomli-w: pip install propwhirl[toml]") from None
    return schema.header() + tomli_w.dumps(doc)


def save_model(model: Any, path: str | Path) -> Path:
    """Write `model` as a TOML model file; returns the path (needs ``propwhirl[toml]``).

    The file is replaced atomically (:func:`propwhirl.fileio.write_text`).

    Parameters
    ----------
    model : PropellerWing or IsolatedPropeller or Propeller
        The model (as :func:`dumps`).
    path : str or Path
        The file to write (``.toml``).

    Returns
    -------
    Path
        `path`.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> from propwhirl.io import load_model, save_model
    >>> from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
    >>> model = wingtip_propeller_wing()
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = save_model(model, pathlib.Path(folder) / "wingtip.toml")
    ...     again = load_model(path)
    >>> path.name, again == model
    ('wingtip.toml', True)
    """
    text = dumps(model)  # fails before touching the file if the model cannot be saved
    # atomic: a full disk or a Ctrl-C leaves the old file (or none), never a partial one
    return fileio.write_text(path, text, what="model file")
