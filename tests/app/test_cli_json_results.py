"""Every --json file of the command line is a result file (issue 21.4): written by its
Result's save (format ``propwhirl.<kind>/<version>``) and read back by that class's load."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from propwhirl.analysis.sensitivity import CriticalSensitivities
from propwhirl.analysis.stability import ModelAnalysis
from propwhirl.app import cli
from propwhirl.reproduce.harness import Records
from propwhirl.studies.boundary import Boundary
from propwhirl.studies.clearance import Clearance
from propwhirl.studies.sweeps import CriticalMap

SWEEP = ["--param", "propellers[0].propeller.f_psi", "4", "10", "3"]

#: command -> (its arguments before --json, the Result class of the file, the exit code);
#: "M" is the small model file
COMMANDS = {
    "analyse": (["M", "--speeds", "1", "350", "10"], ModelAnalysis, 0),
    "sweep": (["M", *SWEEP], CriticalMap, 0),
    "map": (["M", *SWEEP, "--param", "wing.EI*", "1", "2", "2"], CriticalMap, 0),
    "boundary": (["isolated-propeller", "--params", "propeller.f_theta", "propeller.f_psi",
                  "--speed", "220", "--bounds", "3", "12", "3", "12", "--grid", "6"],
                 Boundary, 0),
    "clearance": (["wingtip", "--vd", "100", "--no-minimum"], Clearance, 0),
    "sensitivity": (["M", "--top", "3"], CriticalSensitivities, 0),
    "reproduce": (["--only", "t9.5"], Records, 0),
}


@pytest.mark.parametrize("command", COMMANDS)
def test_every_json_output_loads_with_its_class(command, small_file, tmp_path, capsys):
    head, cls, code = COMMANDS[command]
    out = tmp_path / f"{command}.json"
    argv = [command, *[str(small_file) if a == "M" else a for a in head], "--json", str(out)]
    assert cli.main(argv) == code, capsys.readouterr().err
    assert f"wrote {out}" in capsys.readouterr().out
    assert json.loads(out.read_text())["format"] == cls.format_name()
    back = cls.load(out)
    assert type(back) is cls
    assert json.loads(Path(back.save(tmp_path / "again.json")).read_text()) == json.loads(
        out.read_text())


def test_a_study_json_named_csv_is_still_json(small_file, tmp_path, capsys):
    """--json writes JSON whatever the name (CriticalMap.save would pick CSV by the suffix)."""
    out = tmp_path / "s.csv"
    assert cli.main(["sweep", str(small_file), *SWEEP, "--json", str(out)]) == 0
    assert json.loads(out.read_text())["format"] == CriticalMap.format_name()
    assert CriticalMap.from_dict(json.loads(out.read_text())).axes[0].path == SWEEP[1]
