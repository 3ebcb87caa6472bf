"""`propwhirl export` and `propwhirl import` in the main environment (issue 36, items 1 and
5): the deck is written without pyNastran; reading one needs the `nastran` extra, which lives
in an environment of its own (pyNastran needs numpy < 2): one line saying how to install it."""
from __future__ import annotations

import importlib.util

import pytest

from propwhirl.app import cli


def test_export_writes_a_deck_and_says_how_to_read_it_back(tmp_path, capsys):
    out = tmp_path / "wingtip.bdf"
    assert cli.main(["export", "wingtip", "--out", str(out)]) == 0
    said = capsys.readouterr().out
    assert f"wrote {out}" in said and "propwhirl import" in said and "--hubs 1001" in said
    assert out.read_text().rstrip().endswith("ENDDATA")


def test_export_refuses_what_is_not_a_beam_model(tmp_path, capsys):
    assert cli.main(["export", "isolated-propeller", "--out", str(tmp_path / "p.bdf")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "not a beam model" in err
    assert not (tmp_path / "p.bdf").exists()


@pytest.mark.skipif(importlib.util.find_spec("pyNastran") is not None,
                    reason="pyNastran is installed here: tests/nastran test the import")
def test_import_without_pynastran_says_how_to_install_it(tmp_path, capsys):
    bdf = tmp_path / "w.bdf"
    bdf.write_text("ENDDATA\n")
    code = cli.main(["import", str(bdf), "--out", str(tmp_path / "w.toml"), "--units", "si"])
    err = capsys.readouterr().err
    assert code == 2 and err.count("\n") == 1
    assert "pip install 'propwhirl[nastran]' in an environment of its own" in err
    assert "numpy < 2" in err
    assert not (tmp_path / "w.toml").exists()
