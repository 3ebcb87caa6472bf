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
from propwhirl.model.flight import FlightCondition
from propwhirl.model.modal import MOUNTS, ModalInstallation, ModalPropellerWing
from propwhirl.model.modal_structure import MAX_MODES, ModalStructure, StripPlanform, id_list
from propwhirl.model.propellers.propeller import Propeller
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
               what: str = "modes file") -> ModalStructure:
    """The :class:`~propwhirl.model.modal.ModalStructure` of the ``.npz`` at ``path`` (a
    `what`), whose arrays must have the sizes given (checked before reading); errors name
    the file."""
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
    return ModalStructure(**arrays, source=where)


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


def _from_dict(data: dict[str, Any], path: Path) -> ModalPropellerWing:
    top = Table(data, "", ("format", "format_version", "name", "units", "modes", "strips",
                           "installations", "flight", "switches", "propellers"))
    if top.string("format") != FORMAT:
        raise top.bad("format", repr(FORMAT))
    version = top.integer("format_version")
    if version != FORMAT_VERSION:
        raise top.bad("format_version", f"{FORMAT_VERSION} (this propwhirl reads version "
                      f"{FORMAT_VERSION} of {FORMAT})")
    name = top.string("name") if top.has("name") else "modal propeller-wing"
    if not top.has("units"):
        raise top.missing("units", "the units must be stated: [units] "
                          + ", ".join(f'{k} = "{u}"' for k, u in UNITS.items()))
    units = top.sub("units", tuple(UNITS))
    for key, unit in UNITS.items():
        if not units.has(key):
            raise units.missing(key, f"every unit must be stated; propwhirl reads SI: "
                                f'{key} = "{unit}"')
        if units.string(key) != unit:
            raise units.bad(key, f'"{unit}": propwhirl reads SI units only (convert the modes '
                            "and the strips to " + ", ".join(UNITS.values()) + ")")
    modes = top.sub("modes", ("file", "n_modes", "n_grids", "wing_grids"))
    file = path.parent / modes.string("file")
    n_modes, n_grids = modes.integer("n_modes"), modes.integer("n_grids")
    for key, n, most in (("n_modes", n_modes, MAX_MODES), ("n_grids", n_grids, None)):
        if n < 1 or (most is not None and n > most):
            raise modes.bad(key, f"an integer in [1, {most}]" if most else "an integer >= 1")
    raw_grids = modes.raw("wing_grids")
    if (not isinstance(raw_grids, list) or len(raw_grids) < 2
            or any(isinstance(g, bool) or not isinstance(g, int) for g in raw_grids)):
        raise modes.bad("wing_grids", "a list of two or more grid ids (integers)")
    strips_t = top.sub("strips", ("aero_model",) + tuple(k for k, _ in STRIP_KEYS))
    values = {f: strips_t.numbers(k) for k, f in STRIP_KEYS}
    n_strips = len(values["y"])
    for k, f in STRIP_KEYS:
        if len(values[f]) != n_strips:
            raise strips_t.bad(k, f"a list of {n_strips} numbers (one per strip, as y_m)")
    aero_model = (strips_t.string("aero_model", choices=("leishman-nguyen", "wagner"))
                  if strips_t.has("aero_model") else "leishman-nguyen")
    flight = from_table(FlightCondition, top.sub("flight", _keys(FlightCondition)), {})
    switches = {"wing_aero": True, "propeller_aero": True, "rotating": True}
    if top.has("switches"):
        sw = top.sub("switches", tuple(switches))
        for k in switches:
            if sw.has(k):
                switches[k] = sw.boolean(k)
    props_raw = data.get("propellers", {})
    if not isinstance(props_raw, dict):
        raise top.bad("propellers", "tables [propellers.KEY]")
    ctx = {k: from_table(Propeller, Table(p, f"propellers.{k}", _keys(Propeller)), {})
           for k, p in props_raw.items()}
    raw_inst = data.get("installations", [])
    if not isinstance(raw_inst, list):
        raise top.bad("installations", "a list of tables {propeller, grid, mount, aero}")
    inst_tables = [Table(t, f"installations[{j}]", ("propeller", "grid", "mount", "aero"))
                   for j, t in enumerate(raw_inst)]
    for t in inst_tables:
        if t.string("propeller") not in ctx:
            raise t.bad("propeller", "the key of a [propellers.KEY] table ("
                        + (", ".join(ctx) or "none given") + ")")
    # only now the arrays: the description is whole and consistent
    structure = load_modes(file, n_modes, n_grids, what="[modes] file")
    ids = set(int(i) for i in structure.grid_ids)
    for i, g in enumerate(raw_grids):
        if g not in ids:
            raise _fail(str(path), f"[modes] wing_grids[{i}] = {g} is not a grid of {file} "
                        f"(grids {id_list(structure.grid_ids)})")
    installations = []
    for j, t in enumerate(inst_tables):
        g = t.integer("grid")
        if g not in ids:
            raise _fail(str(path), f"installations[{j}].grid = {g} is not a grid of {file}: "
                        f"the modes have no hub grid {g} (grids {id_list(structure.grid_ids)})")
        mount = t.string("mount", choices=MOUNTS) if t.has("mount") else "flexible"
        aero = t.boolean("aero") if t.has("aero") else True
        installations.append(ModalInstallation(ctx[t.string("propeller")], g, mount, aero))
    planform = StripPlanform(**{f: np.array(x) for f, x in values.items()},
                             aero_model=aero_model, source=f"{path} [strips]")
    try:
        return ModalPropellerWing(structure, tuple(raw_grids), planform, flight,
                                  tuple(installations), name=name, **switches)
    except v.InputError as exc:     # the model's own names → the file's keys
        raise v.InputError(str(exc).replace("propellers[", "installations[")) from None


def _keys(cls: type) -> tuple[str, ...]:
    return schema.table_keys(cls)


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
    planform = StripPlanform.from_wing(wing)
    w = Writer()
    installations = [{"propeller": w.propeller_key(inst.propeller), "grid": g, "mount": m,
                      "aero": inst.aero}
                     for inst, g, m in zip(model.propellers, grids, mounts)]
    doc: dict[str, Any] = {
        "format": FORMAT, "format_version": FORMAT_VERSION, "name": f"{model.name} (modal)",
        "installations": installations,
        "units": dict(UNITS),
        "modes": {"file": npz.name, "n_modes": s.n_modes, "n_grids": int(s.grid_ids.size),
                  "wing_grids": [int(g) for g in s.grid_ids[:wing.n_nodes]]},
        "strips": {"aero_model": planform.aero_model,
                   **{k: [float(x) for x in getattr(planform, f)] for k, f in STRIP_KEYS}},
        "flight": w.encode(model.flight, "flight"),
        "switches": {"wing_aero": model.wing_aero, "propeller_aero": model.propeller_aero,
                     "rotating": model.rotating},
        "propellers": w.propellers,
    }
    buf = io.BytesIO()
    np.savez(buf, **{k: np.asarray(getattr(s, k), dtype=np.int64 if k == "grid_ids"
                                   else np.float64) for k in ARRAYS})
    fileio.write_bytes(npz, buf.getvalue(), what="modes file")
    header = (f"# propwhirl modal model: the modes of {model.name!r}'s wing, in {npz.name}\n"
              "# (docs/modal-structures.md: frame x aft, y outboard, z up; SI units)\n")
    fileio.write_text(path, header + tomli_w.dumps(doc), what="modal model file")
    return path, npz


def save_modal_model(model: ModalPropellerWing, path: str | Path) -> tuple[Path, Path]:
    """Write a :class:`~propwhirl.model.modal.ModalPropellerWing` (its modes, wing grids,
    strips, installations, flight condition, switches and propellers) as a modal model file:
    the modes to ``<stem>.modes.npz`` beside ``path``, the TOML description to ``path``, in
    the format :func:`load_modal_model` reads (docs/modal-structures.md).  The targets are
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
    s, planform = model.structure, model.planform
    w = Writer()
    installations = [{"propeller": w.propeller_key(inst.propeller), "grid": int(inst.grid),
                      "mount": inst.mount, "aero": inst.aero} for inst in model.propellers]
    doc: dict[str, Any] = {
        "format": FORMAT, "format_version": FORMAT_VERSION, "name": model.name,
        "installations": installations,
        "units": dict(UNITS),
        "modes": {"file": npz.name, "n_modes": s.n_modes, "n_grids": int(s.grid_ids.size),
                  "wing_grids": [int(g) for g in model.wing_grids]},
        "strips": {"aero_model": planform.aero_model,
                   **{k: [float(x) for x in getattr(planform, f)] for k, f in STRIP_KEYS}},
        "flight": w.encode(model.flight, "flight"),
        "switches": {"wing_aero": model.wing_aero, "propeller_aero": model.propeller_aero,
                     "rotating": model.rotating},
        "propellers": w.propellers,
    }
    buf = io.BytesIO()
    np.savez(buf, **{k: np.asarray(getattr(s, k), dtype=np.int64 if k == "grid_ids"
                                   else np.float64) for k in ARRAYS})
    fileio.write_bytes(npz, buf.getvalue(), what="modes file")
    header = (f"# propwhirl modal model {model.name!r}: its modes in {npz.name}\n"
              "# (docs/modal-structures.md: frame x aft, y outboard, z up; SI units)\n")
    fileio.write_text(path, header + tomli_w.dumps(doc), what="modal model file")
    return path, npz
