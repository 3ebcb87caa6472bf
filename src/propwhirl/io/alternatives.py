"""Model-file keys that stand for other fields: the ISA altitude of a ``[flight]`` table.

A ``[flight]`` table gives the air either by ``density_kg_per_m3`` and
``speed_of_sound_m_per_s`` or by one altitude, ``altitude_m`` or ``altitude_ft``, from which
the reader takes both from the ICAO standard atmosphere
(:meth:`propwhirl.model.flight.FlightCondition.from_altitude`).  Giving both altitudes, or an
altitude together with a density or a speed of sound, is an error naming the keys.  The writer
writes the density and speed of sound (a saved file states the air it was analysed in).
:mod:`propwhirl.io.schema` adds these keys to the table's allowed keys and documentation,
:mod:`propwhirl.io.model_files` reads them with :func:`read`.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Callable

from propwhirl import validate as v
from propwhirl.model import atmosphere
from propwhirl.model.fields import Range
from propwhirl.model.flight import FlightCondition


@dataclass(frozen=True)
class Key:
    """One alternative key: its unit, its meaning and its valid range."""

    key: str
    unit: str
    doc: str
    range: Range

    @property
    def what(self) -> str:
        return f"{self.doc}; {self.unit}; valid range {self.range} {self.unit}"


@dataclass(frozen=True)
class Alternative:
    """Keys of which a table may give one instead of the fields `replaces`; `build(key, value)`
    returns the values of those fields."""

    keys: tuple[Key, ...]
    replaces: tuple[str, ...]
    build: Callable[[str, float], dict[str, Any]]

    def key_names(self) -> tuple[str, ...]:
        return tuple(k.key for k in self.keys)


def _isa(key: str, value: float) -> dict[str, Any]:
    fc = FlightCondition.from_altitude(**{key: value})
    return {"density": fc.density, "speed_of_sound": fc.speed_of_sound}


_ISA_DOC = ("ISA geopotential (pressure) altitude: density and speed of sound from the ICAO "
            "standard atmosphere, instead of density_kg_per_m3 and speed_of_sound_m_per_s")

#: The alternatives of each schema class.
ALTERNATIVES: dict[type, Alternative] = {
    FlightCondition: Alternative(
        keys=(Key("altitude_m", "m", _ISA_DOC,
                  Range(atmosphere.MIN_ALTITUDE, atmosphere.MAX_ALTITUDE)),
              Key("altitude_ft", "ft", "the ISA altitude in feet (1 ft = 0.3048 m), instead of "
                  "altitude_m", Range(atmosphere.MIN_ALTITUDE_FT, atmosphere.MAX_ALTITUDE_FT))),
        replaces=("density", "speed_of_sound"),
        build=_isa),
}


def keys(cls: type) -> tuple[str, ...]:
    """The alternative keys a table of `cls` may hold (none for most classes)."""
    alt = ALTERNATIVES.get(cls)
    return alt.key_names() if alt else ()


def read(cls: type, table: Any, replaced_keys: dict[str, str]) -> tuple[dict[str, Any], set[str]]:
    """(field values, names of the fields they replace) from the alternative keys of `table`
    (a :class:`propwhirl.io.model_files.Table`); ({}, set()) when it gives none.

    `replaced_keys` maps the replaced fields to their file keys (for the messages).  Errors
    are InputErrors naming the table and the keys."""
    alt = ALTERNATIVES.get(cls)
    given = [k for k in (alt.keys if alt else ()) if table.has(k.key)]
    if not given:
        return {}, set()
    where = f"[{table.where}]" if table.where else "the top level"
    if len(given) > 1:
        raise v.InputError(f"{where}: give one of {' or '.join(k.key for k in given)}, not both")
    key = given[0]
    clash = [replaced_keys[n] for n in alt.replaces if table.has(replaced_keys[n])]
    if clash:
        raise v.InputError(
            f"{where}: {key.key} gives {' and '.join(replaced_keys[n] for n in alt.replaces)} "
            f"(ISA); give either {key.key} or {', '.join(clash)}, not both")
    x = table.number(key.key, key.what)
    if not bool(key.range.contains(x)):
        prefix = f"[{table.where}] " if table.where else ""
        raise v.InputError(f"{prefix}{key.key} = {v.short_repr(x)} is outside the valid range "
                           f"{key.range} {key.unit} ({key.doc})")
    return alt.build(key.key, x), set(alt.replaces)
