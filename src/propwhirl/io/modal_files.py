"""Modal-model files: a structure's normal modes in an open format (``.npz`` arrays beside a
TOML description), read by :func:`load_modal_model`, written from a beam model by
:func:`write_modes`.  The format is documented in ``docs/modal-structures.md``.

The TOML file (``format = "propwhirl-modal-model"``) states the units (SI only, every one
stated), the modes file and its sizes, the reference-axis grids the strips are splined to,
the strips, the propellers' installations at hub grids, the flight condition and switches,
and the propellers (the ``[propellers.KEY]`` tables of a propwhirl model file).  The ``.npz``
holds six arrays: ``grid_ids`` (int64, n_grids), ``xyz`` (float64, n_grids × 3),
``frequencies_hz``, ``modal_mass``, ``damping_ratio`` (float64, n_modes) and ``shapes``
(float64, n_modes × n_grids × 6).  Its arrays are checked against the sizes the TOML states
before anything is read (:func:`read_arrays`: no pickle, no allocation on the
file's word).  Every problem is one line naming the file, the key and
the id; a file is read whole or not at all.

A NASTRAN SOL 103 OP2 is read into this format by :mod:`propwhirl.io.nastran_op2` (and
written by :func:`save_modal_model`); any other FE code's modes can be written to it.  A
NASTRAN stick model (BDF) is read as a beam model: :mod:`propwhirl.io.nastran_read`.
"""
from __future__ import annotations

import io
import tomllib
from pathlib import Path
from typing import Any

import numpy as np

from propwhirl import fileio, limits
from propwhirl import validate as v
from propwhirl.io import schema
from propwhirl.io.model_files import Table, Writer, from_table, toml_error
from propwhirl.io.tables import OMITTED, Key, TableSpec, markdown, read
from propwhirl.model.aerodynamics.planform import Planform
from propwhirl.model.flight import FlightCondition
from propwhirl.model.modal import (AERO, MOUNTS, ModalInstallation, ModalPropellerWing,
                                  check_hub_grids)
from propwhirl.model.modal_structure import MAX_MODES, ModalStructure, StripPlanform, id_list
from propwhirl.model.modal_surface import MAX_SURFACES, ModalSurface
from propwhirl.model.propellers.propeller import Propeller
from propwhirl.model.structure.wing import DEFAULT_CHORDWISE, DLM_MACH_MAX, DLM_MATCHED
from propwhirl.model.systems import PropellerWing

FORMAT = "propwhirl-modal-model"
FORMAT_VERSION = 1
#: The units a file must state, and the one value each may have (SI).
UNITS = {"length": "m", "mass": "kg", "time": "s", "angle": "rad", "frequency": "Hz"}
#: The strips' keys: (file key, StripPlanform field).
STRIP_KEYS = (("y_m", "y"), ("width_m", "width"), ("chord_m", "chord"),
              ("leading_edge_x_m", "leading_edge_x"), ("elastic_axis", "elastic_axis"),
              ("aerodynamic_centre", "aerodynamic_centre"),
              ("lift_slope_per_rad", "lift_slope"))
ARRAYS = ("grid_ids", "xyz", "frequencies_hz", "modal_mass", "damping_ratio", "shapes")


def _fail(source: str, text: str) -> v.InputError:
    return v.InputError(f"{source}: {text}")


#: Bytes allowed beyond the arrays' own: each .npy header, the zip's directory.
_HEADER_MAX, _ZIP_OVERHEAD = 4096, 65536


def read_arrays(path: Path, expected: dict[str, tuple[tuple[int, ...], np.dtype]],
                where: str, mismatch: str = "", what: str = "modes file"
                ) -> dict[str, np.ndarray]:
    """The arrays of the ``.npz`` at ``path`` (a `what`, e.g. "[modes] file"), each of the
    shape and dtype ``expected``: the file — a regular file of at most the bytes its arrays
    take (:func:`propwhirl.fileio.open_input`, before it is opened) —, its member names, each
    member's declared size and ``.npy`` header are checked before its data is read (within
    :func:`propwhirl.limits.memory_limit`); no pickle.  Anything else: one line starting with
    ``where`` naming the array."""
    import zipfile

    from numpy.lib import format as npf

    n_bytes = {k: int(np.prod(s, dtype=np.int64)) * np.dtype(d).itemsize
               for k, (s, d) in expected.items()}
    limits.check_read(sum(n_bytes.values()), f"{where}: its arrays")
    most = sum(n_bytes.values()) + len(expected) * _HEADER_MAX + _ZIP_OVERHEAD
    try:
        with fileio.open_input(path, what, most, bound=f"its arrays take at most{mismatch}"
                               ) as fh:
            with zipfile.ZipFile(fh) as z:
                names = sorted(i.filename for i in z.infolist())
                if names != sorted(f"{k}.npy" for k in expected):
                    raise v.InputError(f"{where}: holds the arrays "
                                       f"{[n.removesuffix('.npy') for n in names][:10]}, need "
                                       + ", ".join(expected))
                out = {}
                for info in z.infolist():
                    key = info.filename.removesuffix(".npy")
                    shape, dtype = expected[key]
                    if info.file_size > n_bytes[key] + _HEADER_MAX:
                        raise v.InputError(f"{where}: array {key} declares {info.file_size:,} "
                                           f"bytes, expected shape {shape}{mismatch}")
                    with z.open(info) as member:
                        version = npf.read_magic(member)
                        read = (npf.read_array_header_1_0 if version == (1, 0)
                                else npf.read_array_header_2_0)
                        got_shape, fortran, got = read(member)
                    if (tuple(got_shape) != tuple(shape) or got.hasobject
                            or got.str[1:] != np.dtype(dtype).str[1:]):
                        raise v.InputError(f"{where}: array {key} has shape {tuple(got_shape)} "
                                           f"{got}, expected {tuple(shape)} "
                                           f"{np.dtype(dtype)}{mismatch}")
                    with z.open(info) as member:
                        out[key] = np.asarray(npf.read_array(member, allow_pickle=False),
                                              dtype=dtype)
                return out
    except v.InputError as exc:     # fileio's line names the file: `where` only if it is not
        msg = str(exc)
        named = msg.startswith(where) or fileio.quoted(path) in msg
        raise v.InputError(msg if named else f"{where}: {msg}") from None
    except (OSError, ValueError, zipfile.BadZipFile, EOFError, RuntimeError) as exc:
        why = " ".join(str(exc).split())[:200]
        raise v.InputError(f"{where}: cannot read the modes file: {why}") from None


def load_modes(path: str | Path, n_modes: int, n_grids: int, where: str | None = None,
               what: str = "modes file", free: bool = False) -> ModalStructure:
    """The :class:`~propwhirl.model.modal.ModalStructure` of the ``.npz`` at ``path`` (a
    `what`), whose arrays must have the sizes given (checked before reading); errors name
    the file.  ``free``: the structure is free (its plunge, roll and pitch rigid-body
    modes kept, a pitch needing a tail in the model:
    :class:`~propwhirl.model.modal_structure.ModalStructure`)."""
    path = Path(v.file_path("path", path, "a modes file (.npz)"))
    if where is not None and not isinstance(where, str):
        raise v.fail("where", where, "invalid: must be a str (how errors name the file) or None")
    where = str(path) if where is None else where
    nm = v.integer_at_least("n_modes", n_modes, 1)
    ng = v.integer_at_least("n_grids", n_grids, 1)
    expected = {"grid_ids": ((ng,), np.int64), "xyz": ((ng, 3), np.float64),
                "frequencies_hz": ((nm,), np.float64), "modal_mass": ((nm,), np.float64),
                "damping_ratio": ((nm,), np.float64), "shapes": ((nm, ng, 6), np.float64)}
    arrays = read_arrays(path, expected, where,
                         f" (n_modes = {nm}, n_grids = {ng} as the model file states)", what)
    return ModalStructure(**arrays, source=where, free=free)


def modes_path(path: str | Path) -> Path | None:
    """The modes file (``.npz``) the modal model file at ``path`` names (``[modes] file``,
    relative to its folder), None when ``path`` is no readable modal model file or names
    none: the reader then says why."""
    try:
        data = tomllib.loads(fileio.read_text(path, "model file", limit=fileio.MAX_TOML_BYTES))
    except (v.InputError, tomllib.TOMLDecodeError, RecursionError):
        return None
    if not (isinstance(data, dict) and data.get("format") == FORMAT):
        return None
    modes = data.get("modes")
    file = modes.get("file") if isinstance(modes, dict) else None
    return Path(path).parent / file if isinstance(file, str) and file else None


def is_modal_file(path: str | Path) -> bool:
    """Whether the TOML file at ``path`` declares ``format = "propwhirl-modal-model"`` (a file
    that cannot be read or parsed is not: the model-file reader then says why)."""
    try:
        data = tomllib.loads(fileio.read_text(path, "model file", limit=fileio.MAX_TOML_BYTES))
    except (v.InputError, tomllib.TOMLDecodeError, RecursionError):
        return False
    return isinstance(data, dict) and data.get("format") == FORMAT


def load_modal_model(path: str | Path) -> ModalPropellerWing:
    """The :class:`~propwhirl.model.modal.ModalPropellerWing` of the TOML file at ``path``
    and the ``.npz`` it names (relative to the TOML's folder).  Errors: one line starting with
    the file, naming the key (and the grid id) as written.

    The file format (SI units, stated with each key) is in docs/modal-structures.md.

    Parameters
    ----------
    path : str or Path
        The modal model's TOML description.

    Returns
    -------
    ModalPropellerWing
        The model: its modes (frequencies [Hz], modal masses [kg], damping ratios, shapes at
        the grids [m, rad]), strips, propellers, flight condition and switches.

    Raises
    ------
    InputError
        An unreadable file or a bad value, one line naming the file and the key.

    Examples
    --------
    The wingtip model's six lowest wing modes, written by :func:`write_modes` and read back:

    >>> import pathlib, tempfile
    >>> from propwhirl.io import load_modal_model, write_modes
    >>> from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     toml, npz = write_modes(wingtip_propeller_wing(), pathlib.Path(folder) / "m.toml",
    ...                             n_modes=6)
    ...     model = load_modal_model(toml)
    >>> model.structure.n_modes, model.dof_map().q_labels[-2:]
    (6, ('propeller 1 theta', 'propeller 1 psi'))
    >>> from propwhirl.analysis import analyse
    >>> c = analyse(model, speeds=[50.0, 100.0, 150.0, 200.0]).critical
    >>> c.kind, round(c.V)                          # the beam model's: 143.15 m/s
    ('divergence', 143)
    """
    path = Path(v.file_path("path", path, "a modal model file (TOML)"))
    src = str(path)
    text = fileio.read_text(path, "modal model file", limit=fileio.MAX_TOML_BYTES)
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise _fail(src, f"not valid TOML: {toml_error(exc, text)}") from None
    except RecursionError:
        raise limits.nesting_error(src) from None
    limits.check_nesting(data, src)
    try:
        return _from_dict(data, path)
    except v.InputError as exc:
        msg = str(exc)
        raise v.InputError(msg if msg.startswith(src) else f"{src}: {msg}") from None


#: What each unit is of.
_UNIT_OF = {"length": "lengths, positions and translations", "mass": "masses",
            "time": "times", "angle": "angles, rotations and slopes",
            "frequency": "frequencies"}
_SI = ("propwhirl reads SI units only (convert the modes and the strips to "
       + ", ".join(UNITS.values()) + ")")
UNITS_TABLE = TableSpec("[units]", "Every unit stated; SI only.", tuple(
    Key(k, "string", f"the unit of {_UNIT_OF[k]}", choices=(u,), must=f'"{u}": {_SI}',
        missing=f'every unit must be stated; propwhirl reads SI: {k} = "{u}"')
    for k, u in UNITS.items()))
MODES_TABLE = TableSpec("[modes]", "The modes file and its sizes, checked before it is read.", (
    Key("file", "string", "the modes (`.npz`, the arrays above), relative to this file"),
    Key("n_modes", "integer", "the number of modes in the file", range=(1, MAX_MODES)),
    Key("n_grids", "integer", "the number of grids in the file", range=(1, None)),
    Key("wing_grids", "integers", "the reference-axis grids the strips are splined to, root to "
        "tip (ids of the modes file)", items=(2, None),
        must="a list of two or more grid ids (integers)"),
    Key("free", "boolean", "`true`: the structure is free (a whole or half aircraft): its "
        "modes below 0.001 Hz are rigid-body modes, kept when a plunge, a roll or — with a "
        "tail in `surfaces` — a pitch (a pitch without a tail, a yaw, surge or sway is "
        "refused by name); `false`: clamped, none below 0.001 Hz", default=False),
))
STRIPS_TABLE = TableSpec("[strips]", "One entry per strip in each list, all lists of the same "
                         "length.", (
    *(Key(k, "numbers", doc) for k, doc in (
        ("y_m", "stations y [m], increasing, within the span of the grids they are splined "
         "to (`wing_grids`; a surface's `grids`)"),
        ("width_m", "strip widths [m]"),
        ("chord_m", "chords [m]"),
        ("leading_edge_x_m", "x of the leading edge in the wing frame [m]"),
        ("elastic_axis", "the elastic axis, a fraction of the chord aft of the leading edge"),
        ("aerodynamic_centre", "the aerodynamic centre, a fraction of the chord aft of the "
         "leading edge"),
        ("lift_slope_per_rad", "lift-curve slopes [1/rad]"))),
    Key("aero_model", "string", "the strips' unsteady aerodynamics (lag states)",
        choices=("leishman-nguyen", "wagner"), default="leishman-nguyen"),
))
SURFACE = TableSpec("surfaces[i]", "A lifting surface besides the wing (a horizontal tail): "
                    "its strips, as `[strips]` (one entry per strip in each list), splined to "
                    "its own reference-axis grids; a free structure's rigid pitch needs one.", (
    Key("name", "string", "its name: the first word of its strips' lag states (`\"tail strip 1 "
        "w1\"`), each surface its own", default="tail"),
    Key("grids", "integers", "its reference-axis grids, root to tip (ids of the modes file; on "
        "a free structure grids that move with the body)", items=(2, None),
        must="a list of two or more grid ids (integers)"),
    *STRIPS_TABLE.keys,
))
SWITCHES_TABLE = TableSpec("[switches]", "Model switches.", tuple(
    Key(k, "boolean", doc, default=True) for k, doc in (
        ("wing_aero", "the strips' aerodynamics (the wing's and every surface's)"),
        ("propeller_aero", "the propellers' aerodynamics"),
        ("rotating", "the rotors' gyroscopic coupling"))))
DLM_TABLE = TableSpec("[dlm]", "The doublet lattice's lifting surface (as NASTRAN's CAERO1: "
                      "the leading edge and the streamwise chord at two or more spanwise "
                      "stations, linear between them, and the panel counts), in the modes' "
                      "frame, within the wing grids' span; one entry per station in each list.", (
    Key("leading_edge_x_m", "numbers", "x of the leading edge at each station [m]",
        items=(2, None), must="a list of {fewest} or more numbers"),
    Key("leading_edge_y_m", "numbers", "y of each station [m], increasing, >= 0 (y = 0 the "
        "plane of symmetry), within the wing grids' span", items=(2, None),
        must="a list of {fewest} or more numbers"),
    Key("leading_edge_z_m", "numbers", "z of the leading edge at each station [m]; omitted: "
        "0 (a flat planform)", items=(2, None), default=OMITTED,
        must="a list of {fewest} or more numbers"),
    Key("chord_m", "numbers", "the streamwise chord at each station [m], > 0", items=(2, None),
        must="a list of {fewest} or more numbers"),
    Key("chordwise_panels", "integer", "panels along each chord", range=(1, None),
        default=DEFAULT_CHORDWISE),
    Key("spanwise_panels", "integer", "equal panel strips along the span; omitted: the fewest "
        "with a panel aspect ratio (width / length) <= 2", range=(1, None), default=OMITTED),
    Key("mach", "number", "the Mach number of the doublet-lattice loads at every speed; "
        "omitted: V/a at each analysed speed (matched)", range=(0.0, DLM_MACH_MAX),
        default=OMITTED),
))
INSTALLATION = TableSpec("installations[i]", "A propeller at a hub grid.", (
    Key("propeller", "string", "the key of a `[propellers.KEY]` table"),
    Key("grid", "integer", "its hub grid (an id of the modes file)"),
    Key("mount", "string", "`\"flexible\"`, `\"rigid\"` (way a: the propeller's own mount) or "
        "`\"on-grid\"` (way b: rigid on the grid, the mount in the modes)", choices=MOUNTS,
        default="flexible"),
    Key("aero", "boolean", "its aerodynamic loads", default=True),
))
#: The top level of a modal model's description.
TOP = TableSpec("Top level", "A modal propeller-wing: the modes' description.", (
    Key("format", "string", "the file format", choices=(FORMAT,), must=repr(FORMAT)),
    Key("format_version", "integer", f"this propwhirl reads version {FORMAT_VERSION}",
        range=(FORMAT_VERSION, FORMAT_VERSION),
        must=f"{FORMAT_VERSION} (this propwhirl reads version {FORMAT_VERSION} of {FORMAT})"),
    Key("name", "string", "the model's name", default="modal propeller-wing"),
    Key("units", "table", "the units: `[units]`", table=UNITS_TABLE,
        missing="the units must be stated: [units] "
                + ", ".join(f'{k} = "{u}"' for k, u in UNITS.items())),
    Key("modes", "table", "the modes file: `[modes]`", table=MODES_TABLE),
    Key("strips", "table", "the strips: `[strips]`", table=STRIPS_TABLE),
    Key("aero", "string", "the wing aerodynamics: the strips, or the doublet lattice on the "
        "`[dlm]` planform (the strips then the finite-state twin the p-k method tracks with)",
        choices=AERO, default="strip"),
    Key("dlm", "table", "the doublet lattice's planform: `[dlm]` (needed with aero = "
        "\"dlm\")", table=DLM_TABLE, default=OMITTED),
    Key("flight", "model table", "the flight condition, as in a model file "
        "([Model files](model-file.md), `[flight]`)"),
    Key("switches", "table", "model switches: `[switches]`", table=SWITCHES_TABLE,
        default=OMITTED),
    Key("propellers", "model tables", "the propellers, one table `[propellers.KEY]` each, as in "
        "a model file ([Model files](model-file.md))", default=OMITTED),
    Key("installations", "tables", "the propellers at hub grids, one table each: "
        "`installations[i]`", table=INSTALLATION, default=OMITTED,
        must="a list of tables {{propeller, grid, mount, aero}}"),
    Key("surfaces", "tables", "lifting surfaces besides the wing (a tail), one table "
        "`[[surfaces]]` each: `surfaces[i]`; omitted: the wing alone", table=SURFACE,
        items=(0, MAX_SURFACES), default=OMITTED,
        must="a list of at most {most} tables {{name, grids, y_m, width_m, chord_m, ...}}"),
))


def _from_dict(data: dict[str, Any], path: Path) -> ModalPropellerWing:
    """The model of a description read by its schema (:data:`TOP`; the keys that tie
    together checked after: the strips' lengths, a propeller's key, the grids in the modes)."""
    top = read(Table(data, "", TOP.names), TOP)
    modes, strips = top["modes"], top["strips"]
    file = path.parent / modes["file"]
    planform = _strips(strips, f"{path} [strips]")
    surfaces = [(t, _strips(t, f"{path} surfaces[{i}]"))
                for i, t in enumerate(top["surfaces"] or [])]
    flight = from_table(FlightCondition, Table(top["flight"], "flight",
                                               schema.table_keys(FlightCondition)), {})
    ctx = {k: from_table(Propeller, Table(p, f"propellers.{k}", schema.table_keys(Propeller)),
                         {}) for k, p in (top["propellers"] or {}).items()}
    installations = top["installations"] or []
    for t in installations:
        if t["propeller"] not in ctx:
            raise t.table.bad("propeller", "the key of a [propellers.KEY] table ("
                              + (", ".join(ctx) or "none given") + ")")
    # only now the arrays: the description is whole and consistent
    structure = load_modes(file, modes["n_modes"], modes["n_grids"], what="[modes] file",
                           free=modes["free"])
    ids = set(int(i) for i in structure.grid_ids)
    for i, g in enumerate(modes["wing_grids"]):
        if g not in ids:
            raise _fail(str(path), f"[modes] wing_grids[{i}] = {g} is not a grid of {file} "
                        f"(grids {id_list(structure.grid_ids)})")
    check_hub_grids(structure, [t["grid"] for t in installations], "installations")
    switches = {k: top["switches"][k] for k in SWITCHES_TABLE.names}
    dlm_planform, dlm_mach = _dlm_planform(top["dlm"], path)
    if top["aero"] == "dlm" and dlm_planform is None:
        raise _fail(str(path), "aero = \"dlm\" needs the [dlm] table (the doublet lattice's "
                    "planform: leading_edge_x_m, leading_edge_y_m, chord_m)")
    return ModalPropellerWing(
        structure, tuple(modes["wing_grids"]), planform, flight,
        tuple(ModalInstallation(ctx[t["propeller"]], t["grid"], t["mount"], t["aero"])
              for t in installations), name=top["name"], **switches, aero=top["aero"],
        dlm_planform=dlm_planform, dlm_mach=dlm_mach,
        surfaces=tuple(_surface(t, p, i) for i, (t, p) in enumerate(surfaces)))


def _strips(t, source: str) -> StripPlanform:
    """The :class:`StripPlanform` of a table read with the strips' keys (``[strips]``, a
    ``surfaces[i]``): its lists one per strip, as ``y_m``."""
    values = {f: t[k] for k, f in STRIP_KEYS}
    n_strips = len(values["y"])
    for k, f in STRIP_KEYS:
        if len(values[f]) != n_strips:
            raise t.table.bad(k, f"a list of {n_strips} numbers (one per strip, as y_m)")
    return StripPlanform(**{f: np.array(x) for f, x in values.items()},
                         aero_model=t["aero_model"], source=source)


def _surface(t, planform: StripPlanform, i: int) -> ModalSurface:
    """The :class:`ModalSurface` of a ``surfaces[i]`` table read; its errors naming it."""
    try:
        return ModalSurface(grids=tuple(t["grids"]), planform=planform, name=t["name"])
    except v.InputError as exc:
        raise v.InputError(f"[surfaces[{i}]] {exc}") from None


def _dlm_planform(dlm, path: Path) -> tuple[Planform | None, float | str]:
    """The :class:`~propwhirl.model.aerodynamics.planform.Planform` and the Mach setting of a
    ``[dlm]`` table as read (None, "speed" when there is none); the lists' lengths checked."""
    if dlm is None:
        return None, DLM_MATCHED
    n = len(dlm["leading_edge_y_m"])
    z = dlm["leading_edge_z_m"]
    for k in ("leading_edge_x_m", "chord_m") + (("leading_edge_z_m",) if z is not None else ()):
        if len(dlm[k]) != n:
            raise dlm.table.bad(k, f"a list of {n} numbers (one per station, as "
                                "leading_edge_y_m)")
    le = np.stack([dlm["leading_edge_x_m"], dlm["leading_edge_y_m"],
                   np.zeros(n) if z is None else z], axis=1)
    planform = Planform(le, np.array(dlm["chord_m"], float), dlm["chordwise_panels"],
                        dlm["spanwise_panels"], source=f"{path} [dlm]")
    return planform, DLM_MATCHED if dlm["mach"] is None else float(dlm["mach"])


def docs_parts() -> dict[str, str]:
    """The generated parts of docs/modal-structures.md: the description's key tables."""
    return {f"modal {name}": markdown(spec) for name, spec in (
        ("top", TOP), ("units", UNITS_TABLE), ("modes", MODES_TABLE),
        ("strips", STRIPS_TABLE), ("dlm", DLM_TABLE), ("switches", SWITCHES_TABLE),
        ("installations", INSTALLATION), ("surfaces", SURFACE))}


def _check_targets(path: Path, npz: Path) -> None:
    """:func:`write_modes`' outputs: regular files or new paths, apart, and `path` a new path
    or a modal model file (no other file is replaced: the model written from may have been
    read from it)."""
    outputs = [("write_modes: path", path), ("write_modes: its modes file", npz)]
    for label, p in outputs:
        fileio.check_output(p, label)
    fileio.check_apart(outputs)
    if fileio.exists(path, "modal model file") and not is_modal_file(path):
        raise v.InputError(f"write_modes: path {fileio.quoted(path)} exists and is not a modal "
                           f"model file (format = {FORMAT!r}): write_modes replaces only a "
                           "modal model file, never another file such as the beam model's "
                           "own; give another path")


# =============================================================================== writing
def _write_modal_file(path: Path, npz: Path, header: str, dumps, *, name: str, structure,
                      planform, installations, wing_grids, flight, switches,
                      aero: str = "strip", dlm_planform: Planform | None = None,
                      dlm_mach: float | str = DLM_MATCHED, surfaces=()) -> None:
    """The modal model file (TOML at ``path``, ``header`` first) and its modes (``npz``), the
    one document :func:`write_modes` and :func:`save_modal_model` write; ``installations``
    holds (installation, grid, mount) and ``switches`` (wing_aero, propeller_aero,
    rotating); ``aero``, ``dlm_planform`` and ``dlm_mach`` the doublet lattice (written only
    when there is a planform); ``surfaces`` the further lifting surfaces (written only when
    there are some: ``[[surfaces]]``); ``dumps`` is tomli-w's (the callers check the extra and
    the targets)."""
    s = structure
    w = Writer()
    rows = [{"propeller": w.propeller_key(inst.propeller), "grid": int(g), "mount": m,
             "aero": inst.aero} for inst, g, m in installations]
    doc: dict[str, Any] = {
        "format": FORMAT, "format_version": FORMAT_VERSION, "name": name,
        "installations": rows,
        "units": dict(UNITS),
        "modes": {"file": npz.name, "n_modes": s.n_modes, "n_grids": int(s.grid_ids.size),
                  "wing_grids": [int(g) for g in wing_grids],
                  **({"free": True} if s.free else {})},
        "strips": _strip_keys(planform),
        "flight": w.encode(flight, "flight"),
        "switches": dict(zip(("wing_aero", "propeller_aero", "rotating"), switches)),
        "propellers": w.propellers,
    }
    if surfaces:
        doc["surfaces"] = [{"name": surf.name, "grids": [int(g) for g in surf.grids],
                            **_strip_keys(surf.planform)} for surf in surfaces]
    if dlm_planform is not None:
        p = dlm_planform
        doc["aero"] = aero
        doc["dlm"] = {"leading_edge_x_m": [float(x) for x in p.leading_edge[:, 0]],
                      "leading_edge_y_m": [float(x) for x in p.leading_edge[:, 1]],
                      "leading_edge_z_m": [float(x) for x in p.leading_edge[:, 2]],
                      "chord_m": [float(x) for x in p.chord],
                      "chordwise_panels": int(p.chordwise_panels),
                      **({} if p.spanwise_panels is None
                         else {"spanwise_panels": int(p.spanwise_panels)}),
                      **({} if isinstance(dlm_mach, str) else {"mach": float(dlm_mach)})}
    buf = io.BytesIO()
    np.savez(buf, **{k: np.asarray(getattr(s, k), dtype=np.int64 if k == "grid_ids"
                                   else np.float64) for k in ARRAYS})
    fileio.write_bytes(npz, buf.getvalue(), what="modes file")
    fileio.write_text(path, header + dumps(doc), what="modal model file")


def _strip_keys(planform: StripPlanform) -> dict[str, Any]:
    """The strips' keys of a file (``[strips]``, a ``surfaces[i]``) for ``planform``."""
    return {"aero_model": planform.aero_model,
            **{k: [float(x) for x in getattr(planform, f)] for k, f in STRIP_KEYS}}


def write_modes(model: PropellerWing, path: str | Path, n_modes: int | None = None,
                mount: str = "own") -> tuple[Path, Path]:
    """Write ``model`` as a modal model: modes to ``<stem>.modes.npz`` beside ``path``, the
    TOML description to ``path`` (the strips at the wing's nodes, the propellers, the flight
    condition and switches).  Read back with :func:`load_modal_model`.  Returns (TOML path,
    npz path).  Needs tomli-w.

    ``mount = "own"`` (way a): the wing's in-vacuo modes alone (the lowest ``n_modes``,
    default all; :meth:`ModalStructure.from_wing`, one grid per node), every propeller at its
    node's grid with its own mount (a flexible one's pitch and yaw DOFs and springs, and its
    mass, added by the modal model).  ``mount = "on-grid"`` (way b): the modes of the whole
    structure — wing, propeller masses and mount springs (:meth:`ModalStructure.with_mounts`)
    — and every propeller "on-grid" at a hub grid of its own.

    Before anything is computed, ``path`` must be a new path or a modal model file (one
    :func:`write_modes` wrote: any other file there — the beam model's own file above all —
    is refused, not replaced), neither file a device, a FIFO or a socket, and the two not one
    file (:func:`propwhirl.fileio.check_output`, :func:`propwhirl.fileio.check_apart`).

    Parameters
    ----------
    model : PropellerWing
        A beam model (no in-plane bending with ``mount = "on-grid"``).
    path : str or Path
        The TOML description to write; the modes go to ``<stem>.modes.npz`` beside it.
    n_modes : int, optional
        Keep the lowest `n_modes` modes (default all).
    mount : {"own", "on-grid"}
        Way a (the wing's modes, each propeller on its own mount) or way b (the whole
        structure's modes, propellers rigid on hub grids).

    Returns
    -------
    toml : Path
        The TOML description (`path`).
    npz : Path
        The modes (frequencies [Hz], modal masses [kg], damping ratios, shapes [m, rad]).

    Examples
    --------
    >>> import pathlib, tempfile
    >>> from propwhirl.io import write_modes
    >>> from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     toml, npz = write_modes(wingtip_propeller_wing(), pathlib.Path(folder) / "m.toml",
    ...                             n_modes=6)
    ...     written = sorted(p.name for p in pathlib.Path(folder).iterdir())
    >>> written, npz.name
    (['m.modes.npz', 'm.toml'], 'm.modes.npz')
    """
    if not isinstance(model, PropellerWing):
        raise v.InputError(f"write_modes: model is a {type(model).__name__}: only a "
                           "PropellerWing's wing can be written as modes")
    if model.wing.in_plane:
        raise v.InputError("write_modes: the wing has in-plane bending (EI_chordwise): "
                           "modal models carry bending and torsion only")
    try:
        import tomli_w
    except ImportError:
        raise v.InputError("writing a modal model file needs tomli-w: "
                           "pip install propwhirl[toml]") from None
    path = Path(path)
    if mount not in ("own", "on-grid"):
        raise v.InputError(f"write_modes: mount = {mount!r} is invalid: must be 'own' or "
                           "'on-grid'")
    npz = path.with_name(path.name.removesuffix(".toml") + ".modes.npz")
    _check_targets(path, npz)
    wing = model.wing
    if mount == "own":
        s = ModalStructure.from_wing(wing, n_modes)
        grids = [int(1 + node) for node in model.nodes]
        mounts = [inst.mount for inst in model.propellers]
    else:
        s, hubs, _ = ModalStructure.with_mounts(model, n_modes)
        grids, mounts = list(hubs), ["on-grid"] * len(hubs)
    header = (f"# propwhirl modal model: the modes of {model.name!r}'s wing, in {npz.name}\n"
              "# (docs/modal-structures.md: frame x aft, y outboard, z up; SI units)\n")
    _write_modal_file(path, npz, header, tomli_w.dumps, name=f"{model.name} (modal)",
                      structure=s,
                      planform=StripPlanform.from_wing(wing),
                      installations=[(inst, g, m) for inst, g, m in
                                     zip(model.propellers, grids, mounts)],
                      wing_grids=s.grid_ids[:wing.n_nodes], flight=model.flight,
                      switches=(model.wing_aero, model.propeller_aero, model.rotating),
                      aero=wing.aero,
                      dlm_planform=Planform.from_wing(wing) if wing.aero == "dlm" else None,
                      dlm_mach=wing.dlm_mach)
    return path, npz


def save_modal_model(model: ModalPropellerWing, path: str | Path) -> tuple[Path, Path]:
    """Write a :class:`~propwhirl.model.modal.ModalPropellerWing` (its modes, wing grids,
    strips, further surfaces, installations, flight condition, switches and propellers) as a
    modal model file: the modes to ``<stem>.modes.npz`` beside ``path``, the TOML
    description to ``path``, in the format :func:`load_modal_model` reads (docs/modal-structures.md).  The targets are
    checked as :func:`write_modes` checks them (a new path or a modal model file; regular
    files; apart).  Needs tomli-w.

    Parameters
    ----------
    model : ModalPropellerWing
        The modal model (e.g. :func:`propwhirl.io.nastran_op2.read_op2`'s).
    path : str or Path
        The TOML description to write.

    Returns
    -------
    toml : Path
        The TOML description (`path`).
    npz : Path
        The modes (frequencies [Hz], modal masses [kg], damping ratios, shapes [m, rad]).

    Examples
    --------
    >>> import pathlib, tempfile
    >>> from propwhirl.io import load_modal_model, write_modes
    >>> from propwhirl.io.modal_files import save_modal_model
    >>> from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     toml, _ = write_modes(wingtip_propeller_wing(), pathlib.Path(folder) / "a.toml",
    ...                           n_modes=6)
    ...     model = load_modal_model(toml)
    ...     again, _ = save_modal_model(model, pathlib.Path(folder) / "b.toml")
    ...     back = load_modal_model(again)
    >>> bool((back.structure.shapes == model.structure.shapes).all()), back.wing_grids[:3]
    (True, (1, 2, 3))
    """
    if not isinstance(model, ModalPropellerWing):
        raise v.InputError(f"save_modal_model: model is a {type(model).__name__}: it must be "
                           "a ModalPropellerWing (a beam model: write_modes)")
    try:
        import tomli_w
    except ImportError:
        raise v.InputError("writing a modal model file needs tomli-w: "
                           "pip install propwhirl[toml]") from None
    path = Path(path)
    npz = path.with_name(path.name.removesuffix(".toml") + ".modes.npz")
    _check_targets(path, npz)
    header = (f"# propwhirl modal model {model.name!r}: its modes in {npz.name}\n"
              "# (docs/modal-structures.md: frame x aft, y outboard, z up; SI units)\n")
    _write_modal_file(path, npz, header, tomli_w.dumps, name=model.name,
                      structure=model.structure,
                      planform=model.planform,
                      installations=[(inst, int(inst.grid), inst.mount)
                                     for inst in model.propellers],
                      wing_grids=model.wing_grids, flight=model.flight,
                      switches=(model.wing_aero, model.propeller_aero, model.rotating),
                      aero=model.aero, dlm_planform=model.dlm_planform,
                      dlm_mach=model.dlm_mach, surfaces=model.surfaces)
    return path, npz
