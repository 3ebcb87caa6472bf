"""`propwhirl modes` on a model with in-plane wing bending shows the chordwise share."""
from __future__ import annotations

from dataclasses import replace

from propwhirl import io
from propwhirl.app import cli
from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing


def test_modes_shows_the_chordwise_share(tmp_path, capsys):
    m = wingtip_propeller_wing()
    io.save_model(m.with_(wing=replace(m.wing, EI_chordwise=20 * m.wing.EI)), tmp_path / "m.toml")
    assert cli.main(["modes", str(tmp_path / "m.toml"), "--count", "4"]) == 0
    lines = capsys.readouterr().out.splitlines()
    header = lines[1].split()
    assert header[3:] == ["bending", "torsion", "chordwise", "pitch", "yaw"]
    row = lines[5].split()                       # the 4th mode, 8.84 Hz: mostly chordwise
    shares = dict(zip(header[3:], map(float, row[-5:])))
    assert shares["chordwise"] > 0.8
    assert abs(sum(shares.values()) - 1) < 1e-3
