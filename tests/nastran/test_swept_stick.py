"""A swept stick (issue 36, item 6e): read as the modes of its straight beam on its swept
grids, a modal model; its strip aerodynamics refuse it by name.

The decks are tests/data/nastran/pylons.bdf's wing (13 CBARs, 5.7 m) with every grid moved
aft by y·tan Λ and inward to y·cos Λ — (x, y, z) → (x + y sin Λ, y cos Λ, z): the stick keeps
its length along the swept axis, a propeller's hub and nacelle grids stay on its shaft along
the basic x axis through their wing grid — held in its plane and along its axis (SPC1 126 on
the stick grids).  The independent FE frame solver (tests/helpers/frame_fe.py: CBARs in any
direction, CONM2, RBE2) gives the same structure's modes in the basic frame.
"""
from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import pytest

from helpers import frame_fe
from propwhirl import InputError
from propwhirl.cases import registry
from propwhirl.io.nastran_read import planform_corners, read_bdf
from propwhirl.model.modal import ModalPropellerWing
from propwhirl.model.modal_structure import ModalStructure

DECK = Path(__file__).resolve().parents[1] / "data" / "nastran" / "pylons.bdf"
SWEEP = 30.0
HUBS = (1001, 1011)
HELD = "SPC1,1,126,2,THRU,14\n"          # the stick rigid in its plane and along its axis


def swept(text: str, sweep_deg: float) -> str:
    """Every GRID (x, y, z) -> (x + y sin Λ, y cos Λ, z)."""
    s, c = math.sin(math.radians(sweep_deg)), math.cos(math.radians(sweep_deg))

    def move(match):
        gid, x, y, z = match.group(1), *(float(match.group(k)) for k in (2, 3, 4))
        return f"GRID,{gid},,{x + y * s!r},{y * c!r},{z!r}"
    return re.sub(r"^GRID,(\d+),,([-\d.eE+]+),([-\d.eE+]+),([-\d.eE+]+)$", move, text,
                  flags=re.M)


def bare(text: str) -> str:
    """The deck's wing alone, clamped, held in its plane."""
    return text.split("$ propeller 1")[0] + "SPC1,1,123456,1\n" + HELD + "ENDDATA\n"


def on_the_wing(text: str) -> str:
    """The propellers rigid on their wing grids (no pylon; test_pylons.on_the_wing), the
    rotors' I11 out, the stick held in its plane."""
    for k, (wing, y) in enumerate(((5, 1.596), (14, 5.7))):
        text = (text.replace(f"CBAR,{101 + k},2,{wing},{201 + k},1.,0.,0.\n", "")
                .replace(f"GRID,{201 + k},,0.,{y!r},-0.35\n", "")
                .replace(f"RBE2,{301 + k},{201 + k},", f"RBE2,{301 + k},{wing},"))
    text = text.replace(",-0.35\n", ",0.\n").replace(",1.548,0.,", ",0.,0.,")
    return text.replace("ENDDATA", HELD + "ENDDATA")


def write(tmp_path, name: str, text: str) -> Path:
    path = tmp_path / name
    path.write_text(text)
    return path


@pytest.fixture(scope="module")
def base():
    return registry.case_model("two-propeller")


def test_a_swept_stick_is_the_straight_beams_modes_on_its_swept_grids(tmp_path, base):
    quiet = base.with_(propellers=(), wing_aero=False)
    straight = read_bdf(write(tmp_path, "straight.bdf", bare(DECK.read_text())), units="si",
                        base=quiet)
    notes: list[str] = []
    path = write(tmp_path, "swept.bdf", swept(bare(DECK.read_text()), SWEEP))
    m = read_bdf(path, units="si", base=quiet, notes=notes)
    assert isinstance(m, ModalPropellerWing) and not m.wing_aero
    s = m.structure
    ref = ModalStructure.from_wing(straight.wing)
    assert s.n_modes == ref.n_modes == 39                   # 13 elements x 3 DOFs
    # the grids as written (17 digits) projected on the axis: element lengths to 4e-16; the
    # eigenproblem (omega_max / omega_1 = 2700) turns that into 3e-10 on the first frequency
    np.testing.assert_allclose(s.frequencies_hz, ref.frequencies_hz, rtol=1e-9)
    # the grids are the deck's, on the axis swept by 30 deg through the root
    assert m.wing_grids == tuple(range(1, 15)) and s.grid_ids.tolist() == list(range(1, 15))
    lam = math.radians(SWEEP)
    np.testing.assert_allclose(s.xyz[:, 0], np.tan(lam) * s.xyz[:, 1], rtol=0, atol=1e-12)
    np.testing.assert_allclose(np.hypot(s.xyz[:, 0], s.xyz[:, 1]), straight.wing.node_y,
                               rtol=0, atol=1e-12)
    # each grid's motion: the straight beam's turned by the sweep about z (heave and the
    # rotations about the axis' normal and the axis themselves; nothing in the plane)
    normal, along = np.array([math.cos(lam), -math.sin(lam)]), np.array([math.sin(lam),
                                                                        math.cos(lam)])
    tol = 1e-9 * np.abs(ref.shapes).max()        # the eigenvectors as the frequencies above
    np.testing.assert_allclose(s.shapes[..., 2], ref.shapes[..., 2], rtol=0, atol=tol)
    np.testing.assert_allclose(s.shapes[..., 3:5] @ normal, ref.shapes[..., 3], atol=tol)
    np.testing.assert_allclose(s.shapes[..., 3:5] @ along, ref.shapes[..., 4], atol=tol)
    assert not np.any(s.shapes[..., [0, 1, 5]])
    (note,) = [n for n in notes if "stick is swept" in n]
    assert "swept by 30.0 deg" in note and "39 modes of its straight beam" in note
    # the planform CAERO1 would give: streamwise chords at the root and tip grids
    p1, p2, p3, p4 = planform_corners(m)
    chord = base.wing.chord_at(0.0), base.wing.chord_at(base.wing.semi_span)
    ea = base.wing.elastic_axis
    np.testing.assert_allclose(p1, s.xyz[0] - [ea * chord[0], 0, 0], atol=1e-12)
    np.testing.assert_allclose(p4, s.xyz[-1] - [ea * chord[1], 0, 0], atol=1e-12)
    np.testing.assert_allclose([p2[0] - p1[0], p3[0] - p4[0]], chord, rtol=1e-12)


def test_the_fe_frame_gives_the_swept_sticks_modes(tmp_path, base):
    """The swept deck's modes by the independent frame solver (its CBARs along the swept
    axis, in the basic frame) against the modal model's: frequencies and shapes."""
    path = write(tmp_path, "swept.bdf", swept(bare(DECK.read_text()), SWEEP))
    m = read_bdf(path, units="si", base=base.with_(propellers=(), wing_aero=False))
    ids, xyz, w2, shapes = frame_fe.modes(path, 12)
    np.testing.assert_allclose(xyz, m.structure.xyz, atol=1e-12)
    f = np.sqrt(w2) / (2 * np.pi)
    np.testing.assert_allclose(f, m.structure.frequencies_hz[:12], rtol=1e-9)
    for k in range(12):                          # mass-normalised both: equal up to the sign
        a, b = shapes[k].ravel(), m.structure.shapes[k].ravel()
        np.testing.assert_allclose(a * np.sign(a @ b), b, atol=1e-7 * np.abs(b).max())


def test_its_strip_aerodynamics_refuse_it_by_name(tmp_path, base):
    path = write(tmp_path, "swept.bdf", swept(bare(DECK.read_text()), SWEEP))
    with pytest.raises(InputError) as info:
        read_bdf(path, units="si", base=base.with_(propellers=()))
    message = str(info.value)
    assert "\n" not in message and message.startswith(f"{path}")
    for said in ("wing_grids (GRID 1 to GRID 14)", "swept by 30.0 deg", "more than the 5 deg",
                 "unswept wing's", "doublet lattice", "wing_aero = false"):
        assert said in message, (said, message)
    # a few degrees (a tapered wing's axis leans so) are the strips' still
    m = read_bdf(write(tmp_path, "four.bdf", swept(bare(DECK.read_text()), 4.0)),
                 units="si", base=base.with_(propellers=()))
    assert m.wing_aero and m.planform.y.size == 13


def test_propellers_on_a_swept_stick_against_the_fe(tmp_path, base):
    """Two propellers rigid on the swept stick, their shafts along the basic x axis: the
    modal model's structure (the bare stick's 39 modes, each propeller's rigid-mount block on
    its wing grid's heave and basic R_y) against the FE of the same deck (the rotors' I11 out:
    item c)."""
    path = write(tmp_path, "swept.bdf", swept(on_the_wing(DECK.read_text()), SWEEP))
    m = read_bdf(path, units="si", base=base.with_(wing_aero=False), hubs=HUBS)
    assert [(p.grid, p.mount) for p in m.propellers] == [(5, "rigid"), (14, "rigid")]
    quiet = m.with_(propeller_aero=False, rotating=False).second_order(np.array([1.0]))
    import scipy.linalg
    f = np.sqrt(scipy.linalg.eigh(quiet.S3[0], quiet.S1[0], eigvals_only=True)) / (2 * np.pi)
    _, _, w2, _ = frame_fe.modes(path, 10)
    np.testing.assert_allclose(np.sqrt(w2) / (2 * np.pi), f[:10], rtol=1e-9)


def test_a_bent_stick_and_a_swept_one_free_in_its_plane_are_refused(tmp_path, base):
    quiet = base.with_(propellers=(), wing_aero=False)
    text = swept(bare(DECK.read_text()), SWEEP).replace(HELD, "")
    with pytest.raises(InputError, match=r"GRID 2 \(on the stick, swept by 30\.0 deg\) leaves "
                                         r"component\(s\) 126 free: a swept stick is read rigid "
                                         r"in its plane"):
        read_bdf(write(tmp_path, "free.bdf", text), units="si", base=quiet)
    bent = swept(bare(DECK.read_text()), SWEEP).replace("GRID,14,,", "GRID,14,,0.5+", 1)
    bent = re.sub(r"GRID,14,,0\.5\+([-\d.eE+]+)",
                  lambda mt: f"GRID,14,,{float(mt.group(1)) + 0.5!r}", bent)
    with pytest.raises(InputError, match=r"GRID \d+ lies [\d.]+ m off the line from the root "
                                         r"GRID 1 to the tip GRID 14: a bent stick"):
        read_bdf(write(tmp_path, "bent.bdf", bent), units="si", base=quiet)
    dihedral = bare(DECK.read_text()).replace("GRID,8,,0.,2.964,0.", "GRID,8,,0.,2.964,0.1")
    with pytest.raises(InputError, match=r"GRID 8 lies 0\.1 m off \(in z\) the plane z = 0 m "
                                         r"of the root GRID 1: a stick with dihedral or bent"):
        read_bdf(write(tmp_path, "dihedral.bdf", dihedral), units="si", base=quiet)


def test_propwhirl_import_writes_a_swept_stick_as_a_modal_model_file(tmp_path, base, capsys):
    from propwhirl.app import cli
    from propwhirl.io import load_modal_model, save_model

    save_model(base.with_(propellers=(), wing_aero=False), tmp_path / "base.toml")
    path = write(tmp_path, "swept.bdf", swept(bare(DECK.read_text()), SWEEP))
    out = tmp_path / "swept.toml"
    assert cli.main(["import", str(path), "--out", str(out), "--units", "si", "--base",
                     str(tmp_path / "base.toml")]) == 0
    said = capsys.readouterr()
    assert "stick is swept by 30.0 deg" in said.err + said.out
    assert "modal model of the swept stick: 39 modes" in said.out
    back = load_modal_model(out)
    direct = read_bdf(path, units="si", base=base.with_(propellers=(), wing_aero=False))
    np.testing.assert_array_equal(back.structure.shapes, direct.structure.shapes)
    np.testing.assert_array_equal(back.structure.xyz, direct.structure.xyz)


def test_the_doublet_lattice_serves_it(tmp_path, base):
    """With the base's wing on the doublet lattice (4 x 8 panels: bounded work), the swept
    stick's modal model gets its panels on the swept planform (a CAERO1 of the base's chords
    at the root and tip grids).  Barely swept (0.001 deg: the tip 0.1 mm aft) it is the
    straight deck's beam DLM model: every event within 2 xtol (the modal DLM's agreement with
    the beam DLM, tests/model/test_modal_dlm.py; measured 0.004 m/s).  Swept 30 deg aft, the
    bending-torsion wash-out of a swept-back wing removes the divergence (161.2 m/s unswept)
    from the range and raises the flutter (measured 138.4 -> 163.6 m/s)."""
    from dataclasses import replace

    pytest.importorskip("panelaero")
    from propwhirl.analysis import analyse
    from propwhirl.engine import XTOL

    dlm = base.with_(propellers=(), flight=replace(base.flight, speed_range=(10.0, 250.0, 5.0)),
                     wing=replace(base.wing, aero="dlm", dlm_chordwise_panels=4,
                                  dlm_spanwise_panels=8))
    straight = read_bdf(write(tmp_path, "straight.bdf", bare(DECK.read_text())), units="si",
                        base=dlm)
    ref = analyse(straight).events
    assert [(e.kind, e.event) for e in ref] == [("flutter", "onset"), ("divergence", "onset")]
    notes: list[str] = []
    barely = read_bdf(write(tmp_path, "barely.bdf", swept(bare(DECK.read_text()), 0.001)),
                      units="si", base=dlm, notes=notes)
    assert isinstance(barely, ModalPropellerWing) and barely.aero == "dlm"
    assert any("doublet-lattice panels on the swept planform" in n for n in notes)
    events = analyse(barely).events
    assert [(e.kind, e.event) for e in events] == [(e.kind, e.event) for e in ref]
    for a, b in zip(events, ref):
        assert abs(a.V - b.V) <= 2 * XTOL, (a.V, b.V)
    m = read_bdf(write(tmp_path, "swept.bdf", swept(bare(DECK.read_text()), SWEEP)),
                 units="si", base=dlm)
    p = m.dlm_planform
    np.testing.assert_allclose(p.leading_edge[:, :2], planform_corners(m)[[0, 3], :2],
                               atol=1e-12)
    events = analyse(m).events
    assert not [e for e in events if e.kind == "divergence"]
    flutter = [e.V for e in events if e.kind == "flutter"]
    assert flutter and min(flutter) > 1.1 * ref[0].V


def test_hinged_propellers_on_a_barely_swept_stick_are_the_beam_models(tmp_path, base):
    """tests/data/nastran/wing_two_propellers.bdf (two propellers on pitch and yaw hinges,
    CELAS2 springs), held in its plane: swept by 0.001 deg (strips still: under 5 deg) its
    modal model — the stick's 39 modes, each propeller's own pitch and yaw on its wing grid —
    gives the straight deck's beam model's instabilities within 2 xtol (the same structure
    and strips, the tip 0.1 mm aft)."""
    from propwhirl.analysis import analyse
    from propwhirl.engine import XTOL

    text = (Path(__file__).resolve().parents[1] / "data" / "nastran"
            / "wing_two_propellers.bdf").read_text().replace("ENDDATA", HELD + "ENDDATA")
    hubs = (1001, 2001)
    beam = read_bdf(write(tmp_path, "straight.bdf", text), units="si", base=base, hubs=hubs)
    m = read_bdf(write(tmp_path, "barely.bdf", swept(text, 0.001)), units="si", base=base,
                 hubs=hubs)
    assert isinstance(m, ModalPropellerWing)
    assert [(p.grid, p.mount) for p in m.propellers] == [(5, "flexible"), (14, "flexible")]
    assert [p.propeller for p in m.propellers] == [p.propeller for p in beam.propellers]
    ref, events = analyse(beam).events, analyse(m).events
    assert len(ref) >= 3
    assert [(e.kind, e.event) for e in events] == [(e.kind, e.event) for e in ref]
    for a, b in zip(events, ref):
        assert abs(a.V - b.V) <= 2 * XTOL, (a.V, b.V)
