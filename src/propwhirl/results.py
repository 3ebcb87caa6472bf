"""The result protocol: every result propwhirl saves is a :class:`Result`, re-read with every
key checked (:class:`SavedDict`).

A result file is JSON with a ``"format"`` of the form ``propwhirl.<kind>/<version>``
(``propwhirl.analysis/3``, ``propwhirl.clearance/1``, ...).  A result class names its
:attr:`~Result.KIND`, the :attr:`~Result.VERSION` it writes and the versions it reads
(:attr:`~Result.READABLE`, with the format names of older releases in
:attr:`~Result.OLD_FORMATS`), and implements only its fields: :meth:`~Result.encode` (a plain
JSON-able dict) and :meth:`~Result.decode` (the fields back, checked).  The base gives

* ``to_dict()`` — ``{"format": "propwhirl.<kind>/<version>", **encode()}``;
* ``from_dict(d, where="")`` — the format checked (another kind, an unknown version or no
  propwhirl format: one line naming both kinds or the versions read), then ``decode``;
* ``save(path)`` — the JSON written atomically (:func:`propwhirl.fileio.write_text`); a
  non-finite number is an error naming its key, and nothing is written;
* ``load(path)`` — :func:`read_document` (UTF-8 JSON, no NaN/Infinity constants, nesting
  bounded), then ``from_dict``; every error is one line starting with the path.

Only JSON is read: never pickle, ``eval`` or any other format that carries code.  Parts of a
result (a sweep inside an analysis, an event, a margin) have ``to_dict``/``from_dict(d,
where)`` of their own, without a format tag: they are read by the result that holds them.

This module is at the package's bottom layer (it imports only :mod:`propwhirl.fileio` and
:mod:`propwhirl.validate`): the engine, the analyses and the studies build on it.
"""
from __future__ import annotations

import json
import re
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any, ClassVar

import numpy as np

from propwhirl import fileio
from propwhirl.validate import InputError, file_path

__all__ = ["OLD_FORMAT_KINDS", "Result", "SavedDict", "format_kind", "non_finite_key",
           "read_document"]

#: ``propwhirl.<kind>/<version>``: kind in lower case letters, digits and hyphens
FORMAT_PATTERN = re.compile(r"propwhirl\.([a-z][a-z0-9-]*)/([0-9]{1,6})")

#: Format names of earlier releases and the kind of file they name (for messages about a
#: file of another kind; each kind's own old names are its :attr:`Result.OLD_FORMATS`).
OLD_FORMAT_KINDS = {"propwhirl-analysis": "analysis", "propwhirl partial results": "partial",
                    "propwhirl-model": "model"}


def shape_text(shape: tuple[int, ...]) -> str:
    """An array shape as error messages print it: ``(35, 12)``."""
    return str(tuple(int(s) for s in shape))


class SavedDict:
    """Reading a dict re-read from a result file: every value is checked for its type, shape
    and finiteness, and an error names the key (``sweep.eigenvalues.re: shape (35, 12) does
    not match 3 speeds``) — never a ``KeyError`` or ``TypeError``.

    `where` is the dotted path of the dict in the file ("sweep", "events[3]"); `required` and
    `optional` are its keys (any other key is an error).
    """

    _KINDS = {float: "fiu", int: "iu", bool: "b"}
    _TYPE_NAMES = {float: "numbers", int: "integers", bool: "booleans (true/false)"}

    def __init__(self, d: Any, where: str, required: Sequence[str], optional: Sequence[str] = ()):
        self.where = where
        if not isinstance(d, Mapping):
            raise InputError(f"{_at(where)}must be an object, got {json_type(d)}")
        missing = [k for k in required if k not in d]
        if missing:
            raise InputError(f"{_at(where)}missing key{'s' * (len(missing) > 1)} "
                             + ", ".join(repr(k) for k in missing))
        unknown = sorted(str(k) for k in d if k not in required and k not in optional)
        if unknown:
            raise InputError(f"{_at(where)}unknown key{'s' * (len(unknown) > 1)} "
                             + ", ".join(repr(k) for k in unknown))
        self.d = d

    def name(self, key: str) -> str:
        return f"{self.where}.{key}" if self.where else key

    def has(self, key: str) -> bool:
        return key in self.d

    def raw(self, key: str) -> Any:
        return self.d[key]

    def sub(self, key: str, required: Sequence[str], optional: Sequence[str] = ()) -> "SavedDict":
        return SavedDict(self.d[key], self.name(key), required, optional)

    def _fail(self, key: str, must: str) -> InputError:
        return InputError(f"{self.name(key)}: {must}")

    def array(self, key: str, kind: type = float, ndim: int = 1,
              shape: Sequence[int | None] | None = None, finite: bool = True) -> np.ndarray:
        """`key` as an array of `kind` (float, int or bool) with `ndim` dimensions; `shape`
        entries that are not None must match."""
        raw = self.d[key]
        if not isinstance(raw, list):
            raise self._fail(key, f"must be a list, got {json_type(raw)}")
        try:
            arr = np.asarray(raw)
        except (ValueError, TypeError, RecursionError):
            raise self._fail(key, "must be a rectangular list of lists "
                             f"({ndim}-dimensional)") from None
        if arr.size == 0 and arr.ndim == 1 and ndim > 1:  # [] for an empty (0, m) table
            rest = tuple(shape[1:]) if shape is not None else (None,) * (ndim - 1)
            arr = arr.reshape((0,) + tuple(0 if m is None else m for m in rest))
        if arr.ndim != ndim:
            raise self._fail(key, f"must be {ndim}-dimensional, got shape {shape_text(arr.shape)}")
        if arr.size and arr.dtype.kind not in self._KINDS[kind]:
            raise self._fail(key, f"must hold {self._TYPE_NAMES[kind]} only")
        arr = arr.astype(kind)
        if finite and kind is float and not np.isfinite(arr).all():
            raise self._fail(key, "holds non-finite numbers (NaN or infinity)")
        if shape is not None:
            for axis, (got, want) in enumerate(zip(arr.shape, shape)):
                if want is not None and got != want:
                    raise self._fail(key, f"shape {shape_text(arr.shape)}: axis {axis} must "
                                     f"have {want} entries")
        return arr

    def complex_array(self, key: str, ndim: int, shape: Sequence[int | None] | None = None
                      ) -> np.ndarray:
        """`key` saved as ``{"re": ..., "im": ...}`` (finite, same shape)."""
        c = self.sub(key, ("re", "im"))
        re = c.array("re", ndim=ndim, shape=shape)
        im = c.array("im", ndim=ndim, shape=re.shape)
        return re + 1j * im

    def number(self, key: str, optional: bool = False) -> float | None:
        """A finite number (None allowed with `optional`)."""
        x = self.d[key]
        if x is None and optional:
            return None
        if isinstance(x, bool) or not isinstance(x, (int, float)):
            raise self._fail(key, f"must be a finite number, got {_json_value(x)}")
        try:
            value = float(x)               # an integer of 400 digits: OverflowError
        except OverflowError:
            value = float("inf")
        if not np.isfinite(value):
            raise self._fail(key, f"must be a finite number, got {_json_value(x)}")
        return value

    def integer(self, key: str, low: int | None = None, high: int | None = None) -> int:
        x = self.d[key]
        if isinstance(x, bool) or not isinstance(x, int):
            raise self._fail(key, f"must be an integer, got {_json_value(x)}")
        if (low is not None and x < low) or (high is not None and x > high):
            raise self._fail(key, f"= {x} is outside [{low}, {high}]")
        return x

    def string(self, key: str, choices: Sequence[str] = (), optional: bool = False) -> str | None:
        x = self.d[key]
        if x is None and optional:
            return None
        if not isinstance(x, str):
            raise self._fail(key, f"must be a string, got {_json_value(x)}")
        if choices and x not in choices:
            raise self._fail(key, f"= {x!r} is invalid: must be one of {', '.join(choices)}")
        return x

    def boolean(self, key: str) -> bool:
        """true or false (not 0 or 1)."""
        x = self.d[key]
        if not isinstance(x, bool):
            raise self._fail(key, f"must be true or false, got {_json_value(x)}")
        return x

    def number_or_nan(self, key: str) -> float:
        """A finite number, or null for one that was not finite (read back as NaN)."""
        x = self.number(key, optional=True)
        return float("nan") if x is None else x

    def items(self, key: str) -> list[tuple[str, Any]]:
        """The entries of the list `key` with their dotted paths (``key[i]``)."""
        x = self.d[key]
        if not isinstance(x, list):
            raise self._fail(key, f"must be a list, got {json_type(x)}")
        return [(f"{self.name(key)}[{i}]", y) for i, y in enumerate(x)]

    def strings(self, key: str, n: int | None = None) -> tuple[str, ...]:
        x = self.d[key]
        if not isinstance(x, list) or not all(isinstance(s, str) for s in x):
            raise self._fail(key, "must be a list of strings")
        if n is not None and len(x) != n:
            raise self._fail(key, f"has {len(x)} entries, need {n}")
        return tuple(x)

    def counters(self, key: str) -> dict[str, int]:
        x = self.d[key]
        if not isinstance(x, Mapping) or not all(
                isinstance(k, str) and isinstance(c, int) and not isinstance(c, bool)
                for k, c in x.items()):
            raise self._fail(key, "must be an object of integer counters")
        return dict(x)

    def bracket(self, key: str) -> tuple[float, float]:
        """A speed interval [lo, hi] [m/s], finite, lo <= hi."""
        b = self.array(key, shape=(2,))
        if not b[0] <= b[1]:
            raise self._fail(key, f"= [{float(b[0])!r}, {float(b[1])!r}] is invalid: must "
                             "have lo <= hi")
        return float(b[0]), float(b[1])


def _at(where: str) -> str:
    """``"where: "`` for a message (nothing at a document's top level)."""
    return f"{where}: " if where else ""


def json_type(x: Any) -> str:
    """What a JSON value is, as error messages name it ("an object", "a list", "null", ...)."""
    return {dict: "an object", list: "a list", str: "a string", bool: "a boolean",
            int: "a number", float: "a number", type(None): "null"}.get(type(x), type(x).__name__)


def _json_value(x: Any) -> str:
    if isinstance(x, (dict, list)):
        return json_type(x)
    text = repr(x)
    return text if len(text) <= 40 else text[:37] + "..."


def format_kind(fmt: Any) -> tuple[str, int] | None:
    """``(kind, version)`` of a format tag ``propwhirl.<kind>/<version>``, None for anything
    else.

    >>> format_kind("propwhirl.clearance/1")
    ('clearance', 1)
    >>> format_kind("propwhirl-analysis") is None
    True
    """
    m = FORMAT_PATTERN.fullmatch(fmt) if isinstance(fmt, str) else None
    return None if m is None else (m.group(1), int(m.group(2)))


def non_finite_key(obj: Any, where: str = "") -> str:
    """The dotted key of the first non-finite number in a JSON-able document ("" if none).

    >>> non_finite_key({"a": [1.0, {"b": float("nan")}]})
    'a[1].b'
    """
    if isinstance(obj, Mapping):
        for k, x in obj.items():
            found = non_finite_key(x, f"{where}.{k}" if where else str(k))
            if found:
                return found
    elif isinstance(obj, (list, tuple)):
        for i, x in enumerate(obj):
            found = non_finite_key(x, f"{where}[{i}]")
            if found:
                return found
    elif isinstance(obj, (float, np.floating)) and not np.isfinite(obj):
        return where or "the value"
    return ""


def _refuse_constant(name: str) -> Any:
    raise InputError(f"holds {name}, which a result file must not (numbers are finite)")


def read_document(path: str | Path, what: str) -> Any:
    """The JSON document of the result file `path` (a `what`, e.g. "analysis file"): UTF-8
    (:func:`propwhirl.fileio.read_text`: not found, unreadable, empty), valid JSON (the line
    and column of the first error; "truncated?" when it ends early), no ``NaN`` or
    ``Infinity``, nesting within Python's recursion limit — else an
    :class:`~propwhirl.validate.InputError` of one line starting with the path.  Only JSON:
    nothing in the file is executed."""
    text = fileio.read_text(path, what)
    where = fileio.shown(path)
    try:
        return json.loads(text, parse_constant=_refuse_constant)
    except json.JSONDecodeError as exc:
        end = " (the file ends early: truncated?)" if exc.pos >= len(text.rstrip()) else ""
        msg = exc.msg[:-3] if exc.msg.endswith(" at") else exc.msg   # "... starting at"
        raise InputError(f"{where}: not valid JSON: {msg} (line {exc.lineno}, column "
                         f"{exc.colno}){end}") from None
    except RecursionError:
        raise InputError(f"{where}: not {_article(what)} {what}: nested too deeply") from None
    except ValueError as exc:  # InputError from _refuse_constant, too-long integers
        raise InputError(f"{where}: not {_article(what)} {what}: {exc}") from None


def _article(what: str) -> str:
    return "an" if what[:1].lower() in "aeiou" else "a"


class Result:
    """Base of the results propwhirl saves: the format tag, checked reading, atomic saving
    (the module docstring).

    A subclass sets :attr:`KIND`, :attr:`VERSION`, :attr:`READABLE` (and
    :attr:`OLD_FORMATS`, :attr:`UNTAGGED` for files of older releases), :attr:`WHAT`, and
    implements :meth:`encode` and :meth:`decode`.
    """

    #: the kind of result: the ``<kind>`` of ``propwhirl.<kind>/<version>``
    KIND: ClassVar[str] = ""
    #: the version this propwhirl writes
    VERSION: ClassVar[int] = 1
    #: the versions this propwhirl reads (VERSION among them)
    READABLE: ClassVar[tuple[int, ...]] = (1,)
    #: format names of older releases → their version: an int, or (the key holding it, the
    #: versions read), e.g. ``{"propwhirl-analysis": ("format_version", (1, 2))}``
    OLD_FORMATS: ClassVar[Mapping[str, int | tuple[str, tuple[int, ...]]]] = {}
    #: the version of a dict without "format" (written before the key existed), or None:
    #: such a dict is refused
    UNTAGGED: ClassVar[int | None] = None
    #: what a file of this kind is called in messages ("analysis file")
    WHAT: ClassVar[str] = "result file"
    #: keys of the old forms' version (dropped before :meth:`decode`)
    _VERSION_KEYS: ClassVar[tuple[str, ...]] = ("format", "format_version")

    # ------------------------------------------------------------------ to implement
    def encode(self) -> dict[str, Any]:
        """The fields as a plain JSON-able dict (no "format": :meth:`to_dict` adds it)."""
        raise NotImplementedError

    @classmethod
    def decode(cls, d: Mapping[str, Any], version: int, where: str) -> "Result":
        """The result of `d` (a dict of :meth:`encode`'s keys, without "format"), written by
        `version` of the format; checked, errors naming the key under `where`."""
        raise NotImplementedError

    # ------------------------------------------------------------------ the protocol
    @classmethod
    def format_name(cls, version: int | None = None) -> str:
        """``propwhirl.<KIND>/<version>`` (default: the version written)."""
        return f"propwhirl.{cls.KIND}/{cls.VERSION if version is None else version}"

    def to_dict(self) -> dict[str, Any]:
        """The result as a plain JSON-able dict: ``{"format": ..., **encode()}``."""
        return {"format": self.format_name(), **self.encode()}

    @classmethod
    def check_format(cls, d: Any, where: str = "") -> int:
        """The version of the document `d` (a dict with this kind's "format", or an older
        form of :attr:`OLD_FORMATS` / :attr:`UNTAGGED`); else a one-line
        :class:`~propwhirl.validate.InputError` naming what it is and what was expected."""
        at = _at(where)
        want = f"{_article(cls.WHAT)} {cls.WHAT} (format {cls.format_name()!r})"
        if not isinstance(d, Mapping):
            raise InputError(f"{at}not {want}: must be an object, got {json_type(d)}")
        if "format" not in d:
            if cls.UNTAGGED is None:
                raise InputError(f"{at}not {want}: it has no \"format\" key")
            return cls.UNTAGGED
        fmt = d["format"]
        if isinstance(fmt, str) and fmt in cls.OLD_FORMATS:
            how = cls.OLD_FORMATS[fmt]
            if isinstance(how, int):
                return how
            key, versions = how
            if key not in d:
                raise InputError(f"{at}missing key {key!r} (format {fmt!r})")
            version = d[key]
            if isinstance(version, bool) or version not in versions:
                raise InputError(f"{at}{key} = {_json_value(version)} is not supported: this "
                                 f"propwhirl reads {fmt!r} versions "
                                 f"{', '.join(map(str, versions))}")
            return int(version)
        tag = format_kind(fmt)
        other = tag[0] if tag else OLD_FORMAT_KINDS.get(fmt) if isinstance(fmt, str) else None
        if other is not None and other != cls.KIND:
            raise InputError(f"{at}format {_json_value(fmt)} is {_article(other)} {other} "
                             f"file, not {want}")
        if tag is None:
            raise InputError(f"{at}not {want}: format = {_json_value(fmt)} is invalid")
        if tag[1] not in cls.READABLE:
            newer = " (written by a newer propwhirl?)" if tag[1] > cls.VERSION else ""
            raise InputError(f"{at}format {fmt!r}: version {tag[1]} is not supported{newer}: "
                             f"this propwhirl reads {cls.KIND} versions {cls._versions()}")
        return tag[1]

    @classmethod
    def _versions(cls) -> str:
        return ", ".join(map(str, cls.READABLE))

    @classmethod
    def from_dict(cls, d: Any, where: str = ""):
        """The result of a dict written by :meth:`to_dict` (or an older version's), checked:
        its format (:meth:`check_format`), then every field (:meth:`decode`); an error is one
        :class:`~propwhirl.validate.InputError` line naming the key (under `where`)."""
        version = cls.check_format(d, where)
        body = {k: x for k, x in d.items() if k not in cls._version_keys(d)}
        try:
            return cls.decode(body, version, where)
        except RecursionError:
            raise InputError(f"{_at(where)}nested too deeply") from None

    @classmethod
    def _version_keys(cls, d: Mapping[str, Any]) -> tuple[str, ...]:
        fmt = d.get("format")
        how = cls.OLD_FORMATS.get(fmt) if isinstance(fmt, str) else None
        return ("format", how[0]) if isinstance(how, tuple) else ("format",)

    def to_json(self) -> str:
        """:meth:`to_dict` as JSON text (finite numbers only: a non-finite one is an error
        naming its key)."""
        d = self.to_dict()
        try:
            return json.dumps(d, indent=1, allow_nan=False) + "\n"
        except ValueError:
            raise InputError(f"cannot write the {self.WHAT}: {non_finite_key(d)} is not a "
                             "finite number") from None

    def save(self, path: str | Path) -> Path:
        """Write the result as JSON to `path`, atomically (:func:`propwhirl.fileio.write_text`:
        a full disk or a Ctrl-C leaves the old file or none, never a partial one).  A
        non-finite number is an :class:`~propwhirl.validate.InputError` naming its key, and
        nothing is written."""
        file_path("path", path, f"the {self.WHAT} to write")
        try:
            text = self.to_json()
        except InputError as exc:
            raise InputError(f"cannot write {self.WHAT} {fileio.quoted(path)}: "
                             f"{str(exc).split(': ', 1)[1]}") from None
        return fileio.write_text(path, text, what=self.WHAT)

    @classmethod
    def load(cls, path: str | Path):
        """Re-read a result written by :meth:`save` (or by an older version of propwhirl):
        :func:`read_document`, then :meth:`from_dict`; every error is one line starting with
        the path."""
        file_path("path", path, f"a {cls.WHAT}")
        doc = read_document(path, cls.WHAT)
        try:
            result = cls.from_dict(doc)
        except InputError as exc:
            raise InputError(f"{fileio.shown(path)}: {exc}") from None
        return result.loaded_from(Path(path), doc)

    def loaded_from(self, path: Path, doc: Mapping[str, Any]) -> "Result":
        """The result re-read from the file `path` (document `doc`, already checked): itself;
        a result with files beside its JSON reads them here."""
        return self
