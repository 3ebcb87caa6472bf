"""Model-file metadata carried by the fields of the model dataclasses, and the checks it drives.

Every field of a model dataclass declares, with ``metadata=spec(...)``, how a model file holds
it: the key (with its SI unit suffix, e.g. ``EI_N_m2``), the unit, a one-line description,
the valid range of a physical quantity and, when the field has a Python default, what kind of
default it is::

    EI: Spanwise = field(metadata=spec("EI_N_m2", "N m^2", "bending rigidity", form="spanwise",
                                       range=(1e-3, 1e12)))
    elastic_axis: Spanwise = field(default=0.5, metadata=spec(
        "elastic_axis_chord", "chord", "elastic-axis position", form="spanwise",
        default="physical", range=(0.0, 1.0)))

:mod:`propwhirl.io.schema` turns these declarations into the reader, the writer, their error
messages and ``docs/model-file.md``; the default *values* stay those of the dataclasses.
:func:`check_fields`, called first by each ``__post_init__``, enforces the declarations on
construction: strict types (a number is a real int or float, a switch a bool, a table an
instance of its class) and the ranges, every value of an array or table included.  The ranges
are an envelope that real aircraft, from a small UAV to a large turboprop or tiltrotor, do not
leave (docs/model-file.md, "Valid ranges"): a value outside is a typing or unit error, and
refusing it keeps every computed matrix finite.  This module imports only
:mod:`propwhirl.validate`, so the model packages use it without depending on :mod:`propwhirl.io`.
"""
from __future__ import annotations

import dataclasses
import functools
import types
import typing
from dataclasses import dataclass
from typing import Any, Literal, Mapping

import numpy as np

from propwhirl import validate as v

#: Key of the :class:`FieldSpec` in a dataclass field's ``metadata``.
META_KEY = "propwhirl.model_file"

#: How a value is written.  Forms left as ``None`` in :func:`spec` follow from the field's type
#: hint: bool → "boolean", int → "integer", float → "number", str or Literal → "string",
#: a dataclass → "table", tuple[dataclass, ...] → "tables".
Form = Literal[
    "number", "integer", "string", "boolean",
    "spanwise",          # a number or one number per wing element (never a function)
    "number_or_string",  # a number or one of the Literal strings of the type hint
    "numbers",           # a fixed-length list of numbers (`length`)
    "split",             # a tuple of numbers written as separate keys (`key`, `unit` are tuples)
    "table",             # a nested dataclass: a sub-table
    "tables",            # a tuple of dataclasses: a list of tables
    "flat",              # a nested dataclass whose keys sit in the enclosing table
    "mapping",           # a dict with the fixed entries `entries`
    "distribution",      # a number (`number_key`) or a radial table (name, eta, `value_key`)
    "derivatives",       # an aerodynamic derivative source: a table chosen by its `source` key
    "reference",         # a Propeller, written as the key of a [propellers.KEY] table
    "installations",     # the installed propellers of a wing: a list of tables
    "groups",            # named groups of installations: a table NAME = [indices from 0]
    "unsaved",           # not in the file: only the Python default can be saved (`doc` says why)
    "derived",           # not in the file: computed by the class from the other fields
]

#: What a Python default stands for (issue 9 audits the "physical" ones):
#: "physical" — a value of the aircraft or the air (a position, a stiffness, an angle, ...);
#: "setting"  — a modelling or numerical choice, a switch or a label;
#: "none"     — ``None`` (or empty): not given, the field's description says what then holds.
DefaultKind = Literal["physical", "setting", "none"]


@dataclass(frozen=True)
class Range:
    """Valid range [low, high] of a quantity; `ends` gives the brackets ("[]", "(]", "[)", "()")."""

    low: float
    high: float
    ends: str = "[]"

    def __post_init__(self) -> None:
        if self.ends not in ("[]", "(]", "[)", "()") or not self.low < self.high:
            raise TypeError(f"Range({self.low}, {self.high}, {self.ends!r}) is malformed")

    def __str__(self) -> str:
        return v.fmt_range(self.low, self.high, self.ends)

    def contains(self, x: np.ndarray) -> np.ndarray:
        lo = x > self.low if self.ends[0] == "(" else x >= self.low
        hi = x < self.high if self.ends[1] == ")" else x <= self.high
        return lo & hi

    def check(self, name: str, value: Any, unit: str = "", path: tuple | None = None
              ) -> np.ndarray:
        """`value` (a number or an array) as floats; InputError unless every value is in range."""
        return v.in_range(name, value, self.low, self.high, unit, self.ends[0] == "(",
                          self.ends[1] == ")", path)


def _range(r: Any, ends: str) -> Range | None:
    if r is None or isinstance(r, Range):
        return r
    return Range(float(r[0]), float(r[1]), ends)


@dataclass(frozen=True)
class Entry:
    """One fixed entry of a "mapping" field: Python name, file key, unit, description, range."""

    name: str
    key: str
    unit: str = ""
    doc: str = ""
    range: Range | None = None

    def __post_init__(self) -> None:
        object.__setattr__(self, "range", _range(self.range, "[]"))


@dataclass(frozen=True)
class FieldSpec:
    """How one dataclass field appears in a model file (see :func:`spec`)."""

    key: str | tuple[str, ...] | None
    unit: str | tuple[str, ...] = ""
    doc: str = ""
    default: DefaultKind | None = None
    form: Form | None = None
    section: str | None = None
    length: int | None = None
    number_key: str | None = None
    value_key: str | None = None
    entries: tuple[Entry, ...] = ()
    file_required: bool | str = False
    file_default: Any = None
    range: Range | tuple[Range, ...] | None = None

    def range_of(self, i: int | None = None) -> Range | None:
        """The range (of entry `i` of a "split" field)."""
        if isinstance(self.range, tuple):
            return self.range[i or 0]
        return self.range

    def unit_of(self, i: int | None = None) -> str:
        return self.unit[i or 0] if isinstance(self.unit, tuple) else self.unit


def spec(key: str | tuple[str, ...] | None, unit: str | tuple[str, ...] = "", doc: str = "", *,
         default: DefaultKind | None = None, form: Form | None = None, section: str | None = None,
         length: int | None = None, number_key: str | None = None, value_key: str | None = None,
         entries: tuple[Entry, ...] = (), file_required: bool | str = False,
         file_default: Any = None, range: Any = None, ends: str | tuple[str, ...] = "[]",
         ) -> Mapping[str, FieldSpec]:
    """Metadata for ``dataclasses.field(metadata=...)`` declaring a model-file field.

    Parameters
    ----------
    key : the key in the model file, SI unit suffix included (``"semi_span_m"``); a tuple of
        keys for form "split"; None for fields that are not saved (forms "unsaved", "derived").
    unit : SI unit as written in the documentation (``"N m^2"``, ``"chord"`` for fractions of
        the local chord, ``""`` dimensionless); must agree with the key's suffix.
    doc : one line for the documentation and error messages.
    default : kind of the dataclass default ("physical", "setting" or "none"); required for
        a field with a default, forbidden for one without (checked by propwhirl.io.schema).
    form : how the value is written (see :data:`Form`); None: from the type hint.
    section : sub-table of the enclosing table that holds the key (``"switches"``).
    length : number of entries of a "numbers" list.
    number_key, value_key : "distribution": key of the number alternative and of the values
        column of the table.
    entries : "mapping": the allowed entries.
    file_required : the file must give the field although the dataclass has a default; a
        string names a condition (:data:`REQUIRED_WHEN`): required only then.
    file_default : value used when the file omits a field that the dataclass requires.
    range : valid range ``(low, high)`` of the quantity (every value of an array, list,
        table or distribution); for form "split" one pair per key.  Checked on construction
        by :func:`check_fields`, listed in docs/model-file.md.
    ends : brackets of the range: "[]" closed (default), "(]", "[)" or "()"; a tuple for "split".
    """
    if range is not None and isinstance(range[0], (tuple, list)):
        ends_t = ends if isinstance(ends, tuple) else (ends,) * len(range)
        rng: Any = tuple(_range(r, e) for r, e in zip(range, ends_t))
    else:
        rng = _range(range, ends if isinstance(ends, str) else ends[0])
    return {META_KEY: FieldSpec(key, unit, doc, default, form, section, length, number_key,
                                value_key, tuple(entries), file_required, file_default, rng)}


#: Conditions of ``spec(file_required=...)``: the file must give the key when ...
REQUIRED_WHEN: dict[str, str] = {
    "houbolt-reed": "the propeller's derivatives come from its blades (no [derivatives] table)",
    "fixed-pitch": 'operation = "fixed-pitch" (the default)',
}


# =============================================================================== checks
def literals(hint: Any) -> tuple[str, ...]:
    """The strings of a Literal type hint (through unions)."""
    if typing.get_origin(hint) is Literal:
        return tuple(typing.get_args(hint))
    if typing.get_origin(hint) in (typing.Union, types.UnionType):
        return tuple(s for h in typing.get_args(hint) for s in literals(h))
    return ()


def infer_form(hint: Any) -> tuple[str | None, type | None]:
    """The form a type hint implies (see :data:`Form`) and the dataclass of a table."""
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


@dataclass(frozen=True)
class _Check:
    name: str
    spec: FieldSpec
    form: str | None
    choices: tuple[str, ...]
    item: type | None
    none_ok: bool


@functools.cache
def _checks(cls: type) -> tuple[_Check, ...]:
    hints = typing.get_type_hints(cls)
    out = []
    for dc in dataclasses.fields(cls):
        s = dc.metadata.get(META_KEY)
        if not isinstance(s, FieldSpec):
            continue
        hint = hints[dc.name]
        inferred, item = infer_form(hint)
        form = s.form or inferred
        if form in ("reference", "installations", "flat") or (form == "table" and item is None):
            item = infer_form(hint)[1] or (hint if isinstance(hint, type) else None)
        out.append(_Check(dc.name, s, form, literals(hint), item, dc.default is None))
    return tuple(out)


def declared_fields(cls: type) -> tuple[tuple[str, FieldSpec, str | None], ...]:
    """Each field of a model dataclass that carries a :class:`FieldSpec`, in declaration
    order: (name, spec, form — the spec's own or the one inferred from the type hint)."""
    return tuple((c.name, c.spec, c.form) for c in _checks(cls))


def _type_error(name: str, value: Any, expected: str) -> v.InputError:
    return v.fail(name, value, f"invalid: must be {expected}, got {type(value).__name__}")


def _number(name: str, value: Any, s: FieldSpec, i: int | None = None,
            path: tuple | None = None) -> None:
    if v.real(name, value, path=path).ndim:
        raise _type_error(name, value, "a number")
    _in(name, value, s.range_of(i), s.unit_of(i), path)


def _in(name: str, value: Any, rng: Range | None, unit: str, path: tuple | None) -> None:
    if rng is not None:
        rng.check(name, value, unit, path)
    else:
        v.finite(name, value, unit, path)


def _sequence(name: str, value: Any, length: int | None, what: str) -> tuple:
    if isinstance(value, np.ndarray) and value.ndim == 1:
        value = tuple(value.tolist())
    if not isinstance(value, (tuple, list)) or (length is not None and len(value) != length):
        n = f"{length} " if length is not None else ""
        raise _type_error(name, value, f"a tuple of {n}{what}")
    return tuple(value)


def _check(c: _Check, value: Any) -> Any:
    """`value` checked against the declaration `c`; returns it (lists made tuples)."""
    name, s, form = c.name, c.spec, c.form
    if value is None and c.none_ok:
        return value
    if form in ("number", "integer"):
        if form == "integer" and (isinstance(value, (bool, np.bool_))
                                  or not isinstance(value, (int, np.integer))):
            raise _type_error(name, value, "an integer")
        _number(name, value, s)
    elif form == "boolean":
        v.boolean(name, value)
    elif form == "string":
        if not isinstance(value, str):
            raise _type_error(name, value, "a string")
        if c.choices and value not in c.choices:
            raise v.fail(name, value, "invalid: must be one of "
                         + ", ".join(repr(x) for x in c.choices))
    elif form == "spanwise":
        if callable(value):
            return value
        arr = v.real(name, value)
        if arr.ndim > 1:
            raise v.fail(name, value, "invalid: must be a number, one value per element or a "
                         f"function of y, got an array of shape {arr.shape}")
        _in(name, value, s.range, s.unit, None)
    elif form == "number_or_string":
        if isinstance(value, str):
            if value not in c.choices:
                raise v.fail(name, value, "invalid: must be a number, a function of y or one of "
                             + ", ".join(repr(x) for x in c.choices))
        elif not callable(value):
            _number(name, value, s)
    elif form in ("numbers", "split"):
        length = s.length if form == "numbers" else len(s.key)
        value = _sequence(name, value, length, f"numbers ({s.doc.split(':')[0]})")
        for i, x in enumerate(value):
            _number(f"{name}[{i}]", x, s, i if form == "split" else None, (name, i))
    elif form in ("table", "flat", "reference"):
        if c.item is not None and not isinstance(value, c.item):
            raise _type_error(name, value, f"a {c.item.__name__}")
    elif form in ("tables", "installations"):
        value = _sequence(name, value, None, f"{c.item.__name__} objects")
        for i, x in enumerate(value):
            if not isinstance(x, c.item):
                raise v.fail(f"{name}[{i}]", x, f"invalid: must be a {c.item.__name__}, got "
                             f"{type(x).__name__}", path=(name, i))
    elif form == "mapping":
        if not isinstance(value, Mapping):
            raise _type_error(name, value, "a dict")
        entries = {e.name: e for e in s.entries}
        unknown = [k for k in value if k not in entries]
        if unknown:
            raise v.fail(name, dict(value), f"invalid: unknown entr{'y' if len(unknown) == 1 else 'ies'} "
                         f"{', '.join(map(repr, unknown))}; valid names are "
                         + ", ".join(entries))
        for k, x in value.items():
            e = entries[k]
            if v.real(f"{name}[{k!r}]", x, path=(name, k)).ndim:
                raise _type_error(f"{name}[{k!r}]", x, "a number")
            _in(f"{name}[{k!r}]", x, e.range, e.unit, (name, k))
    elif form == "distribution":
        if hasattr(value, "eta") and hasattr(value, "values") and callable(value):
            _in(name, v.real(name, value.values), s.range, s.unit, None)
        elif not callable(value):
            if v.real(name, value).ndim:
                raise _type_error(name, value, "a number, a Distribution or a function of eta")
            _in(name, value, s.range, s.unit, None)
    elif form in ("derivatives", None):
        if not callable(value):
            raise _type_error(name, value, "a function" + (" or None" if c.none_ok else ""))
    return value


def check_fields(obj: Any) -> None:
    """Check every declared field of dataclass instance `obj` (types and ranges).

    Raises :class:`propwhirl.validate.InputError` naming the field, the value (and its type,
    or the valid range with its unit); a list given for a tuple field is stored as a tuple.
    Functions (spanwise properties, chords) are checked where the class evaluates them, with
    :func:`check_values`.
    """
    for c in _checks(type(obj)):
        value = getattr(obj, c.name)
        new = _check(c, value)
        if new is not value:
            object.__setattr__(obj, c.name, new)


def field_range(cls: type, name: str) -> Range | None:
    """The declared range of field `name` of `cls`."""
    return next(c.spec.range_of() for c in _checks(cls) if c.name == name)


def check_values(cls: type, name: str, values: Any, at: np.ndarray | None = None,
                 at_name: str = "y", at_unit: str = "m") -> np.ndarray:
    """Values of field `name` of `cls` (e.g. evaluated from a function) as floats, each
    checked against the declared range (InputError naming the first bad one, and its
    position ``at_name = at[i]`` when the positions `at` are given)."""
    c = next(c for c in _checks(cls) if c.name == name)
    arr = v.real(name, values)
    unit = c.spec.unit_of()
    try:
        _in(name, arr, c.spec.range_of(), unit, None)
    except v.InputError as exc:
        if at is None or len(exc.path) < 2 or exc.reason is None:
            raise
        where = f"{at_name} = {float(np.ravel(at)[exc.path[1]]):.6g}{' ' + at_unit if at_unit else ''}"
        raise v.fail(f"{name}({where})", exc.value, exc.reason, unit, exc.path) from None
    return arr
