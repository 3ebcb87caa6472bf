"""Model-file format versions: which this propwhirl writes and reads, and what an older
version's file means where it omits a key the current version requires.

Raise :data:`FORMAT_VERSION` whenever a file of the previous version would be read differently
(a key made required, a meaning changed), and record in :data:`OLD_DEFAULTS` the values the
previous version gave the keys it let a file omit.  :mod:`propwhirl.io.model_files` reads a
file with a :class:`Reading`: the version the file states, and the values it assumed, named
in one note; :mod:`propwhirl.io.schema` documents the versions (docs/model-file.md).
"""
from __future__ import annotations

import contextvars
import json
from dataclasses import dataclass, field
from typing import Any

from propwhirl import validate as v
from propwhirl.model.flight import FlightCondition
from propwhirl.model.propellers.propeller import Propeller
from propwhirl.model.propellers.propeller_aero import PropellerGeometry
from propwhirl.model.structure.wing import Wing

#: The format version this propwhirl writes.
FORMAT_VERSION = 2
#: Every format version this propwhirl reads.
FORMAT_VERSIONS: tuple[int, ...] = (1, 2)
#: The version of a file without ``format_version`` (version 1 documented it as the default).
UNSTATED_VERSION = 1

#: What a format-1 file's omitted keys meant: (class, field) → the value the version-1 reader
#: gave the field (the dataclass defaults and reader of that time, git 874de5b^1).  Version 2
#: requires these keys (issue 9: no silent default for a value of the aircraft; the blade
#: geometry only without [derivatives], the blade angles only for fixed pitch).
VERSION_1_DEFAULTS: dict[tuple[type, str], Any] = {
    (Wing, "elastic_axis"): 0.5,
    (Wing, "centre_of_gravity"): 0.5,
    (FlightCondition, "speed_of_sound"): 330.8027446243564,  # ISA at 8000 ft
    (Propeller, "pivot_pitch"): 0.0,
    (Propeller, "pivot_yaw"): 0.0,
    (Propeller, "n_blades"): 3,
    (Propeller, "hub_radius"): 0.0,
    (Propeller, "blade_chord"): 0.1,
    (Propeller, "beta_075_deg"): 35.0,
    (Propeller, "zero_lift_angle_deg"): -3.0,
    (Propeller, "rotation"): 1,
    (PropellerGeometry, "hub_ratio"): 0.0,
}
#: For each older version: the values it gave keys that the next version requires.
OLD_DEFAULTS: dict[int, dict[tuple[type, str], Any]] = {1: VERSION_1_DEFAULTS}
#: The table holding a class's keys, for the documentation of the old defaults.
TABLE_OF: dict[type, str] = {Wing: "[wing]", FlightCondition: "[flight]",
                             Propeller: "[propellers.KEY]",
                             PropellerGeometry: '[propellers.KEY.derivatives] ("houbolt-reed")'}


def old_defaults(version: int) -> dict[tuple[type, str], Any]:
    """The values a file of format `version` takes for omitted keys the current version
    requires ({} for the current version): its own version's, else the next version's, ..."""
    out: dict[tuple[type, str], Any] = {}
    for later in range(FORMAT_VERSION - 1, version - 1, -1):
        out.update(OLD_DEFAULTS.get(later, {}))
    return out


def text(value: Any) -> str:
    """A value as TOML writes it (0.5, 1, "x")."""
    return json.dumps(value) if isinstance(value, str) else repr(value)


@dataclass
class Reading:
    """The format version of the file being read and the values assumed for the keys it
    omits (table, key, value), in reading order."""

    version: int = FORMAT_VERSION
    stated: bool = True  # the file gives format_version
    assumed: list[tuple[str, str, Any]] = field(default_factory=list)

    def read_version(self, top: Any) -> None:
        """The version of the file whose top-level table is `top` (a model_files.Table);
        a one-line InputError for a version that is not an integer, unknown or newer."""
        self.stated = top.has("format_version")
        self.version = top.integer("format_version") if self.stated else UNSTATED_VERSION
        versions = ", ".join(map(str, FORMAT_VERSIONS))
        if self.version > FORMAT_VERSION:
            raise v.InputError(f"format_version = {self.version} is newer than this propwhirl "
                               f"reads (versions {versions}): update propwhirl to read it")
        if self.version not in FORMAT_VERSIONS:
            raise top.bad("format_version", f"one of {versions}")

    def default(self, cls: type, name: str, where: str, key: str, missing: Any) -> Any:
        """The value this file's version gives field `name` of `cls` (key `key` of table
        `where`), which the file omits where the current version requires it; recorded for
        the note.  `missing` when the version gives none (the key is required)."""
        old = old_defaults(self.version)
        if (cls, name) not in old:
            return missing
        self.assumed.append((where, key, old[(cls, name)]))
        return old[(cls, name)]

    def note(self, source: str) -> str | None:
        """One line naming every assumed value; None when none was assumed."""
        if not self.assumed:
            return None
        tables: dict[str, list[str]] = {}
        for where, key, value in self.assumed:
            tables.setdefault(where, []).append(f"{key} = {text(value)}")
        order = sorted(tables, key=lambda w: w.startswith("propellers"))  # the file's layout
        values = "; ".join(f"[{w}] {', '.join(tables[w])}" if w else ", ".join(tables[w])
                           for w in order)
        head = (f"format version {self.version}" if self.stated else
                f"no format_version: read as format version {self.version}")
        return (f"{source}: {head}: assumed the values version {self.version} gave omitted keys: "
                f"{values} (`propwhirl upgrade-model OLD NEW` writes a version-{FORMAT_VERSION} "
                "file stating them)")


#: The reading of the file being read (set by :func:`propwhirl.io.model_files.loads`).
CURRENT: contextvars.ContextVar[Reading] = contextvars.ContextVar("CURRENT")


def current() -> Reading:
    """The reading of the file being read; a reading of the current version outside
    :func:`~propwhirl.io.model_files.loads` (nothing is then assumed)."""
    return CURRENT.get(_CURRENT_VERSION)


_CURRENT_VERSION = Reading()
