"""Two propellers on pylons below the wing (issue 36, item 6d): an FE model the thesis never
had, written by hand (tests/data/nastran/pylons.bdf: a 13-CBAR wing, two 0.35 m pylon CBARs
straight down, an RBE2 from each pylon's foot to the hub and nacelle grids, rotor and nacelle
CONM2 with inertia), end to end.

* The BDF route refuses it, naming the pylon: propwhirl's beam model carries a propeller on
  the wing's chord line.
* The OP2 route takes it: its modes, computed by an independent frame solver
  (tests/helpers/frame_fe.py, checked here against propwhirl's beam wing), written as an OP2
  by pyNastran and read with ``mount="on-grid"`` (each propeller rigid on its hub grid, the
  pylon in the modes).  The same deck with the propellers rigid on the wing grids (no pylon)
  gives, through the same route, the beam model's critical speeds (the BDF route) within
  0.5 %: the FE's 3-D wing (axial and in-plane motion, coupled by the nacelles' chordwise
  offsets) is what the beam model leaves out (measured 0.04 to 0.25 %).  The rotor's CONM2
  I11 is left out of that comparison: NASTRAN counts it as the hub's rotary inertia about x
  (the wing's bending slope at the hub), propwhirl's beam model as spin inertia only; with it
  the wing flutter moves 0.7 % (docs/validation.md).
"""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from helpers import frame_fe
from helpers.op2_files import write_op2_arrays
from propwhirl import InputError
from propwhirl.analysis.stability import analyse
from propwhirl.cases import registry
from propwhirl.io.nastran_op2 import read_op2
from propwhirl.io.nastran_read import read_bdf
from propwhirl.model.modal_structure import ModalStructure

DECK = Path(__file__).resolve().parents[1] / "data" / "nastran" / "pylons.bdf"
HUBS = (1001, 1011)
WING_GRIDS = tuple(range(1, 15))


@pytest.fixture(scope="module")
def base():
    return registry.case_model("two-propeller")


def on_the_wing(text: str) -> str:
    """The deck with each propeller rigid on its wing grid (no pylon: the hub and nacelle
    grids at the wing's z, the RBE2 from the wing grid) and the rotors' I11 left out."""
    for k, (wing, y) in enumerate(((5, 1.596), (14, 5.7))):
        text = (text.replace(f"CBAR,{101 + k},2,{wing},{201 + k},1.,0.,0.\n", "")
                .replace(f"GRID,{201 + k},,0.,{y!r},-0.35\n", "")
                .replace(f"RBE2,{301 + k},{201 + k},", f"RBE2,{301 + k},{wing},"))
    return text.replace(",-0.35\n", ",0.\n").replace(",1.548,0.,", ",0.,0.,")


def through_an_op2(tmp_path, deck: Path, base, n_modes: int = 40):
    ids, xyz, w2, shapes = frame_fe.modes(deck, n_modes)
    op2 = write_op2_arrays(tmp_path / (deck.stem + ".op2"), ids, xyz, w2, shapes, "si")
    return read_op2(op2, units="si", base=base, hubs=list(HUBS), wing_grids=list(WING_GRIDS),
                    mount="on-grid", mass_normalised=True)


def test_the_bdf_route_refuses_the_pylons_by_name(base):
    with pytest.raises(InputError) as info:
        read_bdf(DECK, units="si", base=base, hubs=HUBS)
    message = str(info.value)
    assert "\n" not in message
    assert message.startswith(f"{DECK}: CBAR 101 (GRID 5-201) joins a propeller's rigid body "
                              "0.35 m below the stick to it: a pylon")
    assert "--mount on-grid" in message


def test_the_frame_solver_gives_propwhirls_beam_wing(tmp_path):
    """The helper's modes of the bare wing (no propellers) against propwhirl's beam wing of
    the same deck: the vertical bending and torsion frequencies to 1e-5 (both consistent-mass
    Euler-Bernoulli beams on the same mesh; the FE's other modes are in-plane or axial)."""
    text = DECK.read_text().split("$ propeller 1")[0] + "SPC1,1,123456,1\nENDDATA\n"
    path = tmp_path / "wing.bdf"
    path.write_text(text)
    bare = registry.case_model("two-propeller").with_(propellers=())
    wing = read_bdf(path, units="si", base=bare, hubs=()).wing
    ref = ModalStructure.from_wing(wing).frequencies_hz[:5]
    _, _, w2, shapes = frame_fe.modes(path, 12)
    f = np.sqrt(w2) / (2 * np.pi)
    out_of_plane = np.abs(shapes[:, :, [2, 3, 4]]).max(axis=1).max(axis=1) > \
        10 * np.abs(shapes[:, :, [0, 1, 5]]).max(axis=1).max(axis=1)
    np.testing.assert_allclose(f[out_of_plane][:5], ref, rtol=1e-5)


def test_without_pylons_the_fe_modes_give_the_beam_models_critical_speeds(tmp_path, base):
    path = tmp_path / "on_wing.bdf"
    path.write_text(on_the_wing(DECK.read_text()))
    beam = analyse(read_bdf(path, units="si", base=base, hubs=HUBS)).events
    modal = analyse(through_an_op2(tmp_path, path, base)).events
    assert len(beam) >= 3
    assert [(e.kind, e.event) for e in modal] == [(e.kind, e.event) for e in beam]
    for a, b in zip(modal, beam):
        assert abs(a.V - b.V) <= 0.005 * b.V, (a.V, b.V)


def test_the_pylon_model_end_to_end(tmp_path, base):
    """The pylon model through an OP2: converged in the modes (30 against 40: within 0.1 %),
    and its pylons (flexible in fore-aft bending and torsion, the hubs 0.35 m below the
    wing) bring the whirl flutter far below the rigidly mounted propellers'."""
    events = analyse(through_an_op2(tmp_path, DECK, base)).events
    fewer = analyse(through_an_op2(tmp_path, DECK, base, n_modes=30)).events
    assert [(e.kind, e.event) for e in fewer] == [(e.kind, e.event) for e in events]
    for a, b in zip(fewer, events):
        assert abs(a.V - b.V) <= 1e-3 * b.V, (a.V, b.V)
    path = tmp_path / "on_wing.bdf"
    path.write_text(on_the_wing(DECK.read_text()))
    rigid = analyse(through_an_op2(tmp_path, path, base)).events
    first_flutter = min(e.V for e in events if e.kind == "flutter")
    assert first_flutter < 0.7 * min(e.V for e in rigid if e.kind == "flutter")


CAMPAIGN = '''format = "propwhirl-campaign"
format_version = 1
name = "two propellers on pylons: CS-25 whirl-flutter clearance"
model = "pylons.toml"
convention = "propwhirl"
[regulation]
name = "cs25"
[envelope]
airspeed = "EAS"
V_D_m_per_s = 110.0
altitudes_m = [0.0, 3000.0]
[[cases]]
name = "nominal"
[[cases]]
name = "rotation reversed"
reverse_rotation = true
'''


def test_the_pylon_model_on_the_command_line_to_a_campaign_and_its_report(tmp_path, capsys):
    """OP2 -> `propwhirl import` (a modal model file) -> `propwhirl certify` (a campaign of
    two cases at two altitudes) -> campaign.json, campaign.csv, report.html.  Measured:
    NOT CLEARED at V_D = 110 m/s EAS, the wing's divergence at 126.19 m/s TAS at sea level
    and 145.85 at 3000 m against 126.5 and 146.8 required (the pylons' whirl flutter is
    above it)."""
    import json

    from propwhirl.app import cli
    ids, xyz, w2, shapes = frame_fe.modes(DECK, 40)
    write_op2_arrays(tmp_path / "pylons.op2", ids, xyz, w2, shapes, "si")
    assert cli.main(["case", "two-propeller", "--save", str(tmp_path / "base.toml")]) == 0
    assert cli.main(["import", str(tmp_path / "pylons.op2"), "--out",
                     str(tmp_path / "pylons.toml"), "--base", str(tmp_path / "base.toml"),
                     "--units", "si", "--hubs", *map(str, HUBS), "--wing-grids",
                     *map(str, WING_GRIDS), "--mount", "on-grid", "--mass-normalised"]) == 0
    (tmp_path / "campaign.toml").write_text(CAMPAIGN)
    out = tmp_path / "report"
    code = cli.main(["certify", str(tmp_path / "campaign.toml"), "--out", str(out),
                     "--no-pdf"])
    assert code in (0, 1), capsys.readouterr().err
    assert {p.name for p in out.iterdir()} == {"campaign.json", "campaign.csv", "report.html"}
    rows = json.loads((out / "campaign.json").read_text())["rows"]
    assert len(rows) == 4
    speeds = [r["critical_speed"] for r in rows]
    assert all(np.isfinite(speeds)) and code == (0 if all(r["cleared"] for r in rows) else 1)
    html = (out / "report.html").read_text()
    assert "two propellers on pylons" in html and "pylons.toml" in html


def test_a_swept_grid_line_is_refused_by_the_strips(tmp_path, base):
    """Issue 36 item 6e: the OP2 of a swept FE wing is read; its strip aerodynamics (an
    unswept wing's) refuse it by name, and without them the structure is read (the unswept
    deck's strips take it)."""
    ids, xyz, w2, shapes = frame_fe.modes(DECK, 20)
    op2 = write_op2_arrays(tmp_path / "straight.op2", ids, xyz, w2, shapes, "si")
    read_op2(op2, units="si", base=base, hubs=list(HUBS), wing_grids=list(WING_GRIDS),
             mount="on-grid", mass_normalised=True)
    swept = xyz.copy()
    swept[:, 0] += np.tan(np.radians(20.0)) * swept[:, 1]
    op2 = write_op2_arrays(tmp_path / "swept.op2", ids, swept, w2, shapes, "si")
    with pytest.raises(InputError) as info:
        read_op2(op2, units="si", base=base, hubs=list(HUBS), wing_grids=list(WING_GRIDS),
                 mount="on-grid", mass_normalised=True)
    message = str(info.value)
    assert message.startswith(f"{op2} (subcase 1): wing_grids (GRID 1 to GRID 14) make a "
                              "reference axis swept by 20.0 deg") and "\n" not in message
    assert "doublet lattice" in message
    m = read_op2(op2, units="si", base=base.with_(wing_aero=False), hubs=list(HUBS),
                 wing_grids=list(WING_GRIDS), mount="on-grid", mass_normalised=True)
    assert m.structure.n_modes == 20 and not m.wing_aero
