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

The keys are declared once (:mod:`propwhirl.io.tables`): the top-level, ``[regulation]`` and
``[envelope]`` keys as the metadata of the :class:`CampaignSpec` field each fills, a case's in
:data:`CASE`; :func:`propwhirl.io.tables.read` reads them and ``docs/campaign.md``'s key tables
are generated from them (:func:`docs_parts`).  A new key is one declaration: e.g. a damping
requirement's basis in ``[regulation]`` is one more ``CampaignSpec`` field,
``basis: str = spec_field("regulation", Key("basis", "string", "...", choices=(...),
default="..."))``.

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

import dataclasses
import math
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from propwhirl import fileio, limits
from propwhirl import validate as v
from propwhirl.certification import (AIRSPEEDS, CASE_FACTORS, DAMPING_APPLIES_TO, DAMPING_MODES,
                                     EXPLICIT, FACTOR_RANGE, OPERATIONS,
                                     PART25, REGULATIONS, STATES)
from propwhirl.io.modal_files import is_modal_file, load_modal_model
from propwhirl.io.model_files import Table, load_model, toml_error
from propwhirl.io.tables import OMITTED, Key, TableSpec, Values, markdown, read

#: The format tag and version of a campaign file.
FORMAT = "propwhirl-campaign"
FORMAT_VERSION = 1
#: Most (case, envelope point) analyses a campaign file may ask for.
MAX_TASKS = 10_000
#: Most altitudes, cases (before expansion), added masses or values of one case.
MAX_ITEMS = 1000
#: Feet to metres.
FT = 0.3048
#: Ranges of the case factors: key → (low, high) (:data:`propwhirl.certification.CASE_FACTORS`).
FACTOR_RANGES = CASE_FACTORS
#: The valid altitudes [m] (the ISA's range).
ALTITUDES_M = (-5000.0, 32000.0)
#: The valid design speeds V_D and V_C [m/s].
SPEEDS = (1.0, 1000.0)
#: The valid design Mach numbers M_D and M_C.
MACHS = (0.01, 0.95)


# =============================================================================== the keys
#: The keys of the metadata of a :class:`CampaignSpec` field: its table ("" the top level)
#: and its keys in the file.
TABLE, KEYS = "campaign table", "campaign keys"


def spec_field(table: str, *keys: Key, **kw: Any) -> Any:
    """A :class:`CampaignSpec` field read from `keys` of `table` ("", "regulation",
    "envelope"): the field holds the first key's value (checked and defaulted by its
    declaration), unless :func:`_from_dict` ties several keys together."""
    return field(metadata={TABLE: table, KEYS: keys}, **kw)


MASS = TableSpec("cases[i].added_masses[j]", "A mass added on each chosen propeller's shaft.", (
    Key("mass_kg", "number", "the mass", "kg", (1e-4, 1e5)),
    Key("x_m", "number", "its position on the shaft, from the wing mid-chord, positive aft (as "
        "a propeller's masses, docs/model-file.md)", "m", (-100.0, 100.0)),
))

_FACTOR_DOCS = {
    "mount_stiffness": "factor on the pitch and yaw mount stiffness K_θ, K_ψ (a mount given by "
                       "frequencies has f_θ, f_ψ times its square root): 0.5 is a mount "
                       "degraded to 50 %",
    "mount_damping": "factor on `damping_theta` and `damping_psi`: 0 is a failed damper",
    "wing_damping": "factor on the wing's Rayleigh structural damping (μ, λ)",
    "rpm_factor": "overspeed: rpm times this; constant-speed propellers only (a windmilling "
                  "propeller's rotational speed follows the airspeed: refused)",
}

#: A ``[[cases]]`` table: the case's own keys (name, group, propellers, each_propeller) and
#: the transformations it sets (every other key: a :class:`~propwhirl.studies.campaign.Case`
#: field of that name).
CASE = TableSpec("[[cases]]", "Each case is a named transformation of the model; a case "
                 "without transformations is the nominal model.", (
    Key("name", "string", "the case's name, unique in the campaign (after expansion); "
        "printable, at most 200 characters"),
    Key("group", "string", "with `combine = \"product\"`: the group the case belongs to "
        "(required there)", default=OMITTED),
    Key("propellers", "integers", "the propellers the transformations act on, numbered from 1 "
        "(default: every propeller together)", range=(1, "the model's propellers"),
        default=OMITTED, distinct=True, must="a list of distinct propeller numbers in "
        "[1, {high}] (the model's propellers, from 1)"),
    Key("each_propeller", "boolean", "`true`: one case per propeller of `propellers` (or of "
        "the model), one at a time: \"... (propeller 1)\", ...", default=False),
    *(Key(name, "number", _FACTOR_DOCS[name], range=CASE_FACTORS[name], default=OMITTED)
      for name in ("mount_stiffness", "mount_damping", "wing_damping")),
    Key("operation", "string", "`\"windmilling\"`: a constant-speed propeller switched to "
        "fixed-pitch windmilling at its blade angle (a fixed-pitch propeller already "
        "windmills: unchanged)", choices=OPERATIONS, default=OMITTED,
        what="a constant-speed propeller switched to windmilling; feathered or stopped rotors: "
             "state"),
    Key("state", "string", "the chosen installations' `state` (docs/model-file.md, "
        "`installations[i]`): `\"feathered\"` — the rotor stopped (Ω = 0, no gyroscopic "
        "coupling) with its blades along the free stream: the blades act as fins, the Ω → 0 "
        "limit of the Houbolt–Reed blade elements (side forces C_Yψ = −C_Zθ only; needs the "
        "propeller's blade geometry); `\"stopped\"` — Ω = 0 and no propeller aerodynamic loads "
        "(folded blades); `\"operating\"` — turning as its propeller's operation says. The "
        "mount and the masses stay in every state", choices=STATES, default=OMITTED,
        what="the chosen installations' state: feathered (Omega = 0, the feathered blades' "
             "side forces), stopped (Omega = 0, no propeller aerodynamics) or operating"),
    Key("rpm_factor", "number", _FACTOR_DOCS["rpm_factor"], range=CASE_FACTORS["rpm_factor"],
        default=OMITTED),
    Key("reverse_rotation", "boolean", "`true`: the sense of rotation reversed, on each chosen "
        "installation (its `rotation`; propellers sharing a `[propellers.KEY]` table are "
        "reversed one by one). Without in-plane bending (`wing.EI_chordwise`) nothing of the "
        "wing moves sideways and reversing a rotor is the mirror image ψ → −ψ of its yaw: "
        "the "
        "same eigenvalues, V_crit and margins (only the whirl senses named in the results "
        "change sides); the sense matters with in-plane bending, which couples the yaw to the "
        "wing", default=OMITTED),
    Key("added_masses", "tables", "masses added on each chosen propeller's shaft (a battery or "
        "fuel case in the nacelle): `{ mass_kg = ..., x_m = ... }` each", table=MASS,
        items=(1, MAX_ITEMS), default=OMITTED),
    Key("values", "mapping", "`\"parameter path\" = number` set on the model after the rest "
        "(any path of `propwhirl.studies.paths`, e.g. `\"wing.mass_per_length*\" = 1.1` for "
        "fuel in the wing, `\"wing.rayleigh[0]\" = 0.0`)", items=(1, MAX_ITEMS),
        default=OMITTED, what="a parameter path's value",
        must="a table of {fewest} to {most} \"path\" = number entries"),
    Key("failure", "boolean", "`true`: a failure condition of 25.629(d), held to 25.629(b)(2) "
        "under `cs25`/`far25` (above); `false`: not; omitted: from its transformations (a "
        "degraded mount or damper, a feathered or stopped rotor, overspeed)", default=OMITTED),
))
#: The keys of a case that are the case's own, not a transformation.
CASE_OWN = ("name", "group", "propellers", "each_propeller")
#: How a transformation's value goes to its Case field (the others as read).
_TRANSFORM = {"added_masses": lambda ms: tuple((m["mass_kg"], m["x_m"]) for m in ms),
              "values": lambda d: tuple(d.items())}


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


#: ``[regulation] damping``: how ``min_damping_g`` is read (issue 35 item 2; the choices those
#: of :mod:`propwhirl.analysis.damping_requirement`).
DAMPING = TableSpec("[regulation] damping", "How the damping requirement is read.", (
    Key("applies_to", "string", "`\"total\"`: the damping of the aeroelastic system, "
        "structural damping included (the V-g-f's g; a mount with g = 0.02 fails g ≥ 0.03 at "
        "the first speed); `\"aerodynamic\"`: the increment the air adds above the structural "
        "damping, 2 (ζ(V) − ζ(V_0)) of each mode, V_0 the lowest analysed speed (the NASTRAN V-g "
        "reading)", choices=DAMPING_APPLIES_TO,
        what="total: structural damping included; aerodynamic: the increment above it"),
    Key("above_m_per_s", "number", "the requirement applies from this speed up to V_D",
        "m/s", (0.0, 1000.0), default=0.0),
    Key("modes", "string", "`\"all\"`: every oscillatory mode of interest; `\"critical\"`: "
        "the modes with an instability in the analysed range", choices=DAMPING_MODES, default="all"),
    Key("source", "string", "where this reading comes from (MIL-A-8870C 3.1.1, AC 25.629-1B, "
        "company practice): printed in the report; printable, at most 200 characters",
        what="where this reading of the requirement comes from"),
))


@dataclass(frozen=True)
class CampaignSpec:
    """A campaign file, checked (module docstring): source (the file's name), name, model
    (loaded), model_path, convention ("propwhirl"/"thesis"), combine ("list"/"product"),
    regulation, factor, min_damping_g (None: none), airspeed ("EAS"/"TAS"), V_D [m/s] (one,
    or one per altitude), altitudes_m [m], M_D (None: none), cases, V_C [m/s EAS] (one, or
    one per altitude; None: none) and M_C (None: none): the failure-case envelope of
    25.629(b)(2)(ii).  Each field read from the file declares its keys (:func:`spec_field`):
    the file's documentation is generated from them."""

    source: str
    name: str = spec_field("", Key(
        "name", "string", "the campaign's name in the report (default: the file's name)",
        default=OMITTED))
    model: Any
    model_path: str = spec_field("", Key(
        "model", "string", "a propeller-wing model file ([Model files](model-file.md), or a "
        "modal model's, [modal structures](modal-structures.md)), relative to the campaign file; "
        "its `[flight]` density and speed of sound are replaced by the ISA at each altitude, its "
        "speed grid (first speed and step) is kept and extended beyond factor · V_D",
        what="the model file, relative to the campaign file"))
    convention: str = spec_field("", Key(
        "convention", "string", "`\"propwhirl\"`: every instability counts (`propwhirl "
        "analyse`'s critical instability); `\"thesis\"`: the thesis's exclusions (the wing's "
        "static divergence and recovering low-speed instabilities left out)",
        choices=("propwhirl", "thesis"), default="propwhirl"))
    combine: str = spec_field("", Key(
        "combine", "string", "`\"list\"`: the cases as given; `\"product\"`: every combination "
        "of one case from each `group` (names joined with \" + \", factors multiplied)",
        choices=("list", "product"), default="list"))
    regulation: str = spec_field("regulation", Key(
        "name", "string", "the regulation (the table below): its speed factor on V_D and, "
        "under `cs25` and `far25`, the failure cases' envelope",
        choices=(*REGULATIONS, EXPLICIT)))
    factor: float = spec_field("regulation", Key(
        "factor", "number", "with `name = \"explicit\"` only (required there): the speed "
        "factor on V_D", range=FACTOR_RANGE, default=OMITTED,
        what="the speed factor of regulation 'explicit'"))
    min_damping_g: float | None = spec_field("regulation", Key(
        "min_damping_g", "number", "every oscillatory mode must have a structural damping "
        "coefficient g = 2ζ of at least this at every analysed speed up to V_D (below); "
        "omitted: damping is reported, not judged", range=(0.0, 1.0), default=OMITTED))
    airspeed: str = spec_field("envelope", Key(
        "airspeed", "string", "which airspeed `V_D_m_per_s` is. An EAS is converted with the "
        "ISA density at each altitude, V_TAS = V_EAS · sqrt(ρ0 / ρ(h)), ρ0 = 1.225 kg/m³; the "
        "analyses' speeds are true airspeeds (`FlightCondition`)", choices=AIRSPEEDS,
        what="which airspeed V_D is"))
    V_D: tuple[float, ...] = spec_field("envelope", Key(
        "V_D_m_per_s", "number_or_numbers", "the design dive speed V_D: one number for every "
        "altitude, or one per altitude (a V–altitude line)", "m/s", SPEEDS,
        items=(1, MAX_ITEMS), missing="the design dive speed [m/s]"))
    altitudes_m: tuple[float, ...] = spec_field("envelope", Key(
        "altitudes_m", "numbers", "the ISA (geopotential) altitudes: exactly one of "
        "`altitudes_m`, `altitudes_ft`", "m", ALTITUDES_M, items=(1, MAX_ITEMS),
        default=OMITTED), Key(
        "altitudes_ft", "numbers", "the same in feet (instead of `altitudes_m`)", "ft",
        (ALTITUDES_M[0] / FT, ALTITUDES_M[1] / FT), items=(1, MAX_ITEMS), default=OMITTED))
    M_D: float | None = spec_field("envelope", Key(
        "M_D", "number", "the design dive Mach number: V_D at each altitude is at most "
        "M_D · a(h) (the row says `mach_limited`)", range=MACHS, default=OMITTED))
    cases: tuple[CaseSpec, ...] = spec_field("", Key(
        "cases", "tables", "the cases: one `[[cases]]` table each (below)", table=CASE,
        items=(1, MAX_ITEMS), must="{fewest} to {most} [[cases]] tables",
        missing="one [[cases]] table per case"))
    V_C: tuple[float, ...] | None = spec_field("envelope", Key(
        "V_C_m_per_s", "number_or_numbers", "`cs25`, `far25` only: the design cruise speed "
        "V_C, always an **equivalent** airspeed (the words of 25.629(b)(2)(ii)), one number or "
        "one per altitude (linear between the altitudes, constant beyond): the failure cases' "
        "envelope (above)", "m/s", SPEEDS, default=OMITTED, items=(1, MAX_ITEMS),
        what="the design cruise speed, an equivalent airspeed [m/s]"), default=None)
    M_C: float | None = spec_field("envelope", Key(
        "M_C", "number", "with `V_C_m_per_s`: the design cruise Mach number; an M_C whose "
        "line is below 1.15 V_C already at −5000 m is an error", range=MACHS,
        default=OMITTED), default=None)
    damping: dict[str, Any] | None = spec_field("regulation", Key(
        "damping", "table", "with `min_damping_g`: how it is read — which damping, from which "
        "speed, which modes, and where that reading comes from: `{ applies_to = ..., source = "
        "... }` (below). Omitted: the total damping of every mode of interest at every analysed "
        "speed (the reading of files written before this key; the report says it was not "
        "stated)", table=DAMPING, default=OMITTED), default=None)


def _table(name: str, title: str, text: str, first: tuple[Key, ...] = (),
           last: tuple[Key, ...] = (), spec: type | None = None) -> TableSpec:
    """The table `name` of a campaign file: `first`, the keys of the fields of `spec`
    (:class:`CampaignSpec`) in it (in field order), `last`."""
    keys = [k for f in dataclasses.fields(spec or CampaignSpec) if f.metadata.get(TABLE) == name
            for k in f.metadata[KEYS]]
    return TableSpec(title, text, first + tuple(k for k in keys if k.key != "cases") + last)


REGULATION = _table("regulation", "[regulation]", "The regulation the campaign clears to.")
ENVELOPE = _table("envelope", "[envelope]", "The envelope points: ISA altitudes and V_D there.")
#: The top level of a campaign file.
TOP = _table("", "Top level", "A whirl-flutter clearance campaign.", (
    Key("format", "string", "the file format", choices=(FORMAT,), must=repr(FORMAT)),
    Key("format_version", "integer", f"this propwhirl reads version {FORMAT_VERSION}",
        range=(FORMAT_VERSION, FORMAT_VERSION), must=f"{FORMAT_VERSION} (this propwhirl reads "
        f"campaign files of version {FORMAT_VERSION})"),
), (Key("regulation", "table", "the regulation: `[regulation]`", table=REGULATION),
    Key("envelope", "table", "the flight envelope: `[envelope]`", table=ENVELOPE),
    CampaignSpec.__dataclass_fields__["cases"].metadata[KEYS][0]))


# =============================================================================== reading
def _regulation(r: Values) -> tuple[str, float]:
    """The regulation and its factor: an explicit one's own, a named one's (a factor given
    with it must be that)."""
    name, t = r["name"], r.table
    if name == EXPLICIT:
        if r["factor"] is None:
            raise t.missing("factor", REGULATION["factor"].what)
        return name, r["factor"]
    factor = REGULATIONS[name].factor
    if r["factor"] is not None and r["factor"] != factor:
        raise t.bad("factor", f"{factor:g} with name = {name!r} (or give name = 'explicit')")
    return name, factor


def _damping(r: Values) -> dict[str, Any] | None:
    """[regulation] damping as a dict (None when omitted): only with min_damping_g; its
    source a non-empty printable text of at most 200 characters."""
    d = r["damping"]
    if d is None:
        return None
    if r["min_damping_g"] is None:
        raise r.table.bad("damping", "absent without min_damping_g (it says how min_damping_g "
                                     "is read)")
    src = d["source"]
    if not src.strip() or not src.isprintable() or len(src) > 200:
        raise d.table.bad("source", "a non-empty printable text of at most 200 characters")
    return dict(d)


def _per_altitude(e: Values, key: str, n: int) -> tuple[float, ...] | None:
    """A speed of the envelope: one (a tuple of one) or one per altitude (`n`)."""
    x = e[key]
    if x is None or not isinstance(x, list):
        return None if x is None else (x,)
    if len(x) != n:
        raise e.table.bad(key, f"one speed, or one per altitude ({n})")
    return tuple(x)


def _envelope(e: Values) -> dict[str, Any]:
    """The [envelope]'s CampaignSpec fields: exactly one altitude key, V_D and V_C one or one
    per altitude, M_C only with V_C."""
    t = e.table
    if (e["altitudes_m"] is None) == (e["altitudes_ft"] is None):
        raise v.InputError(f"[{t.where}] give exactly one of altitudes_m, altitudes_ft")
    alts = e["altitudes_m"] or [h * FT for h in e["altitudes_ft"]]
    V_C = _per_altitude(e, "V_C_m_per_s", len(alts))
    if e["M_C"] is not None and V_C is None:
        raise t.missing("V_C_m_per_s", "M_C needs V_C (the failure-case envelope of "
                                       "25.629(b)(2)(ii))")
    return dict(airspeed=e["airspeed"], V_D=_per_altitude(e, "V_D_m_per_s", len(alts)),
                altitudes_m=tuple(alts), M_D=e["M_D"], V_C=V_C, M_C=e["M_C"])


def _case(c: Values, combine: str) -> CaseSpec:
    """A [[cases]] table's CaseSpec: its own keys and the transformations it gives."""
    t = c.table
    name = c["name"]
    if not name.strip() or not name.isprintable() or len(name) > 200:
        raise t.bad("name", "a non-empty printable name of at most 200 characters")
    if combine == "product" and not c["group"]:
        raise t.missing("group", "every case of combine = 'product' names its group")
    transform = {k.key: _TRANSFORM.get(k.key, lambda x: x)(c[k.key]) for k in CASE.keys
                 if k.key not in CASE_OWN and t.has(k.key)}
    return CaseSpec(t.where, name, c["group"] or "", tuple(c["propellers"] or ()),
                    c["each_propeller"], transform)


def _load(top: Values, base: Path) -> tuple[Any, Path, int]:
    """The campaign's model (a beam or a modal model's file), its path and its number of
    propellers (at least one)."""
    model_key = top["model"]
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
        raise top.table.bad("model", "a propeller-wing model with at least one propeller "
                                     f"({str(path)!r} holds a {type(model).__name__} without "
                                     "any)")
    return model, path, n


def _from_dict(data: dict[str, Any], base: Path, source: str) -> CampaignSpec:
    top = read(Table(data, "", TOP.names), TOP, only=lambda k: k.key != "cases")
    regulation, factor = _regulation(top["regulation"])
    damping = _damping(top["regulation"])
    env = _envelope(top["envelope"])
    if env["V_C"] is not None and regulation not in PART25:
        raise top["envelope"].table.bad(
            "V_C_m_per_s", f"absent with [regulation] name = {regulation!r}: the failure-case "
            "envelope (V_C, M_C) is that of 25.629(b)(2) (cs25, far25); under "
            f"{regulation!r} every case, failure or not, is held to {factor:g} V_D")
    model, path, n = _load(top, base)
    cases = [_case(c, top["combine"]) for c in read(
        top.table, TOP, {"the model's propellers": n}, only=lambda k: k.key == "cases")["cases"]]
    groups: dict[str, int] = {}
    for c in cases:
        groups[c.group] = groups.get(c.group, 0) + (len(c.propellers) or n if c.each_propeller
                                                    else 1)
    count = math.prod(groups.values()) if top["combine"] == "product" else sum(groups.values())
    alts = env["altitudes_m"]
    if count * len(alts) > MAX_TASKS:
        raise v.InputError(f"the cases ({count}) x altitudes ({len(alts)}) make "
                           f"{count * len(alts)} analyses, at most {MAX_TASKS}")
    read_tables = {"": top, "regulation": top["regulation"], "envelope": top["envelope"]}
    values = {f.name: read_tables[f.metadata[TABLE]][f.metadata[KEYS][0].key]
              for f in dataclasses.fields(CampaignSpec)
              if KEYS in f.metadata and f.metadata[KEYS][0].key in read_tables[f.metadata[TABLE]]}
    values.update(env, source=source, name=top["name"] or Path(source).stem, model=model,
                  model_path=str(path), regulation=regulation, factor=factor, cases=tuple(cases),
                  damping=damping)
    return CampaignSpec(**values)      # a field of its key's value, unless tied above


def _regulations_table() -> str:
    """The regulations a campaign names (:data:`propwhirl.certification.REGULATIONS`)."""
    rows = [f"| `{name}` | {r.factor:g} | {r.source} |\n" for name, r in REGULATIONS.items()]
    low, high = FACTOR_RANGE
    rows.append(f"| `{EXPLICIT}` | `factor` in [{low:g}, {high:g}] | whatever your "
                "certification basis says |\n")
    return "| `name` | speed factor | source |\n|---|---|---|\n" + "".join(rows)


def docs_parts() -> dict[str, str]:
    """The generated parts of docs/campaign.md: every table's keys (:data:`TOP`,
    :data:`REGULATION`, :data:`ENVELOPE`, :data:`CASE`, :data:`MASS`) and the regulations."""
    return {"campaign top": markdown(TOP), "campaign regulation": markdown(REGULATION),
            "campaign regulations": _regulations_table(),
            "campaign envelope": markdown(ENVELOPE), "campaign cases": markdown(CASE),
            "campaign added masses": markdown(MASS), "campaign damping": markdown(DAMPING)}


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
