"""The partial-results file of a run of independent analyses: the finished points kept as
plain JSON with the fingerprint of the study, read back with every entry checked.

Used by :func:`propwhirl.studies.execution.map_analyses` (``checkpoint=``); a point whose
analysis failed is a :class:`TaskError`, here because the file keeps it too.

The partial-results file (format ``propwhirl.partial/2``) is plain JSON — numbers, strings,
lists and objects, nothing that carries code: it may come from anyone, so it is read like any
other result file, every entry checked (:meth:`Checkpoint.load`).  It holds

* ``fingerprint``: an object naming everything that decides a point's result — for a study the
  sha256 of the model's canonical content (:func:`content_digest`), the parameter paths and
  values, the speeds, the method, the convention, the tolerance — plus the propwhirl version and
  the kind of the points.  A file whose fingerprint differs is refused, naming the entries that
  differ; it is never mixed in.  The study functions fill the fingerprint in from their own
  arguments (a Checkpoint given without one gets a full one);
* ``points``: one object per finished point, ``{"index", "key", "value"}`` or, for a failed
  point, ``{"index", "key", "error", "error_type"}``.  The value is written and read by the
  checkpoint's :class:`PointFormat`: :data:`PLAIN` (the default: numbers, strings, booleans,
  null, lists and objects with string keys; floats round-trip exactly) or a per-kind schema
  such as the study row of :mod:`propwhirl.studies.runner`.
"""

from __future__ import annotations

import dataclasses
import hashlib
import json
import marshal
import math
import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable, Mapping, Sequence

import numpy as np

from propwhirl import __version__, fileio
from propwhirl import validate as v

#: Version of the partial-results file layout (2: plain JSON only, a structured fingerprint).
PARTIAL_VERSION = 2
#: The format tag of a partial-results file.
PARTIAL_FORMAT = f"propwhirl.partial/{PARTIAL_VERSION}"
#: The format tag of the files of version 1 (they could hold pickles: never read).
OLD_PARTIAL_FORMAT = "propwhirl partial results"
#: Largest partial-results file read [bytes] (a map of 250 000 points is ~100 MB).
MAX_PARTIAL_BYTES = 256 * 2**20
#: Deepest nesting of lists and objects in a partial-results file (the file's own levels
#: included: a point's value may nest about 12 deep).
MAX_DEPTH = 16
#: Longest string of a partial-results file (a key, a message, a label) [characters].
MAX_STRING = 100_000

_AGAIN = "remove it or run without --resume"


# ----------------------------------------------------------------------------- records
@dataclass(frozen=True)
class TaskError:
    """A point whose analysis failed: the exception's type name and its one-line message."""

    kind: str
    message: str

    def __str__(self) -> str:
        return f"{self.kind}: {self.message}"


# ----------------------------------------------------------------------------- plain data
def _json_type(x: Any) -> str:
    return {dict: "an object", list: "a list", str: "a string", bool: "a boolean",
            int: "an integer", float: "a number", type(None): "null"}.get(type(x), type(x).__name__)


def check_plain(x: Any, where: str, *, max_depth: int = MAX_DEPTH, finite: bool = False) -> Any:
    """`x` when it is plain JSON data — None, bool, int, float, str, lists and dicts with
    string keys — nested at most `max_depth` deep with strings of at most :data:`MAX_STRING`
    characters (and, with `finite`, no NaN or infinity); else an InputError naming where
    (`where`, then the keys and indices) and what is wrong.  Iterative: any depth is refused
    without recursion."""
    stack: list[tuple[Any, str, int]] = [(x, where, 0)]
    while stack:
        y, at, depth = stack.pop()
        if y is None or type(y) in (bool, int):
            continue
        if isinstance(y, float):
            if finite and not math.isfinite(y):
                raise v.InputError(f"{at}: {y!r} is invalid: must be a finite number")
            continue
        if isinstance(y, str):
            if len(y) > MAX_STRING:
                raise v.InputError(f"{at}: a string of {len(y)} characters (at most {MAX_STRING})")
            continue
        if not isinstance(y, (list, dict)):
            raise v.InputError(f"{at}: {_json_type(y)} is not plain data (numbers, strings, "
                               "booleans, null, lists and objects with string keys)")
        if depth >= max_depth:
            raise v.InputError(f"{at}: nested too deeply (more than {max_depth} levels)")
        if isinstance(y, list):
            stack.extend((z, f"{at}[{i}]", depth + 1) for i, z in enumerate(y))
        else:
            for k, z in y.items():
                if not isinstance(k, str):
                    raise v.InputError(f"{at}: key {k!r} is not a string")
                stack.append((z, f"{at}.{k}", depth + 1))
    return x


# ----------------------------------------------------------------------------- fingerprints
def _canonical(obj: Any, depth: int, seen: dict[int, Any]) -> Any:
    """A JSON-able form of `obj` that two equal models share and two different ones do not:
    dataclasses by their type and init fields (derived, ``_``-prefixed fields left out),
    floats by their exact repr, arrays by dtype, shape and the sha256 of their bytes,
    functions by their qualified name and the sha256 of their code."""
    if depth > 64:
        raise v.InputError("the model is nested too deeply to be fingerprinted (more than 64 levels)")
    if obj is None or isinstance(obj, (bool, str)):
        return obj
    if isinstance(obj, (int, np.integer)):
        return int(obj)
    if isinstance(obj, (float, np.floating)):
        return ["float", repr(float(obj))]
    if isinstance(obj, np.generic):
        return ["scalar", str(obj.dtype), repr(obj.item())]
    if isinstance(obj, np.ndarray):
        key = id(obj)
        if key not in seen:
            arr = np.ascontiguousarray(obj)
            seen[key] = ["array", str(arr.dtype), list(arr.shape),
                         hashlib.sha256(arr.tobytes()).hexdigest()]
        return seen[key]
    if dataclasses.is_dataclass(obj) and not isinstance(obj, type):
        return ["dataclass", f"{type(obj).__module__}.{type(obj).__qualname__}",
                {f.name: _canonical(getattr(obj, f.name), depth + 1, seen)
                 for f in dataclasses.fields(obj) if f.init and not f.name.startswith("_")}]
    if isinstance(obj, (list, tuple)):
        return [type(obj).__name__, [_canonical(x, depth + 1, seen) for x in obj]]
    if isinstance(obj, Mapping):
        items = [[_canonical(k, depth + 1, seen), _canonical(x, depth + 1, seen)]
                 for k, x in obj.items()]
        return ["mapping", sorted(items, key=lambda kv: json.dumps(kv, sort_keys=True))]
    if callable(obj):
        code = getattr(obj, "__code__", None)
        return ["callable", f"{getattr(obj, '__module__', '')}.{getattr(obj, '__qualname__', repr(obj))}",
                None if code is None else hashlib.sha256(marshal.dumps(code)).hexdigest()]
    return ["object", f"{type(obj).__module__}.{type(obj).__qualname__}", repr(obj)]


def content_digest(obj: Any) -> str:
    """``"sha256:<hex>"`` of the canonical content of `obj` (a model, a propeller, a list of
    speed grids ...): equal for equal content, whatever file or defaults it came from; any
    field that differs (a number in its last bit, a distribution, a switch) changes it."""
    text = json.dumps(_canonical(obj, 0, {}), sort_keys=True, separators=(",", ":"))
    return "sha256:" + hashlib.sha256(text.encode("utf-8")).hexdigest()


def _fingerprint(fp: Any) -> dict[str, Any]:
    """A checkpoint's fingerprint as a dict (a non-empty string is ``{"label": text}``)."""
    if isinstance(fp, str):
        return {"label": fp} if fp else {}
    if not isinstance(fp, Mapping):
        raise v.InputError(f"fingerprint = {v.short_repr(fp)} is invalid: must be a mapping "
                           "{name: plain value} (or a string)")
    out = dict(fp)
    check_plain(out, "fingerprint")
    return out


def _short(x: Any) -> str:
    if isinstance(x, str) and x.startswith("sha256:"):
        return f"sha256 {x[7:19]}…"
    return v.short_repr(x, 40)


def fingerprint_differences(stored: Mapping[str, Any], current: Mapping[str, Any]) -> list[str]:
    """``name (the file's vs this run's)`` of each entry that differs (absent: "none")."""
    out = []
    for k in sorted(set(stored) | set(current)):
        a, b = stored.get(k, None), current.get(k, None)
        if k not in stored or k not in current or a != b or type(a) is not type(b):
            out.append(f"{k} ({_short(a) if k in stored else 'none'} vs "
                       f"{_short(b) if k in current else 'none'})")
    return out


# ----------------------------------------------------------------------------- point formats
@dataclass(frozen=True)
class PointFormat:
    """How a point's result is kept in a partial-results file: as plain JSON, each kind with
    its schema.

    name:   the kind, recorded in the fingerprint (a file of another kind is refused);
    encode: result -> plain JSON data (an InputError when the result does not fit the schema);
    decode: (plain data, where, key) -> the result of the point named `key`, every entry
            checked (an InputError naming ``where`` and the entry).
    """

    name: str
    encode: Callable[[Any], Any]
    decode: Callable[[Any, str, str], Any]


def _plain_encode(result: Any) -> Any:
    return check_plain(result, "result")


def _plain_decode(value: Any, where: str, key: str | None = None) -> Any:
    return check_plain(value, where)


#: The default point format: the result itself when it is plain JSON data (numbers, strings,
#: booleans, None, lists, dicts with string keys; NaN and infinities as JSON's extensions).
PLAIN = PointFormat("plain", _plain_encode, _plain_decode)


# ----------------------------------------------------------------------------- checkpoint
@dataclass(frozen=True)
class Checkpoint:
    """Where a run keeps its finished points, and whether it resumes from them.

    path:        the partial-results file (JSON), e.g. beside the final result;
    resume:      load the finished points of `path` (if it exists) and run only the others;
    fingerprint: what decides a point's result, ``{name: plain value}`` (a string is
                 ``{"label": text}``): a file with another fingerprint is refused.  The study
                 functions add their own entries (:meth:`with_entries`);
    interval:    shortest time between two rewrites of the file while running [s];
    points:      how a point's result is written and read (:class:`PointFormat`; default
                 :data:`PLAIN`).
    """

    path: str | Path
    resume: bool = False
    fingerprint: Mapping[str, Any] | str = field(default_factory=dict)
    interval: float = 2.0
    points: PointFormat = PLAIN

    def __post_init__(self) -> None:
        if not isinstance(self.path, (str, Path)) or not str(self.path):
            raise v.InputError(f"path = {self.path!r} is invalid: must be a file name")
        v.boolean("resume", self.resume)
        v.non_negative("interval", self.interval, "s")
        object.__setattr__(self, "fingerprint", _fingerprint(self.fingerprint))
        if not isinstance(self.points, PointFormat):
            raise v.InputError(f"points = {self.points!r} is invalid: must be a "
                               "propwhirl.studies.execution.PointFormat")

    def with_entries(self, points: PointFormat | None = None, **entries: Any) -> "Checkpoint":
        """This checkpoint with `entries` added to its fingerprint (replacing those of the
        same name) and, if given, the point format `points`."""
        new = {**self.fingerprint, **entries}
        return dataclasses.replace(self, fingerprint=new,
                                   points=self.points if points is None else points)

    def full_fingerprint(self, total: int) -> dict[str, Any]:
        """The fingerprint written to the file: this one, the point kind, the number of
        points and the propwhirl version."""
        return {**self.fingerprint, "points": self.points.name, "total": total,
                "propwhirl": __version__}

    def _name(self) -> str:
        return f"partial results file {str(self.path)!r}"

    def load(self, keys: Sequence[str]) -> dict[int, Any]:
        """The finished points {index: result} of the file ({} when it does not exist);
        every entry checked: a one-line InputError naming the file and the entry otherwise."""
        path = Path(self.path)
        if not fileio.exists(path, "partial results file"):
            return {}
        name = self._name()
        try:
            size = path.stat().st_size
        except OSError as exc:
            raise v.InputError(f"cannot read {name}: {fileio.reason(exc)}") from None
        if size > MAX_PARTIAL_BYTES:
            raise v.InputError(f"{name} has {size} bytes, more than a partial results file "
                               f"holds ({MAX_PARTIAL_BYTES}): {_AGAIN}")
        data = _parse(fileio.read_text(path, "partial results file"), name)
        try:
            return self._points(data, keys, name)
        except v.InputError as exc:
            raise v.InputError(f"{name}: {exc}: {_AGAIN}") from None

    def _points(self, data: Any, keys: Sequence[str], name: str) -> dict[int, Any]:
        if not isinstance(data, dict):
            raise v.InputError(f"not a propwhirl partial results file (format {PARTIAL_FORMAT!r}): "
                               f"it is {_json_type(data)}")
        if data.get("format") == OLD_PARTIAL_FORMAT:
            raise v.InputError("written by an older propwhirl (partial results version 1, which "
                               "could hold pickled data: never read)")
        if data.get("format") != PARTIAL_FORMAT:
            raise v.InputError(f"not a propwhirl partial results file (format "
                               f"{PARTIAL_FORMAT!r}, got {v.short_repr(data.get('format'))})")
        wanted = {"format", "fingerprint", "done", "points"}
        missing = sorted(wanted - set(data))
        unknown = sorted(set(data) - wanted)
        if missing or unknown:
            raise v.InputError(f"missing keys {missing}" if missing else f"unknown keys {unknown}")
        stored = data["fingerprint"]
        if not isinstance(stored, dict):
            raise v.InputError(f"fingerprint: must be an object, got {_json_type(stored)}")
        diff = fingerprint_differences(stored, self.full_fingerprint(len(keys)))
        if diff:
            raise v.InputError(f"was written for another study: {', '.join(diff)} differ "
                               "(the file's vs this run's)")
        points = data["points"]
        if not isinstance(points, list):
            raise v.InputError(f"points: must be a list, got {_json_type(points)}")
        done = data["done"]
        if type(done) is not int or done != len(points):
            raise v.InputError(f"done = {v.short_repr(done)} is invalid: the file holds "
                               f"{len(points)} points")
        out: dict[int, Any] = {}
        for j, point in enumerate(points):
            where = f"points[{j}]"
            if isinstance(point, dict) and "pickle" in point:
                raise v.InputError(f"{where} holds a pickle (a file of an older propwhirl): "
                                   "never read")
            if not isinstance(point, dict):
                raise v.InputError(f"{where}: must be an object, got {_json_type(point)}")
            kind = "error" if "error" in point else "value"
            allowed = {"index", "key", kind} | ({"error_type"} if kind == "error" else set())
            if set(point) != allowed:
                unknown = sorted(set(point) - allowed)
                missing = sorted(allowed - set(point))
                raise v.InputError(f"{where}: unknown keys {unknown}" if unknown
                                   else f"{where}: missing keys {missing}")
            i, key = point["index"], point["key"]
            if type(i) is not int or not 0 <= i < len(keys):
                raise v.InputError(f"{where}.index = {v.short_repr(i)} is invalid: must be an "
                                   f"integer in [0, {len(keys) - 1}]")
            if key != keys[i]:
                raise v.InputError(f"point {v.short_repr(key)} at index {i} is not point {i} "
                                   f"of this study ({v.short_repr(keys[i])})")
            if i in out:
                raise v.InputError(f"{where}: point {i} is given twice")
            if kind == "error":
                message, error_type = point["error"], point["error_type"]
                if not isinstance(message, str) or not isinstance(error_type, str) \
                        or not error_type.isidentifier() or "\n" in message:
                    raise v.InputError(f"{where}: error and error_type must be a one-line "
                                       "message and an exception's name")
                check_plain(message, f"{where}.error")
                out[i] = TaskError(error_type, message)
            else:
                out[i] = self.points.decode(point["value"], f"{where}.value", key)
        return out

    def encode(self, keys: Sequence[str], i: int, result: Any) -> str:
        """The JSON text of point `i` in the file (its value by :attr:`points`)."""
        if isinstance(result, TaskError):
            entry = {"error": str(result.message), "error_type": str(result.kind)}
        else:
            try:
                entry = {"value": self.points.encode(result)}
            except v.InputError as exc:
                raise v.InputError(f"{self._name()}: the result of point {keys[i]!r} cannot be "
                                   f"kept ({exc})") from None
        return json.dumps({"index": i, "key": keys[i], **entry})

    def write(self, keys: Sequence[str], results: dict[int, Any],
              encoded: dict[int, str] | None = None) -> Path:
        """Write the finished points (atomically: the file is complete at every moment);
        `encoded`: the points' JSON texts already made by :meth:`encode` (kept by the run)."""
        lines = [encoded[i] if encoded is not None and i in encoded else self.encode(keys, i, results[i])
                 for i in sorted(results)]
        head = json.dumps({"format": PARTIAL_FORMAT, "fingerprint": self.full_fingerprint(len(keys)),
                           "done": len(results)})
        text = head[:-1] + ', "points": [\n' + ",\n".join(lines) + "\n]}\n"
        return fileio.write_text(self.path, text, what="partial results file")

    def discard(self) -> None:
        """Remove the file (after the final result is written); nothing if it is absent."""
        try:
            os.remove(self.path)
        except FileNotFoundError:
            pass
        except OSError as exc:
            raise v.InputError(f"cannot remove partial results file {str(self.path)!r}: "
                               f"{fileio.reason(exc)}") from None


def check_checkpoint(checkpoint: Any) -> None:
    """InputError unless `checkpoint` is a :class:`Checkpoint`."""
    if not isinstance(checkpoint, Checkpoint):
        raise v.InputError(f"checkpoint = {v.short_repr(checkpoint)} is invalid: must be a "
                           "propwhirl.studies.execution.Checkpoint")


def _parse(text: str, name: str) -> Any:
    """The JSON of a partial-results file, checked to be plain data of bounded depth."""
    try:
        data = json.loads(text)
    except json.JSONDecodeError as exc:
        raise v.InputError(f"{name} is not valid JSON ({exc.msg}, line {exc.lineno}): "
                           f"{_AGAIN}") from None
    except RecursionError:
        raise v.InputError(f"{name}: nested too deeply (more than {MAX_DEPTH} levels): "
                           f"{_AGAIN}") from None
    except ValueError as exc:  # an integer of too many digits
        raise v.InputError(f"{name} is not a partial results file ({' '.join(str(exc).split())}): "
                           f"{_AGAIN}") from None
    try:
        return check_plain(data, "file")
    except v.InputError as exc:
        raise v.InputError(f"{name}: {exc}: {_AGAIN}") from None
