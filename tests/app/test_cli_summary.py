"""`propwhirl analyse --summary / --summary-csv / --events-csv` (issue 11, items 1-2)."""
from __future__ import annotations

import pytest

from propwhirl import io
from propwhirl.app import cli
from propwhirl.cases.ch09_baseline import isolated_baseline_propeller


@pytest.fixture
def model_file(tmp_path):
    pytest.importorskip("tomli_w")
    path = tmp_path / "m.toml"
    io.save_model(isolated_baseline_propeller(), path)
    return path


def test_summary_and_csvs(model_file, tmp_path, capsys):
    s, e = tmp_path / "s.csv", tmp_path / "e.csv"
    assert cli.main(["analyse", str(model_file), "--speeds", "100", "300", "50", "--summary",
                     "--summary-csv", str(s), "--events-csv", str(e)]) == 0
    out = capsys.readouterr().out
    assert "flutter summary" in out and "g < 0 UNSTABLE" in out and "propeller radius R" in out
    assert "propeller 1: 100 %, backward whirl" in out
    assert s.read_text().startswith("mode,label,V_m_per_s,k,")
    assert e.read_text().splitlines()[1].split(",")[6] == "1"
