"""`propwhirl analyse --method pk` on a thesis model (the Patil wing, ch. 7): the printed
summary with the p-k vs finite-state table, and the --json file with the finite-state events
and the comparison."""
import json

import numpy as np
import pytest

from propwhirl.analysis import analyse, load
from propwhirl.app import cli
from propwhirl.cases.ch07_patil import patil_model


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    folder = tmp_path_factory.mktemp("pk")
    model, out = folder / "patil.toml", folder / "patil.json"
    assert cli.main(["case", "patil", "--save", str(model)]) == 0
    return model, out


def test_analyse_method_pk_prints_and_writes_the_comparison(run, capsys):
    model, out = run
    capsys.readouterr()
    assert cli.main(["analyse", str(model), "--method", "pk", "--speeds", "5", "45", "5",
                     "--json", str(out), "--quiet"]) == 0
    text = capsys.readouterr().out
    a = load(out)
    # the file: the p-k events, the finite-state ones and the comparison of the two
    doc = json.loads(out.read_text())
    assert doc["finite_state"]["aero_model"] == "leishman-nguyen"
    assert doc["method_comparison"] == a.method_comparison().to_dict()
    rows = doc["method_comparison"]["rows"]
    assert {r["kind"] for r in rows} == {"flutter", "divergence"}
    for r in rows:
        assert r["found_by"] == "both" and r["dV"] == r["V_pk"] - r["V_fs"]
    # the same as the Python API on the same grid
    ref = analyse(patil_model(), np.arange(5.0, 46.0, 5.0), vgf=True, method="pk")
    assert a.events == ref.events and a.finite_state == ref.finite_state
    # the printout: the summary of the file's analysis, the table in it
    assert a.summary() in text
    assert "vs finite-state (Leishman-Nguyen) aerodynamics" in text
    for r in rows:
        assert f"{r['V_pk']:.2f}" in text and f"{r['V_fs']:.2f}" in text
        assert f"{r['dV']:+.2f}" in text
    assert f"wrote {out}" in text


def test_a_dense_analysis_has_no_comparison(run, capsys, tmp_path):
    model, _ = run
    out = tmp_path / "dense.json"
    assert cli.main(["analyse", str(model), "--method", "dense", "--speeds", "5", "45", "5",
                     "--json", str(out), "--quiet"]) == 0
    assert "vs finite-state" not in capsys.readouterr().out
    doc = json.loads(out.read_text())
    assert "finite_state" not in doc and "method_comparison" not in doc
