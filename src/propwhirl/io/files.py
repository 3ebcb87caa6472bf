"""Model files (TOML) and result tables (CSV).

Model files
-----------
:func:`save_model` / :func:`dumps` write a :class:`~propwhirl.model.systems.PropellerWing` (wing, flight
condition, installed propellers, switches), an :class:`~propwhirl.model.systems.IsolatedPropeller` or a
bare :class:`~propwhirl.model.propeller.Propeller` as TOML; :func:`load_model` / :func:`loads` read
them back (with the standard library's ``tomllib``).  The TOML is written by hand here — the
standard library has no TOML writer and the package adds no dependency for one.

SI units throughout; the unit of every quantity is the suffix of its key (``semi_span_m``,
``EI_N_m2``, ``f_theta_hz``, ...; the table :data:`UNIT_SUFFIXES` is repeated as a comment at
the top of every file).  Chordwise wing positions are fractions of the local chord from the
leading edge (suffix ``_chord``); positions on the propeller shaft are from the wing mid-chord,
positive aft (as in :class:`~propwhirl.model.propeller.Propeller`).  Floats are written with
``repr`` so a save → load round trip reproduces every number exactly.

Layout of a file::

    format = "propwhirl-model"
    format_version = 1
    type = "propeller-wing"          # or "isolated-propeller", "propeller"
    name = "..."
    propeller = "p1"                 # isolated-propeller / propeller files only
    [switches]                       # wing_aero, propeller_aero, rotating
    [flight]                         # density_kg_per_m3, speed_of_sound_m_per_s,
                                     # speed_range_m_per_s = [first, last, step]
    [wing]                           # Wing fields
    [[installations]]                # one per installed propeller: propeller key, y_m, mount,
                                     # aero (this propeller's aerodynamics on/off)
    [propellers.p1]                  # Propeller fields; identical propellers share one key
    [propellers.p1.inertia]          # optional measured inertia about the pivots
    [propellers.p1.aero_settings]    # Houbolt–Reed switches (chapter 4)
    [propellers.p1.derivatives]      # optional: source = "measured" with a [..values] table of
                                     # the 16 derivatives, or "houbolt-reed" with its own geometry

What cannot be saved raises :class:`~propwhirl.validate.InputError` naming the field: spanwise
properties or chords given as Python functions (tabulate them per element instead), a blade
chord given as a function that is not a :class:`~propwhirl.model.propeller_aero.Distribution`, and derivative
sources other than :class:`~propwhirl.model.propeller.MeasuredDerivatives` and
:class:`~propwhirl.model.propeller_aero.HouboltReedSource`.  Reading is strict: an unknown field, a missing
required field or a value of the wrong type is an InputError naming the field.

Result tables
-------------
:func:`write_vgf_csv` / :func:`read_vgf_csv`: the tidy V-g-f table of a sweep
(:meth:`propwhirl.engine.core.Sweep.table`) as CSV with unit-suffixed column names.
(The whole analysis is saved as JSON by :meth:`propwhirl.analysis.stability.ModelAnalysis.save`.)
"""
from __future__ import annotations

import contextlib
import csv
import dataclasses
import json
import math
import tomllib
from pathlib import Path
from typing import Any, Iterable, Iterator, Mapping

import numpy as np

from propwhirl import validate as v
from propwhirl.model.propeller_aero import DERIVATIVE_NAMES, AeroSettings, Distribution, HouboltReedSource, PropellerGeometry
from propwhirl.model.systems import FlightCondition, Installation, IsolatedPropeller, PropellerWing
from propwhirl.model.propeller import MeasuredDerivatives, PointMass, Propeller
from propwhirl.model.wing import Wing

FORMAT = "propwhirl-model"
FORMAT_VERSION = 1

#: Unit suffixes of the keys (written as a comment at the top of every model file).
UNIT_SUFFIXES: tuple[tuple[str, str], ...] = (
    ("_m", "metre"), ("_kg", "kilogram"), ("_kg_per_m", "kg/m"), ("_kg_m", "kg m"),
    ("_kg_m2", "kg m^2"), ("_kg_per_m3", "kg/m^3"), ("_N_m2", "N m^2"),
    ("_N_m_per_rad", "N m/rad"), ("_m_per_s", "m/s"), ("_hz", "hertz"), ("_per_rad", "1/rad"),
    ("_per_s", "1/s"), ("_s", "second"), ("_deg", "degree"), ("rpm", "rev/min"),
    ("_chord", "fraction of the local chord from the leading edge"),
    ("(none)", "dimensionless"),
)

_HEADER = [
    "propwhirl model file: read it with `propwhirl analyse FILE` or propwhirl.io.load_model.",
    "SI units; the unit of each quantity is the suffix of its key:",
    *(f"  {s:12s} {u}" for s, u in UNIT_SUFFIXES),
    "Positions on a propeller shaft (x_m, pivot_*_m) are from the wing mid-chord, positive aft;",
    "wing h is positive down, twist alpha positive nose up (thesis conventions).",
]


# =============================================================================== TOML writing
def _key(k: str) -> str:
    """A TOML key: bare when it can be, quoted otherwise."""
    if k and all(c.isascii() and (c.isalnum() or c in "_-") for c in k):
        return k
    return _string(k)


def _string(s: str) -> str:
    """A TOML basic string (JSON escapes are valid TOML escapes; DEL must be escaped too)."""
    return json.dumps(s, ensure_ascii=False).replace("\x7f", "\\u007F")


def _literal(x: Any, field: str) -> str:
    """TOML literal of a bool, int, float, string, sequence or mapping."""
    if isinstance(x, (bool, np.bool_)):
        return "true" if x else "false"
    if isinstance(x, (int, np.integer)):
        return str(int(x))
    if isinstance(x, (float, np.floating)):
        f = float(x)
        if not math.isfinite(f):
            raise v.InputError(f"{field} = {f!r} cannot be saved: must be finite")
        return repr(f)
    if isinstance(x, str):
        return _string(x)
    if isinstance(x, np.ndarray):
        x = x.tolist()
    if isinstance(x, Mapping):
        return "{ " + ", ".join(f"{_key(k)} = {_literal(val, f'{field}.{k}')}" for k, val in x.items()) + " }"
    if isinstance(x, (list, tuple)):
        return "[" + ", ".join(_literal(item, f"{field}[{i}]") for i, item in enumerate(x)) + "]"
    raise v.InputError(f"{field} = {x!r} cannot be saved to TOML: not a number, string or table")


Row = tuple[str, Any, str]  # key, value, comment ("" for none)


class _Writer:
    """Collects TOML lines: top-level keys first, then tables (TOML requires that order)."""

    def __init__(self) -> None:
        self.lines: list[str] = ["# " + line if line else "#" for line in _HEADER]
        self.lines.append("")

    def rows(self, rows: Iterable[Row], where: str) -> None:
        for key, value, comment in rows:
            if value is None:
                continue
            text = f"{_key(key)} = {_literal(value, f'{where}.{key}' if where else key)}"
            self.lines.append(text + (f"  # {comment}" if comment else ""))

    def table(self, header: str, rows: Iterable[Row], comment: str = "", array: bool = False) -> None:
        self.lines.append("")
        if comment:
            self.lines.append(f"# {comment}")
        self.lines.append(f"[[{header}]]" if array else f"[{header}]")
        self.rows(rows, header)

    def text(self) -> str:
        return "\n".join(self.lines) + "\n"


def _float(x) -> float:
    return float(x)


def _spanwise(name: str, value, where: str):
    """A spanwise Wing property as a number or a per-element list; functions cannot be saved."""
    if value is None:
        return None
    if callable(value):
        raise v.InputError(
            f"{where}.{name} is a function of y and cannot be saved to TOML: give a number or one "
            "value per element (evaluate the function at wing.element_y)"
        )
    arr = np.asarray(value, dtype=float)
    return float(arr) if arr.ndim == 0 else arr.tolist()


def _wing_rows(w: Wing) -> list[Row]:
    where = "wing"
    if w.chord is not None:
        raise v.InputError(
            "wing.chord is a function of y and cannot be saved to TOML: use root_chord/tip_chord "
            "(linear taper)"
        )
    if callable(w.lift_slope) and not isinstance(w.lift_slope, str):
        raise v.InputError(
            "wing.lift_slope is a function of y and cannot be saved to TOML: use a number or "
            "\"elliptic\""
        )
    slope = w.lift_slope if isinstance(w.lift_slope, str) else _float(w.lift_slope)
    mu, lam = w.rayleigh
    return [
        ("name", w.name, ""),
        ("semi_span_m", _float(w.semi_span), "root to tip"),
        ("root_chord_m", _float(w.root_chord), ""),
        ("tip_chord_m", None if w.tip_chord is None else _float(w.tip_chord), "linear taper"),
        ("mass_per_length_kg_per_m", _spanwise("mass_per_length", w.mass_per_length, where),
         "number or one value per element"),
        ("polar_inertia_kg_m", _spanwise("polar_inertia", w.polar_inertia, where),
         "about the elastic axis"),
        ("radius_of_gyration_chord", _spanwise("radius_of_gyration", w.radius_of_gyration, where),
         "about the centre of gravity"),
        ("elastic_axis_chord", _spanwise("elastic_axis", w.elastic_axis, where), ""),
        ("centre_of_gravity_chord", _spanwise("centre_of_gravity", w.centre_of_gravity, where), ""),
        ("EI_N_m2", _spanwise("EI", w.EI, where), "bending rigidity"),
        ("GJ_N_m2", _spanwise("GJ", w.GJ, where), "torsional rigidity"),
        ("lift_slope_per_rad", slope, "a number or \"elliptic\" (eq. 7.81)"),
        ("aerodynamic_centre_chord", _spanwise("aerodynamic_centre", w.aerodynamic_centre, where), ""),
        ("n_elements", int(w.n_elements), "equal beam elements"),
        ("aero_model", w.aero_model, "\"leishman-nguyen\" or \"wagner\""),
        ("rayleigh_mu_per_s", _float(mu), "Rayleigh damping C = mu M + lambda K (eq. 7.22)"),
        ("rayleigh_lambda_s", _float(lam), ""),
    ]


def _mass(p: PointMass) -> dict[str, float]:
    return {"mass_kg": _float(p.mass), "x_m": _float(p.x)}


def _distribution(d: Distribution, value_key: str) -> dict[str, Any]:
    return {"name": d.name, "eta": list(d.eta), value_key: list(d.values)}


def _chord_value(chord, where: str):
    """Blade chord: a number, a constant Distribution as a number, or a table (None: table)."""
    if isinstance(chord, Distribution):
        if chord.eta == (0.0, 1.0) and chord.values[0] == chord.values[1]:
            return chord.values[0], None
        return None, _distribution(chord, "chord_m")
    if callable(chord):
        raise v.InputError(
            f"{where} is a function and cannot be saved to TOML: give a number or a "
            "propwhirl.model.propeller_aero.Distribution (tabulated chord)"
        )
    return _float(chord), None


def _settings_rows(s: AeroSettings) -> list[Row]:
    return [
        ("wake", bool(s.wake), "Theodorsen lift lag F + iG (section 4.1.4)"),
        ("compressibility", bool(s.compressibility), "Prandtl-Glauert with Rodden-Rose cut-off"),
        ("aspect_ratio_correction", bool(s.aspect_ratio_correction), "A'/(A'+2) (eq. 4.19)"),
        ("cnq_sign", s.cnq_sign, "\"thesis\" or \"rodden_rose\""),
        ("method", s.method, "\"houbolt_reed\" or \"bennett_bland\""),
        ("cutoff_lift_slope_per_rad", _float(s.cutoff_lift_slope), "a_m of eq. 4.23-4.24"),
        ("quadrature_order", int(s.quadrature_order), "Gauss-Legendre points per panel"),
    ]


def _propeller_tables(key: str, p: Propeller, w: _Writer) -> None:
    where = f"propellers.{key}"
    chord, chord_table = _chord_value(p.blade_chord, f"{where}.blade_chord")
    rows: list[Row] = [
        ("name", p.name, ""),
        ("radius_m", _float(p.radius), "rotor radius R"),
        ("hub_radius_m", _float(p.hub_radius), "r0"),
        ("n_blades", int(p.n_blades), ""),
        ("blade_chord_m", chord, "constant chord (Houbolt-Reed input)"),
        ("rotor", _mass(p.rotor), "rotor point mass; its x is the propeller plane"),
        ("masses", [_mass(m) for m in p.masses], "further point masses on the shaft"),
        ("pivot_pitch_m", _float(p.pivot_pitch), "l_theta"),
        ("pivot_yaw_m", _float(p.pivot_yaw), "l_psi"),
        ("f_theta_hz", None if p.f_theta is None else _float(p.f_theta), "uncoupled pitch frequency"),
        ("K_theta_N_m_per_rad", None if p.K_theta is None else _float(p.K_theta), "pitch stiffness"),
        ("f_psi_hz", None if p.f_psi is None else _float(p.f_psi), "uncoupled yaw frequency"),
        ("K_psi_N_m_per_rad", None if p.K_psi is None else _float(p.K_psi), "yaw stiffness"),
        ("damping", p.damping, "\"g\" (structural, zeta = g/2) or \"zeta\" (viscous ratio)"),
        ("damping_theta", _float(p.damping_theta), ""),
        ("damping_psi", _float(p.damping_psi), ""),
        ("spin_inertia_kg_m2", None if p.spin_inertia is None else _float(p.spin_inertia),
         "I_Omega (omitted: M_r R^2/3, eq. 9.2)"),
        ("operation", p.operation, "\"fixed-pitch\" or \"constant-speed\""),
        ("beta_075_deg", _float(p.beta_075_deg), "blade angle at 0.75 R"),
        ("zero_lift_angle_deg", _float(p.zero_lift_angle_deg), ""),
        ("advance_rule", p.advance_rule, "\"thesis_eq_9_1\" or \"blade_element\""),
        ("rpm", None if p.rpm is None else _float(p.rpm), "constant-speed operation"),
        ("rotation", int(p.rotation), "+1 counter-clockwise seen from the front"),
    ]
    w.table(where, rows, f"propeller {key!r}")
    if chord_table is not None:
        w.table(f"{where}.blade_chord", [(k, val, "") for k, val in chord_table.items()],
                "tabulated blade chord c(eta), eta = r/R")
    if p.inertia is not None:
        units = {"M_P": "kg", "S_theta_P": "kg_m", "I_theta_P": "kg_m2", "I_psi_P": "kg_m2"}
        w.table(f"{where}.inertia",
                [(f"{k}_{units[k]}", _float(val), "") for k, val in p.inertia.items()],
                "measured inertia about the pivots (overrides the point masses)")
    w.table(f"{where}.aero_settings", _settings_rows(p.aero_settings), "Houbolt-Reed switches")
    _derivative_tables(f"{where}.derivatives", p.derivatives, w)


def _derivative_tables(where: str, d, w: _Writer) -> None:
    if d is None:
        return
    if isinstance(d, MeasuredDerivatives):
        w.table(where, [("source", "measured", "constant in V; missing derivatives are zero")],
                "user-supplied aerodynamic derivatives (eq. 4.25)")
        w.table(f"{where}.values", [(k, _float(d.values[k]), "") for k in DERIVATIVE_NAMES
                                    if k in d.values])
        return
    if isinstance(d, HouboltReedSource):
        g = d.geometry
        chord, chord_table = _chord_value(g.chord, f"{where}.chord")
        w.table(where, [
            ("source", "houbolt-reed", "Houbolt-Reed with the geometry below"),
            ("n_blades", int(g.n_blades), ""),
            ("radius_m", _float(g.radius), ""),
            ("hub_ratio", _float(g.hub_ratio), "r0/R"),
            ("chord_m", chord, ""),
            ("reference_chord_m", None if g.reference_chord is None else _float(g.reference_chord), ""),
            ("aspect_ratio", None if g.aspect_ratio is None else _float(g.aspect_ratio), "eq. 4.20"),
        ], "aerodynamic derivative source")
        if chord_table is not None:
            w.table(f"{where}.chord", [(k, val, "") for k, val in chord_table.items()])
        if g.lift_slope is not None:
            w.table(f"{where}.lift_slope",
                    [(k, val, "") for k, val in _distribution(g.lift_slope, "lift_slope_per_rad").items()])
        w.table(f"{where}.settings", _settings_rows(d.settings))
        return
    raise v.InputError(
        f"{where} = {d!r} cannot be saved to TOML: only MeasuredDerivatives and "
        "HouboltReedSource (or None, Houbolt-Reed from the propeller) can"
    )


def _propeller_keys(props: Iterable[Propeller]) -> tuple[dict[int, str], list[tuple[str, Propeller]]]:
    """Keys p1, p2, ... for distinct propellers (identical TOML text → one key)."""
    by_text: dict[str, str] = {}
    keys: dict[int, str] = {}
    order: list[tuple[str, Propeller]] = []
    for p in props:
        if id(p) in keys:
            continue
        probe = _Writer()
        _propeller_tables("x", p, probe)
        text = probe.text()
        if text not in by_text:
            by_text[text] = f"p{len(by_text) + 1}"
            order.append((by_text[text], p))
        keys[id(p)] = by_text[text]
    return keys, order


def dumps(model: PropellerWing | IsolatedPropeller | Propeller) -> str:
    """The TOML text of a model (see the module docstring for the layout)."""
    w = _Writer()
    head: list[Row] = [("format", FORMAT, ""), ("format_version", FORMAT_VERSION, "")]
    if isinstance(model, PropellerWing):
        keys, order = _propeller_keys(inst.propeller for inst in model.propellers)
        w.rows(head + [("type", "propeller-wing", ""), ("name", model.name, "")], "")
        w.table("switches", [
            ("wing_aero", bool(model.wing_aero), "strip aerodynamics of the wing"),
            ("propeller_aero", bool(model.propeller_aero), "propeller aerodynamic derivatives"),
            ("rotating", bool(model.rotating), "propellers spinning (gyroscopic terms)"),
        ])
        _flight(model.flight, w)
        w.table("wing", _wing_rows(model.wing))
        for inst in model.propellers:
            w.table("installations", [
                ("propeller", keys[id(inst.propeller)], "key of a [propellers.*] table"),
                ("y_m", _float(inst.y), "spanwise position (must be a node)"),
                ("mount", inst.mount, "\"flexible\" or \"rigid\""),
                ("aero", bool(inst.aero), "this propeller's aerodynamic loads"),
            ], array=True)
    elif isinstance(model, IsolatedPropeller):
        keys, order = _propeller_keys([model.propeller])
        w.rows(head + [("type", "isolated-propeller", ""), ("name", model.name, ""),
                       ("propeller", keys[id(model.propeller)], "key of a [propellers.*] table")], "")
        w.table("switches", [
            ("propeller_aero", bool(model.propeller_aero), "propeller aerodynamic derivatives"),
            ("rotating", bool(model.rotating), "propeller spinning (gyroscopic terms)"),
        ])
        _flight(model.flight, w)
    elif isinstance(model, Propeller):
        keys, order = _propeller_keys([model])
        w.rows(head + [("type", "propeller", ""), ("name", model.name, ""),
                       ("propeller", keys[id(model)], "key of a [propellers.*] table")], "")
    else:
        raise v.InputError(
            f"cannot save a {type(model).__name__}: model files hold a PropellerWing, an "
            "IsolatedPropeller or a Propeller"
        )
    for key, p in order:
        _propeller_tables(key, p, w)
    return w.text()


def _flight(f: FlightCondition, w: _Writer) -> None:
    w.table("flight", [("density_kg_per_m3", _float(f.density), "air density"),
                       ("speed_of_sound_m_per_s", _float(f.speed_of_sound), ""),
                       ("speed_range_m_per_s", [_float(x) for x in f.speed_range],
                        "[first, last, step]: initial grid of the V-g-f sweep")])


def save_model(model: PropellerWing | IsolatedPropeller | Propeller, path: str | Path) -> Path:
    """Write `model` as a TOML model file; returns the path."""
    text = dumps(model)  # fails before touching the file if the model cannot be saved
    path = Path(path)
    try:
        path.write_text(text, encoding="utf-8")
    except OSError as exc:
        raise v.InputError(f"cannot write model file {str(path)!r}: {exc.strerror or exc}") from exc
    return path


# =============================================================================== TOML reading
_MISSING = object()


class _Table:
    """A TOML table being read: known keys only, typed accessors, errors name the field."""

    def __init__(self, data: Any, where: str, allowed: Iterable[str]):
        if not isinstance(data, dict):
            raise v.InputError(f"{where} = {data!r} is invalid: must be a table")
        self.data, self.where = data, where
        allowed = tuple(allowed)
        unknown = [k for k in data if k not in allowed]
        if unknown:
            raise v.InputError(
                f"unknown field {self._name(unknown[0])!r}: valid fields of "
                f"[{where or 'top level'}] are {', '.join(allowed)}"
            )

    def _name(self, key: str) -> str:
        return f"{self.where}.{key}" if self.where else key

    def has(self, key: str) -> bool:
        return key in self.data

    def raw(self, key: str, default: Any = _MISSING) -> Any:
        if key in self.data:
            return self.data[key]
        if default is _MISSING:
            raise v.InputError(f"missing field {self._name(key)!r}")
        return default

    def number(self, key: str, default: Any = _MISSING) -> Any:
        x = self.raw(key, default)
        if x is default and key not in self.data:
            return x
        if isinstance(x, bool) or not isinstance(x, (int, float)):
            raise v.InputError(f"{self._name(key)} = {x!r} is invalid: must be a number")
        return float(x)

    def numbers(self, key: str, default: Any = _MISSING) -> Any:
        """A number or a list of numbers (per-element property)."""
        x = self.raw(key, default)
        if key not in self.data:
            return x
        if isinstance(x, list):
            if not x or any(isinstance(i, bool) or not isinstance(i, (int, float)) for i in x):
                raise v.InputError(
                    f"{self._name(key)} = {x!r} is invalid: must be a number or a non-empty list "
                    "of numbers")
            return np.asarray(x, dtype=float)
        return self.number(key)

    def integer(self, key: str, default: Any = _MISSING) -> Any:
        x = self.raw(key, default)
        if key not in self.data:
            return x
        if isinstance(x, bool) or not isinstance(x, int):
            raise v.InputError(f"{self._name(key)} = {x!r} is invalid: must be an integer")
        return x

    def string(self, key: str, default: Any = _MISSING, choices: tuple[str, ...] | None = None) -> Any:
        x = self.raw(key, default)
        if key not in self.data:
            return x
        if not isinstance(x, str):
            raise v.InputError(f"{self._name(key)} = {x!r} is invalid: must be a string")
        if choices is not None and x not in choices:
            raise v.InputError(
                f"{self._name(key)} = {x!r} is invalid: must be one of {', '.join(choices)}")
        return x

    def boolean(self, key: str, default: Any = _MISSING) -> Any:
        x = self.raw(key, default)
        if key not in self.data:
            return x
        if not isinstance(x, bool):
            raise v.InputError(f"{self._name(key)} = {x!r} is invalid: must be true or false")
        return x

    def sub(self, key: str, allowed: Iterable[str], required: bool = False) -> "_Table | None":
        if key not in self.data:
            if required:
                raise v.InputError(f"missing table [{self._name(key)}]")
            return None
        return _Table(self.data[key], self._name(key), allowed)


@contextlib.contextmanager
def _context(where: str) -> Iterator[None]:
    """Prefix errors raised while building an object with the table it comes from."""
    try:
        yield
    except v.InputError as exc:
        msg = str(exc)
        raise v.InputError(msg if msg.startswith("in [") else f"in [{where}]: {msg}") from exc


_WING_KEYS = ("name", "semi_span_m", "root_chord_m", "tip_chord_m", "mass_per_length_kg_per_m",
              "polar_inertia_kg_m", "radius_of_gyration_chord", "elastic_axis_chord",
              "centre_of_gravity_chord", "EI_N_m2", "GJ_N_m2", "lift_slope_per_rad",
              "aerodynamic_centre_chord", "n_elements", "aero_model", "rayleigh_mu_per_s",
              "rayleigh_lambda_s")
_PROPELLER_KEYS = ("name", "radius_m", "hub_radius_m", "n_blades", "blade_chord_m", "blade_chord",
                   "rotor", "masses", "pivot_pitch_m", "pivot_yaw_m", "f_theta_hz",
                   "K_theta_N_m_per_rad", "f_psi_hz", "K_psi_N_m_per_rad", "damping",
                   "damping_theta", "damping_psi", "spin_inertia_kg_m2", "operation",
                   "beta_075_deg", "zero_lift_angle_deg", "advance_rule", "rpm", "rotation",
                   "inertia", "aero_settings", "derivatives")
_SETTINGS_KEYS = ("wake", "compressibility", "aspect_ratio_correction", "cnq_sign", "method",
                  "cutoff_lift_slope_per_rad", "quadrature_order")
_INERTIA_KEYS = {"M_P_kg": "M_P", "S_theta_P_kg_m": "S_theta_P", "I_theta_P_kg_m2": "I_theta_P",
                 "I_psi_P_kg_m2": "I_psi_P"}


def _read_wing(t: _Table) -> Wing:
    slope = t.raw("lift_slope_per_rad", 2.0 * math.pi)
    if not isinstance(slope, str):
        slope = t.number("lift_slope_per_rad")
    kw = dict(
        name=t.string("name", "wing"),
        semi_span=t.number("semi_span_m"),
        root_chord=t.number("root_chord_m"),
        tip_chord=t.number("tip_chord_m", None),
        mass_per_length=t.numbers("mass_per_length_kg_per_m"),
        polar_inertia=t.numbers("polar_inertia_kg_m", None),
        radius_of_gyration=t.numbers("radius_of_gyration_chord", None),
        elastic_axis=t.numbers("elastic_axis_chord", 0.5),
        centre_of_gravity=t.numbers("centre_of_gravity_chord", 0.5),
        EI=t.numbers("EI_N_m2"),
        GJ=t.numbers("GJ_N_m2"),
        lift_slope=slope,
        aerodynamic_centre=t.numbers("aerodynamic_centre_chord", 0.25),
        n_elements=t.integer("n_elements", 20),
        aero_model=t.string("aero_model", "leishman-nguyen", ("leishman-nguyen", "wagner")),
        rayleigh=(t.number("rayleigh_mu_per_s", 0.0), t.number("rayleigh_lambda_s", 0.0)),
    )
    with _context(t.where):
        return Wing(**kw)


def _read_mass(x: Any, where: str) -> PointMass:
    t = _Table(x, where, ("mass_kg", "x_m"))
    with _context(where):
        return PointMass(t.number("mass_kg"), t.number("x_m"))


def _read_distribution(t: _Table, value_key: str, default_name: str) -> Distribution:
    eta, values = t.raw("eta"), t.raw(value_key)
    for key, arr in (("eta", eta), (value_key, values)):
        if not isinstance(arr, list) or any(isinstance(i, bool) or not isinstance(i, (int, float))
                                            for i in arr):
            raise v.InputError(f"{t.where}.{key} = {arr!r} is invalid: must be a list of numbers")
    with _context(t.where):
        return Distribution.tabulated(eta, values, t.string("name", default_name))


def _read_settings(t: _Table | None) -> AeroSettings:
    if t is None:
        return AeroSettings()
    d = AeroSettings()
    with _context(t.where):
        return _settings(t, d)


def _settings(t: _Table, d: AeroSettings) -> AeroSettings:
    return AeroSettings(
        wake=t.boolean("wake", d.wake),
        compressibility=t.boolean("compressibility", d.compressibility),
        aspect_ratio_correction=t.boolean("aspect_ratio_correction", d.aspect_ratio_correction),
        cnq_sign=t.string("cnq_sign", d.cnq_sign),
        method=t.string("method", d.method),
        cutoff_lift_slope=t.number("cutoff_lift_slope_per_rad", d.cutoff_lift_slope),
        quadrature_order=t.integer("quadrature_order", d.quadrature_order),
    )


def _read_chord(t: _Table, number_key: str, table_key: str, required: bool = True):
    """A chord as a number or a Distribution; _MISSING when optional and not given."""
    if not required and not t.has(number_key) and not t.has(table_key):
        return _MISSING
    if t.has(number_key) == t.has(table_key):
        raise v.InputError(
            f"{t.where}: give exactly one of {number_key} (a number) or [{t.where}.{table_key}] "
            "(a table eta, chord_m)")
    if t.has(number_key):
        return t.number(number_key)
    return _read_distribution(t.sub(table_key, ("name", "eta", "chord_m")), "chord_m", "chord")


def _read_derivatives(t: _Table | None):
    if t is None:
        return None
    source = t.raw("source")
    if source == "measured":
        t = _Table(t.data, t.where, ("source", "values"))
        values = t.sub("values", DERIVATIVE_NAMES, required=True)
        with _context(values.where):
            return MeasuredDerivatives({k: values.number(k) for k in DERIVATIVE_NAMES if values.has(k)})
    if source == "houbolt-reed":
        t = _Table(t.data, t.where, ("source", "n_blades", "radius_m", "hub_ratio", "chord_m",
                                     "chord", "reference_chord_m", "aspect_ratio", "lift_slope",
                                     "settings"))
        ls = t.sub("lift_slope", ("name", "eta", "lift_slope_per_rad"))
        with _context(t.where):
            geo = _geometry(t, ls)
        return HouboltReedSource(geo, _read_settings(t.sub("settings", _SETTINGS_KEYS)))
    raise v.InputError(
        f"{t.where}.source = {source!r} is invalid: must be \"measured\" or \"houbolt-reed\"")


def _geometry(t: _Table, ls: _Table | None) -> PropellerGeometry:
    return PropellerGeometry(
        n_blades=t.integer("n_blades"), radius=t.number("radius_m"),
        hub_ratio=t.number("hub_ratio", 0.0), chord=_read_chord(t, "chord_m", "chord"),
        lift_slope=None if ls is None else _read_distribution(ls, "lift_slope_per_rad", "lift_slope"),
        reference_chord=t.number("reference_chord_m", None),
        aspect_ratio=t.number("aspect_ratio", None),
    )


def _read_propeller(t: _Table) -> Propeller:
    masses = t.raw("masses", [])
    if not isinstance(masses, list):
        raise v.InputError(f"{t.where}.masses = {masses!r} is invalid: must be a list of tables "
                           "{ mass_kg = ..., x_m = ... }")
    inertia_t = t.sub("inertia", tuple(_INERTIA_KEYS))
    inertia = (None if inertia_t is None else
               {_INERTIA_KEYS[k]: inertia_t.number(k) for k in _INERTIA_KEYS if inertia_t.has(k)})
    optional = {}
    chord = _read_chord(t, "blade_chord_m", "blade_chord", required=False)
    if chord is not _MISSING:  # not needed with measured derivatives
        optional["blade_chord"] = chord
    kw = dict(
        **optional,
        name=t.string("name", "propeller"),
        radius=t.number("radius_m"),
        hub_radius=t.number("hub_radius_m", 0.0),
        n_blades=t.integer("n_blades", 3),
        rotor=_read_mass(t.raw("rotor"), f"{t.where}.rotor"),
        masses=tuple(_read_mass(m, f"{t.where}.masses[{i}]") for i, m in enumerate(masses)),
        pivot_pitch=t.number("pivot_pitch_m", 0.0),
        pivot_yaw=t.number("pivot_yaw_m", 0.0),
        f_theta=t.number("f_theta_hz", None),
        K_theta=t.number("K_theta_N_m_per_rad", None),
        f_psi=t.number("f_psi_hz", None),
        K_psi=t.number("K_psi_N_m_per_rad", None),
        damping=t.string("damping", "g", ("g", "zeta")),
        damping_theta=t.number("damping_theta", 0.0),
        damping_psi=t.number("damping_psi", 0.0),
        spin_inertia=t.number("spin_inertia_kg_m2", None),
        operation=t.string("operation", "fixed-pitch", ("fixed-pitch", "constant-speed")),
        beta_075_deg=t.number("beta_075_deg", 35.0),
        zero_lift_angle_deg=t.number("zero_lift_angle_deg", -3.0),
        advance_rule=t.string("advance_rule", "thesis_eq_9_1", ("thesis_eq_9_1", "blade_element")),
        rpm=t.number("rpm", None),
        rotation=t.integer("rotation", 1),
        inertia=inertia,
        aero_settings=_read_settings(t.sub("aero_settings", _SETTINGS_KEYS)),
        derivatives=_read_derivatives(t.sub("derivatives", ("source", "values", "n_blades",
                                                            "radius_m", "hub_ratio", "chord_m",
                                                            "chord", "reference_chord_m",
                                                            "aspect_ratio", "lift_slope",
                                                            "settings"))),
    )
    with _context(t.where):
        return Propeller(**kw)


def _read_flight(top: _Table) -> FlightCondition:
    f = top.sub("flight", ("density_kg_per_m3", "speed_of_sound_m_per_s", "speed_range_m_per_s"),
                required=True)
    kw = {"density": f.number("density_kg_per_m3")}
    if f.has("speed_of_sound_m_per_s"):
        kw["speed_of_sound"] = f.number("speed_of_sound_m_per_s")
    if f.has("speed_range_m_per_s"):
        rng = f.numbers("speed_range_m_per_s")
        if np.ndim(rng) != 1 or np.size(rng) != 3:
            raise v.InputError(f"flight.speed_range_m_per_s = {f.raw('speed_range_m_per_s')!r} is "
                               "invalid: must be [first, last, step] in m/s")
        kw["speed_range"] = tuple(float(x) for x in rng)
    with _context("flight"):
        return FlightCondition(**kw)


def _from_dict(data: dict[str, Any]):
    kind = data.get("type")
    keys = {
        "propeller-wing": ("format", "format_version", "type", "name", "switches", "flight", "wing",
                           "installations", "propellers"),
        "isolated-propeller": ("format", "format_version", "type", "name", "propeller", "switches",
                               "flight", "propellers"),
        "propeller": ("format", "format_version", "type", "name", "propeller", "propellers"),
    }
    if kind not in keys:
        raise v.InputError(f"type = {kind!r} is invalid: must be one of {', '.join(keys)}")
    top = _Table(data, "", keys[kind])
    fmt = top.string("format", FORMAT)
    if fmt != FORMAT:
        raise v.InputError(f"format = {fmt!r} is invalid: must be {FORMAT!r}")
    version = top.integer("format_version", FORMAT_VERSION)
    if version != FORMAT_VERSION:
        raise v.InputError(f"format_version = {version!r} is invalid: this propwhirl reads "
                           f"version {FORMAT_VERSION}")
    props_raw = top.raw("propellers", {})
    if not isinstance(props_raw, dict):
        raise v.InputError(f"propellers = {props_raw!r} is invalid: must be tables [propellers.KEY]")
    props = {k: _read_propeller(_Table(val, f"propellers.{k}", _PROPELLER_KEYS))
             for k, val in props_raw.items()}

    def prop(key: Any, where: str) -> Propeller:
        if not isinstance(key, str) or key not in props:
            raise v.InputError(f"{where} = {key!r} is invalid: must name a [propellers.*] table "
                               f"({', '.join(props) or 'none given'})")
        return props[key]

    if kind == "propeller":
        return prop(top.raw("propeller"), "propeller")
    if kind == "isolated-propeller":
        sw = top.sub("switches", ("propeller_aero", "rotating"))
        sw = sw or _Table({}, "switches", ())
        return IsolatedPropeller(
            prop(top.raw("propeller"), "propeller"), _read_flight(top),
            propeller_aero=sw.boolean("propeller_aero", True), rotating=sw.boolean("rotating", True),
            name=top.string("name", "isolated propeller"))
    sw = top.sub("switches", ("wing_aero", "propeller_aero", "rotating")) or _Table({}, "switches", ())
    insts_raw = top.raw("installations", [])
    if not isinstance(insts_raw, list):
        raise v.InputError("installations is invalid: must be an array of tables [[installations]]")
    insts = []
    for i, raw in enumerate(insts_raw):
        it = _Table(raw, f"installations[{i}]", ("propeller", "y_m", "mount", "aero"))
        p, y = prop(it.raw("propeller"), f"installations[{i}].propeller"), it.number("y_m")
        mount = it.string("mount", "flexible", ("flexible", "rigid"))
        aero = it.boolean("aero", True)
        with _context(it.where):
            insts.append(Installation(p, y, mount, aero))
    wing = _read_wing(top.sub("wing", _WING_KEYS, required=True))
    flight = _read_flight(top)
    switches = dict(wing_aero=sw.boolean("wing_aero", True),
                    propeller_aero=sw.boolean("propeller_aero", True),
                    rotating=sw.boolean("rotating", True), name=top.string("name", "propeller-wing"))
    with _context("installations"):  # a propeller off the mesh, two at one node
        return PropellerWing(wing, flight, tuple(insts), **switches)


def loads(text: str, source: str = "<string>"):
    """The model in TOML `text` (a PropellerWing, IsolatedPropeller or Propeller).

    Every problem — bad TOML, an unknown or missing field, a wrong type, an invalid value — is
    an InputError whose message starts with `source`."""
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise v.InputError(f"{source}: not valid TOML: {exc}") from exc
    try:
        return _from_dict(data)
    except v.InputError as exc:
        raise v.InputError(f"{source}: {exc}") from exc
    except (TypeError, ValueError) as exc:  # anything a constructor let through unchecked
        raise v.InputError(f"{source}: invalid model: {exc}") from exc


def load_model(path: str | Path):
    """Read a TOML model file written by :func:`save_model` (or by hand)."""
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise v.InputError(f"model file {str(path)!r} not found") from None
    except (OSError, UnicodeDecodeError) as exc:
        raise v.InputError(f"cannot read model file {str(path)!r}: {exc}") from exc
    return loads(text, str(path))


# =============================================================================== V-g-f CSV
#: CSV column names (unit suffixes) ↔ keys of :meth:`propwhirl.engine.core.Sweep.table`.
VGF_COLUMNS: tuple[tuple[str, str], ...] = (
    ("V_m_per_s", "V"), ("mode", "mode"), ("label", "label"), ("frequency_hz", "frequency_hz"),
    ("damping_ratio", "damping_ratio"), ("real_per_s", "real"), ("imag_per_s", "imag"),
)


def write_vgf_csv(result, path: str | Path) -> Path:
    """Write the V-g-f table of a ModelAnalysis or Sweep as CSV (one row per speed and
    physical mode: V [m/s], mode id, label, f [Hz], ζ (eq. 5.5), Re λ, Im λ [1/s])."""
    sweep = getattr(result, "sweep", result)
    table = sweep.table()
    path = Path(path)
    try:
        with path.open("w", newline="", encoding="utf-8") as fh:
            out = csv.writer(fh)
            out.writerow([c for c, _ in VGF_COLUMNS])
            cols = [table[k] for _, k in VGF_COLUMNS]
            for row in zip(*cols):
                out.writerow([repr(float(x)) if isinstance(x, (float, np.floating)) else
                              str(int(x)) if isinstance(x, (int, np.integer)) else str(x)
                              for x in row])
    except OSError as exc:
        raise v.InputError(f"cannot write {str(path)!r}: {exc.strerror or exc}") from exc
    return path


def read_vgf_csv(path: str | Path) -> dict[str, np.ndarray]:
    """Read a table written by :func:`write_vgf_csv` back into Sweep.table() columns."""
    path = Path(path)
    try:
        with path.open(newline="", encoding="utf-8") as fh:
            rows = list(csv.reader(fh))
    except FileNotFoundError:
        raise v.InputError(f"V-g-f table {str(path)!r} not found") from None
    except OSError as exc:
        raise v.InputError(f"cannot read {str(path)!r}: {exc}") from exc
    expected = [c for c, _ in VGF_COLUMNS]
    if not rows or rows[0] != expected:
        raise v.InputError(f"{path}: not a V-g-f table: the header must be {','.join(expected)}")
    body = rows[1:]
    if any(len(r) != len(expected) for r in body):
        bad = next(i for i, r in enumerate(body) if len(r) != len(expected))
        raise v.InputError(f"{path}: row {bad + 2} has {len(body[bad])} columns, need {len(expected)}")
    cols = list(zip(*body)) if body else [()] * len(expected)
    out: dict[str, np.ndarray] = {}
    try:
        for (name, key), col in zip(VGF_COLUMNS, cols):
            if key == "label":
                out[key] = np.asarray(col, dtype=object)
            elif key == "mode":
                out[key] = np.asarray([int(x) for x in col], dtype=int)
            else:
                out[key] = np.asarray([float(x) for x in col], dtype=float)
    except ValueError as exc:
        raise v.InputError(f"{path}: column {name}: {exc}") from exc
    return out


def model_fields() -> dict[str, tuple[str, ...]]:
    """Dataclass fields of each saved type (used by a test that fails when a model class gains a
    field that this module does not write)."""
    return {cls.__name__: tuple(f.name for f in dataclasses.fields(cls))
            for cls in (Wing, Propeller, PropellerWing, IsolatedPropeller, Installation,
                        FlightCondition, AeroSettings, PointMass, PropellerGeometry)}
