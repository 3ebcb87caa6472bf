"""Campaign files (TOML): :func:`loads` / :func:`load_campaign` read a whirl-flutter clearance
campaign as a :class:`CampaignSpec` (plain checked values and the loaded model), which
:func:`propwhirl.studies.campaign.from_spec` makes a
:class:`~propwhirl.studies.campaign.Campaign` (io does not import the studies: the package
layers, tests/test_layering.py); the format is ``docs/campaign.md``.

Every problem — bad TOML, an unknown or missing key, a wrong type, a value out of its range,
a model file that cannot be read, a case the model cannot take (overspeed of a windmilling
propeller, a propeller it does not have) — is a one-line InputError starting with the file's
name and naming the key as written, the value and the valid range; all of it before any
analysis (:func:`~propwhirl.studies.campaign.from_spec` builds the model of every case at every
envelope point before the first analysis; its errors start with the file's name and name the
case's table too).

Layout::

    format = "propwhirl-campaign"
    format_version = 1
    name = "..."
    model = "wingtip.toml"            # relative to the campaign file
    convention = "propwhirl"          # or "thesis"
    combine = "list"                  # or "product" (of the case groups)
    [regulation]                      # name = cs25 | far25 | far23 | explicit (+ factor)
    [envelope]                        # airspeed, V_D_m_per_s, M_D, altitudes_m | altitudes_ft,
                                      # V_C_m_per_s, M_C (failure cases, 25.629(b)(2))
    [[cases]]                         # name, propellers, each_propeller, mount_stiffness, ...,
                                      # failure
"""
from __future__ import annotations

import math
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from propwhirl import fileio, limits
from propwhirl import validate as v
from propwhirl.io.modal_files import is_modal_file, load_modal_model
from propwhirl.io.model_files import Table, load_model, toml_error

#: The format tag and version of a campaign file.
FORMAT = "propwhirl-campaign"
FORMAT_VERSION = 1
#: Most (case, envelope point) analyses a campaign file may ask for.
MAX_TASKS = 10_000
#: Most altitudes, cases (before expansion), added masses or values of one case.
MAX_ITEMS = 1000
#: The regulations' speed factors (those of :data:`propwhirl.studies.campaign.REGULATIONS`).
REGULATIONS = {"cs25": 1.15, "far25": 1.15, "far23": 1.2}
#: The regulations whose failure cases are held to the envelope of 25.629(b)(2).
PART25 = ("cs25", "far25")
#: The airspeeds V_D can be given as; the operations a case can switch a propeller to.
AIRSPEEDS = ("EAS", "TAS")
OPERATIONS = ("windmilling",)
#: The installation states a case can set (those of :data:`propwhirl.studies.campaign.STATES`).
STATES = ("operating", "feathered", "stopped")
#: Feet to metres.
FT = 0.3048

_TOP = ("format", "format_version", "name", "model", "convention", "combine", "regulation",
        "envelope", "cases")
_REGULATION = ("name", "factor", "min_damping_g", "damping")
_ENVELOPE = ("airspeed", "V_D_m_per_s", "M_D", "V_C_m_per_s", "M_C", "altitudes_m",
             "altitudes_ft")
_CASE = ("name", "group", "propellers", "each_propeller", "mount_stiffness", "mount_damping",
         "wing_damping", "operation", "state", "rpm_factor", "reverse_rotation", "added_masses",
         "values", "failure")
_MASS = ("mass_kg", "x_m")
#: Ranges of the case factors: key → (low, high).
FACTOR_RANGES = {"mount_stiffness": (1e-3, 100.0), "mount_damping": (0.0, 100.0),
                 "wing_damping": (0.0, 100.0), "rpm_factor": (0.1, 3.0)}


def _number_in(t: Table, key: str, low: float, high: float, what: str = "") -> float:
    x = t.number(key, what)
    if not (math.isfinite(x) and low <= x <= high):
        raise t.bad(key, f"a number in [{low:g}, {high:g}]", what)
    return x


def _list_of_numbers(t: Table, key: str, low: float, high: float) -> list[float]:
    x = t.raw(key)
    if not isinstance(x, list) or not 1 <= len(x) <= MAX_ITEMS or any(
            isinstance(i, bool) or not isinstance(i, (int, float)) or not math.isfinite(i)
            or not low <= i <= high for i in x):
        raise t.bad(key, f"a list of 1 to {MAX_ITEMS} numbers in [{low:g}, {high:g}]")
    return [float(i) for i in x]


def _regulation(t: Table) -> tuple[str, float, float | None]:
    name = t.string("name", choices=(*REGULATIONS, "explicit"))
    if name == "explicit":
        factor = _number_in(t, "factor", 1.0, 3.0, "the speed factor of regulation 'explicit'")
    else:
        factor = REGULATIONS[name]
        if t.has("factor") and t.data["factor"] != factor:
            raise t.bad("factor", f"{factor:g} with name = {name!r} (or give name = 'explicit')")
    g = _number_in(t, "min_damping_g", 0.0, 1.0) if t.has("min_damping_g") else None
    return name, factor, g


# ---- issue 35 item 2: [regulation] damping, the damping requirement's reading (one key) ----
#: Its keys, and the choices of two of them (those of propwhirl.analysis.damping_requirement).
_DAMPING = ("applies_to", "above_m_per_s", "modes", "source")
DAMPING_APPLIES_TO = ("total", "aerodynamic")
DAMPING_MODES = ("all", "critical")


def _damping(t: Table, g: float | None) -> dict[str, Any] | None:
    """[regulation] damping = {applies_to, above_m_per_s, modes, source}: which damping the
    min_damping_g requirement applies to; required with min_damping_g, refused without it."""
    if g is None:
        if t.has("damping"):
            raise t.bad("damping", "absent without min_damping_g (it says how min_damping_g is "
                        "read)")
        return None
    if not t.has("damping"):
        raise t.missing("damping", 'min_damping_g needs it: damping = { applies_to = "total" '
                        'or "aerodynamic", source = "MIL-A-8870C 3.1.1" (or your practice), '
                        'above_m_per_s = 0.0, modes = "all" or "critical" } (docs/campaign.md)')
    d = t.sub("damping", _DAMPING)
    out: dict[str, Any] = {"applies_to": d.string(
        "applies_to", "total: structural damping included; aerodynamic: the increment above it",
        DAMPING_APPLIES_TO)}
    out["above_m_per_s"] = _number_in(d, "above_m_per_s", 0.0, 1000.0) \
        if d.has("above_m_per_s") else 0.0
    out["modes"] = d.string("modes", "", DAMPING_MODES) if d.has("modes") else "all"
    out["source"] = d.string("source", "where this reading of the requirement comes from")
    if not out["source"].strip() or not out["source"].isprintable() or len(out["source"]) > 200:
        raise d.bad("source", "a non-empty printable text of at most 200 characters")
    return out
# ---- end of issue 35 item 2 ----


def _envelope(t: Table) -> tuple[str, tuple[float, ...], tuple[float, ...], float | None,
                                 tuple[float, ...] | None, float | None]:
    airspeed = t.string("airspeed", "which airspeed V_D is", AIRSPEEDS)
    if t.has("altitudes_m") == t.has("altitudes_ft"):
        raise v.InputError(f"[{t.where}] give exactly one of altitudes_m, altitudes_ft")
    if t.has("altitudes_m"):
        alts = _list_of_numbers(t, "altitudes_m", -5000.0, 32000.0)
    else:
        alts = [h * FT for h in _list_of_numbers(t, "altitudes_ft", -5000.0 / FT, 32000.0 / FT)]
    raw = t.raw("V_D_m_per_s", "the design dive speed [m/s]")
    if isinstance(raw, list):
        vd = _list_of_numbers(t, "V_D_m_per_s", 1.0, 1000.0)
        if len(vd) != len(alts):
            raise t.bad("V_D_m_per_s", f"one speed, or one per altitude ({len(alts)})")
    else:
        vd = [_number_in(t, "V_D_m_per_s", 1.0, 1000.0)]
    M_D = _number_in(t, "M_D", 0.01, 0.95) if t.has("M_D") else None
    V_C: tuple[float, ...] | None = None
    if t.has("V_C_m_per_s"):
        if isinstance(t.raw("V_C_m_per_s"), list):
            V_C = tuple(_list_of_numbers(t, "V_C_m_per_s", 1.0, 1000.0))
            if len(V_C) != len(alts):
                raise t.bad("V_C_m_per_s", f"one speed, or one per altitude ({len(alts)})")
        else:
            V_C = (_number_in(t, "V_C_m_per_s", 1.0, 1000.0,
                              "the design cruise speed, an equivalent airspeed [m/s]"),)
    M_C = _number_in(t, "M_C", 0.01, 0.95) if t.has("M_C") else None
    if M_C is not None and V_C is None:
        raise t.missing("V_C_m_per_s", "M_C needs V_C (the failure-case envelope of "
                                       "25.629(b)(2)(ii))")
    return airspeed, tuple(vd), tuple(alts), M_D, V_C, M_C


def _case(t: Table, n_propellers: int) -> CaseSpec:
    name = t.string("name")
    if not name.strip() or not name.isprintable() or len(name) > 200:
        raise t.bad("name", "a non-empty printable name of at most 200 characters")
    group = t.string("group") if t.has("group") else ""
    kw: dict[str, Any] = {}
    for key, (lo, hi) in FACTOR_RANGES.items():
        if t.has(key):
            kw[key] = _number_in(t, key, lo, hi)
    if t.has("operation"):
        kw["operation"] = t.string("operation", "a constant-speed propeller switched to "
                                   "windmilling; feathered or stopped rotors: state", OPERATIONS)
    if t.has("state"):
        kw["state"] = t.string("state", "the chosen installations' state: feathered (Omega = 0, "
                               "the feathered blades' side forces), stopped (Omega = 0, no "
                               "propeller aerodynamics) or operating", STATES)
    if t.has("reverse_rotation"):
        kw["reverse_rotation"] = t.boolean("reverse_rotation")
    props: tuple[int, ...] = ()
    if t.has("propellers"):
        x = t.raw("propellers")
        if (not isinstance(x, list) or not x or len(set(map(str, x))) != len(x)
                or any(isinstance(i, bool) or not isinstance(i, int) or not 1 <= i <= n_propellers
                       for i in x)):
            raise t.bad("propellers", f"a list of distinct propeller numbers in [1, "
                                      f"{n_propellers}] (the model's propellers, from 1)")
        props = tuple(x)
    if t.has("added_masses"):
        x = t.raw("added_masses")
        if not isinstance(x, list) or not 1 <= len(x) <= MAX_ITEMS:
            raise t.bad("added_masses", f"a list of 1 to {MAX_ITEMS} tables "
                                        "{ mass_kg = ..., x_m = ... }")
        masses = []
        for i, m in enumerate(x):
            mt = Table(m, f"{t.where}.added_masses[{i}]", _MASS)
            masses.append((_number_in(mt, "mass_kg", 1e-4, 1e5), _number_in(mt, "x_m", -100.0, 100.0)))
        kw["added_masses"] = tuple(masses)
    if t.has("values"):
        vt = t.sub("values", [k for k in (t.data["values"] if isinstance(t.data["values"], dict)
                                          else ())])
        if not 1 <= len(vt.data) <= MAX_ITEMS:
            raise t.bad("values", f"a table of 1 to {MAX_ITEMS} \"path\" = number entries")
        kw["values"] = tuple((k, vt.number(k, "a parameter path's value")) for k in vt.data)
    if t.has("failure"):
        kw["failure"] = t.boolean("failure")
    each = t.boolean("each_propeller") if t.has("each_propeller") else False
    return CaseSpec(t.where, name, group, props, each, kw)


@dataclass(frozen=True)
class CaseSpec:
    """One [[cases]] table, checked: table ("cases[2]"), name, group ("" outside a product),
    propellers (numbers from 1; empty: all), each_propeller (one case per propeller) and
    transform: the :class:`~propwhirl.studies.campaign.Case` fields it sets."""

    table: str
    name: str
    group: str
    propellers: tuple[int, ...]
    each_propeller: bool
    transform: dict[str, Any] = field(default_factory=dict)


@dataclass(frozen=True)
class CampaignSpec:
    """A campaign file, checked (module docstring): source (the file's name), name, model
    (loaded), model_path, convention ("propwhirl"/"thesis"), combine ("list"/"product"),
    regulation, factor, min_damping_g (None: none), airspeed ("EAS"/"TAS"), V_D [m/s] (one,
    or one per altitude), altitudes_m [m], M_D (None: none), cases, V_C [m/s EAS] (one, or
    one per altitude; None: none) and M_C (None: none): the failure-case envelope of
    25.629(b)(2)(ii)."""

    source: str
    name: str
    model: Any
    model_path: str
    convention: str
    combine: str
    regulation: str
    factor: float
    min_damping_g: float | None
    airspeed: str
    V_D: tuple[float, ...]
    altitudes_m: tuple[float, ...]
    M_D: float | None
    cases: tuple[CaseSpec, ...]
    V_C: tuple[float, ...] | None = None
    M_C: float | None = None
    #: [regulation] damping: how min_damping_g is read ({applies_to, above_m_per_s, modes,
    #: source}; None without min_damping_g)
    damping: dict[str, Any] | None = None


def _from_dict(data: dict[str, Any], base: Path, source: str) -> CampaignSpec:
    top = Table(data, "", _TOP)
    fmt = top.string("format")
    if fmt != FORMAT:
        raise top.bad("format", repr(FORMAT))
    version = top.integer("format_version")
    if version != FORMAT_VERSION:
        raise top.bad("format_version", f"{FORMAT_VERSION} (this propwhirl reads campaign files "
                                        f"of version {FORMAT_VERSION})")
    name = top.string("name") if top.has("name") else Path(source).stem
    model_key = top.string("model", "the model file, relative to the campaign file")
    path = Path(model_key)
    if not path.is_absolute():
        path = base / path
    try:                            # a beam model's file or a modal model's
        model = load_modal_model(path) if is_modal_file(path) else load_model(path)
    except v.InputError as exc:
        raise v.InputError(f"model = {model_key!r}: {exc}") from None
    n = len(getattr(model, "propellers", ()) if isinstance(getattr(model, "propellers", None),
                                                           tuple) else ())
    if n == 0:
        raise top.bad("model", "a propeller-wing model with at least one propeller "
                               f"({str(path)!r} holds a {type(model).__name__} without any)")
    conv = top.string("convention", choices=("propwhirl", "thesis")) \
        if top.has("convention") else "propwhirl"
    combine = top.string("combine", choices=("list", "product")) \
        if top.has("combine") else "list"
    reg = top.sub("regulation", _REGULATION)
    regulation, factor, g = _regulation(reg)
    damping = _damping(reg, g)
    env = top.sub("envelope", _ENVELOPE)
    airspeed, vd, alts, M_D, V_C, M_C = _envelope(env)
    if V_C is not None and regulation not in PART25:
        raise env.bad("V_C_m_per_s", f"absent with [regulation] name = {regulation!r}: the "
                      "failure-case envelope (V_C, M_C) is that of 25.629(b)(2) (cs25, far25); "
                      f"under {regulation!r} every case, failure or not, is held to "
                      f"{factor:g} V_D")
    raw = top.raw("cases", "one [[cases]] table per case")
    if not isinstance(raw, list) or not 1 <= len(raw) <= MAX_ITEMS:
        raise top.bad("cases", f"1 to {MAX_ITEMS} [[cases]] tables")
    specs = []
    groups: dict[str, int] = {}
    for i, d in enumerate(raw):
        t = Table(d, f"cases[{i}]", _CASE)
        c = _case(t, n)
        if combine == "product" and not c.group:
            raise t.missing("group", "every case of combine = 'product' names its group")
        groups[c.group] = groups.get(c.group, 0) + (len(c.propellers) or n if c.each_propeller
                                                    else 1)
        specs.append(c)
    count = math.prod(groups.values()) if combine == "product" else sum(groups.values())
    if count * len(alts) > MAX_TASKS:
        raise v.InputError(f"the cases ({count}) x altitudes ({len(alts)}) make "
                           f"{count * len(alts)} analyses, at most {MAX_TASKS}")
    return CampaignSpec(source, name, model, str(path), conv, combine, regulation, factor, g,
                        airspeed, vd, alts, M_D, tuple(specs), V_C, M_C, damping)


def loads(text: str, source: str = "<string>", base: str | Path = ".") -> CampaignSpec:
    """The campaign in TOML `text`; its model path is relative to `base`.  Every problem is a
    one-line InputError starting with `source` (module docstring)."""
    if not isinstance(text, str):
        raise v.fail("text", text, "invalid: must be the TOML text of a campaign file (a str; "
                     f"a file: load_campaign(path)), got {type(text).__name__}")
    if not isinstance(source, str):
        raise v.fail("source", source, "invalid: must be a str (how errors name the campaign), "
                     f"got {type(source).__name__}")
    v.file_path("base", base, "the folder the model path is relative to")
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise v.InputError(f"{source}: not valid TOML: {toml_error(exc, text)}") from exc
    except RecursionError:
        raise limits.nesting_error(source) from None
    limits.check_nesting(data, source)
    try:
        return _from_dict(data, Path(base), source)
    except v.InputError as exc:
        raise v.InputError(f"{source}: {' '.join(str(exc).split())}") from exc
    except (TypeError, ValueError) as exc:   # anything a constructor let through unchecked
        raise v.InputError(f"{source}: invalid campaign: {exc}") from exc


def load_campaign(path: str | Path) -> CampaignSpec:
    """Read a campaign file (errors as :func:`loads`, naming the path)."""
    path = Path(v.file_path("path", path, "a campaign file (TOML)"))
    text = fileio.read_text(path, "campaign file", empty_ok=True, limit=fileio.MAX_TOML_BYTES)
    return loads(text, str(path), path.parent)
