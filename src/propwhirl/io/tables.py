"""Declarative schemas of the TOML files that are no model dataclass, one reader, their docs.

Model files are read from the metadata of the model dataclasses' fields
(:mod:`propwhirl.io.schema`).  The other TOML files — a campaign file
(:mod:`propwhirl.io.campaign_files`) and a modal model's description
(:mod:`propwhirl.io.modal_files`) — declare each table as a :class:`TableSpec`: its keys
(:class:`Key`: key, form, unit, valid range, default, meaning, and the parenthesis an error
adds).  :func:`read` reads any table of such a schema, every key by its form, and gives its
values by key (a default for an omitted key, a one-line error naming the table and the key
as written otherwise); what ties keys together (exactly one of two keys, a list as long as
another) stays with the file's reader, after the keys are read.  :func:`markdown` writes a
table of the documentation from the same declaration, so the docs cannot drift from the
reader: ``python -m propwhirl.io --update docs`` rewrites the generated parts of
``docs/campaign.md`` and ``docs/modal-structures.md`` (between ``<!-- generated: NAME -->`` and
``<!-- end generated -->``), and a test checks that they are current.

Adding a key to such a file is one :class:`Key` in its table (for a campaign file's
top-level, ``[regulation]`` or ``[envelope]`` keys: the metadata of one
:class:`~propwhirl.io.campaign_files.CampaignSpec` field): the reader, the checks, the default
and the documentation follow from it.
"""
from __future__ import annotations

import math
import re
from dataclasses import dataclass
from typing import Any, Callable, Mapping

from propwhirl.io.model_files import Table

#: The default of a key the file must give.
REQUIRED = "required"
#: The default of a key that may be left out (its meaning says what then holds).
OMITTED = "omitted"

#: The forms of a key: how its value is written and read.
FORMS = ("string", "integer", "number", "numbers", "number_or_numbers", "integers", "boolean",
         "table", "tables", "mapping", "model table", "model tables")


@dataclass(frozen=True)
class Key:
    """One key of a table.

    key:      as written in the file.
    form:     one of :data:`FORMS`: "string" (one of `choices` when given), "integer",
              "number" (in `range`), "numbers" (a list of `items` numbers in `range`),
              "number_or_numbers" (one number, or a list), "integers" (a list of `items`
              integers in `range`, distinct with `distinct`), "boolean", "table" (the sub-table
              `table`), "tables" (a list of `items` tables `table`), "mapping" (a table of
              `items` free keys, each a number), "model table" / "model tables" (a table of a
              model file, or one per key: read by the caller, documented in
              docs/model-file.md).
    doc:      its meaning (the documentation).
    unit:     its unit ("" dimensionless).
    range:    the valid range (low, high) of a number (or of each number of a list); high
              None: no upper bound; a string: the name of a bound the caller gives
              (``bounds=`` of :func:`read`, e.g. the model's number of propellers).
    default:  :data:`REQUIRED`, :data:`OMITTED` (None when left out) or the value.
    choices:  the strings a "string" may be.
    what:     what an error adds in parentheses (the key's meaning in a few words).
    items:    (fewest, most) entries of a list, tables or mapping (most None: no bound).
    table:    the :class:`TableSpec` of a "table" or the entries of "tables".
    must:     the "must be ..." of a bad value, where the form's own would say less (its
              ``{low}``, ``{high}``, ``{fewest}`` and ``{most}`` filled in).
    distinct: the entries of "integers" are distinct.
    missing:  what the error of a required key left out adds (None: `what`).
    """

    key: str
    form: str
    doc: str
    unit: str = ""
    range: tuple[float, float | str | None] | None = None
    default: Any = REQUIRED
    choices: tuple[str, ...] = ()
    what: str = ""
    items: tuple[int, int | None] | None = None
    table: "TableSpec | None" = None
    must: str = ""
    distinct: bool = False
    missing: str | None = None

    def __post_init__(self) -> None:
        if self.form not in FORMS:
            raise TypeError(f"Key {self.key!r}: form {self.form!r} is not one of {FORMS}")
        if (self.table is None) == (self.form in ("table", "tables")):
            raise TypeError(f"Key {self.key!r}: a sub-table exactly for the forms 'table' and "
                            "'tables'")


@dataclass(frozen=True)
class TableSpec:
    """A table of a file: its title in the documentation (``[envelope]``, ``cases[i]``), a
    sentence saying what it is, and its keys in the order they are read and documented."""

    title: str
    text: str
    keys: tuple[Key, ...]

    @property
    def names(self) -> tuple[str, ...]:
        """The keys allowed in the table."""
        return tuple(k.key for k in self.keys)

    def __getitem__(self, key: str) -> Key:
        return next(k for k in self.keys if k.key == key)


# =============================================================================== reading
def _is(default: Any, word: str) -> bool:
    return isinstance(default, str) and default == word


def _bound(x: Any, bounds: Mapping[str, float]) -> Any:
    return bounds[x] if isinstance(x, str) else x


def _fmt(x: Any) -> str:
    return f"{x:g}" if isinstance(x, float) else str(x)


def _must(k: Key, default: str, low: Any = None, high: Any = None) -> str:
    fewest, most = k.items or (None, None)
    return (k.must or default).format(low=_fmt(low), high=_fmt(high), fewest=fewest, most=most)


def _is_number(x: Any) -> bool:
    return not isinstance(x, bool) and isinstance(x, (int, float))


def _number(t: Table, k: Key, bounds: Mapping[str, float]) -> float:
    x = t.number(k.key, k.what)
    if k.range is not None:
        low, high = (_bound(b, bounds) for b in k.range)
        if not (math.isfinite(x) and low <= x and (high is None or x <= high)):
            raise t.bad(k.key, _must(k, "a number in [{low}, {high}]", low, high), k.what)
    return x


def _numbers(t: Table, k: Key, bounds: Mapping[str, float]) -> list[float]:
    if k.range is None and k.items is None:
        return t.numbers(k.key, k.what)
    x = t.raw(k.key, k.what)
    low, high = ((_bound(b, bounds) for b in k.range) if k.range is not None
                 else (-math.inf, math.inf))
    fewest, most = k.items or (1, None)
    if not isinstance(x, list) or len(x) < fewest or (most is not None and len(x) > most) \
            or any(not _is_number(i) or not math.isfinite(i) or not low <= i <= high
                   for i in x):
        raise t.bad(k.key, _must(k, "a list of {fewest} to {most} numbers in [{low}, {high}]",
                                 low, high), k.what)
    return [float(i) for i in x]


def _integer(t: Table, k: Key, bounds: Mapping[str, float]) -> int:
    x = t.integer(k.key, k.what)
    if k.range is not None:
        low, high = (_bound(b, bounds) for b in k.range)
        if x < low or (high is not None and x > high):
            raise t.bad(k.key, _must(k, "an integer in [{low}, {high}]" if high is not None
                                     else "an integer >= {low}", low, high), k.what)
    return x


def _integers(t: Table, k: Key, bounds: Mapping[str, float]) -> list[int]:
    x = t.raw(k.key, k.what)
    low, high = ((_bound(b, bounds) for b in k.range) if k.range is not None else (None, None))
    fewest, most = k.items or (1, None)
    if (not isinstance(x, list) or len(x) < fewest or (most is not None and len(x) > most)
            or (k.distinct and len(set(map(str, x))) != len(x))
            or any(isinstance(i, bool) or not isinstance(i, int)
                   or (low is not None and i < low) or (high is not None and i > high)
                   for i in x)):
        raise t.bad(k.key, _must(k, "a list of {fewest} or more integers", low, high), k.what)
    return list(x)


def _tables(t: Table, k: Key) -> list[Any]:
    x = t.raw(k.key)
    fewest, most = k.items or (0, None)
    if not isinstance(x, list) or len(x) < fewest or (most is not None and len(x) > most):
        keys = ", ".join(f"{e.key} = ..." for e in k.table.keys)        # type: ignore[union-attr]
        raise t.bad(k.key, _must(k, "a list of {fewest} to {most} tables {{ " + keys + " }}"),
                    k.what)
    return x


def _mapping(t: Table, k: Key) -> dict[str, float]:
    raw = t.raw(k.key, k.what)
    sub = t.sub(k.key, list(raw) if isinstance(raw, dict) else ())
    fewest, most = k.items or (0, None)
    if len(sub.data) < fewest or (most is not None and len(sub.data) > most):
        raise t.bad(k.key, _must(k, "a table of {fewest} to {most} entries"))
    return {key: sub.number(key, k.what) for key in sub.data}


def read_key(t: Table, k: Key, bounds: Mapping[str, float] | None = None) -> Any:
    """The value of key `k` of table `t` (given: the file's checks of its form, see
    :class:`Key`; a "table" read whole, each of "tables" read by its `table` at
    ``KEY[i]``; a "model table(s)" the raw table(s), for the caller)."""
    bounds = bounds or {}
    form = k.form
    if form == "string":
        x = t.string(k.key, k.what)
        if k.choices and x not in k.choices:
            raise t.bad(k.key, _must(k, f"one of {', '.join(k.choices)}"), k.what)
        return x
    if form == "integer":
        return _integer(t, k, bounds)
    if form == "number":
        return _number(t, k, bounds)
    if form == "numbers":
        return _numbers(t, k, bounds)
    if form == "number_or_numbers":
        return (_numbers(t, k, bounds) if isinstance(t.raw(k.key, k.what), list)
                else _number(t, k, bounds))
    if form == "integers":
        return _integers(t, k, bounds)
    if form == "boolean":
        return t.boolean(k.key, k.what)
    if form == "table":
        return read(t.sub(k.key, k.table.names), k.table, bounds)     # type: ignore[union-attr]
    if form == "tables":
        return [read(Table(d, f"{t.name(k.key)}[{i}]", k.table.names),  # type: ignore[union-attr]
                     k.table, bounds) for i, d in enumerate(_tables(t, k))]
    if form == "mapping":
        return _mapping(t, k)
    if form == "model tables" and not isinstance(t.raw(k.key, k.what), dict):
        raise t.bad(k.key, _must(k, f"tables [{k.key}.KEY]"), k.what)
    return t.raw(k.key, k.what)                                       # "model table(s)"


class Values(dict):
    """The values of a table read by :func:`read`, by key, and the table they were read from
    (``table``: the checks that tie keys together name them with it)."""

    def __init__(self, table: Table):
        super().__init__()
        self.table = table


def read(t: Table, spec: TableSpec, bounds: Mapping[str, float] | None = None,
         only: Callable[[Key], bool] | None = None) -> Values:
    """Every key of table `t` by its declaration in `spec`, in order (`only`: those keys):
    key → value, an omitted key's default (None for :data:`OMITTED`); a required key left
    out, a wrong type or a value outside its range is a one-line InputError naming the table
    and the key as written.  `bounds`: the values of the ranges given by name.  The table
    itself refuses an unknown key (:class:`~propwhirl.io.model_files.Table`)."""
    out = Values(t)
    for k in spec.keys:
        if only is not None and not only(k):
            continue
        if t.has(k.key):
            out[k.key] = read_key(t, k, bounds)
        elif _is(k.default, REQUIRED):
            raise t.missing(k.key, k.what if k.missing is None else k.missing)
        elif k.form == "table" and not _is(k.default, OMITTED):  # omitted: its keys' defaults
            out[k.key] = read(Table({}, t.name(k.key), k.table.names), k.table, bounds)
        else:
            out[k.key] = None if _is(k.default, OMITTED) else k.default
    return out


# =============================================================================== documentation
def _toml(x: Any) -> str:
    if isinstance(x, bool):
        return "true" if x else "false"
    if isinstance(x, str):
        return f'"{x}"'
    return _fmt(x)


def _value(k: Key) -> str:
    if k.form == "string" and k.choices:
        return " or ".join(f"`{_toml(c)}`" for c in k.choices)
    fewest, most = k.items or (1, None)
    count = f"{fewest} to {most}" if most is not None else f"{fewest} or more"
    return {"string": "string", "integer": "integer", "number": "number",
            "numbers": f"list of {count} numbers", "number_or_numbers":
            f"number, or list of {count} numbers", "integers": f"list of {count} integers",
            "boolean": "true/false", "table": "table", "tables": f"list of {count} tables",
            "mapping": f"table of {count} entries", "model table": "table",
            "model tables": "tables"}[k.form]


def _range(k: Key) -> str:
    if k.range is None:
        return ""
    low, high = k.range
    text = (f"[{_fmt(low)}, {high if isinstance(high, str) else _fmt(high)}]" if high is not None
            else f"≥ {_fmt(low)}")
    return text + (f" {k.unit}" if k.unit else "")


def _default(k: Key) -> str:
    if _is(k.default, REQUIRED) or _is(k.default, OMITTED):
        return k.default
    return f"`{_toml(k.default)}`"


def _cell(text: str) -> str:
    return text.replace("|", "\\|").replace("\n", " ")


def markdown(spec: TableSpec, extra: tuple[tuple[str, ...], ...] = ()) -> str:
    """The documentation's table of `spec`: key, value, unit, default, valid range, meaning
    (the columns of docs/model-file.md); `extra`: rows written before the keys' (e.g. the
    format's), each six cells."""
    rows = list(extra) + [(f"`{k.key}`", _value(k), k.unit, _default(k), _range(k), k.doc)
                          for k in spec.keys]
    return ("| key | value | unit | default | valid range | meaning |\n"
            "|---|---|---|---|---|---|\n"
            + "".join("| " + " | ".join(_cell(c) for c in r) + " |\n" for r in rows))


_REGION = re.compile(r"(<!-- generated: ([\w .-]+) -->\n)(.*?)(<!-- end generated -->)", re.S)


def update(text: str, parts: Mapping[str, str]) -> str:
    """`text` (a docs page) with every region ``<!-- generated: NAME -->`` ... ``<!-- end
    generated -->`` holding ``parts[NAME]``; a region whose NAME is not in `parts`, or a part
    with no region, is a TypeError (a programming error the docs test catches)."""
    seen: list[str] = []

    def sub(m: re.Match) -> str:
        name = m.group(2)
        if name not in parts:
            raise TypeError(f"generated region {name!r} has no generator")
        seen.append(name)
        return m.group(1) + parts[name] + m.group(4)

    out = _REGION.sub(sub, text)
    missing = set(parts) - set(seen)
    if missing:
        raise TypeError(f"no region for the generated parts {sorted(missing)}")
    return out
