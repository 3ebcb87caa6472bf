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
import typing
from dataclasses import dataclass
from typing import Any

from propwhirl.io import alternatives, versions
from propwhirl.io.versions import FORMAT_VERSION, FORMAT_VERSIONS, UNSTATED_VERSION
from propwhirl.model.fields import META_KEY, REQUIRED_WHEN, FieldSpec, infer_form, literals
from propwhirl.model.propellers.propeller import MeasuredDerivatives, PointMass, Propeller
from propwhirl.model.propellers.propeller_aero import AeroSettings, HouboltReedSource, PropellerGeometry
from propwhirl.model.systems import FlightCondition, Installation, IsolatedPropeller, PropellerWing
from propwhirl.model.structure.wing import Wing

FORMAT = "propwhirl-model"  # its versions (written, read, the old ones' defaults): io/versions.py

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
        """The file must always give this field."""
        return self.spec.file_required is True or (self.default is dataclasses.MISSING
                                                   and self.spec.file_default is None)

    @property
    def required_when(self) -> str | None:
        """The condition (a key of fields.REQUIRED_WHEN) under which the file must give it."""
        r = self.spec.file_required
        return r if isinstance(r, str) else None

    def range_text(self, i: int | None = None) -> str:
        """"[1e-3, 1e12] N m^2" (entry `i` of a "split" field), or "" without a range."""
        r = self.spec.range_of(i)
        if r is None:
            return ""
        unit = self.spec.unit_of(i)
        return f"{r}{' ' + unit if unit and unit != 'chord' else ''}"

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


_literals = literals
_infer_form = infer_form


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
    return tuple(keys) + alternatives.keys(cls)


def section_fields(cls: type, section: str) -> tuple[Field, ...]:
    """The fields of `cls` whose keys sit in the sub-table `section`."""
    return tuple(f for f in fields_of(cls) if f.spec.section == section)


def model_fields() -> dict[str, tuple[str, ...]]:
    """Dataclass fields of each saved type, by class name.

    The units of the fields are the suffixes of their keys in a model file
    (docs/model-file.md, generated from the same schema).

    Returns
    -------
    dict of str to tuple of str
        Class name (``"Wing"``, ``"Propeller"``, ...) → the names of its dataclass fields.

    Examples
    --------
    >>> from propwhirl.io import model_fields
    >>> fields = model_fields()
    >>> fields["FlightCondition"]
    ('density', 'speed_of_sound', 'speed_range')
    >>> "PropellerWing" in fields and "semi_span" in fields["Wing"]
    True
    """
    return {cls.__name__: tuple(f.name for f in dataclasses.fields(cls)) for cls in SCHEMA_CLASSES}


def check() -> None:
    """Resolve every schema class (raises TypeError on an incomplete declaration), and check
    that each old default belongs to a field this version requires."""
    for cls in SCHEMA_CLASSES:
        fields_of(cls)
        table_keys(cls)
    for version, table in versions.OLD_DEFAULTS.items():
        for cls, name in table:
            f = next((f for f in fields_of(cls) if f.name == name), None)
            if f is None or not (f.required or f.required_when) or cls not in versions.TABLE_OF:
                raise TypeError(f"OLD_DEFAULTS[{version}]: {cls.__name__}.{name} is not a field "
                                "this format version requires")


# =============================================================================== locating
def join(where: str, key: str) -> str:
    """"wing" + "EI_N_m2" → "wing.EI_N_m2" (a top-level key stays itself)."""
    return f"{where}.{key}" if where else key


def what(f: Field, i: int | None = None) -> str:
    """The meaning of a field for messages: description, unit, valid range."""
    unit = f.spec.unit_of(i)
    rng = f.range_text(i)
    return (f.spec.doc + (f"; {unit}" if unit else "")
            + (f"; valid range {rng}" if rng else ""))


def _field(cls: type | None, name: Any) -> Field | None:
    if cls is None or not isinstance(name, str):
        return None
    return next((f for f in fields_of(cls) if f.name == name), None)


def locate(cls: type, where: str, path: tuple) -> tuple[str, str, str] | None:
    """(table, key as written, meaning) of the value at `path` (an InputError's path) of an
    object of `cls` built from table `where`; None when the path leads to no key of the file."""
    parts = list(path)
    while parts:
        f = _field(cls, parts.pop(0))
        if f is None or f.spec.key is None:
            return None
        index = parts.pop(0) if parts else None
        if f.form in ("tables", "installations") and isinstance(index, int):
            where = f"{join(where, f.spec.key)}[{index}]"
            cls = Installation if f.form == "installations" else f.item
            continue
        if f.spec.section:
            where = join(where, f.spec.section)
        if f.form == "split" and isinstance(index, int):
            return where, f.spec.key[index], what(f, index)
        if f.form == "mapping" and isinstance(index, str):
            e = next(e for e in f.spec.entries if e.name == index)
            rng = f"; valid range {e.range}{' ' + e.unit if e.unit else ''}" if e.range else ""
            return join(where, f.spec.key), e.key, e.doc + rng
        if f.form == "distribution":
            if index is None and f.spec.number_key:
                return where, f.spec.number_key, what(f)
            key = f.spec.value_key + ("" if index is None else f"[{index}]")
            return join(where, f.spec.key), key, what(f)
        if f.form == "flat":
            return locate(f.item, where, (index,) + tuple(parts)) if index else None
        key = f.spec.key + (f"[{index}]" if isinstance(index, int) else "")
        return where, key, what(f)
    return None


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
        "numbers": f"{f.spec.length} numbers" if f.spec.length else "list of numbers",
        "table": "table", "tables": "list of tables", "mapping": "table",
        "derivatives": "table", "reference": "string",
        "installations": "list of tables",
        "groups": "table of lists of integers",
    }[f.form]


def _default(f: Field, value: Any = dataclasses.MISSING) -> str:
    """The default column: "required", "omitted", or the value and its kind."""
    if f.required:
        return "required"
    if f.required_when:
        return REQUIRED_LABEL[f.required_when]
    kind = f.spec.default
    if value is dataclasses.MISSING:
        value = f.default if f.default is not dataclasses.MISSING else f.spec.file_default
    if kind == "none" and (value is None or (isinstance(value, (tuple, dict)) and not value)):
        return "omitted"
    if dataclasses.is_dataclass(value):
        return f"its defaults ({kind})"
    return f"`{_toml(value)}` ({kind})"


#: Default column of a field required under a condition (fields.REQUIRED_WHEN).
REQUIRED_LABEL = {"houbolt-reed": "required without [derivatives]",
                  "fixed-pitch": "required for fixed-pitch"}
assert set(REQUIRED_LABEL) == set(REQUIRED_WHEN)

Row = tuple[str, str, str, str, str, str]  # key, value, unit, default, valid range, meaning


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
                rows.append((k, "number", u, _default(f, f.default[i]), f.range_text(i), doc))
        elif f.form == "flat":
            rows.extend(_rows(f.item, path, out))
        elif f.form == "distribution":
            title = f"[{sub}{s.key}]"
            if s.number_key:
                rows.append((s.number_key, "number", s.unit, _default(f), f.range_text(),
                             f"{doc}, constant"))
            rows.append((s.key, "table", "", "omitted" if s.number_key else _default(f), "",
                         f"{doc} as a table of eta = r/R: {title}"
                         + (f" (instead of {s.number_key})" if s.number_key else "")))
            _section(title, "A radial distribution, piecewise linear in eta = r/R; the table "
                     "must cover [hub ratio, 1].", out).rows = [
                ("name", "string", "", f'`"{distribution_name(s)}"` (setting)', "", "label"),
                ("eta", "list of numbers", "", "required", "", "stations r/R, strictly increasing"),
                (s.value_key, "list of numbers", s.unit, "required", f.range_text(),
                 "one value per station")]
        elif f.form == "mapping":
            title = f"[{sub}{s.key}]"
            rows.append((s.key, "table", "", _default(f), "", f"{doc}: {title}"))
            _section(title, f"{doc[0].upper()}{doc[1:]}; any subset of:", out).rows = [
                (e.key, "number", e.unit, "omitted",
                 f"{e.range}{' ' + e.unit if e.unit else ''}" if e.range else "", e.doc)
                for e in s.entries]
        elif f.form == "derivatives":
            rows.append((s.key, "table", "", _default(f), "", f"{doc}: [{sub}{s.key}]"))
            for source, src_cls in DERIVATIVE_SOURCES.items():
                sec = _section(f'[{sub}{s.key}] with source = "{source}"', _first_line(src_cls),
                               out)
                sec.rows = [("source", f'`"{source}"`', "", "required", "",
                             "the derivative source")]
                sec.rows += _rows(src_cls, f"{sub}{s.key}", out)
        elif f.form in ("table", "tables", "installations"):
            item = Installation if f.form == "installations" else f.item
            if f.form == "table":
                title, text = f"[{sub}{s.key}]", _first_line(item)
            else:
                title, text = f"{sub}{s.key}[i]", f"Each entry of the list: {_first_line(item)}"
            rows.append((s.key, _value_type(f), "", _default(f), "", f"{doc}: {title}"))
            _section(title, text, out, item, title)
        else:
            rows.append((s.key, _value_type(f), s.unit, _default(f), f.range_text(), doc))
    alt = alternatives.ALTERNATIVES.get(cls)
    if alt is not None and section is None:  # e.g. altitude_m for density and speed of sound
        replaced = {f.key for f in fields_of(cls) if f.name in alt.replaces}
        unless = f" unless {' or '.join(alt.key_names())}"
        rows = [r[:3] + (r[3] + unless,) + r[4:] if r[0] in replaced else r for r in rows]
        rows += [(k.key, "number", k.unit, "omitted", f"{k.range} {k.unit}", k.doc)
                 for k in alt.keys]
    return rows


def sections() -> list[Section]:
    """Every table of every model type, in the order of docs/model-file.md."""
    out: list[Section] = []
    file_rows: list[Row] = [
        ("format", f'`"{FORMAT}"`', "", f'`"{FORMAT}"`', "", "file format"),
        ("format_version", f"`{FORMAT_VERSION}`", "", f"`{UNSTATED_VERSION}`", "",
         f"this propwhirl writes version {FORMAT_VERSION} and reads versions "
         f"{', '.join(map(str, FORMAT_VERSIONS))} (see Format versions)"),
    ]
    for kind, cls in MODEL_TYPES.items():
        top = _section(f'Top level of type = "{kind}"', _first_line(cls), out)
        top.rows = file_rows + [("type", f'`"{kind}"`', "", "required", "", cls.__name__)]
        if cls is Propeller:
            top.rows += [("name", "string", "", "omitted", "", "label (not read: the "
                                                                 "propeller's own name counts)"),
                         ("propeller", "string", "", "required", "",
                          "key of a [propellers.KEY] table")]
        else:
            top.rows += _rows(cls, "", out)
            top.rows.append(("switches", "table", "", "omitted", "",
                             "on/off switches: [switches]"))
            _section(f'[switches] of type = "{kind}"', "Model switches.", out, cls, "",
                     "switches")
        top.rows.append(("propellers", "table", "", "required", "",
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
wrong type is an error naming the file and the key. Every error of a file is reported at once,
one line each (`propwhirl: error: FILE: [table] key = ... is invalid: ...`, exit code 2; at most
20); a table that cannot be read is not used further, and a table with an unknown key reports
no missing key (it may be the misspelled one), so no error follows from another. Omitted optional keys take the defaults
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

Required keys: a value of the aircraft that no default can stand for is *required* (the
reader names the missing key with its meaning, unit and range). Some keys are required only
where they are used: the blade geometry (`n_blades`, `hub_radius_m`, `blade_chord_m`) when
the propeller's derivatives come from its blades by Houbolt–Reed (no `[derivatives]` table),
the blade angles (`beta_075_deg`, `zero_lift_angle_deg`) for fixed-pitch operation. The
Python classes require the same values: `Propeller(...)` without `pivot_pitch`, `pivot_yaw`,
`rotation` (or the blade geometry, or the blade angles, where used) is one InputError naming
every missing one, so a script and a file never build different models. Defaults
kept: switches, labels and numerical settings; thin-aerofoil values (lift-curve slope 2 pi,
aerodynamic centre at quarter chord); the Rodden–Rose cut-off slope 4 pi; the spin inertia
M_r R^2/3 (eq. 9.2); and no structural damping (Rayleigh and mount damping 0: the
conservative assumption).

Valid ranges: every physical quantity has a *valid range* (column below), checked when a
file is read and when a Python model is built, every value of a list or radial table
included; a value outside is an error naming the key, the value and the range. The ranges are
an envelope around real aircraft, from a small UAV to a large turboprop or tiltrotor, with a
margin of about ten either way: semi-spans 1 cm to 1 km, masses per length 0.1 g/m to
100 t/m, rigidities EI, GJ 1e-3 to 1e12 N m^2 (a balsa model wing to ten times a large
transport's root), rotor radii 1 cm to 20 m (tiltrotors: about 6 m), blade chords 1 mm to
5 m, mount frequencies 1 mHz to 1 kHz, air densities 1e-4 to 10 kg/m^3 (the stratosphere
to a heavy-gas wind tunnel), speeds of sound 100 to 1000 m/s, airspeeds up to 10 km/s, mount
damping g or zeta up to 2 (critically damped and beyond), Rayleigh coefficients up to
1e3 1/s and 1 s, dimensionless derivatives within ±1e3, chordwise positions within the chord
and lift-curve slopes in (0, 4 pi]. A value beyond is a typing or unit error, and the
computation would overflow (an EI of 1e300 N m^2 gives infinite matrices).

Groups (type = "propeller-wing"): a top-level `[groups]` table names groups of installations
for parameter paths of studies, each a list of indices into `installations` from 0 (as in the
paths; the reports number propellers from 1): `high_lift = [0, 1, 2, 3, 4, 5]` makes
`propellers[high_lift].propeller.f_theta` set the first six installations' f_theta
(docs/studies.md).

| suffix | unit |
|---|---|
""" + "".join(f"| `{s}` | {u} |\n" for s, u in UNIT_SUFFIXES)


def _versions_section() -> str:
    """The "Format versions" section: what each version changed, the values of the old
    defaults (from OLD_DEFAULTS), and the upgrade command."""
    rows = "".join(f"| {versions.TABLE_OF[cls]} | `{_field(cls, name).keys()[0]}` | "
                   f"`{_toml(value)}` |\n"
                   for (cls, name), value in versions.VERSION_1_DEFAULTS.items())
    return f"""
## Format versions

`format_version` says which rules a file follows: this propwhirl writes version {FORMAT_VERSION} and
reads versions {', '.join(map(str, FORMAT_VERSIONS))}. A file without `format_version` is read as version {UNSTATED_VERSION} (the default that
version documented); a file of a newer version is refused with one line naming its version
(update propwhirl to read it).

* **Version 2** (the valid ranges, issue 9): the values of the aircraft that version 1 let a
  file omit are required (below; no silent default). The optional keys added since
  (`stations_m`, `max_element_length_m`, `EI_chordwise_N_m2`, `altitude_m`, `altitude_ft`)
  are read in files of either version.
* **Version 1** (the first release): read by the same rules, except that a key of the table
  below, when omitted where version 2 needs it (the blade geometry without `[derivatives]`,
  the blade angles for fixed pitch), takes the value version 1 gave it. The model is the one
  version 1 built, so every result is the same. Reading such a file gives one note naming
  each value assumed: the commands print it (`propwhirl: note: ...` on stderr); from Python,
  `propwhirl.io.load_model(path, notes=notes)` appends it to the list `notes`.

`propwhirl upgrade-model OLD.toml NEW.toml` writes a file of an older version in version {FORMAT_VERSION}:
every value written out (the assumed ones, printed in the note, included), the same model.
Comments of the old file are not kept. NEW must not be OLD unless `--force` is given (the
old file is then replaced atomically, after it was read whole).

| table | key | version-1 value |
|---|---|---|
{rows}"""


def markdown() -> str:
    """docs/model-file.md: every table, key, unit, default and meaning of a model file."""
    parts = [_INTRO, _versions_section()]
    for s in sections():
        parts.append(f"\n## {s.title}\n\n{s.text}\n\n"
                     "| key | value | unit | default | valid range | meaning |\n"
                     "|---|---|---|---|---|---|\n")
        parts += [f"| `{k}` | {t} | {u} | {d} | {r} | {m} |\n" for k, t, u, d, r, m in s.rows]
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
