"""`propwhirl analyse` takes a modal model's file (issue 22, item 2); what a modal model cannot
run (the p-k, the reduced method, the sensitivities) is refused in one line giving the reason
the model gives (issue 34; the other commands: test_cli_modal_commands.py)."""
from __future__ import annotations

import json

import pytest

from propwhirl.analysis import analyse
from propwhirl.app import cli
from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
from propwhirl.io import load_modal_model, write_modes


@pytest.fixture(scope="module")
def modal_file(tmp_path_factory):
    path = tmp_path_factory.mktemp("modal") / "wing.toml"
    write_modes(wingtip_propeller_wing(), path, 12, mount="on-grid")
    return path


def test_analyse_takes_a_modal_model(modal_file, tmp_path, capsys):
    out = tmp_path / "a.json"
    assert cli.main(["analyse", str(modal_file), "--json", str(out), "--quiet"]) == 0
    printed = capsys.readouterr().out
    expected = analyse(load_modal_model(modal_file)).critical
    assert f"critical: divergence of wing 1 at {expected.V:.2f} m/s" in printed   # issue 34.4
    saved = json.loads(out.read_text())
    assert saved["model_name"].endswith("(modal)") and saved["format"] == "propwhirl.analysis/3"


@pytest.mark.parametrize("argv, says", [
    (["analyse", "{m}", "--method", "reduced"], "a modal model is reduced already"),
])
def test_what_does_not_take_a_modal_model_says_so_in_one_line(modal_file, capsys, argv, says):
    assert cli.main([a.format(m=modal_file) for a in argv]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and says in err, err
