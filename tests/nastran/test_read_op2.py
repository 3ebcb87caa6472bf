"""Modes in from an OP2 (issue 36, items 4 and 7): a propwhirl beam model's own modes written
as a SOL 103 OP2 by pyNastran (tests/helpers/op2_files.py) and read back by
``propwhirl.io.read_op2`` give the beam model's analysis; free structures' rigid-body modes are
left out where the user says the structure is free and refused where not; every problem is
one line naming the file and the grid, mode or table.

Tolerances: an OP2 holds the eigenvectors, their eigenvalues and the grids in single
precision (float32, relative 6e-8), so frequencies agree to 1e-6 relative, and critical
speeds to the engine's crossing tolerance (0.01 m/s) plus the documented difference of a
modal model from its beam model (docs/modal-structures.md: within 0.02 m/s).
"""
from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from helpers.op2_files import free_free_modes, tailed_modal_model, write_op2, write_op2_arrays
from propwhirl import io
from propwhirl.analysis import analyse
from propwhirl.app import cli
from propwhirl.cases import registry
from propwhirl.io.nastran import UNIT_SYSTEMS
from propwhirl.io.nastran_op2 import read_op2
from propwhirl.model.modal import ModalPropellerWing
from propwhirl.model.modal_structure import ModalStructure
from propwhirl.validate import InputError

WINGTIP = registry.case_model("wingtip")
TWO = registry.case_model("two-propeller")
#: modal model against its beam model (docs/modal-structures.md) [m/s]
SPEED_TOL = 0.02


def _events(a):
    return [(e.kind, e.event, e.V) for e in a.events]


def _same_events(a, b, tol):
    ea, eb = _events(a), _events(b)
    assert [e[:2] for e in ea] == [e[:2] for e in eb], (ea, eb)
    for x, y in zip(ea, eb):
        assert abs(x[2] - y[2]) <= tol, (x, y)


def _own(model, tmp_path, units="si", **kw):
    s = ModalStructure.from_wing(model.wing)
    path = write_op2(s, tmp_path / "wing.op2", units)
    hubs = [1 + n for n in model.nodes]
    out = read_op2(path, units=units, base=model, hubs=hubs, wing_grids=list(s.grid_ids),
                   mount="own", mass_normalised=True, **kw)
    return s, out


@pytest.mark.parametrize("units", ["si", "mm-t-s", "in-lbf-s"])
def test_the_wings_modes_through_an_op2_give_the_beam_models_instabilities(tmp_path, units):
    s, model = _own(WINGTIP, tmp_path, units)
    np.testing.assert_allclose(model.structure.frequencies_hz, s.frequencies_hz, rtol=1e-6)
    # mass-normalised in the deck's units: 1 deck mass unit x length unit² in SI, the shapes
    # scaled alike (φᵀMφ the same in SI)
    u = UNIT_SYSTEMS[units]
    np.testing.assert_allclose(model.structure.modal_mass, u.mass * u.length ** 2, rtol=1e-15)
    scale = np.sqrt(model.structure.modal_mass[0])
    np.testing.assert_allclose(model.structure.shapes / scale, s.shapes, atol=1e-6)
    inst = model.propellers[0]
    assert inst.mount == "flexible" and inst.grid == 1 + WINGTIP.nodes[0]
    _same_events(analyse(model), analyse(WINGTIP), SPEED_TOL)


def test_on_grid_the_structures_modes_with_the_mounts_give_its_modal_model(tmp_path):
    """Way b: the whole structure's modes (wing, propeller masses, mount springs) with the
    hub grids, through an OP2, equal the same modes in memory (the damping: the base wing's
    Rayleigh damping, as the OP2 route takes it)."""
    s, hubs, _ = ModalStructure.with_mounts(TWO)
    path = write_op2(s, tmp_path / "two.op2", "mm-t-s")
    model = read_op2(path, units="mm-t-s", base=TWO, hubs=hubs, mass_normalised=True,
                     wing_grids=[int(g) for g in s.grid_ids[:TWO.wing.n_nodes]])
    mu, lam = TWO.wing.rayleigh
    ref_s = dataclasses.replace(s, damping_ratio=0.5 * (mu / s.omega + lam * s.omega))
    from propwhirl.model.modal import ModalInstallation
    from propwhirl.model.modal_structure import StripPlanform
    ref = ModalPropellerWing(ref_s, tuple(int(g) for g in s.grid_ids[:TWO.wing.n_nodes]),
                             StripPlanform.from_wing(TWO.wing), TWO.flight,
                             tuple(ModalInstallation(i.propeller, h, "on-grid", i.aero)
                                   for i, h in zip(TWO.propellers, hubs)))
    assert [p.mount for p in model.propellers] == ["on-grid", "on-grid"]
    _same_events(analyse(model), analyse(ref), 0.01)


def test_import_op2_on_the_command_line_writes_a_modal_model_file(tmp_path, capsys):
    base = tmp_path / "base.toml"
    assert cli.main(["case", "wingtip", "--save", str(base)]) == 0
    s = ModalStructure.from_wing(WINGTIP.wing, n_modes=20)
    op2 = write_op2(s, tmp_path / "wing.op2", "in-lbf-s")
    out = tmp_path / "modal.toml"
    hub = str(1 + WINGTIP.nodes[0])
    argv = ["import", str(op2), "--out", str(out), "--units", "in-lbf-s", "--base", str(base),
            "--hubs", hub, "--mount", "own", "--mass-normalised", "--modes", "12",
            "--wing-grids", *map(str, s.grid_ids)]
    capsys.readouterr()
    assert cli.main(argv) == 0
    said = capsys.readouterr()
    assert f"wrote {out}" in said.out and "12 modes" in said.out and said.err == ""
    back = io.load_modal_model(out)
    assert back.structure.n_modes == 12
    np.testing.assert_allclose(back.structure.frequencies_hz, s.frequencies_hz[:12], rtol=1e-6)
    assert cli.main(["analyse", str(out), "--speeds", "100", "200", "10"]) == 0


def _one_line(capsys, argv) -> str:
    assert cli.main(argv) == 2
    err = capsys.readouterr().err
    assert err.startswith("propwhirl: error: ") and err.count("\n") == 1, err
    return err


def test_command_line_errors_are_one_line_and_write_nothing(tmp_path, capsys):
    base = tmp_path / "base.toml"
    assert cli.main(["case", "wingtip", "--save", str(base)]) == 0
    s = ModalStructure.from_wing(WINGTIP.wing, n_modes=6)
    op2 = write_op2(s, tmp_path / "wing.op2")
    out = tmp_path / "modal.toml"
    common = ["import", str(op2), "--out", str(out), "--base", str(base), "--mass-normalised",
              "--mount", "own", "--wing-grids", *map(str, s.grid_ids)]
    capsys.readouterr()
    err = _one_line(capsys, common + ["--hubs", "9999", "--units", "si"])
    assert f"{op2}: hub GRID 9999 is not in the modes" in err
    err = _one_line(capsys, common + ["--hubs", "26"])
    assert "units not stated" in err
    err = _one_line(capsys, common + ["--hubs", "26", "--units", "si", "--rigid-below", "1"])
    assert "--rigid-below" in err and "--free" in err
    err = _one_line(capsys, common + ["--hubs", "26", "--units", "si", "--keep-rigid"])
    assert "--keep-rigid" in err and "--free" in err
    bdf = tmp_path / "x.bdf"
    bdf.write_text("ENDDATA\n")
    err = _one_line(capsys, ["import", str(bdf), "--out", str(out), "--units", "si",
                             "--base", str(base), "--free"])
    assert "--free is for an OP2's modes" in err
    assert not out.exists() and not (tmp_path / "modal.modes.npz").exists()


# ------------------------------------------------------------------------ free structures
def _wing_inertia(wing):
    """The beam wing's own rigid-body mass [kg], roll and pitch inertia about the root
    [kg m²] (its mass matrix on the rigid heave, roll and pitch shapes)."""
    from propwhirl.model.structure.assembly import wing_structure

    M = wing_structure(wing)[0]
    y = wing.node_y
    shapes = np.zeros((3, M.shape[0]))
    shapes[0, 0::3] = 1.0                      # heave h = 1
    shapes[1, 0::3], shapes[1, 1::3] = y, 1.0  # roll: h = y, φ = ∂h/∂y = 1
    shapes[2, 2::3] = 1.0                      # pitch α = 1
    return [float(r @ M @ r) for r in shapes]


def _free_model(tmp_path, ratio, root, units="si", **kw):
    m, roll, pitch = (ratio * x for x in _wing_inertia(WINGTIP.wing))
    ids, xyz, w2, shapes = free_free_modes(WINGTIP.wing, m, roll, pitch, root)
    path = write_op2_arrays(tmp_path / "free.op2", ids, xyz, w2, shapes, units)
    notes: list[str] = []
    model = read_op2(path, units=units, base=WINGTIP, hubs=[1 + WINGTIP.nodes[0]],
                     wing_grids=list(ids), mount="own", mass_normalised=True, notes=notes,
                     **kw)
    return path, model, notes


@pytest.mark.parametrize("free, n_rigid", [("free", 3), ("symmetric", 2),
                                           ("antisymmetric", 1)])
def test_a_heavy_bodys_elastic_modes_give_the_clamped_wings_instabilities(tmp_path, free,
                                                                          n_rigid):
    """A body 10⁴ times the wing's mass and inertias: its free structure's elastic modes
    (rigid-body modes left out) are the clamped wing's, and so are the instabilities (to the
    modal tolerance)."""
    _, model, notes = _free_model(tmp_path, 1e4, free, free=True)
    assert model.structure.n_modes == 3 * WINGTIP.wing.n_nodes - 3
    assert len(notes) == 1 and f"its {n_rigid} rigid-body mode(s)" in notes[0]
    _same_events(analyse(model), analyse(WINGTIP), SPEED_TOL)


def test_a_light_bodys_free_structure_is_not_the_clamped_wing(tmp_path):
    """A body of the wing's own mass and inertias: the elastic modes differ (the free wing's
    first bending mode at 4.35 Hz, the clamped one's 2.88 Hz), and so do the instabilities."""
    _, model, _ = _free_model(tmp_path, 1.0, "free", free=True)
    clamped = ModalStructure.from_wing(WINGTIP.wing, n_modes=1).frequencies_hz[0]
    assert model.structure.frequencies_hz[0] > 1.4 * clamped
    a, b = analyse(model), analyse(WINGTIP)
    assert [e.kind for e in a.events] != [e.kind for e in b.events]


def test_rigid_body_modes_are_refused_unless_the_structure_is_said_free(tmp_path):
    with pytest.raises(InputError, match=r"free\.op2: mode 1 \([-0-9.e]+ Hz\) is a "
                                         r"rigid-body mode: .*\(--free;"):
        _free_model(tmp_path, 1.0, "free")
    ids, xyz, w2, shapes = free_free_modes(WINGTIP.wing, 10.0, 1.0, 1.0, "free")
    w2 = w2.copy()
    w2[3:8] = 0.0                                       # eight modes at zero: a mechanism
    path = write_op2_arrays(tmp_path / "mech.op2", ids, xyz, w2, shapes)
    with pytest.raises(InputError, match=r"mech\.op2: 8 modes below 0\.1 Hz .* at most 6 "
                                         "rigid-body modes"):
        read_op2(path, units="si", base=WINGTIP, hubs=[26], wing_grids=list(ids),
                 mount="own", mass_normalised=True, free=True)


def test_a_free_structures_plunge_and_roll_are_kept_and_its_pitch_refused(tmp_path):
    """``keep_rigid``: an OP2 of a wing on a heavy body free in plunge and roll keeps both
    rigid-body modes (0 Hz, undamped) and gives the clamped wing's instabilities; one free
    in pitch too is refused naming a mode and the missing tail (docs/modal-structures.md)."""
    _, model, notes = _free_model(tmp_path, 1e4, "plunge-roll", free=True, keep_rigid=True)
    s = model.structure
    assert s.free and s.n_modes == 3 * WINGTIP.wing.n_nodes - 1
    assert np.all(s.frequencies_hz[:2] == 0.0) and np.all(s.damping_ratio[:2] == 0.0)
    assert len(notes) == 1 and "2 rigid-body mode(s)" in notes[0] and "kept" in notes[0]
    got, ref = analyse(model).events, analyse(WINGTIP).events
    assert all(g.V > 0.999 * ref[0].V for g in got)
    for e in ref:
        assert min(abs(g.V - e.V) for g in got) < 5e-4 * e.V, e
    with pytest.raises(InputError, match=r"free\.op2 .*: mode [123] \(0 Hz\) is a rigid-body "
                                         r".*pitch.*no tail"):
        _free_model(tmp_path, 1e4, "free", free=True, keep_rigid=True)
    with pytest.raises(InputError, match=r"keep_rigid = True is invalid: .*free=True"):
        _free_model(tmp_path, 1e4, "plunge-roll", keep_rigid=True)


def test_a_tail_given_to_read_op2_keeps_the_free_pitch(tmp_path):
    """The wing on a body free in plunge, roll and pitch with a tail on a rigid arm
    (tests/helpers/op2_files.tailed_modal_model) through an OP2: with the tail's surface given,
    the pitch is kept and the model is the one built directly (single precision: its roots
    at 100 m/s to 1e-5); without it the pitch is refused, saying to add a tail."""
    direct, n_rigid = tailed_modal_model(WINGTIP, 1e2)
    s = direct.structure
    path = write_op2(s, tmp_path / "tail.op2")
    args = dict(units="si", base=WINGTIP, hubs=[26], wing_grids=list(direct.wing_grids),
                mount="own", mass_normalised=True, free=True, keep_rigid=True)
    model = read_op2(path, surfaces=direct.surfaces, **args)
    assert [k for _, k in model.structure.rigid_body_modes()].count("pitch") == 1
    assert model.dof_map().w_labels == direct.dof_map().w_labels
    V = np.array([100.0])
    a, b = (np.sort_complex(np.linalg.eigvals(m.state_matrix(V)[0])) for m in (direct, model))
    big = np.abs(a) > 1e-3
    np.testing.assert_allclose(b[big], a[big], rtol=1e-5)
    with pytest.raises(InputError, match=r"tail\.op2 .*rigid-body pitch: a wing alone has no "
                                         r"tail.*add a tail"):
        read_op2(path, **args)


def test_the_base_installations_rotation_and_state_apply_as_on_the_bdf_route(tmp_path):
    """read_op2 reads the base's installation as the BDF route's swept stick does
    (nastran_read.modal_installation): its ``rotation`` override on the propeller, a stopped or
    feathered installation refused in one line naming the file and the hub grid."""
    inst = WINGTIP.propellers[0]
    assert inst.propeller.rotation == 1
    turned = WINGTIP.with_(propellers=(dataclasses.replace(inst, rotation=-1),))
    _, model = _own(turned, tmp_path)
    assert model.propellers[0].propeller.rotation == -1
    _, same = _own(WINGTIP, tmp_path)
    assert same.propellers[0].propeller.rotation == 1
    stopped = WINGTIP.with_(propellers=(dataclasses.replace(inst, state="stopped"),))
    with pytest.raises(InputError, match=r"^[^\n]*wing\.op2[^\n]*: hub GRID 26: the base's "
                                         r"installation is stopped: an OP2 is read as "
                                         r"a modal model, whose propellers operate$"):
        _own(stopped, tmp_path)


# ------------------------------------------------------------------------ the file's problems
def _structure():
    return ModalStructure.from_wing(WINGTIP.wing, n_modes=5)


def _read(path, **kw):
    s = _structure()
    args = dict(units="si", base=WINGTIP, hubs=[26], wing_grids=list(s.grid_ids),
                mount="own", mass_normalised=True)
    args.update(kw)
    return read_op2(path, **args)


def test_components_in_a_turned_displacement_frame_are_turned_back(tmp_path):
    s = _structure()
    frame = (7, (0.0, 0.0, 0.0), (0.0, 0.0, 1.0), (0.0, 1.0, 0.0))   # x along basic y
    plain = _read(write_op2(s, tmp_path / "a.op2"))
    turned = _read(write_op2(s, tmp_path / "b.op2", cd={10: frame, 26: frame}))
    np.testing.assert_allclose(turned.structure.shapes, plain.structure.shapes, atol=1e-6)


def test_scalar_points_are_left_out_and_said(tmp_path):
    notes: list[str] = []
    m = _read(write_op2(_structure(), tmp_path / "s.op2", scalar_points=(9001,)), notes=notes)
    assert 9001 not in m.structure.grid_ids and "1 scalar or extra point(s) left out" in notes[0]


@pytest.mark.parametrize("change, message", [
    ({"hubs": [77]}, r"hub GRID 77 is not in the modes \(the eigenvectors' grids: 1, 2"),
    ({"wing_grids": [1, 2, 500]}, r"wing GRID 500 is not in the modes"),
    ({"wing_grids": [1]}, r"give the wing's reference-axis grids"),
    ({"hubs": [26, 26]}, r"2 hub grid\(s\) for the base model's 1 installation"),
    ({"units": None}, r"units not stated"),
    ({"units": "furlongs"}, r"units = 'furlongs' is invalid"),
    ({"base": None}, r"an OP2 holds the modes only: give the base model"),
    ({"mass_normalised": False}, r"holds no eigenvalue table \(LAMA\): .*\(--mass-normalised;"),
    ({"n_modes": 9}, r"n_modes = 9 is invalid: the OP2 has 5 modes"),
    ({"subcase": 4}, r"subcase 4 is not in the file"),
    ({"damping": 1.5}, r"damping = 1.5 is invalid"),
    ({"mount": "glued"}, r"mount = 'glued' is invalid"),
])
def test_bad_arguments_are_one_line_naming_the_file(tmp_path, change, message):
    path = write_op2(_structure(), tmp_path / "w.op2")
    with pytest.raises(InputError, match=r"w\.op2: " + message):
        _read(path, **change)


def test_a_hub_grid_the_modes_do_not_move_is_refused(tmp_path):
    s = _structure()
    shapes = np.array(s.shapes)
    shapes[:, -1, :] = 0.0                    # the tip grid (26) never moves
    path = write_op2_arrays(tmp_path / "still.op2", s.grid_ids, s.xyz, s.omega ** 2, shapes)
    with pytest.raises(InputError, match=r"still\.op2: hub GRID 26 does not move in any mode"):
        _read(path)


def test_two_subcases_need_one_chosen(tmp_path):
    path = write_op2(_structure(), tmp_path / "two.op2", subcases=(1, 2))
    with pytest.raises(InputError, match=r"two\.op2: holds the eigenvectors of subcases "
                                         r"\[1, 2\]: choose one"):
        _read(path)
    assert _read(path, subcase=2).structure.n_modes == 5


def test_an_op2_without_geometry_is_refused(tmp_path):
    path = write_op2(_structure(), tmp_path / "bare.op2", geometry=False)
    with pytest.raises(InputError, match=r"bare\.op2: holds no grid geometry \(GEOM1\): "
                                         "write the OP2 with PARAM,POST,-1"):
        _read(path)


@pytest.mark.parametrize("keep", [0.05, 0.3, 0.6, 0.9, 0.99])
def test_a_truncated_op2_is_one_line(tmp_path, keep):
    path = write_op2(_structure(), tmp_path / "cut.op2")
    data = path.read_bytes()
    path.write_bytes(data[: int(keep * len(data))])
    with pytest.raises(InputError) as info:
        _read(path)
    message = str(info.value)
    assert "\n" not in message, message
    assert message.startswith(f"{path}: cannot read the OP2 (truncated, or not an OP2"), message


def test_not_an_op2_and_a_device_are_one_line(tmp_path):
    path = tmp_path / "text.op2"
    path.write_text("this is not an OP2\n" * 10)
    with pytest.raises(InputError, match=r"text\.op2: cannot read the OP2"):
        _read(path)
    with pytest.raises(InputError, match=r"/dev/zero.*not a regular file"):
        _read("/dev/zero")
    big = tmp_path / "big.op2"
    with open(big, "wb") as fh:                 # sparse: no disk space taken
        fh.truncate(3 * 2 ** 30)
    with pytest.raises(InputError, match=r"big\.op2.*more than 2,147,483,648 \(propwhirl reads "
                                         r"OP2s of at most 2 GiB\)"):
        _read(big)


def test_the_generalised_masses_of_an_eigenvalue_table_are_used(tmp_path, monkeypatch):
    """An OP2 of NASTRAN has its eigenvalue table (LAMA); pyNastran 1.4.1 writes none, so the
    table is added to the OP2 as read: its generalised masses (deck units) × mass unit ×
    length unit² are the modal masses, and a mode missing from it is refused."""
    from pyNastran.op2.tables.lama_eigenvalues.lama_objects import RealEigenvalues

    from propwhirl.io import nastran_op2

    s = _structure()
    path = write_op2(s, tmp_path / "lama.op2", "mm-t-s")
    real_read = nastran_op2._read

    def with_lama(masses):
        def read(p, where):
            op2 = real_read(p, where)
            table = RealEigenvalues("", "LAMA", len(masses))
            table.mode[:] = np.arange(1, len(masses) + 1)
            table.generalized_mass[:] = masses
            op2.eigenvalues[""] = table
            return op2
        return read

    monkeypatch.setattr(nastran_op2, "_read", with_lama([2.0] * 5))
    m = read_op2(path, units="mm-t-s", base=WINGTIP, hubs=[26], wing_grids=list(s.grid_ids),
                 mount="own")                               # no mass_normalised needed
    u = UNIT_SYSTEMS["mm-t-s"]
    np.testing.assert_allclose(m.structure.modal_mass, 2.0 * u.mass * u.length ** 2,
                               rtol=1e-7)                    # LAMA is single precision
    monkeypatch.setattr(nastran_op2, "_read", with_lama([1.0] * 4))
    with pytest.raises(InputError, match=r"lama\.op2: mode 5 has an eigenvector but no line "
                                         r"in the eigenvalue table \(LAMA\)"):
        read_op2(path, units="mm-t-s", base=WINGTIP, hubs=[26], wing_grids=list(s.grid_ids),
                 mount="own")


@pytest.mark.parametrize("written, read_as", [("mm-t-s", "si"), ("si", "mm-t-s"),
                                              ("mm-t-s", "in-lbf-s")])
def test_an_op2_read_in_other_units_than_its_own_is_one_line(tmp_path, written, read_as):
    """Issue 36, item 7: an OP2 read in the wrong unit system is refused (its wing grids span
    25.4 to 1000 times the base's wing), naming the grids and the units, before a 5.7 km
    wing is analysed; through the command line nothing is written."""
    s = ModalStructure.from_wing(WINGTIP.wing)
    path = write_op2(s, tmp_path / "wing.op2", written)
    hubs = [1 + n for n in WINGTIP.nodes]
    with pytest.raises(InputError) as info:
        read_op2(path, units=read_as, base=WINGTIP, hubs=hubs, wing_grids=list(s.grid_ids),
                 mount="own", mass_normalised=True)
    message = str(info.value)
    assert "\n" not in message and message.startswith(f"{path}: wing GRID 1 to GRID 26 span")
    assert f"are the OP2's units {read_as}, and not mixed?" in message


def test_the_command_line_writes_nothing_for_an_op2_in_other_units(tmp_path, capsys):
    base = tmp_path / "base.toml"
    assert cli.main(["case", "wingtip", "--save", str(base)]) == 0
    s = ModalStructure.from_wing(WINGTIP.wing, n_modes=6)
    op2 = write_op2(s, tmp_path / "wing.op2", "mm-t-s")
    out = tmp_path / "modal.toml"
    capsys.readouterr()
    err = _one_line(capsys, ["import", str(op2), "--out", str(out), "--base", str(base),
                             "--mass-normalised", "--mount", "own", "--units", "si",
                             "--hubs", "26", "--wing-grids", *map(str, s.grid_ids)])
    assert "are the OP2's units si" in err
    assert not out.exists() and not (tmp_path / "modal.modes.npz").exists()
