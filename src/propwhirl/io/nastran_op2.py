"""NASTRAN modes in: :func:`read_op2` makes a modal model of a SOL 103 OP2's eigenvectors.

pyNastran (the optional extra ``nastran``, in an environment of its own: it needs numpy < 2)
reads the OP2 (``read_op2_geom``: the results and the geometry tables); everything else is
here, and every problem is one line naming the file, the table or grid and its id, a model
returned whole or not at all.

What maps to what (docs/modal-structures.md, "Modes from an OP2"):

* **the modes** — the real eigenvectors (OUGV1/BOUGV1, ``op2.eigenvectors``) of one subcase:
  each mode's six components at every GRID (scalar points are left out, said in a note),
  its eigenvalue λ = ω² [1/s²] (f = √λ / 2π), in the deck's units (``units``, as for a BDF:
  NASTRAN has none), turned into the basic frame where a GRID's displacement frame (CD) is a
  CORD2R of its own, and converted to SI: translations × the length unit, rotations as they
  are; the generalised masses of the eigenvalue table (LAMA) × mass unit × length unit²
  (φᵀMφ with φ in SI), or 1 kg where the user states that the eigenvectors are
  mass-normalised (EIGRL NORM=MASS, NASTRAN's default) and the OP2 has no LAMA;
* **the grids** — their positions from the OP2's geometry (GEOM1, written with
  ``PARAM,POST,-1``; single precision), CP frames resolved, in the basic frame, which is the
  wing frame (x aft, y outboard, z up, as for a BDF);
* **the damping** — an OP2 has none: the base wing's Rayleigh damping,
  ζ_i = (μ/ω_i + λ ω_i)/2 (``damping="rayleigh"``, the default, as the BDF route takes it), or
  one ratio for every mode, or one per mode;
* **what an OP2 cannot say** — from ``base``, a beam model: the strips (the base wing's, at
  its nodes, their elastic axis put on the line of the ``wing_grids``), the flight
  condition, the switches and every propeller, each at its hub grid (``hubs``, in the
  base's order) either "on-grid" (its mass and mount are in the modes: way b, the usual case
  of a FE model with nacelles) or with the base's own mount (``mount="own"``: the modes are
  the bare wing's).  The strips are an unswept wing's: wing grids whose line is swept by more
  than :data:`~propwhirl.model.modal_structure.STRIP_SWEEP_LIMIT_DEG` are refused with them
  (the model's :func:`~propwhirl.model.modal_structure.check_strip_sweep`: the doublet lattice
  takes a swept wing), and read with a base whose wing aerodynamics are off.

**Free structures.** A free aircraft's SOL 103 (no SPC: a whole or half aircraft, symmetric or
antisymmetric) has rigid-body modes, at λ ≈ 0.  A clamped structure (the default) has none:
any mode below :data:`propwhirl.model.modal_structure.RIGID_BODY_HZ` is refused, naming it.
With ``free=True`` the modes below ``rigid_body_hz`` (default :data:`RIGID_BODY_HZ_FREE`; at
most six of them, else a mechanism is refused) are **left out** and a note says so: the
analysis then runs on the free structure's elastic modes with its rigid-body coordinates held
at zero — the body's mean axes fixed in space, the limit of a body much heavier than the wing
(docs/validation.md, "Free-free structures", has the table: the elastic instabilities of a
heavy fuselage's model equal the clamped wing's, a light fuselage's do not).  The rigid-body
modes themselves are not analysed (their flight mechanics needs aerodynamics on every
surface that holds the body — a tail where pitch is free, ``surfaces`` — and with the wing
alone only plunge and roll are physical freedoms).  With
``keep_rigid=True`` too they are kept — at 0 Hz, undamped, the strips' aerodynamics on them —
when each is a plunge or a roll, or a pitch where ``surfaces`` gives a tail (a second lifting
surface on grids of the OP2); a yaw (no fin), surge or sway, or a pitch without a tail, is
refused naming the mode (:mod:`propwhirl.model.rigid_body`).
"""
from __future__ import annotations

import contextlib
import io
import warnings
from dataclasses import replace
from pathlib import Path
from typing import Sequence

import numpy as np

from propwhirl import fileio
from propwhirl import validate as v
from propwhirl.io.nastran import INSTALL_HINT, UnitSystem, unit_system
from propwhirl.io import nastran_read
from propwhirl.io.nastran_deck import fail
from propwhirl.model.modal import ModalPropellerWing
from propwhirl.model.modal_surface import ModalSurface
from propwhirl.model.modal_structure import (MAX_MODES, RIGID_BODY_HZ, ModalStructure,
                                             StripPlanform, id_list)
from propwhirl.model.systems import PropellerWing

#: Default frequency [Hz] below which a free structure's modes are rigid-body modes: far above
#: a FE solution's numerical zeros (~1e-4 Hz), far below any aircraft's elastic modes (> 1 Hz).
RIGID_BODY_HZ_FREE = 0.1
#: Largest OP2 read [bytes]: pyNastran reads the whole file into memory; a SOL 103 OP2 of a
#: whole aircraft's eigenvectors (10⁵ grids × 6 × 200 modes in single precision: 0.5 GB) fits,
#: a /dev/zero or a results database of every load case is refused before it is opened.
MAX_OP2_BYTES = 2 * 2 ** 30
#: Most rigid-body modes a free structure has (three translations, three rotations).
MAX_RIGID_BODY_MODES = 6
#: How ``mount`` places the base's propellers on their hub grids.
MOUNT_CHOICES = ("on-grid", "own")
#: Relative resolution of an OP2's single-precision geometry (4 ulp of float32).
_SINGLE = 4.0 * float(np.finfo(np.float32).eps)
#: pyNastran's grid type of a GRID in ``node_gridtype`` (others: scalar and extra points).
_GRID_TYPE = 1


def _read(path: Path, where: str):
    """pyNastran's OP2 (results and geometry) of the file, its messages off the terminal;
    any failure (a truncated or foreign file) one line naming the file."""
    try:
        from pyNastran.op2.op2_geom import read_op2_geom
    except ImportError:
        raise v.InputError(f"reading an OP2 needs pyNastran, which is not installed here: "
                           f"{INSTALL_HINT}") from None
    chatter = io.StringIO()
    try:
        with contextlib.redirect_stdout(chatter), contextlib.redirect_stderr(chatter), \
                warnings.catch_warnings():
            warnings.simplefilter("ignore")
            return read_op2_geom(str(path), debug=None, log=None, build_dataframe=False,
                                 skip_undefined_matrices=True)
    except (KeyboardInterrupt, MemoryError):
        raise
    except Exception as exc:              # a third-party parser: every failure is the file's
        first = (str(exc).strip().split("\n")[0].strip() or type(exc).__name__)[:200]
        raise fail(where, f"cannot read the OP2 (truncated, or not an OP2 of NASTRAN's "
                           f"MSC/NX format): {type(exc).__name__}: {first}") from None


def _subcase(op2, subcase: int | None, where: str):
    """The eigenvector table of the subcase asked, or of the only one."""
    vectors = getattr(op2, "eigenvectors", {}) or {}
    if not vectors:
        raise fail(where, "holds no real eigenvectors (OUGV1): write the OP2 of a SOL 103 "
                           "(normal modes) with DISPLACEMENT(PLOT) = ALL")
    keys = sorted(vectors)
    if subcase is None:
        if len(keys) > 1:
            raise fail(where, f"holds the eigenvectors of subcases {keys}: choose one "
                               "(--subcase; Python: subcase=...)")
        return vectors[keys[0]]
    if subcase not in vectors:
        raise fail(where, f"subcase {subcase} is not in the file (its eigenvectors: subcases "
                           f"{keys})")
    return vectors[subcase]


def _frame(op2, cid: int, by: str, where: str, u: UnitSystem):
    """(origin [m], axes rows) of CORD2R ``cid`` of the OP2's geometry, in the basic frame."""
    if cid == 0:
        return np.zeros(3), np.eye(3)
    coord = op2.coords.get(cid)
    if coord is None:
        raise fail(where, f"{by} refers to coordinate system {cid}, which is not in the OP2's "
                           "geometry")
    if coord.type != "CORD2R":
        raise fail(where, f"{coord.type} {cid}: not read: coordinate systems are CORD2R")
    if int(coord.rid or 0) != 0:
        raise fail(where, f"CORD2R {cid} is given in CORD2R {coord.rid}: the OP2 route reads "
                           "coordinate systems given in the basic one (RID = 0)")
    a, b, c = (np.asarray(p, dtype=float) for p in (coord.e1, coord.e2, coord.e3))
    axes = nastran_read.cord2r_axes(a, b, c)
    if axes is None:
        raise fail(where, f"CORD2R {cid}: its points A, B, C do not define axes (on one line)")
    return a * u.length, axes


def _geometry(op2, ids: np.ndarray, where: str, u: UnitSystem
              ) -> tuple[np.ndarray, list[np.ndarray | None]]:
    """Every grid's basic position [m] and its displacement frame's axes (None: basic)."""
    nodes = getattr(op2, "nodes", {}) or {}
    if not nodes:
        raise fail(where, "holds no grid geometry (GEOM1): write the OP2 with PARAM,POST,-1 "
                           "so that it has the grids' positions")
    xyz = np.zeros((ids.size, 3))
    turned: list[np.ndarray | None] = []
    for i, nid in enumerate(ids):
        g = nodes.get(int(nid))
        if g is None:
            raise fail(where, f"GRID {nid} has eigenvector components but no position in the "
                               "OP2's geometry (GEOM1)")
        by = f"GRID {nid}"
        o, R = _frame(op2, int(g.cp or 0), by, where, u)
        xyz[i] = o + R.T @ (np.asarray(g.xyz, dtype=float) * u.length)
        cd = int(g.cd or 0)
        if cd < 0:
            raise fail(where, f"{by}: CD = {cd} (a fluid grid): not read")
        axes = _frame(op2, cd, by, where, u)[1] if cd else None
        turned.append(None if axes is None or np.allclose(axes, np.eye(3), rtol=0.0,
                                                          atol=1e-12) else axes)
    return xyz, turned


def _generalised_masses(op2, n: int, modes: np.ndarray, mass_normalised: bool,
                        where: str) -> np.ndarray:
    """The generalised mass of each mode (deck units) from the eigenvalue table (LAMA), or 1
    where the user states that the eigenvectors are mass-normalised."""
    tables = [t for t in (getattr(op2, "eigenvalues", {}) or {}).values()
              if hasattr(t, "generalized_mass")]
    if tables:
        t = tables[0]
        by_mode = {int(m): float(g) for m, g in zip(t.mode, t.generalized_mass)}
        missing = [int(m) for m in modes if int(m) not in by_mode]
        if missing:
            raise fail(where, f"mode {missing[0]} has an eigenvector but no line in the "
                               "eigenvalue table (LAMA)")
        return np.array([by_mode[int(m)] for m in modes])
    if not mass_normalised:
        raise fail(where, "holds no eigenvalue table (LAMA): the generalised masses are not "
                           "known; if the eigenvectors are mass-normalised (EIGRL NORM=MASS, "
                           "NASTRAN's default) say so (--mass-normalised; Python: "
                           "mass_normalised=True)")
    return np.ones(n)


def _grids_arg(name: str, grids, where: str) -> tuple[int, ...]:
    grids = tuple(grids or ())
    for g in grids:
        if isinstance(g, (bool, np.bool_)) or not isinstance(g, (int, np.integer)) or g <= 0:
            raise fail(where, f"{name} grid {g!r} is invalid: grid ids are integers > 0")
    return tuple(int(g) for g in grids)


def _check_span(xyz: np.ndarray, wing_idx: list[int], wing_ids: tuple[int, ...], base,
                u, where: str, notes: list[str]) -> None:
    """The wing grids' span (root to tip, in SI as read in the stated units) against the base
    wing's semi-span, whose strips they carry: off by a factor of 2 or more is refused as
    units not the OP2's (the unit systems' lengths differ by 25.4 or more: no modelling
    difference is that large), more than 1 % noted."""
    span = float(xyz[wing_idx[-1], 1] - xyz[wing_idx[0], 1])
    if not span > 0.0:
        return                       # the model's check names the grids out of order
    L = float(base.wing.semi_span)
    text = (f"wing GRID {wing_ids[0]} to GRID {wing_ids[-1]} span {span:.6g} m (read in "
            f"{u.name} units: {u.description}), the base model's wing {L:.6g} m")
    if not 0.5 <= span / L <= 2.0:
        raise fail(where, f"{text}: are the OP2's units {u.name}, and not mixed?")
    if abs(span / L - 1.0) > 0.01:
        notes.append(f"{where}: {text}: the strips are the base's, splined to the grids")


def _in_modes(ids: np.ndarray, grid: int, what: str, where: str) -> int:
    hit = np.flatnonzero(ids == grid)
    if not hit.size:
        raise fail(where, f"{what} GRID {grid} is not in the modes (the eigenvectors' grids: "
                           f"{id_list(ids)})")
    return int(hit[0])


def _kept_modes(freq: np.ndarray, modes: np.ndarray, free: bool, rigid_body_hz: float,
                where: str, notes: list[str], keep_rigid: bool = False) -> np.ndarray:
    """Indices of the modes kept: every one of a clamped structure (none may be rigid), the
    elastic ones of a free structure (its rigid-body modes, below ``rigid_body_hz``, left
    out and said), or with ``keep_rigid`` all of a free structure's."""
    if not free:
        low = np.flatnonzero(freq < RIGID_BODY_HZ)
        if low.size:
            i = int(low[0])
            raise fail(where, f"mode {int(modes[i])} ({freq[i]:.3g} Hz) is a rigid-body mode: "
                               "a clamped structure has none; if the structure is free (a "
                               "whole or half aircraft) say so (--free; Python: free=True): its "
                               f"rigid-body modes, below {RIGID_BODY_HZ_FREE:g} Hz "
                               "(--rigid-below), are then left out")
        return np.arange(freq.size)
    rigid = np.flatnonzero(freq < rigid_body_hz)
    if rigid.size > MAX_RIGID_BODY_MODES:
        raise fail(where, f"{rigid.size} modes below {rigid_body_hz:g} Hz (modes "
                           f"{id_list(modes[rigid])}): a free body has at most "
                           f"{MAX_RIGID_BODY_MODES} rigid-body modes; the others are a "
                           "mechanism of the FE model (or lower --rigid-below)")
    if rigid.size and keep_rigid:
        notes.append(f"{where}: the structure is free: its {rigid.size} rigid-body mode(s) "
                     f"below {rigid_body_hz:g} Hz (mode(s) {id_list(modes[rigid])}) kept at "
                     "0 Hz, undamped (each a plunge or a roll: docs/modal-structures.md, "
                     "'Free structures')")
        return np.arange(freq.size)
    if rigid.size:
        notes.append(f"{where}: the structure is free: its {rigid.size} rigid-body mode(s) "
                     f"below {rigid_body_hz:g} Hz (mode(s) {id_list(modes[rigid])}) left out; "
                     "the analysis holds the body's mean axes fixed (the heavy-body limit: "
                     "docs/modal-structures.md, 'Free structures')")
    else:
        notes.append(f"{where}: --free, but no mode below {rigid_body_hz:g} Hz: the "
                     "structure has no rigid-body mode (is it free?)")
    return np.flatnonzero(freq >= rigid_body_hz)


def _damping(damping, base: PropellerWing, omega: np.ndarray, where: str,
             rigid: np.ndarray | None = None) -> np.ndarray:
    if isinstance(damping, str) and damping == "rayleigh":
        mu, lam = base.wing.rayleigh
        if rigid is not None and rigid.any():    # kept rigid-body modes: undamped
            w = np.where(rigid, 1.0, omega)
            return np.where(rigid, 0.0, 0.5 * (mu / w + lam * w))
        return 0.5 * (mu / omega + lam * omega)
    if isinstance(damping, (list, tuple, np.ndarray)):
        z = np.asarray(damping, dtype=float) if all(
            isinstance(x, (int, float, np.floating, np.integer))
            and not isinstance(x, (bool, np.bool_)) for x in damping) else None
        if z is None or z.shape != omega.shape or not np.all((z >= 0) & (z < 1)):
            raise fail(where, f"damping has {len(damping)} values: give one modal damping "
                               f"ratio in [0, 1) per mode kept ({omega.size})")
        return z
    if (isinstance(damping, (bool, np.bool_)) or not isinstance(damping, (int, float))
            or not 0.0 <= float(damping) < 1.0):
        raise fail(where, f"damping = {v.short_repr(damping)} is invalid: must be 'rayleigh' "
                           "(the base wing's) or a modal damping ratio in [0, 1)")
    return np.full(omega.size, float(damping))


def _planform(base: PropellerWing, xyz: np.ndarray, wing_idx: list[int]) -> StripPlanform:
    """The base wing's strips at its nodes, their elastic axis on the wing grids' line (its x
    linear in y between the grids)."""
    p = StripPlanform.from_wing(base.wing)
    y, x = xyz[wing_idx, 1], xyz[wing_idx, 0]
    if not np.all(np.diff(y) > 0):
        return p                     # the model's check names the grids out of order
    # an OP2's geometry is single precision (relative 6e-8): a strip at the base's tip or
    # root station, outside the grids' span by less than that, is put on the end grid
    slack = _SINGLE * max(abs(y[0]), abs(y[-1]), 1.0)
    ys = np.where((p.y > y[-1]) & (p.y <= y[-1] + slack), y[-1], p.y)
    ys = np.where((ys < y[0]) & (ys >= y[0] - slack), y[0], ys)
    return replace(p, y=ys, leading_edge_x=p.leading_edge_x + np.interp(ys, y, x))


def read_op2(path: str | Path, *, units: str | None = None, base=None,
             hubs: Sequence[int] = (), wing_grids: Sequence[int] = (),
             mount: str = "on-grid", n_modes: int | None = None, damping="rayleigh",
             subcase: int | None = None, free: bool = False,
             rigid_body_hz: float = RIGID_BODY_HZ_FREE, mass_normalised: bool = False,
             notes: list[str] | None = None, keep_rigid: bool = False,
             surfaces: Sequence[ModalSurface] = ()) -> ModalPropellerWing:
    """The modal model of a NASTRAN SOL 103 OP2's modes (the module docstring says what maps
    to what).

    Parameters
    ----------
    path : str or Path
        The OP2 (MSC or NX format), with the eigenvectors of a SOL 103 and its geometry
        (``PARAM,POST,-1``).
    units : str
        The deck's unit system, one of "si", "mm-t-s", "in-lbf-s" (NASTRAN has none).
    base : PropellerWing
        What an OP2 cannot say: the strips, the flight condition, the switches, the
        propellers (its structure is replaced by the modes; each installation's ``rotation``
        override applied, a stopped or feathered one refused: a modal model's propellers
        operate, as the BDF route's swept stick).
    hubs : sequence of int
        The hub grid of each of ``base``'s installations, in their order.
    wing_grids : sequence of int
        The reference-axis grids the strips are splined to, root to tip (two or more).
    mount : {"on-grid", "own"}
        "on-grid": each propeller rigid on its hub grid, its mass and mount in the modes (a FE
        model with the nacelles); "own": the base's own mount of each propeller on its hub
        grid (the modes are the bare wing's).
    n_modes : int, optional
        Keep the lowest ``n_modes`` elastic modes (default all).
    damping : "rayleigh", float or sequence of float
        The modal damping ratios: the base wing's Rayleigh damping, one ratio in [0, 1) for
        every mode, or one per mode kept (e.g. a TABDMP1's values at the modes' frequencies).
    subcase : int, optional
        The subcase whose eigenvectors are read (default: the only one).
    free : bool
        The structure is free (rigid-body modes expected and left out; module docstring).
    rigid_body_hz : float
        [Hz] With ``free``: the modes below this are rigid-body modes (at most six).
    keep_rigid : bool
        With ``free``: the rigid-body modes are kept (at 0 Hz, undamped) instead of left
        out, each a plunge, a roll or — with a tail in ``surfaces`` — a pitch (a yaw, surge or
        sway, or a pitch without a tail, is refused naming the mode:
        :mod:`propwhirl.model.rigid_body`).
    surfaces : sequence of ModalSurface
        Lifting surfaces besides the wing on grids of the OP2 (a tail:
        :class:`~propwhirl.model.modal_surface.ModalSurface`, its grids' ids as in the deck,
        its strips in SI), e.g. to keep a free aircraft's rigid pitch.
    mass_normalised : bool
        The eigenvectors are mass-normalised (generalised masses 1); needed only when the OP2
        has no eigenvalue table (LAMA), whose generalised masses are used otherwise.
    notes : list of str, optional
        Receives a line per thing left out (rigid-body modes, scalar points).

    Returns
    -------
    ModalPropellerWing
        The modal model (SI), whole; or an InputError, one line naming the file and the
        table, grid or mode.

    Examples
    --------
    (Needs pyNastran, the ``nastran`` extra in an environment of its own: not run here;
    tests/nastran/test_read_op2.py writes OP2s of beam models' modes and reads them back.)

    >>> from propwhirl.io import read_op2
    >>> model = read_op2("wing.op2", units="si", base=base, hubs=[1001],
    ...                  wing_grids=range(1, 12))                    # doctest: +SKIP
    """
    where = fileio.shown(path) if isinstance(path, (str, Path)) else repr(path)
    u = unit_system(units, where)
    if not isinstance(base, PropellerWing):
        raise fail(where, "an OP2 holds the modes only: give the base model (a wing with "
                           "propellers, type \"propeller-wing\"; --base MODEL.toml) for the "
                           "strips, the flight condition and the propellers"
                    if base is None else f"the base model is a {type(base).__name__}: it "
                    "must be a wing with propellers (type \"propeller-wing\")")
    if mount not in MOUNT_CHOICES:
        raise fail(where, f"mount = {v.short_repr(mount)} is invalid: must be one of "
                           f"{', '.join(MOUNT_CHOICES)}")
    hubs = nastran_read.hub_ids(hubs, base, where)
    wing_ids = _grids_arg("wing", wing_grids, where)
    if len(wing_ids) < 2:
        raise fail(where, "give the wing's reference-axis grids, root to tip, two or more "
                           "(--wing-grids; Python: wing_grids=...)")
    if len(set(wing_ids)) != len(wing_ids):
        twice = next(g for g in wing_ids if wing_ids.count(g) > 1)
        raise fail(where, f"wing GRID {twice} is given twice")
    if n_modes is not None:
        n_modes = v.integer_at_least("n_modes", n_modes, 1)
    if free:
        rigid_body_hz = float(v.positive("rigid_body_hz", rigid_body_hz, "Hz"))
    if not isinstance(keep_rigid, (bool, np.bool_)) or (keep_rigid and not free):
        raise fail(where, f"keep_rigid = {v.short_repr(keep_rigid)} is invalid: must be "
                           "true or false, and true only for a free structure (free=True)")
    fileio.check_input(path, "OP2 file", MAX_OP2_BYTES,
                       bound=f"propwhirl reads OP2s of at most {MAX_OP2_BYTES // 2 ** 30} GiB")
    op2 = _read(Path(path), where)
    table = _subcase(op2, subcase, where)
    here: list[str] = []

    kinds = np.asarray(table.node_gridtype)[:, 1]
    all_ids = np.asarray(table.node_gridtype)[:, 0].astype(np.int64)
    data = np.asarray(table.data, dtype=float)
    if data.ndim != 3 or data.shape[1:] != (all_ids.size, 6) or data.shape[0] == 0:
        raise fail(where, f"its eigenvector table has shape {data.shape}, expected (modes, "
                           f"{all_ids.size} points, 6)")
    keep_points = kinds == _GRID_TYPE
    if not keep_points.all():
        here.append(f"{where}: {int((~keep_points).sum())} scalar or extra point(s) left out "
                    "(their one component is no grid's motion)")
    ids, data = all_ids[keep_points], data[:, keep_points, :]
    modes = np.asarray(getattr(table, "modes", np.arange(1, data.shape[0] + 1)), dtype=int)
    eigns = np.asarray(getattr(table, "eigns", []), dtype=float)
    if eigns.size != data.shape[0] or not np.all(np.isfinite(eigns)):
        raise fail(where, "its eigenvectors lack their eigenvalues (one per mode)")
    if not np.all(np.isfinite(data)):
        i = np.argwhere(~np.isfinite(data))[0]
        raise fail(where, f"mode {int(modes[i[0]])}: GRID {int(ids[i[1]])} component "
                           f"{int(i[2]) + 1} is not finite")
    hub_idx = [_in_modes(ids, h, "hub", where) for h in hubs]
    wing_idx = [_in_modes(ids, g, "wing", where) for g in wing_ids]
    xyz, turned = _geometry(op2, ids, where, u)
    _check_span(xyz, wing_idx, wing_ids, base, u, where, here)
    for i, axes in enumerate(turned):                    # components in the basic frame
        if axes is not None:
            data[:, i, :3] = data[:, i, :3] @ axes
            data[:, i, 3:] = data[:, i, 3:] @ axes
    gm = _generalised_masses(op2, modes.size, modes, mass_normalised, where)
    freq = np.sign(eigns) * np.sqrt(np.abs(eigns)) / (2.0 * np.pi)
    kept = _kept_modes(freq, modes, free, rigid_body_hz, where, here, keep_rigid)
    if n_modes is not None:
        if n_modes > kept.size:
            raise fail(where, f"n_modes = {n_modes} is invalid: the OP2 has {kept.size} "
                               f"{'elastic ' if free else ''}modes")
        kept = kept[:n_modes]
    if kept.size > MAX_MODES:
        raise fail(where, f"{kept.size} modes is too many: at most {MAX_MODES} (keep the "
                           "lowest: --modes)")
    if kept.size == 0:
        raise fail(where, "no elastic mode left")
    bad = [int(modes[k]) for k in kept if not gm[k] > 0]
    if bad:
        raise fail(where, f"mode {bad[0]}: generalised mass {gm[list(modes).index(bad[0])]:g} "
                           "is invalid: must be > 0")
    shapes = data[kept].copy()
    shapes[:, :, :3] *= u.length
    f = freq[kept]
    rigid = f < rigid_body_hz if (free and keep_rigid) else np.zeros(f.size, dtype=bool)
    f = np.where(rigid, 0.0, f)                   # kept rigid-body modes: 0 Hz, undamped
    structure_src = f"{where} (subcase {table.isubcase})"
    for j, h in enumerate(hub_idx):
        if not np.any(shapes[:, h, :]):
            raise fail(where, f"hub GRID {hubs[j]} does not move in any mode kept: the "
                               "modes do not include the hub grid")
    try:
        s = ModalStructure(grid_ids=ids, xyz=xyz, frequencies_hz=f,
                           modal_mass=gm[kept] * u.mass * u.length ** 2,
                           damping_ratio=_damping(damping, base, 2.0 * np.pi * f, where,
                                                  rigid),
                           shapes=shapes, source=structure_src, free=bool(free))
        installations = tuple(
            nastran_read.modal_installation(
                inst, hub, "on-grid" if mount == "on-grid" else inst.mount, hub,
                lambda text: fail(where, text), "an OP2")
            for inst, hub in zip(base.propellers, hubs))
        model = ModalPropellerWing(s, wing_ids, _planform(base, xyz, wing_idx), base.flight,
                                   installations, wing_aero=base.wing_aero,
                                   propeller_aero=base.propeller_aero, rotating=base.rotating,
                                   name=f"{base.name} (modes of {Path(str(path)).name})",
                                   surfaces=surfaces)
    except v.InputError as exc:
        msg = str(exc)
        raise v.InputError(msg if msg.startswith(where) else f"{where}: {msg}") from None
    if notes is not None:
        notes.extend(here)
    return model


__all__ = ["MAX_OP2_BYTES", "MAX_RIGID_BODY_MODES", "MOUNT_CHOICES", "RIGID_BODY_HZ_FREE",
           "read_op2"]
