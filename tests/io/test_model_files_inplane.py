"""The in-plane bending rigidity in model files: EI_chordwise_N_m2 is read and written, and a
wing without it is written without the key (the thesis's model, unchanged files)."""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from propwhirl import io
from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing


def test_round_trip(tmp_path):
    m0 = wingtip_propeller_wing()
    m1 = m0.with_(wing=replace(m0.wing, EI_chordwise=1.4e7))
    io.save_model(m1, tmp_path / "a.toml")
    text = (tmp_path / "a.toml").read_text()
    assert "EI_chordwise_N_m2 = 14000000.0" in text
    back = io.load_model(tmp_path / "a.toml")
    assert back.wing.EI_chordwise == 1.4e7 and back.wing.in_plane
    V = np.array([120.0])
    np.testing.assert_array_equal(back.second_order(V).S3, m1.second_order(V).S3)
    io.save_model(m0, tmp_path / "b.toml")
    assert "EI_chordwise" not in (tmp_path / "b.toml").read_text()
    assert not io.load_model(tmp_path / "b.toml").wing.in_plane
