"""Input checks shared by every model: clear errors naming parameter, value and valid range.

All raise :class:`InputError` (a ValueError) with messages such as
``radius = -1.0 m is invalid: must be > 0``.  Arrays are checked element-wise and the message
shows the first offending value.
"""
from __future__ import annotations

import numpy as np


class InputError(ValueError):
    """Bad user input: the message names the parameter, its value and the valid range."""


def _fmt(value, unit: str) -> str:
    return f"{value!r}{' ' + unit if unit else ''}"


def _first_bad(arr: np.ndarray, bad: np.ndarray):
    return arr[bad].flat[0].item() if arr.ndim else arr.item()


def finite(name: str, value, unit: str = "") -> np.ndarray:
    """Return `value` as a float array; raise unless every element is finite."""
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError) as exc:
        raise InputError(f"{name} = {value!r} is invalid: must be a real number") from exc
    bad = ~np.isfinite(arr)
    if bad.any():
        raise InputError(f"{name} = {_fmt(_first_bad(arr, bad), unit)} is invalid: must be finite")
    return arr


def positive(name: str, value, unit: str = "") -> np.ndarray:
    """Finite and > 0."""
    arr = finite(name, value, unit)
    bad = arr <= 0
    if bad.any():
        raise InputError(f"{name} = {_fmt(_first_bad(arr, bad), unit)} is invalid: must be > 0")
    return arr


def non_negative(name: str, value, unit: str = "") -> np.ndarray:
    """Finite and >= 0."""
    arr = finite(name, value, unit)
    bad = arr < 0
    if bad.any():
        raise InputError(f"{name} = {_fmt(_first_bad(arr, bad), unit)} is invalid: must be >= 0")
    return arr


def in_range(name: str, value, low: float, high: float, unit: str = "",
             low_open: bool = False, high_open: bool = False) -> np.ndarray:
    """Finite and within [low, high] (ends open where asked)."""
    arr = finite(name, value, unit)
    bad = (arr <= low if low_open else arr < low) | (arr >= high if high_open else arr > high)
    if bad.any():
        rng = f"{'(' if low_open else '['}{low}, {high}{')' if high_open else ']'}"
        raise InputError(
            f"{name} = {_fmt(_first_bad(arr, bad), unit)} is invalid: must be in {rng}"
        )
    return arr


def integer_at_least(name: str, value, minimum: int) -> int:
    """An integer >= minimum."""
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < minimum:
        raise InputError(f"{name} = {value!r} is invalid: must be an integer >= {minimum}")
    return int(value)


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
