"""Input checks shared by every model: clear errors naming parameter, value and valid range.

All raise :class:`InputError` (a ValueError) with one-line messages such as
``radius = -1.0 m is invalid: must be > 0`` or
``EI = 1e+300 N m^2 is outside the valid range [1e-3, 1e12] N m^2``.  Arrays are checked
element-wise and the message shows the first offending value.  Strict types: a number is a
real int or float (numpy scalars included), never a bool, a string, a complex number or None.
"""
from __future__ import annotations

import math
import re
from typing import Any

import numpy as np

_UNSET: Any = object()


class InputError(ValueError):
    """Bad user input: the message names the parameter, its value and the valid range.

    Errors about one field carry, besides the message, where the value sits (`path`: field
    names and indices from the object being built, e.g. ``("EI", 3)`` or
    ``("propellers", 2, "y")``), the offending `value` and the `reason` (the text after
    ``NAME = VALUE [UNIT] is``), so that a file reader can restate them with the key the
    user wrote.  A ``ValueError``.

    Parameters
    ----------
    message : str
        One line: parameter, value (with its unit) and what is valid.
    path : tuple
        Field names and indices from the object being built to the value; () when not about
        one field.
    value : object, optional
        The offending value.
    reason : str, optional
        The text after ``NAME = VALUE [UNIT] is``.

    Examples
    --------
    >>> from propwhirl import InputError, Wing
    >>> try:
    ...     Wing(semi_span=6.0, mass_per_length=20.0, EI=-2.0e5, GJ=1.0e5,
    ...          radius_of_gyration=0.25)
    ... except InputError as e:
    ...     print(e)
    ...     print(e.path, e.value)
    EI = -200000.0 N m^2 is outside the valid range [1e-3, 1e12] N m^2
    ('EI',) -200000.0
    """

    def __init__(self, message: str, *, path: tuple = (), value: Any = _UNSET,
                 reason: str | None = None):
        super().__init__(message)
        self.path = tuple(path)
        self.value = value
        self.reason = reason

    @property
    def structured(self) -> bool:
        """True when path, value and reason describe the error."""
        return bool(self.path) and self.value is not _UNSET and self.reason is not None


def short_repr(value: Any, limit: int = 60) -> str:
    """repr(value) on one line (an array's rows joined), cut to `limit` characters (a huge list
    must not flood the terminal)."""
    text = re.sub(r"\s*\n\s*", " ", repr(value))
    return text if len(text) <= limit else text[: limit - 3] + "..."


def fmt_bound(x: float) -> str:
    """A range end for messages: 0.001 → "1e-3", 1e12 → "1e12", 0.5 → "0.5", 4π → "12.5664"."""
    if x == 0 or (1e-3 < abs(x) < 1e5):
        return f"{x:.6g}"
    mant, exp = f"{x:.6e}".split("e")
    mant = mant.rstrip("0").rstrip(".")
    return f"{mant}e{int(exp)}"


def fmt_range(low: float, high: float, ends: str = "[]") -> str:
    """"[1e-3, 1e12]", "(0, 1]", ... (`ends`: the two brackets)."""
    return f"{ends[0]}{fmt_bound(low)}, {fmt_bound(high)}{ends[1]}"


def _fmt(value, unit: str) -> str:
    return f"{short_repr(value)}{' ' + unit if unit else ''}"


def fail(name: str, value: Any, reason: str, unit: str = "", path: tuple | None = None,
         ) -> InputError:
    """The InputError "NAME = VALUE UNIT is REASON", carrying path (default: (name,))."""
    return InputError(f"{name} = {_fmt(value, unit)} is {reason}",
                      path=(name,) if path is None else path, value=value, reason=reason)


def _first_bad(arr: np.ndarray, bad: np.ndarray, value: Any = _UNSET):
    """The first offending value (the caller's own object for a scalar: 3 stays an int)."""
    if not arr.ndim:
        return value if value is not _UNSET and np.ndim(value) == 0 else arr.item()
    return arr[bad].flat[0].item()


def _first_index(bad: np.ndarray) -> tuple:
    return tuple(int(i) for i in np.argwhere(bad)[0]) if bad.ndim else ()


def _plain(value) -> bool:
    """A Python float, or an int within int64 (the values numpy keeps as they are): the
    checks below take these without numpy's machinery, with the same outcome."""
    t = type(value)
    return t is float or (t is int and -(1 << 63) <= value < (1 << 63))


def real(name: str, value, unit: str = "", path: tuple | None = None) -> np.ndarray:
    """`value` as a float array of real numbers (scalar or array); anything else
    (bool, str, complex, None, dict, objects, ragged lists) is an InputError naming the type."""
    if _plain(value):                # a plain float or int: at once (a model has hundreds)
        return np.array(float(value))
    path = (name,) if path is None else path
    if isinstance(value, (bool, np.bool_, str, bytes, complex, np.complexfloating, dict)) \
            or value is None:
        raise fail(name, value, f"invalid: must be a real number, got {type(value).__name__}",
                   "", path)
    try:
        arr = np.asarray(value)
    except (TypeError, ValueError) as exc:
        raise fail(name, value, f"invalid: must be a real number, got {type(value).__name__}",
                   "", path) from exc
    if arr.dtype.kind not in "iuf":
        if isinstance(value, (list, tuple)):
            got = f"{type(value).__name__} of {', '.join(sorted({type(x).__name__ for x in value}))}"
        elif isinstance(value, np.ndarray):
            got = f"array of {value.dtype}"
        else:
            got = type(value).__name__
        raise fail(name, value, f"invalid: must be a real number, got {got}", "", path)
    with np.errstate(over="ignore"):
        return arr.astype(float)


def finite(name: str, value, unit: str = "", path: tuple | None = None) -> np.ndarray:
    """Return `value` as a float array; raise unless every element is a finite real number."""
    if _plain(value) and math.isfinite(value):
        return np.array(float(value))
    arr = real(name, value, unit, path)
    bad = ~np.isfinite(arr)
    if bad.any():
        raise fail(name, _first_bad(arr, bad, value), "invalid: must be finite", unit,
                   ((name,) if path is None else path) + _first_index(bad))
    return arr


def positive(name: str, value, unit: str = "", path: tuple | None = None) -> np.ndarray:
    """Finite and > 0."""
    arr = finite(name, value, unit, path)
    bad = arr <= 0
    if bad.any():
        raise fail(name, _first_bad(arr, bad, value), "invalid: must be > 0", unit,
                   ((name,) if path is None else path) + _first_index(bad))
    return arr


def non_negative(name: str, value, unit: str = "", path: tuple | None = None) -> np.ndarray:
    """Finite and >= 0."""
    arr = finite(name, value, unit, path)
    bad = arr < 0
    if bad.any():
        raise fail(name, _first_bad(arr, bad, value), "invalid: must be >= 0", unit,
                   ((name,) if path is None else path) + _first_index(bad))
    return arr


def in_range(name: str, value, low: float, high: float, unit: str = "",
             low_open: bool = False, high_open: bool = False,
             path: tuple | None = None) -> np.ndarray:
    """Finite and within [low, high] (ends open where asked); the message states the range."""
    if _plain(value) and math.isfinite(value) and (
            (low < value if low_open else low <= value)
            and (value < high if high_open else value <= high)):
        return np.array(float(value))
    arr = finite(name, value, unit, path)
    bad = (arr <= low if low_open else arr < low) | (arr >= high if high_open else arr > high)
    if bad.any():
        rng = fmt_range(low, high, ("(" if low_open else "[") + (")" if high_open else "]"))
        raise fail(name, _first_bad(arr, bad, value),
                   f"outside the valid range {rng}{' ' + unit if unit else ''}", unit,
                   ((name,) if path is None else path) + _first_index(bad))
    return arr


def integer_at_least(name: str, value, minimum: int) -> int:
    """An integer >= minimum."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer)) \
            or value < minimum:
        raise fail(name, value, f"invalid: must be an integer >= {minimum}")
    return int(value)


def boolean(name: str, value) -> bool:
    """Strictly a bool (Python or numpy): "no", 0 or None are not taken for False."""
    if not isinstance(value, (bool, np.bool_)):
        raise fail(name, value, f"invalid: must be True or False, got {type(value).__name__}")
    return bool(value)


def increasing(name: str, value, unit: str = "") -> np.ndarray:
    """A finite 1-D array, strictly increasing, with at least two entries."""
    arr = finite(name, value, unit)
    if arr.ndim != 1 or arr.size < 2:
        raise InputError(f"{name} must be a 1-D array of at least 2 values, got shape {arr.shape}")
    steps = np.diff(arr)
    if (steps <= 0).any():
        i = int(np.argmax(steps <= 0))
        raise InputError(
            f"{name} is invalid: must be strictly increasing, but {name}[{i + 1}] = "
            f"{_fmt(arr[i + 1].item(), unit)} follows {_fmt(arr[i].item(), unit)}"
        )
    return arr


def file_path(name: str, value: Any, what: str = "a file"):
    """`value` when it is a path: a non-empty ``str`` or an :class:`os.PathLike` of one
    (``pathlib.Path``); anything else (None, a number, bytes, a list) is an InputError naming
    `name`, what the path is of (`what`) and the type given.

    >>> file_path("path", None, "a campaign file")
    Traceback (most recent call last):
    ...
    propwhirl.validate.InputError: path = None is invalid: must be the path of a campaign file (a str or os.PathLike), got NoneType
    """
    import os

    text = value
    if isinstance(value, os.PathLike):
        try:
            text = os.fspath(value)
        except TypeError:
            text = None
    if not isinstance(text, str) or not text or "\0" in text:
        got = ("an empty string" if text == "" else "a str with a NUL character"
               if isinstance(text, str) else type(value).__name__)
        raise fail(name, value, f"invalid: must be the path of {what} (a str or os.PathLike), "
                   f"got {got}")
    return value


def shaped_array(source: str, key: str, value, shape: tuple, dtype=float,
                 unit: str = "") -> np.ndarray:
    """``value`` as a read-only copy of ``shape`` (-1: any length) and ``dtype``, finite; else
    a one-line InputError naming ``source`` (a file or model) and ``key``: never a silent cast
    of a bool, complex, date, string or object array, nor of a non-integral value to integers.

    >>> shaped_array("wing", "y", [0.0, 1.5], (-1,)).tolist()
    [0.0, 1.5]
    >>> shaped_array("wing", "chord", [1.0], (2,), unit="m")
    Traceback (most recent call last):
    ...
    propwhirl.validate.InputError: wing: chord = [1.0] is invalid: has shape (1,), must be real numbers of shape (2,) [m]
    """
    try:
        raw = None if isinstance(value, (str, bytes)) else np.asarray(value)
    except (TypeError, ValueError, OverflowError):
        raw = None
    if raw is not None and raw.dtype.kind in "bcmMUSVO":   # never cast to a number silently
        raise InputError(f"{source}: {key} has dtype {raw.dtype}, must be real numbers")
    try:
        arr = None if raw is None else np.array(value, dtype=dtype, copy=True)
    except (TypeError, ValueError, OverflowError):
        arr = None
    if arr is not None and np.dtype(dtype).kind == "i":
        if raw.dtype.kind not in "iu" or not np.array_equal(raw, arr):
            raise InputError(f"{source}: {key} has dtype {raw.dtype}, must be integers")
    if arr is None or arr.ndim != len(shape) or any(
            s not in (-1, n) for s, n in zip(shape, arr.shape)):
        got = None if arr is None else arr.shape
        want = tuple("n" if s == -1 else s for s in shape)
        raise InputError(f"{source}: {key} = {short_repr(value)} is invalid: has shape {got}, "
                         f"must be real numbers of shape {want}{f' [{unit}]' if unit else ''}")
    if arr.dtype.kind == "f" and not np.all(np.isfinite(arr)):
        i = tuple(int(x) for x in np.argwhere(~np.isfinite(arr))[0])
        raise InputError(f"{source}: {key}{list(i)} = {arr[i]} is invalid: must be finite")
    arr.flags.writeable = False
    return arr


def is_finite_number(x: Any) -> bool:
    """A real, finite int or float (no bool)."""
    return (isinstance(x, (int, float, np.integer, np.floating))
            and not isinstance(x, (bool, np.bool_)) and math.isfinite(x))
