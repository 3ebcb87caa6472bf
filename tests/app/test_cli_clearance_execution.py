"""`propwhirl clearance` with the execution of the studies (issue 24.2): --processes,
--resume (beside --json), --quiet, and --propellers choosing whose minimum-frequency
searches run."""
from __future__ import annotations

import json

from propwhirl.app import cli

FAST = ["--vd", "100", "--frequency-range", "5", "9", "--quiet"]


def test_propellers_chooses_the_searches_and_is_checked(small_file, capsys):
    assert cli.main(["clearance", str(small_file), *FAST, "--propellers", "7"]) == 2
    err = capsys.readouterr().err
    assert "propellers = 7 is invalid" in err and "are 1" in err and len(err.splitlines()) == 1


def test_two_processes_and_resume_give_the_result_of_one(small_file, tmp_path, capsys):
    outs = {}
    for n in ("1", "2"):
        out = tmp_path / f"{n}.json"
        assert cli.main(["clearance", str(small_file), *FAST, "--propellers", "1",
                         "--processes", n, "--json", str(out)]) in (0, 1)
        outs[n] = json.loads(out.read_text())
        assert not list(tmp_path.glob("*.partial*"))       # removed once written
    assert outs["1"] == outs["2"]
    assert [q["propeller"] for q in outs["1"]["minimum_frequencies"]] == [1, 1]
    assert cli.main(["clearance", str(small_file), *FAST, "--resume"]) == 2
    assert "--resume needs the output file" in capsys.readouterr().err
    out = tmp_path / "r.json"
    assert cli.main(["clearance", str(small_file), *FAST, "--json", str(out), "--resume"]) \
        in (0, 1)
    assert json.loads(out.read_text()) == outs["1"]
