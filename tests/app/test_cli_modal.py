"""`propwhirl analyse` takes a modal model's file (issue 22, item 2: "the engine, studies, plots
and reports work unchanged" — for the command line, the analysis); the commands that do not
yet take one refuse it in one line before any work."""
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
    assert f"critical: divergence of mode 1 (modal) at {expected.V:.2f} m/s" in printed
    saved = json.loads(out.read_text())
    assert saved["model_name"].endswith("(modal)") and saved["format"] == "propwhirl.analysis/3"


@pytest.mark.parametrize("argv, says", [
    (["analyse", "{m}", "--method", "reduced"], "only wing models (PropellerWing) are reduced"),
    (["analyse", "{m}", "--method", "pk"], "ModalPropellerWing 'wingtip"),
    (["sweep", "{m}", "--param", "flight.density", "1", "1.2", "2"], "only `propwhirl analyse`"),
    (["modes", "{m}"], "only `propwhirl analyse` takes modal models"),
])
def test_what_does_not_take_a_modal_model_says_so_in_one_line(modal_file, capsys, argv, says):
    assert cli.main([a.format(m=modal_file) for a in argv]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and says in err, err
