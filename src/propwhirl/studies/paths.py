"""Parameter paths: any numeric field of any model, addressed by a string.

A path names a field the way Python reaches it from the model, with the field names of the
model dataclasses (:mod:`propwhirl.model`) joined by dots and tuple entries by their index
(Python's, from 0 — the index of the model's own error messages, ``propellers[0].y``, while
figures and reports number propellers from 1)::

    flight.density                       # a number of a nested table
    wing.GJ                              # a spanwise property, set uniform along the span
    wing.EI*                             # the scale form: a factor on the whole distribution
    wing.EI[3]                           # one element's value of a per-element property
    wing.rayleigh[0]                     # one entry of a list of numbers
    propellers[1].propeller.f_theta      # a field of the second installation's propeller
    propellers[*].propeller.f_psi        # the same field of every installation
    propellers[0:6].propeller.f_psi      # a slice (Python's: 0 to 5, STOP excluded; 0:6:2)
    propellers[0,2,4].propeller.f_psi    # a list of installations
    propellers[high_lift].propeller.f_psi    # a named group (PropellerWing.groups, [groups])
    propellers[0].propeller.masses[0].mass
    propellers[0].propeller.inertia.I_theta_P    # an entry of a mapping
    propeller.beta_075_deg               # an IsolatedPropeller's propeller
    propellers[0].propeller.f_theta,propellers[0].propeller.f_psi   # linked: one value, both

Selections (``*``, slices, lists, groups) address lists of tables (the installations, a
propeller's masses); a list of numbers takes one index.  The indices of installations are
those of ``model.propellers`` and of the file's ``installations`` list, from 0 — the reports
and figures number propellers from 1, so "propellers 1–6" are ``propellers[0:6]``.  A named
group is a model's ``groups`` entry (``PropellerWing(groups={"high_lift": (0, 1, 2)})``, the
``[groups]`` table of a model file).  Setting a field through one installation changes that
installation's propeller only, also when the file shares one ``[propellers.KEY]`` table
between installations (each installation holds its own copy once changed).

Linked paths (a tuple of paths, or paths joined by commas outside brackets) are one
parameter: every path takes its one value (an isotropic mount: f_theta and f_psi together).
They must share the unit (or all be scale forms) and reach distinct values; the value is
checked against every path's range.

The field metadata (``model/fields.py``'s :func:`~propwhirl.model.fields.spec`: unit, range,
description) gives every path its unit and valid range, and the list of valid paths of a
model (:func:`parameters`).  An unknown path is an InputError listing the nearest valid paths
(:mod:`difflib`); a field that is not a number (a string, a switch, a function) is refused.

Setting a value rebuilds the model with :func:`dataclasses.replace`, innermost object first,
so every object's own validation runs (a wing's mesh, a propeller's checks, the model's
installation nodes).  A value outside the declared range is an error naming the path and the
range before anything is built; any other error of the model is restated with the path.  A
field with an alternative (f_theta or K_theta, f_psi or K_psi, polar_inertia or
radius_of_gyration) is set with its alternative cleared, so varying a field together with its
alternative — or two paths reaching one value — is refused (:func:`check_independent`); the
values of a study are checked all at once (:meth:`Parameter.check_values`).

The scale form ``PATH*`` (listed for the distributed properties, accepted for any number
given) multiplies the current value of a distributed property — a spanwise
wing property (a number, one value per element, or a function of y), a radial
:class:`~propwhirl.model.propellers.propeller_aero.Distribution` — or of a number by a factor (1 = the
model as given).  A scaled function stays picklable (:class:`Scaled`) so that variants can go
to worker processes.
"""
from __future__ import annotations

import dataclasses
import difflib
import re
from dataclasses import dataclass
from typing import Any, Callable, Iterable, Mapping, Sequence

import numpy as np

from propwhirl import validate as v
from propwhirl.model.fields import FieldSpec, Range, declared_fields
from propwhirl.model.propellers.propeller_aero import Distribution

#: Fields that exclude each other (class name, field) → the field cleared when it is set.
ALTERNATIVES: dict[tuple[str, str], str] = {
    ("Propeller", "f_theta"): "K_theta", ("Propeller", "K_theta"): "f_theta",
    ("Propeller", "f_psi"): "K_psi", ("Propeller", "K_psi"): "f_psi",
    ("Wing", "polar_inertia"): "radius_of_gyration",
    ("Wing", "radius_of_gyration"): "polar_inertia",
}

#: Forms of a field holding one number (possibly None: not given).
_NUMBER_FORMS = ("number", "integer")
#: Forms that can be scaled as a whole (a distribution along the span or the radius).
_DISTRIBUTED_FORMS = ("spanwise", "distribution", "number_or_string")
#: Forms holding a nested dataclass (or a tuple of them).
_TABLE_FORMS = ("table", "flat", "reference", "derivatives")
_TUPLE_FORMS = ("tables", "installations")
#: Forms never addressable (not a model quantity).
_HIDDEN_FORMS = ("derived",)

_SEGMENT = re.compile(r"^([A-Za-z_][A-Za-z0-9_]*)((?:\[[^\[\]]*\])*)$")
_INDEX = re.compile(r"\[([^\[\]]*)\]")
#: The forms of an index between brackets: a number, ``*``, a slice, a list, a group name.
_NUMBER_INDEX = re.compile(r"^\d+$")
_SLICE_INDEX = re.compile(r"^(-?\d*):(-?\d*)(?::(-?\d*))?$")
_LIST_INDEX = re.compile(r"^\d+(?:,\d+)+$")
_GROUP_INDEX = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")
#: How indices of lists of tables are numbered, for messages.
NUMBERING = "from 0: propellers[0] is propeller 1 of the reports"
#: An index of more significant digits than this addresses no entry of any model (int() of a
#: string of thousands of digits is refused by Python itself): it is taken as this large number,
#: which every list's bounds check refuses.
_MAX_INDEX_DIGITS = 9
#: Paths longer than this are cut in the middle in messages (an error stays one short line).
_SHOWN_PATH = 100


@dataclass(frozen=True)
class Scaled:
    """A function of position multiplied by a factor: ``Scaled(fn, 2.0)(y) == 2 fn(y)``
    (picklable when `fn` is)."""

    function: Callable[[np.ndarray], np.ndarray]
    factor: float

    def __call__(self, x):
        return self.factor * np.asarray(self.function(x), dtype=float)


@dataclass(frozen=True)
class _Step:
    name: str
    #: int; "*" for every entry; a tuple of ints for a selection (a slice, a list, a group)
    indices: tuple[int | str | tuple[int, ...], ...] = ()
    #: the indices as the path writes them ("0:6", "high_lift"); "" where the index is shown
    #: as its resolved value
    shown: tuple[str, ...] = ()


@dataclass(frozen=True)
class Parameter:
    """A resolved parameter path of one model.

    path:  the path as text (normalised: no spaces), ``*`` last for the scale form
    scale: True for the scale form (the value is a factor, 1 = the model as given)
    unit:  SI unit of the value ("" for a factor or a dimensionless field)
    doc:   the field's description (its metadata)
    range: the declared valid range of the value (None for a factor or an undeclared one)
    integer: the field holds an integer (values must be whole numbers)
    links: the parameters this one sets to its one value (linked paths, ``PATH1,PATH2``);
        () for one path
    """

    path: str
    steps: tuple[_Step, ...]
    scale: bool
    unit: str
    doc: str
    range: Range | None
    integer: bool = False
    #: the class holding the field (for its alternative: f_theta of a Propeller clears K_theta)
    owner: str = ""
    links: tuple["Parameter", ...] = ()

    @property
    def members(self) -> tuple["Parameter", ...]:
        """The single-path parameters this one sets: its links, or itself."""
        return self.links or (self,)

    @property
    def label(self) -> str:
        """Axis label: ``'wing.GJ [N m^2]'``, ``'wing.EI* (factor)'``."""
        if self.scale:
            return f"{self.path} (factor)"
        return f"{self.path} [{self.unit}]" if self.unit else self.path

    def describe(self) -> str:
        """One line: path, unit, range, description."""
        rng = "" if self.range is None else f" in {self.range}"
        unit = f" [{self.unit}]" if self.unit and not self.scale else ""
        return f"{self.path}{unit}{rng}: {self.doc}"

    def value(self, model: Any) -> float | None:
        """The model's current value (1.0 for the scale form; None where the field is not
        given, e.g. f_theta of a propeller given K_theta, or not one number)."""
        if self.scale:
            return 1.0
        if self.links:
            vals = [p.value(model) for p in self.links]
            return vals[0] if vals[0] is not None and all(x == vals[0] for x in vals) else None
        vals = [x for x in _leaves(model, self.steps)]
        if not vals or any(not _is_number(x) for x in vals):
            return None
        first = float(np.asarray(vals[0]))
        return first if all(float(np.asarray(x)) == first for x in vals) else None

    def set(self, model: Any, value: float) -> Any:
        """`model` with this parameter set to `value` (a factor for the scale form), rebuilt
        through :func:`dataclasses.replace` so that its own validation runs."""
        if self.links:
            if np.ndim(value):
                raise v.InputError(f"{self.path} = {v.short_repr(value)} is invalid: must be "
                                   "one number")
            for p in self.links:
                p.check_values(value)       # every path's range before anything is built
            for p in self.links:
                model = p.set(model, value)
            return model
        x = self._checked(value)
        try:
            return _set(model, self.steps, lambda old: self._leaf(old, x))
        except v.InputError as exc:
            unit = "" if self.scale or not self.unit else f" {self.unit}"
            raise v.InputError(f"{self.path} = {x:g}{unit}: {exc}") from None

    def check_values(self, values: Any, name: str | None = None) -> np.ndarray:
        """`values` (one number or a 1-D sequence) as a float array, every one of them checked
        at once against what the path accepts — finite, a whole number for an integer field,
        > 0 for a factor, inside the declared range — before any variant is built or analysed.

        One InputError names the path (or `name`, e.g. ``"upper"``), the offending values
        (the first few) and the valid range.
        """
        if self.links:
            arr = np.asarray(0.0)
            for p in self.links:
                arr = p.check_values(values, name)
            return arr
        label = self.path if name is None else f"{self.path}: {name}"
        arr = np.atleast_1d(np.asarray(v.finite(label, values, "" if self.scale else self.unit),
                                       dtype=float))
        if arr.ndim != 1:
            raise v.InputError(f"{label}: the values must be a 1-D sequence, got shape "
                               f"{arr.shape}")
        if self.scale:
            bad, why = arr <= 0, "invalid: a factor must be > 0"
        elif self.integer and np.any(arr != np.round(arr)):
            bad, why = arr != np.round(arr), "invalid: must be whole numbers (an integer field)"
        elif self.range is not None:
            bad = ~np.asarray(self.range.contains(arr), dtype=bool)
            unit = f" {self.unit}" if self.unit else ""
            why = f"outside the valid range {self.range}{unit}"
        else:
            return arr
        if bad.any():
            raise v.InputError(f"{label} = {_some(arr[bad], self.unit)} "
                               f"{'is' if bad.sum() == 1 else 'are'} {why}")
        return arr

    # ------------------------------------------------------------------ helpers
    def _checked(self, value: Any) -> float | int:
        name = self.path
        if np.ndim(value):
            raise v.InputError(f"{name} = {v.short_repr(value)} is invalid: must be one number")
        x = float(v.finite(name, value, "" if self.scale else self.unit))
        if self.scale:
            v.positive(name, x)
            return x
        if self.integer:
            if x != round(x):
                raise v.fail(name, value, "invalid: must be a whole number (an integer field)")
            x = int(round(x))
        if self.range is not None:
            self.range.check(name, x, self.unit)
        return x

    def _leaf(self, old: Any, x: float | int) -> Any:
        if not self.scale:
            return x
        if old is None or isinstance(old, str):
            raise v.InputError(f"{self.path}: the field is {v.short_repr(old)}: there is no "
                               "value to scale (give a number, or set it without '*')")
        # a product beyond the floats is inf, which the model's own check names (no
        # RuntimeWarning before that one-line error)
        if isinstance(old, Distribution):
            with np.errstate(over="ignore", invalid="ignore"):
                return dataclasses.replace(old, values=tuple(x * np.asarray(old.values)))
        if isinstance(old, Scaled):
            return Scaled(old.function, x * old.factor)
        if callable(old):
            return Scaled(old, x)
        with np.errstate(over="ignore", invalid="ignore"):
            arr = np.asarray(old, dtype=float) * x
        return float(arr) if arr.ndim == 0 and not isinstance(old, np.ndarray) else arr


def _some(values: np.ndarray, unit: str = "", most: int = 3) -> str:
    """'2000 Hz' or '2000, 5000 and 3 more Hz': the first few of `values` for a message."""
    shown = ", ".join(f"{x:g}" for x in values[:most])
    more = f" and {len(values) - most} more" if len(values) > most else ""
    return f"{shown}{more}{' ' + unit if unit else ''}"


def _shown(text: str) -> str:
    """`text` for a message: cut in the middle beyond :data:`_SHOWN_PATH` characters."""
    if len(text) <= _SHOWN_PATH:
        return text
    half = (_SHOWN_PATH - 5) // 2
    return f"{text[:half]}...({len(text)} characters)...{text[-half:]}"


def _index_number(digits: str) -> int:
    """The index written as `digits` (leading zeros allowed); an absurdly long one (more than
    :data:`_MAX_INDEX_DIGITS` significant digits) as 10**_MAX_INDEX_DIGITS, out of any list's
    range."""
    significant = digits.lstrip("0") or "0"
    if len(significant) > _MAX_INDEX_DIGITS:
        return 10 ** _MAX_INDEX_DIGITS
    return int(significant)


def _is_number(x: Any) -> bool:
    return isinstance(x, (int, float, np.integer, np.floating)) and not isinstance(x, (bool, np.bool_))


def _leaves(obj: Any, steps: Sequence[_Step]) -> Iterable[Any]:
    """The values a path reaches (several with a ``[*]`` index)."""
    if not steps:
        yield obj
        return
    step, rest = steps[0], steps[1:]
    if obj is None:
        yield None
        return
    cur = obj.get(step.name) if isinstance(obj, Mapping) else getattr(obj, step.name)
    items = [cur]
    for i in step.indices:
        items = [y for c in items for y in _select(c, i)]
    for c in items:
        yield from _leaves(c, rest)


def _select(container: Any, i: int | str | tuple[int, ...]) -> list[Any]:
    """The entries of `container` index `i` reaches (every one for "*", a selection's)."""
    if i == "*":
        return list(container)
    if isinstance(i, tuple):
        return [container[k] for k in i]
    return [container[i]]


def _positions(i: int | str | tuple[int, ...], n: int) -> Iterable[int]:
    """The positions index `i` reaches in a list of `n` entries."""
    return range(n) if i == "*" else i if isinstance(i, tuple) else [i]


def _replace_index(container: Any, indices: Sequence[int | str], fn: Callable[[Any], Any]) -> Any:
    if not indices:
        return fn(container)
    i, rest = indices[0], indices[1:]
    if isinstance(container, np.ndarray):
        out = container.astype(float, copy=True)
        for k in _positions(i, out.size):
            out[k] = _replace_index(out[k], rest, fn)
        return out
    items = list(container)
    for k in _positions(i, len(items)):
        items[k] = _replace_index(items[k], rest, fn)
    return tuple(items)


def _set(obj: Any, steps: Sequence[_Step], leaf: Callable[[Any], Any]) -> Any:
    step, rest = steps[0], steps[1:]

    def inner(old: Any) -> Any:
        return leaf(old) if not rest else _set(old, rest, leaf)

    if isinstance(obj, Mapping) or obj is None:           # an entry of a mapping field
        new = dict(obj or {})
        new[step.name] = _replace_index(new.get(step.name), step.indices, inner)
        return new
    new_value = _replace_index(getattr(obj, step.name), step.indices, inner)
    changes = {step.name: new_value}
    other = ALTERNATIVES.get((type(obj).__name__, step.name))
    if other is not None and not rest:
        changes[other] = None
    return dataclasses.replace(obj, **changes)


# ============================================================================ resolution
@dataclass(frozen=True)
class _Node:
    """What a prefix of a path reaches: a field's declaration and its value."""

    spec: FieldSpec | None
    form: str | None
    value: Any
    cls_name: str


def _fields_of(obj: Any) -> dict[str, _Node]:
    """The declared fields of a dataclass instance (derived fields hidden)."""
    out = {}
    for name, spec, form in declared_fields(type(obj)):
        if form in _HIDDEN_FORMS or name.startswith("_"):
            continue
        out[name] = _Node(spec, form, getattr(obj, name), type(obj).__name__)
    return out


def _entries_of(node: _Node) -> dict[str, _Node]:
    """The entries of a mapping field (declared in its metadata)."""
    value = node.value or {}
    return {e.name: _Node(FieldSpec(e.key, e.unit, e.doc, range=e.range), "number",
                          value.get(e.name), node.cls_name) for e in node.spec.entries}


def _children(node: _Node) -> dict[str, _Node] | None:
    """The named children of a node (None for a leaf)."""
    if node.form == "mapping":
        return _entries_of(node)
    if dataclasses.is_dataclass(node.value) and not isinstance(node.value, type):
        return _fields_of(node.value)
    return None


def _enumerate(obj: Any, prefix: str = "") -> list[str]:
    """Every valid path below dataclass instance `obj`."""
    out = []
    for name, node in _fields_of(obj).items():
        out += _enumerate_node(node, f"{prefix}{name}")
    return out


def _enumerate_node(node: _Node, text: str) -> list[str]:
    form, value = node.form, node.value
    if form in _NUMBER_FORMS:
        if value is None or _is_number(value):
            return [text]
        return []
    if form in _DISTRIBUTED_FORMS:
        if isinstance(value, str):
            return [text]
        return [text, f"{text}*"]
    if form in ("numbers", "split"):
        if value is None:
            return []
        return [f"{text}[{i}]" for i in range(len(value))]
    if form in _TUPLE_FORMS:
        out = []
        for i, item in enumerate(value or ()):
            out += _enumerate(item, f"{text}[{i}].")
        if len(value or ()) > 1:
            out += _enumerate(value[0], f"{text}[*].")
        return out
    kids = _children(node)
    if kids is None:
        return []
    return [p for name, k in kids.items() for p in _enumerate_node(k, f"{text}.{name}")]


def valid_paths(model: Any) -> list[str]:
    """Every parameter path of `model` (scale forms included), in field order."""
    _check_model(model)
    return _enumerate(model)


def parameters(model: Any) -> list[Parameter]:
    """Every parameter of `model`, resolved (units, ranges, descriptions)."""
    return [resolve(model, p) for p in valid_paths(model)]


def _check_model(model: Any) -> None:
    if not dataclasses.is_dataclass(model) or isinstance(model, type):
        raise v.InputError(f"model = {v.short_repr(model)} is invalid: parameter paths address the "
                           "fields of a model dataclass (PropellerWing, IsolatedPropeller, ...)")


def _unknown(model: Any, text: str, why: str) -> v.InputError:
    paths = valid_paths(model)
    near = difflib.get_close_matches(text, paths, n=5, cutoff=0.5)
    if not near:  # match on the last name alone ("GJ" → "wing.GJ")
        last = re.split(r"[.\[]", text.rstrip("*"))[-1]
        near = [p for p in paths if re.split(r"[.\[]", p.rstrip("*"))[-1] == last][:5]
    if not near:
        near = difflib.get_close_matches(text, paths, n=5, cutoff=0.0)
    return v.InputError(f"parameter path {_shown(text)!r} is invalid: {why}; nearest valid "
                        "paths: " + ", ".join(near))


def _not_numeric(text: str, node: _Node, what: str) -> v.InputError:
    return v.InputError(f"parameter path {_shown(text)!r} is invalid: {what} "
                        f"({node.cls_name} field, value {v.short_repr(node.value, 40)}), "
                        "not a number: only numeric fields can be varied")


def resolve(model: Any, path: str | Sequence[str]) -> Parameter:
    """The :class:`Parameter` of `path` in `model` (see the module docstring for the syntax).

    `path` may link several paths that take one value: a tuple of paths, or one string of
    paths separated by commas (outside brackets), e.g.
    ``"propellers[high_lift].propeller.f_theta,propellers[high_lift].propeller.f_psi"``.

    Raises
    ------
    InputError
        The path is malformed or unknown (the message lists the nearest valid paths), an index
        is out of range, a slice or a list selects nothing or an entry twice, a group is not
        defined, or it names a field that is not a number (a string, a switch, a table, a
        function); linked paths of different units, or that reach one value twice.
    """
    _check_model(model)
    if isinstance(path, (tuple, list)):
        if not path or not all(isinstance(x, str) for x in path):
            raise v.InputError(f"parameter path = {v.short_repr(path)} is invalid: linked paths "
                               "must be a non-empty tuple of strings such as "
                               "('propellers[0].propeller.f_theta', 'propellers[0].propeller.f_psi')")
        parts = [x for text in path for x in _split_links(text)] if path else []
    else:
        if not isinstance(path, str) or not path.strip():
            raise v.InputError(f"parameter path = {v.short_repr(path)} is invalid: must be a "
                               "non-empty string such as 'wing.GJ'")
        parts = _split_links(path)
    if len(parts) == 1:
        return _resolve_one(model, parts[0])
    if any(not x for x in parts):
        raise v.InputError(f"parameter path {_shown(','.join(parts))!r} is invalid: an empty "
                           "path between commas (linked paths: PATH1,PATH2,...)")
    return _linked(model, [_resolve_one(model, x) for x in parts])


def _split_links(text: str) -> list[str]:
    """`text` split at the commas outside brackets (the commas of linked paths), spaces
    removed."""
    text = "".join(text.split())
    out, depth, cur = [], 0, ""
    for ch in text:
        depth += (ch == "[") - (ch == "]")
        if ch == "," and depth == 0:
            out.append(cur)
            cur = ""
        else:
            cur += ch
    out.append(cur)
    return out


def _linked(model: Any, members: list[Parameter]) -> Parameter:
    """One parameter setting every one of `members` to its value (linked paths)."""
    check_independent(members)
    first = members[0]
    for p in members[1:]:
        if p.scale != first.scale or (not p.scale and p.unit != first.unit):
            what = lambda q: "a factor" if q.scale else f"[{q.unit or 'dimensionless'}]"
            raise v.InputError(f"parameter paths {first.path!r} and {p.path!r} are invalid "
                               f"linked: one value for both, but one is {what(first)} and the "
                               f"other {what(p)} (link paths of one unit)")
    text = ",".join(p.path for p in members)
    return Parameter(text, (), first.scale, first.unit,
                     "linked: " + "; ".join(dict.fromkeys(p.doc for p in members)),
                     first.range, any(p.integer for p in members), "", tuple(members))


def _resolve_one(model: Any, path: str) -> Parameter:
    """The :class:`Parameter` of one path (no commas outside brackets)."""
    text = "".join(path.split())
    scale = text.endswith("*")
    body = text[:-1] if scale else text
    raw = []
    for seg in body.split("."):
        m = _SEGMENT.match(seg)
        if m is None:
            raise _unknown(model, text, f"{_shown(seg)!r} is not a field name with optional "
                           "[index]")
        raw.append((m.group(1), tuple(_INDEX.findall(m.group(2)))))
    node = _Node(None, "table", model, type(model).__name__)
    done = ""
    steps = []
    for k, (name, tokens) in enumerate(raw):
        kids = _children(node)
        if kids is None:
            raise _unknown(model, text, f"{done or type(model).__name__} has no fields")
        if name not in kids:
            where = done or type(model).__name__
            raise _unknown(model, text, f"{where} has no field {name!r}")
        node = kids[name]
        done = f"{done}.{name}" if done else name
        indices, shown = [], []
        for token in tokens:
            node, done, index, written = _index(model, text, node, done, token)
            indices.append(index)
            shown.append(written)
        steps.append(_Step(name, tuple(indices), tuple(shown)))
        if k < len(raw) - 1 and node.form in _TUPLE_FORMS:
            raise _unknown(model, text, f"{done} is a list of tables: give an index, e.g. {done}[0]")
    return _leaf_parameter(model, _canonical(steps, scale), steps, node, scale)


def _canonical(steps: Sequence[_Step], scale: bool) -> str:
    """The path text of `steps`: indices without leading zeros (a slice, a list or a group as
    written), ``*`` last for the scale form."""
    return ".".join(s.name + "".join(f"[{t}]" for t in (s.shown or map(str, s.indices)))
                    for s in steps) + ("*" if scale else "")


def groups_of(model: Any) -> dict[str, tuple[int, ...]]:
    """The named groups of installations of `model` (``{}`` when it defines none): name →
    indices into ``model.propellers`` (from 0, as in paths)."""
    return dict(getattr(model, "groups", None) or {})


def _selection_error(model: Any, text: str, done: str, token: str, why: str, n: int) -> v.InputError:
    valid = (f"an index 0 to {n - 1}, *, a slice such as 0:{n}, a list such as 0,1"
             + (f", or a group ({', '.join(groups_of(model))})" if groups_of(model) and
                done.endswith("propellers") else ""))
    return v.InputError(f"parameter path {_shown(text)!r} is invalid: {done}[{_shown(token)}] "
                        f"{why}; {done} has {n} entr{'y' if n == 1 else 'ies'}, {NUMBERING}: "
                        f"give {valid}")


def _tuple_index(model: Any, text: str, node: _Node, done: str,
                 token: str) -> tuple[int | str | tuple[int, ...], str]:
    """The resolved index `token` of a list of tables (and its text in the canonical path)."""
    n = len(node.value or ())
    if token == "*":
        return "*", "*"
    if _NUMBER_INDEX.match(token):
        i = _index_number(token)
        if not i < n:
            raise _unknown(model, text, f"{done} has {n} entr{'y' if n == 1 else 'ies'} "
                           f"(indices 0 to {n - 1}, {NUMBERING})")
        return i, str(i)
    m = _SLICE_INDEX.match(token)
    if m is not None:
        parts = [None if not g else _index_number(g.lstrip("-")) * (-1 if g.startswith("-") else 1)
                 for g in m.groups()]
        if parts[2] == 0:
            raise _selection_error(model, text, done, token, "has a slice step of 0", n)
        chosen = tuple(range(n)[slice(*parts)])
        if not chosen:
            raise _selection_error(model, text, done, token, "selects no entry (a Python slice: "
                                   "START:STOP excludes STOP)", n)
        return chosen, token
    if _LIST_INDEX.match(token):
        chosen = tuple(_index_number(x) for x in token.split(","))
        bad = [i for i in chosen if not i < n]
        if bad:
            raise _selection_error(model, text, done, token, f"has {bad[0]}, out of range", n)
        if len(set(chosen)) != len(chosen):
            dup = next(i for i in chosen if chosen.count(i) > 1)
            raise _selection_error(model, text, done, token, f"lists {dup} twice", n)
        return chosen, ",".join(map(str, chosen))
    if _GROUP_INDEX.match(token):
        groups = groups_of(model) if done == "propellers" else {}
        if token not in groups:
            known = (f"the model's groups are {', '.join(groups)}" if groups else
                     "the model defines no groups (a [groups] table of the model file, or "
                     "PropellerWing(groups={...}))")
            if done != "propellers":
                known = "groups name installations: propellers[GROUP]"
            raise v.InputError(f"parameter path {_shown(text)!r} is invalid: {done}[{token}] "
                               f"names no group: {known}")
        return tuple(groups[token]), token
    raise _selection_error(model, text, done, token, "is not an index", n)


def _index(model: Any, text: str, node: _Node, done: str,
           token: str) -> tuple[_Node, str, int | str | tuple[int, ...], str]:
    """The node index `token` reaches below `node`, the path text so far, the resolved index
    and its text."""
    value, form = node.value, node.form
    if form in _TUPLE_FORMS:
        i, written = _tuple_index(model, text, node, done, token)
        n = len(value or ())
        first = 0 if i == "*" else i[0] if isinstance(i, tuple) else i
        item = value[first] if n else None
        sub = _Node(node.spec, "table", item, node.cls_name)
        return sub, f"{done}[{written}]", i, written
    if not _NUMBER_INDEX.match(token):
        if form in ("numbers", "split") or (form == "spanwise" and isinstance(value, np.ndarray)):
            n = 0 if value is None else len(value)
            raise _unknown(model, text, f"{done} has {n} values: give one index from 0 to "
                           f"{n - 1} (slices, lists and groups select tables, e.g. propellers)")
        raise _unknown(model, text, f"{done} is not a list: it takes no index")
    i = _index_number(token)
    if form in ("numbers", "split") or (form == "spanwise" and isinstance(value, np.ndarray)):
        n = 0 if value is None else len(value)
        if not i < n:
            raise _unknown(model, text, f"{done} has {n} values: give an index from 0 to {n - 1}")
        spec = node.spec
        if form == "split":
            spec = dataclasses.replace(spec, unit=spec.unit_of(i), range=spec.range_of(i),
                                       doc=f"{spec.doc} (entry {i})")
        return _Node(spec, "number", value[i], node.cls_name), f"{done}[{i}]", i, str(i)
    raise _unknown(model, text, f"{done} is not a list: it takes no index")


def _leaf_parameter(model: Any, text: str, steps: list[_Step], node: _Node, scale: bool) -> Parameter:
    form, value, s = node.form, node.value, node.spec
    if form in _NUMBER_FORMS:
        if value is not None and not _is_number(value):
            raise _not_numeric(text, node, "a function")
        integer = form == "integer"
        if scale and (integer or value is None):
            raise v.InputError(f"parameter path {text!r} is invalid: the scale form needs a "
                               f"number to scale, the field is {v.short_repr(value)}; use "
                               f"{text[:-1]!r}")
    elif form in _DISTRIBUTED_FORMS:
        integer = False
        if scale and isinstance(value, str):
            raise _not_numeric(text, node, f"a named rule {value!r}: set a number without '*'")
    elif form == "string":
        raise _not_numeric(text, node, "a string")
    elif form == "boolean":
        raise _not_numeric(text, node, "a switch (True/False)")
    elif form in ("numbers", "split"):
        raise _unknown(model, text, f"{text.rstrip('*')} is a list of numbers: address one entry")
    elif form in _TUPLE_FORMS or _children(node) is not None:
        raise _unknown(model, text, f"{text.rstrip('*')} is a table, not a number: address one "
                       "of its fields")
    else:
        raise _not_numeric(text, node, "a function or an object")
    unit = s.unit_of() if s is not None else ""
    rng = s.range_of() if s is not None else None
    doc = s.doc if s is not None else ""
    return Parameter(text, tuple(steps), scale, "" if scale else unit, doc,
                     None if scale else rng, integer, node.cls_name)


# ============================================================================ variants
def _disjoint(i: int | str | tuple[int, ...], j: int | str | tuple[int, ...]) -> bool:
    """Indices `i` and `j` of one list reach no common entry."""
    if "*" in (i, j):
        return False
    return not set(i if isinstance(i, tuple) else (i,)) & set(j if isinstance(j, tuple) else (j,))


def _conflict(a: Parameter, b: Parameter) -> str | None:
    """Why `a` and `b` cannot be varied together (they reach the same value, or a field and
    its alternative of the same object), or None when they are independent."""
    if a.links or b.links:
        for x in a.members:
            for y in b.members:
                why = _conflict(x, y)
                if why is not None:
                    return f"{x.path!r} and {y.path!r}: {why}"
        return None
    for k, (x, y) in enumerate(zip(a.steps, b.steps)):
        if any(_disjoint(i, j) for i, j in zip(x.indices, y.indices)):
            return None                      # different entries of one list: independent
        if x.name != y.name:
            last = k == len(a.steps) - 1 and k == len(b.steps) - 1
            if last and a.owner == b.owner and ALTERNATIVES.get((a.owner, x.name)) == y.name:
                return (f"{y.name} is the alternative of {x.name} (setting one clears the "
                        "other, so the first would be ignored): vary one of them")
            return None
    if a.path.rstrip("*") == b.path.rstrip("*"):
        return "a path appears twice"
    return "they set the same value: vary it once"


def check_independent(params: Sequence[Parameter]) -> None:
    """Refuse parameters that cannot be varied together: a path twice (``wing.EI`` and
    ``wing.EI*``), paths reaching the same value (``propellers[*].propeller.f_psi`` and
    ``propellers[0].propeller.f_psi``, ``wing.EI*`` and ``wing.EI[3]``), or a field and its
    alternative on the same object (f_theta and K_theta of one propeller: setting one clears
    the other, :data:`ALTERNATIVES`); selections that share an entry (``propellers[0:3]`` and
    ``propellers[2]``); linked paths, each of their paths.  One InputError naming the two
    paths."""
    for k, a in enumerate(params):
        for b in params[k + 1:]:
            why = _conflict(a, b)
            if why is not None:
                raise v.InputError(f"parameter paths {a.path!r} and {b.path!r} are invalid "
                                   f"together: {why}")


def set_value(model: Any, path: str | Parameter, value: float) -> Any:
    """`model` with the parameter `path` set to `value` [its unit] (see :class:`Parameter`)."""
    p = path if isinstance(path, Parameter) else resolve(model, path)
    return p.set(model, value)


def set_values(model: Any, values: Mapping[str | Parameter, float]) -> Any:
    """`model` with several parameters set at once (in the order given)."""
    params = [path if isinstance(path, Parameter) else resolve(model, path) for path in values]
    check_independent(params)
    out = model
    for p, x in zip(params, values.values()):
        out = p.set(out, x)
    return out


def _column(p: Parameter, values: Any) -> np.ndarray:
    """The values of `p`, all checked before any variant is built (:meth:`Parameter.check_values`)."""
    arr = p.check_values(values)
    if arr.size == 0:
        raise v.InputError(f"{p.path}: the values must be a non-empty 1-D sequence, got shape "
                           f"{arr.shape}")
    return arr


def variants(model: Any, columns: Mapping[str, Sequence[float]]) -> list[Any]:
    """One model per row of `columns` (path → equal-length values, set together): e.g.
    ``variants(m, {"propellers[0].propeller.f_theta": f, "propellers[0].propeller.f_psi": f})``.
    Each path is resolved once."""
    params = [resolve(model, p) for p in columns]
    check_independent(params)
    cols = [_column(p, columns[k]) for p, k in zip(params, columns)]
    n = len(cols[0]) if cols else 0
    for p, c in zip(params, cols):
        if len(c) != n:
            raise v.InputError(f"{p.path}: {len(c)} values, expected {n} (one per variant)")
    out = []
    for i in range(n):
        m = model
        for p, c in zip(params, cols):
            m = p.set(m, c[i])
        out.append(m)
    return out


def grid_variants(model: Any, axes: Sequence[tuple[str, Sequence[float]]]) -> list[Any]:
    """One model per point of the outer product of `axes` ((path, values) pairs), the last
    axis fastest (C order, as ``numpy.meshgrid(..., indexing="ij")`` flattened)."""
    params = [resolve(model, p) for p, _ in axes]
    check_independent(params)
    cols = [_column(p, vals) for p, (_, vals) in zip(params, axes)]
    out = []
    for idx in np.ndindex(*(len(c) for c in cols)):
        m = model
        for p, c, i in zip(params, cols, idx):
            m = p.set(m, c[i])
        out.append(m)
    return out


__all__ = ["Parameter", "Scaled", "ALTERNATIVES", "NUMBERING", "resolve", "groups_of",
           "valid_paths", "parameters",
           "set_value", "set_values", "variants", "grid_variants", "check_independent"]
