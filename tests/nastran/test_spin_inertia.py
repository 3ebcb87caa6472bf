"""The rotor's CONM2 I11 (issue 36, item c): what it is in the FE, and what propwhirl reads.

NASTRAN's CONM2 is a rigid mass of its grid: its I11 is rotary inertia about x of that grid,
so on a hub grid carried rigidly by the wing (RBE2) it is inertia of the wing's roll at the
hub — its bending slope (R_x = −∂h/∂y).  propwhirl's beam model reads the rotor's I11 as its
spin inertia I_Ω (the gyroscopic moments of a spinning rotor) and puts no roll inertia on the
wing: a rotor on its bearings, driven at constant torque, is not turned about its shaft when
the nacelle rolls (docs/modal-structures.md, "The rotor's I11").  Here, on
tests/data/nastran/pylons.bdf's wing with the two propellers rigid on it (no pylons, the
stick held in its plane and along its axis, so that the FE has exactly the beam model's
freedoms), the independent FE frame solver (tests/helpers/frame_fe.py) measures it:

* with the rotors' I11 out of the deck, the FE's frequencies are the beam model's;
* with them in, they are not — and they are the beam model's with I11 added to the wing's
  bending-slope inertia at each hub node, to the same precision: the FE's I11 is that and
  nothing else.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import scipy.linalg

from helpers import frame_fe
from propwhirl.cases import registry
from propwhirl.io.nastran_read import read_bdf

DECK = Path(__file__).resolve().parents[1] / "data" / "nastran" / "pylons.bdf"
HUBS = (1001, 1011)
SPIN = 1.548                               # the deck's rotor I11 [kg m^2]
N = 12                                      # frequencies compared


def on_the_wing(text: str, i11: bool) -> str:
    """The deck's propellers rigid on their wing grids (no pylon), the stick held in its
    plane and along its axis, the rotors' I11 kept or left out."""
    for k, (wing, y) in enumerate(((5, 1.596), (14, 5.7))):
        text = (text.replace(f"CBAR,{101 + k},2,{wing},{201 + k},1.,0.,0.\n", "")
                .replace(f"GRID,{201 + k},,0.,{y!r},-0.35\n", "")
                .replace(f"RBE2,{301 + k},{201 + k},", f"RBE2,{301 + k},{wing},"))
    text = text.replace(",-0.35\n", ",0.\n")
    if not i11:
        text = text.replace(f",{SPIN},0.,", ",0.,0.,")
    return text.replace("ENDDATA", "SPC1,1,126,2,THRU,14\nENDDATA")


def fe_hz(path: Path) -> np.ndarray:
    _, _, w2, _ = frame_fe.modes(path, N)
    return np.sqrt(w2) / (2 * np.pi)


def beam_hz(model, roll_inertia: float = 0.0) -> np.ndarray:
    """The beam model's in-vacuo frequencies (not spinning), with ``roll_inertia`` [kg m^2]
    added to the bending-slope DOF of each propeller's node."""
    quiet = model.with_(wing_aero=False, propeller_aero=False, rotating=False)
    sys = quiet.second_order(np.array([1.0]))
    M, K = sys.S1[0].copy(), sys.S3[0]
    d = quiet.dof_map()
    for node in model.nodes[:len(model.propellers)]:
        (i,) = [k for k, (kind, n) in enumerate(zip(d.q_kinds, d.q_node))
                if kind == "phi" and n == node]
        M[i, i] += roll_inertia
    return np.sqrt(scipy.linalg.eigh(K, M, eigvals_only=True)[:N]) / (2 * np.pi)


@pytest.fixture(scope="module")
def base():
    return registry.case_model("two-propeller")


def test_the_rotors_i11_is_spin_inertia_in_propwhirl_and_roll_inertia_in_the_fe(tmp_path,
                                                                                base):
    out, inn = tmp_path / "i11_out.bdf", tmp_path / "i11_in.bdf"
    out.write_text(on_the_wing(DECK.read_text(), i11=False))
    inn.write_text(on_the_wing(DECK.read_text(), i11=True))
    model = read_bdf(inn, units="si", base=base, hubs=HUBS)
    assert [p.propeller.spin_inertia for p in model.propellers] == [SPIN, SPIN]
    assert [p.mount for p in model.propellers] == ["rigid", "rigid"] and not model.wing.in_plane
    # the beam model's structure is the FE's without the I11 (the rotors' spin inertia acts
    # only when they spin): to the eigenproblems' rounding
    plain = beam_hz(model)
    np.testing.assert_allclose(fe_hz(out), plain, rtol=1e-9)
    # with it, the FE's differ (measured: -0.07, -0.05, -0.14 % for the three lowest, -1.5 %
    # for the fourth at 19.9 Hz, down to -10.4 % by the twelfth), and are the beam's with
    # I11 on the wing's roll at each hub node
    with_i11 = fe_hz(inn)
    shift = with_i11 / plain - 1.0
    assert np.max(np.abs(shift)) > 1e-3
    np.testing.assert_allclose(with_i11, beam_hz(model, roll_inertia=SPIN), rtol=1e-9)
