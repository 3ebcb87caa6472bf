"""The model-file schema, read from the metadata of the model dataclasses' fields.

Each saved field declares its key, unit, description and the kind of its default with
:func:`propwhirl.model.fields.spec`; this module resolves those declarations (the form of the
value, its allowed strings, the nested dataclass) once per class, checks them (every field
declared, the kind of default given exactly when there is a default, the key's unit suffix
matching the unit), and generates the documentation ``docs/model-file.md``
(:func:`markdown`; ``python -m propwhirl.io > docs/model-file.md`` rewrites it).
:mod:`propwhirl.io.model_files` reads and writes files from the same resolved fields.
"""
from __future__ import annotations

import dataclasses
import functools
import json
import types
import typing
from dataclasses import dataclass
from typing import Any, Literal

from propwhirl.model.fields import META_KEY, FieldSpec
from propwhirl.model.propeller import MeasuredDerivatives, PointMass, Propeller
from propwhirl.model.propeller_aero import AeroSettings, HouboltReedSource, PropellerGeometry
from propwhirl.model.systems import FlightCondition, Installation, IsolatedPropeller, PropellerWing
from propwhirl.model.wing import Wing

FORMAT = "propwhirl-model"
FORMAT_VERSION = 1

#: The `type` key of a model file → the class it holds.
MODEL_TYPES: dict[str, type] = {"propeller-wing": PropellerWing,
                                "isolated-propeller": IsolatedPropeller, "propeller": Propeller}
#: The `source` key of a [propellers.KEY.derivatives] table → the derivative source class.
DERIVATIVE_SOURCES: dict[str, type] = {"measured": MeasuredDerivatives,
                                       "houbolt-reed": HouboltReedSource}
#: Every class with model-file fields.
SCHEMA_CLASSES: tuple[type, ...] = (PropellerWing, IsolatedPropeller, Installation,
                                    FlightCondition, Wing, Propeller, PointMass, AeroSettings,
                                    MeasuredDerivatives, HouboltReedSource, PropellerGeometry)

#: Units as written in specs → (key suffix, description).  A key ends with its unit's suffix.
UNITS: dict[str, tuple[str, str]] = {
    "m": ("_m", "metre"), "kg": ("_kg", "kilogram"), "kg/m": ("_kg_per_m", "kg/m"),
    "kg m": ("_kg_m", "kg m"), "kg m^2": ("_kg_m2", "kg m^2"), "kg/m^3": ("_kg_per_m3", "kg/m^3"),
    "N m^2": ("_N_m2", "N m^2"), "N m/rad": ("_N_m_per_rad", "N m/rad"),
    "m/s": ("_m_per_s", "m/s"), "Hz": ("_hz", "hertz"), "1/rad": ("_per_rad", "1/rad"),
    "1/s": ("_per_s", "1/s"), "s": ("_s", "second"), "deg": ("_deg", "degree"),
    "rev/min": ("rpm", "rev/min"),
    "chord": ("_chord", "fraction of the local chord from the leading edge"),
    "": ("", "dimensionless"),
}
#: (suffix, unit) pairs of the file header; "(none)" for dimensionless keys.
UNIT_SUFFIXES: tuple[tuple[str, str], ...] = tuple((s or "(none)", d) for s, d in UNITS.values())

HEADER_LINES: tuple[str, ...] = (
    f"propwhirl model file ({FORMAT}, format version {FORMAT_VERSION}): read it with",
    "`propwhirl analyse FILE` or propwhirl.io.load_model; every key: docs/model-file.md.",
    "SI units; the unit of each quantity is the suffix of its key:",
    *(f"  {s:12s} {u}" for s, u in UNIT_SUFFIXES),
    "Positions on a propeller shaft (x_m, pivot_*_m) are from the wing mid-chord, positive aft;",
    "wing h is positive down, twist alpha positive nose up (thesis conventions).",
)


def header() -> str:
    """The comment block at the top of every model file."""
    return "".join(f"# {line}\n" if line else "#\n" for line in HEADER_LINES) + "\n"


def unit_of_key(key: str) -> str:
    """The unit a key's suffix states (the longest matching suffix; "" when none matches)."""
    best = ""
    for unit, (suffix, _) in UNITS.items():
        if suffix and key.endswith(suffix) and len(suffix) > len(UNITS[best][0]):
            best = unit
    return best


# =============================================================================== fields
@dataclass(frozen=True)
class Field:
    """A dataclass field resolved for the model file."""

    name: str
    spec: FieldSpec
    form: str
    choices: tuple[str, ...]  # allowed strings (Literal of the type hint)
    item: type | None  # dataclass of a "table", "tables" or "flat" field
    default: Any  # the dataclass default; dataclasses.MISSING if none

    @property
    def key(self) -> str:
        return self.spec.key  # type: ignore[return-value]

    @property
    def required(self) -> bool:
        """The file must give this field."""
        return self.spec.file_required or (self.default is dataclasses.MISSING
                                           and self.spec.file_default is None)

    def keys(self) -> tuple[str, ...]:
        """The keys this field takes in its table (a "flat" field: its item's keys)."""
        if self.spec.key is None:
            return ()
        if self.form == "split":
            return tuple(self.spec.key)
        if self.form == "flat":
            return table_keys(self.item)
        if self.form == "distribution" and self.spec.number_key:
            return (self.spec.number_key, self.key)
        return (self.key,)


def _literals(hint: Any) -> tuple[str, ...]:
    if typing.get_origin(hint) is Literal:
        return tuple(typing.get_args(hint))
    if typing.get_origin(hint) in (typing.Union, types.UnionType):
        return tuple(s for h in typing.get_args(hint) for s in _literals(h))
    return ()


def _infer_form(hint: Any) -> tuple[str | None, type | None]:
    args = [a for a in typing.get_args(hint) if a is not type(None)]
    if typing.get_origin(hint) in (typing.Union, types.UnionType) and len(args) == 1:
        hint = args[0]  # X | None
    if hint is bool:
        return "boolean", None
    if hint is int:
        return "integer", None
    if hint is float:
        return "number", None
    if hint is str or (typing.get_origin(hint) is Literal
                       and all(isinstance(a, str) for a in typing.get_args(hint))):
        return "string", None
    if isinstance(hint, type) and dataclasses.is_dataclass(hint):
        return "table", hint
    if typing.get_origin(hint) is tuple:
        a = typing.get_args(hint)
        if len(a) == 2 and a[1] is Ellipsis and dataclasses.is_dataclass(a[0]):
            return "tables", a[0]
    return None, None


def _check_units(cls: type, f: Field) -> None:
    pairs: list[tuple[str, str]]
    if f.form == "split":
        pairs = list(zip(f.spec.key, f.spec.unit))
    elif f.form == "distribution":
        pairs = [(k, f.spec.unit) for k in (f.spec.number_key, f.spec.value_key) if k]
    elif f.form == "mapping":
        pairs = [(e.key, e.unit) for e in f.spec.entries]
    elif f.form in ("number", "numbers", "spanwise", "number_or_string"):
        pairs = [(f.key, f.spec.unit)]
    else:
        pairs = []
    for key, unit in pairs:
        if unit not in UNITS:
            raise TypeError(f"{cls.__name__}.{f.name}: unit {unit!r} is not in schema.UNITS")
        if unit_of_key(key) != unit:
            raise TypeError(f"{cls.__name__}.{f.name}: key {key!r} does not end with the suffix "
                            f"{UNITS[unit][0]!r} of its unit {unit!r}")


@functools.cache
def fields_of(cls: type) -> tuple[Field, ...]:
    """The resolved model-file fields of a schema class, in declaration order.

    Raises TypeError (a programming error, caught by the tests) when a field has no spec,
    when the kind of default is missing for a field with a default (or given for one without),
    when the form cannot be inferred, or when a key's suffix contradicts its unit."""
    hints = typing.get_type_hints(cls)
    out = []
    for dc in dataclasses.fields(cls):
        s = dc.metadata.get(META_KEY)
        if not isinstance(s, FieldSpec):
            raise TypeError(f"{cls.__name__}.{dc.name} has no model-file spec: declare it with "
                            "field(metadata=propwhirl.model.fields.spec(...))")
        default = dc.default
        if dc.default_factory is not dataclasses.MISSING:  # type: ignore[misc]
            default = dc.default_factory()  # type: ignore[misc]
        has_default = default is not dataclasses.MISSING or s.file_default is not None
        if has_default != (s.default is not None):
            raise TypeError(f"{cls.__name__}.{dc.name}: give spec(default=...) (physical, setting "
                            "or none) exactly when the field has a default")
        form, item = (s.form, None) if s.form is not None else _infer_form(hints[dc.name])
        if form is None:
            raise TypeError(f"{cls.__name__}.{dc.name}: give spec(form=...): the type hint "
                            f"{hints[dc.name]!r} does not tell how to write it")
        if form in ("table", "tables", "flat") and item is None:
            item = _infer_form(hints[dc.name])[1] or (
                typing.get_args(hints[dc.name])[0] if form == "tables" else hints[dc.name])
        if (s.key is None) != (form in ("unsaved", "derived")):
            raise TypeError(f"{cls.__name__}.{dc.name}: key None exactly for the forms "
                            "'unsaved' and 'derived'")
        f = Field(dc.name, s, form, _literals(hints[dc.name]), item, default)
        _check_units(cls, f)
        out.append(f)
    return tuple(out)


@functools.cache
def table_keys(cls: type) -> tuple[str, ...]:
    """Keys allowed in the table of a schema class (sections such as "switches" included)."""
    keys: list[str] = []
    for f in fields_of(cls):
        if f.spec.section is not None:
            if f.spec.section not in keys:
                keys.append(f.spec.section)
        else:
            keys.extend(f.keys())
    return tuple(keys)


def section_fields(cls: type, section: str) -> tuple[Field, ...]:
    """The fields of `cls` whose keys sit in the sub-table `section`."""
    return tuple(f for f in fields_of(cls) if f.spec.section == section)


def model_fields() -> dict[str, tuple[str, ...]]:
    """Dataclass fields of each saved type, by class name."""
    return {cls.__name__: tuple(f.name for f in dataclasses.fields(cls)) for cls in SCHEMA_CLASSES}


def check() -> None:
    """Resolve every schema class (raises TypeError on an incomplete declaration)."""
    for cls in SCHEMA_CLASSES:
        fields_of(cls)
        table_keys(cls)


# =============================================================================== documentation
def _toml(x: Any) -> str:
    if isinstance(x, bool):
        return "true" if x else "false"
    if isinstance(x, str):
        return json.dumps(x, ensure_ascii=False)
    if isinstance(x, float):
        return repr(x)
    if isinstance(x, (tuple, list)):
        return "[" + ", ".join(_toml(i) for i in x) + "]"
    return repr(x)


def _value_type(f: Field) -> str:
    strings = " or ".join(f"`{_toml(c)}`" for c in f.choices)
    return {
        "number": "number", "integer": "integer", "boolean": "true/false",
        "string": strings or "string",
        "spanwise": "number, or one per element",
        "number_or_string": f"number or {strings}",
        "numbers": f"{f.spec.length} numbers",
        "table": "table", "tables": "list of tables", "mapping": "table",
        "derivatives": "table", "reference": "string",
        "installations": "list of tables",
    }[f.form]


def _default(f: Field, value: Any = dataclasses.MISSING) -> str:
    """The default column: "required", "omitted", or the value and its kind."""
    if f.required:
        return "required"
    kind = f.spec.default
    if value is dataclasses.MISSING:
        value = f.default if f.default is not dataclasses.MISSING else f.spec.file_default
    if kind == "none" and value in (None, ()):
        return "omitted"
    if dataclasses.is_dataclass(value):
        return f"its defaults ({kind})"
    return f"`{_toml(value)}` ({kind})"


Row = tuple[str, str, str, str, str]  # key, value, unit, default, meaning


@dataclass
class Section:
    """One table of the documentation."""

    title: str
    text: str
    rows: list[Row]


def distribution_name(s: FieldSpec) -> str:
    """Name of a tabulated distribution that the file leaves unnamed: its quantity
    ("chord" for chord_m, "lift_slope" for lift_slope_per_rad)."""
    return s.value_key[: len(s.value_key) - len(UNITS[s.unit][0])]


def _first_line(cls: type) -> str:
    return (cls.__doc__ or "").strip().splitlines()[0]


def _section(title: str, text: str, out: list[Section], cls: type | None = None,
             path: str = "", section: str | None = None) -> Section:
    """Append the section of `cls`'s table at `path`, then those of its sub-tables."""
    sec = Section(title, text, [])
    out.append(sec)
    if cls is not None:
        sec.rows = _rows(cls, path, out, section)
    return sec


def _rows(cls: type, path: str, out: list[Section], section: str | None = None) -> list[Row]:
    """Rows of `cls`'s table at `path`; the sections of its sub-tables are appended to `out`."""
    rows: list[Row] = []
    sub = f"{path}." if path else ""
    for f in fields_of(cls):
        if f.spec.key is None or f.spec.section != section:
            continue
        s, doc = f.spec, f.spec.doc
        if f.form == "split":
            for i, (k, u) in enumerate(zip(s.key, s.unit)):
                rows.append((k, "number", u, _default(f, f.default[i]), doc))
        elif f.form == "flat":
            rows.extend(_rows(f.item, path, out))
        elif f.form == "distribution":
            title = f"[{sub}{s.key}]"
            if s.number_key:
                rows.append((s.number_key, "number", s.unit, _default(f), f"{doc}, constant"))
            rows.append((s.key, "table", "", "omitted" if s.number_key else _default(f),
                         f"{doc} as a table of eta = r/R: {title}"
                         + (f" (instead of {s.number_key})" if s.number_key else "")))
            _section(title, "A radial distribution, piecewise linear in eta = r/R; the table "
                     "must cover [hub ratio, 1].", out).rows = [
                ("name", "string", "", f'`"{distribution_name(s)}"` (setting)', "label"),
                ("eta", "list of numbers", "", "required", "stations r/R, strictly increasing"),
                (s.value_key, "list of numbers", s.unit, "required", "one value per station")]
        elif f.form == "mapping":
            title = f"[{sub}{s.key}]"
            rows.append((s.key, "table", "", _default(f), f"{doc}: {title}"))
            _section(title, f"{doc[0].upper()}{doc[1:]}; any subset of:", out).rows = [
                (e.key, "number", e.unit, "omitted", e.doc) for e in s.entries]
        elif f.form == "derivatives":
            rows.append((s.key, "table", "", _default(f), f"{doc}: [{sub}{s.key}]"))
            for source, src_cls in DERIVATIVE_SOURCES.items():
                sec = _section(f'[{sub}{s.key}] with source = "{source}"', _first_line(src_cls),
                               out)
                sec.rows = [("source", f'`"{source}"`', "", "required", "the derivative source")]
                sec.rows += _rows(src_cls, f"{sub}{s.key}", out)
        elif f.form in ("table", "tables", "installations"):
            item = Installation if f.form == "installations" else f.item
            if f.form == "table":
                title, text = f"[{sub}{s.key}]", _first_line(item)
            else:
                title, text = f"{sub}{s.key}[i]", f"Each entry of the list: {_first_line(item)}"
            rows.append((s.key, _value_type(f), "", _default(f), f"{doc}: {title}"))
            _section(title, text, out, item, title)
        else:
            rows.append((s.key, _value_type(f), s.unit, _default(f), doc))
    return rows


def sections() -> list[Section]:
    """Every table of every model type, in the order of docs/model-file.md."""
    out: list[Section] = []
    file_rows: list[Row] = [
        ("format", f'`"{FORMAT}"`', "", f'`"{FORMAT}"`', "file format"),
        ("format_version", f"`{FORMAT_VERSION}`", "", f"`{FORMAT_VERSION}`",
         f"this propwhirl reads version {FORMAT_VERSION}"),
    ]
    for kind, cls in MODEL_TYPES.items():
        top = _section(f'Top level of type = "{kind}"', _first_line(cls), out)
        top.rows = file_rows + [("type", f'`"{kind}"`', "", "required", cls.__name__)]
        if cls is Propeller:
            top.rows += [("name", "string", "", "omitted", "label (not read: the propeller's "
                                                             "own name counts)"),
                         ("propeller", "string", "", "required", "key of a [propellers.KEY] table")]
        else:
            top.rows += _rows(cls, "", out)
            top.rows.append(("switches", "table", "", "omitted", "on/off switches: [switches]"))
            _section(f'[switches] of type = "{kind}"', "Model switches.", out, cls, "",
                     "switches")
        top.rows.append(("propellers", "table", "", "required",
                         "the propellers, one table [propellers.KEY] each"))
    _section("[propellers.KEY]", "One table per distinct propeller, under any key (the writer "
             "uses p1, p2, ...); installations refer to it by its key.", out, Propeller,
             "propellers.KEY")
    seen: set[str] = set()
    unique = []
    for s in out:  # a table met from several model types is documented once
        if s.title not in seen:
            seen.add(s.title)
            unique.append(s)
    return unique


_INTRO = f"""\
# Model files

<!-- Generated by propwhirl.io.schema.markdown() from the field declarations of the model
dataclasses; do not edit. Rewrite with `python -m propwhirl.io > docs/model-file.md`
(a test checks that this file is current). -->

A model file is TOML: `propwhirl case NAME --save FILE` writes one, `propwhirl analyse FILE`
reads it; from Python `propwhirl.io.save_model(model, path)` and `propwhirl.io.load_model(path)`
(writing needs the optional extra: `pip install propwhirl[toml]`; reading uses the standard
library). `examples/wingtip.toml` is an example.

Reading is strict: an unknown key, a missing required key, a key given twice or a value of the
wrong type is an error naming the file and the key. Omitted optional keys take the defaults
below (the defaults of the Python classes); the writer writes every value, so a saved file does
not depend on them. Floats are written exactly (a save and load round trip is exact).

Not saveable (an error names the field): spanwise wing properties or chords given as Python
functions (tabulate them per element), a blade chord given as a function that is not a
`Distribution`, and derivative sources other than `MeasuredDerivatives` and
`HouboltReedSource`.

Conventions: SI units, the unit of a quantity is the suffix of its key (table below); chordwise
wing positions are fractions of the local chord from the leading edge (suffix `_chord`);
positions on the propeller shaft are from the wing mid-chord, positive aft. The *default*
column gives the value an omitted key takes and its kind: *physical* (a value of the aircraft
or the air), *setting* (a modelling or numerical choice, a switch, a label); *omitted* means
the key may be left out (its meaning says what then holds).

| suffix | unit |
|---|---|
""" + "".join(f"| `{s}` | {u} |\n" for s, u in UNIT_SUFFIXES)


def markdown() -> str:
    """docs/model-file.md: every table, key, unit, default and meaning of a model file."""
    parts = [_INTRO]
    for s in sections():
        parts.append(f"\n## {s.title}\n\n{s.text}\n\n| key | value | unit | default | meaning |\n"
                     "|---|---|---|---|---|\n")
        parts += [f"| `{k}` | {t} | {u} | {d} | {m} |\n" for k, t, u, d, m in s.rows]
    return "".join(parts)


def defaults_table() -> list[tuple[str, str, str, str]]:
    """(class.field, default value, kind, file key) of every field with a default (the list
    the defaults audit starts from)."""
    rows = []
    for cls in SCHEMA_CLASSES:
        for f in fields_of(cls):
            if f.spec.default is not None:
                value = f.default if f.default is not dataclasses.MISSING else f.spec.file_default
                rows.append((f"{cls.__name__}.{f.name}", repr(value), f.spec.default,
                             str(f.spec.key)))
    return rows
