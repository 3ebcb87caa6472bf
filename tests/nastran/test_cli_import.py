"""`propwhirl import MODEL.bdf --out MODEL.toml --units ... --base BASE.toml --hubs ...` and
`propwhirl export` (issue 36, items 3, 5 and 7): the command line's round trip, its one-line
errors (exit code 2) and nothing half-imported: no output file, an existing one untouched."""
from __future__ import annotations

import numpy as np
import pytest

from helpers import bdf_decks as d
from propwhirl import io
from propwhirl.analysis.modes import model_modes
from propwhirl.app import cli


def _one_line_error(capsys, argv) -> str:
    assert cli.main(argv) == 2
    err = capsys.readouterr().err
    assert err.startswith("propwhirl: error: ") and err.count("\n") == 1, err
    return err


@pytest.fixture
def base_file(tmp_path):
    path = tmp_path / "base.toml"
    assert cli.main(["case", "two-propeller", "--save", str(path)]) == 0
    return path


def test_export_then_import_gives_the_model_back(tmp_path, base_file, capsys):
    bdf, out = tmp_path / "wing.bdf", tmp_path / "back.toml"
    assert cli.main(["export", str(base_file), "--out", str(bdf), "--units", "mm-t-s"]) == 0
    said = capsys.readouterr().out
    assert "--hubs 1001 2001" in said and "--units mm-t-s" in said
    assert cli.main(["import", str(bdf), "--out", str(out), "--units", "mm-t-s", "--base",
                     str(base_file), "--hubs", "1001", "2001"]) == 0
    captured = capsys.readouterr()
    assert f"wrote {out}" in captured.out and captured.err == ""
    a, b = io.load_model(base_file), io.load_model(out)
    fa, fb = (np.sort(model_modes(m)[0].frequency_hz) for m in (a, b))
    np.testing.assert_allclose(fb, fa, rtol=1e-8)          # model_modes: see test_round_trip


def test_a_bad_deck_is_one_line_and_nothing_is_written(tmp_path, base_file, capsys):
    bdf, out = tmp_path / "wing.bdf", tmp_path / "out.toml"
    cards = d.replace_card(d.standard(), "PBAR", 10, None)
    bdf.write_text(d.text(cards))
    argv = ["import", str(bdf), "--out", str(out), "--units", "si", "--base", str(base_file),
            "--hubs", "101", "102"]
    err = _one_line_error(capsys, argv)
    assert f"{bdf}: " in err and "CBAR 1 refers to PBAR or PBARL 10" in err
    assert not out.exists()
    out.write_text("kept\n")                               # an existing output stays as it was
    _one_line_error(capsys, argv)
    assert out.read_text() == "kept\n"


def test_units_base_and_outputs_are_checked_first(tmp_path, base_file, capsys):
    bdf, out = tmp_path / "wing.bdf", tmp_path / "out.toml"
    bdf.write_text(d.text(d.standard()))
    err = _one_line_error(capsys, ["import", str(bdf), "--out", str(out), "--base",
                                   str(base_file), "--hubs", "101"])
    assert "units not stated" in err
    err = _one_line_error(capsys, ["import", str(bdf), "--out", str(out), "--units", "si"])
    assert "give --base" in err
    err = _one_line_error(capsys, ["import", str(bdf), "--out", str(bdf), "--units", "si",
                                   "--base", str(base_file)])
    assert "--out" in err and "MODEL.bdf" in err
    err = _one_line_error(capsys, ["import", str(bdf), "--out", str(out), "--units", "si",
                                   "--base", str(base_file), "--hubs", "x"])
    assert "--hubs" in err
    assert not out.exists()


def test_a_hub_grid_not_in_the_model(tmp_path, base_file, capsys):
    bdf, out = tmp_path / "wing.bdf", tmp_path / "out.toml"
    assert cli.main(["export", str(base_file), "--out", str(bdf)]) == 0
    err = _one_line_error(capsys, ["import", str(bdf), "--out", str(out), "--units", "si",
                                   "--base", str(base_file), "--hubs", "1001", "3001"])
    assert "hub GRID 3001 (installation 2) is not in the file" in err
    assert not out.exists()
