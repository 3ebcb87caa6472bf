"""`propwhirl boundary` and `propwhirl clearance`: outputs and exit codes."""
from __future__ import annotations

import json

from propwhirl.app import cli


def test_boundary_of_a_case_writes_json_csv_and_plot(tmp_path, capsys):
    out = tmp_path / "b"
    code = cli.main(["boundary", "isolated-propeller", "--params", "propeller.f_theta",
                     "propeller.f_psi", "--speed", "220", "--bounds", "3", "12", "3", "12",
                     "--grid", "6", "--json", f"{out}.json", "--csv", f"{out}.csv",
                     "--plot", f"{out}.png"])
    text = capsys.readouterr().out
    assert code == 0
    assert "neutral-stability curve at V = 220 m/s" in text
    assert "1 branch, every sign change of a 6 x 6 grid map on one of them" in text
    assert ("ends at (3, 6.281): the plane's edge propeller.f_theta = lower and at (6.281, 3): "
            "the plane's edge propeller.f_psi = lower") in text
    assert "grid map 6 x 6 (36 eigen-solutions)" in text
    d = json.loads((tmp_path / "b.json").read_text())
    assert d["kind"] == "neutral-stability" and len(d["curves"]) == 1
    assert d["parameters"] == ["propeller.f_theta", "propeller.f_psi"]
    rows = (tmp_path / "b.csv").read_text().splitlines()
    assert rows[0].startswith("curve,point,propeller.f_theta [Hz],propeller.f_psi [Hz]")
    assert len(rows) == 1 + len(d["curves"][0]["points"])
    assert (tmp_path / "b.png").stat().st_size > 1000


def test_boundary_of_a_model_file_default_bounds(tmp_path, capsys):
    assert cli.main(["case", "isolated-propeller", "--save", str(tmp_path / "m.toml")]) == 0
    code = cli.main(["boundary", str(tmp_path / "m.toml"), "--params", "propeller.f_theta",
                     "propeller.f_psi", "--speed", "220"])
    text = capsys.readouterr().out
    assert code == 0 and "in [3.5, 14] Hz" in text       # half to twice 7 Hz


def test_boundary_bad_input_exit_2(capsys):
    assert cli.main(["boundary", "no-such-model", "--params", "a", "b", "--speed", "1"]) == 2
    assert "nor a case name" in capsys.readouterr().err
    assert cli.main(["boundary", "isolated-propeller", "--params", "propeller.f_thetaa",
                     "propeller.f_psi", "--speed", "220"]) == 2
    assert "propeller.f_theta" in capsys.readouterr().err      # the nearest valid path


def test_clearance_exit_codes_and_outputs(tmp_path, capsys):
    code = cli.main(["clearance", "wingtip", "--vd", "130", "--no-minimum",
                     "--json", str(tmp_path / "c.json"), "--csv", str(tmp_path / "c.csv"),
                     "--plot", str(tmp_path / "c.png")])
    text = capsys.readouterr().out
    assert code == 1 and "NOT CLEARED" in text and "wing 1" in text
    assert json.loads((tmp_path / "c.json").read_text())["cleared"] is False
    assert (tmp_path / "c.csv").read_text().startswith("model,V_D [m/s],factor")
    assert (tmp_path / "c.png").stat().st_size > 1000
    assert cli.main(["clearance", "wingtip", "--vd", "100", "--no-minimum"]) == 0
    assert "CLEARED" in capsys.readouterr().out
    assert cli.main(["clearance", "wingtip", "--vd", "130", "--thesis", "--no-minimum",
                     "--factor", "1.2"]) == 0
    assert "1.2 V_D = 1.2 x 130 = 156.00 m/s: CLEARED" in capsys.readouterr().out


def test_clearance_bad_input_exit_2(capsys):
    assert cli.main(["clearance", "wingtip", "--vd", "-1", "--no-minimum"]) == 2
    assert "V_D" in capsys.readouterr().err
